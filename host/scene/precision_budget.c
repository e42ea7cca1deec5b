/* precision_budget.c: see precision_budget.h. Everything is measured in the packed space
 * (relative to the eye by default), where the renderers compute. */
#include "scene/precision_budget.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "math/rcm_mat3.h"

/* The spacing of f32 values near x. */
static double ulp_f32(double x) {
  float f = fabsf((float)x);
  return (double)nextafterf(f, INFINITY) - (double)f;
}

/* Counts a finding; the first one's message is kept. */
static void note(uint32_t *count, char *first, size_t size, const char *fmt, ...) {
  if ((*count)++ != 0) return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(first, size, fmt, ap);
  va_end(ap);
}

/* How far e lies outside the interval spanned by a, b, c (0 inside): one axis of the
 * distance from the eye to a triangle's bounding box. */
static double gap(double e, double a, double b, double c) {
  return fmax(fmax(fmin(a, fmin(b, c)) - e, 0), e - fmax(a, fmax(b, c)));
}

/* Spheres: tiny, far, seen from just above a huge one, or with a centre f32 moves. */
static void judge_spheres(const rc_packed_scene *p, dvec3 eye, double u, bool algebraic, rc_precision_report *r) {
  for (size_t i = 0; i < p->frame.sphere_count; i++) {
    const packed_sphere *s = &p->spheres[i];
    if (s->transform != RC_NO_TRANSFORM) continue; /* ellipsoids: object space, scale 1 by construction */
    double rad = s->radius;
    double dist = rcm_length_d(rcm_sub_d(rcm_to_d(s->center), eye));
    double reach = rcm_length_d(rcm_to_d(s->center)) + rad; /* the largest |p| the sphere's math sees */
    if (rad < RC_BUDGET_TINY_RADIUS || reach > RC_BUDGET_FAR_COORDINATE) {
      note(&r->needs_f64, r->first_f64, sizeof r->first_f64,
           "sphere %zu: radius %g at |p| %g leaves the f32 range once squared", i, rad * u, reach * u);
      continue;
    }
    double height = fabs(dist - rad);
    if (height > 0 && rad / height > RC_BUDGET_HUGE_SPHERE) {
      note(&r->needs_f64, r->first_f64, sizeof r->first_f64,
           "sphere %zu: the eye is %g above a sphere of radius %g (ratio %.3g)", i, height * u, rad * u, rad / height);
    } else if (dist / rad > (algebraic ? RC_BUDGET_FAR_SPHERE_ALGEBRAIC : RC_BUDGET_FAR_SPHERE)) {
      note(&r->needs_f64, r->first_f64, sizeof r->first_f64, "sphere %zu%s: distance %g over radius %g (ratio %.3g)",
           i, algebraic ? " (algebraic formula)" : "", dist * u, rad * u, dist / rad);
    }
    double centre = rcm_max_abs_comp_f(s->center), q = 0.5 * ulp_f32(centre) / rad;
    if (q > RC_BUDGET_QUANTIZATION)
      note(&r->quantized, r->first_quantized, sizeof r->first_quantized,
           "sphere %zu: its centre at |p| %g is rounded to f32 by up to %.3g of its radius", i, centre * u, q);
  }
}

/* Triangles, standalone and of composites' mesh operands alike. */
static void judge_triangles(const rc_packed_scene *p, dvec3 eye, double u, rc_precision_report *r) {
  for (size_t i = 0; i < p->triangle_total; i++) {
    const packed_triangle *t = &p->triangles[i];
    dvec3 a = rcm_to_d(t->v0), b = rcm_to_d(t->v1), c = rcm_to_d(t->v2);
    dvec3 e0 = rcm_sub_d(b, a), e1 = rcm_sub_d(c, b), e2 = rcm_sub_d(a, c);
    double longest = fmax(rcm_length_d(e0), fmax(rcm_length_d(e1), rcm_length_d(e2)));
    dvec3 normal = rcm_cross_d(e0, rcm_neg_d(e2));
    double twice_area = rcm_length_d(normal);
    double altitude = longest > 0 ? twice_area / longest : 0;
    double reach = fmax(rcm_max_abs_comp_f(t->v0), fmax(rcm_max_abs_comp_f(t->v1), rcm_max_abs_comp_f(t->v2)));
    if (reach > RC_BUDGET_FAR_COORDINATE) {
      note(&r->needs_f64, r->first_f64, sizeof r->first_f64, "triangle %zu: |p| %g leaves the f32 range once squared",
           i, reach * u);
      continue;
    }
    /* The eye's height over the triangle's plane, as for huge spheres: the hit point and
     * its error bound are built from vertices far bigger than the distances that matter. */
    double height = twice_area > 0 ? fabs(rcm_dot_d(rcm_sub_d(eye, a), normal)) / twice_area : 0;
    /* ... or to its bounding box, when farther: a distant triangle whose plane happens to
     * pass by the eye is not "seen up close". */
    dvec3 box_gap = rcm_make_d(gap(eye.x, a.x, b.x, c.x), gap(eye.y, a.y, b.y, c.y), gap(eye.z, a.z, b.z, c.z));
    height = fmax(height, rcm_length_d(box_gap));
    /* A triangle thinner than a few f32 ulps of its coordinates: f32 edge functions and
     * t-error bounds cannot resolve it (slivers), where f64 ones can. */
    double q = altitude > 0 ? 0.5 * ulp_f32(reach) / altitude : INFINITY;
    if (height > 0 && reach / height > RC_BUDGET_HUGE_SPHERE)
      note(&r->needs_f64, r->first_f64, sizeof r->first_f64,
           "triangle %zu: the eye is %g above a triangle reaching |p| %g (ratio %.3g)", i, height * u, reach * u,
           reach / height);
    else if (q > RC_BUDGET_QUANTIZATION)
      note(&r->needs_f64, r->first_f64, sizeof r->first_f64,
           "triangle %zu: altitude %g at |p| %g, %.3g of it per f32 ulp", i, altitude * u, reach * u, 2 * q);
  }
}

/* A patch piece (RC_QUADRIC_PATCH): Newton's method converges to within 32 f32 ulps of the
 * net's coordinates relative to the ray's origin (rc_patch.glsl), about the eye's distance,
 * which must stay well below the piece's size, as a sphere's rounding must below its
 * radius: the far-sphere rule with the piece's largest half-extent (a flat piece has no
 * smallest). Its control points' f32 rounding against that size, too. */
static void judge_patch_piece(const packed_quadric *q, uint32_t i, dvec3 eye, double u, rc_precision_report *r) {
  dvec3 half = rcm_scale_d(rcm_sub_d(rcm_to_d(q->hi), rcm_to_d(q->lo)), 0.5);
  double size = fmax(half.x, fmax(half.y, half.z));
  double dist = rcm_length_d(rcm_sub_d(rcm_to_d(q->center), eye));
  double reach = rcm_max_abs_comp_f(q->center) + size;
  if (reach > RC_BUDGET_FAR_COORDINATE || size < RC_BUDGET_TINY_RADIUS)
    note(&r->needs_f64, r->first_f64, sizeof r->first_f64, "patch piece %u: size %g at |p| %g leaves the f32 range once squared",
         i, size * u, reach * u);
  else if (dist / size > RC_BUDGET_FAR_PATCH)
    note(&r->needs_f64, r->first_f64, sizeof r->first_f64, "patch piece %u: distance %g over size %g (ratio %.3g)", i,
         dist * u, size * u, dist / size);
  double qz = 0.5 * ulp_f32(reach) / size;
  if (qz > RC_BUDGET_QUANTIZATION)
    note(&r->quantized, r->first_quantized, sizeof r->first_quantized,
         "patch piece %u: its control points are rounded to f32 by up to %.3g of its size", i, qz);
}

/* Quadrics (standalone and composite leaves): their math runs on p - centre in their own
 * frame, the sphere's geometric form generalized, so the far-sphere rule applies with
 * the box's smallest half-extent as the radius; and the centre's f32 rounding against it.
 * Under a transform the frame is scaled: a half-extent h along frame axis k spans
 * h |column k of R^-1| in packed space. */
static void judge_quadrics(const rc_packed_scene *p, dvec3 eye, double u, rc_precision_report *r) {
  for (uint32_t i = 0; i < p->quadric_total; i++) {
    const packed_quadric *q = &p->quadrics[i];
    if (q->flags & RC_QUADRIC_UNBOUNDED) {
      /* An infinite plane is centred on its point nearest the eye (scene_pack.c): a primary
       * ray's t is one division of two inputs rounded once, its hit point is projected onto
       * the plane, and its normal is exact, at any distance or angle; rounding the centre
       * moves the plane by 2^-24 of its distance from the eye. Only the f32 range limits it. */
      double reach = rcm_max_abs_comp_f(q->center);
      if (reach > RC_BUDGET_FAR_COORDINATE)
        note(&r->needs_f64, r->first_f64, sizeof r->first_f64, "plane %u: %g from the eye leaves the f32 range once squared",
             i - (p->frame.quadric_count - p->frame.plane_count), reach * u);
      continue;
    }
    if (q->flags & RC_QUADRIC_MESH) continue; /* a mesh operand: its triangles were judged above */
    if (q->flags & RC_QUADRIC_PATCH) {
      judge_patch_piece(q, i, eye, u, r);
      continue;
    }
    dvec3 half = rcm_scale_d(rcm_sub_d(rcm_to_d(q->hi), rcm_to_d(q->lo)), 0.5);
    const double w[3][3] = {{q->axis_x.x, q->axis_x.y, q->axis_x.z}, {q->axis_y.x, q->axis_y.y, q->axis_y.z},
                            {q->axis_z.x, q->axis_z.y, q->axis_z.z}};
    double m[3][3];
    if (rcm_mat3_inverse_d(w, m)) {
      half.x *= sqrt(m[0][0] * m[0][0] + m[1][0] * m[1][0] + m[2][0] * m[2][0]);
      half.y *= sqrt(m[0][1] * m[0][1] + m[1][1] * m[1][1] + m[2][1] * m[2][1]);
      half.z *= sqrt(m[0][2] * m[0][2] + m[1][2] * m[1][2] + m[2][2] * m[2][2]);
    }
    double size = fmin(half.x, fmin(half.y, half.z));
    double dist = rcm_length_d(rcm_sub_d(rcm_to_d(q->center), eye));
    double reach = rcm_max_abs_comp_f(q->center) + fmax(half.x, fmax(half.y, half.z));
    const char *what = i < p->frame.quadric_count ? "quadric" : "composite operand";
    size_t k = i < p->frame.quadric_count ? i : i - p->frame.quadric_count;
    if (reach > RC_BUDGET_FAR_COORDINATE || size < RC_BUDGET_TINY_RADIUS) {
      note(&r->needs_f64, r->first_f64, sizeof r->first_f64, "%s %zu: size %g at |p| %g leaves the f32 range once squared",
           what, k, size * u, reach * u);
    } else if (dist / size > RC_BUDGET_FAR_SPHERE) {
      note(&r->needs_f64, r->first_f64, sizeof r->first_f64, "%s %zu: distance %g over size %g (ratio %.3g)", what, k,
           dist * u, size * u, dist / size);
    }
    double qz = 0.5 * ulp_f32(rcm_max_abs_comp_f(q->center)) / size;
    if (qz > RC_BUDGET_QUANTIZATION)
      note(&r->quantized, r->first_quantized, sizeof r->first_quantized,
           "%s %zu: its centre is rounded to f32 by up to %.3g of its size", what, k, qz);
  }
}

/* `u`: the messages give lengths in scene units, packed units times 1 / scale. */
void rc_precision_budget(const rc_packed_scene *p, bool algebraic, rc_precision_report *r) {
  double t0 = rc_now_ms();
  *r = (rc_precision_report){0};
  const dvec3 eye = rcm_to_d(p->frame.camera.eye);
  const double u = 1.0 / p->scale;
  judge_spheres(p, eye, u, algebraic, r);
  judge_triangles(p, eye, u, r);
  judge_quadrics(p, eye, u, r);
  r->ms = rc_now_ms() - t0;
}

rc_precision_choice rc_precision_choose(uint32_t requested, const rc_precision_report *budget, bool reference,
                                        bool device_f64) {
  /* certified: f32 with every decision checked, and the samples it cannot vouch for in f64. */
  if (requested == RC_PRECISION_CERTIFIED) return (rc_precision_choice){false, true, RC_PRECISION_QUIET};
  if (reference) return (rc_precision_choice){requested != RC_PRECISION_F32, false, RC_PRECISION_QUIET};
  if (requested == RC_PRECISION_F64) return (rc_precision_choice){true, false, RC_PRECISION_QUIET};
  if (requested == RC_PRECISION_F32)
    return (rc_precision_choice){false, false, budget->needs_f64 ? RC_PRECISION_F32_DEGRADED : RC_PRECISION_QUIET};
  if (!budget->needs_f64) return (rc_precision_choice){false, false, RC_PRECISION_QUIET};
  if (device_f64) return (rc_precision_choice){true, false, RC_PRECISION_AUTO_F64};
  /* No f64 on the device (most consumer GPUs, Apple): certified f32, which makes every
   * decision the reference's with the CPU's help, rather than a degraded f32 image. */
  return (rc_precision_choice){false, true, RC_PRECISION_AUTO_CERTIFIED};
}
