/* cmd_compare.c: `vkraycast compare A B`: metrics on stdout (text or --json), exit 0
 * within the thresholds, 1 beyond, 2 for unreadable files or different sizes. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "aov.h"
#include "cli.h"
#include "compare.h"
#include "image/image_io.h"

static const char compare_usage[] =
    "usage: vkraycast compare A B [options]\n"
    "\n"
    "  --fail T          a pixel fails when a channel differs by more than T (default 1e-6)\n"
    "  --failpercent P   allow up to P percent failing pixels (default 0)\n"
    "  --hardfail H      fail if any channel differs by more than H (default: no limit)\n"
    "  --decisions N     AOV files: allow up to N pixels whose hit flag, object or shadow bits\n"
    "                    differ (default 0)\n"
    "  --band REF2        AOV files: a re-render of B's scene with perturbed inputs (render\n"
    "                    --perturb); pixels whose decisions differ between B and it form the\n"
    "                    conditioning band and are left out of the decision counts (repeatable)\n"
    "  --diff OUT        write a heat map of the absolute difference: black up to --fail, white at\n"
    "                    the max error, logarithmic in between\n"
    "  --json            print the metrics as one JSON object\n"
    "\n"
    "Exit status: 0 within the thresholds, 1 beyond, 2 unreadable files or different sizes.\n";

static rc_status parse_double(const char *name, const char *text, double *out) {
  char *end = NULL;
  double v = strtod(text, &end);
  if (!text[0] || *end || !isfinite(v) || v < 0) {
    rc_error("%s: expected a non-negative number, got '%s'", name, text);
    return RC_ERR_USAGE;
  }
  *out = v;
  return RC_OK;
}

typedef struct {
  int w, h, c;
  float *px;
  bool aov;
  rc_aov_layout layout;
} loaded;

static rc_status load(const char *path, loaded *im) {
  char err[512];
  char names[RC_AOV_MAX_CHANNELS][32];
  int n = 0;
  if (rc_check_input(path, "image", NULL) != RC_OK) return RC_ERR_IO;
  if (rc_image_read_named(path, &im->w, &im->h, &im->c, &im->px, names, RC_AOV_MAX_CHANNELS, &n, err, sizeof err) != 0) {
    rc_error("%s: cannot read image: %s", path, err);
    return RC_ERR_IO;
  }
  im->aov = rc_aov_find_channels(names, n, &im->layout);
  return RC_OK;
}

/* The conditioning band: pixels of the reference b whose decisions change when its scene's
 * inputs are perturbed by a few f32 ulps (each band file is such a re-render). */
static rc_status load_band(const char *const *paths, int n, const loaded *b, unsigned char **out) {
  if (!b->aov) {
    rc_error("compare: --band needs AOV files (render --aov)");
    return RC_ERR_USAGE;
  }
  unsigned char *band = calloc((size_t)b->w * b->h, 1);
  if (!band) return RC_ERR_OUT_OF_MEMORY;
  rc_status st = RC_OK;
  for (int k = 0; k < n && st == RC_OK; k++) {
    loaded p = {0};
    st = load(paths[k], &p);
    if (st == RC_OK && (!p.aov || p.w != b->w || p.h != b->h)) {
      rc_error("compare: --band %s is not an AOV file of the same size", paths[k]);
      st = RC_ERR_INPUT;
    }
    for (size_t i = 0; st == RC_OK && i < (size_t)b->w * b->h; i++)
      if (!rc_aov_same_decisions(p.px, &p.layout, b->px, &b->layout, b->c, i)) band[i] = 1;
    free(p.px);
  }
  if (st != RC_OK) free(band), band = NULL;
  *out = band;
  return st;
}

rc_status rc_cmd_compare(int argc, char **argv) {
  const char *files[2] = {NULL, NULL}, *diff = NULL;
  double fail = 1e-6, failpercent = 0, hardfail = INFINITY;
  uint32_t decisions_allowed = 0;
  bool json = false;
  int nfiles = 0;
  const char *bands[8];
  int nbands = 0;
  for (int i = 0; i < argc; i++) {
    const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    rc_status st = RC_OK;
    if (strcmp(o, "--help") == 0 || strcmp(o, "-h") == 0) {
      fputs(compare_usage, stdout);
      return RC_OK;
    } else if (strcmp(o, "--json") == 0) {
      json = true;
      continue;
    } else if (o[0] == '-' && o[1] && !v) {
      rc_error("compare: option %s needs a value", o);
      return RC_ERR_USAGE;
    } else if (strcmp(o, "--fail") == 0) {
      st = parse_double(o, v, &fail);
    } else if (strcmp(o, "--failpercent") == 0) {
      st = parse_double(o, v, &failpercent);
    } else if (strcmp(o, "--hardfail") == 0) {
      st = parse_double(o, v, &hardfail);
    } else if (strcmp(o, "--decisions") == 0) {
      st = rc_cli_uint(o, v, 0, UINT32_MAX, &decisions_allowed);
    } else if (strcmp(o, "--diff") == 0) {
      diff = v;
    } else if (strcmp(o, "--band") == 0) {
      if (nbands == 8) {
        rc_error("compare: at most 8 --band files");
        return RC_ERR_USAGE;
      }
      bands[nbands++] = v;
    } else if (o[0] == '-' && o[1]) {
      rc_error("compare: unknown option %s (see vkraycast compare --help)", o);
      return RC_ERR_USAGE;
    } else {
      if (nfiles == 2) {
        rc_error("compare: more than two images given");
        return RC_ERR_USAGE;
      }
      files[nfiles++] = o;
      continue;
    }
    if (st != RC_OK) return st;
    i++;
  }
  if (nfiles != 2) {
    rc_error("compare: two images are needed");
    fputs(compare_usage, stderr);
    return RC_ERR_USAGE;
  }
  const rc_file_role roles[] = {{files[0], "image A", false}, {files[1], "image B", false}, {diff, "the heat map", true}};
  if (rc_check_distinct(roles, 3) != RC_OK) return RC_ERR_USAGE;
  if (diff && !rc_image_can_write(diff)) {
    rc_error("%s: no image format for this file name", diff);
    return RC_ERR_USAGE;
  }
  loaded a = {0}, b = {0};
  rc_status st = load(files[0], &a);
  if (st == RC_OK) st = load(files[1], &b);
  if (st == RC_OK && (a.w != b.w || a.h != b.h || a.c != b.c)) {
    rc_error("compare: %s is %dx%d with %d channels, %s is %dx%d with %d channels", files[0], a.w, a.h, a.c, files[1],
             b.w, b.h, b.c);
    st = RC_ERR_INPUT;
  }
  unsigned char *band = NULL;
  if (st == RC_OK && nbands) st = load_band(bands, nbands, &b, &band);
  rc_compare_result r;
  if (st == RC_OK) {
    rc_compare_images(a.px, b.px, a.w, a.h, a.c, fail, &r);
    if (a.aov && b.aov) rc_aov_compare_decisions(a.px, &a.layout, b.px, &b.layout, a.w, a.h, a.c, band, &r);
    double share = r.pixels ? 100.0 * (double)r.over / (double)r.pixels : 0;
    uint64_t decision_total = r.hit_mismatch + r.object_mismatch + r.shadow_mismatch;
    bool ok = share <= failpercent && r.max <= hardfail && (!r.decisions || decision_total <= decisions_allowed);
    if (json) {
      cJSON *o = cJSON_CreateObject();
      cJSON_AddNumberToObject(o, "width", r.width);
      cJSON_AddNumberToObject(o, "height", r.height);
      cJSON_AddNumberToObject(o, "channels", r.channels);
      cJSON_AddNumberToObject(o, "mean_error", r.mean);
      cJSON_AddNumberToObject(o, "rms_error", r.rms);
      cJSON_AddNumberToObject(o, "max_error", isfinite(r.max) ? r.max : 1e300);
      cJSON_AddNumberToObject(o, "max_x", r.max_x);
      cJSON_AddNumberToObject(o, "max_y", r.max_y);
      cJSON_AddNumberToObject(o, "max_channel", r.max_channel);
      cJSON_AddNumberToObject(o, "psnr", isfinite(r.psnr) ? r.psnr : 999);
      cJSON_AddNumberToObject(o, "threshold", fail);
      cJSON_AddNumberToObject(o, "pixels_over", (double)r.over);
      cJSON_AddNumberToObject(o, "percent_over", share);
      cJSON_AddNumberToObject(o, "nonfinite_a", (double)r.nan_a);
      cJSON_AddNumberToObject(o, "nonfinite_b", (double)r.nan_b);
      if (r.decisions) {
        cJSON_AddNumberToObject(o, "hit_mismatch", (double)r.hit_mismatch);
        cJSON_AddNumberToObject(o, "object_mismatch", (double)r.object_mismatch);
        cJSON_AddNumberToObject(o, "shadow_mismatch", (double)r.shadow_mismatch);
        cJSON_AddNumberToObject(o, "band_pixels", (double)r.band_pixels);
        cJSON_AddNumberToObject(o, "a_hits", (double)r.a_hits);
        cJSON_AddNumberToObject(o, "b_hits", (double)r.b_hits);
        cJSON_AddNumberToObject(o, "a_shadowed", (double)r.a_shadowed);
        cJSON_AddNumberToObject(o, "b_shadowed", (double)r.b_shadowed);
        cJSON_AddNumberToObject(o, "max_depth_rel_error", isfinite(r.max_depth_rel) ? r.max_depth_rel : 1e300);
        cJSON_AddNumberToObject(o, "max_normal_angle", isfinite(r.max_normal_angle) ? r.max_normal_angle : 1e300);
      }
      cJSON_AddBoolToObject(o, "pass", ok);
      char *text = cJSON_Print(o);
      puts(text);
      free(text);
      cJSON_Delete(o);
    } else {
      printf("%s vs %s: %dx%d, %d channels\n", files[0], files[1], r.width, r.height, r.channels);
      printf("  mean error %.6g, RMS error %.6g, PSNR %.2f dB\n", r.mean, r.rms, r.psnr);
      printf("  max error %.6g at (%d, %d) channel %d: %.9g vs %.9g\n", r.max, r.max_x, r.max_y, r.max_channel, r.max_a,
             r.max_b);
      printf("  %llu pixels (%.4f%%) over %g\n", (unsigned long long)r.over, share, fail);
      if (r.decisions)
        printf("  decisions differ: hit %llu, object %llu, shadow %llu pixels%s; depth error %.3g (relative), "
               "normal error %.3g rad\n",
               (unsigned long long)r.hit_mismatch, (unsigned long long)r.object_mismatch,
               (unsigned long long)r.shadow_mismatch, band ? " outside the band" : "", r.max_depth_rel,
               r.max_normal_angle);
      if (band) printf("  conditioning band: %llu pixels\n", (unsigned long long)r.band_pixels);
      printf("%s\n", ok ? "PASS" : "FAIL");
    }
    if (diff) {
      float *heat = rc_alloc((size_t)a.w * a.h * 3, sizeof(float), "the heat map");
      char err[512];
      if (!heat) {
        st = RC_ERR_OUT_OF_MEMORY;
      } else {
        double floor = fail > 0 ? fail : 1e-7;
        rc_compare_heat_map(a.px, b.px, a.w, a.h, a.c, floor, isfinite(r.max) ? r.max : 1.0, heat);
        if (rc_image_write(diff, a.w, a.h, 3, heat, RC_ENCODING_LINEAR, false, err, sizeof err) != 0) {
          rc_error("%s: cannot write the heat map: %s", diff, err);
          st = RC_ERR_IO;
        }
        free(heat);
      }
    }
    if (st == RC_OK && !ok) st = RC_MISMATCH;
  }
  free(a.px);
  free(b.px);
  free(band);
  return st;
}
