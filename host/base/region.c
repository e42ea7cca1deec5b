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
