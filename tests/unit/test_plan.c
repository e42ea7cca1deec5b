/* The loop-budget plan: the worst-case step count mirrors the shader's loop nest. */
#include "gpu/gpu_plan.h"
#include "rc_test.h"
#include "scene/scene.h"

TEST(steps_per_sample_counts_every_loop) {
  packed_frame f = {0};
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
  packed_frame f = {0};
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
  packed_frame f = {0};
  f.triangle_count = 30000;
  f.light_count = 1;
  f.samples_per_pixel = 1;
  rc_gpu_plan p;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 0, RC_LOOP_BUDGET, &p), RC_ERR_TOO_LARGE);
}

TEST(lights_beyond_one_dispatch_go_in_passes_that_fit_the_budget) {
  /* 100 spheres and 5,000 lights by brute force: a sample's rays cost 1 + (1 + 100) and
   * each light 1 + 100 more; a pass takes as many lights as the rest of the budget pays. */
  packed_frame f = {0};
  f.sphere_count = 100;
  f.light_count = 5000;
  f.samples_per_pixel = 4;
  f.reflection_depth = 0;
  rc_gpu_plan p;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 0, 6144, &p), RC_OK);
  CHECK_EQ_INT(p.batch_samples, 1);
  CHECK_EQ_INT(p.light_pass, (6144 - 102) / 101);
  CHECK(102 + (uint64_t)p.light_pass * 101 <= 6144 && 102 + (uint64_t)(p.light_pass + 1) * 101 > 6144);
  /* Two bounces: the rays and each light cost three times as much. */
  f.reflection_depth = 2;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 0, 6144, &p), RC_OK);
  CHECK_EQ_INT(p.light_pass, (6144 - 1 - 3 * 102) / (3 * 101));
  /* A sample that fits keeps its lights together. */
  f.light_count = 3;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 0, 6144, &p), RC_OK);
  CHECK_EQ_INT(p.light_pass, 0);
  /* Rays that alone exceed the budget cannot be split: refused. */
  f.light_count = 5000;
  f.sphere_count = 3000;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 0, 6144, &p), RC_ERR_TOO_LARGE);
  /* Nor can a pixel count more than 2^24 lights' progress in its float. */
  f.sphere_count = 100;
  f.reflection_depth = 0;
  f.samples_per_pixel = 4000;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 0, 6144, &p), RC_ERR_TOO_LARGE);
  /* Through the BVH the estimate is loose: a pass starts with every light. */
  f.samples_per_pixel = 4;
  f.object_count = 100;
  CHECK_EQ_INT(rc_gpu_plan_make(&f, 7, 6144, &p), RC_OK);
  CHECK_EQ_INT(p.batch_samples, 1);
  CHECK_EQ_INT(p.light_pass, 5000);
}

TEST(bvh_plans_from_the_depth_and_never_refuses) {
  packed_frame f = {0};
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
  packed_frame f = {0};
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

/* Limits of a device: its workgroup invocations and height. */
static VkPhysicalDeviceLimits limits(uint32_t invocations, uint32_t height) {
  VkPhysicalDeviceLimits l = {0};
  l.maxComputeWorkGroupInvocations = invocations;
  l.maxComputeWorkGroupSize[0] = l.maxComputeWorkGroupSize[1] = height;
  l.maxComputeWorkGroupSize[2] = 64;
  return l;
}

TEST(workgroup_holds_whole_subgroups_of_every_vendor) {
  /* llvmpipe 4 (128-bit vectors), 8 (AVX2) and 16 (AVX-512); Intel 8 to 32; NVIDIA and
   * Apple 32; AMD 32 or 64; and 128 for a device not yet seen. Vulkan guarantees 128
   * invocations and 128 x 128 x 64; lavapipe and most GPUs offer 1,024. */
  const uint32_t sizes[] = {1, 4, 8, 16, 32, 64, 128};
  const uint32_t invocations[] = {128, 256, 1024};
  for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
    for (size_t j = 0; j < sizeof invocations / sizeof *invocations; j++) {
      VkPhysicalDeviceLimits l = limits(invocations[j], invocations[j] < 128 ? invocations[j] : 128);
      rc_workgroup g = rc_gpu_workgroup(sizes[i], &l);
      uint32_t n = g.x * g.y;
      CHECK_EQ_INT(g.x, 8);
      CHECK(n >= 64);
      CHECK(n <= l.maxComputeWorkGroupInvocations);
      CHECK(g.y <= l.maxComputeWorkGroupSize[1]);
      CHECK_EQ_INT(n % sizes[i], 0); /* whole subgroups: no idle lane */
      /* The largest frame's dispatch stays within the guaranteed 65,535 groups a side. */
      CHECK(RC_MAX_IMAGE_SIDE / g.x <= 65535 && RC_MAX_IMAGE_SIDE / g.y <= 65535);
    }
  }
  /* A device that cannot take the subgroup in one workgroup gets 64. */
  VkPhysicalDeviceLimits small = limits(128, 128);
  rc_workgroup g = rc_gpu_workgroup(256, &small);
  CHECK_EQ_INT(g.x * g.y, 64);
}

TEST(loop_budget_keeps_llvmpipe_under_its_cap_at_every_width) {
  /* llvmpipe counts a loop's iterations per SIMD vector (a subgroup), at most 65,535. */
  for (uint32_t size = 1; size <= 64; size *= 2) {
    uint32_t b = rc_gpu_loop_budget(true, size);
    CHECK((uint64_t)b * size <= 65535);
    CHECK(b * size >= RC_LOOP_BUDGET - size); /* no more lost than the division's remainder */
    CHECK_EQ_INT(rc_gpu_loop_budget(false, size), RC_LOOP_BUDGET);
    /* The showcase's plan (3 spheres + 5 triangles, 3 lights, 1 bounce, BVH depth 4) fits
     * at least one sample into a dispatch at every width, within the budget. */
    packed_frame f = {0};
    f.sphere_count = 3, f.triangle_count = 5, f.object_count = 8, f.light_count = 3;
    f.reflection_depth = 1, f.samples_per_pixel = 4;
    rc_gpu_plan p;
    CHECK_EQ_INT(rc_gpu_plan_make(&f, 4, b, &p), RC_OK);
    CHECK(p.batch_samples >= 1 && p.batch_samples * p.steps_per_sample <= b);
  }
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(steps_per_sample_counts_every_loop);
  RUN(batch_fits_the_budget_and_the_samples);
  RUN(one_sample_over_budget_is_refused);
  RUN(lights_beyond_one_dispatch_go_in_passes_that_fit_the_budget);
  RUN(bvh_plans_from_the_depth_and_never_refuses);
  RUN(bvh_plan_counts_composites_by_their_loaders_steps);
  RUN(workgroup_holds_whole_subgroups_of_every_vendor);
  RUN(loop_budget_keeps_llvmpipe_under_its_cap_at_every_width);
  TEST_MAIN_END
}
