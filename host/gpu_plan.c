#include "gpu_plan.h"

static uint64_t steps_per_sample(const gpu_frame *f, uint64_t prims) {
  uint64_t bounce = 1 + prims + (uint64_t)f->light_count * (1 + prims);
  return 1 + ((uint64_t)f->reflection_depth + 1) * bounce;
}

uint64_t rc_gpu_plan_steps_per_sample(const gpu_frame *f) {
  return steps_per_sample(f, (uint64_t)f->sphere_count + f->triangle_count);
}

rc_status rc_gpu_plan_make(const gpu_frame *f, uint32_t bvh_depth, uint32_t budget, rc_gpu_plan *plan) {
  plan->budget = budget;
  plan->steps_per_sample = bvh_depth ? steps_per_sample(f, 4ull * bvh_depth + 16) : rc_gpu_plan_steps_per_sample(f);
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
