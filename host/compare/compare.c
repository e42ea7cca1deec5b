#include "compare/compare.h"

#include <math.h>
#include <string.h>

/* |x - y|, with equal values (infinities too) at 0 and NaN against NaN at 0: "the same"
 * in the sense a regression test means. Anything else involving a non-finite value has
 * no size: +Inf, flagged through *nonfinite. */
double rc_compare_channel_error(float x, float y, bool *nonfinite) {
  if (x == y || (isnan(x) && isnan(y))) return 0;
  if (!isfinite(x) || !isfinite(y)) {
    *nonfinite = true;
    return INFINITY;
  }
  return fabs((double)x - (double)y);
}

double rc_compare_pixel_error(const float *a, const float *b, int c, const bool *colour, size_t p, int *channel) {
  double e = 0;
  *channel = 0;
  for (int k = 0; k < c; k++) {
    if (colour && !colour[k]) continue;
    bool nonfinite = false;
    double d = rc_compare_channel_error(a[p * c + k], b[p * c + k], &nonfinite);
    if (d > e) e = d, *channel = k;
  }
  return e;
}

/* Keeps r->top sorted worst first; ties keep the earlier pixel (row-major order). */
static void offer_top(rc_compare_result *r, int x, int y, int channel, double e) {
  if (!(e > 0)) return;
  if (r->top_count == RC_COMPARE_TOP && !(e > r->top[RC_COMPARE_TOP - 1].error)) return;
  int i = r->top_count < RC_COMPARE_TOP ? r->top_count++ : RC_COMPARE_TOP - 1;
  while (i > 0 && r->top[i - 1].error < e) {
    r->top[i] = r->top[i - 1];
    i--;
  }
  r->top[i] = (rc_compare_pixel){x, y, channel, e};
}

void rc_compare_images(const float *a, const float *b, int w, int h, int c, const bool *colour, double fail,
                       double warn, rc_compare_result *r) {
  memset(r, 0, sizeof *r);
  r->width = w, r->height = h, r->channels = c;
  for (int k = 0; k < c; k++) r->colour_channels += !colour || colour[k];
  r->pixels = (uint64_t)w * h;
  double sum = 0, sum2 = 0;
  for (int y = 0; y < h; y++) {
    for (int x = 0; x < w; x++) {
      size_t i = ((size_t)y * w + x) * c;
      bool over = false, warned = false;
      double pixel_max = 0;
      int pixel_channel = 0;
      for (int k = 0; k < c; k++) {
        if (colour && !colour[k]) continue;
        r->nan_a += !isfinite(a[i + k]);
        r->nan_b += !isfinite(b[i + k]);
        bool nonfinite = false;
        double d = rc_compare_channel_error(a[i + k], b[i + k], &nonfinite);
        r->nonfinite_mismatch += nonfinite;
        sum += isfinite(d) ? d : 0;
        sum2 += isfinite(d) ? d * d : 0;
        over |= d > fail;
        warned |= d > warn;
        if (d > pixel_max) pixel_max = d, pixel_channel = k;
        if (d > r->max) {
          r->max = d, r->max_x = x, r->max_y = y, r->max_channel = k;
          r->max_a = a[i + k], r->max_b = b[i + k];
        }
      }
      r->over += over;
      r->warned += warned;
      offer_top(r, x, y, pixel_channel, pixel_max);
    }
  }
  double n = (double)r->pixels * r->colour_channels;
  r->mean = n ? sum / n : 0;
  double mse = n ? sum2 / n : 0;
  r->rms = sqrt(mse);
  /* mean and RMS run over the values with a size; a NaN against a number has none, so
   * PSNR is undefined there (NaN), never "infinite". */
  r->psnr = r->nonfinite_mismatch ? NAN : mse > 0 ? 10.0 * log10(1.0 / mse) : INFINITY;
}
