#include "gpu/gpu_pipeline_cache.h"

#include <stdlib.h>
#include <string.h>

#include "gpu/disk_cache.h"

/* The file (disk_cache.h) holds the driver's cache data, which starts with Vulkan's own
 * VkPipelineCacheHeaderVersionOne. The checksum catches a torn or corrupted file before
 * the driver sees it; the key catches a file copied from another device. */
#define MAGIC "VKRCPC01"

static uint64_t checksum(const void *data, size_t n) { return rc_fnv1a(RC_FNV_OFFSET, data, n); }

static uint64_t cache_key(const rc_vk_ctx *ctx, rc_spirv module) {
  const VkPhysicalDeviceProperties *p = &ctx->props;
  uint64_t h = RC_FNV_OFFSET;
  h = rc_fnv1a(h, p->pipelineCacheUUID, VK_UUID_SIZE);
  h = rc_fnv1a(h, &p->vendorID, sizeof p->vendorID);
  h = rc_fnv1a(h, &p->deviceID, sizeof p->deviceID);
  h = rc_fnv1a(h, &p->driverVersion, sizeof p->driverVersion);
  return rc_fnv1a(h, module.words, module.size);
}

/* The driver's own header (Vulkan spec, VkPipelineCacheHeaderVersionOne) must name this
 * device: the driver would ignore a foreign one too, but some drivers have crashed on
 * data they did not write, so it is checked before the driver sees it. */
static bool driver_header_matches(const rc_vk_ctx *ctx, const void *data, size_t size) {
  VkPipelineCacheHeaderVersionOne h;
  if (size < sizeof h) return false;
  memcpy(&h, data, sizeof h);
  return h.headerSize >= sizeof h && h.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
         h.vendorID == ctx->props.vendorID && h.deviceID == ctx->props.deviceID &&
         memcmp(h.pipelineCacheUUID, ctx->props.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

void rc_pipeline_cache_open(const rc_vk_ctx *ctx, rc_spirv module, rc_pipeline_cache *pc) {
  memset(pc, 0, sizeof *pc);
  if (!rc_disk_cache_enabled()) return;
  pc->key = cache_key(ctx, module);
  void *data = NULL;
  size_t size = 0;
  if (rc_disk_cache_path(pc->key, ".bin", pc->path, sizeof pc->path)) {
    data = rc_disk_cache_read(pc->path, MAGIC, pc->key, "pipeline cache", &size);
    if (data && !driver_header_matches(ctx, data, size)) {
      rc_disk_cache_ignored(pc->path, "pipeline cache", "made for another device or driver");
      free(data);
      data = NULL;
      size = 0;
    }
  }
  VkPipelineCacheCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO,
                                  .initialDataSize = size,
                                  .pInitialData = data};
  if (vkCreatePipelineCache(ctx->device, &ci, NULL, &pc->cache) != VK_SUCCESS) {
    pc->cache = VK_NULL_HANDLE;
    if (data) rc_warning("%s: the driver refused the pipeline cache; compiling without it", pc->path);
  } else {
    pc->loaded = data != NULL;
    pc->loaded_checksum = data ? checksum(data, size) : 0;
  }
  free(data);
}

void rc_pipeline_cache_close(const rc_vk_ctx *ctx, rc_pipeline_cache *pc) {
  if (!pc->cache) return;
  size_t size = 0;
  void *data = NULL;
  if (pc->path[0] && vkGetPipelineCacheData(ctx->device, pc->cache, &size, NULL) == VK_SUCCESS && size > 0 &&
      size <= RC_DISK_CACHE_MAX_BYTES && (data = malloc(size)) &&
      vkGetPipelineCacheData(ctx->device, pc->cache, &size, data) == VK_SUCCESS &&
      !(pc->loaded && checksum(data, size) == pc->loaded_checksum)) {
    rc_disk_cache_write(pc->path, MAGIC, pc->key, data, size, "pipeline cache");
  }
  free(data);
  vkDestroyPipelineCache(ctx->device, pc->cache, NULL);
  pc->cache = VK_NULL_HANDLE;
}
