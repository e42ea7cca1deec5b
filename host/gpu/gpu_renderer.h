/* gpu_renderer.h: the GPU renderer's own state, shared by the files that build it
 * (gpu_upload.c: the scene arrays; gpu_pipeline.c: pipeline and descriptors) and the one
 * that runs it (gpu_render.c: tiles, dispatches, readback). Not for use outside gpu/. */
#ifndef RC_GPU_RENDERER_H
#define RC_GPU_RENDERER_H

#include "gpu/gpu_render.h"

#define SCENE_ARRAYS 12 /* spheres, triangles, materials, lights, BVH nodes, BVH references, transforms, normals,
                           quadrics, composites, CSG programs, textures (and triangles' texture coordinates) */

struct rc_gpu_renderer {
  rc_vk_ctx *ctx;
  rc_gpu_options opts;
  uint32_t budget; /* the shader's per-invocation loop budget (spec constant) */
  bool light_passes;   /* RC_SPEC_LIGHT_PASSES: samples too long for one dispatch */
  uint32_t light_pass; /* then: lights per pass, halved where a pass ran out (for later tiles too) */
  uint32_t batch_samples; /* samples per dispatch: the plan's, then grown from the shader's
                             measured steps and halved where a batch ran out (for later tiles
                             and frames too) */
  packed_frame frame;
  rc_region region; /* the pixels rendered, within the frame */
  bool mesh_operands; /* a composite has a mesh operand (RC_KIND_CSG_MESHES) */
  bool sphere_transforms, vertex_normals; /* RC_KIND_SPHERE_TRANSFORMS, RC_KIND_VERTEX_NORMALS */
  bool one_sided_triangles;               /* RC_KIND_ONE_SIDED_TRIANGLES */
  bool textures;                          /* RC_KIND_TEXTURES */
  bool patches;                           /* RC_KIND_PATCHES */
  uint64_t upload_bytes;                  /* the scene arrays and the frame, as uploaded */
  rc_buffer frame_buf;
  rc_buffer arrays[SCENE_ARRAYS];
  VkBufferView views[SCENE_ARRAYS];
  uint32_t local_x, local_y; /* workgroup shape (spec constants 0 and 1) */
  double tile_budget_ms;     /* resolved: 0 where no watchdog limits a dispatch */
  /* Staging: two readback slots each, so that the host can read one tile out of one while
   * the next tile's dispatch copies into the other (`pending`). The second is made when a
   * frame first has two tiles. */
  rc_buffer accum, accum_readback[2];
  rc_buffer status, status_readback;
  /* The AOV records; with opts.levels the encoding and the tile's levels instead
   * (RC_BINDING_AOV); else a 32-byte placeholder. */
  rc_buffer aov, aov_readback[2];
  float *band_rgb;             /* one band of rows on the host (NULL with opts.levels) */
  uint8_t *band_levels;        /* with opts.levels: the band as 8-bit levels, 3 a pixel */
  packed_aov *band_aov;
  /* rc_gpu_renderer_rerender: the records that mark the pixels to trace, a row of the
   * region's width each from the region's top; NULL otherwise. The tile's records reach
   * the AOV buffer directly where it is mapped, else through mask_upload. */
  const packed_aov *mask;
  rc_buffer mask_upload;
  VkDescriptorSetLayout set_layout;
  VkPipelineLayout pipeline_layout;
  VkPipeline pipeline;
  VkDescriptorPool descriptor_pool;
  VkDescriptorSet set;
  VkQueryPool queries;
  VkCommandPool pool; /* holds `cmd` alone: reset as a whole before each recording */
  VkCommandBuffer cmd;
  VkFence fence;
  bool staging;
  /* Staging: the last dispatch recorded also copied the tile's pixels (and AOV records) into
   * the readback buffers, so that read_tile needs no submit of its own. */
  bool tile_copied;
  uint32_t slot; /* the readback slot the next tile's copy goes to */
  /* A tile copied out into its slot whose pixels the host has not read yet: read while the
   * next tile's first dispatch runs on the device (render_tile), the next band's included,
   * or at the frame's end. */
  struct {
    bool valid;
    uint32_t x0, tw, th, slot;
  } pending;
  /* A band whose tiles are all rendered, handed to `band` while the next band's first
   * dispatch runs (its last tile, pending, read first), or at the frame's end. */
  struct {
    bool valid;
    uint32_t y0, rows;
  } band_done;
  rc_band_fn band;
  void *band_user;
};

/* The binding of scene array i (rc_shared.h, RC_BINDING_*), in upload order. */
extern const uint32_t rc_gpu_array_bindings[SCENE_ARRAYS];

/* The descriptor type of the scene arrays as buffers of `kind`, and whether they are read
 * through texel views (gpu_upload.c). */
VkDescriptorType rc_gpu_kind_descriptor(rc_scene_buffers kind);
bool rc_gpu_is_texel_kind(rc_scene_buffers kind);

/* Chooses the buffer kind the device can take (r->opts.scene_buffers, changed where the
 * asked-for kind does not fit), checks the whole render against the device-local heap
 * with tiles of `tile_pixels`, and uploads the scene arrays and the frame (gpu_upload.c). */
rc_status rc_gpu_upload_scene(rc_gpu_renderer *r, const rc_packed_scene *s, uint64_t tile_pixels);

/* The descriptor set layout, the pipeline layout and the compute pipeline specialized to
 * the scene (*cache_hit: a pipeline cache file was loaded); then the descriptor set that
 * binds the uploaded arrays and the output buffers (gpu_pipeline.c). */
rc_status rc_gpu_create_pipeline(rc_gpu_renderer *r, rc_gpu_stats *stats);
rc_status rc_gpu_create_descriptors(rc_gpu_renderer *r);

#endif
