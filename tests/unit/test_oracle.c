/* docs/numerics.md §7 (extremes suite, S22): the f64 reference checked against a __float128 oracle. Rays of
 * the S03 (sphere distance) and S07 (triangles far from the origin) configurations; the
 * oracle solves the same problem (the same f64 ray, the same f32 scene values) in 113-bit
 * arithmetic, where the f64 products are exact. Outside the f64 conditioning band (rays
 * whose decision is within 1e-9 relative of flipping for the sphere; for triangles within
 * 1e-12 (1 + |o|) of an edge, as f64 resolves coordinates of magnitude |o| to about
 * 1e-16 |o|, with margin) the classification must agree and t must match to 1e-12
 * relative. */
#if __has_include(<quadmath.h>)
#include <quadmath.h>
#else
/* clang does not search GCC's private include folder, where quadmath.h lives; libquadmath
 * links with either compiler. The functions used here, as quadmath.h declares them: */
__float128 fabsq(__float128);
__float128 fminq(__float128, __float128);
__float128 sqrtq(__float128);
#endif
#include <stdlib.h>

#include "ref/ref_intersect.h"
#include "rc_test.h"

typedef __float128 q128;

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static double uniform(void) { /* xorshift64*, [0, 1) */
  rng ^= rng >> 12, rng ^= rng << 25, rng ^= rng >> 27;
  return (double)((rng * 0x2545f4914f6cdd1dull) >> 11) * 0x1p-53;
}

static q128 qdot(dvec3 a, dvec3 b) { return (q128)a.x * b.x + (q128)a.y * b.y + (q128)a.z * b.z; }

/* The nearest root in (0, inf) of |o + t d - c|^2 = r^2, or -1; *disc_rel: the
 * discriminant over a r^2, which is 1 - (l / r)^2 for the ray's distance l from the
 * centre: how far the ray is from grazing. */
static q128 oracle_sphere(dvec3 o, dvec3 d, dvec3 c, double r, q128 *disc_rel) {
  dvec3 f = rcm_sub_d(o, c); /* exact: o = 0 */
  q128 a = qdot(d, d), b = qdot(f, d), cc = qdot(f, f) - (q128)r * r;
  q128 disc = b * b - a * cc;
  *disc_rel = fabsq(disc) / (a * (q128)r * r);
  if (disc < 0) return -1;
  q128 s = sqrtq(disc), t0 = (-b - s) / a, t1 = (-b + s) / a;
  return t0 > 0 ? t0 : (t1 > 0 ? t1 : -1);
}

/* The comparison of one batch of rays: rays in the band are counted and skipped; the
 * others must be classified alike, and the worst relative t error of the hits is kept. */
typedef struct {
  int checked, band, wrong_class, hits;
  double worst_t;
} tally;

static void tally_ray(tally *a, bool in_band, double closeness, double t, q128 tq) {
  if (in_band) {
    a->band++;
    return;
  }
  a->checked++;
  bool hit_q = tq > 0, hit = t < RC_T_FAR;
  if (hit_q != hit) {
    a->wrong_class++;
    printf("  misclassified: oracle %s, f64 %s, closeness %.3g, t %.17g, oracle t %.17g\n", hit_q ? "hit" : "miss",
           hit ? "hit" : "miss", closeness, t, (double)tq);
    return;
  }
  if (hit) {
    a->hits++;
    double e = (double)(fabsq((q128)t - tq) / tq);
    if (e > a->worst_t) a->worst_t = e;
  }
}

TEST(f64_sphere_reference_matches_the_oracle_at_s03_distances) {
  const double distances[4] = {10, 1e3, 1e5, 1e8};
  for (int k = 0; k < 4; k++) {
    double D = distances[k];
    packed_sphere s = {{0, 0, (float)-D}, 1, 0, RC_NO_TRANSFORM, 0, 0};
    dvec3 c = rcm_make_d(0, 0, -D);
    tally a = {0};
    for (int i = 0; i < 20000; i++) {
      /* Aim at a point within 1.2 radii of the centre, across the sphere's rim. */
      double ang = 2 * M_PI * uniform(), rad = 1.2 * sqrt(uniform());
      dvec3 d = rcm_normalize_d(rcm_make_d(rad * cos(ang), rad * sin(ang), -D));
      q128 disc_rel;
      q128 tq = oracle_sphere(rcm_make_d(0, 0, 0), d, c, 1.0, &disc_rel);
      double side;
      double t = ref_intersect_sphere_geometric_d(rcm_make_d(0, 0, 0), d, s, RC_T_FAR, &side);
      tally_ray(&a, disc_rel < 1e-9, (double)disc_rel, t, tq);
    }
    printf("  D = %g: %d rays checked, %d in the band, %d misclassified, worst t error %.3g\n", D, a.checked, a.band,
           a.wrong_class, a.worst_t);
    CHECK_EQ_INT(a.wrong_class, 0);
    CHECK(a.worst_t <= 1e-12);
    CHECK(a.checked > 19000);
  }
}

/* Exact (in q128) barycentric test of the ray o + t d against triangle v: the signed
 * volumes of (d, v_i - o, v_j - o), whose products of f64 values are exact here (v - o is
 * formed in q128 too). *edge_rel: the smallest |volume| over the size of its products. */
static q128 oracle_triangle(dvec3 o, dvec3 d, const dvec3 v[3], q128 *edge_rel) {
  q128 w[3], sum = 0, mag = 0;
  for (int i = 0; i < 3; i++) {
    const dvec3 *va = &v[(i + 1) % 3], *vb = &v[(i + 2) % 3];
    /* d . (a x b) */
    q128 ax = (q128)va->x - o.x, ay = (q128)va->y - o.y, az = (q128)va->z - o.z;
    q128 bx = (q128)vb->x - o.x, by = (q128)vb->y - o.y, bz = (q128)vb->z - o.z;
    w[i] = (q128)d.x * (ay * bz - az * by) + (q128)d.y * (az * bx - ax * bz) + (q128)d.z * (ax * by - ay * bx);
    sum += w[i];
    /* The size of the products w is made of: its rounding scales with this, not with w. */
    mag += (fabsq(ax) + fabsq(ay) + fabsq(az)) * (fabsq(bx) + fabsq(by) + fabsq(bz));
  }
  q128 least = fminq(fabsq(w[0]), fminq(fabsq(w[1]), fabsq(w[2])));
  *edge_rel = least / mag;
  bool inside = (w[0] >= 0 && w[1] >= 0 && w[2] >= 0) || (w[0] <= 0 && w[1] <= 0 && w[2] <= 0);
  if (!inside || sum == 0) return -1;
  /* t from the plane: n . (v0 - o) / n . d, n = (v1 - v0) x (v2 - v0), in q128. */
  q128 e1[3] = {(q128)v[1].x - v[0].x, (q128)v[1].y - v[0].y, (q128)v[1].z - v[0].z};
  q128 e2[3] = {(q128)v[2].x - v[0].x, (q128)v[2].y - v[0].y, (q128)v[2].z - v[0].z};
  q128 n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  q128 p[3] = {(q128)v[0].x - o.x, (q128)v[0].y - o.y, (q128)v[0].z - o.z};
  q128 t = (n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / (n[0] * d.x + n[1] * d.y + n[2] * d.z);
  return t > 0 ? t : -1;
}

TEST(f64_watertight_reference_matches_the_oracle_at_s07_positions) {
  const double offsets[3][3] = {{0, 0, 0}, {148376, 1234, -223423}, {1e6, 1e6, 1e6}};
  for (int k = 0; k < 3; k++) {
    tally a = {0};
    for (int i = 0; i < 20000; i++) {
      /* A random triangle of size ~1 about 2 units from an origin near the offset, and a
       * ray aimed at a random point of the triangle's plane near it: across its edges,
       * at its vertices (one ray in 8 aims exactly at one) or inside. */
      dvec3 base = rcm_make_d(offsets[k][0], offsets[k][1], offsets[k][2]);
      vec3 fv[3];
      dvec3 v[3];
      for (int j = 0; j < 3; j++) {
        fv[j].x = (float)(base.x + uniform() - 0.5);
        fv[j].y = (float)(base.y + uniform() - 0.5);
        fv[j].z = (float)(base.z - 2 + uniform() - 0.5);
      }
      packed_triangle tri = {fv[0], 0, fv[1], RC_NO_NORMALS, fv[2], 0};
      for (int j = 0; j < 3; j++) v[j] = rcm_make_d(fv[j].x, fv[j].y, fv[j].z);
      double b1 = uniform() * 1.4 - 0.2, b2 = uniform() * 1.4 - 0.2;
      if (i % 8 == 0) b1 = (i / 8) % 2, b2 = 0;
      dvec3 target = rcm_add_d(v[0], rcm_add_d(rcm_scale_d(rcm_sub_d(v[1], v[0]), b1), rcm_scale_d(rcm_sub_d(v[2], v[0]), b2)));
      dvec3 o = rcm_make_d(base.x + 0.1 * uniform(), base.y + 0.1 * uniform(), base.z);
      dvec3 d = rcm_normalize_d(rcm_sub_d(target, o));
      q128 edge_rel;
      q128 tq = oracle_triangle(o, d, v, &edge_rel);
      ref_shear_d sh = ref_ray_shear_for_d(d);
      dvec3 bary;
      ref_spawned_ray = false;
      double t = ref_intersect_triangle_d(o, &sh, tri, RC_T_FAR, &bary);
      tally_ray(&a, edge_rel < 1e-12 * (1 + rcm_max_abs_comp_d(o)), (double)edge_rel, t, tq);
    }
    printf("  offset %g: %d rays checked (%d hits), %d in the band, %d misclassified, worst t error %.3g\n",
           offsets[k][0], a.checked, a.hits, a.band, a.wrong_class, a.worst_t);
    CHECK_EQ_INT(a.wrong_class, 0);
    CHECK(a.worst_t <= 1e-12);
    CHECK(a.hits > 4000 && a.band > 1000); /* coverage: a quarter of the rays hit, one in 8 aims at a vertex */
  }
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(f64_sphere_reference_matches_the_oracle_at_s03_distances);
  RUN(f64_watertight_reference_matches_the_oracle_at_s07_positions);
  TEST_MAIN_END
}
