/* vk_buffer.h: buffers and their memory. Three uses, each with its memory-type
 * preference (docs/design.md §4):
 *   RC_MEM_DEVICE    what the shader reads and writes: DEVICE_LOCAL, preferably not host
 *                    visible (discrete GPUs); lavapipe's single type is all of these;
 *   RC_MEM_UPLOAD    staging for uploads: HOST_VISIBLE, coherent preferred;
 *   RC_MEM_READBACK  staging for readback: HOST_VISIBLE, HOST_CACHED preferred (reads from
 *                    write-combined memory are slow).
 * A DEVICE buffer that happens to be host visible is mapped and used directly unless
 * staging is forced (--staging or VKRAYCAST_FORCE_STAGING=1), which is how the staging
 * path is tested on lavapipe. Non-coherent memory is flushed and invalidated. Memory comes
 * from vk_memory.c's blocks, never one allocation per buffer. */
#ifndef RC_VK_BUFFER_H
#define RC_VK_BUFFER_H

#include "gpu/vk_memory.h"

typedef struct rc_buffer {
  VkBuffer buffer;
  rc_mem_slice memory; /* a slice of a shared block (vk_memory.h); memory.mapped is non-NULL
                          when it is host visible */
  VkDeviceSize size;
} rc_buffer;

rc_status rc_buffer_create(rc_vk_ctx *ctx, VkDeviceSize size, VkBufferUsageFlags usage, rc_mem_use use,
                           rc_buffer *out);
/* Safe on a zeroed or half-built buffer. */
void rc_buffer_destroy(rc_vk_ctx *ctx, rc_buffer *buf);

/* True when the buffer is written and read through its own mapping (no staging copy). */
bool rc_buffer_is_direct(const rc_buffer *buf, bool force_staging);

/* Fills a DEVICE buffer: through its mapping, or through a staging buffer and a copy. */
rc_status rc_buffer_upload(rc_vk_ctx *ctx, rc_buffer *dst, const void *data, VkDeviceSize size,
                           bool force_staging);

/* Makes host writes visible to the device / device writes visible to the host. */
rc_status rc_buffer_flush(rc_vk_ctx *ctx, const rc_buffer *buf);
rc_status rc_buffer_invalidate(rc_vk_ctx *ctx, const rc_buffer *buf);


#endif
