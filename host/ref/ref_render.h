/* ref_render.h: the CPU reference renderer. It reads the very gpu_* arrays the GPU gets
 * (scene_pack.h; the BVH when rc_bvh_build made one) and runs the shader's functions' C twins, in f64 (the accuracy
 * reference) or f32 (the GPU's arithmetic). Pixels are independent, so the output is
 * bit-identical whatever the thread count. */
#ifndef RC_REF_RENDER_H
#define RC_REF_RENDER_H

#include "scene/scene_pack.h"

typedef struct rc_ref_options {
  bool f64;
  uint32_t threads; /* 0: all cores */
} rc_ref_options;

typedef struct rc_ref_stats {
  double render_ms, cpu_ms;
  uint64_t shadow_rays, reflection_rays;
  uint32_t threads;
  /* A ray line crossed a composite's mesh operand more often than its max_crossings, or an
   * odd number of times (rc_quadric.glsl, mesh_intervals): the composite's object number and
   * the pixel; the render then fails with RC_ERR_TOO_LARGE. */
  uint32_t crossing_object, crossing_x, crossing_y;
} rc_ref_stats;

/* Renders into rgb (width * height * 3 floats, rows top to bottom). */
/* Renders rows [y0, y0 + rows) into rgb (rows * width * 3 floats) and, if aov is not
 * NULL, the gpu_aov records of each pixel's first sample (rows * width). The stats add up
 * over calls. */
rc_status rc_ref_render(const rc_packed_scene *scene, const rc_ref_options *opts, uint32_t y0, uint32_t rows,
                        float *rgb, gpu_aov *aov, rc_ref_stats *stats);

#endif
