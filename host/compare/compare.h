/* compare.h: how far apart two images are, in the vocabulary of OpenImageIO's idiff:
 * mean, RMS and max absolute error (with where the max is), PSNR against a peak of 1,
 * and how many pixels have a channel over the fail and warn thresholds. These colour
 * metrics run over the channels marked as colour: every channel of an image, R, G and B
 * of an AOV file (aov.h), whose other channels are not colours: for those it counts the
 * pixels whose decisions differ (hit flag, object id, shadow bits) and measures depth
 * and normals by their own relative metrics. */
#ifndef RC_COMPARE_H
#define RC_COMPARE_H

#include "base/rc_base.h"

#define RC_COMPARE_TOP 16
/* One pixel's largest colour difference: where, which channel, how much. */
typedef struct rc_compare_pixel {
  int x, y, channel;
  double error;
} rc_compare_pixel;

typedef struct rc_compare_result {
  int width, height, channels;
  double mean, rms, max, psnr;
  int max_x, max_y, max_channel; /* max_channel: an index among all channels */
  double max_a, max_b; /* the two values at the max */
  int colour_channels;   /* how many channels the colour metrics ran over */
  uint64_t pixels, over; /* pixels with some colour channel over the fail threshold */
  uint64_t warned;       /* ... over the warn threshold */
  bool decisions;        /* both files are AOV files: the counts below are meaningful */
  uint64_t hit_mismatch, object_mismatch, shadow_mismatch; /* outside the band */
  uint64_t band_pixels;           /* left out: the conditioning band */
  /* A's pixels with uncertified samples (its `uncertified` channel, --precision certified),
   * and A's certified pixels whose decisions differ from B's (outside the band). */
  uint64_t uncertified_pixels, certified_mismatch;
  /* Both AOV files have the digest of every sample's decisions (packed_aov.decisions), and
   * the pixels whose digests differ: a decision of some sample or bounce differs. */
  bool digests;
  uint64_t sample_mismatch;
  /* The pixels whose decisions agree in the first sample and, where both have digests, in
   * every other (band or not), and the PSNR of their colour: what arithmetic alone, not a
   * flipped decision, made of it (NaN where such a pixel is non-finite in one file and not
   * the other). */
  uint64_t pixels_alike;
  double psnr_alike;
  /* A's certified pixels inside the band (--band), where inputs moved by a few ulps flip a
   * decision of the reference: each should be uncertified (docs/numerics.md §10). */
  uint64_t certified_in_band;
  uint64_t a_hits, b_hits, a_shadowed, b_shadowed; /* pixels that hit; with any shadow bit */
  double max_depth_rel;           /* |t_a - t_b| / |t_b| where both hit the same object */
  double max_normal_angle;        /* radians, likewise */
  uint64_t nan_a, nan_b;          /* non-finite colour values */
  /* Colour values non-finite in one file and not the same in the other (NaN against a
   * number, +Inf against -Inf or a number): no error has a size there, so PSNR is NaN. */
  uint64_t nonfinite_mismatch;
  int top_count;                  /* the worst pixels, worst first (RC_COMPARE_TOP at most) */
  rc_compare_pixel top[RC_COMPARE_TOP];
} rc_compare_result;

/* a and b: width * height * channels floats; colour[k]: channel k is a colour (NULL: all
 * are). Equal values differ by 0, infinities included (+Inf against +Inf, NaN against
 * NaN); a non-finite value against anything else counts as an infinite error and as a
 * nonfinite_mismatch. */
void rc_compare_images(const float *a, const float *b, int width, int height, int channels, const bool *colour,
                       double fail, double warn, rc_compare_result *r);

/* |x - y| of one channel, 0 where the values are equal (infinities too) or both NaN; +Inf,
 * and *nonfinite set, where one side is non-finite and they differ. */
double rc_compare_channel_error(float x, float y, bool *nonfinite);

/* The largest absolute difference over the colour channels of pixel p: +Inf where one
 * side is non-finite and the two differ, 0 where they are equal. */
double rc_compare_pixel_error(const float *a, const float *b, int channels, const bool *colour, size_t p,
                              int *channel);

#endif
