/* region.h: parts of a frame, for renders that outgrow one machine (docs/cluster.md).
 *
 * A region is a window of the full frame in pixels, pbrt's crop window: columns
 * [x0, x1) and rows [y0, y1). The camera, the BVH and every pixel's sample seeds are
 * those of the full frame, so a pixel comes out bit-identical whichever region renders
 * it. A shard I/N is one of N bands of rows (tiles where a row outweighs a shard), cut by
 * an estimate of the cost (ref_render.c): a band of sky is taller than a band through a
 * mirror sphere. Pure arithmetic: unit-tested without a device
 * (tests/unit/test_region.c). */
#ifndef RC_REGION_H
#define RC_REGION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct rc_region {
  uint32_t x0, y0, x1, y1;
} rc_region;

static inline uint32_t rc_region_width(rc_region r) { return r.x1 - r.x0; }
static inline uint32_t rc_region_height(rc_region r) { return r.y1 - r.y0; }
static inline uint64_t rc_region_pixels(rc_region r) { return (uint64_t)rc_region_width(r) * rc_region_height(r); }

/* "X0,Y0,X1,Y1" (decimal, no spaces); false with the reason in why (a static string). */
bool rc_region_parse(const char *text, rc_region *r, const char **why);
/* "I/N" with 0 <= I < N; false with the reason. */
bool rc_shard_parse(const char *text, uint32_t *index, uint32_t *count, const char **why);

/* A frame's cost estimate: cells of cell_w x cell_h pixels from the top-left corner (the
 * last row and column of cells may be cut short by the frame's edge), cost[i * cols + j]
 * the cost of each pixel of cell row i, column j (non-negative). */
typedef struct rc_cost_grid {
  const double *cost;
  uint32_t cols, rows, cell_w, cell_h;
} rc_cost_grid;

/* The region of shard `index` of `count` over a width x height frame whose costs are
 * `grid` (NULL: all pixels equal), cut by cost (shard_cut.c): full-width bands of rows,
 * and tiles of a band where a row outweighs a shard's share. The shards tile the frame,
 * each at least one pixel (count <= height), and the cuts depend only on the costs, so
 * every shard of a render computes the same ones. False when out of memory. */
bool rc_shard_region(const rc_cost_grid *grid, uint32_t width, uint32_t height, uint32_t index, uint32_t count,
                     rc_region *out);

/* Coverage of a width x height frame by n parts (region_coverage.c: O(n log n), whatever
 * the sizes): 0 when every pixel lies in exactly one part. Otherwise 3 with *overlap_a the
 * first part that is empty or leaves the frame; else 1 with *overlap_a < *overlap_b two
 * parts that share a pixel (the topmost such pair); else 2 with *gap the first uncovered
 * rectangle (its first row, its columns there, and the rows where the same columns stay
 * uncovered); 4 when memory ran out. */
int rc_region_coverage(const rc_region *parts, size_t n, uint32_t width, uint32_t height, size_t *overlap_a,
                       size_t *overlap_b, rc_region *gap);

#endif
