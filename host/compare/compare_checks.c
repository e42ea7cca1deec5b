#include "compare/compare_checks.h"

#include <math.h>
#include <string.h>

/* The presets' numbers and their reasons are docs/gpu-vs-cpu.md's ("Tolerances"); the
 * test gpu_vs_cpu holds every example scene to them through this table. Shares are
 * percentages of the image's pixels; colour is in linear units. */
#define NONE NAN
const rc_compare_preset rc_compare_presets[] = {
    /* Same backend, same precision, same settings: threads, tiles, regions and merged
     * shards must not change a bit (docs/cluster.md), nor may anything else. */
    {"same-backend", "two renders by one backend at one precision: bit-identical",
     {.fail = 0, .fail_percent = 0, .hardfail = NONE, .warn = 0, .warn_percent = 0, .min_psnr = NONE,
      .decisions = 0, .decisions_percent = NONE, .depth_tolerance = 0, .normal_tolerance = 0}},
    /* GPU f32 against CPU f32, or f64 against f64: the same arithmetic in the same order;
     * what remains are driver builtins a few ulps off libm's (inversesqrt 2 ulps, pow up
     * to 17), which can flip a grazing decision in a later sample or a bounce (measured:
     * 2 of 172,800 pixels of scenes/mesh.json by 0.006). */
    {"same-precision", "GPU against CPU at one precision (f32/f32 or f64/f64)",
     {.fail = 1e-3, .fail_percent = 0.01, .hardfail = NONE, .warn = 1e-4, .warn_percent = 0.01, .min_psnr = 80,
      .decisions = NONE, .decisions_percent = 0.05, .depth_tolerance = NONE, .normal_tolerance = NONE}},
    /* GPU f32 against the CPU f64 reference: f32 rounding of every intersection flips
     * decisions in the conditioning band (grazing rays, shadow terminators), which
     * docs/numerics.md §7 bounds at 0.5 % of pixels; we hold 0.2 %. Colour: 0.5 % of
     * pixels over 1e-3 (mirror bounces multiply the band); a warning past idiff's 0.1 %.
     * A flipped decision may move a pixel by its whole value: no hard cap. */
    {"gpu-vs-cpu", "GPU f32 (or auto) against the CPU f64 reference",
     {.fail = 1e-3, .fail_percent = 0.5, .hardfail = NONE, .warn = 1e-3, .warn_percent = 0.1, .min_psnr = NONE,
      .decisions = NONE, .decisions_percent = 0.2, .depth_tolerance = NONE, .normal_tolerance = NONE}},
    /* f32 against f64 on one backend: the f32 rounding alone, which gpu-vs-cpu's
     * allowances were set for; the driver's ulps are not in it, so the same limits hold. */
    {"f32-vs-f64", "f32 against f64 on one backend",
     {.fail = 1e-3, .fail_percent = 0.5, .hardfail = NONE, .warn = 1e-3, .warn_percent = 0.1, .min_psnr = NONE,
      .decisions = NONE, .decisions_percent = 0.2, .depth_tolerance = NONE, .normal_tolerance = NONE}},
    {0},
};
const char *const rc_compare_preset_names[] = {"same-backend", "same-precision", "gpu-vs-cpu", "f32-vs-f64", NULL};

static void fill(double *field, double preset, double fallback) {
  if (isnan(*field)) *field = isnan(preset) ? fallback : preset;
}

void rc_compare_limits_finish(rc_compare_limits *l, const rc_compare_preset *preset) {
  const rc_compare_limits none = {NONE, NONE, NONE, NONE, NONE, NONE, NONE, NONE, NONE, NONE};
  const rc_compare_limits *p = preset ? &preset->limits : &none;
  fill(&l->fail, p->fail, 1e-6);
  fill(&l->fail_percent, p->fail_percent, 0);
  fill(&l->hardfail, p->hardfail, INFINITY);
  fill(&l->warn, p->warn, 1e-6);
  fill(&l->warn_percent, p->warn_percent, 0);
  fill(&l->min_psnr, p->min_psnr, -INFINITY);
  /* A share of pixels given (by a preset or --decisions-percent) replaces the default
   * count of 0; a count given explicitly still applies beside it. */
  bool share = !isnan(l->decisions_percent) || !isnan(p->decisions_percent);
  fill(&l->decisions_percent, p->decisions_percent, INFINITY);
  fill(&l->decisions, p->decisions, share ? INFINITY : 0);
  fill(&l->depth_tolerance, p->depth_tolerance, INFINITY);
  fill(&l->normal_tolerance, p->normal_tolerance, INFINITY);
}

const char *rc_group_digits(uint64_t n, char *buf, size_t len) {
  char digits[32];
  int d = snprintf(digits, sizeof digits, "%llu", (unsigned long long)n);
  size_t o = 0;
  for (int i = 0; i < d && o + 1 < len; i++) {
    if (i && (d - i) % 3 == 0 && o + 2 < len) buf[o++] = ',';
    buf[o++] = digits[i];
  }
  buf[o < len ? o : len - 1] = '\0';
  return buf;
}

static double percent(uint64_t n, uint64_t of) { return of ? 100.0 * (double)n / (double)of : 0; }

static rc_compare_check *add(rc_compare_judgement *j, const char *id, rc_verdict level) {
  rc_compare_check *c = &j->checks[j->count++];
  memset(c, 0, sizeof *c);
  c->id = id;
  c->level = level;
  return c;
}

/* A count of pixels against a share of the image: "1 (0.0004 %)" against "0.5 % = 1,280". */
static void pixel_share(rc_compare_check *c, uint64_t n, uint64_t pixels, double allowed_percent) {
  char a[32], b[32];
  double limit = floor(allowed_percent / 100.0 * (double)pixels + 1e-9);
  snprintf(c->measured, sizeof c->measured, "%s (%.4g %%)", rc_group_digits(n, a, sizeof a), percent(n, pixels));
  snprintf(c->allowed, sizeof c->allowed, "%g %% = %s", allowed_percent, rc_group_digits((uint64_t)limit, b, sizeof b));
  c->measured_value = (double)n;
  c->allowed_value = limit;
  c->ok = (double)n <= limit;
}

/* The first sample's decisions (its hit, object and the shadow rays of lights 0-23): the
 * share that numerics.md §7 bounds for f32 rounding. Every sample's and bounce's, and every
 * light's, are more: mesh with 700 lights at 32 x 20 and 1 spp, GPU f32 against CPU f64
 * (ctest light_passes), differs in 1 pixel's first-sample record and 5 pixels' digests,
 * where the preset allows 0.2 % = 1. Those flips are left to the shares of pixels over
 * --fail and --warn, which count every pixel, and reported (sample_mismatch). */
static void decisions_check(const rc_compare_result *r, const rc_compare_limits *l, rc_compare_judgement *j) {
  uint64_t n = r->hit_mismatch + r->object_mismatch + r->shadow_mismatch;
  rc_compare_check *c = add(j, "decisions", RC_VERDICT_FAIL);
  snprintf(c->what, sizeof c->what, "pixels whose first-sample decisions differ");
  char a[32], b[32];
  double by_share = isfinite(l->decisions_percent) ? floor(l->decisions_percent / 100.0 * (double)r->pixels + 1e-9)
                                                    : INFINITY;
  double limit = fmin(l->decisions, by_share);
  snprintf(c->measured, sizeof c->measured, "%s (hit %llu, object %llu, shadow %llu)",
           rc_group_digits(n, a, sizeof a), (unsigned long long)r->hit_mismatch,
           (unsigned long long)r->object_mismatch, (unsigned long long)r->shadow_mismatch);
  if (by_share <= l->decisions)
    snprintf(c->allowed, sizeof c->allowed, "%g %% = %s", l->decisions_percent,
             rc_group_digits((uint64_t)limit, b, sizeof b));
  else if (isfinite(limit))
    snprintf(c->allowed, sizeof c->allowed, "%s", rc_group_digits((uint64_t)limit, b, sizeof b));
  else
    snprintf(c->allowed, sizeof c->allowed, "any");
  c->measured_value = (double)n;
  c->allowed_value = limit;
  c->ok = (double)n <= limit;
}

static void limit_check(rc_compare_judgement *j, const char *id, const char *what, double measured, double allowed,
                        const char *unit) {
  rc_compare_check *c = add(j, id, RC_VERDICT_FAIL);
  snprintf(c->what, sizeof c->what, "%s", what);
  snprintf(c->measured, sizeof c->measured, "%.3g%s", measured, unit);
  snprintf(c->allowed, sizeof c->allowed, "%.3g%s", allowed, unit);
  c->measured_value = measured, c->allowed_value = allowed;
  c->ok = measured <= allowed;
}

void rc_compare_judge(const rc_compare_result *r, const rc_compare_limits *l, rc_compare_judgement *j) {
  memset(j, 0, sizeof *j);
  rc_compare_check *c = add(j, "pixels_over_fail", RC_VERDICT_FAIL);
  snprintf(c->what, sizeof c->what, "pixels over --fail %g", l->fail);
  pixel_share(c, r->over, r->pixels, l->fail_percent);
  if (r->nonfinite_mismatch || r->nan_a || r->nan_b) {
    c = add(j, "nonfinite", RC_VERDICT_FAIL);
    snprintf(c->what, sizeof c->what, "values NaN or infinite in one file, not in the other");
    snprintf(c->measured, sizeof c->measured, "%llu", (unsigned long long)r->nonfinite_mismatch);
    snprintf(c->allowed, sizeof c->allowed, "0");
    c->measured_value = (double)r->nonfinite_mismatch;
    c->ok = r->nonfinite_mismatch == 0;
  }
  if (isfinite(l->hardfail)) limit_check(j, "max_error", "max error (--hardfail)", r->max, l->hardfail, "");
  if (isfinite(l->min_psnr)) {
    /* PSNR judges arithmetic. A pixel whose decision flips in some sample may move by its
     * whole value, and one such pixel, of 153,600, held earth's GPU f32 against CPU f32 at
     * 78.7 dB on the H200 (docs/porting.md), where the preset allows 0.05 % of pixels to
     * flip. Where the digests can tell, PSNR runs over the pixels that decide alike in
     * every sample; the others are judged by the decision check and the shares of pixels
     * over --fail and --warn, which count them. */
    bool alike = r->decisions && r->digests;
    double psnr = alike ? r->psnr_alike : r->psnr;
    c = add(j, "psnr", RC_VERDICT_FAIL);
    snprintf(c->what, sizeof c->what, "PSNR%s (--min-psnr)", alike ? " of the pixels that decide alike" : "");
    if (isnan(psnr))
      snprintf(c->measured, sizeof c->measured, "undefined (NaN against a number)");
    else
      snprintf(c->measured, sizeof c->measured, "%.2f dB", psnr);
    snprintf(c->allowed, sizeof c->allowed, "at least %.2f dB", l->min_psnr);
    c->measured_value = psnr, c->allowed_value = l->min_psnr;
    c->ok = psnr >= l->min_psnr;
  }
  if (r->decisions) {
    decisions_check(r, l, j);
    if (isfinite(l->depth_tolerance))
      limit_check(j, "depth", "relative depth error, same object", r->max_depth_rel, l->depth_tolerance, "");
    if (isfinite(l->normal_tolerance))
      limit_check(j, "normal", "normal angle, same object", r->max_normal_angle, l->normal_tolerance, " rad");
  }
  c = add(j, "pixels_over_warn", RC_VERDICT_WARN);
  snprintf(c->what, sizeof c->what, "pixels over --warn %g", l->warn);
  pixel_share(c, r->warned, r->pixels, l->warn_percent);

  j->verdict = RC_VERDICT_PASS;
  for (int i = 0; i < j->count; i++)
    if (!j->checks[i].ok && j->checks[i].level > j->verdict) j->verdict = j->checks[i].level;
}
