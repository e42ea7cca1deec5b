/* Regions and shards (host/base/region.c): parsing, the cuts of shards by cost, and the
 * coverage check that `vkraycast merge` relies on. Pure arithmetic, no device. */
#include "cli/part.h"
#include "base/region.h"
#include "rc_test.h"

#include <stdlib.h>
#include <string.h>
#include <stdio.h>

TEST(parse) {
  rc_region r;
  const char *why = NULL;
  CHECK(rc_region_parse("0,0,640,480", &r, &why));
  CHECK(r.x0 == 0 && r.y0 == 0 && r.x1 == 640 && r.y1 == 480);
  CHECK(rc_region_parse("10,20,11,21", &r, &why) && rc_region_pixels(r) == 1);
  const char *bad[] = {"", "1,2,3", "1,2,3,4,5", "0,0,0,10", "5,0,4,10", "0,0,10,-1", " 0,0,1,1", "0,0,1,1 ",
                       "0x0,0,1,1", "0,0,1,10000000000", "a,b,c,d"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    why = NULL;
    CHECK(!rc_region_parse(bad[i], &r, &why) && why != NULL);
  }
  uint32_t i, n;
  CHECK(rc_shard_parse("0/1", &i, &n, &why) && i == 0 && n == 1);
  CHECK(rc_shard_parse("3/4", &i, &n, &why) && i == 3 && n == 4);
  const char *bad_shards[] = {"4/4", "0/0", "1", "1/", "/4", "-1/4", "1/4/5", "1 /4"};
  for (size_t k = 0; k < sizeof bad_shards / sizeof *bad_shards; k++) CHECK(!rc_shard_parse(bad_shards[k], &i, &n, &why));
}

/* A grid of one column of 1-pixel-tall cells: the costs of the rows of a frame whose
 * rows are uniform across. */
static rc_cost_grid rows_grid(const double *cost, uint32_t height) {
  return (rc_cost_grid){cost, 1, height, 1u << 20, 1};
}

/* The shards of one count tile the frame (merge's own coverage check), each at least a
 * pixel; returns the largest shard's cost over the fair share (total / count). */
static double check_tiling(const rc_cost_grid *g, uint32_t width, uint32_t height, uint32_t count) {
  rc_region *r = calloc(count, sizeof *r);
  double total = 0, worst = 0;
  for (uint32_t y = 0; y < height; y++)
    for (uint32_t x = 0; x < width; x++) total += g ? g->cost[(y / g->cell_h) * g->cols + x / g->cell_w] : 1;
  for (uint32_t k = 0; k < count; k++) {
    CHECK(rc_shard_region(g, width, height, k, count, &r[k]));
    CHECK(rc_region_pixels(r[k]) >= 1);
    double sum = 0;
    for (uint32_t y = r[k].y0; y < r[k].y1; y++)
      for (uint32_t x = r[k].x0; x < r[k].x1; x++) sum += g ? g->cost[(y / g->cell_h) * g->cols + x / g->cell_w] : 1;
    if (total > 0 && sum / (total / count) > worst) worst = sum / (total / count);
  }
  size_t a, b;
  rc_region gap;
  CHECK_EQ_INT(rc_region_coverage(r, count, width, height, &a, &b, &gap), 0);
  free(r);
  return worst;
}

TEST(shards_tile_the_frame) {
  double cost[300];
  for (uint32_t y = 0; y < 300; y++) cost[y] = y < 200 ? 1.0 : 50.0; /* sky, then a mirror */
  rc_cost_grid g = rows_grid(cost, 300);
  for (uint32_t count = 1; count <= 300; count += count < 10 ? 1 : 37) {
    check_tiling(NULL, 40, 300, count);
    check_tiling(&g, 40, 300, count);
  }
  check_tiling(&g, 40, 300, 300); /* as many shards as rows */
  check_tiling(&g, 1, 300, 300);  /* one pixel each */
  /* One row holding all the cost: the others still get a pixel each. */
  double spike[7] = {0, 0, 0, 100, 0, 0, 0};
  rc_cost_grid s = rows_grid(spike, 7);
  for (uint32_t count = 1; count <= 7; count++) check_tiling(&s, 1, 7, count);
  double zero[6] = {0};
  rc_cost_grid z = rows_grid(zero, 6);
  check_tiling(&z, 3, 6, 3);
  /* No cost anywhere: cut by pixels, as with no estimate. */
  for (uint32_t k = 0; k < 3; k++) {
    rc_region a, b;
    CHECK(rc_shard_region(&z, 3, 6, k, 3, &a) && rc_shard_region(NULL, 3, 6, k, 3, &b));
    CHECK(a.y0 == 2 * k && a.y1 == 2 * k + 2 && b.y0 == a.y0 && b.y1 == a.y1);
  }
}

TEST(shards_balance_cost) {
  /* 200 cheap rows, then 100 rows 50 times costlier: 4 bands of 1/4 of the cost each
   * (5,200 / 4 = 1,300): the first takes all the cheap rows and 22 costly ones. */
  double cost[300], total = 0;
  for (uint32_t y = 0; y < 300; y++) total += cost[y] = y < 200 ? 1.0 : 50.0;
  rc_cost_grid g = rows_grid(cost, 300);
  rc_region r;
  CHECK(rc_shard_region(&g, 40, 300, 0, 4, &r));
  CHECK(r.x0 == 0 && r.x1 == 40 && r.y0 == 0 && r.y1 == 222);
  /* Every shard a full-width band, within one row's cost of the ideal quarter. */
  for (uint32_t k = 0; k < 4; k++) {
    CHECK(rc_shard_region(&g, 40, 300, k, 4, &r));
    CHECK(r.x0 == 0 && r.x1 == 40);
  }
  CHECK(check_tiling(&g, 40, 300, 4) <= 1 + 50.0 * 4 / total);
  /* Equal costs: equal bands, the remainder spread. */
  CHECK(rc_shard_region(NULL, 8, 10, 1, 3, &r));
  CHECK(r.y0 == 3 && r.y1 == 6 && r.x0 == 0 && r.x1 == 8);
}

TEST(hot_rows_become_tiles) {
  /* A 64 x 48 frame whose row 20 holds 90 % of the cost (a strip of mirrors seen edge on):
   * bands alone would give 8 shards a worst load of 7.2 times the fair share (the row's
   * shard); tiles of the hot row bring it to within 10 % of it. */
  double cost[48];
  for (uint32_t y = 0; y < 48; y++) cost[y] = y == 20 ? 0.9 * 47 / 0.1 : 1.0;
  rc_cost_grid g = rows_grid(cost, 48);
  double worst = check_tiling(&g, 64, 48, 8);
  CHECK(worst < 1.10);
  bool tiles = false;
  for (uint32_t k = 0; k < 8; k++) {
    rc_region r;
    CHECK(rc_shard_region(&g, 64, 48, k, 8, &r));
    tiles = tiles || r.x1 - r.x0 < 64;
  }
  CHECK(tiles);
  /* Cells of a real estimate's shape (4 x 4 pixels, 16 x 12 of them), one hot cell
   * row, and every count up to the rows. */
  double cells[16 * 12];
  for (uint32_t i = 0; i < 16 * 12; i++) cells[i] = i / 16 == 5 ? 400.0 + i % 7 : 8.0 + i % 3;
  rc_cost_grid c = {cells, 16, 12, 4, 4};
  for (uint32_t count = 1; count <= 48; count++) {
    double w = check_tiling(&c, 64, 48, count);
    CHECK(count < 2 || w < 2.0);
  }
}

TEST(coverage) {
  uint32_t w = 64, h = 48;
  size_t a = 99, b = 99;
  rc_region gap;
  rc_region whole[] = {{0, 0, 64, 48}};
  CHECK_EQ_INT(rc_region_coverage(whole, 1, w, h, &a, &b, &gap), 0);
  /* Uneven rectangles that tile the frame. */
  rc_region tiles[] = {{0, 0, 64, 10}, {0, 10, 17, 48}, {17, 10, 64, 30}, {17, 30, 40, 48}, {40, 30, 64, 48}};
  CHECK_EQ_INT(rc_region_coverage(tiles, 5, w, h, &a, &b, &gap), 0);
  /* One missing: the gap is that rectangle. */
  rc_region missing[] = {{0, 0, 64, 10}, {0, 10, 17, 48}, {17, 30, 40, 48}, {40, 30, 64, 48}};
  CHECK_EQ_INT(rc_region_coverage(missing, 4, w, h, &a, &b, &gap), 2);
  CHECK(gap.x0 == 17 && gap.y0 == 10 && gap.x1 == 64 && gap.y1 == 30);
  /* A part given twice. */
  rc_region twice[] = {{0, 0, 64, 10}, {0, 10, 64, 48}, {0, 0, 64, 10}};
  CHECK_EQ_INT(rc_region_coverage(twice, 3, w, h, &a, &b, &gap), 1);
  CHECK(a == 0 && b == 2);
  /* Overlap by one pixel, with the areas adding up to the frame's. */
  rc_region shifted[] = {{0, 0, 64, 11}, {0, 10, 64, 47}};
  CHECK_EQ_INT(rc_region_coverage(shifted, 2, w, h, &a, &b, &gap), 1);
  /* Outside the frame. */
  rc_region outside[] = {{0, 0, 65, 48}};
  CHECK_EQ_INT(rc_region_coverage(outside, 1, w, h, &a, &b, &gap), 3);
  CHECK(a == 0);
  /* A hole in the middle of a row. */
  rc_region hole[] = {{0, 0, 64, 20}, {0, 20, 30, 21}, {31, 20, 64, 21}, {0, 21, 64, 48}};
  CHECK_EQ_INT(rc_region_coverage(hole, 4, w, h, &a, &b, &gap), 2);
  CHECK(gap.x0 == 30 && gap.y0 == 20 && gap.x1 == 31 && gap.y1 == 21);
}

/* A random guillotine tiling of a w x h frame into at most max rectangles. */
static size_t tile(rc_region *out, size_t max, rc_region r, unsigned *seed) {
  uint32_t w = r.x1 - r.x0, h = r.y1 - r.y0;
  if (max < 2 || (w < 2 && h < 2) || rand_r(seed) % 4 == 0) {
    out[0] = r;
    return 1;
  }
  rc_region a = r, b = r;
  if (w >= 2 && (h < 2 || rand_r(seed) % 2)) {
    a.x1 = b.x0 = r.x0 + 1 + (uint32_t)rand_r(seed) % (w - 1);
  } else {
    a.y1 = b.y0 = r.y0 + 1 + (uint32_t)rand_r(seed) % (h - 1);
  }
  size_t n = tile(out, max / 2, a, seed);
  return n + tile(out + n, max - n, b, seed);
}

/* The coverage verdict by counting every pixel (the oracle), and for a gap its rectangle
 * as rc_region_coverage defines it. */
static int oracle(const rc_region *parts, size_t n, uint32_t w, uint32_t h, rc_region *gap) {
  static unsigned char count[64 * 64];
  memset(count, 0, sizeof count);
  for (size_t i = 0; i < n; i++)
    for (uint32_t y = parts[i].y0; y < parts[i].y1; y++)
      for (uint32_t x = parts[i].x0; x < parts[i].x1; x++)
        if (++count[y * w + x] > 1) return 1;
  for (uint32_t y = 0; y < h; y++)
    for (uint32_t x = 0; x < w; x++) {
      if (count[y * w + x]) continue;
      uint32_t x1 = x;
      while (x1 < w && !count[y * w + x1]) x1++;
      uint32_t y1 = y + 1;
      for (bool empty = true; empty && y1 < h; y1 += empty) {
        for (uint32_t k = x; k < x1; k++) empty = empty && !count[y1 * w + k];
      }
      *gap = (rc_region){x, y, x1, y1};
      return 2;
    }
  return 0;
}

static bool share_a_pixel(rc_region p, rc_region q) {
  return p.x0 < q.x1 && q.x0 < p.x1 && p.y0 < q.y1 && q.y0 < p.y1;
}

/* Generated: 3,000 random tilings of frames up to 64 x 64, each as it is, with one or two
 * parts taken out, a part given twice, a part moved by one pixel, and a part one column
 * narrower; the sweep's verdict and gap against counting every pixel. */
TEST(coverage_generated) {
  unsigned seed = 45;
  rc_region parts[80], gap = {0}, want_gap = {0};
  int wrong = 0;
  for (int round = 0; round < 3000; round++) {
    uint32_t w = 1 + (uint32_t)rand_r(&seed) % 64, h = 1 + (uint32_t)rand_r(&seed) % 64;
    size_t n = tile(parts, 40, (rc_region){0, 0, w, h}, &seed);
    /* Shuffle: the verdict must not depend on the parts' order. */
    for (size_t i = n; i > 1; i--) {
      size_t j = (size_t)rand_r(&seed) % i;
      rc_region t = parts[i - 1];
      parts[i - 1] = parts[j];
      parts[j] = t;
    }
    int how = round % 6;
    size_t k = (size_t)rand_r(&seed) % n;
    if (how == 1 && n > 1) parts[k] = parts[--n];
    if (how == 4 && n > 2) { /* two out: gaps of other shapes than a rectangle */
      parts[k] = parts[--n];
      parts[(size_t)rand_r(&seed) % n] = parts[n - 1];
      n--;
    }
    if (how == 5 && parts[k].x1 - parts[k].x0 > 1) parts[k].x1--;
    if (how == 2) parts[n++] = parts[k];
    if (how == 3) {
      rc_region *p = &parts[k];
      if (p->x1 < w) p->x0++, p->x1++;
      else if (p->x0 > 0) p->x0--, p->x1--;
    }
    size_t a = SIZE_MAX, b = SIZE_MAX;
    int got = rc_region_coverage(parts, n, w, h, &a, &b, &gap);
    int want = oracle(parts, n, w, h, &want_gap);
    bool ok = got == want;
    if (ok && got == 1) ok = a < b && b < n && share_a_pixel(parts[a], parts[b]);
    if (ok && got == 2)
      ok = gap.x0 == want_gap.x0 && gap.y0 == want_gap.y0 && gap.x1 == want_gap.x1 && gap.y1 == want_gap.y1;
    if (!ok && wrong++ < 5) printf("  round %d (%ux%u, %zu parts, change %d): verdict %d, expected %d\n", round, w, h, n, how, got, want);
  }
  CHECK_EQ_INT(wrong, 0);
}

/* What a header may declare cannot make the check slow: 4,096 one-row bands of a
 * 4,096 x 65,536 frame with the last missing, and three parts of a 4e9 x 4e9 frame. */
TEST(coverage_at_scale) {
  size_t n = 4096, a, b;
  rc_region *bands = malloc(n * sizeof *bands), gap;
  if (!bands) { CHECK(false); return; }
  for (size_t i = 0; i < n; i++) bands[i] = (rc_region){0, (uint32_t)(16 * i), 4096, (uint32_t)(16 * i + 16)};
  CHECK_EQ_INT(rc_region_coverage(bands, n, 4096, 65536, &a, &b, &gap), 0);
  CHECK_EQ_INT(rc_region_coverage(bands, n - 1, 4096, 65536, &a, &b, &gap), 2);
  CHECK(gap.x0 == 0 && gap.y0 == 65520 && gap.x1 == 4096 && gap.y1 == 65536);
  /* Every band twice, in reverse: the first pair found is the topmost. */
  for (size_t i = 0; i < n; i++) bands[i] = (rc_region){0, (uint32_t)(i / 2), 7, (uint32_t)(i / 2 + 1)};
  CHECK_EQ_INT(rc_region_coverage(bands, n, 7, 2048, &a, &b, &gap), 1);
  CHECK(a == 0 && b == 1);
  free(bands);
  rc_region huge[] = {{0, 0, 4000000000u, 1}, {0, 2, 4000000000u, 4000000000u}, {5, 1, 4000000000u, 2}};
  CHECK_EQ_INT(rc_region_coverage(huge, 3, 4000000000u, 4000000000u, &a, &b, &gap), 2);
  CHECK(gap.x0 == 0 && gap.y0 == 1 && gap.x1 == 5 && gap.y1 == 2);
}

/* The settings string of a part's header (part.c): one setting's value, and the first
 * setting in which two strings differ. */
TEST(part_settings) {
  const char *s = "backend=gpu precision=f32 spp=16 encoding=srgb quantize=round";
  char v[16], a[32], b[32];
  rc_part_setting(s, "encoding", v, sizeof v);
  CHECK(strcmp(v, "srgb") == 0);
  rc_part_setting(s, "quantize", v, sizeof v);
  CHECK(strcmp(v, "round") == 0);
  rc_part_setting(s, "backend", v, sizeof v);
  CHECK(strcmp(v, "gpu") == 0);
  rc_part_setting(s, "spp", v, 3); /* truncated to the buffer */
  CHECK(strcmp(v, "16") == 0);
  rc_part_setting(s, "sp", v, sizeof v); /* a prefix of a name is not the name */
  CHECK(v[0] == '\0');
  rc_part_setting(s, "shadows", v, sizeof v);
  CHECK(v[0] == '\0');
  CHECK(!rc_part_settings_differ(s, s, a, sizeof a, b, sizeof b));
  CHECK(rc_part_settings_differ(s, "backend=gpu precision=f32 spp=1 encoding=srgb quantize=round", a, sizeof a, b,
                                sizeof b));
  CHECK(strcmp(a, "spp=16") == 0 && strcmp(b, "spp=1") == 0);
  CHECK(rc_part_settings_differ(s, "backend=gpu precision=f32", a, sizeof a, b, sizeof b));
  CHECK(strcmp(a, "spp=16") == 0 && b[0] == '\0');
}

/* The 8-bit encoding in a part's settings: written, read back the same; absent (parts of
 * older builds) is linear at exposure 0; anything render does not write is refused. */
TEST(part_encoding) {
  char text[96], settings[160];
  rc_encoding in = {RC_CURVE_GAMMA, 2.2f, 0.5f}, out;
  rc_part_encoding_text(in, text, sizeof text);
  CHECK(strcmp(text, "encoding=gamma2.20000005 exposure=0.5") == 0);
  snprintf(settings, sizeof settings, "backend=gpu %s quantize=round", text);
  CHECK(rc_part_encoding(settings, &out));
  CHECK(out.curve == RC_CURVE_GAMMA && out.gamma == in.gamma && out.exposure == in.exposure);
  CHECK(rc_part_encoding("backend=gpu encoding=srgb quantize=round", &out));
  CHECK(out.curve == RC_CURVE_SRGB && out.exposure == 0);
  CHECK(rc_part_encoding("backend=gpu quantize=round", &out));
  CHECK(out.curve == RC_CURVE_LINEAR && out.exposure == 0);
  const char *refused[] = {"encoding=gamma0", "encoding=gamma", "encoding=gammax", "encoding=gamma2.2x",
                           "encoding=gamma1e999", "encoding=cie", "encoding=linear exposure=65",
                           "encoding=linear exposure=nan"};
  for (size_t i = 0; i < sizeof refused / sizeof *refused; i++) CHECK(!rc_part_encoding(refused[i], &out));
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(parse);
  RUN(shards_tile_the_frame);
  RUN(shards_balance_cost);
  RUN(hot_rows_become_tiles);
  RUN(coverage);
  RUN(coverage_generated);
  RUN(coverage_at_scale);
  RUN(part_settings);
  RUN(part_encoding);
  TEST_MAIN_END
}
