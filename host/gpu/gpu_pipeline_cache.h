/* gpu_pipeline_cache.h: a VkPipelineCache kept on disk between runs, so that a warm start
 * skips the driver's shader compilation where the driver fills the cache (NVIDIA, AMD,
 * Intel). One file per device and shader module under $XDG_CACHE_HOME/vkraycast/ (else
 * ~/.cache/vkraycast/), named by a hash of the device's pipelineCacheUUID, vendor, device
 * and driver version and the SPIR-V the driver is given: with the constants applied on the
 * host (spirv_specialize.h) one file per specialization, with --spec-constants driver one
 * per module, shared by its specializations.
 * A missing, corrupt, truncated or foreign file is ignored with a warning, and a cache
 * that cannot be written costs a warning: the cache never fails a render (the file itself:
 * disk_cache.h). VKRAYCAST_PIPELINE_CACHE=0 turns it off, with spirv_cache.h's. (lavapipe returns a 32-byte header and no
 * pipelines: its warm start comes from Mesa's own disk cache, MESA_SHADER_CACHE_DIR;
 * docs/performance.md measures both.) */
#ifndef RC_GPU_PIPELINE_CACHE_H
#define RC_GPU_PIPELINE_CACHE_H

#include <limits.h>

#include "gpu/gpu_shaders.h"
#include "gpu/vk_context.h"

typedef struct rc_pipeline_cache {
  VkPipelineCache cache; /* VK_NULL_HANDLE when off */
  char path[PATH_MAX];   /* empty when there is nowhere to keep it */
  uint64_t key;          /* of the device and module: in the file's header and its name */
  uint64_t loaded_checksum; /* of the driver data read from the file */
  bool loaded;              /* a valid file was found and taken by the driver */
} rc_pipeline_cache;

/* Opens the cache for this device and module; never fails (VK_NULL_HANDLE on error). */
void rc_pipeline_cache_open(const rc_vk_ctx *ctx, rc_spirv module, rc_pipeline_cache *pc);
/* Writes the cache back if the driver's data changed, then destroys it. */
void rc_pipeline_cache_close(const rc_vk_ctx *ctx, rc_pipeline_cache *pc);

#endif
