/* gpu_plan.h: how much work one dispatch may give a pixel. Every shader loop iteration is
 * one step of the per-invocation loop budget (rc_budget.glsl); this module counts the
 * worst-case steps of one sample exactly as the shader's loops are nested, and sizes the
 * sample batch so that a dispatch never exceeds the budget. */
#ifndef RC_GPU_PLAN_H
#define RC_GPU_PLAN_H

#include <vulkan/vulkan.h>

#include "base/rc_base.h"
#include "rc_shared.h"

typedef struct rc_gpu_plan {
  uint64_t steps_per_sample; /* worst case over all pixels */
  uint32_t batch_samples;    /* samples per pixel per dispatch */
  uint32_t light_pass;       /* 0: a sample's lights in one dispatch (accum.a counts samples);
                              * else lights per pass to start with (accum.a counts lights) */
  uint32_t budget;           /* the budget the plan was made for */
  bool uncountable;          /* a sample over the budget whose lights still go in one dispatch:
                              * samples x lights is more than a pixel's progress counts */
} rc_gpu_plan;

/* Light passes count a pixel's progress in lights in a float (accum.a), exact to 2^24. */
#define RC_LIGHT_PASS_UNITS (1u << 24)

/* Worst-case loop steps of one sample by brute force, with N the objects' steps (1 per
 * sphere or triangle; a quadric's clipped pieces and scan; a composite's count from the
 * loader: gpu_plan.c, object_steps):
 *   1 (sample loop) + (depth + 1) * [1 (bounce loop) + N (closest hit)
 *                                   + L * (1 (light loop) + N (shadow ray))]. */
uint64_t rc_gpu_plan_steps_per_sample(const packed_frame *frame);

/* Brute force (bvh_depth 0): the exact worst case.
 * Where one sample exceeds the budget, its lights are split into passes: each dispatch
 * traces one sample's rays again and shades with the next `light_pass` lights, as many as
 * the budget pays for after the rays themselves, so that any number of lights the CPU
 * renders the GPU renders too. Fails with RC_ERR_TOO_LARGE, the message naming the numbers,
 * only where the rays of one sample with one light exceed the budget (brute force over
 * too many objects) or a pixel could not count its passes.
 * BVH (bvh_depth = tree depth): no useful worst case exists, so the batch comes from an
 * estimate of a traversal's steps, 4 x depth node visits + 2 leaves of 8 objects, and the
 * shader's exhaustion flag catches what the estimate misses (the batch is halved and the
 * work repeated, then the lights of a sample halved into passes; one sample with one light
 * over the budget is an error, never a wrong image). Where the estimate puts one sample
 * over the budget, the pipeline counts light passes, starting with all of a sample's
 * lights in one. */
rc_status rc_gpu_plan_make(const packed_frame *frame, uint32_t bvh_depth, uint32_t budget, rc_gpu_plan *plan);

/* The per-invocation loop budget on a device. llvmpipe (`capped`) caps the loop
 * iterations of one SIMD vector, a subgroup of invocations run as lanes, at 65,535; with
 * divergent nested loops the vector runs the union of its lanes' iterations, so only
 * lanes x the per-lane count bounds it: RC_LOOP_BUDGET / subgroup size there. Other
 * drivers have no such cap (docs/porting.md). */
uint32_t rc_gpu_loop_budget(bool capped, uint32_t subgroup_size);

/* The workgroup: 8 invocations wide (8 x 8 pixels share their rays' coherence) and
 * max(64, subgroup size) in all, so that it holds whole subgroups (NVIDIA 32, AMD 64 or
 * 32, Intel 8 to 32, Apple 32, llvmpipe 4 to 16) and no lane idles for want of a full one;
 * 64 where the device's limits cannot take that many. */
typedef struct rc_workgroup {
  uint32_t x, y;
} rc_workgroup;
rc_workgroup rc_gpu_workgroup(uint32_t subgroup_size, const VkPhysicalDeviceLimits *limits);

#endif
