#include "compare/compare_report.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>

static const char *const verdict_names[] = {"PASS", "WARNING", "FAIL"};

/* JSON has no infinity: a non-finite metric is written as 1e300 (and PSNR of identical
 * images as 999), as before. */
static double finite_or(double v, double big) { return isfinite(v) ? v : big; }

static double percent(uint64_t n, uint64_t of) { return of ? 100.0 * (double)n / (double)of : 0; }

/* "R 0.25, G 0.5, ..., shadow 3": every channel of one pixel, by name. */
static void print_pixel(const rc_compare_image *im, int x, int y, FILE *f) {
  const float *p = im->px + ((size_t)y * im->w + x) * im->c;
  for (int k = 0; k < im->c; k++) fprintf(f, "%s%s %.9g", k ? ", " : "", im->names[k], p[k]);
}

void rc_compare_print_text(const rc_compare_report *rep, FILE *f) {
  const rc_compare_result *r = rep->r;
  fprintf(f, "%s vs %s: %dx%d, %d channels%s\n", rep->path_a, rep->path_b, r->width, r->height, r->channels,
          r->decisions ? " (AOV files: colour metrics over R, G, B)" : "");
  fprintf(f, "  mean error %.6g, RMS error %.6g, PSNR %.2f dB\n", r->mean, r->rms, r->psnr);
  if (r->max > 0) {
    fprintf(f, "  max error %.6g in %s at (%d, %d)\n    A: ", r->max, rep->a->names[r->max_channel], r->max_x,
            r->max_y);
    print_pixel(rep->a, r->max_x, r->max_y, f);
    fputs("\n    B: ", f);
    print_pixel(rep->b, r->max_x, r->max_y, f);
    fputc('\n', f);
  } else {
    fputs("  max error 0\n", f);
  }
  fprintf(f, "  %llu pixels (%.4f%%) over --fail %g, %llu (%.4f%%) over --warn %g\n", (unsigned long long)r->over,
          percent(r->over, r->pixels), rep->fail, (unsigned long long)r->warned, percent(r->warned, r->pixels),
          rep->warn);
  if (r->nan_a || r->nan_b)
    fprintf(f, "  non-finite values: %llu in A, %llu in B\n", (unsigned long long)r->nan_a,
            (unsigned long long)r->nan_b);
  if (r->decisions) {
    fprintf(f, "  decisions differ: hit %llu, object %llu, shadow %llu pixels%s\n", (unsigned long long)r->hit_mismatch,
            (unsigned long long)r->object_mismatch, (unsigned long long)r->shadow_mismatch,
            rep->banded ? " outside the band" : "");
    fprintf(f, "  where both hit the same object: depth error %.3g (relative), normal error %.3g rad\n",
            r->max_depth_rel, r->max_normal_angle);
    if (rep->banded) fprintf(f, "  conditioning band: %llu pixels\n", (unsigned long long)r->band_pixels);
  }
  fprintf(f, "%s\n", verdict_names[rep->verdict]);
}

static cJSON *pixel_json(const rc_compare_image *im, int x, int y) {
  cJSON *o = cJSON_CreateObject();
  const float *p = im->px + ((size_t)y * im->w + x) * im->c;
  for (int k = 0; k < im->c; k++) cJSON_AddNumberToObject(o, im->names[k], finite_or(p[k], p[k] > 0 ? 1e300 : -1e300));
  return o;
}

void rc_compare_print_json(const rc_compare_report *rep, FILE *f) {
  const rc_compare_result *r = rep->r;
  cJSON *o = cJSON_CreateObject();
  cJSON_AddNumberToObject(o, "width", r->width);
  cJSON_AddNumberToObject(o, "height", r->height);
  cJSON_AddNumberToObject(o, "channels", r->channels);
  cJSON_AddNumberToObject(o, "colour_channels", r->colour_channels);
  cJSON_AddNumberToObject(o, "mean_error", r->mean);
  cJSON_AddNumberToObject(o, "rms_error", r->rms);
  cJSON_AddNumberToObject(o, "max_error", finite_or(r->max, 1e300));
  cJSON_AddNumberToObject(o, "max_x", r->max_x);
  cJSON_AddNumberToObject(o, "max_y", r->max_y);
  cJSON_AddNumberToObject(o, "max_channel", r->max_channel);
  cJSON_AddStringToObject(o, "max_channel_name", rep->a->names[r->max_channel]);
  cJSON_AddItemToObject(o, "max_pixel_a", pixel_json(rep->a, r->max_x, r->max_y));
  cJSON_AddItemToObject(o, "max_pixel_b", pixel_json(rep->b, r->max_x, r->max_y));
  cJSON_AddNumberToObject(o, "psnr", finite_or(r->psnr, 999));
  cJSON_AddNumberToObject(o, "threshold", rep->fail);
  cJSON_AddNumberToObject(o, "pixels_over", (double)r->over);
  cJSON_AddNumberToObject(o, "percent_over", percent(r->over, r->pixels));
  cJSON_AddNumberToObject(o, "warn_threshold", rep->warn);
  cJSON_AddNumberToObject(o, "pixels_warn", (double)r->warned);
  cJSON_AddNumberToObject(o, "percent_warn", percent(r->warned, r->pixels));
  cJSON_AddNumberToObject(o, "nonfinite_a", (double)r->nan_a);
  cJSON_AddNumberToObject(o, "nonfinite_b", (double)r->nan_b);
  if (r->decisions) {
    cJSON_AddNumberToObject(o, "hit_mismatch", (double)r->hit_mismatch);
    cJSON_AddNumberToObject(o, "object_mismatch", (double)r->object_mismatch);
    cJSON_AddNumberToObject(o, "shadow_mismatch", (double)r->shadow_mismatch);
    cJSON_AddNumberToObject(o, "band_pixels", (double)r->band_pixels);
    cJSON_AddNumberToObject(o, "a_hits", (double)r->a_hits);
    cJSON_AddNumberToObject(o, "b_hits", (double)r->b_hits);
    cJSON_AddNumberToObject(o, "a_shadowed", (double)r->a_shadowed);
    cJSON_AddNumberToObject(o, "b_shadowed", (double)r->b_shadowed);
    cJSON_AddNumberToObject(o, "max_depth_rel_error", finite_or(r->max_depth_rel, 1e300));
    cJSON_AddNumberToObject(o, "max_normal_angle", finite_or(r->max_normal_angle, 1e300));
  }
  cJSON_AddStringToObject(o, "verdict", verdict_names[rep->verdict]);
  cJSON_AddBoolToObject(o, "pass", rep->verdict != RC_VERDICT_FAIL);
  char *text = cJSON_Print(o);
  fprintf(f, "%s\n", text);
  free(text);
  cJSON_Delete(o);
}
