/* gpu_render.h: the GPU renderer: pipeline, descriptors, scene upload, tiled dispatch
 * under the loop budget, timestamps and readback. The objects are created once and can
 * render several frames (--repeat). */
#ifndef RC_GPU_RENDER_H
#define RC_GPU_RENDER_H

#include "gpu/gpu_plan.h"
#include "base/region.h"
#include "scene/scene_pack.h"
#include "gpu/gpu_shaders.h"
#include "gpu/vk_buffer.h"

typedef struct rc_gpu_options {
  rc_scene_buffers scene_buffers;
  bool force_staging;   /* upload and read back through staging buffers even if mappable */
  uint32_t tile_size;   /* fixed tiles of this side; 0: tiles from tile_budget_ms (gpu_tiles.h) */
  double tile_budget_ms;  /* the longest a dispatch (one submit) should run: real GPUs reset
                             after ~2 s (Windows TDR) or kill long dispatches. Negative: the
                             device's default (none on a CPU device, else
                             RC_DEFAULT_TILE_BUDGET_MS); 0: no limit */
  uint32_t plan_budget; /* 0: the device's budget (rc_gpu_loop_budget); larger values only in
                           tests, to make the shader's exhaustion flag fire */
  bool progress;        /* tiles done on stderr */
  bool f64;             /* the f64 shader module (the device must have shaderFloat64) */
  bool aov;             /* record the decision outputs (packed_aov) of each pixel's first sample */
  uint32_t bvh_depth;   /* 0: brute force (no BVH in the scene); else traverse the BVH */
  bool generic_pipeline; /* one pipeline for every scene (all primitive kinds, light count,
                            shadows, specular model and bounces read from the frame), to
                            measure what specializing to the scene buys */
  bool driver_spec_constants; /* the driver applies the specialization constants, not the
                                 host's SPIR-V optimizer (spirv_specialize.h) */
  rc_region region;     /* the pixels to render (region.h); all zero: the whole frame */
  /* NULL: the host reads each pixel's sums back and divides (bands of float RGB). Else
   * the output file's encoding (rc_shared.h): the shader encodes each pixel into its
   * 8-bit levels as it completes, and the host reads 4 bytes a pixel instead of 16
   * (bands of levels). Not with aov, nor for a re-render. */
  const packed_levels *levels;
  uint32_t level_curve; /* with levels: RC_LEVEL_CURVE_*, a specialization constant */
} rc_gpu_options;

#define RC_DEFAULT_TILE_BUDGET_MS 100.0

typedef struct rc_gpu_stats {
  double upload_ms;    /* scene buffers, wall */
  double pipeline_ms;  /* shader module + pipeline creation, wall */
  bool pipeline_cache_hit; /* a valid pipeline cache file was loaded (gpu_pipeline_cache.h) */
  bool host_specialized;   /* the module the driver got had its constants applied by the host */
  bool spec_cache_hit;     /* ... read from its file on disk (spirv_cache.h) */
  double specialize_ms;    /* that, wall (part of pipeline_ms) */
  double gpu_ms;       /* sum of dispatch times from timestamp queries (wall if none) */
  double render_ms;    /* the whole frame, wall: dispatches, waits, readback */
  double readback_ms;  /* accumulation buffer to the host image, wall */
  /* Bytes moved between host and device: the scene arrays and the frame, once per
   * renderer; per frame, what the host reads back (each dispatch's status, each tile's
   * accumulated sums, 16 bytes a pixel, or its 8-bit levels, 4, and AOV records, 64). */
  uint64_t upload_bytes, readback_bytes;
  uint64_t shadow_rays, reflection_rays;
  uint64_t uncertified_at[3]; /* as rc_ref_stats.uncertified_at (ref_render.h), from the f32 pass */
  uint32_t dispatches, tiles;
  /* Submits made only to copy a tile out of device memory after its last dispatch (staging,
   * where that dispatch could not copy it itself: light passes, or a batch grown past its
   * plan); 0 where the host reads the buffers directly. */
  uint32_t readback_submits;
  /* Tiles the host read out of their staging slot while the next tile's first dispatch ran
   * on the device (the others: the frame's last, and tiles read directly). */
  uint32_t readback_overlapped;
  /* Bands handed to the band function while the next band's first dispatch ran on the
   * device (all but the last, unless a re-render left a band without a dispatch), and the
   * wall time spent in the band function then; of that, what the device's work ran beside:
   * each such band's time up to its dispatch's (timestamps; without them the wall time the
   * host waited after the band, which can only say less). */
  uint32_t bands_overlapped;
  double band_overlapped_ms, band_hidden_ms;
  double tile_budget_ms;   /* the budget in force: 0 where none limits a dispatch */
  double max_dispatch_ms;  /* the longest dispatch (GPU timestamps) */
  uint32_t over_budget;    /* dispatches longer than tile_budget_ms */
  uint32_t budget_retries; /* dispatches repeated with a smaller batch after exhaustion */
  bool budget_refused;     /* a single sample ran out of the loop budget: nothing written */
  uint32_t budget_pixels;  /* then: the pixels of the dispatch that ran out */
  uint32_t budget_object;  /* an object a ray was testing then (UINT32_MAX: unknown) */
  uint32_t budget_x, budget_y; /* and that ray's pixel */
  uint32_t crossing_object;    /* UINT32_MAX, or as rc_ref_stats.crossing_object (ref_render.h) */
  uint32_t crossing_x, crossing_y;
  uint64_t patch_stalls;       /* as rc_ref_stats.patch_stalls (ref_render.h) */
  uint32_t patch_stall_object, patch_stall_x, patch_stall_y;
  rc_gpu_plan plan;
  uint32_t batch_samples_end; /* samples per dispatch in the end: the plan's, grown from the
                                 shader's measured steps or halved where a batch ran out */
  uint32_t lights_per_pass; /* 0: each sample's lights in one dispatch; else the passes' size
                               in the end (plan.light_pass, halved where the shader ran out) */
  uint32_t loop_budget;    /* the shader's per-invocation budget on this device */
  uint32_t subgroup_size;
  uint32_t workgroup_x, workgroup_y; /* invocations per workgroup, chosen from the subgroup size */
  bool staging;            /* uploads and readback went through staging buffers */
  bool encoded;            /* the shader encoded the pixels into 8-bit levels (opts.levels) */
  bool readback_cached;    /* the memory the host reads the pixels from is HOST_CACHED (reads
                              from write-combined memory are slow) */
  uint32_t memory_blocks;  /* device memory allocations (vk_memory.h) after set-up */
  uint64_t memory_bytes;   /* and their bytes */
  rc_scene_buffers scene_buffers;
} rc_gpu_stats;

typedef struct rc_gpu_renderer rc_gpu_renderer;

rc_status rc_gpu_renderer_create(rc_vk_ctx *ctx, const rc_packed_scene *scene, const rc_gpu_options *opts,
                                 rc_gpu_renderer **out, rc_gpu_stats *stats);
/* Receives the region's pixels in bands of rows, top to bottom: rgb (rows * width * 3
 * floats, width the region's) or, from a renderer with opts.levels, levels (rows *
 * width * 3 bytes) and a NULL rgb; when the renderer records AOVs, aov (rows * width
 * records), NULL otherwise. y0 counts from the region's first row. */
typedef rc_status (*rc_band_fn)(uint32_t y0, uint32_t rows, const float *rgb, const uint8_t *levels,
                                const packed_aov *aov, void *user);

/* Renders one frame, band by band: host memory is one band, whatever the image size. */
rc_status rc_gpu_renderer_render(rc_gpu_renderer *r, rc_band_fn band, void *user, rc_gpu_stats *stats);

/* Certified mode's re-render in f64 on the GPU (r made with opts.f64 and opts.aov): renders
 * `region` (rows of the renderer's region, its full width) tracing only the pixels whose
 * record in `mask` (one per pixel of `region`, row by row) counts uncertified samples;
 * `band` gets the others black, or, in a tile with no such pixel (not dispatched), unset. */
rc_status rc_gpu_renderer_rerender(rc_gpu_renderer *r, rc_region region, const packed_aov *mask, rc_band_fn band,
                                   void *user, rc_gpu_stats *stats);
void rc_gpu_renderer_destroy(rc_gpu_renderer *r);

#endif
