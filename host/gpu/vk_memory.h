/* vk_memory.h: device memory in a few large blocks, buffers bound at offsets inside them
 * (docs/porting.md, "Memory"). Drivers cap the number of live allocations
 * (maxMemoryAllocationCount: 4,096 on many Windows drivers) and round each one up to a
 * page or more, so one vkAllocateMemory per buffer does not scale and wastes memory on
 * small buffers; NVIDIA's and AMD's best-practice checks flag both.
 *
 * Blocks are kept per memory type and per use (rc_mem_use), so each block has one
 * VK_EXT_memory_priority priority: what the shader reads and writes above readback above
 * upload staging. Inside a block, slices are taken bottom-up and a freed slice at the top
 * is given back at once (uploads take a staging slice and free it right away, so they
 * reuse the same bytes); a block whose slices are all freed starts over. A request of more
 * than half the block size gets a block of its own. Host-visible blocks are mapped once,
 * and slices of non-coherent memory are aligned to nonCoherentAtomSize so that flushing
 * one never touches its neighbour. */
#ifndef RC_VK_MEMORY_H
#define RC_VK_MEMORY_H

#include "gpu/vk_context.h"

typedef enum { RC_MEM_DEVICE, RC_MEM_UPLOAD, RC_MEM_READBACK } rc_mem_use;

typedef struct rc_mem_slice {
  struct rc_mem_block *block;
  VkDeviceMemory memory;
  VkDeviceSize offset, size;
  void *mapped; /* at `offset`; NULL when the memory is not host visible */
  bool coherent;
} rc_mem_slice;

/* The first block of a type and use; later ones double up to RC_MEM_BLOCK_MAX. Both are at
 * least the 256 KiB under which the best-practice checks call an allocation small. */
#define RC_MEM_BLOCK_MIN ((VkDeviceSize)4 << 20)
#define RC_MEM_BLOCK_MAX ((VkDeviceSize)64 << 20)

/* Memory for `req` from memory type `type`. */
rc_status rc_mem_alloc(rc_vk_ctx *ctx, const VkMemoryRequirements *req, uint32_t type, rc_mem_use use,
                       rc_mem_slice *out);
/* Safe on a zeroed slice. */
void rc_mem_free(rc_vk_ctx *ctx, rc_mem_slice *slice);
/* Frees every block; at device destruction. */
void rc_mem_release_all(rc_vk_ctx *ctx);

/* The slice's range for vkFlush/InvalidateMappedMemoryRanges: aligned to nonCoherentAtomSize. */
VkMappedMemoryRange rc_mem_range(const rc_vk_ctx *ctx, const rc_mem_slice *slice);

/* The property flags of the memory type a slice lies in. */
VkMemoryPropertyFlags rc_mem_flags(const rc_vk_ctx *ctx, const rc_mem_slice *slice);

/* Live blocks and their bytes, for the statistics and the tests. */
void rc_mem_usage(const rc_vk_ctx *ctx, uint32_t *blocks, VkDeviceSize *bytes);

#endif
