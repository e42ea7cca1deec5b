/* precision_budget.h: "model only what a scene requires" (docs/accuracy.md). Before
 * rendering, an f64 pass over the packed scene measures each object's scale ratios and says
 * whether f32 arithmetic can render it faithfully, naming the object and the ratio. */
#ifndef RC_PRECISION_BUDGET_H
#define RC_PRECISION_BUDGET_H

#include "scene/scene_pack.h"

/* The thresholds, each with its reason beside it, gated by the extremes suite
 * (docs/accuracy.md, tests/extremes/). */
#define RC_BUDGET_HUGE_SPHERE 1.0e4      /* r / (eye's height over the sphere): f32 depth error > 0.1 % */
/* |C| / r, geometric form: beyond it the f32 error-bound offset (gamma(10) |p| ~ 6e-7 |p|)
 * passes 6 % of r, and contact shadows between such spheres are lost (S21 at D = 1e3). */
#define RC_BUDGET_FAR_SPHERE 1.0e5
/* A patch piece's distance over its size: Newton stops within 2^-19 of the distance
 * (rc_shared.h), 1 % of the piece's size at this ratio. */
#define RC_BUDGET_FAR_PATCH 5.0e3
#define RC_BUDGET_FAR_SPHERE_ALGEBRAIC 1.0e2 /* |C| / r, textbook form: f32 loses the sphere from ~1e3 */
/* The two range limits are in packed units: a scene tiny or huge as a whole was packed in
 * power-of-two units first (scene_pack.c), so they catch only one that spans both. */
#define RC_BUDGET_TINY_RADIUS 1.0e-18    /* r^2 (and |l|^2 beside it) near the f32 normal range, 1.2e-38 */
#define RC_BUDGET_FAR_COORDINATE 1.0e18  /* |f|^2 near the f32 range, 3.4e38 */
#define RC_BUDGET_QUANTIZATION 1.0e-2    /* half an f32 ulp of |p| over the feature size */
/* Triangles use RC_BUDGET_HUGE_SPHERE for |p| over the eye's height above their plane, and
 * RC_BUDGET_QUANTIZATION for thin ones: both need f64 arithmetic. */

typedef struct rc_precision_report {
  /* f32 arithmetic cannot render the scene faithfully but f64 arithmetic on the same packed
   * arrays can: --precision auto picks f64 where the device has it. */
  uint32_t needs_f64;
  /* Rounding the positions to f32 (the packed arrays both backends read) moves a feature by
   * more than RC_BUDGET_QUANTIZATION of its size: no shader precision helps. */
  uint32_t quantized;
  char first_f64[320];       /* the first object that needs f64: what, which, the ratio */
  char first_quantized[320]; /* likewise for quantization */
  double ms;                 /* time the pass took */
} rc_precision_report;

void rc_precision_budget(const rc_packed_scene *p, bool algebraic_spheres, rc_precision_report *out);

/* The precision a render runs in: the one decision both backends take, from what was asked
 * (RC_PRECISION_*: the command line's, else the scene's), the budget's finding, and what
 * the renderer has. The CPU reference is the accuracy yardstick: f64 unless f32 is asked
 * for. The GPU: f32 unless f64 is asked for, or auto finds the scene needs it: then f64
 * where the device has shaderFloat64, else certified f32 (docs/numerics.md §10), whose
 * uncertified samples the CPU renders again in f64. `why` says what the user should hear
 * about it. */
typedef enum {
  RC_PRECISION_QUIET,         /* nothing to say */
  RC_PRECISION_AUTO_F64,      /* auto chose f64 (a note) */
  RC_PRECISION_F32_DEGRADED,  /* f32 as asked, but the scene needs f64 (a warning) */
  RC_PRECISION_AUTO_CERTIFIED /* auto wanted f64, the device has none: certified f32 (a note) */
} rc_precision_why;
typedef struct rc_precision_choice {
  bool f64;
  bool certified; /* f32 with certified decisions, the uncertified samples again in f64 */
  rc_precision_why why;
} rc_precision_choice;
rc_precision_choice rc_precision_choose(uint32_t requested, const rc_precision_report *budget, bool reference,
                                        bool device_f64);

#endif
