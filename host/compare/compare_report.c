#include "compare/compare_report.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const verdict_names[] = {"PASS", "WARNING", "FAIL"};

/* JSON has no infinity: a non-finite metric is written as 1e300, the PSNR of identical
 * images as 999 (idiff's "inf" has no JSON spelling), an undefined PSNR as null. */
static double finite_or(double v, double big) { return isfinite(v) ? v : big; }

static double percent(uint64_t n, uint64_t of) { return of ? 100.0 * (double)n / (double)of : 0; }

#define MAX_DIFFERENCES 24

/* "R 0.25, G 0.5, ..., shadow 3": every channel of one pixel, by name. */
static void print_pixel(const rc_compare_image *im, int x, int y, FILE *f) {
  const float *p = im->px + ((size_t)y * im->w + x) * im->c;
  for (int k = 0; k < im->c; k++) fprintf(f, "%s%s %.9g", k ? ", " : "", im->names[k], p[k]);
}

static bool same_decisions(const rc_compare_report *rep, int x, int y) {
  return rc_aov_same_decisions(rep->a->px, &rep->a->layout, rep->b->px, &rep->b->layout, rep->a->c,
                               (size_t)y * rep->a->w + x);
}

/* What the two headers say about the renders: the same scene or not, and each setting
 * that differs. */
static void print_headers(const rc_compare_report *rep, FILE *f) {
  const rc_image_header *x = &rep->a->header, *y = &rep->b->header;
  if (!x->present || !y->present) {
    if (x->present || y->present)
      fprintf(f, "  headers: %s has no vkraycast header: scenes and settings cannot be compared\n",
              x->present ? rep->path_b : rep->path_a);
    return;
  }
  if (strcmp(x->scene_hash, y->scene_hash) == 0)
    fprintf(f, "  headers: the same scene (%s)", x->scene_hash);
  else
    fprintf(f, "  headers: DIFFERENT SCENES (A %s, B %s)", x->scene_hash, y->scene_hash);
  rc_setting_difference d[MAX_DIFFERENCES];
  int n = rc_settings_differences(x->settings, y->settings, d, MAX_DIFFERENCES);
  if (n == 0) fputs(", the same settings", f);
  for (int i = 0; i < n && i < MAX_DIFFERENCES; i++)
    fprintf(f, "%s%s %s / %s", i ? ", " : "; settings differ (A / B): ", d[i].name, d[i].a[0] ? d[i].a : "(none)",
            d[i].b[0] ? d[i].b : "(none)");
  fputc('\n', f);
}

static void print_top(const rc_compare_report *rep, FILE *f) {
  const rc_compare_result *r = rep->r;
  int n = r->top_count < rep->top ? r->top_count : rep->top;
  if (n <= 1) return; /* the max error line has the first */
  fprintf(f, "  worst %d pixels:\n", n);
  for (int i = 0; i < n; i++) {
    const rc_compare_pixel *p = &r->top[i];
    fprintf(f, "    (%d, %d) %s %.3g", p->x, p->y, rep->a->names[p->channel], p->error);
    if (r->decisions) fputs(same_decisions(rep, p->x, p->y) ? ", same decisions" : ", decisions differ", f);
    fputc('\n', f);
  }
}

static void print_checks(const rc_compare_report *rep, FILE *f) {
  const rc_compare_judgement *j = rep->judgement;
  fprintf(f, "  checks%s%s%s:\n", rep->preset ? " (--preset " : "", rep->preset ? rep->preset : "",
          rep->preset ? ")" : "");
  for (int i = 0; i < j->count; i++) {
    const rc_compare_check *c = &j->checks[i];
    fprintf(f, "    %-4s %s: %s, allowed %s\n", c->ok ? "ok" : c->level == RC_VERDICT_FAIL ? "FAIL" : "WARN", c->what,
            c->measured, c->allowed);
  }
}

/* Notes that explain a result a reader would otherwise misread. */
static void print_notes(const rc_compare_report *rep, FILE *f) {
  const rc_compare_result *r = rep->r;
  if (r->decisions && rep->over_same_decisions && r->digests) {
    fprintf(f,
            "  note: %llu of the %llu pixels over --fail %g make the same decisions in A and B, in every\n"
            "        sample and bounce (their digests agree): a colour difference, not a flipped decision,\n"
            "        such as a texture lookup (not a decision) whose colour moves with the hit point's last\n"
            "        bits: a texel edge under nearest filtering where the texture is magnified (minified,\n"
            "        it reads mip levels).\n",
            (unsigned long long)rep->over_same_decisions, (unsigned long long)r->over, rep->limits->fail);
  } else if (r->decisions && rep->over_same_decisions) {
    char spp[16];
    bool known = rc_settings_value(rep->b->header.settings, "spp", spp, sizeof spp);
    fprintf(f,
            "  note: %llu of the %llu pixels over --fail %g make the same first-sample decisions in A and B.\n"
            "        An AOV file records each pixel's first sample%s%s%s and first ray only; the\n"
            "        difference comes from a later sample, a mirror bounce, or a texture lookup (not\n"
            "        recorded) whose colour moves with the hit point's last bits: a texel edge under\n"
            "        nearest filtering where the texture is magnified (minified, it reads mip levels).\n"
            "        Render both with --spp 1 and --reflection-depth 0 to see every decision of a\n"
            "        pixel in its AOV, or with a vkraycast that writes the `decisions` channel.\n",
            (unsigned long long)rep->over_same_decisions, (unsigned long long)r->over, rep->limits->fail,
            known ? " (these renders have spp " : "", known ? spp : "", known ? ")" : "");
  }
  if (isnan(r->psnr))
    fprintf(f, "  note: PSNR is undefined: %llu colour values are NaN or infinite in one file and not the same in "
               "the other\n", (unsigned long long)r->nonfinite_mismatch);
  if (rep->heat_path)
    fprintf(f, "  heat map %s: |A - B| of the larger colour channel, log scale %g .. %g over B in grey;\n"
               "        --fail %g marked on the bar, %llu pixel%s over it ringed%s\n",
            rep->heat_path, rep->heat.lo, rep->heat.hi, rep->heat.mark, (unsigned long long)rep->ringed,
            rep->ringed == 1 ? "" : "s", r->over > RC_HEAT_MAX_RINGS ? " (too many to ring: they show as areas)" : "");
}

static void print_verdict(const rc_compare_report *rep, FILE *f) {
  const rc_compare_judgement *j = rep->judgement;
  fputs(verdict_names[j->verdict], f);
  int shown = 0;
  for (int i = 0; i < j->count; i++) {
    const rc_compare_check *c = &j->checks[i];
    if (c->ok || c->level != j->verdict) continue;
    fprintf(f, "%s %s: %s, allowed %s", shown++ ? ";" : ":", c->what, c->measured, c->allowed);
  }
  fputc('\n', f);
}

void rc_compare_print_text(const rc_compare_report *rep, FILE *f) {
  const rc_compare_result *r = rep->r;
  fprintf(f, "%s vs %s: %dx%d, %d channels%s\n", rep->path_a, rep->path_b, r->width, r->height, r->channels,
          r->decisions ? " (AOV files: colour metrics over R, G, B)" : "");
  print_headers(rep, f);
  if (isnan(r->psnr))
    fprintf(f, "  mean error %.6g, RMS error %.6g (over the values with a size), PSNR undefined\n", r->mean, r->rms);
  else
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
  print_top(rep, f);
  fprintf(f, "  %llu pixels (%.4f%%) over --fail %g, %llu (%.4f%%) over --warn %g\n", (unsigned long long)r->over,
          percent(r->over, r->pixels), rep->limits->fail, (unsigned long long)r->warned,
          percent(r->warned, r->pixels), rep->limits->warn);
  if (r->nan_a || r->nan_b)
    fprintf(f, "  non-finite values: %llu in A, %llu in B, %llu where the files differ\n",
            (unsigned long long)r->nan_a, (unsigned long long)r->nan_b, (unsigned long long)r->nonfinite_mismatch);
  if (r->decisions) {
    fprintf(f, "  decisions differ: hit %llu, object %llu, shadow %llu pixels%s\n", (unsigned long long)r->hit_mismatch,
            (unsigned long long)r->object_mismatch, (unsigned long long)r->shadow_mismatch,
            rep->banded ? " outside the band" : "");
    if (r->digests) {
      fprintf(f, "  decisions of every sample and bounce differ: %llu pixels%s\n", (unsigned long long)r->sample_mismatch,
              rep->banded ? " outside the band" : "");
      if (isnan(r->psnr_alike))
        fprintf(f, "  the %llu pixels that decide alike: PSNR undefined (NaN against a number)\n",
                (unsigned long long)r->pixels_alike);
      else if (isinf(r->psnr_alike))
        fprintf(f, "  the %llu pixels that decide alike: the same colour\n", (unsigned long long)r->pixels_alike);
      else
        fprintf(f, "  the %llu pixels that decide alike: PSNR %.2f dB\n", (unsigned long long)r->pixels_alike,
                r->psnr_alike);
    }
    fprintf(f, "  where both hit the same object: depth error %.3g (relative), normal error %.3g rad\n",
            r->max_depth_rel, r->max_normal_angle);
    if (rep->banded) fprintf(f, "  conditioning band: %llu pixels\n", (unsigned long long)r->band_pixels);
    /* A render without --precision certified marks every sample uncertified. */
    if (rep->a->layout.uncertified >= 0 && r->uncertified_pixels == r->pixels)
      fputs("  certified (A): no pixel (as in any render without --precision certified)\n", f);
    else if (rep->a->layout.uncertified >= 0)
      fprintf(f, "  certified (A): %llu pixels with uncertified samples; certified pixels whose decisions differ: %llu\n",
              (unsigned long long)r->uncertified_pixels, (unsigned long long)r->certified_mismatch);
    if (rep->a->layout.uncertified >= 0 && rep->banded)
      fprintf(f, "  certified (A) pixels inside the band: %llu\n", (unsigned long long)r->certified_in_band);
  }
  print_checks(rep, f);
  print_notes(rep, f);
  print_verdict(rep, f);
}

static cJSON *pixel_json(const rc_compare_image *im, int x, int y) {
  cJSON *o = cJSON_CreateObject();
  const float *p = im->px + ((size_t)y * im->w + x) * im->c;
  for (int k = 0; k < im->c; k++) cJSON_AddNumberToObject(o, im->names[k], finite_or(p[k], p[k] > 0 ? 1e300 : -1e300));
  return o;
}

static cJSON *checks_json(const rc_compare_judgement *j) {
  cJSON *list = cJSON_CreateArray();
  for (int i = 0; i < j->count; i++) {
    const rc_compare_check *c = &j->checks[i];
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "check", c->id);
    cJSON_AddStringToObject(o, "what", c->what);
    if (isnan(c->measured_value))
      cJSON_AddNullToObject(o, "measured");
    else
      cJSON_AddNumberToObject(o, "measured", finite_or(c->measured_value, 1e300));
    cJSON_AddNumberToObject(o, "allowed", finite_or(c->allowed_value, c->allowed_value > 0 ? 1e300 : -1e300));
    cJSON_AddStringToObject(o, "measured_text", c->measured);
    cJSON_AddStringToObject(o, "allowed_text", c->allowed);
    cJSON_AddStringToObject(o, "level", c->level == RC_VERDICT_FAIL ? "fail" : "warn");
    cJSON_AddBoolToObject(o, "ok", c->ok);
    cJSON_AddItemToArray(list, o);
  }
  return list;
}

static cJSON *headers_json(const rc_compare_report *rep) {
  const rc_image_header *x = &rep->a->header, *y = &rep->b->header;
  cJSON *o = cJSON_CreateObject();
  cJSON_AddBoolToObject(o, "a_has_header", x->present);
  cJSON_AddBoolToObject(o, "b_has_header", y->present);
  if (!x->present || !y->present) return o;
  cJSON_AddStringToObject(o, "scene_hash_a", x->scene_hash);
  cJSON_AddStringToObject(o, "scene_hash_b", y->scene_hash);
  cJSON_AddBoolToObject(o, "same_scene", strcmp(x->scene_hash, y->scene_hash) == 0);
  rc_setting_difference d[MAX_DIFFERENCES];
  int n = rc_settings_differences(x->settings, y->settings, d, MAX_DIFFERENCES);
  cJSON *list = cJSON_AddArrayToObject(o, "settings_differ");
  for (int i = 0; i < n && i < MAX_DIFFERENCES; i++) {
    cJSON *s = cJSON_CreateObject();
    cJSON_AddStringToObject(s, "setting", d[i].name);
    cJSON_AddStringToObject(s, "a", d[i].a);
    cJSON_AddStringToObject(s, "b", d[i].b);
    cJSON_AddItemToArray(list, s);
  }
  return o;
}

static cJSON *top_json(const rc_compare_report *rep) {
  cJSON *list = cJSON_CreateArray();
  for (int i = 0; i < rep->r->top_count && i < rep->top; i++) {
    const rc_compare_pixel *p = &rep->r->top[i];
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "x", p->x);
    cJSON_AddNumberToObject(o, "y", p->y);
    cJSON_AddStringToObject(o, "channel", rep->a->names[p->channel]);
    cJSON_AddNumberToObject(o, "error", finite_or(p->error, 1e300));
    if (rep->r->decisions) cJSON_AddBoolToObject(o, "same_decisions", same_decisions(rep, p->x, p->y));
    cJSON_AddItemToArray(list, o);
  }
  return list;
}

void rc_compare_print_json(const rc_compare_report *rep, FILE *f) {
  const rc_compare_result *r = rep->r;
  cJSON *o = cJSON_CreateObject();
  cJSON_AddNumberToObject(o, "width", r->width);
  cJSON_AddNumberToObject(o, "height", r->height);
  cJSON_AddNumberToObject(o, "channels", r->channels);
  cJSON_AddNumberToObject(o, "colour_channels", r->colour_channels);
  if (rep->preset) cJSON_AddStringToObject(o, "preset", rep->preset);
  cJSON_AddItemToObject(o, "headers", headers_json(rep));
  cJSON_AddNumberToObject(o, "mean_error", r->mean);
  cJSON_AddNumberToObject(o, "rms_error", r->rms);
  cJSON_AddNumberToObject(o, "max_error", finite_or(r->max, 1e300));
  cJSON_AddNumberToObject(o, "max_x", r->max_x);
  cJSON_AddNumberToObject(o, "max_y", r->max_y);
  cJSON_AddNumberToObject(o, "max_channel", r->max_channel);
  cJSON_AddStringToObject(o, "max_channel_name", rep->a->names[r->max_channel]);
  cJSON_AddItemToObject(o, "max_pixel_a", pixel_json(rep->a, r->max_x, r->max_y));
  cJSON_AddItemToObject(o, "max_pixel_b", pixel_json(rep->b, r->max_x, r->max_y));
  cJSON_AddItemToObject(o, "worst_pixels", top_json(rep));
  if (isnan(r->psnr))
    cJSON_AddNullToObject(o, "psnr");
  else
    cJSON_AddNumberToObject(o, "psnr", finite_or(r->psnr, 999));
  cJSON_AddNumberToObject(o, "threshold", rep->limits->fail);
  cJSON_AddNumberToObject(o, "pixels_over", (double)r->over);
  cJSON_AddNumberToObject(o, "percent_over", percent(r->over, r->pixels));
  cJSON_AddNumberToObject(o, "warn_threshold", rep->limits->warn);
  cJSON_AddNumberToObject(o, "pixels_warn", (double)r->warned);
  cJSON_AddNumberToObject(o, "percent_warn", percent(r->warned, r->pixels));
  cJSON_AddNumberToObject(o, "nonfinite_a", (double)r->nan_a);
  cJSON_AddNumberToObject(o, "nonfinite_b", (double)r->nan_b);
  cJSON_AddNumberToObject(o, "nonfinite_mismatch", (double)r->nonfinite_mismatch);
  if (r->decisions) {
    cJSON_AddNumberToObject(o, "hit_mismatch", (double)r->hit_mismatch);
    cJSON_AddNumberToObject(o, "object_mismatch", (double)r->object_mismatch);
    cJSON_AddNumberToObject(o, "shadow_mismatch", (double)r->shadow_mismatch);
    cJSON_AddNumberToObject(o, "band_pixels", (double)r->band_pixels);
    cJSON_AddNumberToObject(o, "uncertified_pixels", (double)r->uncertified_pixels);
    cJSON_AddNumberToObject(o, "certified_mismatch", (double)r->certified_mismatch);
    if (r->digests) {
      cJSON_AddNumberToObject(o, "sample_mismatch", (double)r->sample_mismatch);
      cJSON_AddNumberToObject(o, "pixels_alike", (double)r->pixels_alike);
      if (isnan(r->psnr_alike))
        cJSON_AddNullToObject(o, "psnr_alike");
      else
        cJSON_AddNumberToObject(o, "psnr_alike", finite_or(r->psnr_alike, 999));
    }
    cJSON_AddNumberToObject(o, "certified_in_band", (double)r->certified_in_band);
    cJSON_AddNumberToObject(o, "a_hits", (double)r->a_hits);
    cJSON_AddNumberToObject(o, "b_hits", (double)r->b_hits);
    cJSON_AddNumberToObject(o, "a_shadowed", (double)r->a_shadowed);
    cJSON_AddNumberToObject(o, "b_shadowed", (double)r->b_shadowed);
    cJSON_AddNumberToObject(o, "max_depth_rel_error", finite_or(r->max_depth_rel, 1e300));
    cJSON_AddNumberToObject(o, "max_normal_angle", finite_or(r->max_normal_angle, 1e300));
    cJSON_AddNumberToObject(o, "over_same_decisions", (double)rep->over_same_decisions);
  }
  if (rep->heat_path) {
    cJSON *h = cJSON_AddObjectToObject(o, "heat_map");
    cJSON_AddStringToObject(h, "file", rep->heat_path);
    cJSON_AddNumberToObject(h, "scale_min", rep->heat.lo);
    cJSON_AddNumberToObject(h, "scale_max", rep->heat.hi);
    cJSON_AddNumberToObject(h, "marked_threshold", rep->heat.mark);
    cJSON_AddNumberToObject(h, "ringed", (double)rep->ringed);
  }
  cJSON_AddItemToObject(o, "checks", checks_json(rep->judgement));
  cJSON_AddStringToObject(o, "verdict", verdict_names[rep->judgement->verdict]);
  cJSON_AddBoolToObject(o, "pass", rep->judgement->verdict != RC_VERDICT_FAIL);
  char *text = cJSON_Print(o);
  fprintf(f, "%s\n", text);
  free(text);
  cJSON_Delete(o);
}
