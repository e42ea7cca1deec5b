#include "compare/compare.h"

#include <math.h>
#include <string.h>

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
      for (int k = 0; k < c; k++) {
        if (colour && !colour[k]) continue;
        r->nan_a += !isfinite(a[i + k]);
        r->nan_b += !isfinite(b[i + k]);
        double d = fabs((double)a[i + k] - (double)b[i + k]);
        if (!isfinite(d)) d = isnan(a[i + k]) && isnan(b[i + k]) ? 0 : HUGE_VAL;
        sum += isfinite(d) ? d : 0;
        sum2 += isfinite(d) ? d * d : 0;
        over |= d > fail;
        warned |= d > warn;
        if (d > r->max) {
          r->max = d, r->max_x = x, r->max_y = y, r->max_channel = k;
          r->max_a = a[i + k], r->max_b = b[i + k];
        }
      }
      r->over += over;
      r->warned += warned;
    }
  }
  double n = (double)r->pixels * r->colour_channels;
  r->mean = n ? sum / n : 0;
  double mse = n ? sum2 / n : 0;
  r->rms = sqrt(mse);
  r->psnr = mse > 0 ? 10.0 * log10(1.0 / mse) : INFINITY;
}

void rc_compare_heat_map(const float *a, const float *b, int w, int h, int c, const bool *colour, double floor,
                         double top, float *rgb) {
  double lo = log10(floor), span = top > floor ? log10(top) - lo : 1.0;
  for (size_t p = 0; p < (size_t)w * h; p++) {
    double e = 0;
    for (int k = 0; k < c; k++) {
      if (colour && !colour[k]) continue;
      double d = fabs((double)a[p * c + k] - (double)b[p * c + k]);
      if (!(d <= e)) e = d; /* NaN becomes the maximum */
    }
    double t = e <= floor ? 0.0 : (log10(e) - lo) / span;
    if (!(t <= 1)) t = 1;
    /* black -> red (1/3) -> yellow (2/3) -> white */
    rgb[3 * p + 0] = (float)fmin(1.0, 3 * t);
    rgb[3 * p + 1] = (float)fmin(1.0, fmax(0.0, 3 * t - 1));
    rgb[3 * p + 2] = (float)fmin(1.0, fmax(0.0, 3 * t - 2));
  }
}
