/* The tile planner (host/gpu/gpu_tiles.c) driven by simulated devices: each dispatch's time is
 * computed from a cost model, never read from a clock, so every figure here is exact and
 * the test cannot depend on the machine's load. */
#include "gpu/gpu_tiles.h"
#include "rc_test.h"

#include <math.h>
#include <stdlib.h>

#define MAX_PIXELS (1u << 20)

/* A simulated device: a fixed cost per dispatch plus a per-pixel-sample cost that may
 * depend on where the pixel lies (cost_scale over a region, like a mirror sphere). */
typedef struct {
  double overhead_ms, per_sample_ms;
  uint32_t hot_x0, hot_y0, hot_x1, hot_y1; /* pixels in this box cost hot_scale times more */
  double hot_scale;
} device;

static double dispatch_ms(const device *d, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h, uint32_t batch) {
  double units = 0;
  for (uint32_t y = y0; y < y0 + h; y++) {
    for (uint32_t x = x0; x < x0 + w; x++) {
      bool hot = x >= d->hot_x0 && x < d->hot_x1 && y >= d->hot_y0 && y < d->hot_y1;
      units += hot ? d->hot_scale : 1.0;
    }
  }
  return d->overhead_ms + d->per_sample_ms * units * batch;
}

typedef struct {
  uint32_t dispatches, over_budget, covered_pixels;
  double longest_ms, longest_after_seed_ms;
  bool overlap_or_gap;
} frame_result;

/* Renders a frame through the planner as gpu_render.c does (bands, tiles, batches). */
static frame_result run_frame(const device *d, uint32_t w, uint32_t h, uint32_t fixed, double budget, uint32_t spp,
                              uint32_t batch) {
  frame_result res = {0};
  rc_tile_planner p;
  rc_tiles_init(&p, w, h, fixed, budget, MAX_PIXELS);
  unsigned char *seen = calloc((size_t)w * h, 1);
  for (uint32_t y0 = 0; y0 < h;) {
    uint32_t rows = rc_tiles_band_rows(&p, y0, batch);
    if (rows == 0 || rows > rc_tiles_max_band_rows(&p)) {
      res.overlap_or_gap = true;
      break;
    }
    for (uint32_t x0 = 0; x0 < w;) {
      uint32_t cols = rc_tiles_cols(&p, rows, x0, batch);
      if (cols == 0 || (uint64_t)cols * rows > MAX_PIXELS) {
        res.overlap_or_gap = true;
        free(seen);
        return res;
      }
      for (uint32_t y = y0; y < y0 + rows; y++)
        for (uint32_t x = x0; x < x0 + cols; x++) {
          if (seen[(size_t)y * w + x]++) res.overlap_or_gap = true;
          res.covered_pixels++;
        }
      for (uint32_t done = 0; done < spp; done += batch) {
        uint32_t b = spp - done < batch ? spp - done : batch;
        double ms = dispatch_ms(d, x0, y0, cols, rows, b);
        rc_tiles_observe(&p, (double)cols * rows, b, ms);
        if (ms > res.longest_ms) res.longest_ms = ms;
        if (res.dispatches > 0 && ms > res.longest_after_seed_ms) res.longest_after_seed_ms = ms;
        if (budget > 0 && ms > budget) res.over_budget++;
        res.dispatches++;
      }
      x0 += cols;
    }
    y0 += rows;
  }
  free(seen);
  return res;
}

TEST(no_budget_takes_the_fewest_dispatches) {
  /* lavapipe-like: 8 ms a dispatch. 640 x 400 in one dispatch; 16384^2 in bands of 64 full
   * rows (2^20 pixels each), 256 dispatches rather than thousands. */
  device d = {.overhead_ms = 8, .per_sample_ms = 1e-3};
  frame_result r = run_frame(&d, 640, 400, 0, 0, 1, 1);
  CHECK(!r.overlap_or_gap);
  CHECK_EQ_INT(r.covered_pixels, 640 * 400);
  CHECK_EQ_INT(r.dispatches, 1);
  rc_tile_planner p;
  rc_tiles_init(&p, 16384, 16384, 0, 0, MAX_PIXELS);
  CHECK_EQ_INT(rc_tiles_max_band_rows(&p), 64);
  CHECK_EQ_INT(rc_tiles_band_rows(&p, 0, 1), 64);
  CHECK_EQ_INT(rc_tiles_cols(&p, 64, 0, 1), 16384);
  /* Batches still split the samples: 16 spp in batches of 6 are 3 dispatches. */
  r = run_frame(&d, 320, 240, 0, 0, 16, 6);
  CHECK_EQ_INT(r.dispatches, 3);
}

TEST(fixed_tiles_are_fixed) {
  device d = {.overhead_ms = 1, .per_sample_ms = 1e-4};
  frame_result r = run_frame(&d, 100, 70, 32, 100, 1, 1);
  CHECK(!r.overlap_or_gap);
  CHECK_EQ_INT(r.covered_pixels, 100 * 70);
  CHECK_EQ_INT(r.dispatches, 4 * 3);
}

TEST(small_scenes_take_one_or_two_dispatches_under_a_budget) {
  /* A real GPU: 0.05 ms a dispatch, 20 ns a pixel-sample. 480 x 320 at 1 spp fits the
   * budget many times over: the seed band, then the rest. */
  device d = {.overhead_ms = 0.05, .per_sample_ms = 2e-5};
  frame_result r = run_frame(&d, 480, 320, 0, 100, 1, 1);
  CHECK(!r.overlap_or_gap);
  CHECK_EQ_INT(r.covered_pixels, 480 * 320);
  CHECK(r.dispatches <= 2);
  CHECK_EQ_INT(r.over_budget, 0);
  /* An image smaller than the seed: one dispatch. */
  r = run_frame(&d, 64, 48, 0, 100, 1, 1);
  CHECK_EQ_INT(r.dispatches, 1);
}

TEST(big_frames_stay_within_the_budget) {
  /* A slow device: 2 ms a dispatch, 1 us a pixel-sample, 1920 x 1080 at 16 spp in batches
   * of 4: the whole frame would take 33 s, each dispatch must stay under 100 ms. */
  device d = {.overhead_ms = 2, .per_sample_ms = 1e-3};
  frame_result r = run_frame(&d, 1920, 1080, 0, 100, 16, 4);
  CHECK(!r.overlap_or_gap);
  CHECK_EQ_INT(r.covered_pixels, 1920 * 1080);
  CHECK_EQ_INT(r.over_budget, 0);
  CHECK(r.longest_ms <= 100);
  /* Not timid either: dispatches use a fair share of the budget (over 30 ms on average). */
  CHECK(33177.6 / r.dispatches > 30);
}

TEST(a_costly_region_does_not_break_the_budget) {
  /* A band in the middle of the frame costs 6x per pixel (a mirror sphere): the planner
   * aims at half the budget, so the first tile that meets the region can be up to 2x too
   * big, not 6x; after it the slope has risen. */
  device d = {.overhead_ms = 1, .per_sample_ms = 2e-4, .hot_x0 = 0, .hot_x1 = 4096, .hot_y0 = 700, .hot_y1 = 1400,
              .hot_scale = 6};
  frame_result r = run_frame(&d, 2048, 2048, 0, 100, 1, 1);
  CHECK(!r.overlap_or_gap);
  CHECK_EQ_INT(r.covered_pixels, 2048 * 2048);
  CHECK(r.longest_after_seed_ms <= 3.0 * 100);
  CHECK(r.over_budget <= 2);
}

TEST(an_overhead_above_the_budget_keeps_tiles_useful) {
  /* A budget below the fixed cost cannot be met; tiles then cost about twice the overhead
   * instead of shrinking to a pixel (here 30 ms overhead against a 40 ms budget). */
  device d = {.overhead_ms = 30, .per_sample_ms = 1e-3};
  frame_result r = run_frame(&d, 640, 400, 0, 40, 1, 1);
  CHECK(!r.overlap_or_gap);
  CHECK(r.dispatches < 20);
  CHECK(r.longest_after_seed_ms <= 2.5 * 30 + 1e-9);
}

TEST(the_two_point_fit_recovers_the_device) {
  rc_tile_planner p;
  rc_tiles_init(&p, 1000, 1000, 0, 100, MAX_PIXELS);
  rc_tiles_observe(&p, 10000, 1, 8 + 0.001 * 10000);
  CHECK_NEAR(p.overhead_ms, 0, 0);                    /* one point: all time charged to pixels */
  CHECK_NEAR(rc_tiles_predict_ms(&p, 20000, 1), 36, 1e-9); /* which over-estimates */
  rc_tiles_observe(&p, 40000, 1, 8 + 0.001 * 40000);
  CHECK(p.fitted);
  CHECK_NEAR(p.overhead_ms, 8, 1e-9);
  CHECK_NEAR(p.slope_ms, 0.001, 1e-12);
  /* Next dispatch aims at half the budget: (50 - 8) / 0.001 = 42,000 pixels = 42 rows. */
  CHECK_EQ_INT(rc_tiles_band_rows(&p, 0, 1), 40);
}

TEST(noise_never_makes_a_negative_model) {
  /* The bigger dispatch measured faster (a loaded machine): no fit; the slope only rises. */
  rc_tile_planner p;
  rc_tiles_init(&p, 1000, 1000, 0, 100, MAX_PIXELS);
  rc_tiles_observe(&p, 10000, 1, 30);
  rc_tiles_observe(&p, 40000, 1, 20);
  CHECK(!p.fitted);
  CHECK(p.slope_ms >= 30.0 / 10000);
  CHECK(rc_tiles_band_rows(&p, 0, 1) >= 1);
  CHECK(rc_tiles_cols(&p, 1, 0, 1) >= 8);
}

/* How a dispatch of `rows` x `cols` workgroups, its rows visited in `stride` order
 * (raycast.comp), falls to T threads as Mesa 22.3's lp_cs_tpool.c splits it: each thread
 * takes one contiguous run of iterations (workgroups in dispatch order, x fastest), the
 * last total % T one by one. An image row is costly (`hot`, else 1) inside the fraction
 * [hot_lo, hot_hi) of the rows: a band of floor and mirrors, say. Returns the busiest
 * thread's cost over the idlest one's, and in *deviation the largest difference, in rows,
 * between a thread's costly workgroups and its fair share of them. */
static double thread_split(uint32_t rows, uint32_t cols, uint32_t threads, uint32_t stride, double hot_lo,
                           double hot_hi, double hot, double *deviation) {
  double cost[64] = {0}, hot_groups[64] = {0}, groups[64] = {0};
  uint32_t total = rows * cols, per = total / threads, hot_rows = 0;
  for (uint32_t row = 0; row < rows; row++) {
    double y = (row + 0.5) / rows;
    hot_rows += y >= hot_lo && y < hot_hi;
  }
  for (uint32_t i = 0; i < total; i++) {
    uint32_t t = i < per * threads ? i / per : (i - per * threads) % threads;
    uint32_t row = (uint32_t)(((uint64_t)(i / cols) * stride) % rows);
    double y = (row + 0.5) / rows;
    bool is_hot = y >= hot_lo && y < hot_hi;
    cost[t] += is_hot ? hot : 1.0;
    hot_groups[t] += is_hot;
    groups[t]++;
  }
  double lo = cost[0], hi = cost[0];
  *deviation = 0;
  for (uint32_t t = 0; t < threads; t++) {
    if (cost[t] < lo) lo = cost[t];
    if (cost[t] > hi) hi = cost[t];
    double off = fabs(hot_groups[t] - groups[t] * hot_rows / rows) / cols;
    if (off > *deviation) *deviation = off;
  }
  return hi / lo;
}

TEST(row_order_is_a_permutation_that_cannot_wrap) {
  const uint32_t rows[] = {1, 2, 3, 4, 5, 12, 50, 96, 97, 128, 1000, 65535, 65536, 1u << 20, 4000000000u};
  for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
    uint32_t n = rows[k], s = rc_tiles_row_stride(n);
    CHECK(s >= 1);
    CHECK((uint64_t)s * (n - 1) <= UINT32_MAX);
    if (n > 100000) continue;
    unsigned char *hit = calloc(n, 1);
    for (uint32_t i = 0; i < n; i++) hit[(i * s) % n]++;
    bool once = true;
    for (uint32_t i = 0; i < n; i++) once = once && hit[i] == 1;
    CHECK(once);
    free(hit);
  }
}

TEST(row_order_balances_llvmpipes_threads) {
  /* The showcase at 640x400 (50 rows of 8x8 workgroups, 80 columns): sky above, floor
   * and mirrors below at about 3 times the cost. In dispatch order one thread takes all
   * the floor and 3 times as long as the other; in stride order they are within 5 %. */
  double dev;
  CHECK(thread_split(50, 80, 2, 1, 0.5, 1.0, 3.0, &dev) > 2.9);
  CHECK(dev > 12);
  CHECK(thread_split(50, 80, 2, rc_tiles_row_stride(50), 0.5, 1.0, 3.0, &dev) < 1.05);
  /* Any frame height, thread count and costly band: each thread's share of the costly
   * rows is fair to within 1 + log2(rows) / 2 rows (the discrepancy of Kronecker's
   * sequence grows as log n); dispatch order misses by up to all of them. Whole rows are
   * the unit, so with few rows a thread the time ratio can still be 1.5. */
  const uint32_t heights[] = {16, 50, 96, 128, 135, 256, 1000, 2048};
  const double bands[][2] = {{0.5, 1.0}, {0.0, 0.3}, {0.4, 0.6}, {0.7, 0.8}, {0.1, 0.15}};
  for (size_t h = 0; h < sizeof heights / sizeof heights[0]; h++)
    for (uint32_t threads = 2; threads <= 32; threads *= 2)
      for (size_t b = 0; b < sizeof bands / sizeof bands[0]; b++) {
        uint32_t n = heights[h];
        if (n < 2 * threads) continue;
        thread_split(n, 7, threads, rc_tiles_row_stride(n), bands[b][0], bands[b][1], 3.0, &dev);
        CHECK(dev <= 1 + log2(n) / 2);
      }
  thread_split(1000, 7, 4, 1, 0.0, 0.3, 3.0, &dev);
  CHECK(dev > 100);
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(no_budget_takes_the_fewest_dispatches);
  RUN(fixed_tiles_are_fixed);
  RUN(small_scenes_take_one_or_two_dispatches_under_a_budget);
  RUN(big_frames_stay_within_the_budget);
  RUN(a_costly_region_does_not_break_the_budget);
  RUN(an_overhead_above_the_budget_keeps_tiles_useful);
  RUN(the_two_point_fit_recovers_the_device);
  RUN(noise_never_makes_a_negative_model);
  RUN(row_order_is_a_permutation_that_cannot_wrap);
  RUN(row_order_balances_llvmpipes_threads);
  TEST_MAIN_END
}
