#include "gpu/vk_buffer.h"

#include <string.h>

/* Scores each memory type allowed by `bits`: -1 if it lacks a required flag, else the
 * number of preferences it meets (higher is better). */
static int score(VkMemoryPropertyFlags f, rc_mem_use use) {
  const VkMemoryPropertyFlags visible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
  switch (use) {
    case RC_MEM_DEVICE:
      return ((f & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) ? 2 : 0) + ((f & visible) ? 0 : 1);
    case RC_MEM_UPLOAD:
      if (!(f & visible)) return -1;
      return ((f & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) ? 2 : 0) +
             ((f & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) ? 0 : 1);
    case RC_MEM_READBACK:
      if (!(f & visible)) return -1;
      return ((f & VK_MEMORY_PROPERTY_HOST_CACHED_BIT) ? 2 : 0) +
             ((f & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) ? 1 : 0);
  }
  return -1;
}

static int pick_memory_type(const rc_vk_ctx *ctx, uint32_t bits, rc_mem_use use) {
  int best = -1, best_score = -1;
  for (uint32_t i = 0; i < ctx->memory.memoryTypeCount; i++) {
    if (!(bits & (1u << i))) continue;
    int s = score(ctx->memory.memoryTypes[i].propertyFlags, use);
    if (s > best_score) {
      best = (int)i;
      best_score = s;
    }
  }
  return best;
}

rc_status rc_buffer_create(rc_vk_ctx *ctx, VkDeviceSize size, VkBufferUsageFlags usage, rc_mem_use use,
                           rc_buffer *out) {
  memset(out, 0, sizeof *out);
  out->size = size;
  VkBufferCreateInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                             .size = size,
                             .usage = usage,
                             .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
  RC_VK_TRY(vkCreateBuffer(ctx->device, &info, NULL, &out->buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx->device, out->buffer, &req);
  int type = pick_memory_type(ctx, req.memoryTypeBits, use);
  if (type < 0) {
    rc_error("no suitable memory type for a %llu-byte buffer", (unsigned long long)size);
    return RC_ERR_VULKAN;
  }
  rc_status st = rc_mem_alloc(ctx, &req, (uint32_t)type, use, &out->memory);
  if (st != RC_OK) return st;
  RC_VK_TRY(vkBindBufferMemory(ctx->device, out->buffer, out->memory.memory, out->memory.offset));
  return RC_OK;
}

void rc_buffer_destroy(rc_vk_ctx *ctx, rc_buffer *buf) {
  vkDestroyBuffer(ctx->device, buf->buffer, NULL);
  rc_mem_free(ctx, &buf->memory);
  memset(buf, 0, sizeof *buf);
}

bool rc_buffer_is_direct(const rc_buffer *buf, bool force_staging) {
  return buf->memory.mapped != NULL && !force_staging;
}

rc_status rc_buffer_flush(rc_vk_ctx *ctx, const rc_buffer *buf) {
  if (buf->memory.coherent) return RC_OK;
  VkMappedMemoryRange r = rc_mem_range(ctx, &buf->memory);
  RC_VK_TRY(vkFlushMappedMemoryRanges(ctx->device, 1, &r));
  return RC_OK;
}

rc_status rc_buffer_invalidate(rc_vk_ctx *ctx, const rc_buffer *buf) {
  if (buf->memory.coherent) return RC_OK;
  VkMappedMemoryRange r = rc_mem_range(ctx, &buf->memory);
  RC_VK_TRY(vkInvalidateMappedMemoryRanges(ctx->device, 1, &r));
  return RC_OK;
}

typedef struct {
  VkBuffer src, dst;
  VkDeviceSize size;
} copy_job;

static void record_copy(VkCommandBuffer cmd, void *user) {
  const copy_job *job = user;
  VkBufferCopy region = {.size = job->size};
  vkCmdCopyBuffer(cmd, job->src, job->dst, 1, &region);
}

rc_status rc_buffer_upload(rc_vk_ctx *ctx, rc_buffer *dst, const void *data, VkDeviceSize size,
                           bool force_staging) {
  RC_ASSERT(size <= dst->size);
  if (rc_buffer_is_direct(dst, force_staging)) {
    memcpy(dst->memory.mapped, data, size);
    return rc_buffer_flush(ctx, dst);
  }
  rc_buffer staging;
  rc_status st = rc_buffer_create(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, RC_MEM_UPLOAD, &staging);
  if (st == RC_OK) {
    memcpy(staging.memory.mapped, data, size);
    st = rc_buffer_flush(ctx, &staging);
  }
  copy_job job = {staging.buffer, dst->buffer, size};
  if (st == RC_OK) st = rc_vk_submit_and_wait(ctx, record_copy, &job);
  rc_buffer_destroy(ctx, &staging);
  return st;
}
