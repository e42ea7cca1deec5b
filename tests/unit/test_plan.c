/* The loop-budget plan: the worst-case step count mirrors the shader's loop nest. */
#include "gpu_plan.h"
#include "rc_test.h"

TEST(steps_per_sample_counts_every_loop) {
  gpu_frame f = {0};
  f.sphere_count = 3;
  f.triangle_count = 4;
  f.light_count = 2;
  f.reflection_depth = 0;
  /* 1 sample loop + 1 bounce + 7 closest-hit + 2 * (1 light + 7 shadow) = 25 */
  CHECK_EQ_INT(rc_gpu_plan_steps_per_sample(&f), 25);
  f.reflection_depth = 2;
  CHECK_EQ_INT(rc_gpu_plan_steps_per_sample(&f), 1 + 3 * 24);
}

TEST(batch_fits_the_budget_and_the_samples) {
  gpu_frame f = {0};
  f.sphere_count = 100;
  f.light_count = 1;
  f.samples_per_pixel = 1024;
  rc_gpu_plan p;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 0, RC_LOOP_BUDGET, &p), RC_OK);
  CHECK_EQ_INT(p.steps_per_sample, 1 + 1 + 100 + 101);
  CHECK_EQ_INT(p.batch_samples, RC_LOOP_BUDGET / 203);
  CHECK(p.batch_samples * p.steps_per_sample <= RC_LOOP_BUDGET);
  f.samples_per_pixel = 4;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 0, RC_LOOP_BUDGET, &p), RC_OK);
  CHECK_EQ_INT(p.batch_samples, 4);
}

TEST(one_sample_over_budget_is_refused) {
  gpu_frame f = {0};
  f.triangle_count = 30000;
  f.light_count = 1;
  f.samples_per_pixel = 1;
  rc_gpu_plan p;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 0, RC_LOOP_BUDGET, &p), RC_ERR_TOO_LARGE);
}

TEST(bvh_plans_from_the_depth_and_never_refuses) {
  gpu_frame f = {0};
  f.triangle_count = 1000000;
  f.object_count = 1000000;
  f.light_count = 2;
  f.samples_per_pixel = 1024;
  rc_gpu_plan p;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 21, RC_LOOP_BUDGET, &p), RC_OK);
  /* 4 x 21 node visits + 16 objects per traversal: 1 + (1 + 100 + 2 * 101) = 304 */
  CHECK_EQ_INT(p.steps_per_sample, 304);
  CHECK_EQ_INT(p.batch_samples, RC_LOOP_BUDGET / 304);
}

TEST(bvh_plan_counts_composites_by_their_loaders_steps) {
  /* 4 objects (a box and three composites, the longest taking 47 steps per ray), depth 4:
   * a ray tests at most the 4 objects, 47 steps each: 16 + 4 x 47 = 204 per traversal,
   * 1 + (1 + 204 + 2 x 205) = 616 with two lights. */
  gpu_frame f = {0};
  f.quadric_count = 1;
  f.csg_count = 3;
  f.object_count = 4;
  f.csg_max_steps = 47;
  f.light_count = 2;
  f.samples_per_pixel = 4;
  rc_gpu_plan p;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 4, 6144, &p), RC_OK);
  CHECK_EQ_INT(p.steps_per_sample, 616);
  CHECK_EQ_INT(p.batch_samples, 4); /* 6144 / 616 = 9, capped at the 4 samples */
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(steps_per_sample_counts_every_loop);
  RUN(batch_fits_the_budget_and_the_samples);
  RUN(one_sample_over_budget_is_refused);
  RUN(bvh_plans_from_the_depth_and_never_refuses);
  RUN(bvh_plan_counts_composites_by_their_loaders_steps);
  TEST_MAIN_END
}
