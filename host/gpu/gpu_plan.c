#include "gpu/gpu_plan.h"

static uint64_t steps_per_sample(const gpu_frame *f, uint64_t prims) {
  uint64_t bounce = 1 + prims + (uint64_t)f->light_count * (1 + prims);
  return 1 + ((uint64_t)f->reflection_depth + 1) * bounce;
}

/* Loop steps of one ray against one object, at most: 1 for a sphere or triangle; a
 * quadric's two clipped pieces and its first-end scan; a composite's count from the loader
 * (its program, pieces, merges, copies and scan, from its tree's interval bounds). */
static uint64_t object_steps(const gpu_frame *f) {
  uint64_t csg = f->csg_count ? f->csg_max_steps : 0;
  uint64_t quadric = f->quadric_count ? 1 + 2 + 4 : 1;
  return csg > quadric ? csg : quadric;
}

/* Objects a ray tests through the BVH, as planned: 16, or all of them in a smaller scene
 * (each object is in one leaf, so no ray tests more). */
static uint64_t leaf_tests(const gpu_frame *f) { return f->object_count < 16 ? f->object_count : 16; }

uint64_t rc_gpu_plan_steps_per_sample(const gpu_frame *f) {
  return steps_per_sample(f, ((uint64_t)f->sphere_count + f->triangle_count + f->quadric_count + f->csg_count) *
                                 object_steps(f));
}

rc_status rc_gpu_plan_make(const gpu_frame *f, uint32_t bvh_depth, uint32_t budget, rc_gpu_plan *plan) {
  plan->budget = budget;
  /* Through the BVH: its boxes and leaves, then every infinite plane, one step each (a
   * plane's test has no loop: rc_bvh.glsl, test_planes). */
  plan->steps_per_sample =
      bvh_depth ? steps_per_sample(f, 4ull * bvh_depth + leaf_tests(f) * object_steps(f) + f->plane_count)
                : rc_gpu_plan_steps_per_sample(f);
  uint64_t batch = budget / plan->steps_per_sample;
  if (batch == 0 && bvh_depth) batch = 1;
  if (batch == 0) {
    rc_refuse_scene("scene too large for brute-force GPU rendering: one sample needs up to %llu loop "
             "iterations (%u spheres + %u triangles, %u lights, reflection depth %u), more than the "
             "per-invocation budget of %u that keeps llvmpipe under its 65,535-iteration cap; use "
             "the BVH (--accel bvh), or fewer objects, lights or reflection bounces",
             (unsigned long long)plan->steps_per_sample, f->sphere_count, f->triangle_count,
             f->light_count, f->reflection_depth, budget);
    return RC_ERR_TOO_LARGE;
  }
  if (batch > f->samples_per_pixel) batch = f->samples_per_pixel;
  plan->batch_samples = (uint32_t)batch;
  return RC_OK;
}

uint32_t rc_gpu_loop_budget(bool capped, uint32_t subgroup_size) {
  return capped && subgroup_size > 1 ? RC_LOOP_BUDGET / subgroup_size : RC_LOOP_BUDGET;
}

rc_workgroup rc_gpu_workgroup(uint32_t subgroup_size, const VkPhysicalDeviceLimits *limits) {
  const uint32_t wide = 8, least = 64; /* Vulkan guarantees 128 invocations, 128 x 128 x 64 */
  uint32_t group = subgroup_size > least ? subgroup_size : least;
  if (group > limits->maxComputeWorkGroupInvocations || group / wide > limits->maxComputeWorkGroupSize[1])
    group = least;
  return (rc_workgroup){wide, group / wide};
}
