/* ref_render.h: the CPU reference renderer. It reads the very gpu_* arrays the GPU gets
 * (scene_pack.h; the BVH when rc_bvh_build made one) and runs the shader's functions' C twins, in f64 (the accuracy
 * reference) or f32 (the GPU's arithmetic). Pixels are independent, so the output is
 * bit-identical whatever the thread count. */
#ifndef RC_REF_RENDER_H
#define RC_REF_RENDER_H

#include "base/region.h"
#include "scene/scene_pack.h"

typedef struct rc_ref_options {
  bool f64;
  uint32_t threads; /* 0: all cores */
  /* Flush subnormal inputs and results to zero (x86 FTZ + DAZ, arm64 FZ), as a GPU may in
   * f32 (docs/numerics.md §1): f64 flushes too, at 2^-1022, where no scene reaches. */
  bool flush_subnormals;
} rc_ref_options;

/* Whether this CPU has the mode rc_ref_options.flush_subnormals sets. */
bool rc_ref_can_flush_subnormals(void);

typedef struct rc_ref_stats {
  double render_ms, cpu_ms;
  uint64_t shadow_rays, reflection_rays;
  uint32_t threads;
  /* A ray line crossed a composite's mesh operand more often than its max_crossings, or an
   * odd number of times (rc_quadric.glsl, mesh_intervals): the composite's object number and
   * the pixel; the render then fails with RC_ERR_TOO_LARGE. */
  uint32_t crossing_object, crossing_x, crossing_y;
  /* Newton runs on patch pieces that stayed in their piece, near the ray, without
   * converging (rc_patch.glsl, intersect_patch): rays taken as missing a piece they may
   * hit. With patch_stalls > 0, the first one's object number and pixel. */
  uint64_t patch_stalls;
  uint32_t patch_stall_object, patch_stall_x, patch_stall_y;
  /* --precision certified (frame.certify, rc_certify.glsl): the f32 pass's samples whose
   * decisions were not all certified; rc_ref_rerender's pixels and wall time. */
  uint64_t samples_uncertified, pixels_rerendered, samples_rerendered;
  /* samples_uncertified by where their first uncertified decision lies (RC_UNCERTIFIED_HIT,
   * _SHADOW, _BOUNCE, in that order). */
  uint64_t uncertified_at[3];
  double rerender_ms;
  /* A model of what SIMD lanes lose (issue 48): the loop steps of every sample (lane_steps),
   * and the steps of vectors of 8 neighbouring pixels of a row that run each sample until
   * the slowest lane is done: 8 x the most a lane took, summed over samples and vectors
   * (vector_steps). Their ratio is the share of a vector's steps that do some pixel's work,
   * at best: lanes that diverge inside a sample lose more. */
  uint64_t lane_steps, vector_steps;
} rc_ref_stats;

/* Renders the pixels of `region` (of the full frame) into rgb (its pixels * 3 floats,
 * rows top to bottom) and, if aov is not NULL, the packed_aov records of each pixel's first
 * sample. The stats add up over calls. */
rc_status rc_ref_render(const rc_packed_scene *scene, const rc_ref_options *opts, rc_region region, float *rgb,
                        packed_aov *aov, rc_ref_stats *stats);

/* The second half of --precision certified, after either backend's f32 pass: renders again,
 * in f64, the pixels of `region` whose aov record counts uncertified samples
 * (aov[i].uncertified > 0), replacing their rgb and record (the count stays). */
rc_status rc_ref_rerender(const rc_packed_scene *scene, const rc_ref_options *opts, rc_region region, float *rgb,
                          packed_aov *aov, rc_ref_stats *stats);

/* The frame's cost estimate for cutting shards (region.h): the loop steps (BVH nodes
 * visited, objects tested) of the first sample of the middle pixel of each cell of a grid
 * of at most 256 x 64 cells, in f32 on this thread, plus a fixed cost per pixel. Integer
 * counts of the same arithmetic on every machine, so that every shard of a render cuts
 * the frame alike. grid->cost points into `cost`. */
#define RC_REF_COST_ROWS 256u
#define RC_REF_COST_COLS 64u
#define RC_REF_COST_CELLS (RC_REF_COST_ROWS * RC_REF_COST_COLS)
void rc_ref_cost_grid(const rc_packed_scene *scene, double cost[RC_REF_COST_CELLS], rc_cost_grid *grid);

#endif
