/* heat_map.h: the picture `vkraycast compare --diff` writes. Per pixel the larger colour
 * difference e = max_k |A_k - B_k| on a fixed logarithmic scale [lo, hi], drawn over the
 * reference B in faint grey so that one sees where the differences sit; below the image
 * a colour bar with a tick and label per decade, the --fail threshold marked, and the
 * colour of NaN. Logarithmic because GPU/CPU differences span orders of magnitude:
 * rounding noise near 1e-6 and a decision flip near 0.1 must both show. The scale is
 * fixed (not the image's own maximum), so two heat maps drawn with one scale compare.
 * Pixels over the threshold are few and single where they are decision flips: each gets
 * a ring around it, so that one pixel in 256,000 is still seen. */
#ifndef RC_HEAT_MAP_H
#define RC_HEAT_MAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct rc_heat_scale {
  double lo, hi;  /* e <= lo: no colour, the reference alone; e >= hi: the top colour */
  double mark;    /* the --fail threshold: marked on the bar, ringed in the image */
} rc_heat_scale;

/* The default scale: 1e-6 (f32 rounding of values near 1) to 1 (an 8-bit image's whole
 * range), for every preset, so that any two default heat maps compare. */
#define RC_HEAT_LO 1e-6
#define RC_HEAT_HI 1.0

/* Pixels over `mark` get rings only while there are at most this many: past it they
 * form areas that show by themselves. */
#define RC_HEAT_MAX_RINGS 2000

/* The picture's size for a w x h image: at least RC_HEAT_MIN_WIDTH wide (for the
 * legend), RC_HEAT_LEGEND rows taller. */
#define RC_HEAT_MIN_WIDTH 360
#define RC_HEAT_LEGEND 40
void rc_heat_map_size(int w, int h, int *out_w, int *out_h);

/* Draws into rgb (out_w * out_h * 3 floats, display values in [0, 1]); a, b: w * h * c
 * floats, colour[k] marking the colour channels (NULL: all). Returns the pixels ringed. */
uint64_t rc_heat_map_draw(const float *a, const float *b, int w, int h, int c, const bool *colour,
                          const rc_heat_scale *scale, float *rgb);

/* The colour of position t in [0, 1] on the bar (indigo, blue, green, yellow, red). */
void rc_heat_colour(double t, float out[3]);

#endif
