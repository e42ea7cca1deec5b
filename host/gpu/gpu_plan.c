#include "gpu/gpu_plan.h"

#include "scene/bvh.h"

/* Loop steps of one sample whose rays cost `ray` steps each, shading `lights` lights:
 * 1 (sample loop) + (depth + 1) x [1 (bounce) + ray + lights x (1 (light) + ray)]. With
 * every light it is the whole sample; with fewer, one light pass (gpu_plan.h). */
static uint64_t pass_steps(const packed_frame *f, uint64_t ray, uint64_t lights) {
  return 1 + ((uint64_t)f->reflection_depth + 1) * (1 + ray + lights * (1 + ray));
}

/* Loop steps of one ray against one object, at most: 1 for a sphere or triangle; a
 * quadric's two clipped pieces and its first-end scan, or, in a scene with patches, a
 * piece's Newton steps; a composite's count from the loader (its program, pieces, merges,
 * copies and scan, from its tree's interval bounds), twice where it is certified. */
static uint64_t object_steps(const packed_frame *f) {
  uint64_t csg = f->csg_count ? f->csg_max_steps : 0;
  /* Certified mode runs a composite's program twice: the test, then its certificate's copy
   * (rc_certify_csg.glsl), whose loops step the same budget. */
  if (f->certify != RC_CERTIFY_OFF) csg *= 2;
  uint64_t quadric = f->quadric_count ? 1 + 2 + 4 : 1;
  /* Certified, a piece's certificate runs its Newton steps and the test takes that run
   * (rc_certify_patch.glsl): once either way; the certificate then follows the reference's
   * last steps, six at most (patch_settles), a step each. */
  uint64_t patch = 1 + RC_PATCH_NEWTON_STEPS + (f->certify != RC_CERTIFY_OFF ? 6 : 0);
  if (f->patch_count && quadric < patch) quadric = patch;
  return csg > quadric ? csg : quadric;
}

/* Objects a ray tests through the BVH, as planned: 16, or all of them in a smaller scene
 * (each object is in one leaf, so no ray tests more). */
static uint64_t leaf_tests(const packed_frame *f) { return f->object_count < 16 ? f->object_count : 16; }

uint64_t rc_gpu_plan_steps_per_sample(const packed_frame *f) {
  return pass_steps(f, ((uint64_t)f->sphere_count + f->triangle_count + f->quadric_count + f->csg_count) *
                           object_steps(f),
                    f->light_count);
}

rc_status rc_gpu_plan_make(const packed_frame *f, uint32_t bvh_depth, uint32_t budget, rc_gpu_plan *plan) {
  plan->budget = budget;
  plan->light_pass = 0;
  plan->uncountable = false;
  /* Through the BVH: the loose objects, its boxes and leaves, then every infinite plane, one
   * step each (a plane's test has no loop: rc_bvh.glsl, test_planes). */
  uint64_t objects = (uint64_t)f->sphere_count + f->triangle_count + f->quadric_count + f->csg_count;
  uint64_t ray = bvh_depth ? 4ull * bvh_depth + ((uint64_t)leaf_tests(f) + rc_loose_objects(f)) * object_steps(f) +
                                 f->plane_count
                           : objects * object_steps(f);
  plan->steps_per_sample = pass_steps(f, ray, f->light_count);
  uint64_t batch = budget / plan->steps_per_sample;
  if (batch > 0) {
    /* The whole sample fits: its lights in one dispatch. */
    plan->batch_samples = (uint32_t)(batch > f->samples_per_pixel ? f->samples_per_pixel : batch);
    return RC_OK;
  }
  /* One sample is over the budget. Its lights are the work that splits: a pass re-traces
   * the sample's rays (the same rays, bit for bit) and shades with the next lights. A
   * pixel's progress then counts lights (accum.a = sample x lights + lights done), exact in
   * a float up to 2^24. */
  plan->batch_samples = 1;
  uint64_t path = pass_steps(f, ray, 0), per_light = pass_steps(f, ray, 1) - path;
  uint64_t units = (uint64_t)f->samples_per_pixel * f->light_count;
  bool countable = f->light_count > 0 && units <= RC_LIGHT_PASS_UNITS;
  if (bvh_depth) {
    /* The BVH's estimate is loose: a pass starts with every light and halves where the
     * shader finds it over the budget (gpu_render.c, render_tile). Where the passes cannot
     * be counted the sample is tried whole, and a refusal names the count (cmd_render.c). */
    plan->light_pass = countable ? f->light_count : 0;
    plan->uncountable = f->light_count > 0 && !countable;
    return RC_OK;
  }
  uint64_t lights = budget > path ? (budget - path) / per_light : 0;
  if (lights == 0) {
    rc_refuse_scene("scene too large for brute-force GPU rendering: the rays of one sample with %s need up to %llu "
                    "loop iterations (%llu objects: %u spheres, %u triangles, %u quadrics, %u composites; reflection "
                    "depth %u), more than the per-invocation budget of %u that keeps llvmpipe under its "
                    "65,535-iteration cap; use the BVH (--accel bvh), or fewer objects or reflection bounces",
                    f->light_count ? "one light" : "no light",
                    (unsigned long long)(f->light_count ? path + per_light : path), (unsigned long long)objects,
                    f->sphere_count, f->triangle_count, f->quadric_count, f->csg_count, f->reflection_depth, budget);
    return RC_ERR_TOO_LARGE;
  }
  if (!countable) {
    rc_refuse_scene("scene too large for brute-force GPU rendering: one sample with its %u lights needs up to %llu "
                    "loop iterations, over the per-invocation budget of %u, so its lights would be shaded in passes "
                    "of %llu; but %u samples x %u lights is more than the 16,777,216 a pixel can count; use fewer "
                    "samples per pixel or lights, the BVH (--accel bvh), or --backend cpu",
                    f->light_count, (unsigned long long)plan->steps_per_sample, budget, (unsigned long long)lights,
                    f->samples_per_pixel, f->light_count);
    return RC_ERR_TOO_LARGE;
  }
  plan->light_pass = (uint32_t)lights;
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
