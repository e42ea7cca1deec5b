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

#endif
