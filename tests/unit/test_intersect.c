/* Ray/sphere and ray/triangle tests of the CPU reference (the twins of rc_intersect.glsl),
 * in f64 and f32: hit, miss, behind the origin, origin inside, grazing, degenerate. */
#include <math.h>

#include "ref/ref_intersect.h"
#include "rc_test.h"

static packed_sphere sphere(float x, float y, float z, float r) {
  packed_sphere s = {{x, y, z}, r, 0, RC_NO_TRANSFORM, 0, 0};
  return s;
}

static packed_triangle triangle(vec3 a, vec3 b, vec3 c) {
  packed_triangle t = {a, 0, b, RC_NO_NORMALS, c, 0};
  return t;
}

#define FAR RC_T_FAR

TEST(sphere_hit_from_outside_takes_the_near_root) {
  double side;
  double t = ref_intersect_sphere_geometric_d(rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), sphere(0, 0, -10, 2), FAR, &side);
  CHECK_NEAR(t, 8.0, 1e-12);
  CHECK(side == -1);
  float sidef;
  float tf = ref_intersect_sphere_geometric_f(rcm_make_f(0, 0, 0), rcm_make_f(0, 0, -1), sphere(0, 0, -10, 2), (float)FAR, &sidef);
  CHECK_NEAR(tf, 8.0, 1e-5);
}

TEST(sphere_miss) {
  double side;
  CHECK(ref_intersect_sphere_geometric_d(rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), sphere(3, 0, -10, 2), FAR, &side) == FAR);
  CHECK(side == 0);
}

TEST(sphere_behind_the_origin_is_missed) {
  double side;
  CHECK(ref_intersect_sphere_geometric_d(rcm_make_d(0, 0, 0), rcm_make_d(0, 0, 1), sphere(0, 0, -10, 2), FAR, &side) == FAR);
}

TEST(sphere_origin_inside_hits_the_exit_root) {
  double side;
  double t = ref_intersect_sphere_geometric_d(rcm_make_d(0, 0, 0), rcm_make_d(1, 0, 0), sphere(0.5f, 0, 0, 2), FAR, &side);
  CHECK_NEAR(t, 2.5, 1e-12);
  CHECK(side == 1);
}

TEST(sphere_respects_t_max) {
  double side;
  CHECK(ref_intersect_sphere_geometric_d(rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), sphere(0, 0, -10, 2), 7.9, &side) == FAR);
}

TEST(sphere_grazing_rays_just_inside_hit_and_just_outside_miss) {
  /* Impact parameter 1 - 1e-6 and 1 + 1e-6 on a unit sphere 10 units away. */
  double side;
  dvec3 d = rcm_make_d(0, 0, -1);
  double t_in = ref_intersect_sphere_geometric_d(rcm_make_d(1 - 1e-6, 0, 0), d, sphere(0, 0, -10, 1), FAR, &side);
  CHECK_NEAR(t_in, 10.0 - sqrt(1.0 - (1 - 1e-6) * (1 - 1e-6)), 1e-9);
  CHECK(ref_intersect_sphere_geometric_d(rcm_make_d(1 + 1e-6, 0, 0), d, sphere(0, 0, -10, 1), FAR, &side) == FAR);
}

TEST(sphere_far_away_and_small_stays_visible_in_f32) {
  /* D/r = 1e5: the textbook b^2 - 4ac loses the sphere in f32 (docs/numerics.md §2); the
   * Hearn-Baker discriminant keeps it. */
  float side;
  float t = ref_intersect_sphere_geometric_f(rcm_make_f(0, 0, 0), rcm_make_f(0, 0, -1), sphere(0, 0, -1e5f, 1), (float)FAR, &side);
  CHECK_NEAR(t, 1e5 - 1, 0.02);
}

static double tri_t(dvec3 o, dvec3 d, packed_triangle tri, dvec3 *bary) {
  ref_shear_d sh = ref_ray_shear_for_d(d);
  return ref_intersect_triangle_d(o, &sh, tri, FAR, bary);
}

TEST(triangle_hit_gives_t_and_barycentrics) {
  packed_triangle tri = triangle(rcm_make_f(-1, -1, -5), rcm_make_f(1, -1, -5), rcm_make_f(0, 1, -5));
  dvec3 bary;
  double t = tri_t(rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), tri, &bary);
  CHECK_NEAR(t, 5.0, 1e-12);
  CHECK_NEAR(bary.x + bary.y + bary.z, 1.0, 1e-12);
  CHECK_NEAR(bary.z, 0.5, 1e-12); /* (0,0) is halfway up from the base to the apex */
}

TEST(triangle_miss_and_behind) {
  packed_triangle tri = triangle(rcm_make_f(-1, -1, -5), rcm_make_f(1, -1, -5), rcm_make_f(0, 1, -5));
  dvec3 bary;
  CHECK(tri_t(rcm_make_d(2, 0, 0), rcm_make_d(0, 0, -1), tri, &bary) == FAR);
  CHECK(tri_t(rcm_make_d(0, 0, 0), rcm_make_d(0, 0, 1), tri, &bary) == FAR);
}

TEST(triangle_both_windings_hit) {
  packed_triangle tri = triangle(rcm_make_f(0, 1, -5), rcm_make_f(1, -1, -5), rcm_make_f(-1, -1, -5));
  dvec3 bary;
  CHECK_NEAR(tri_t(rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), tri, &bary), 5.0, 1e-12);
}

TEST(triangle_shared_edge_has_no_crack) {
  /* Rays aimed exactly at the diagonal shared by two triangles of a quad hit at least one
   * (watertight: inclusive edges and exactly negated edge functions). The diagonal's end
   * points are the quad's outer corners, where a rounded direction may rightly miss both,
   * so only its interior is aimed at. */
  packed_triangle a = triangle(rcm_make_f(-1, -1, -3), rcm_make_f(1, -1, -3), rcm_make_f(1, 1, -3));
  packed_triangle b = triangle(rcm_make_f(-1, -1, -3), rcm_make_f(1, 1, -3), rcm_make_f(-1, 1, -3));
  int leaks = 0;
  for (int i = 1; i < 1000; i++) {
    float s = -1.0f + 2.0f * (float)i / 1000.0f;
    vec3 o = rcm_make_f(0.37f, -0.21f, 0.0f);
    vec3 d = rcm_normalize_f(rcm_sub_f(rcm_make_f(s, s, -3.0f), o));
    ref_shear_f sh = ref_ray_shear_for_f(d);
    vec3 bary;
    bool hit = ref_intersect_triangle_f(o, &sh, a, (float)FAR, &bary) < (float)FAR ||
               ref_intersect_triangle_f(o, &sh, b, (float)FAR, &bary) < (float)FAR;
    if (!hit) printf("  leak at s = %.9g\n", s);
    leaks += !hit;
  }
  CHECK_EQ_INT(leaks, 0);
}

TEST(degenerate_triangle_is_missed) {
  packed_triangle line = triangle(rcm_make_f(-1, 0, -5), rcm_make_f(0, 0, -5), rcm_make_f(1, 0, -5));
  packed_triangle point = triangle(rcm_make_f(0, 0, -5), rcm_make_f(0, 0, -5), rcm_make_f(0, 0, -5));
  dvec3 bary;
  CHECK(tri_t(rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), line, &bary) == FAR);
  CHECK(tri_t(rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), point, &bary) == FAR);
}

TEST(closest_hit_takes_the_nearest_and_lowest_index_on_ties) {
  packed_sphere spheres[3] = {sphere(0, 0, -10, 1), sphere(0, 0, -5, 1), sphere(0, 0, -5, 1)};
  packed_triangle tris[1] = {triangle(rcm_make_f(-1, -1, -3.5f), rcm_make_f(1, -1, -3.5f), rcm_make_f(0, 1, -3.5f))};
  packed_frame frame = {0};
  frame.sphere_count = 3;
  frame.triangle_count = 0;
  frame.object_count = 3;
  ref_scene sc = {.frame = &frame, .spheres = spheres, .triangles = tris};
  ref_hit_d h;
  CHECK(ref_closest_hit_d(&sc, rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), 0, 0, &h));
  CHECK_EQ_INT(h.kind, RC_HIT_SPHERE);
  CHECK_EQ_INT(h.index, 1);
  CHECK_NEAR(h.t, 4.0, 1e-12);
  frame.triangle_count = 1;
  frame.object_count = 4;
  CHECK(ref_closest_hit_d(&sc, rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), 0, 0, &h));
  CHECK_EQ_INT(h.kind, RC_HIT_TRIANGLE);
  CHECK_NEAR(h.t, 3.5, 1e-12);
}

TEST(occluded_only_within_t_max) {
  packed_sphere spheres[1] = {sphere(0, 0, -5, 1)};
  packed_frame frame = {0};
  frame.sphere_count = 1;
  frame.object_count = 1;
  ref_scene sc = {.frame = &frame, .spheres = spheres};
  CHECK(ref_occluded_d(&sc, rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), 10.0, 0));
  CHECK(!ref_occluded_d(&sc, rcm_make_d(0, 0, 0), rcm_make_d(0, 0, -1), 3.9, 0));
  CHECK(!ref_occluded_d(&sc, rcm_make_d(0, 0, 0), rcm_make_d(0, 1, 0), 10.0, 0));
}

/* A unit cylinder along z, |z| <= 1 (normalized as the loader builds it), solid or open. */
static packed_quadric cylinder_z(bool solid) {
  packed_quadric q = {.center = {0, 0, 0}, .axis_x = {1, 0, 0}, .axis_y = {0, 1, 0}, .axis_z = {0, 0, 1},
                   .constant = -1, .flags = solid ? RC_QUADRIC_SOLID : 0u, .diag = {1, 1, 0},
                   .lo = {-1.001f, -1.001f, -1}, .hi = {1.001f, 1.001f, 1}};
  return q;
}

TEST(quadric_ray_along_a_cylinders_axis_takes_the_a_zero_branch) {
  /* a = 0 exactly: inside the radius the whole line is inside, outside none of it; the
   * solid is then hit on its cap, the open tube not at all. */
  packed_quadric q = cylinder_z(true);
  double lo, hi;
  CHECK_EQ_INT(ref_quadric_roots_d(&q, rcm_make_d(0.5, 0, 5), rcm_make_d(0, 0, -1), &lo, &hi), 1u); /* ALL */
  CHECK_EQ_INT(ref_quadric_roots_d(&q, rcm_make_d(1.5, 0, 5), rcm_make_d(0, 0, -1), &lo, &hi), 0u); /* NONE */
  packed_frame f = {0};
  ref_scene sc = {.frame = &f, .quadrics = &q};
  uint32_t code;
  double t = ref_intersect_quadric_d(&sc, 0, rcm_make_d(0.5, 0, 5), rcm_make_d(0, 0, -1), FAR, &code);
  CHECK_NEAR(t, 4.0, 1e-12);
  CHECK_EQ_INT((code >> 2) & 3u, 3u); /* the z face: the cap */
  dvec3 n = ref_quadric_normal_d(&q, code, rcm_make_d(0.5, 0, 1), rcm_make_d(0, 0, -1));
  CHECK(n.x == 0 && n.y == 0 && n.z == 1);
  q = cylinder_z(false);
  CHECK(ref_intersect_quadric_d(&sc, 0, rcm_make_d(0.5, 0, 5), rcm_make_d(0, 0, -1), FAR, &code) == FAR);
}

TEST(quadric_nearly_parallel_rays_stay_finite_and_right) {
  /* Tilted by 1e-6 from the axis: a ~ 1e-12; the far root is pinned, never Inf or NaN.
   * From (0.5, 0, 5) the ray meets the cap z = 1 at t = 4 / cos, and the wall only far
   * beyond the box. */
  packed_quadric q = cylinder_z(true);
  packed_frame f = {0};
  ref_scene sc = {.frame = &f, .quadrics = &q};
  uint32_t code;
  dvec3 dd = rcm_normalize_d(rcm_make_d(1e-6, 0, -1));
  vec3 df = rcm_normalize_f(rcm_make_f(1e-6f, 0, -1));
  double t = ref_intersect_quadric_d(&sc, 0, rcm_make_d(0.5, 0, 5), dd, FAR, &code);
  float tf = ref_intersect_quadric_f(&sc, 0, rcm_make_f(0.5f, 0, 5), df, (float)FAR, &code);
  CHECK_NEAR(t, 4.0 / -dd.z, 1e-12);
  CHECK_NEAR(tf, 4.0, 1e-5);
  double lo, hi;
  CHECK_EQ_INT(ref_quadric_roots_d(&q, rcm_make_d(0.5, 0, 5), dd, &lo, &hi), 2u); /* BETWEEN */
  CHECK(isfinite(lo) && isfinite(hi) && hi > 1e5);
}

TEST(quadric_paraboloid_along_its_axis_has_one_root) {
  /* x^2 + y^2 = z from above along -z at (0.5, 0): a = 0, h != 0, one root at z = 0.25. */
  packed_quadric q = {.center = {0, 0, 0}, .axis_x = {1, 0, 0}, .axis_y = {0, 1, 0}, .axis_z = {0, 0, 1},
                   .constant = 0, .flags = 0, .diag = {1, 1, 0}, .linear = {0, 0, -0.5f},
                   .lo = {-2, -2, 0}, .hi = {2, 2, 4}};
  packed_frame f = {0};
  ref_scene sc = {.frame = &f, .quadrics = &q};
  uint32_t code;
  CHECK_NEAR(ref_intersect_quadric_d(&sc, 0, rcm_make_d(0.5, 0, 5), rcm_make_d(0, 0, -1), FAR, &code), 4.75, 1e-12);
  CHECK_NEAR(ref_intersect_quadric_f(&sc, 0, rcm_make_f(0.5f, 0, 5), rcm_make_f(0, 0, -1), (float)FAR, &code), 4.75,
             1e-6);
}

/* The cube [-1, 1]^3 as 12 triangles, some wound in, some out (parity needs no winding). */
static void cube_triangles(packed_triangle t[12]) {
  static const float v[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  static const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                               {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  for (int i = 0; i < 12; i++) {
    const float *a = v[f[i][0]], *b = v[f[i][1]], *c = v[f[i][2]];
    t[i] = triangle((vec3){a[0], a[1], a[2]}, (vec3){b[0], b[1], b[2]}, (vec3){c[0], c[1], c[2]});
  }
}

/* Crossings of the line o + t d with the cube, in f64 and in f32 (must agree). */
static int cube_crossings(dvec3 o, dvec3 d) {
  packed_triangle t[12];
  cube_triangles(t);
  ref_shear_d sd = ref_ray_shear_for_d(d);
  vec3 of = rcm_to_f(o), df = rcm_to_f(d);
  ref_shear_f sf = ref_ray_shear_for_f(df);
  int n = 0, nf = 0;
  for (int i = 0; i < 12; i++) {
    n += ref_triangle_crossing_d(o, &sd, t[i]) < FAR;
    nf += ref_triangle_crossing_f(of, &sf, t[i]) < (float)FAR;
  }
  return n == nf ? n : -1;
}

TEST(mesh_line_through_shared_edges_and_vertices_crosses_once_each) {
  /* Through the diagonal that splits the faces z = +-1 into two triangles. */
  CHECK_EQ_INT(cube_crossings(rcm_make_d(0, 0, 5), rcm_make_d(0, 0, -1)), 2);
  /* Through the edges x = y = +-1 (where two faces meet), across the inside. */
  dvec3 diag = rcm_normalize_d(rcm_make_d(-1, -1, 0));
  CHECK_EQ_INT(cube_crossings(rcm_make_d(3, 3, 0.25), diag), 2);
  /* Through the opposite corners (1, 1, 1) and (-1, -1, -1), where fans of triangles meet. */
  CHECK_EQ_INT(cube_crossings(rcm_make_d(3, 3, 3), rcm_normalize_d(rcm_make_d(-1, -1, -1))), 2);
  /* Along the outside of an edge, touching it: none or two, never one. */
  int graze = cube_crossings(rcm_make_d(1, 1, 5), rcm_make_d(0, 0, -1));
  CHECK(graze == 0 || graze == 2);
  /* Every line through the cube's centre in a fan of directions: always two. */
  for (int k = 0; k < 64; k++) {
    double a = k * 0.0981748, b = k * 0.3926991;
    dvec3 d = rcm_make_d(cos(a) * cos(b), sin(a), cos(a) * sin(b));
    CHECK_EQ_INT(cube_crossings(rcm_scale_d(d, -4), d), 2);
  }
}

TEST(csg_difference_and_intersection_give_the_interval_ends) {
  /* Unit sphere at 0 (leaf 0) and radius-0.5 sphere at (0, 0, 0.8) (leaf 1), along -z from
   * z = 5: A is [4, 6], B is [3.7, 4.7]. A - B starts where B ends, 4.7, on B's surface,
   * flipped; A & B starts at 4, on A. */
  packed_quadric leaves[2] = {
      {.center = {0, 0, 0}, .axis_x = {1, 0, 0}, .axis_y = {0, 1, 0}, .axis_z = {0, 0, 1}, .constant = -1,
       .flags = RC_QUADRIC_SOLID, .diag = {1, 1, 1}, .lo = {-1.01f, -1.01f, -1.01f}, .hi = {1.01f, 1.01f, 1.01f}},
      {.center = {0, 0, 0.8f}, .axis_x = {1, 0, 0}, .axis_y = {0, 1, 0}, .axis_z = {0, 0, 1}, .constant = -0.25f,
       .flags = RC_QUADRIC_SOLID, .diag = {1, 1, 1}, .lo = {-0.51f, -0.51f, -0.51f}, .hi = {0.51f, 0.51f, 0.51f}}};
  const uint32_t program[6] = {RC_CSG_LEAF << RC_CSG_OP_SHIFT,       (RC_CSG_LEAF << RC_CSG_OP_SHIFT) | 1u,
                               RC_CSG_DIFFERENCE << RC_CSG_OP_SHIFT, RC_CSG_LEAF << RC_CSG_OP_SHIFT,
                               (RC_CSG_LEAF << RC_CSG_OP_SHIFT) | 1u, RC_CSG_INTERSECTION << RC_CSG_OP_SHIFT};
  const packed_csg csg[2] = {{.first = 0, .count = 3}, {.first = 3, .count = 3}};
  packed_frame f = {0};
  ref_scene sc = {.frame = &f, .quadrics = leaves, .csg = csg, .csg_program = program};
  uint32_t code;
  /* (B's centre is the float nearest 0.8, 1.2e-8 above it.) */
  CHECK_NEAR(ref_intersect_csg_d(&sc, 0, rcm_make_d(0, 0, 5), rcm_make_d(0, 0, -1), FAR, &code), 4.7, 2e-8);
  CHECK_EQ_INT(code >> RC_CSG_CODE_LEAF_SHIFT, 1u);   /* on B */
  CHECK_EQ_INT(code & 1u, 1u);   /* flipped: B was subtracted */
  dvec3 n = ref_quadric_normal_d(&leaves[code >> RC_CSG_CODE_LEAF_SHIFT], code, rcm_make_d(0, 0, 0.3), rcm_make_d(0, 0, -1));
  CHECK(n.z > 0); /* B's inner surface faces up, out of A - B */
  CHECK_NEAR(ref_intersect_csg_d(&sc, 1, rcm_make_d(0, 0, 5), rcm_make_d(0, 0, -1), FAR, &code), 4.0, 1e-12);
  CHECK_EQ_INT(code >> RC_CSG_CODE_LEAF_SHIFT, 0u);
  /* Beside B (x = 0.6) the difference is A itself. */
  CHECK_NEAR(ref_intersect_csg_d(&sc, 0, rcm_make_d(0.6, 0, 5), rcm_make_d(0, 0, -1), FAR, &code), 4.2, 1e-12);
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(sphere_hit_from_outside_takes_the_near_root);
  RUN(sphere_miss);
  RUN(sphere_behind_the_origin_is_missed);
  RUN(sphere_origin_inside_hits_the_exit_root);
  RUN(sphere_respects_t_max);
  RUN(sphere_grazing_rays_just_inside_hit_and_just_outside_miss);
  RUN(sphere_far_away_and_small_stays_visible_in_f32);
  RUN(triangle_hit_gives_t_and_barycentrics);
  RUN(triangle_miss_and_behind);
  RUN(triangle_both_windings_hit);
  RUN(triangle_shared_edge_has_no_crack);
  RUN(mesh_line_through_shared_edges_and_vertices_crosses_once_each);
  RUN(degenerate_triangle_is_missed);
  RUN(closest_hit_takes_the_nearest_and_lowest_index_on_ties);
  RUN(occluded_only_within_t_max);
  RUN(quadric_ray_along_a_cylinders_axis_takes_the_a_zero_branch);
  RUN(quadric_nearly_parallel_rays_stay_finite_and_right);
  RUN(quadric_paraboloid_along_its_axis_has_one_root);
  RUN(csg_difference_and_intersection_give_the_interval_ends);
  TEST_MAIN_END
}
