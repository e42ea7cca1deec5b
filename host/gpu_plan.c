#include "gpu_plan.h"

static uint64_t steps_per_sample(const gpu_frame *f, uint64_t prims) {
  uint64_t bounce = 1 + prims + (uint64_t)f->light_count * (1 + prims);
  return 1 + ((uint64_t)f->reflection_depth + 1) * bounce;
}

/* Loop steps of one ray against one object: 1 for a sphere or triangle; a quadric's two
 * clipped pieces and first-end scan; a composite's program with, per operation, a merge
 * of both operands and the copy back (at most 2 RC_CSG_MAX_INTERVALS ends each). */
static uint64_t object_steps(const gpu_frame *f) {
  uint64_t csg = f->csg_count ? f->csg_max_program * (1 + 6ull * RC_CSG_MAX_INTERVALS) : 0;
  uint64_t quadric = f->quadric_count ? 1 + 2 + 4 : 1;
  return csg > quadric ? csg : quadric;
}

uint64_t rc_gpu_plan_steps_per_sample(const gpu_frame *f) {
  return steps_per_sample(f, ((uint64_t)f->sphere_count + f->triangle_count + f->quadric_count + f->csg_count) *
                                 object_steps(f));
}

rc_status rc_gpu_plan_make(const gpu_frame *f, uint32_t bvh_depth, uint32_t budget, rc_gpu_plan *plan) {
  plan->budget = budget;
  plan->steps_per_sample =
      bvh_depth ? steps_per_sample(f, 4ull * bvh_depth + 16 * object_steps(f)) : rc_gpu_plan_steps_per_sample(f);
  uint64_t batch = budget / plan->steps_per_sample;
  if (batch == 0 && bvh_depth) batch = 1;
  if (batch == 0) {
    rc_error("scene too large for brute-force GPU rendering: one sample needs up to %llu loop "
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
