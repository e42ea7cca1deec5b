/* The cglm-style vector helpers, in both precisions. */
#include "math/rcm_vec3.h"
#include "rc_test.h"

TEST(cross_follows_the_right_hand_rule) {
  dvec3 z = rcm_cross_d(rcm_make_d(1, 0, 0), rcm_make_d(0, 1, 0));
  CHECK(z.x == 0 && z.y == 0 && z.z == 1);
  vec3 x = rcm_cross_f(rcm_make_f(0, 1, 0), rcm_make_f(0, 0, 1));
  CHECK(x.x == 1 && x.y == 0 && x.z == 0);
}

TEST(dot_and_length) {
  CHECK(rcm_dot_d(rcm_make_d(1, 2, 3), rcm_make_d(4, -5, 6)) == 12);
  CHECK(rcm_length_d(rcm_make_d(2, 3, 6)) == 7);
  CHECK(rcm_length_f(rcm_make_f(2, 3, 6)) == 7.0f);
}

TEST(normalize_gives_unit_length) {
  dvec3 n = rcm_normalize_d(rcm_make_d(3e-30, 4e-30, 0));
  CHECK_NEAR(n.x, 0.6, 1e-15);
  CHECK_NEAR(n.y, 0.8, 1e-15);
  vec3 m = rcm_normalize_f(rcm_make_f(1e10f, 1e10f, 1e10f));
  CHECK_NEAR(rcm_length_f(m), 1.0, 1e-6);
}

TEST(reflect_mirrors_about_the_normal) {
  dvec3 r = rcm_reflect_d(rcm_make_d(1, -1, 0), rcm_make_d(0, 1, 0));
  CHECK(r.x == 1 && r.y == 1 && r.z == 0);
}

TEST(max_abs_comp_and_conversion) {
  CHECK(rcm_max_abs_comp_d(rcm_make_d(-7, 3, 5)) == 7);
  vec3 f = rcm_to_f(rcm_make_d(0.1, 1e40, -2));
  CHECK(f.x == 0.1f && isinf(f.y) && f.z == -2.0f);
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(cross_follows_the_right_hand_rule);
  RUN(dot_and_length);
  RUN(normalize_gives_unit_length);
  RUN(reflect_mirrors_about_the_normal);
  RUN(max_abs_comp_and_conversion);
  TEST_MAIN_END
}
