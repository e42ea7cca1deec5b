/* levels8.h: how a linear value becomes one of an 8-bit file's 256 levels. The formula
 * (rc_level_formula: exposure, curve, clamp, truncation, rounding as OpenImageIO rounds)
 * is evaluated once per level to find the least value that reaches it; a pixel's level is
 * then the number of thresholds at or below its value (rc_level_of: 8 comparisons). Both
 * the image writer and the GPU, which encodes in the shader's last batch (issue 48), look
 * levels up in the same table, so their files are identical by construction, whatever
 * either side's pow() would round to. Where the formula is monotone, and it is for every
 * float in [0, 1] under each curve (docs/numerics.md §11), the table gives its levels
 * exactly. */
#ifndef RC_LEVELS8_H
#define RC_LEVELS8_H

#include <stdbool.h>
#include <stdint.h>

#include "image/image_io.h"

#ifdef __cplusplus
extern "C" {
#endif

#define RC_LEVELS 256

/* threshold[k], 1 <= k <= 255: the least float whose level is k or more (+inf if none
 * has); threshold[0] is 0, never compared. Non-decreasing in k. */
typedef struct rc_levels {
  float threshold[RC_LEVELS];
} rc_levels;

/* The level the writer stored before the table (image_io.cpp): the curve of v * 2^exposure
 * clamped to [0, 1], truncated to a level with `truncate` (the CSE167 format), rounded to
 * the nearest level as OpenImageIO's float to UINT8 conversion does (round half away:
 * checked against it for every float in [0, 1]). NaN and negatives are level 0. */
uint8_t rc_level_formula(rc_encoding enc, bool truncate, float v);

/* The table of `enc` and `truncate`: 255 binary searches over the floats' bit patterns. */
void rc_levels_make(rc_encoding enc, bool truncate, rc_levels *out);

/* The level of v: how many of threshold[1..255] are <= v (NaN: 0). A binary search;
 * before the step of size s, k is a sum of larger steps, at most 256 - 2s, so k + s never
 * passes 255. The shader's encode_levels is its twin. */
static inline uint8_t rc_level_of(const rc_levels *t, float v) {
  unsigned k = 0;
  for (unsigned step = RC_LEVELS / 2; step; step >>= 1)
    if (v >= t->threshold[k + step]) k += step;
  return (uint8_t)k;
}

/* The same table for a pixel's sum of `spp` samples, whose value the host computes as
 * sum / (float)spp: threshold[k] becomes the least float s with s / spp >= the value's
 * threshold[k] (IEEE division is monotone, so the comparison is exact). The GPU compares
 * sums with it and never divides. */
void rc_levels_of_sums(const rc_levels *values, uint32_t spp, rc_levels *out);

#ifdef __cplusplus
}
#endif

#endif
