/* certified_marks.h: what certified mode's f32 pass leaves in a pixel's record for the f64
 * re-render (packed_aov: uncertified, uncertified_mask, certified_sum), read alike by the
 * CPU reference's re-render, the GPU's and the statistics. raycast.comp reads the same. */
#ifndef RC_CERTIFIED_MARKS_H
#define RC_CERTIFIED_MARKS_H

#include <stdbool.h>
#include <stdint.h>

#include "rc_shared.h"

/* True when the bits name every uncertified sample, so that only those are rendered again,
 * added to certified_sum. They cannot where a sample from 32 on is uncertified, or where the
 * GPU counted light passes (which set no bits): then the whole pixel is. */
static inline bool rc_aov_per_sample(const packed_aov *a) {
  return (float)__builtin_popcount(a->uncertified_mask) == a->uncertified;
}

/* Whether the re-render traces sample s of a pixel its f32 pass left uncertified. */
static inline bool rc_aov_rerenders(const packed_aov *a, uint32_t s) {
  return !rc_aov_per_sample(a) || (s < 32 && (a->uncertified_mask >> s & 1u));
}

/* The samples the re-render traces in the pixel: 0 where the f32 pass certified them all. */
static inline uint32_t rc_aov_samples_rerendered(const packed_aov *a, uint32_t samples_per_pixel) {
  if (!(a->uncertified > 0)) return 0;
  return rc_aov_per_sample(a) ? (uint32_t)__builtin_popcount(a->uncertified_mask) : samples_per_pixel;
}

/* Carries the f32 pass's marks (count, bits, certified sum) into `to`, a re-rendered
 * record, which the re-render's own frame (certify off) does not fill. */
static inline void rc_aov_keep_marks(packed_aov *to, const packed_aov *marks) {
  to->uncertified = marks->uncertified;
  to->uncertified_mask = marks->uncertified_mask;
  to->certified_sum = marks->certified_sum;
}

#endif
