#include "gpu/gpu_renderer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gpu/gpu_tiles.h"

/* The tile buffers hold this many pixels: no tile exceeds it. */
#define MAX_TILE_PIXELS (1u << 20)

/* Within what every Vulkan device offers, so no device can refuse them (docs/porting.md). */
_Static_assert(sizeof(packed_frame) <= 16384, "packed_frame must fit the guaranteed maxUniformBufferRange");
_Static_assert(sizeof(packed_push) <= 128, "packed_push must fit the guaranteed maxPushConstantsSize");

/* The tile buffers' capacity in pixels: no tile is larger, nor larger than the region. */
static uint32_t max_tile_pixels(const rc_gpu_renderer *r) {
  uint64_t cap = r->opts.tile_size ? (uint64_t)r->opts.tile_size * r->opts.tile_size : MAX_TILE_PIXELS;
  uint64_t region = (uint64_t)rc_region_width(r->region) * rc_region_height(r->region);
  return (uint32_t)(region < cap ? region : cap);
}

static void planner_init(const rc_gpu_renderer *r, rc_tile_planner *p) {
  rc_tiles_init(p, rc_region_width(r->region), rc_region_height(r->region), r->opts.tile_size, r->tile_budget_ms,
                max_tile_pixels(r));
}

static uint32_t max_band_rows(const rc_gpu_renderer *r) {
  rc_tile_planner p;
  planner_init(r, &p);
  return rc_tiles_max_band_rows(&p);
}

/* The time limit of one dispatch: the user's --tile-budget-ms on any device; by default
 * none on a CPU device (lavapipe: no watchdog resets it, and every dispatch has a fixed
 * cost), RC_DEFAULT_TILE_BUDGET_MS elsewhere (Windows resets a GPU after 2 s, Linux
 * drivers kill long dispatches). */
static double resolve_tile_budget(const rc_vk_ctx *ctx, double wanted_ms) {
  if (wanted_ms >= 0) return wanted_ms;
  return ctx->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 0.0 : RC_DEFAULT_TILE_BUDGET_MS;
}


/* Where the levels of a tile's pixels start in the AOV buffer (opts.levels): after the
 * encoding. */
#define LEVELS_OFFSET ((VkDeviceSize)sizeof(packed_levels))

/* The buffer the shader leaves a tile's pixels in (their levels from LEVELS_OFFSET, or
 * their sums), and the one the host reads them from: the same where it is mapped, else
 * its staging twin. */
static const rc_buffer *pixel_buffer(const rc_gpu_renderer *r) { return r->opts.levels ? &r->aov : &r->accum; }
static const rc_buffer *pixel_readback(const rc_gpu_renderer *r, uint32_t slot) {
  if (!r->staging) return pixel_buffer(r);
  return r->opts.levels ? &r->aov_readback[slot] : &r->accum_readback[slot];
}

/* The tile's readback buffers of one slot (staging), as large as the device buffers they
 * copy. */
static rc_status create_readback_slot(rc_gpu_renderer *r, uint32_t slot) {
  rc_status st = rc_buffer_create(r->ctx, r->accum.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, RC_MEM_READBACK,
                                  &r->accum_readback[slot]);
  if (st == RC_OK)
    st = rc_buffer_create(r->ctx, r->aov.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, RC_MEM_READBACK,
                          &r->aov_readback[slot]);
  return st;
}

/* The per-tile accumulation buffer and the status counters, with readback copies when
 * they are not mapped directly. */
static rc_status create_outputs(rc_gpu_renderer *r) {
  rc_vk_ctx *ctx = r->ctx;
  VkDeviceSize tile_pixels = max_tile_pixels(r);
  VkDeviceSize accum_size = tile_pixels * 16;
  VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                             VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkDeviceSize aov_size = r->opts.levels ? LEVELS_OFFSET + tile_pixels * sizeof(uint32_t)
                          : r->opts.aov  ? tile_pixels * sizeof(packed_aov)
                                         : sizeof(packed_aov);
  size_t band = (size_t)rc_region_width(r->region) * max_band_rows(r);
  RC_ASSERT(!(r->opts.levels && r->opts.aov));
  if (r->opts.levels) r->band_levels = rc_alloc(band * 3, 1, "one band of the image");
  else r->band_rgb = rc_alloc(band * 3, sizeof(float), "one band of the image");
  r->band_aov = r->opts.aov ? rc_alloc(band, sizeof(packed_aov), "one band of AOVs") : NULL;
  if (!(r->band_rgb || r->band_levels) || (r->opts.aov && !r->band_aov)) return RC_ERR_OUT_OF_MEMORY;
  rc_status st = rc_buffer_create(ctx, accum_size, usage, RC_MEM_DEVICE, &r->accum);
  if (st == RC_OK) st = rc_buffer_create(ctx, sizeof(packed_status), usage, RC_MEM_DEVICE, &r->status);
  if (st == RC_OK) st = rc_buffer_create(ctx, aov_size, usage, RC_MEM_DEVICE, &r->aov);
  if (st != RC_OK) return st;
  r->staging = !rc_buffer_is_direct(&r->accum, r->opts.force_staging) ||
               !rc_buffer_is_direct(&r->status, r->opts.force_staging);
  if (r->staging) {
    st = create_readback_slot(r, 0);
    if (st == RC_OK)
      st = rc_buffer_create(ctx, sizeof(packed_status), VK_BUFFER_USAGE_TRANSFER_DST_BIT, RC_MEM_READBACK,
                            &r->status_readback);
  }
  if (st == RC_OK && r->opts.levels)
    st = rc_buffer_upload(ctx, &r->aov, r->opts.levels, sizeof *r->opts.levels, r->opts.force_staging);
  return st;
}


/* The timestamp queries, the command pool and buffer, and the fence of the dispatches. */
static rc_status create_commands(rc_gpu_renderer *r) {
  rc_vk_ctx *ctx = r->ctx;
  VkQueryPoolCreateInfo qi = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                              .queryType = VK_QUERY_TYPE_TIMESTAMP,
                              .queryCount = 2};
  if (ctx->timestamp_bits) RC_VK_TRY(vkCreateQueryPool(ctx->device, &qi, NULL, &r->queries));
  VkCommandPoolCreateInfo pci = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
                                  .queueFamilyIndex = ctx->queue_family};
  RC_VK_TRY(vkCreateCommandPool(ctx->device, &pci, NULL, &r->pool));
  VkCommandBufferAllocateInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                    .commandPool = r->pool,
                                    .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                    .commandBufferCount = 1};
  RC_VK_TRY(vkAllocateCommandBuffers(ctx->device, &ci, &r->cmd));
  VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  RC_VK_TRY(vkCreateFence(ctx->device, &fi, NULL, &r->fence));
  return RC_OK;
}


static rc_status warm_up(rc_gpu_renderer *r);

rc_status rc_gpu_renderer_create(rc_vk_ctx *ctx, const rc_packed_scene *scene, const rc_gpu_options *opts,
                                 rc_gpu_renderer **out, rc_gpu_stats *stats) {
  *out = NULL;
  stats->crossing_object = UINT32_MAX; /* a refusal while setting up is no crossing */
  rc_gpu_renderer *r = calloc(1, sizeof *r);
  if (!r) return RC_ERR_VULKAN;
  r->ctx = ctx;
  r->opts = *opts;
  r->frame = scene->frame;
  r->region = opts->region;
  if (r->region.x1 == 0) r->region = (rc_region){0, 0, r->frame.camera.width, r->frame.camera.height};
  RC_ASSERT(r->region.x1 <= r->frame.camera.width && r->region.y1 <= r->frame.camera.height);
  r->mesh_operands = scene->mesh_operand_count > 0;
  r->sphere_transforms = scene->transform_count > 0;
  r->vertex_normals = scene->normal_count > 0;
  r->one_sided_triangles = scene->one_sided_triangle_count > 0;
  r->textures = scene->texture_count > 0;
  r->patches = scene->frame.patch_count > 0;
  /* The shader's budget is the device's, or a smaller --plan-budget: the BVH's light passes
   * halve where the shader runs out, so a test can make them on a device without
   * llvmpipe's cap too. A larger --plan-budget misleads only the plan. */
  r->budget = rc_gpu_loop_budget(ctx->llvmpipe, ctx->subgroup_size);
  if (opts->plan_budget && opts->plan_budget < r->budget) r->budget = opts->plan_budget;
  r->tile_budget_ms = resolve_tile_budget(ctx, opts->tile_budget_ms);
  stats->tile_budget_ms = r->tile_budget_ms;
  stats->loop_budget = r->budget;
  stats->subgroup_size = ctx->subgroup_size;
  rc_workgroup group = rc_gpu_workgroup(ctx->subgroup_size, &ctx->props.limits);
  r->local_x = group.x;
  r->local_y = group.y;
  stats->workgroup_x = r->local_x;
  stats->workgroup_y = r->local_y;
  rc_status st = rc_gpu_plan_make(&scene->frame, opts->bvh_depth, opts->plan_budget ? opts->plan_budget : r->budget,
                                  &stats->plan);
  r->light_passes = stats->plan.light_pass != 0;
  r->light_pass = stats->plan.light_pass;
  r->batch_samples = stats->plan.batch_samples;
  if (st == RC_OK && opts->f64 && !ctx->float64) {
    rc_error("--precision f64: device %u (%s) does not support shaderFloat64 and shaderInt64; use f32, or "
             "--backend cpu for an f64 render",
             ctx->device_index, ctx->props.deviceName);
    st = RC_ERR_DEVICE;
  }
  double t0 = rc_now_ms();
  if (st == RC_OK) st = rc_gpu_upload_scene(r, scene, max_tile_pixels(r));
  double t1 = rc_now_ms();
  if (st == RC_OK) st = create_outputs(r);
  if (st == RC_OK) st = rc_gpu_create_pipeline(r, stats);
  double t2 = rc_now_ms();
  if (st == RC_OK) st = rc_gpu_create_descriptors(r);
  if (st == RC_OK) st = create_commands(r);
  double t3 = rc_now_ms();
  if (st == RC_OK && r->tile_budget_ms > 0) st = warm_up(r);
  stats->upload_ms = t1 - t0;
  stats->upload_bytes = r->upload_bytes;
  stats->pipeline_ms = (t2 - t1) + (rc_now_ms() - t3);
  stats->scene_buffers = r->opts.scene_buffers;
  stats->staging = r->staging || opts->force_staging;
  stats->encoded = opts->levels != NULL;
  if (st == RC_OK)
    stats->readback_cached = (rc_mem_flags(ctx, &pixel_readback(r, 0)->memory) & VK_MEMORY_PROPERTY_HOST_CACHED_BIT) != 0;
  rc_mem_usage(ctx, &stats->memory_blocks, &stats->memory_bytes);
  if (st != RC_OK) {
    rc_gpu_renderer_destroy(r);
    return st;
  }
  *out = r;
  return RC_OK;
}

void rc_gpu_renderer_destroy(rc_gpu_renderer *r) {
  if (!r) return;
  rc_vk_ctx *ctx = r->ctx;
  vkDeviceWaitIdle(ctx->device);
  vkDestroyFence(ctx->device, r->fence, NULL);
  vkDestroyCommandPool(ctx->device, r->pool, NULL); /* frees `cmd` */
  vkDestroyQueryPool(ctx->device, r->queries, NULL);
  vkDestroyDescriptorPool(ctx->device, r->descriptor_pool, NULL);
  vkDestroyPipeline(ctx->device, r->pipeline, NULL);
  vkDestroyPipelineLayout(ctx->device, r->pipeline_layout, NULL);
  vkDestroyDescriptorSetLayout(ctx->device, r->set_layout, NULL);
  for (int i = 0; i < SCENE_ARRAYS; i++) {
    vkDestroyBufferView(ctx->device, r->views[i], NULL);
    rc_buffer_destroy(ctx, &r->arrays[i]);
  }
  rc_buffer_destroy(ctx, &r->frame_buf);
  rc_buffer_destroy(ctx, &r->accum);
  for (int i = 0; i < 2; i++) {
    rc_buffer_destroy(ctx, &r->accum_readback[i]);
    rc_buffer_destroy(ctx, &r->aov_readback[i]);
  }
  rc_buffer_destroy(ctx, &r->status);
  rc_buffer_destroy(ctx, &r->status_readback);
  rc_buffer_destroy(ctx, &r->aov);
  rc_buffer_destroy(ctx, &r->mask_upload);
  free(r->band_rgb);
  free(r->band_levels);
  free(r->band_aov);
  free(r);
}

static void barrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags src_access,
                    VkPipelineStageFlags dst, VkAccessFlags dst_access) {
  VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = src_access,
                        .dstAccessMask = dst_access};
  vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &mb, 0, NULL, 0, NULL);
}

/* Ends the recording and submits it; wait_submitted waits for it. */
static rc_status submit_only(rc_gpu_renderer *r) {
  rc_vk_ctx *ctx = r->ctx;
  RC_VK_TRY(vkEndCommandBuffer(r->cmd));
  VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &r->cmd};
  RC_VK_TRY(vkResetFences(ctx->device, 1, &r->fence));
  RC_VK_TRY(vkQueueSubmit(ctx->queue, 1, &si, r->fence));
  return RC_OK;
}

static rc_status wait_submitted(rc_gpu_renderer *r) {
  VkResult res = vkWaitForFences(r->ctx->device, 1, &r->fence, VK_TRUE, UINT64_MAX);
  if (res == VK_SUCCESS && rc_fault("device-lost")) res = VK_ERROR_DEVICE_LOST;
  if (res == VK_ERROR_DEVICE_LOST) {
    rc_error("the Vulkan device was lost during rendering (a driver reset, often a dispatch that ran too "
             "long); try a smaller tile size");
    return RC_ERR_VULKAN;
  }
  RC_VK_TRY(res);
  return RC_OK;
}

static rc_status submit(rc_gpu_renderer *r) {
  rc_status st = submit_only(r);
  return st == RC_OK ? wait_submitted(r) : st;
}

static rc_status begin(rc_gpu_renderer *r) {
  RC_VK_TRY(vkResetCommandPool(r->ctx->device, r->pool, 0));
  VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                 .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  RC_VK_TRY(vkBeginCommandBuffer(r->cmd, &bi));
  return RC_OK;
}

/* Copies `size` bytes of `src` from `offset` into its readback twin (at the same offset)
 * when staging, then makes them visible to the host. */
static void record_readback(rc_gpu_renderer *r, const rc_buffer *src, const rc_buffer *dst, VkDeviceSize offset,
                            VkDeviceSize size) {
  if (r->staging) {
    barrier(r->cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferCopy region = {.srcOffset = offset, .dstOffset = offset, .size = size};
    vkCmdCopyBuffer(r->cmd, src->buffer, dst->buffer, 1, &region);
    barrier(r->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
            VK_ACCESS_HOST_READ_BIT);
  } else {
    barrier(r->cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
            VK_ACCESS_HOST_READ_BIT);
  }
}

/* A tile's pixels in bytes: its 8-bit levels (4 a pixel) or its sums (16). */
static VkDeviceSize tile_pixel_bytes(const rc_gpu_renderer *r, uint32_t tw, uint32_t th) {
  return (VkDeviceSize)tw * th * (r->opts.levels ? 4 : 16);
}

/* The tile's pixels and, where the frame has them, its AOV records, copied into their
 * readback twins (staging) and made visible to the host. */
static void record_tile_readback(rc_gpu_renderer *r, uint32_t tw, uint32_t th) {
  record_readback(r, pixel_buffer(r), pixel_readback(r, r->slot), r->opts.levels ? LEVELS_OFFSET : 0,
                  tile_pixel_bytes(r, tw, th));
  if (r->band_aov)
    record_readback(r, &r->aov, &r->aov_readback[r->slot], 0, (VkDeviceSize)tw * th * sizeof(packed_aov));
}

/* Workgroups along one side of a tile: the dispatch's size, which the row order
 * (push.row_stride) must be a permutation of. */
static uint32_t group_count(uint32_t pixels, uint32_t local) { return (pixels + local - 1) / local; }

/* The shader over groups_x x groups_y workgroups, with its pipeline, set and push constants. */
static void record_shader(rc_gpu_renderer *r, const packed_push *push, uint32_t groups_x, uint32_t groups_y) {
  vkCmdBindPipeline(r->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->pipeline);
  vkCmdBindDescriptorSets(r->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->pipeline_layout, 0, 1, &r->set, 0, NULL);
  vkCmdPushConstants(r->cmd, r->pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *push, push);
  vkCmdDispatch(r->cmd, groups_x, groups_y, 1);
}

/* One workgroup over an empty tile: no invocation is inside it, so nothing is read or
 * written but the frame. A driver may make the shader's machine code at a pipeline's first
 * dispatch rather than at its creation: Mesa's lavapipe does (LLVM's compile, or the load
 * from Mesa's disk cache: 267-279 ms and 12-20 ms for highlights_phong,
 * docs/performance.md). Where a time budget sizes the tiles, the planner's first
 * measurement must be the shader's time, not the compiler's: from a cold cache that first
 * dispatch had made mesh.json's frame at --tile-budget-ms 5 1,436 tiles instead of about
 * 150, with a 337 ms dispatch. Without a budget (lavapipe's default) nothing is measured,
 * and the extra dispatch would only cost its fixed few ms. */
static rc_status warm_up(rc_gpu_renderer *r) {
  rc_status st = begin(r);
  if (st != RC_OK) return st;
  packed_push push = {.row_stride = 1, .light_pass = r->light_pass};
  /* The uploads before it (the frame is read), as dispatch() orders them. */
  barrier(r->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT);
  record_shader(r, &push, 1, 1);
  return submit(r);
}

static rc_status host_work(rc_gpu_renderer *r, bool overlapped, rc_gpu_stats *stats);

/* One dispatch over a tile: reset the status counters (and the accumulation buffer on the
 * first batch), run the shader between two timestamps, and bring the status back. Through
 * staging, a dispatch that may be the tile's last (copy_tile) also copies the tile out in
 * the same submit: a second submit and wait cost a queue round trip per tile. While it
 * runs, the host does the work left for it (host_work). */
static rc_status dispatch(rc_gpu_renderer *r, const packed_push *push, bool first, bool copy_tile,
                          packed_status *status, double *ms, rc_gpu_stats *stats) {
  rc_status st = begin(r);
  if (st != RC_OK) return st;
  VkCommandBuffer cmd = r->cmd;
  /* Earlier transfers and dispatches (uploads, the previous batch) before this one. */
  barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
          VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
          VK_ACCESS_TRANSFER_WRITE_BIT);
  /* The re-render's marks, where the AOV buffer is not mapped (put_mask). */
  if (first && r->mask && r->mask_upload.buffer) {
    VkBufferCopy copy = {.size = (VkDeviceSize)push->tile_width * push->tile_height * sizeof(packed_aov)};
    vkCmdCopyBuffer(cmd, r->mask_upload.buffer, r->aov.buffer, 1, &copy);
  }
  /* Only the tile's pixels: the buffer holds the largest tile, and clearing all of it cost
   * small frames milliseconds on lavapipe. */
  if (first) vkCmdFillBuffer(cmd, r->accum.buffer, 0, (VkDeviceSize)push->tile_width * push->tile_height * 16, 0);
  /* Byte 3 of a pixel's levels says it is complete (read_tile checks): none is, yet. */
  if (first && r->opts.levels)
    vkCmdFillBuffer(cmd, r->aov.buffer, LEVELS_OFFSET, (VkDeviceSize)push->tile_width * push->tile_height * 4, 0);
  vkCmdFillBuffer(cmd, r->status.buffer, 0, VK_WHOLE_SIZE, 0);
  barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT);
  if (r->queries) {
    vkCmdResetQueryPool(cmd, r->queries, 0, 2);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, r->queries, 0);
  }
  record_shader(r, push, group_count(push->tile_width, r->local_x), group_count(push->tile_height, r->local_y));
  if (r->queries) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, r->queries, 1);
  record_readback(r, &r->status, &r->status_readback, 0, sizeof(packed_status));
  r->tile_copied = r->staging && copy_tile;
  if (r->tile_copied) record_tile_readback(r, push->tile_width, push->tile_height);
  double t0 = rc_now_ms();
  st = submit_only(r);
  const bool submitted = st == RC_OK;
  /* The previous tile, copied out into the other slot, is read while this one runs, and
   * the band it completed is handed on. */
  double read_ms = 0;
  const double band_ms_before = stats->band_overlapped_ms;
  if (st == RC_OK && (r->pending.valid || r->band_done.valid)) {
    double r0 = rc_now_ms();
    st = host_work(r, true, stats);
    read_ms = rc_now_ms() - r0;
  }
  const double written_ms = stats->band_overlapped_ms - band_ms_before; /* this band's write */
  /* Waited for even where the host's work failed (a full disk): the fence and the command
   * buffer are whole again before anything else touches them. */
  if (submitted) {
    rc_status waited = wait_submitted(r);
    if (st == RC_OK) st = waited;
  }
  double wall = rc_now_ms() - t0 - read_ms;
  if (st != RC_OK) return st;
  const rc_buffer *sb = r->staging ? &r->status_readback : &r->status;
  st = rc_buffer_invalidate(r->ctx, sb);
  if (st != RC_OK) return st;
  memcpy(status, sb->memory.mapped, sizeof *status);
  if (r->queries) {
    uint64_t ts[2];
    RC_VK_TRY(vkGetQueryPoolResults(r->ctx->device, r->queries, 0, 2, sizeof ts, ts, sizeof ts[0],
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    /* Only the low timestampValidBits count; the difference wraps modulo 2^bits. */
    uint64_t mask = r->ctx->timestamp_bits >= 64 ? ~0ull : ((1ull << r->ctx->timestamp_bits) - 1);
    uint64_t ticks = (ts[1] - ts[0]) & mask;
    *ms = (double)ticks * r->ctx->props.limits.timestampPeriod * 1e-6;
  } else {
    *ms = wall;
  }
  /* Tests of the tile model inject a dispatch's time (no test may read a clock):
   * VKRAYCAST_FAULT=dispatch-ms:OVERHEAD:PER_PIXEL_SAMPLE, in ms. */
  const char *fake = rc_fault_arg("dispatch-ms");
  double overhead, slope;
  if (fake && sscanf(fake, "%lf:%lf", &overhead, &slope) == 2)
    *ms = overhead + slope * (double)push->tile_width * push->tile_height * push->batch_samples;
  /* A band written while this dispatch ran hid no more of the write than the device's time:
   * past it the device waited for the host. */
  stats->band_hidden_ms += written_ms < *ms ? written_ms : *ms;
  return RC_OK;
}

/* A pixel the shader names in the status record, 1 + y * width + x of the frame (0: none
 * named, read as pixel (0, 0)). */
static void status_pixel(const rc_gpu_renderer *r, uint32_t encoded, uint32_t *x, uint32_t *y) {
  uint32_t at = encoded ? encoded - 1 : 0;
  *x = at % r->frame.camera.width, *y = at / r->frame.camera.width;
}

/* The tile's 8-bit levels (opts.levels) into the band: each pixel's word holds r, g, b
 * and, in byte 3, 255 if the shader completed it. */
static void read_levels(rc_gpu_renderer *r, const uint32_t *src, uint32_t bx, uint32_t tw, uint32_t th) {
  const uint32_t width = rc_region_width(r->region);
  for (uint32_t y = 0; y < th; y++) {
    for (uint32_t x = 0; x < tw; x++) {
      uint32_t word = src[(size_t)y * tw + x];
      uint8_t *o = r->band_levels + 3 * ((size_t)y * width + (bx + x));
      RC_ASSERT(word >> 24 == 255u);
      o[0] = (uint8_t)word, o[1] = (uint8_t)(word >> 8), o[2] = (uint8_t)(word >> 16);
    }
  }
}

/* The tile's sums into the band, each divided by the samples (the value whose level
 * packed_levels.sum_threshold gives from the sum). */
static void read_sums(rc_gpu_renderer *r, const float *acc, uint32_t bx, uint32_t tw, uint32_t th) {
  const uint32_t width = rc_region_width(r->region);
  const uint32_t spp = r->frame.samples_per_pixel;
  const float complete = (float)spp * (float)(r->light_passes ? r->frame.light_count : 1);
  for (uint32_t y = 0; y < th; y++) {
    for (uint32_t x = 0; x < tw; x++) {
      const float *a = acc + 4 * ((size_t)y * tw + x);
      float *o = r->band_rgb + 3 * ((size_t)y * width + (bx + x));
      RC_ASSERT(a[3] == complete);
      for (int c = 0; c < 3; c++) o[c] = a[c] / (float)spp;
    }
  }
}

/* The tile at column x0 of the current band into the band buffers: the pixels (their
 * levels, or their sums over the samples) and the AOV records, read where they lie, or
 * through staging from readback slot `slot` (`copied`: the tile's last dispatch copied them
 * there; else copied out first). */
static rc_status read_tile(rc_gpu_renderer *r, uint32_t x0, uint32_t tw, uint32_t th, uint32_t slot, bool copied,
                           rc_gpu_stats *stats) {
  double t0 = rc_now_ms();
  rc_status st = RC_OK;
  const bool levels = r->opts.levels != NULL;
  const VkDeviceSize bytes = tile_pixel_bytes(r, tw, th);
  const VkDeviceSize offset = levels ? LEVELS_OFFSET : 0;
  const rc_buffer *pb = pixel_readback(r, slot);
  /* Mapped directly, the last dispatch's global barrier to the host (record_readback of
   * the status) already made the pixels and AOVs visible: no second submit, which costs a
   * whole queue round trip on lavapipe. Staging copies them first, in the last dispatch's
   * submit where it could (dispatch's copy_tile), else here. */
  if (r->staging && !copied) {
    RC_ASSERT(slot == r->slot);
    st = begin(r);
    if (st != RC_OK) return st;
    record_tile_readback(r, tw, th);
    st = submit(r);
    stats->readback_submits++;
  }
  const rc_buffer *vb = r->staging ? &r->aov_readback[slot] : &r->aov;
  if (st == RC_OK) st = rc_buffer_invalidate(r->ctx, pb);
  if (st == RC_OK && r->band_aov) st = rc_buffer_invalidate(r->ctx, vb);
  if (st != RC_OK) return st;
  /* Tile (x0, y0) is in frame pixels; the band is the region's width. */
  uint32_t width = rc_region_width(r->region), bx = x0 - r->region.x0;
  if (r->band_aov) {
    const packed_aov *src = vb->memory.mapped;
    for (uint32_t y = 0; y < th; y++)
      memcpy(r->band_aov + (size_t)y * width + bx, src + (size_t)y * tw, tw * sizeof *src);
  }
  const char *mapped = (const char *)pb->memory.mapped + offset;
  if (levels) read_levels(r, (const uint32_t *)mapped, bx, tw, th);
  else read_sums(r, (const float *)mapped, bx, tw, th);
  stats->readback_ms += rc_now_ms() - t0;
  stats->readback_bytes += bytes + (r->band_aov ? (uint64_t)tw * th * sizeof(packed_aov) : 0);
  stats->tiles++;
  return RC_OK;
}

/* Reads the tile left pending; `overlapped`: while a dispatch runs. */
static rc_status read_pending(rc_gpu_renderer *r, bool overlapped, rc_gpu_stats *stats) {
  r->pending.valid = false;
  if (overlapped) stats->readback_overlapped++;
  else r->slot = r->pending.slot; /* nothing runs: the next copy may take the slot back */
  return read_tile(r, r->pending.x0, r->pending.tw, r->pending.th, r->pending.slot, true, stats);
}

/* The host's work that waits for the next dispatch to hide it: the tile left pending, then
 * the band it completed, if it did, to the band function (writing a band of a 4K PNG takes
 * longer than rendering it on a GPU). The band's buffers are free again before the next
 * tile is read into them: after that dispatch. `overlapped`: while a dispatch runs. */
static rc_status host_work(rc_gpu_renderer *r, bool overlapped, rc_gpu_stats *stats) {
  rc_status st = r->pending.valid ? read_pending(r, overlapped, stats) : RC_OK;
  if (st != RC_OK || !r->band_done.valid) return st;
  r->band_done.valid = false;
  double t0 = rc_now_ms();
  st = r->band(r->band_done.y0, r->band_done.rows, r->band_rgb, r->band_levels, r->band_aov, r->band_user);
  if (overlapped) {
    stats->bands_overlapped++;
    stats->band_overlapped_ms += rc_now_ms() - t0;
  }
  return st;
}

/* The plan's batch rests on a worst case (every ray to the deepest leaf, every bounce taken:
 * gpu_plan.c) that real rays rarely approach: the user-like room planned 3,223 steps a
 * sample against a budget of 6,144, so 4 dispatches of one sample, where its invocations
 * took at most a few hundred. After a dispatch that did not run out and traced `traced`
 * samples of each pixel (fewer than the batch at a tile's end), the batch grows to
 * what the measured steps say fits in 3/4 of the budget (and, under a time budget, in 4/5
 * of it), up to the samples left; a batch that runs out anyway is halved and re-run, as
 * for the plan's (render_tile). Fewer dispatches do the same work: each pixel's samples
 * are summed in the same order, so the image is bit for bit the same. */
static void grow_batch(rc_gpu_renderer *r, packed_push *push, uint32_t traced, const packed_status *status, double ms) {
  if (status->max_steps == 0 || traced == 0) return;
  uint64_t fit = (uint64_t)traced * r->budget * 3 / 4 / status->max_steps;
  if (r->tile_budget_ms > 0 && ms > 0) {
    double by_time = traced * 0.8 * r->tile_budget_ms / ms;
    if ((double)fit > by_time) fit = (uint64_t)by_time;
  }
  if (fit > r->frame.samples_per_pixel) fit = r->frame.samples_per_pixel;
  if (fit > push->batch_samples) push->batch_samples = r->batch_samples = (uint32_t)fit;
}

/* The re-render's marks of frame row y from column x0 on (r->mask covers the region). */
static const packed_aov *mask_row(const rc_gpu_renderer *r, uint32_t x0, uint32_t y) {
  return r->mask + (size_t)(y - r->region.y0) * rc_region_width(r->region) + (x0 - r->region.x0);
}

/* The re-render's marks of tile (x0, y0) into the AOV buffer, which the shader reads
 * (push.masked) and then overwrites for the pixels it traces: straight into the buffer
 * where it is mapped, else into mask_upload, which dispatch() copies over. */
static rc_status put_mask(rc_gpu_renderer *r, uint32_t x0, uint32_t y0, uint32_t tw, uint32_t th) {
  const bool direct = rc_buffer_is_direct(&r->aov, r->opts.force_staging);
  if (!direct && !r->mask_upload.buffer) {
    rc_status st = rc_buffer_create(r->ctx, r->aov.size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, RC_MEM_UPLOAD,
                                    &r->mask_upload);
    if (st != RC_OK) return st;
  }
  const rc_buffer *dst = direct ? &r->aov : &r->mask_upload;
  packed_aov *out = dst->memory.mapped;
  for (uint32_t y = 0; y < th; y++) memcpy(out + (size_t)y * tw, mask_row(r, x0, y0 + y), tw * sizeof *out);
  return rc_buffer_flush(r->ctx, dst);
}

/* Renders one tile (a piece of the current band): batches until every pixel has all its
 * samples. A dispatch whose pixels ran out of loop budget (the plan was wrong) is repeated
 * with half the batch; exhaustion at one sample per batch is an error, never a silently
 * wrong pixel. Every dispatch's time goes to the planner. */
static rc_status render_tile(rc_gpu_renderer *r, uint32_t x0, uint32_t y0, uint32_t tw, uint32_t th,
                             rc_tile_planner *planner, rc_gpu_stats *stats) {
  packed_push push = {.tile_x = x0, .tile_y = y0, .tile_width = tw, .tile_height = th,
                   .batch_samples = r->batch_samples,
                   .row_stride = rc_tiles_row_stride(group_count(th, r->local_y)),
                   .light_pass = r->light_pass,
                   .masked = r->mask != NULL};
  if (r->mask) {
    /* A tile without a marked pixel has nothing to re-render: no dispatch, and the band's
     * pixels there are not read (the caller takes the marked ones). */
    bool marked = false;
    for (uint32_t y = 0; y < th && !marked; y++)
      for (uint32_t x = 0; x < tw && !marked; x++) marked = mask_row(r, x0, y0 + y)[x].uncertified > 0;
    if (!marked) return RC_OK;
    rc_status st = put_mask(r, x0, y0, tw, th);
    if (st != RC_OK) return st;
  }
  /* This tile's copy goes to the slot the pending one is not in. */
  if (r->staging && !r->accum_readback[r->slot].buffer) {
    rc_status st = create_readback_slot(r, r->slot);
    if (st != RC_OK) return st;
  }
  bool first = true;
  uint32_t progress = 0; /* samples every pixel of the tile has (not counted in light passes) */
  for (;;) {
    packed_status status;
    double ms = 0;
    /* This batch completes every pixel unless it runs out (or traces one light pass). */
    bool last = !r->light_passes && progress + push.batch_samples >= r->frame.samples_per_pixel;
    rc_status st = dispatch(r, &push, first, last, &status, &ms, stats);
    if (st != RC_OK) return st;
    first = false;
    stats->dispatches++;
    stats->readback_bytes += sizeof status;
    stats->gpu_ms += ms;
    rc_tiles_observe(planner, (double)tw * th, push.batch_samples, ms);
    if (ms > stats->max_dispatch_ms) stats->max_dispatch_ms = ms;
    if (r->tile_budget_ms > 0 && ms > r->tile_budget_ms) stats->over_budget++;
    stats->shadow_rays += status.shadow_rays;
    stats->reflection_rays += status.reflection_rays;
    stats->uncertified_at[0] += status.uncertified_hit;
    stats->uncertified_at[1] += status.uncertified_shadow;
    stats->uncertified_at[2] += status.uncertified_bounce;
    if (status.patch_unconverged && stats->patch_stalls == 0) {
      stats->patch_stall_object = status.patch_unconverged_object ? status.patch_unconverged_object - 1 : 0;
      status_pixel(r, status.patch_unconverged_pixel, &stats->patch_stall_x, &stats->patch_stall_y);
    }
    stats->patch_stalls += status.patch_unconverged;
    if (status.crossing_object) {
      /* A mesh operand crossed more often than its bound, or an odd number of times: no
       * batch size helps, and the pixel would be wrong. Reported by the caller. */
      stats->crossing_object = status.crossing_object - 1;
      status_pixel(r, status.crossing_pixel, &stats->crossing_x, &stats->crossing_y);
      return RC_ERR_TOO_LARGE;
    }
    if (status.exhausted_pixels) {
      /* The batch first, then a sample's lights, halve; the pixels that ran out kept their
       * progress, so the next dispatch goes on where each pixel stands. */
      if (push.batch_samples > 1) {
        push.batch_samples /= 2;
        r->batch_samples = push.batch_samples;
      } else if (push.light_pass > 1) {
        push.light_pass /= 2;
        r->light_pass = push.light_pass; /* the next tiles start here */
      } else {
        /* Reported by the caller, which knows where the object came from. */
        stats->budget_refused = true;
        stats->lights_per_pass = push.light_pass;
        stats->budget_pixels = status.exhausted_pixels;
        stats->budget_object = status.exhausted_object ? status.exhausted_object - 1 : UINT32_MAX;
        status_pixel(r, status.exhausted_pixel, &stats->budget_x, &stats->budget_y);
        return RC_ERR_TOO_LARGE;
      }
      stats->budget_retries++;
    } else if (!r->light_passes) {
      /* (Not after a light pass: it traces part of one sample, its size counted in lights.) */
      uint32_t spp = r->frame.samples_per_pixel, traced = spp - progress < push.batch_samples ? spp - progress : push.batch_samples;
      progress += traced;
      grow_batch(r, &push, traced, &status, ms);
    }
    if (status.incomplete_pixels == 0) break;
  }
  if (!r->tile_copied) return read_tile(r, x0, tw, th, r->slot, false, stats);
  /* Copied out by its last dispatch: read while the next tile's first one runs, the next
   * band's too, which on a GPU hides the host's pass over the tile behind the device's work
   * (at the frame's end, at once). */
  r->pending.valid = true;
  r->pending.x0 = x0, r->pending.tw = tw, r->pending.th = th, r->pending.slot = r->slot;
  r->slot ^= 1;
  return RC_OK;
}

rc_status rc_gpu_renderer_render(rc_gpu_renderer *r, rc_band_fn band, void *user, rc_gpu_stats *stats) {
  stats->gpu_ms = stats->readback_ms = stats->max_dispatch_ms = 0;
  stats->shadow_rays = stats->reflection_rays = 0;
  memset(stats->uncertified_at, 0, sizeof stats->uncertified_at);
  stats->dispatches = stats->tiles = stats->budget_retries = stats->over_budget = stats->readback_submits = 0;
  stats->readback_overlapped = stats->bands_overlapped = 0;
  stats->band_overlapped_ms = stats->band_hidden_ms = 0;
  r->pending.valid = r->band_done.valid = false;
  r->band = band, r->band_user = user;
  stats->crossing_object = UINT32_MAX;
  stats->patch_stalls = 0;
  stats->readback_bytes = 0;
  const rc_region reg = r->region;
  const uint32_t w = rc_region_width(reg), h = rc_region_height(reg), batch = stats->plan.batch_samples;
  const uint64_t total = (uint64_t)w * h;
  uint64_t done = 0;
  rc_tile_planner planner;
  planner_init(r, &planner);
  double t0 = rc_now_ms();
  for (uint32_t y0 = 0; y0 < h;) {
    uint32_t rows = rc_tiles_band_rows(&planner, y0, batch);
    for (uint32_t x0 = 0; x0 < w;) {
      uint32_t cols = rc_tiles_cols(&planner, rows, x0, batch);
      rc_status st = render_tile(r, reg.x0 + x0, reg.y0 + y0, cols, rows, &planner, stats);
      if (st != RC_OK) return st;
      x0 += cols;
      done += (uint64_t)cols * rows;
      if (r->opts.progress) {
        double el = (rc_now_ms() - t0) * 1e-3;
        /* Straight to the descriptor: its carriage return redraws the line, and the
         * filtered stderr (cli/safe_streams.h) would spell it out. */
        dprintf(STDERR_FILENO, "\rvkraycast: %5.1f%%, %u tiles, %.1f s elapsed, about %.1f s left ",
                100.0 * (double)done / total, stats->tiles, el, el * (double)(total - done) / (double)done);
      }
    }
    /* The band goes on during the next band's first dispatch (host_work). One still
     * waiting, where this band had no dispatch (a re-render's tiles without a marked
     * pixel), goes first, at once. */
    rc_status st = r->band_done.valid ? host_work(r, false, stats) : RC_OK;
    if (st != RC_OK) return st;
    r->band_done.valid = true;
    r->band_done.y0 = y0, r->band_done.rows = rows;
    y0 += rows;
  }
  rc_status st = host_work(r, false, stats); /* the frame's last band */
  if (st != RC_OK) return st;
  if (r->opts.progress) fputc('\n', stderr);
  stats->lights_per_pass = r->light_pass;
  stats->batch_samples_end = r->batch_samples;
  stats->render_ms = rc_now_ms() - t0;
  return RC_OK;
}

rc_status rc_gpu_renderer_rerender(rc_gpu_renderer *r, rc_region region, const packed_aov *mask, rc_band_fn band,
                                   void *user, rc_gpu_stats *stats) {
  RC_ASSERT(r->opts.aov && !r->opts.levels);
  RC_ASSERT(region.x0 == r->region.x0 && region.x1 == r->region.x1 && region.y0 >= r->region.y0 &&
            region.y1 <= r->region.y1);
  const rc_region whole = r->region;
  r->region = region;
  r->mask = mask;
  rc_status st = rc_gpu_renderer_render(r, band, user, stats);
  r->region = whole;
  r->mask = NULL;
  return st;
}
