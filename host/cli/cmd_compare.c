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
#include "compare/compare_report.h"
#include "cli/output.h"
#include "image/image_io.h"

typedef struct {
  const char *files[2];
  const char *diff;
  double fail, failpercent, hardfail, warn, warnpercent, depth_tolerance, normal_tolerance;
  uint32_t decisions;
  rc_opt_list bands;
  bool json;
} compare_args;

#define ARG(field) offsetof(compare_args, field)
static const rc_option compare_options[] = {
    {"--fail", NULL, RC_OPT_REAL, ARG(fail), "T", 0, HUGE_VAL,
     .help = "a pixel fails when a colour channel differs by more than T (default 1e-6)"},
    {"--failpercent", NULL, RC_OPT_REAL, ARG(failpercent), "P", 0, 100,
     .help = "allow up to P percent failing pixels (default 0)"},
    {"--hardfail", NULL, RC_OPT_REAL, ARG(hardfail), "H", 0, HUGE_VAL,
     .help = "fail if any colour channel differs by more than H (default: no limit)"},
    {"--warn", NULL, RC_OPT_REAL, ARG(warn), "T", 0, HUGE_VAL,
     .help = "a pixel warns when a colour channel differs by more than T (default 1e-6)"},
    {"--warnpercent", NULL, RC_OPT_REAL, ARG(warnpercent), "P", 0, 100,
     .help = "allow up to P percent warning pixels before the verdict is WARNING (default 0)"},
    {"--decisions", NULL, RC_OPT_UINT, ARG(decisions), "N", 0, UINT32_MAX,
     .heading = "AOV files (render --aov): colour thresholds apply to R, G, B only; the rest is judged here:",
     .help = "allow up to N pixels whose hit flag, object id or shadow bits differ\n(default 0)"},
    {"--depth-tolerance", NULL, RC_OPT_REAL, ARG(depth_tolerance), "R", 0, HUGE_VAL,
     .help = "fail if |t_A - t_B| / |t_B| exceeds R where both hit the same object\n(default: no limit)"},
    {"--normal-tolerance", NULL, RC_OPT_REAL, ARG(normal_tolerance), "RAD", 0, 3.14159265358979323846,
     .help = "fail if the normals of such a pixel differ by more than RAD radians\n(default: no limit)"},
    {"--band", NULL, RC_OPT_LIST, ARG(bands), "REF2",
     .help = "a re-render of B's scene with perturbed inputs (render --perturb);\n"
             "pixels whose decisions differ between B and it form the conditioning\n"
             "band and are left out of the decision counts (repeatable, up to 8)"},
    {"--diff", NULL, RC_OPT_STRING, ARG(diff), "OUT", .heading = "output:",
     .help = "write a heat map of the absolute colour difference: black up to --fail,\n"
             "white at the max error, logarithmic in between"},
    {"--json", NULL, RC_OPT_FLAG, ARG(json), .help = "print the metrics as one JSON object"},
};
#undef ARG

static const char *const compare_positional[] = {"image A", "image B"};
const rc_command_spec rc_compare_spec = {
    .name = "compare",
    .synopsis = "A B [options]",
    .summary = "Error metrics between two images of one size, or two AOV files (render --aov).",
    .epilogue = "Verdict and exit status (diff(1)'s convention; idiff's codes beside it):\n"
                "  PASS     within --fail/--failpercent and --warn/--warnpercent   0 (idiff 0)\n"
                "  WARNING  beyond --warn/--warnpercent only                      0 (idiff 1)\n"
                "  FAIL     beyond --fail/--failpercent/--hardfail, or decisions,\n"
                "           depth or normals beyond their limits                  1 (idiff 2)\n"
                "  trouble  unreadable file, different sizes, bad usage, --diff\n"
                "           not written (no verdict is printed)                   2 (idiff 3, 4)\n",
    .min_positional = 2,
    .max_positional = 2,
    .positional_offset = offsetof(compare_args, files),
    .positional_names = compare_positional,
    .options = compare_options,
    .option_count = sizeof compare_options / sizeof *compare_options,
};

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

static rc_status parse_args(int argc, char **argv, compare_args *a) {
  memset(a, 0, sizeof *a);
  a->fail = a->warn = 1e-6;
  a->hardfail = a->depth_tolerance = a->normal_tolerance = INFINITY;
  rc_status st = rc_parse_command(&rc_compare_spec, argc, argv, a);
  if (st != RC_OK) return st;
  if (a->diff && strcmp(a->diff, "-") == 0) {
    rc_usage_error(&rc_compare_spec, "--diff -: the heat map is not written to standard output; name a file");
    return RC_ERR_USAGE;
  }
  const rc_file_role roles[] = {
      {a->files[0], "image A", false}, {a->files[1], "image B", false}, {a->diff, "the heat map", true}};
  if (rc_check_distinct(roles, 3) != RC_OK) return RC_ERR_USAGE;
  if (a->diff && rc_check_output(a->diff, "the heat map") != RC_OK) return RC_ERR_IO;
  return a->diff ? rc_output_check_format(a->diff) : RC_OK;
}

/* The heat map is written (or has failed) before any verdict is printed. */
static rc_status write_heat_map(const compare_args *a, const rc_compare_image *im, const rc_compare_image *ref,
                                const bool *colour, const rc_compare_result *r) {
  float *heat = rc_alloc((size_t)im->w * im->h * 3, sizeof(float), "the heat map");
  if (!heat) return RC_ERR_OUT_OF_MEMORY;
  char err[512];
  double floor = a->fail > 0 ? a->fail : 1e-7;
  rc_compare_heat_map(im->px, ref->px, im->w, im->h, im->c, colour, floor, isfinite(r->max) ? r->max : 1.0, heat);
  rc_status st = RC_OK;
  if (rc_image_write(a->diff, im->w, im->h, 3, heat, RC_ENCODING_LINEAR, false, err, sizeof err) != 0) {
    rc_error("%s: cannot write the heat map: %s", a->diff, err);
    st = RC_ERR_IO;
  }
  free(heat);
  return st;
}

static rc_verdict judge(const compare_args *a, const rc_compare_result *r) {
  double over = r->pixels ? 100.0 * (double)r->over / (double)r->pixels : 0;
  double warned = r->pixels ? 100.0 * (double)r->warned / (double)r->pixels : 0;
  uint64_t decisions = r->hit_mismatch + r->object_mismatch + r->shadow_mismatch;
  bool fail = over > a->failpercent || r->max > a->hardfail ||
              (r->decisions && (decisions > a->decisions || !(r->max_depth_rel <= a->depth_tolerance) ||
                                !(r->max_normal_angle <= a->normal_tolerance)));
  if (fail) return RC_VERDICT_FAIL;
  return warned > a->warnpercent ? RC_VERDICT_WARN : RC_VERDICT_PASS;
}

rc_status rc_cmd_compare(int argc, char **argv) {
  compare_args args;
  rc_status st = parse_args(argc, argv, &args);
  if (st != RC_OK) return st == RC_DONE ? RC_OK : st;
  rc_compare_image a = {0}, b = {0};
  st = load(args.files[0], &a);
  if (st == RC_OK) st = load(args.files[1], &b);
  if (st == RC_OK && (a.w != b.w || a.h != b.h || a.c != b.c)) {
    rc_error("compare: %s is %dx%d with %d channels, %s is %dx%d with %d channels", args.files[0], a.w, a.h, a.c,
             args.files[1], b.w, b.h, b.c);
    st = RC_ERR_INPUT;
  }
  unsigned char *band = NULL;
  if (st == RC_OK && args.bands.count) st = load_band(&args.bands, &b, &band);
  /* AOV files: the colour metrics over R, G, B only (t, ids and bitfields are not colours). */
  bool colour[RC_AOV_MAX_CHANNELS] = {0};
  bool both_aov = st == RC_OK && a.aov && b.aov;
  if (both_aov) colour[a.layout.r] = colour[a.layout.g] = colour[a.layout.b] = true;
  rc_compare_result r = {0};
  if (st == RC_OK) {
    rc_compare_images(a.px, b.px, a.w, a.h, a.c, both_aov ? colour : NULL, args.fail, args.warn, &r);
    if (both_aov) rc_aov_compare_decisions(a.px, &a.layout, b.px, &b.layout, a.w, a.h, a.c, band, &r);
    if (args.diff) st = write_heat_map(&args, &a, &b, both_aov ? colour : NULL, &r);
  }
  if (st == RC_OK) {
    rc_compare_report report = {.path_a = args.files[0], .path_b = args.files[1], .a = &a, .b = &b, .r = &r,
                                .fail = args.fail, .warn = args.warn, .verdict = judge(&args, &r),
                                .banded = band != NULL};
    if (args.json)
      rc_compare_print_json(&report, stdout);
    else
      rc_compare_print_text(&report, stdout);
    if (report.verdict == RC_VERDICT_FAIL) st = RC_MISMATCH;
  }
  free(a.px);
  free(b.px);
  free(band);
  return st;
}
