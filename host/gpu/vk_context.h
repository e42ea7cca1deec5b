/* vk_context.h: instance, physical device, logical device and queue: the objects that
 * live as long as the process. Validation (VK_LAYER_KHRONOS_validation plus a messenger
 * that counts VALIDATION-type warnings and errors) is on when VKRAYCAST_VALIDATION=1;
 * the test suite always sets it, and a counted message fails the command. */
#ifndef RC_VK_CONTEXT_H
#define RC_VK_CONTEXT_H

#include <vulkan/vulkan.h>

#include "base/rc_base.h"

typedef struct rc_vk_ctx {
  VkInstance instance;
  VkDebugUtilsMessengerEXT messenger;
  VkPhysicalDevice physical;
  VkDevice device;
  VkQueue queue;
  uint32_t queue_family;
  VkCommandPool pool; /* transient command buffers for uploads (a renderer has its own pool) */
  uint32_t device_index;
  VkPhysicalDeviceProperties props;
  VkPhysicalDeviceDriverProperties driver; /* zeroed where the device lacks Vulkan 1.2 */
  VkPhysicalDeviceMemoryProperties memory;
  bool float64;            /* shaderFloat64 supported and enabled */
  uint32_t timestamp_bits; /* timestampValidBits of the queue family; 0 = no timestamps */
  uint32_t subgroup_size;
  bool llvmpipe;           /* Mesa's CPU driver, with its loop-iteration cap */
  bool memory_priority;      /* VK_EXT_memory_priority enabled */
  /* vkSetDeviceMemoryPriorityEXT where VK_EXT_pageable_device_local_memory is enabled,
   * else NULL */
  PFN_vkSetDeviceMemoryPriorityEXT set_memory_priority;
  bool minimum_limits;       /* VKRAYCAST_DEVICE_LIMITS=minimum (see below) */
  struct rc_mem_block *blocks; /* device memory (vk_memory.h) */
  bool validation;
  uint32_t validation_messages; /* validation and performance warnings and errors seen */
} rc_vk_ctx;

typedef struct rc_vk_options {
  int device_index; /* -1: pick discrete > integrated > virtual > CPU */
} rc_vk_options;

rc_status rc_vk_create(const rc_vk_options *opts, rc_vk_ctx *ctx);
/* VKRAYCAST_DEVICE_LIMITS=minimum, a test switch: the host believes the device has only
 * what Vulkan 1.1 guarantees (docs/porting.md): the limits below, no shaderFloat64 and no
 * shaderInt64. Everything the host decides from limits (buffer kinds, refusals, workgroup
 * size, --precision auto) then takes the path a minimal GPU would force. */
void rc_vk_apply_minimum_limits(VkPhysicalDeviceLimits *limits, VkPhysicalDeviceFeatures *features);

/* Destroys everything; returns RC_ERR_VALIDATION when validation reported messages. */
rc_status rc_vk_destroy(rc_vk_ctx *ctx);

/* Prints the physical devices (index, name, type, driver, API version, shaderFloat64). */
rc_status rc_vk_list_devices(void);

/* Records a command buffer from the context's pool with `record`, submits it to the
 * context's queue and waits for it (one-off work: uploads through staging). */
rc_status rc_vk_submit_and_wait(rc_vk_ctx *ctx, void (*record)(VkCommandBuffer cmd, void *user), void *user);

const char *rc_vk_result_str(VkResult r);
const char *rc_vk_device_type_str(VkPhysicalDeviceType t);

/* Logs the failing call with file, line and the VkResult, and returns RC_ERR_VULKAN. */
#define RC_VK_TRY(call)                                                                    \
  do {                                                                                     \
    VkResult rc_vk_res_ = (call);                                                          \
    if (rc_vk_res_ != VK_SUCCESS) {                                                        \
      rc_error("%s:%d: %s failed: %s", __FILE__, __LINE__, #call, rc_vk_result_str(rc_vk_res_)); \
      return RC_ERR_VULKAN;                                                                \
    }                                                                                      \
  } while (0)

#endif
