/* gpu_upload.c: the scene arrays on the device. Which buffer kind the device can take
 * (texel views against storage buffers, each within its own limits), whether the whole
 * render fits the device-local heap, and the uploads themselves. */
#include <stdio.h>
#include <string.h>

#include "gpu/gpu_renderer.h"

const uint32_t rc_gpu_array_bindings[SCENE_ARRAYS] = {
    RC_BINDING_SPHERES,   RC_BINDING_TRIANGLES, RC_BINDING_MATERIALS, RC_BINDING_LIGHTS,
    RC_BINDING_BVH_NODES, RC_BINDING_BVH_PRIMS, RC_BINDING_TRANSFORMS, RC_BINDING_NORMALS,
    RC_BINDING_QUADRICS,  RC_BINDING_CSG,       RC_BINDING_CSG_PROGRAM, RC_BINDING_TEXELS};
static const char *const array_names[SCENE_ARRAYS] = {
    "spheres",    "triangles", "materials", "lights", "BVH nodes", "BVH references", "transforms", "normals",
    "quadrics", "composites", "CSG programs", "textures and texture coordinates"};

/* The shader's descriptors besides the scene arrays: the frame (a uniform buffer) and the
 * accumulation, status and AOV storage buffers. */
#define OUTPUT_STORAGE_BUFFERS 3u

/* The scene-array kinds, fastest on lavapipe first: the order a default render tries them in. */
static const char *const kind_names[3] = {"storage texel buffers", "uniform texel buffers", "storage buffers"};

static const VkDescriptorType kind_descriptor[3] = {VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER,
                                                    VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,
                                                    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
static const VkBufferUsageFlags kind_usage[3] = {VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT,
                                                 VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT};

bool rc_gpu_is_texel_kind(rc_scene_buffers kind) { return kind != RC_SCENE_BUFFERS_STORAGE; }

VkDescriptorType rc_gpu_kind_descriptor(rc_scene_buffers kind) { return kind_descriptor[kind]; }

/* Whether the device can take the scene arrays as buffers of `kind`: NULL, or the first
 * limit that stops it, with the numbers, in `why`. Uniform texel views count against the
 * sampled image limits, storage texel views against the storage image limits (Vulkan 1.1,
 * "Limits"); the arrays' sizes against the texel count or the storage range of one binding. */
static const char *kind_blocked(const rc_vk_ctx *ctx, rc_scene_buffers kind, const VkDeviceSize sizes[SCENE_ARRAYS],
                                char *why, size_t n) {
  const VkPhysicalDeviceLimits *l = &ctx->props.limits;
  bool texel = rc_gpu_is_texel_kind(kind), image = kind == RC_SCENE_BUFFERS_IMAGE;
  uint32_t storage = OUTPUT_STORAGE_BUFFERS + (texel ? 0 : SCENE_ARRAYS);
  if (texel) {
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(ctx->physical, VK_FORMAT_R32G32B32A32_UINT, &fp);
    VkFormatFeatureFlags need = image ? VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT : VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT;
    if (!(fp.bufferFeatures & need)) {
      snprintf(why, n, "the device has no RGBA32UI %s", kind_names[kind]);
      return why;
    }
    for (int i = 0; i < SCENE_ARRAYS; i++) {
      if (sizes[i] / 16 > l->maxTexelBufferElements) {
        snprintf(why, n, "the %s array needs %llu texels, more than maxTexelBufferElements (%u)", array_names[i],
                 (unsigned long long)(sizes[i] / 16), l->maxTexelBufferElements);
        return why;
      }
    }
    uint32_t views = SCENE_ARRAYS;
    uint32_t stage = image ? l->maxPerStageDescriptorStorageImages : l->maxPerStageDescriptorSampledImages;
    uint32_t set = image ? l->maxDescriptorSetStorageImages : l->maxDescriptorSetSampledImages;
    const char *what = image ? "StorageImages" : "SampledImages";
    if (views > stage || views > set) {
      snprintf(why, n, "%u %s, more than maxPerStageDescriptor%s (%u) or maxDescriptorSet%s (%u)", views,
               kind_names[kind], what, stage, what, set);
      return why;
    }
  } else {
    for (int i = 0; i < SCENE_ARRAYS; i++) {
      if (sizes[i] > l->maxStorageBufferRange) {
        snprintf(why, n, "the %s array is %llu bytes, more than maxStorageBufferRange (%u bytes)", array_names[i],
                 (unsigned long long)sizes[i], l->maxStorageBufferRange);
        return why;
      }
    }
  }
  if (storage > l->maxPerStageDescriptorStorageBuffers || storage > l->maxDescriptorSetStorageBuffers) {
    snprintf(why, n, "%u storage buffers, more than maxPerStageDescriptorStorageBuffers (%u) or "
             "maxDescriptorSetStorageBuffers (%u)", storage, l->maxPerStageDescriptorStorageBuffers,
             l->maxDescriptorSetStorageBuffers);
    return why;
  }
  if (RC_BINDING_COUNT > l->maxPerStageResources) {
    snprintf(why, n, "%u descriptors, more than maxPerStageResources (%u)", RC_BINDING_COUNT, l->maxPerStageResources);
    return why;
  }
  return NULL;
}

/* The buffer kind the device can take for this scene: the one asked for, or the next that
 * fits in the order image, texel, storage. Storage texel buffers (the default) give way
 * silently to uniform texel buffers, which read the same texels; falling back to storage
 * buffers (slower on lavapipe) is a warning; an explicit --scene-buffers storage is kept or
 * refused. A scene no kind fits is refused before anything is allocated, with every kind's
 * limit and numbers (docs/porting.md). */
static rc_status choose_buffers(rc_vk_ctx *ctx, rc_scene_buffers *kind, const VkDeviceSize sizes[SCENE_ARRAYS]) {
  char why[3][256];
  for (rc_scene_buffers k = *kind; k <= RC_SCENE_BUFFERS_STORAGE; k++) {
    if (kind_blocked(ctx, k, sizes, why[k], sizeof why[k])) continue;
    if (k == RC_SCENE_BUFFERS_STORAGE && *kind != k)
      rc_warning("texel buffers do not fit (%s); using storage buffers", why[k - 1]);
    *kind = k;
    return RC_OK;
  }
  if (*kind == RC_SCENE_BUFFERS_STORAGE) {
    rc_refuse_scene("--scene-buffers storage: device %u (%s) cannot take this scene: %s", ctx->device_index,
                    ctx->props.deviceName, why[RC_SCENE_BUFFERS_STORAGE]);
  } else {
    char all[800] = "";
    for (rc_scene_buffers k = *kind; k <= RC_SCENE_BUFFERS_STORAGE; k++)
      snprintf(all + strlen(all), sizeof all - strlen(all), "%sas %s %s", k == *kind ? "" : "; ", kind_names[k], why[k]);
    rc_refuse_scene("scene too large for device %u (%s): %s", ctx->device_index, ctx->props.deviceName, all);
  }
  return RC_ERR_TOO_LARGE;
}

rc_status rc_gpu_upload_scene(rc_gpu_renderer *r, const rc_packed_scene *s, uint64_t tile_pixels) {
  rc_vk_ctx *ctx = r->ctx;
  const packed_frame *f = &s->frame;
  /* Without a BVH the node and reference buffers still exist (one dummy element): every
   * binding must be valid even where the specialized shader never reads it. */
  static const packed_bvh_node no_node;
  static const uint32_t no_refs[4];
  bool bvh = s->bvh_node_total > 0; /* the object tree, or a mesh operand's */
  const void *data[SCENE_ARRAYS] = {s->spheres, s->triangles, s->materials, s->lights,
                                    bvh ? (const void *)s->bvh_nodes : &no_node, bvh ? (const void *)s->bvh_prims : no_refs,
                                    s->transforms, s->normals, s->quadrics, s->csg, s->csg_program, s->texels};
  /* +1: the packer always allocates one element, as Vulkan has no empty buffers. */
  VkDeviceSize sizes[SCENE_ARRAYS] = {
      (f->sphere_count + 1) * sizeof(packed_sphere), (s->triangle_total + 1) * sizeof(packed_triangle),
      (f->material_count + 1) * sizeof(packed_material), (f->light_count + 1) * sizeof(packed_light),
      bvh ? s->bvh_node_total * sizeof(packed_bvh_node) : sizeof no_node,
      bvh ? (s->bvh_prim_total + 3) / 4 * 4 * sizeof(uint32_t) : sizeof no_refs,
      (s->transform_count + 1) * sizeof(packed_transform), (s->normal_count + 1) * sizeof(packed_vertex_normals),
      (s->quadric_total + 1) * sizeof(packed_quadric), (f->csg_count + 1) * sizeof(packed_csg),
      (s->csg_program_length + 4) / 4 * 4 * sizeof(uint32_t),
      ((VkDeviceSize)s->texel_count + 1) * 4 * sizeof(uint32_t)};
  rc_status chosen = choose_buffers(ctx, &r->opts.scene_buffers, sizes);
  if (chosen != RC_OK) return chosen;
  /* Everything the render allocates on the device, against its largest device-local heap:
   * refuse what cannot fit before allocating anything. */
  VkDeviceSize need = sizeof(packed_frame) + tile_pixels * (16 + (r->opts.aov ? sizeof(packed_aov) : 0)) +
                     (r->opts.levels ? sizeof(packed_levels) + tile_pixels * 4 : 0);
  for (int i = 0; i < SCENE_ARRAYS; i++) need += sizes[i];
  VkDeviceSize heap = 0;
  for (uint32_t i = 0; i < ctx->memory.memoryHeapCount; i++)
    if ((ctx->memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) && ctx->memory.memoryHeaps[i].size > heap)
      heap = ctx->memory.memoryHeaps[i].size;
  if (heap && need > heap) {
    rc_refuse_scene("scene too large for the device: it needs %.1f MiB of device memory, the largest device-local heap "
             "has %.1f MiB",
             (double)need / (1 << 20), (double)heap / (1 << 20));
    return RC_ERR_TOO_LARGE;
  }
  bool texel = rc_gpu_is_texel_kind(r->opts.scene_buffers);
  for (int i = 0; i < SCENE_ARRAYS; i++) {
    VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT | kind_usage[r->opts.scene_buffers];
    rc_status st = rc_buffer_create(ctx, sizes[i], usage, RC_MEM_DEVICE, &r->arrays[i]);
    if (st == RC_OK) st = rc_buffer_upload(ctx, &r->arrays[i], data[i], sizes[i], r->opts.force_staging);
    if (st != RC_OK) return st;
    r->upload_bytes += sizes[i];
    if (texel) {
      VkBufferViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO,
                                   .buffer = r->arrays[i].buffer,
                                   .format = VK_FORMAT_R32G32B32A32_UINT,
                                   .range = VK_WHOLE_SIZE};
      RC_VK_TRY(vkCreateBufferView(ctx->device, &vi, NULL, &r->views[i]));
    }
  }
  rc_status st = rc_buffer_create(ctx, sizeof(packed_frame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  RC_MEM_DEVICE, &r->frame_buf);
  if (st == RC_OK) st = rc_buffer_upload(ctx, &r->frame_buf, f, sizeof *f, r->opts.force_staging);
  r->upload_bytes += sizeof *f;
  return st;
}

