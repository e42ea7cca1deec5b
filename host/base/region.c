#include "base/region.h"


/* One decimal number of at most 9 digits (every frame side is far below 10^9). */
static bool parse_uint(const char **s, uint32_t *v) {
  const char *p = *s;
  uint64_t x = 0;
  int digits = 0;
  while (*p >= '0' && *p <= '9' && digits < 10) x = 10 * x + (uint64_t)(*p++ - '0'), digits++;
  if (digits == 0 || digits > 9) return false;
  *v = (uint32_t)x;
  *s = p;
  return true;
}

bool rc_region_parse(const char *text, rc_region *r, const char **why) {
  uint32_t v[4];
  const char *p = text;
  for (int i = 0; i < 4; i++) {
    if (!parse_uint(&p, &v[i]) || *p != (i < 3 ? ',' : '\0')) {
      *why = "expected X0,Y0,X1,Y1: four whole numbers of pixels, columns [X0, X1) and rows [Y0, Y1)";
      return false;
    }
    p++;
  }
  if (v[0] >= v[2] || v[1] >= v[3]) {
    *why = "the region is empty: X0 < X1 and Y0 < Y1 are needed";
    return false;
  }
  *r = (rc_region){v[0], v[1], v[2], v[3]};
  return true;
}

bool rc_shard_parse(const char *text, uint32_t *index, uint32_t *count, const char **why) {
  const char *p = text;
  if (!parse_uint(&p, index) || *p++ != '/' || !parse_uint(&p, count) || *p != '\0') {
    *why = "expected I/N: shard I of N, 0 <= I < N";
    return false;
  }
  if (*count == 0 || *index >= *count) {
    *why = "shards are numbered 0 to N-1 (Slurm's $SLURM_ARRAY_TASK_ID with --array=0-(N-1))";
    return false;
  }
  return true;
}

void rc_shard_rows(const double *row_cost, uint32_t height, uint32_t index, uint32_t count, uint32_t *y0,
                   uint32_t *y1) {
  double total = 0;
  for (uint32_t y = 0; row_cost && y < height; y++) total += row_cost[y];
  bool equal = !row_cost || !(total > 0);
  /* Cuts in order, each at the row where the cost before it (a row counting half on
   * either side of its middle) reaches k/count of the total, then kept one row past the
   * previous cut and far enough from the end to leave a row to each later shard. */
  uint32_t prev = 0, y = 0;
  double sum = 0;
  for (uint32_t k = 1; k <= index + 1; k++) {
    uint32_t c;
    if (k == count) {
      c = height;
    } else if (equal) {
      c = (uint32_t)((uint64_t)height * k / count);
    } else {
      double target = total * k / count;
      while (y < height && sum + row_cost[y] * 0.5 < target) sum += row_cost[y++];
      c = y;
    }
    if (c < prev + 1) c = prev + 1;
    if (c > height - (count - k)) c = height - (count - k);
    if (k == index) *y0 = c;
    prev = c;
  }
  if (index == 0) *y0 = 0;
  *y1 = prev;
}
