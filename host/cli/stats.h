/* stats.h: what a render reports: the human summary on stderr and --stats-json. */
#ifndef RC_STATS_H
#define RC_STATS_H

#include "scene/bvh.h"
#include "scene/light_buffer.h"
#include "gpu/gpu_render.h"
#include "scene/scene.h"

typedef struct rc_render_stats {
  const char *version;   /* "0.1.0 (git abc123)" */
  const char *scene;     /* the scene file as given ("<stdin>" for -) */
  const char *device, *device_type, *driver;
  const char *backend;   /* "gpu" or "cpu" */
  const char *precision; /* "f32" or "f64": what ran */
  const char *precision_requested; /* "auto", "f32" or "f64" */
  const char *sphere_formula, *triangle_formula, *shadow_offset;
  bool camera_relative;
  double packing_scale; /* packed units per scene unit (scene_pack.h) */
  uint32_t budget_needs_f64, budget_quantized; /* precision-budget findings (precision_budget.h) */
  double budget_ms;
  uint32_t threads;      /* cpu backend */
  double simd8_efficiency; /* cpu backend: lane_steps / vector_steps (rc_ref_stats) */
  uint32_t width, height, samples_per_pixel; /* the frame's */
  rc_region region;                          /* the pixels rendered (--region, --shard) */
  uint32_t shard_index, shard_count;         /* count 0: no --shard */
  double part_ms;                            /* choosing them (the shard cost estimate) */
  size_t spheres, triangles, lights, quadrics, planes, composites, materials;
  bool shadows;
  bool generic_pipeline;
  const char *prepared; /* the prepared scene rendered (render --prepared, or a .vkrs scene); NULL: parsed */
  double parse_ms, write_ms;
  double first_frame_ms; /* includes the JIT on lavapipe */
  double render_ms;      /* GPU time of one frame: the first, or the median of the others with --repeat */
  double render_wall_ms; /* wall time of that frame, including waits and readback */
  double cpu_ms;         /* process CPU time, whole run */
  uint32_t repeat;
  uint64_t rays_primary, rays_shadow, rays_reflection;
  /* Patch rays Newton's method did not settle (rc_ref_stats.patch_stalls): taken as misses. */
  uint64_t patch_unconverged;
  uint32_t patch_stall_object, patch_stall_x, patch_stall_y;
  rc_gpu_stats gpu;
  rc_bvh_stats bvh; /* zero with --accel none */
  rc_light_buffer_stats light_buffers; /* zero without them (--light-buffers off, no point light, ...) */
  /* --precision certified (rc_certify.glsl): samples whose decisions were not all certified,
   * the pixels rendered again in f64 for them ("cpu": the CPU reference; "none": left as
   * traced) and the samples traced in them (the uncertified ones, or all of a pixel's
   * where its record cannot name them: base/certified_marks.h), and the wall time of
   * those re-renders. */
  uint64_t samples_uncertified, pixels_rerendered, samples_rerendered;
  /* samples_uncertified by where on its path a sample's first uncertified decision lies:
   * the primary hit, its shadow rays, the mirror bounces (RC_UNCERTIFIED_*). */
  uint64_t uncertified_at[3];
  const char *rerender;
  double rerender_ms;
} rc_render_stats;

/* What the statistics say about the scene itself: the frame, the counts of each kind, the
 * quality settings (after the command line's overrides). */
void rc_stats_describe_scene(rc_render_stats *s, const rc_scene *scene);

double rc_stats_mrays_per_s(const rc_render_stats *s);
void rc_stats_print(const rc_render_stats *s);
/* The statistics as one JSON object and a newline (malloc'd; NULL when out of memory). */
char *rc_stats_json(const rc_render_stats *s);

#endif
