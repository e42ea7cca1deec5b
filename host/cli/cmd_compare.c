/* cmd_compare.c: `vkraycast compare A B`, in the manner of OpenImageIO's idiff: metrics
 * on stdout (text or --json), a verdict of PASS, WARNING or FAIL, and the exit status of
 * diff(1): 0 pass or warning, 1 fail, 2 trouble (docs/cli.md, "compare"). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare/aov.h"
#include "cli/cli.h"
#include "cli/options.h"
#include "compare/compare.h"
#include "compare/compare_checks.h"
#include "compare/compare_report.h"
#include "compare/heat_map.h"
#include "cli/output.h"
#include "image/image_io.h"

typedef struct {
  const char *files[2];
  const char *diff, *scale;
  rc_compare_limits limits; /* NAN: not given (the preset's or the default applies) */
  uint32_t decisions, top;  /* decisions UINT32_MAX: not given */
  int preset;               /* index into rc_compare_presets, -1: none */
  rc_opt_list bands;
  bool json, require_same_scene;
} compare_args;

#define ARG(field) offsetof(compare_args, field)
static const rc_option compare_options[] = {
    {"--preset", NULL, RC_OPT_CHOICE, ARG(preset), "NAME", .choices = rc_compare_preset_names,
     .help = "the documented tolerances for a kind of comparison (docs/gpu-vs-cpu.md);\n"
             "options given beside it override its values:\n"
             "  gpu-vs-cpu      GPU f32 (or auto) against the CPU f64 reference: 0.5 % of\n"
             "                  pixels over 1e-3 (a warning past 0.1 %), decisions on 0.2 %\n"
             "  f32-vs-f64      f32 against f64 on one backend: the same limits\n"
             "  same-precision  GPU against CPU at one precision: 0.01 % over 1e-3,\n"
             "                  PSNR >= 80 dB, decisions on 0.05 %\n"
             "  same-backend    one backend, one precision: bit-identical"},
    {"--fail", NULL, RC_OPT_REAL, ARG(limits.fail), "T", 0, HUGE_VAL,
     .help = "a pixel fails when a colour channel differs by more than T (default 1e-6)"},
    {"--fail-percent", "--failpercent", RC_OPT_REAL, ARG(limits.fail_percent), "P", 0, 100,
     .help = "allow up to P percent failing pixels (default 0)"},
    {"--hardfail", NULL, RC_OPT_REAL, ARG(limits.hardfail), "H", 0, HUGE_VAL,
     .help = "fail if any colour channel differs by more than H (default: no limit)"},
    {"--min-psnr", NULL, RC_OPT_REAL, ARG(limits.min_psnr), "DB", 0, 1000,
     .help = "fail if the PSNR (peak 1) is below DB (default: no limit)"},
    {"--warn", NULL, RC_OPT_REAL, ARG(limits.warn), "T", 0, HUGE_VAL,
     .help = "a pixel warns when a colour channel differs by more than T (default 1e-6)"},
    {"--warn-percent", "--warnpercent", RC_OPT_REAL, ARG(limits.warn_percent), "P", 0, 100,
     .help = "allow up to P percent warning pixels before the verdict is WARNING (default 0)"},
    {"--decisions", NULL, RC_OPT_UINT, ARG(decisions), "N", 0, UINT32_MAX - 1,
     .heading = "AOV files (render --aov): colour thresholds apply to R, G, B only; the rest is judged here:",
     .help = "allow up to N pixels whose hit flag, object id or shadow bits differ\n"
             "(default 0, or no count limit where a share is given)"},
    {"--decisions-percent", NULL, RC_OPT_REAL, ARG(limits.decisions_percent), "P", 0, 100,
     .help = "allow up to P percent of pixels whose decisions differ"},
    {"--depth-tolerance", NULL, RC_OPT_REAL, ARG(limits.depth_tolerance), "R", 0, HUGE_VAL,
     .help = "fail if |t_A - t_B| / |t_B| exceeds R where both hit the same object\n(default: no limit)"},
    {"--normal-tolerance", NULL, RC_OPT_REAL, ARG(limits.normal_tolerance), "RAD", 0, 3.14159265358979323846,
     .help = "fail if the normals of such a pixel differ by more than RAD radians\n(default: no limit)"},
    {"--band", NULL, RC_OPT_LIST, ARG(bands), "REF2",
     .help = "a re-render of B's scene with perturbed inputs (render --perturb);\n"
             "pixels whose decisions differ between B and it form the conditioning\n"
             "band and are left out of the decision counts (repeatable, up to 8)"},
    {"--require-same-scene", NULL, RC_OPT_FLAG, ARG(require_same_scene), .heading = "headers:",
     .help = "make it an error (exit 2) when the files' vkraycast headers name\n"
             "different scenes, or either file has none"},
    {"--diff", NULL, RC_OPT_STRING, ARG(diff), "OUT", .heading = "output:",
     .help = "write a heat map of the colour difference over B in grey, with its\n"
             "colour bar: logarithmic from LO to HI (--scale), --fail marked,\n"
             "pixels over --fail ringed"},
    {"--scale", NULL, RC_OPT_STRING, ARG(scale), "LO,HI",
     .help = "the heat map's fixed scale (default 1e-6,1 for every preset, so that\n"
             "any two heat maps compare)"},
    {"--top", NULL, RC_OPT_UINT, ARG(top), "N", 0, RC_COMPARE_TOP,
     .help = "list the N worst pixels (default 5, at most 16)"},
    {"--json", NULL, RC_OPT_FLAG, ARG(json), .help = "print the metrics, headers and checks as one JSON object"},
};
#undef ARG

static const char *const compare_positional[] = {"image A", "image B"};
const rc_command_spec rc_compare_spec = {
    .name = "compare",
    .synopsis = "A B [options]",
    .summary = "Error metrics between two images of one size, or two AOV files (render --aov),\n"
               "judged by named checks; B is the reference.",
    .epilogue = "Verdict and exit status (diff(1)'s convention; idiff's codes beside it):\n"
                "  PASS     every check met                                       0 (idiff 0)\n"
                "  WARNING  beyond --warn/--warn-percent only                     0 (idiff 1)\n"
                "  FAIL     a check failed: the verdict line names each one with\n"
                "           what it measured and what it allows                   1 (idiff 2)\n"
                "  trouble  unreadable file, different sizes, bad usage, --diff\n"
                "           not written (no verdict is printed)                   2 (idiff 3, 4)\n",
    .min_positional = 2,
    .max_positional = 2,
    .positional_offset = offsetof(compare_args, files),
    .positional_names = compare_positional,
    .options = compare_options,
    .option_count = sizeof compare_options / sizeof *compare_options,
};

/* The scene hash and settings `render` wrote into the file's header (cli/part.h). */
static void read_header(const char *path, rc_image_header *h) {
  memset(h, 0, sizeof *h);
  char err[256];
  int w, hh, c;
  bool f32;
  rc_image_reader *r = rc_image_reader_open(path, &w, &hh, &c, &f32, err, sizeof err);
  if (!r) return;
  h->present = rc_image_reader_meta(r, "vkraycast:scene_hash", h->scene_hash, sizeof h->scene_hash) &&
               rc_image_reader_meta(r, "vkraycast:settings", h->settings, sizeof h->settings);
  if (!rc_image_reader_meta(r, "vkraycast:device", h->device, sizeof h->device)) h->device[0] = '\0';
  rc_image_reader_close(r);
}

static rc_status load(const char *path, rc_compare_image *im) {
  char err[512];
  int n = 0;
  if (rc_check_input(path, "image", NULL) != RC_OK) return RC_ERR_IO;
  if (rc_image_read_named(path, &im->w, &im->h, &im->c, &im->px, im->names, RC_AOV_MAX_CHANNELS, &n, err,
                          sizeof err) != 0) {
    rc_error("%s: cannot read image: %s", path, err);
    return RC_ERR_IO;
  }
  /* Files without channel names (PNG, JPEG) get R, G, B, A by position. */
  static const char *const defaults[] = {"R", "G", "B", "A"};
  for (int k = n; k < im->c && k < RC_AOV_MAX_CHANNELS; k++)
    snprintf(im->names[k], sizeof im->names[k], "%s", k < 4 ? defaults[k] : "?");
  im->aov = rc_aov_find_channels(im->names, n, &im->layout);
  read_header(path, &im->header);
  return RC_OK;
}

/* The conditioning band: pixels of the reference b whose decisions change when its scene's
 * inputs are perturbed by a few f32 ulps (each band file is such a re-render). */
static rc_status load_band(const rc_opt_list *paths, const rc_compare_image *b, unsigned char **out) {
  if (!b->aov) {
    rc_error("compare: --band needs AOV files (render --aov)");
    return RC_ERR_USAGE;
  }
  unsigned char *band = calloc((size_t)b->w * b->h, 1);
  if (!band) return RC_ERR_OUT_OF_MEMORY;
  rc_status st = RC_OK;
  for (unsigned k = 0; k < paths->count && st == RC_OK; k++) {
    rc_compare_image p = {0};
    st = load(paths->item[k], &p);
    if (st == RC_OK && (!p.aov || p.w != b->w || p.h != b->h)) {
      rc_error("compare: --band %s is not an AOV file of the same size", paths->item[k]);
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

/* "LO,HI" with 0 < LO < HI, both finite. */
static rc_status parse_scale(const char *text, rc_heat_scale *s) {
  char *end = NULL;
  s->lo = strtod(text, &end);
  if (*end == ',') s->hi = strtod(end + 1, &end);
  if (*end || !(s->lo > 0) || !(s->hi > s->lo) || !isfinite(s->hi)) {
    rc_usage_error(&rc_compare_spec, "--scale: expected LO,HI with 0 < LO < HI (e.g. 1e-6,1), got '%s'", text);
    return RC_ERR_USAGE;
  }
  return RC_OK;
}

static rc_status parse_args(int argc, char **argv, compare_args *a, rc_heat_scale *heat) {
  memset(a, 0, sizeof *a);
  double *limit = &a->limits.fail;
  for (size_t i = 0; i < sizeof a->limits / sizeof(double); i++) limit[i] = NAN;
  a->decisions = UINT32_MAX;
  a->top = 5;
  a->preset = -1;
  rc_status st = rc_parse_command(&rc_compare_spec, argc, argv, a);
  if (st != RC_OK) return st;
  /* An explicit count replaces a preset's share of pixels, unless a share is given too. */
  if (a->decisions != UINT32_MAX) {
    a->limits.decisions = a->decisions;
    if (isnan(a->limits.decisions_percent)) a->limits.decisions_percent = INFINITY;
  }
  rc_compare_limits_finish(&a->limits, a->preset >= 0 ? &rc_compare_presets[a->preset] : NULL);
  *heat = (rc_heat_scale){RC_HEAT_LO, RC_HEAT_HI, a->limits.fail};
  if (a->scale && parse_scale(a->scale, heat) != RC_OK) return RC_ERR_USAGE;
  if (a->diff && strcmp(a->diff, "-") == 0) {
    rc_usage_error(&rc_compare_spec, "--diff -: the heat map is not written to standard output; name a file");
    return RC_ERR_USAGE;
  }
  rc_file_role roles[3 + RC_OPT_LIST_MAX] = {
      {a->files[0], "image A", false}, {a->files[1], "image B", false}, {a->diff, "the heat map", true}};
  size_t n = 3;
  for (unsigned k = 0; k < a->bands.count; k++) roles[n++] = (rc_file_role){a->bands.item[k], "a --band file", false};
  if (rc_check_distinct(roles, n) != RC_OK) return RC_ERR_USAGE;
  if (a->diff && rc_check_output(a->diff, "the heat map") != RC_OK) return RC_ERR_IO;
  return a->diff ? rc_output_check_format(a->diff) : RC_OK;
}

/* The heat map is written (or has failed) before any verdict is printed. */
static rc_status write_heat_map(const char *path, const rc_compare_image *im, const rc_compare_image *ref,
                                const bool *colour, const rc_heat_scale *scale, uint64_t *ringed) {
  int w, h;
  rc_heat_map_size(im->w, im->h, &w, &h);
  float *heat = rc_alloc((size_t)w * h * 3, sizeof(float), "the heat map");
  if (!heat) return RC_ERR_OUT_OF_MEMORY;
  char err[512];
  *ringed = rc_heat_map_draw(im->px, ref->px, im->w, im->h, im->c, colour, scale, heat);
  rc_status st = RC_OK;
  if (rc_image_write(path, w, h, 3, heat, rc_encoding_linear(), false, err, sizeof err) != 0) {
    rc_error("%s: cannot write the heat map: %s", path, err);
    st = RC_ERR_IO;
  }
  free(heat);
  return st;
}

/* --require-same-scene: both files name one scene in their headers. */
static rc_status check_same_scene(const compare_args *args, const rc_compare_image *a, const rc_compare_image *b) {
  for (int i = 0; i < 2; i++)
    if (!(i ? b : a)->header.present) {
      rc_error("%s: no vkraycast header (scene hash and settings): it was not written by vkraycast render, or in "
               "a format that drops the header; --require-same-scene needs both", args->files[i]);
      return RC_ERR_INPUT;
    }
  if (strcmp(a->header.scene_hash, b->header.scene_hash) != 0) {
    rc_error("compare: %s was rendered from scene %s and %s from scene %s: different scenes (--require-same-scene)",
             args->files[0], a->header.scene_hash, args->files[1], b->header.scene_hash);
    return RC_ERR_INPUT;
  }
  return RC_OK;
}

/* Pixels over --fail whose first-sample decisions agree: their difference comes from
 * something the AOV does not record (a later sample, a bounce). */
static uint64_t over_with_same_decisions(const rc_compare_image *a, const rc_compare_image *b, const bool *colour,
                                         double fail) {
  uint64_t n = 0;
  for (size_t p = 0; p < (size_t)a->w * a->h; p++) {
    int channel;
    if (rc_compare_pixel_error(a->px, b->px, a->c, colour, p, &channel) > fail &&
        rc_aov_same_decisions(a->px, &a->layout, b->px, &b->layout, a->c, p))
      n++;
  }
  return n;
}

rc_status rc_cmd_compare(int argc, char **argv) {
  compare_args args;
  rc_heat_scale heat;
  rc_status st = parse_args(argc, argv, &args, &heat);
  if (st != RC_OK) return st == RC_DONE ? RC_OK : st;
  rc_compare_image a = {0}, b = {0};
  st = load(args.files[0], &a);
  if (st == RC_OK) st = load(args.files[1], &b);
  if (st == RC_OK && (a.w != b.w || a.h != b.h || a.c != b.c)) {
    rc_error("compare: %s is %dx%d with %d channels, %s is %dx%d with %d channels", args.files[0], a.w, a.h, a.c,
             args.files[1], b.w, b.h, b.c);
    st = RC_ERR_INPUT;
  }
  if (st == RC_OK && args.require_same_scene) st = check_same_scene(&args, &a, &b);
  unsigned char *band = NULL;
  if (st == RC_OK && args.bands.count) st = load_band(&args.bands, &b, &band);
  /* AOV files: the colour metrics over R, G, B only (t, ids and bitfields are not colours). */
  bool colour[RC_AOV_MAX_CHANNELS] = {0};
  bool both_aov = st == RC_OK && a.aov && b.aov;
  if (both_aov) colour[a.layout.r] = colour[a.layout.g] = colour[a.layout.b] = true;
  rc_compare_result r = {0};
  rc_compare_report report = {.path_a = args.files[0], .path_b = args.files[1], .a = &a, .b = &b, .r = &r,
                              .limits = &args.limits, .banded = band != NULL, .top = (int)args.top,
                              .heat_path = args.diff, .heat = heat,
                              .preset = args.preset >= 0 ? rc_compare_presets[args.preset].name : NULL};
  if (st == RC_OK) {
    rc_compare_images(a.px, b.px, a.w, a.h, a.c, both_aov ? colour : NULL, args.limits.fail, args.limits.warn, &r);
    if (both_aov) {
      rc_aov_compare_decisions(a.px, &a.layout, b.px, &b.layout, a.w, a.h, a.c, band, &r);
      report.over_same_decisions = over_with_same_decisions(&a, &b, colour, args.limits.fail);
    }
    if (args.diff) st = write_heat_map(args.diff, &a, &b, both_aov ? colour : NULL, &heat, &report.ringed);
  }
  if (st == RC_OK) {
    rc_compare_judgement judgement;
    rc_compare_judge(&r, &args.limits, &judgement);
    report.judgement = &judgement;
    if (args.json)
      rc_compare_print_json(&report, stdout);
    else
      rc_compare_print_text(&report, stdout);
    if (judgement.verdict == RC_VERDICT_FAIL) st = RC_MISMATCH;
  }
  free(a.px);
  free(b.px);
  free(band);
  return st;
}
