/* gpu_tiles.h: how a frame is cut into dispatches. Pure arithmetic on measured (or, in
 * tests, injected) dispatch times; no Vulkan here, so the policy is unit-tested without a
 * device and without a clock (tests/unit/test_tiles.c).
 *
 * Three policies:
 *  - fixed: N x N tiles (--tile N).
 *  - unlimited (budget_ms == 0): a device no watchdog can reset, such as lavapipe
 *    (VK_PHYSICAL_DEVICE_TYPE_CPU), takes the fewest dispatches that fit the tile buffers:
 *    full-width bands of up to max_pixels pixels. Each dispatch has a fixed cost there
 *    (about 8 ms on Mesa 22, more with private memory, and about 1 MiB the driver keeps),
 *    so every avoided dispatch is time and memory saved (docs/performance.md).
 *  - adaptive (budget_ms > 0): tiles sized from a model of one dispatch's time,
 *    overhead + slope x pixel-samples. The model is seeded by two dispatches of different
 *    sizes (a two-point fit); before the second one the whole time is charged to the
 *    pixels (no overhead), which over-estimates larger tiles and so errs on the safe side.
 *    Later dispatches aim at half the budget, the margin absorbing tiles costlier per pixel
 *    than those measured (a mirror sphere against the sky). Tiles are full-width bands
 *    whenever a band of at least one row fits, so a small scene takes one or two
 *    dispatches. */
#ifndef RC_GPU_TILES_H
#define RC_GPU_TILES_H

#include <stdbool.h>
#include <stdint.h>

/* The first dispatch of an adaptive frame covers at most this many pixels: small enough
 * that a batch at the full loop budget stays well inside a watchdog's 2 s on any GPU we
 * know of, large enough to measure more than the dispatch's fixed cost. */
#define RC_TILES_SEED_PIXELS 16384u
typedef struct rc_tile_planner {
  uint32_t width, height;
  uint32_t fixed;      /* --tile N, else 0 */
  double budget_ms;    /* 0: no time limit per dispatch */
  uint32_t max_pixels; /* capacity of the tile buffers */
  /* The model. */
  uint32_t points;     /* dispatches observed */
  double first_x, first_ms; /* the first observation (pixel-samples, ms) */
  double overhead_ms, slope_ms;
  bool fitted;         /* overhead from a two-point fit */
} rc_tile_planner;

void rc_tiles_init(rc_tile_planner *p, uint32_t width, uint32_t height, uint32_t fixed, double budget_ms,
                   uint32_t max_pixels);

/* Rows of the band that starts at y0, and columns of the tile at x0 in that band, for
 * dispatches of `batch` samples per pixel. */
uint32_t rc_tiles_band_rows(const rc_tile_planner *p, uint32_t y0, uint32_t batch);
uint32_t rc_tiles_cols(const rc_tile_planner *p, uint32_t rows, uint32_t x0, uint32_t batch);

/* The most rows any band can have under this planner (the host band buffers' size). */
uint32_t rc_tiles_max_band_rows(const rc_tile_planner *p);

/* One dispatch took `ms` for `pixels` pixels at `batch` samples each. */
void rc_tiles_observe(rc_tile_planner *p, double pixels, uint32_t batch, double ms);

/* The model's predicted time of a dispatch (what the planner aims with). */
double rc_tiles_predict_ms(const rc_tile_planner *p, double pixels, uint32_t batch);

/* The order in which a dispatch visits its tile's rows of workgroups: workgroup row i
 * renders pixel-block row (i * stride) mod rows (raycast.comp). Mesa's llvmpipe (22.3,
 * lp_cs_tpool.c) hands each of its T threads one contiguous 1/T of a dispatch's
 * workgroups, which in dispatch order is a horizontal strip of the image; a strip of sky
 * finishes long before a strip of reflective floor, and its thread then sits idle
 * (docs/performance.md, finding 10). A stride near rows / phi (the golden ratio) spreads
 * every contiguous run of rows evenly over the tile, whatever T is (Kronecker's
 * sequence), while each thread still walks whole rows left to right, which keeps
 * neighbouring workgroups' BVH nodes in its cache. The stride is coprime with `rows`, so
 * the order is a permutation, and stride x rows < 2^32, so the shader's 32-bit product
 * cannot wrap. A real GPU schedules workgroups dynamically and is indifferent to it. */
uint32_t rc_tiles_row_stride(uint32_t rows);

#endif
