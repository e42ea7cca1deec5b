#include "gpu/gpu_tiles.h"

#include <math.h>

void rc_tiles_init(rc_tile_planner *p, uint32_t width, uint32_t height, uint32_t fixed, double budget_ms,
                   uint32_t max_pixels) {
  *p = (rc_tile_planner){.width = width, .height = height, .fixed = fixed, .budget_ms = budget_ms,
                         .max_pixels = max_pixels ? max_pixels : 1};
}

static uint32_t min_u(uint32_t a, uint32_t b) { return a < b ? a : b; }

static uint32_t clamp_u(double v, uint32_t lo, uint32_t hi) {
  if (!(v > lo)) return lo;
  if (v > hi) return hi;
  return (uint32_t)v;
}

/* Host band buffers hold one band: at most max_pixels pixels, and at least one row. */
uint32_t rc_tiles_max_band_rows(const rc_tile_planner *p) {
  uint32_t rows = p->fixed ? p->fixed : (p->max_pixels / p->width ? p->max_pixels / p->width : 1);
  return min_u(rows, p->height);
}

/* Pixels the next dispatch should cover. */
static double target_pixels(const rc_tile_planner *p, uint32_t batch) {
  if (p->budget_ms <= 0) return p->max_pixels;
  if (p->points == 0) return RC_TILES_SEED_PIXELS;
  /* Aim at half the budget. A budget below twice the fixed cost cannot be met: tiles then
   * cost twice the overhead rather than shrinking to nothing. */
  double room = 0.5 * p->budget_ms - p->overhead_ms;
  if (room < p->overhead_ms) room = p->overhead_ms;
  double x = room / (p->slope_ms > 0 ? p->slope_ms : 1e-12);
  return x / (batch ? batch : 1);
}

uint32_t rc_tiles_band_rows(const rc_tile_planner *p, uint32_t y0, uint32_t batch) {
  uint32_t left = p->height - y0, cap = rc_tiles_max_band_rows(p);
  if (p->fixed) return min_u(p->fixed, left);
  double area = target_pixels(p, batch);
  uint32_t rows;
  if (area >= p->width) {
    rows = clamp_u(area / p->width, 1, cap); /* full-width bands */
  } else {
    rows = clamp_u(sqrt(area), 1, cap); /* square tiles */
  }
  /* Whole workgroup rows (8) where that costs nothing, so no lane idles in a partial one. */
  if (rows > 8 && rows < left) rows = rows / 8 * 8;
  return min_u(rows, left);
}

uint32_t rc_tiles_cols(const rc_tile_planner *p, uint32_t rows, uint32_t x0, uint32_t batch) {
  uint32_t left = p->width - x0;
  if (p->fixed) return min_u(p->fixed, left);
  uint32_t cap = p->max_pixels / rows ? p->max_pixels / rows : 1;
  if (p->budget_ms <= 0) return min_u(cap, left);
  return min_u(clamp_u(target_pixels(p, batch) / rows, 8, cap), left);
}

double rc_tiles_predict_ms(const rc_tile_planner *p, double pixels, uint32_t batch) {
  return p->overhead_ms + p->slope_ms * pixels * batch;
}

void rc_tiles_observe(rc_tile_planner *p, double pixels, uint32_t batch, double ms) {
  double x = pixels * (batch ? batch : 1);
  if (!(x > 0) || !(ms >= 0)) return;
  p->points++;
  if (p->points == 1) {
    p->first_x = x;
    p->first_ms = ms;
    p->overhead_ms = 0;
    p->slope_ms = ms / x;
    return;
  }
  if (!p->fitted) {
    /* The two-point fit needs two sizes; the same size again (the next batch of the seed
     * tile) only raises the slope if it was slower. */
    double slope = (ms - p->first_ms) / (x - p->first_x);
    double overhead = p->first_ms - slope * p->first_x;
    if ((x > 1.5 * p->first_x || p->first_x > 1.5 * x) && slope > 0 && overhead >= 0) {
      p->fitted = true;
      p->overhead_ms = fmin(overhead, fmin(ms, p->first_ms));
      p->slope_ms = slope;
    } else if (ms / x > p->slope_ms) {
      p->slope_ms = ms / x;
    }
    return;
  }
  /* A dispatch never costs less than the fixed part. The slope rises at once and decays
   * slowly (a quarter of the way to each new measurement): a mirror sphere can cost
   * several times the background per pixel, and tiles stay sized for it a while after,
   * without one noisy dispatch pinning them small. */
  if (ms < p->overhead_ms) p->overhead_ms = ms;
  double slope = (ms - p->overhead_ms) / x;
  if (!(slope > 0)) return;
  p->slope_ms = slope > p->slope_ms ? slope : 0.75 * p->slope_ms + 0.25 * slope;
}

static uint32_t gcd_u(uint32_t a, uint32_t b) {
  while (b) {
    uint32_t t = a % b;
    a = b;
    b = t;
  }
  return a;
}

uint32_t rc_tiles_row_stride(uint32_t rows) {
  if (rows <= 2) return 1;
  double golden = (double)rows * 0.6180339887498949;
  uint32_t limit = (uint32_t)(UINT32_MAX / rows); /* stride * rows must not wrap */
  uint32_t s = golden < limit ? (uint32_t)golden : limit; /* both >= 1 for rows > 2 */
  while (s > 1 && gcd_u(s, rows) != 1) s--;
  return s;
}
