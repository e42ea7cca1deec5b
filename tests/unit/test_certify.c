/* The certificates' bounds (host/ref/ref_certify.c, the twin of rc_certify.glsl;
 * docs/numerics.md §10) against errors measured in f64: each bound holds, and where the
 * derivation says it is attained, it is nearly attained, so that a bound halved would not
 * hold there. */
#include <math.h>
#include <stdlib.h>

#include "ref/ref_intersect.h"
#include "rc_test.h"

/* A fixed sequence, so that a failure repeats. */
static unsigned long long rng_state = 0x9e3779b97f4a7c15ull;
static double uniform(void) {
  rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(rng_state >> 11) / 9007199254740992.0;
}

static double chord(dvec3 a, dvec3 b) { return rcm_length_d(rcm_sub_d(rcm_normalize_d(a), rcm_normalize_d(b))); }

/* cert_turn: normalize(b) against a / |a| when |b - a| <= x |a|. Sound for b anywhere in
 * that ball, and attained by the b whose offset is perpendicular to it (the tangent from a
 * to the ball), where the chord is 2 sin(asin(x) / 2): within 9 % of x / sqrt(1 - x^2) for
 * x <= 0.45, so half the bound fails there. */
TEST(unit_vector_turn_is_sound_and_attained) {
  const double xs[] = {1e-3, 1e-2, 0.1, 0.3, 0.45};
  dvec3 a = rcm_make_d(1, 0, 0);
  for (size_t i = 0; i < sizeof xs / sizeof *xs; i++) {
    double x = xs[i], bound = ref_cert_turn_d(x);
    double th = asin(x);
    dvec3 worst = rcm_scale_d(rcm_make_d(cos(th), sin(th), 0), cos(th));
    CHECK_NEAR(rcm_length_d(rcm_sub_d(worst, a)), x, 1e-12);
    double c = chord(worst, a);
    CHECK(c <= bound);
    CHECK(c >= 0.91 * bound);
    CHECK(c > 0.5 * bound);
    for (int k = 0; k < 2000; k++) {
      /* A random offset of length up to x. */
      dvec3 e = rcm_make_d(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1);
      e = rcm_scale_d(rcm_normalize_d(e), x * uniform());
      CHECK(chord(rcm_add_d(a, e), a) <= bound);
    }
  }
}

/* The triangle's t bound (cert_triangle_t_error), with the ray exact (eo = ed = 0) so that
 * only f32's rounding separates t from the f64 t of the same f32 inputs: it holds on small
 * triangles far from the ray's origin, the case it was made for, and it is far below
 * pbrt's bound (triangle_t_error), which weighs the edge functions' errors by the depths
 * rather than by their spread about t. */
TEST(triangle_t_bound_is_sound_and_tighter_than_pbrts) {
  packed_frame frame = {0};
  frame.triangle_formula = RC_TRIANGLE_WATERTIGHT;
  frame.certify = RC_CERTIFY_ON;
  ref_scene sc = {.frame = &frame};
  int hits = 0, tighter = 0;
  double worst = 0;
  for (int k = 0; k < 4000; k++) {
    double dist = pow(10, 3 * uniform()), size = dist * pow(10, -1 - 2 * uniform());
    /* A triangle of that size around a point at dist, turned at random, and a ray from
     * near the origin to a point inside it. */
    dvec3 dir = rcm_normalize_d(rcm_make_d(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1));
    dvec3 c = rcm_scale_d(dir, dist);
    vec3 v[3];
    for (int j = 0; j < 3; j++) {
      dvec3 p = rcm_add_d(c, rcm_scale_d(rcm_make_d(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1), size));
      v[j] = rcm_make_f((float)p.x, (float)p.y, (float)p.z);
    }
    packed_triangle tri = {v[0], 0, v[1], RC_NO_NORMALS, v[2], 0};
    vec3 of = rcm_make_f((float)(uniform() - 0.5), (float)(uniform() - 0.5), (float)(uniform() - 0.5));
    double w0 = uniform(), w1 = uniform() * (1 - w0);
    dvec3 inside = rcm_add_d(rcm_add_d(rcm_scale_d(rcm_to_d(v[0]), w0), rcm_scale_d(rcm_to_d(v[1]), w1)),
                             rcm_scale_d(rcm_to_d(v[2]), 1 - w0 - w1));
    dvec3 aim = rcm_normalize_d(rcm_sub_d(inside, rcm_to_d(of)));
    vec3 df = rcm_normalize_f(rcm_make_f((float)aim.x, (float)aim.y, (float)aim.z));
    ref_shear_f sh = ref_ray_shear_for_f(df);
    ref_cert_eo_f = ref_cert_ed_f = 0;
    ref_cert_ok_f = true;
    ref_cert_any_f = ref_cert_self_f = false;
    ref_cert_beyond_f = (float)RC_T_FAR;
    ref_spawned_ray = false;
    ref_cert_triangle_f(&sc, of, &sh, tri, (float)RC_T_FAR, false);
    vec3 bary_f;
    float tf = ref_intersect_triangle_f(of, &sh, tri, (float)RC_T_FAR, &bary_f);
    if (!ref_cert_ok_f || !(tf < (float)RC_T_FAR)) continue; /* uncertain, or missed */
    dvec3 od = rcm_make_d(of.x, of.y, of.z), dd = rcm_make_d(df.x, df.y, df.z);
    ref_shear_d shd = ref_ray_shear_for_d(dd);
    dvec3 bary_d;
    double td = ref_intersect_triangle_d(od, &shd, tri, RC_T_FAR, &bary_d);
    CHECK(td < RC_T_FAR);
    if (!(td < RC_T_FAR)) continue;
    hits++;
    double err = fabs((double)tf - td), bound = ref_cert_t_err_f;
    CHECK(err <= bound);
    if (bound > 0 && err / bound > worst) worst = err / bound;
    ref_sheared_f st = ref_shear_triangle_f(of, &sh, tri);
    tighter += bound * 10 < ref_triangle_t_error_f(&st, ref_enclosing_det_f(st.e));
  }
  /* Enough hits to mean something, and the new bound ten times tighter on most. */
  CHECK(hits > 1000);
  CHECK(tighter * 10 > hits * 9);
  CHECK(worst <= 1);
}

/* A one-sided triangle's side (cert_facing_error, cert_triangle_side): rays from nearly in
 * the triangle's plane to well off it, on triangles from 10^-2 to 10^2 across and up to 100
 * times that from the origin, their f32 direction up to ed from the reference's (ed = 0,
 * and ed = 1e-6 in the worst direction, along the normal). The f64 facing of the reference's
 * direction is within the bound of f32's; the cases include f32 and f64 signs that differ,
 * so a bound too small would show, and the move along the normal reaches more than half
 * the bound, so that a halved bound would not hold. */
TEST(one_sided_triangle_side_is_sound_and_attained) {
  packed_frame frame = {0};
  frame.certify = RC_CERTIFY_ON;
  ref_scene sc = {.frame = &frame};
  int certified = 0, flips = 0;
  double worst = 0;
  for (int k = 0; k < 20000; k++) {
    double scale = pow(10, 4 * uniform() - 2);
    dvec3 c = rcm_scale_d(rcm_make_d(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1), scale * 100 * uniform());
    vec3 v[3];
    for (int j = 0; j < 3; j++) {
      dvec3 p = rcm_add_d(c, rcm_scale_d(rcm_make_d(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1), scale));
      v[j] = rcm_make_f((float)p.x, (float)p.y, (float)p.z);
    }
    packed_triangle tri = {v[0], 0, v[1], RC_NO_NORMALS, v[2], RC_TRIANGLE_ONE_SIDED};
    dvec3 n = rcm_cross_d(rcm_sub_d(rcm_to_d(v[1]), rcm_to_d(v[0])), rcm_sub_d(rcm_to_d(v[2]), rcm_to_d(v[0])));
    if (!(rcm_length_d(n) > 0)) continue;
    n = rcm_normalize_d(n);
    /* A direction in the plane, tilted off it by 10^-9 .. 10^-1 to either side. */
    dvec3 in = rcm_normalize_d(rcm_cross_d(n, rcm_make_d(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5)));
    double tilt = (uniform() < 0.5 ? -1 : 1) * pow(10, -9 + 8 * uniform());
    dvec3 dd = rcm_normalize_d(rcm_add_d(in, rcm_scale_d(n, tilt)));
    vec3 df = rcm_make_f((float)dd.x, (float)dd.y, (float)dd.z);
    double ed = (k % 2) ? 1e-6 : 0;
    /* The reference's direction: f32's, moved by ed against f32's side of the plane. */
    float ff = ref_triangle_facing_f(tri, df);
    dvec3 dref = rcm_add_d(rcm_to_d(df), rcm_scale_d(n, ff < 0 ? ed : -ed));
    double fd = ref_triangle_facing_d(tri, dref);
    ref_cert_ed_f = (float)ed;
    double bound = ref_cert_facing_error_f(tri, df);
    uint32_t side = ref_cert_triangle_side_f(&sc, tri, df);
    double err = fabs((double)ff - fd);
    CHECK(err <= bound);
    if (err / bound > worst) worst = err / bound;
    flips += (ff < 0) != (fd < 0);
    if (side == RC_SIDE_UNSURE) continue;
    certified++;
    CHECK((side == RC_SIDE_FRONT) == (fd < 0));
  }
  ref_cert_ed_f = 0;
  CHECK(certified > 10000);
  CHECK(flips > 10);
  CHECK(worst > 0.5);
  CHECK(worst <= 1);
}

/* Which of two triangles on the sides of one edge triangle_crossing crosses (edges owned by
 * one side), in f32 and in f64 along the same ray: 1 the first, 2 the second, 3 both, 0
 * neither. */
static float rv_get_f(vec3 a, int i) { return i == 0 ? a.x : (i == 1 ? a.y : a.z); }

static int crossed_f(vec3 o, vec3 d, const packed_triangle *t) {
  ref_shear_f sh = ref_ray_shear_for_f(d);
  int m = 0;
  for (int i = 0; i < 2; i++) m |= (ref_triangle_crossing_f(o, &sh, t[i]) < (float)RC_T_FAR) << i;
  return m;
}
static int crossed_d(vec3 o, vec3 d, const packed_triangle *t) {
  dvec3 od = rcm_to_d(o), dd = rcm_to_d(d);
  ref_shear_d sh = ref_ray_shear_for_d(dd);
  int m = 0;
  for (int i = 0; i < 2; i++) m |= (ref_triangle_crossing_d(od, &sh, t[i]) < RC_T_FAR) << i;
  return m;
}

/* Two triangles that share an edge, and rays within f32's bound of it (cert_near_edge,
 * cert_edge_errors, cert_edge_pair). The shared edge's bound is the same in both triangles
 * and holds against f64 along the same ray. Where the triangles lie on the edge's two sides
 * as the ray sees them, the pair is certified and each precision crosses exactly one of
 * them (triangle_crossing), though f32 and f64 pick different ones on some rays. Where one
 * folds behind the other (a silhouette), the pair is never certified, and there the
 * precisions do cross both or neither: a certificate that ignored the fold would be wrong. */
TEST(edge_pairs_cross_once_and_folds_are_refused) {
  packed_frame frame = {0};
  frame.triangle_formula = RC_TRIANGLE_WATERTIGHT;
  frame.certify = RC_CERTIFY_ON;
  int paired = 0, other_side = 0, fold_not_once = 0, near_both = 0;
  double worst_edge = 0;
  for (int k = 0; k < 20000; k++) {
    bool fold = k % 2;
    double scale = pow(10, 4 * uniform() - 2);
    dvec3 c = rcm_scale_d(rcm_make_d(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1), scale * 10);
    dvec3 along = rcm_normalize_d(rcm_make_d(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1));
    dvec3 view = rcm_normalize_d(rcm_cross_d(along, rcm_make_d(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5)));
    dvec3 side = rcm_cross_d(view, along); /* across the edge, as the eye (along -view) sees it */
    dvec3 p = rcm_sub_d(c, rcm_scale_d(along, scale)), q = rcm_add_d(c, rcm_scale_d(along, scale));
    /* The third vertices: on the two sides across the edge, each bent off the view plane; or
     * both on one side, the second behind the first (a fold). */
    dvec3 r1 = rcm_add_d(rcm_add_d(c, rcm_scale_d(side, scale * (0.5 + uniform()))), rcm_scale_d(view, scale * (uniform() - 0.5)));
    dvec3 r2 = fold ? rcm_add_d(r1, rcm_scale_d(view, -scale * (0.2 + uniform())))
                    : rcm_add_d(rcm_add_d(c, rcm_scale_d(side, -scale * (0.5 + uniform()))), rcm_scale_d(view, scale * (uniform() - 0.5)));
    vec3 P = rcm_make_f((float)p.x, (float)p.y, (float)p.z), Q = rcm_make_f((float)q.x, (float)q.y, (float)q.z);
    vec3 R1 = rcm_make_f((float)r1.x, (float)r1.y, (float)r1.z), R2 = rcm_make_f((float)r2.x, (float)r2.y, (float)r2.z);
    /* One winding across the edge: P -> Q in the first, Q -> P in the second. */
    packed_triangle t[2] = {{P, 0, Q, RC_NO_NORMALS, R1, 0}, {Q, 0, P, RC_NO_NORMALS, R2, 0}};
    ref_scene sc = {.frame = &frame, .triangles = t};
    /* The eye 5 to 50 edge lengths away along the view; aimed at the edge, off it by up to a
     * few f32 ulps across. */
    dvec3 at = rcm_add_d(rcm_add_d(c, rcm_scale_d(along, scale * (1.6 * uniform() - 0.8))),
                         rcm_scale_d(side, scale * 4e-7 * (2 * uniform() - 1)));
    dvec3 eye = rcm_add_d(at, rcm_scale_d(view, scale * (5 + 45 * uniform())));
    vec3 of = rcm_make_f((float)eye.x, (float)eye.y, (float)eye.z);
    dvec3 aim = rcm_normalize_d(rcm_sub_d(at, rcm_to_d(of)));
    vec3 df = rcm_normalize_f(rcm_make_f((float)aim.x, (float)aim.y, (float)aim.z));
    ref_shear_f sh = ref_ray_shear_for_f(df);
    ref_cert_eo_f = ref_cert_ed_f = 0;
    uint32_t note[2];
    float bound[2];
    bool near = true;
    for (int i = 0; i < 2; i++) {
      ref_sheared_f st = ref_shear_triangle_f(of, &sh, t[i]);
      float dz;
      vec3 ee = ref_cert_edge_errors_f(&st, &sh, &dz), kk = rcm_scale_f(ee, ref_cert_factor_f(&sc));
      float sum = st.e.x + st.e.y + st.e.z;
      uint32_t n = ref_cert_near_edge_f(st.e, sum, kk);
      near = near && n != RC_CERT_NO_EDGE && fabsf(sum) > 3 * rcm_max_abs_comp_f(kk);
      note[i] = (uint32_t)i << RC_CERT_EDGE_SHIFT | n;
      bound[i] = rv_get_f(ee, (int)((n >> 1) & 3u));
    }
    if (!near) continue;
    near_both++;
    /* The shared edge's bound (cert_edge_errors, from its two vertices): the same in both
     * triangles, and it holds against the f64 value of the same edge function along the
     * same ray. */
    {
      CHECK(bound[0] == bound[1]);
      ref_sheared_f sa = ref_shear_triangle_f(of, &sh, t[0]);
      uint32_t ea = (note[0] >> 1) & 3u;
      dvec3 od = rcm_to_d(of), dd = rcm_to_d(df);
      ref_shear_d shd = ref_ray_shear_for_d(dd);
      ref_sheared_d sd = ref_shear_triangle_d(od, &shd, t[0]);
      double ef = rv_get_f(sa.e, (int)ea), ed = ea == 0 ? sd.e.x : (ea == 1 ? sd.e.y : sd.e.z);
      CHECK(fabs((double)ef - ed) <= bound[0]);
      if (bound[0] > 0 && fabs((double)ef - ed) / bound[0] > worst_edge) worst_edge = fabs((double)ef - ed) / bound[0];
    }
    bool pair = ref_cert_edge_pair_f(&sc, note[0], note[1]);
    int cf = crossed_f(of, df, t), cd = crossed_d(of, df, t);
    if (fold) {
      CHECK(!pair);
      fold_not_once += cf == 0 || cf == 3 || cd == 0 || cd == 3;
      continue;
    }
    CHECK(pair);
    if (!pair) continue;
    paired++;
    CHECK(cf == 1 || cf == 2);
    CHECK(cd == 1 || cd == 2);
    other_side += cf != cd;
  }
  /* 20,000, 10,000, 1,958 and 10,000 when written. */
  CHECK(near_both > 15000);
  CHECK(paired > 7500);
  CHECK(other_side > 500);
  CHECK(fold_not_once > 7500);
  /* The f32 rounding reaches 0.185 of the edge's bound (when written): sound, and not loose by
   * orders of magnitude. */
  CHECK(worst_edge > 0.1);
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(unit_vector_turn_is_sound_and_attained);
  RUN(triangle_t_bound_is_sound_and_tighter_than_pbrts);
  RUN(one_sided_triangle_side_is_sound_and_attained);
  RUN(edge_pairs_cross_once_and_folds_are_refused);
  TEST_MAIN_END
}
