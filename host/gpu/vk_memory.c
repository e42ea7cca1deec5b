#include "gpu/vk_memory.h"

#include <stdlib.h>
#include <string.h>

struct rc_mem_block {
  struct rc_mem_block *next;
  VkDeviceMemory memory;
  VkDeviceSize size;
  VkDeviceSize top; /* bytes below it may be in use; above it are free */
  uint32_t live;    /* slices not yet freed */
  uint32_t type;
  rc_mem_use use;
  bool own;     /* holds one request larger than half a block; freed with it */
  bool coherent;
  void *mapped; /* the whole block, when host visible */
};

static VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

/* VK_EXT_memory_priority: 0.5 is the driver's default for allocations without one. */
static float priority(rc_mem_use use) {
  switch (use) {
    case RC_MEM_DEVICE: return 1.0f;
    case RC_MEM_READBACK: return 0.5f;
    case RC_MEM_UPLOAD: return 0.25f;
  }
  return 0.5f;
}

static rc_status new_block(rc_vk_ctx *ctx, VkDeviceSize size, uint32_t type, rc_mem_use use, bool own,
                           struct rc_mem_block **out, VkResult *why) {
  VkMemoryPriorityAllocateInfoEXT prio = {.sType = VK_STRUCTURE_TYPE_MEMORY_PRIORITY_ALLOCATE_INFO_EXT,
                                          .priority = priority(use)};
  VkMemoryAllocateInfo info = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                               .pNext = ctx->memory_priority ? &prio : NULL,
                               .allocationSize = size,
                               .memoryTypeIndex = type};
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkResult r = rc_fault("device-memory") ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                                         : vkAllocateMemory(ctx->device, &info, NULL, &memory);
  *why = r;
  if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY) return RC_ERR_OUT_OF_MEMORY;
  RC_VK_TRY(r);
  /* With pageable device-local memory the driver pages by the priority set through
   * vkSetDeviceMemoryPriorityEXT (NVIDIA's best practices check that it was set before
   * the memory is bound); the same value as at allocation. */
  if (ctx->set_memory_priority) ctx->set_memory_priority(ctx->device, memory, priority(use));
  struct rc_mem_block *b = calloc(1, sizeof *b);
  if (!b) {
    vkFreeMemory(ctx->device, memory, NULL);
    *why = VK_ERROR_OUT_OF_HOST_MEMORY;
    return RC_ERR_OUT_OF_MEMORY;
  }
  VkMemoryPropertyFlags flags = ctx->memory.memoryTypes[type].propertyFlags;
  *b = (struct rc_mem_block){.memory = memory, .size = size, .type = type, .use = use, .own = own,
                             .coherent = (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0};
  if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    r = vkMapMemory(ctx->device, memory, 0, VK_WHOLE_SIZE, 0, &b->mapped);
    if (r != VK_SUCCESS) {
      vkFreeMemory(ctx->device, memory, NULL);
      free(b);
      RC_VK_TRY(r);
    }
    /* A CPU device's memory is ordinary process memory, first touched by the shader or
     * a fill: huge pages save it one fault per 4 KiB (rc_base.h). */
    rc_advise_huge(b->mapped, (size_t)size);
  }
  b->next = ctx->blocks;
  ctx->blocks = b;
  *out = b;
  return RC_OK;
}

/* The size of the next shared block of this type and use: double the largest so far. */
static VkDeviceSize next_block_size(const rc_vk_ctx *ctx, uint32_t type, rc_mem_use use) {
  VkDeviceSize size = RC_MEM_BLOCK_MIN / 2;
  for (const struct rc_mem_block *b = ctx->blocks; b; b = b->next)
    if (b->type == type && b->use == use && !b->own && b->size > size) size = b->size;
  size *= 2;
  return size < RC_MEM_BLOCK_MAX ? size : RC_MEM_BLOCK_MAX;
}

rc_status rc_mem_alloc(rc_vk_ctx *ctx, const VkMemoryRequirements *req, uint32_t type, rc_mem_use use,
                       rc_mem_slice *out) {
  memset(out, 0, sizeof *out);
  VkMemoryPropertyFlags flags = ctx->memory.memoryTypes[type].propertyFlags;
  VkDeviceSize align = req->alignment ? req->alignment : 1;
  bool noncoherent = (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && !(flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceSize atom = ctx->props.limits.nonCoherentAtomSize ? ctx->props.limits.nonCoherentAtomSize : 1;
  if (noncoherent && atom > align) align = atom;

  struct rc_mem_block *block = NULL;
  VkDeviceSize offset = 0;
  for (struct rc_mem_block *b = ctx->blocks; b && !block; b = b->next) {
    if (b->type != type || b->use != use || b->own) continue;
    VkDeviceSize at = align_up(b->top, align);
    if (at + req->size <= b->size) block = b, offset = at;
  }
  rc_status st = RC_OK;
  if (!block) {
    VkDeviceSize size = next_block_size(ctx, type, use);
    bool own = req->size > size / 2;
    VkResult why = VK_SUCCESS;
    st = new_block(ctx, own ? align_up(req->size, align) : size, type, use, own, &block, &why);
    if (st == RC_ERR_OUT_OF_MEMORY && !own) /* a whole block may not fit where the request does */
      st = new_block(ctx, align_up(req->size, align), type, use, true, &block, &why);
    if (st == RC_ERR_OUT_OF_MEMORY)
      rc_error("out of %s memory allocating a %llu-byte buffer on the Vulkan device",
               why == VK_ERROR_OUT_OF_HOST_MEMORY ? "host" : "device", (unsigned long long)req->size);
    if (st != RC_OK) return st;
  }
  block->top = offset + req->size;
  block->live++;
  *out = (rc_mem_slice){.block = block, .memory = block->memory, .offset = offset, .size = req->size,
                        .mapped = block->mapped ? (char *)block->mapped + offset : NULL, .coherent = block->coherent};
  return RC_OK;
}

static void release(rc_vk_ctx *ctx, struct rc_mem_block *block) {
  for (struct rc_mem_block **p = &ctx->blocks; *p; p = &(*p)->next) {
    if (*p == block) {
      *p = block->next;
      break;
    }
  }
  if (block->mapped) vkUnmapMemory(ctx->device, block->memory);
  vkFreeMemory(ctx->device, block->memory, NULL);
  free(block);
}

void rc_mem_free(rc_vk_ctx *ctx, rc_mem_slice *slice) {
  struct rc_mem_block *b = slice->block;
  if (!b) return;
  RC_ASSERT(b->live > 0);
  b->live--;
  if (slice->offset + slice->size == b->top) b->top = slice->offset;
  if (b->live == 0) b->top = 0;
  if (b->live == 0 && b->own) release(ctx, b);
  memset(slice, 0, sizeof *slice);
}

void rc_mem_release_all(rc_vk_ctx *ctx) {
  while (ctx->blocks) release(ctx, ctx->blocks);
}

VkMappedMemoryRange rc_mem_range(const rc_vk_ctx *ctx, const rc_mem_slice *slice) {
  VkDeviceSize atom = ctx->props.limits.nonCoherentAtomSize ? ctx->props.limits.nonCoherentAtomSize : 1;
  VkDeviceSize end = align_up(slice->offset + slice->size, atom);
  VkMappedMemoryRange r = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE,
                           .memory = slice->memory,
                           .offset = slice->offset,
                           .size = end >= slice->block->size ? VK_WHOLE_SIZE : end - slice->offset};
  return r;
}

VkMemoryPropertyFlags rc_mem_flags(const rc_vk_ctx *ctx, const rc_mem_slice *slice) {
  return ctx->memory.memoryTypes[slice->block->type].propertyFlags;
}

void rc_mem_usage(const rc_vk_ctx *ctx, uint32_t *blocks, VkDeviceSize *bytes) {
  *blocks = 0;
  *bytes = 0;
  for (const struct rc_mem_block *b = ctx->blocks; b; b = b->next) {
    (*blocks)++;
    *bytes += b->size;
  }
}
