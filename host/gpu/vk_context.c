#include "gpu/vk_context.h"

#include "rc_shared.h"
#include "gpu/vk_memory.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define VALIDATION_LAYER "VK_LAYER_KHRONOS_validation"

const char *rc_vk_result_str(VkResult r) {
  switch (r) {
#define C(x) \
  case x:    \
    return #x;
    C(VK_SUCCESS) C(VK_NOT_READY) C(VK_TIMEOUT) C(VK_INCOMPLETE) C(VK_ERROR_OUT_OF_HOST_MEMORY)
    C(VK_ERROR_OUT_OF_DEVICE_MEMORY) C(VK_ERROR_INITIALIZATION_FAILED) C(VK_ERROR_DEVICE_LOST)
    C(VK_ERROR_MEMORY_MAP_FAILED) C(VK_ERROR_LAYER_NOT_PRESENT) C(VK_ERROR_EXTENSION_NOT_PRESENT)
    C(VK_ERROR_FEATURE_NOT_PRESENT) C(VK_ERROR_INCOMPATIBLE_DRIVER) C(VK_ERROR_TOO_MANY_OBJECTS)
    C(VK_ERROR_FORMAT_NOT_SUPPORTED) C(VK_ERROR_UNKNOWN)
#undef C
    default:
      return "VkResult (unnamed)";
  }
}

const char *rc_vk_device_type_str(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

/* Best-practice advice that cannot be followed in the situation it is given in. Such
 * messages are printed, not counted:
 *  - VK_EXT_debug_utils is for debugging: vkraycast enables it only while validating;
 *  - memory priorities need VK_EXT_memory_priority, used wherever the device has it;
 *  - "pipeline bound twice in the frame": every command buffer binds the one pipeline
 *    once, as Vulkan requires (binding state does not outlive a command buffer), and the
 *    layer counts binds per frame, which only vkQueuePresentKHR ends; a program without a
 *    swapchain is one endless frame. */
static const char *excused(const rc_vk_ctx *ctx, const char *id) {
  if (!id) return NULL;
  if (strcmp(id, "UNASSIGNED-BestPractices-vkCreateInstance-specialuse-extension-debugging") == 0)
    return "VK_EXT_debug_utils is enabled only while validating";
  if (strcmp(id, "UNASSIGNED-BestPractices-AllocateMemory-SetPriority") == 0 && !ctx->memory_priority)
    return "the device has no VK_EXT_memory_priority";
  if (strcmp(id, "UNASSIGNED-BestPractices-Pipeline-SortAndBind") == 0)
    return "one bind per command buffer; without a swapchain the frame never ends";
  return NULL;
}

/* Counts every warning and error of the validation and performance kinds: a command run
 * with validation fails on any of them, best-practice checks included when they are
 * enabled (VK_LAYER_ENABLES, docs/porting.md). */
static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *data,
                                                 void *user) {
  rc_vk_ctx *ctx = user;
  bool perf = (type & VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT) != 0;
  bool kind = perf || (type & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT);
  if (!kind || severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  const char *why = excused(ctx, data->pMessageIdName);
  if (why) {
    fprintf(stderr, "vkraycast: validation (not counted: %s): %s\n", why, data->pMessage);
  } else {
    ctx->validation_messages++;
    fprintf(stderr, "vkraycast: validation%s: %s\n", perf ? " (performance)" : "", data->pMessage);
  }
  return VK_FALSE;
}

static bool validation_requested(void) {
  const char *v = getenv("VKRAYCAST_VALIDATION");
  return v && strcmp(v, "0") != 0 && v[0] != '\0';
}

/* Whether the instance (pd VK_NULL_HANDLE) or the device offers extension `name`. */
static bool has_extension(VkPhysicalDevice pd, const char *name) {
  uint32_t n = 0;
  VkResult r = pd ? vkEnumerateDeviceExtensionProperties(pd, NULL, &n, NULL)
                  : vkEnumerateInstanceExtensionProperties(NULL, &n, NULL);
  if (r != VK_SUCCESS) return false;
  VkExtensionProperties *ext = calloc(n ? n : 1, sizeof *ext);
  if (!ext) return false;
  r = pd ? vkEnumerateDeviceExtensionProperties(pd, NULL, &n, ext) : vkEnumerateInstanceExtensionProperties(NULL, &n, ext);
  bool found = false;
  for (uint32_t i = 0; r == VK_SUCCESS && i < n && !found; i++) found = strcmp(ext[i].extensionName, name) == 0;
  free(ext);
  return found;
}

static rc_status create_instance(rc_vk_ctx *ctx) {
  ctx->validation = validation_requested();
  if (ctx->validation) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, NULL);
    VkLayerProperties *layers = calloc(n ? n : 1, sizeof *layers);
    if (!layers) return RC_ERR_VULKAN;
    vkEnumerateInstanceLayerProperties(&n, layers);
    bool found = false;
    for (uint32_t i = 0; i < n; i++) found |= strcmp(layers[i].layerName, VALIDATION_LAYER) == 0;
    free(layers);
    if (!found) {
      rc_error("VKRAYCAST_VALIDATION is set but %s is not installed (Debian: vulkan-validationlayers)",
               VALIDATION_LAYER);
      return RC_ERR_DEVICE;
    }
  }
  VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                           .pApplicationName = "vkraycast",
                           .apiVersion = VK_API_VERSION_1_1};
  VkDebugUtilsMessengerCreateInfoEXT dbg = {
      .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
      .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
      .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
      .pfnUserCallback = on_message,
      .pUserData = ctx};
  const char *layer = VALIDATION_LAYER;
  const char *ext[2];
  uint32_t ext_count = 0;
  if (ctx->validation) ext[ext_count++] = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  /* MoltenVK (Apple) is a portability driver: loaders since 1.3.216 list such devices only
   * to an instance that asks for them (docs/porting.md). */
  bool portability = has_extension(VK_NULL_HANDLE, VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
  if (portability) ext[ext_count++] = VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME;
  VkInstanceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                               .pNext = ctx->validation ? &dbg : NULL,
                               .flags = portability ? VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR : 0,
                               .pApplicationInfo = &app,
                               .enabledLayerCount = ctx->validation ? 1 : 0,
                               .ppEnabledLayerNames = &layer,
                               .enabledExtensionCount = ext_count,
                               .ppEnabledExtensionNames = ext};
  VkResult r = vkCreateInstance(&info, NULL, &ctx->instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED) {
    rc_error("no Vulkan driver found (%s); install mesa-vulkan-drivers for lavapipe, or a GPU driver",
             rc_vk_result_str(r));
    return RC_ERR_DEVICE;
  }
  RC_VK_TRY(r);
  if (ctx->validation) {
    PFN_vkCreateDebugUtilsMessengerEXT create = (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
        ctx->instance, "vkCreateDebugUtilsMessengerEXT");
    if (!create) return RC_ERR_VULKAN;
    RC_VK_TRY(create(ctx->instance, &dbg, NULL, &ctx->messenger));
  }
  return RC_OK;
}

static int type_rank(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

/* The first queue family with compute; -1 if none. */
static int compute_family(VkPhysicalDevice pd, uint32_t *timestamp_bits) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, NULL);
  VkQueueFamilyProperties fam[32];
  if (n > 32) n = 32;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, fam);
  for (uint32_t i = 0; i < n; i++) {
    if (fam[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
      if (timestamp_bits) *timestamp_bits = fam[i].timestampValidBits;
      return (int)i;
    }
  }
  return -1;
}

static rc_status enumerate(VkInstance inst, VkPhysicalDevice **out, uint32_t *count) {
  *count = 0;
  RC_VK_TRY(vkEnumeratePhysicalDevices(inst, count, NULL));
  if (*count == 0) {
    rc_error("no Vulkan device found (for CPU rendering install mesa-vulkan-drivers and select "
             "lavapipe with VK_DRIVER_FILES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json)");
    return RC_ERR_DEVICE;
  }
  *out = calloc(*count, sizeof **out);
  if (!*out) return RC_ERR_VULKAN;
  RC_VK_TRY(vkEnumeratePhysicalDevices(inst, count, *out));
  return RC_OK;
}

static void driver_props(VkPhysicalDevice pd, const VkPhysicalDeviceProperties *p,
                         VkPhysicalDeviceDriverProperties *drv) {
  memset(drv, 0, sizeof *drv);
  if (p->apiVersion < VK_API_VERSION_1_2) return;
  drv->sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
  VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = drv};
  vkGetPhysicalDeviceProperties2(pd, &p2);
}

void rc_vk_apply_minimum_limits(VkPhysicalDeviceLimits *l, VkPhysicalDeviceFeatures *f) {
  /* Vulkan 1.1, "Required Limits": the least a conformant device may report (for the
   * alignments, the most). */
#define AT_MOST(field, v) l->field = l->field < (v) ? l->field : (v)
#define AT_LEAST(field, v) l->field = l->field > (v) ? l->field : (v)
  AT_MOST(maxTexelBufferElements, 65536u);
  AT_MOST(maxUniformBufferRange, 16384u);
  AT_MOST(maxStorageBufferRange, 1u << 27);
  AT_MOST(maxPushConstantsSize, 128u);
  AT_MOST(maxMemoryAllocationCount, 4096u);
  AT_MOST(maxBoundDescriptorSets, 4u);
  AT_MOST(maxPerStageDescriptorUniformBuffers, 12u);
  AT_MOST(maxPerStageDescriptorStorageBuffers, 4u);
  AT_MOST(maxPerStageDescriptorSampledImages, 16u);
  AT_MOST(maxPerStageDescriptorStorageImages, 4u);
  AT_MOST(maxPerStageResources, 128u);
  AT_MOST(maxDescriptorSetUniformBuffers, 72u);
  AT_MOST(maxDescriptorSetStorageBuffers, 24u);
  AT_MOST(maxDescriptorSetSampledImages, 96u);
  AT_MOST(maxDescriptorSetStorageImages, 24u);
  AT_MOST(maxComputeSharedMemorySize, 16384u);
  AT_MOST(maxComputeWorkGroupInvocations, 128u);
  AT_MOST(maxComputeWorkGroupSize[0], 128u);
  AT_MOST(maxComputeWorkGroupSize[1], 128u);
  AT_MOST(maxComputeWorkGroupSize[2], 64u);
  for (int i = 0; i < 3; i++) AT_MOST(maxComputeWorkGroupCount[i], 65535u);
  AT_LEAST(minTexelBufferOffsetAlignment, 256u);
  AT_LEAST(minUniformBufferOffsetAlignment, 256u);
  AT_LEAST(minStorageBufferOffsetAlignment, 256u);
  AT_LEAST(nonCoherentAtomSize, 256u);
#undef AT_MOST
#undef AT_LEAST
  if (f) f->shaderFloat64 = f->shaderInt64 = VK_FALSE;
}

/* VKRAYCAST_DEVICE_LIMITS: unset, or "minimum". */
static rc_status limits_requested(bool *minimum) {
  const char *v = getenv("VKRAYCAST_DEVICE_LIMITS");
  *minimum = v && strcmp(v, "minimum") == 0;
  if (v && v[0] && !*minimum) {
    rc_error("VKRAYCAST_DEVICE_LIMITS=%s: the only value is `minimum` (Vulkan 1.1's required limits)", v);
    return RC_ERR_USAGE;
  }
  return RC_OK;
}

static rc_status pick_device(rc_vk_ctx *ctx, int wanted) {
  VkPhysicalDevice *devs = NULL;
  uint32_t n = 0;
  rc_status st = enumerate(ctx->instance, &devs, &n);
  if (st != RC_OK) return st;
  int best = -1, best_rank = -1;
  if (wanted >= 0) {
    if ((uint32_t)wanted >= n) {
      rc_error("--device %d: there %s %u Vulkan device%s (see `vkraycast devices`)", wanted,
               n == 1 ? "is" : "are", n, n == 1 ? "" : "s");
      free(devs);
      return RC_ERR_USAGE;
    }
    best = wanted;
    if (compute_family(devs[best], NULL) < 0) {
      rc_error("--device %d has no compute queue", wanted);
      free(devs);
      return RC_ERR_DEVICE;
    }
  } else {
    for (uint32_t i = 0; i < n; i++) {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(devs[i], &p);
      int rank = type_rank(p.deviceType);
      if (compute_family(devs[i], NULL) >= 0 && p.apiVersion >= VK_API_VERSION_1_1 && rank > best_rank) {
        best = (int)i;
        best_rank = rank;
      }
    }
    if (best < 0) {
      rc_error("no Vulkan 1.1 device with a compute queue among %u device%s", n, n == 1 ? "" : "s");
      free(devs);
      return RC_ERR_DEVICE;
    }
  }
  ctx->physical = devs[best];
  ctx->device_index = (uint32_t)best;
  free(devs);
  vkGetPhysicalDeviceProperties(ctx->physical, &ctx->props);
  driver_props(ctx->physical, &ctx->props, &ctx->driver);
  vkGetPhysicalDeviceMemoryProperties(ctx->physical, &ctx->memory);
  ctx->queue_family = (uint32_t)compute_family(ctx->physical, &ctx->timestamp_bits);
  VkPhysicalDeviceSubgroupProperties sg = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &sg};
  vkGetPhysicalDeviceProperties2(ctx->physical, &p2);
  ctx->subgroup_size = sg.subgroupSize ? sg.subgroupSize : 1;
  ctx->llvmpipe = ctx->driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE ||
                  strstr(ctx->props.deviceName, "llvmpipe") != NULL;
  if (!ctx->props.limits.timestampComputeAndGraphics) ctx->timestamp_bits = 0;
  return RC_OK;
}

rc_status rc_vk_create(const rc_vk_options *opts, rc_vk_ctx *ctx) {
  memset(ctx, 0, sizeof *ctx);
  rc_status st = limits_requested(&ctx->minimum_limits);
  if (st == RC_OK) st = create_instance(ctx);
  if (st == RC_OK) st = pick_device(ctx, opts->device_index);
  if (st != RC_OK) return st;

  VkPhysicalDeviceFeatures supported;
  vkGetPhysicalDeviceFeatures(ctx->physical, &supported);
  if (ctx->minimum_limits) rc_vk_apply_minimum_limits(&ctx->props.limits, &supported);
  VkPhysicalDeviceFeatures enabled = {0};
  enabled.shaderFloat64 = supported.shaderFloat64;
  enabled.shaderInt64 = supported.shaderInt64 && supported.shaderFloat64;
  ctx->float64 = enabled.shaderFloat64 && enabled.shaderInt64;

  float priority = 1.0f;
  VkDeviceQueueCreateInfo q = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                               .queueFamilyIndex = ctx->queue_family,
                               .queueCount = 1,
                               .pQueuePriorities = &priority};
  /* Memory priorities let a driver keep the scene in device memory when memory runs short
   * (NVIDIA's best practices ask for them). */
  VkPhysicalDeviceMemoryPriorityFeaturesEXT prio = {
      .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PRIORITY_FEATURES_EXT};
  const char *prio_ext = VK_EXT_MEMORY_PRIORITY_EXTENSION_NAME;
  if (!ctx->minimum_limits && has_extension(ctx->physical, prio_ext)) {
    VkPhysicalDeviceFeatures2 f2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &prio};
    vkGetPhysicalDeviceFeatures2(ctx->physical, &f2);
    ctx->memory_priority = prio.memoryPriority;
  }
  /* Pageable device-local memory (which needs the priorities) lets the driver move the
   * lowest-priority allocations out of VRAM under pressure rather than fail; NVIDIA's best
   * practices ask for it wherever the driver offers it (seen on an H100, docs/porting.md). */
  VkPhysicalDevicePageableDeviceLocalMemoryFeaturesEXT pageable = {
      .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PAGEABLE_DEVICE_LOCAL_MEMORY_FEATURES_EXT};
  const char *pageable_ext = VK_EXT_PAGEABLE_DEVICE_LOCAL_MEMORY_EXTENSION_NAME;
  bool pageable_memory = false;
  if (ctx->memory_priority && has_extension(ctx->physical, pageable_ext)) {
    VkPhysicalDeviceFeatures2 f2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &pageable};
    vkGetPhysicalDeviceFeatures2(ctx->physical, &f2);
    pageable_memory = pageable.pageableDeviceLocalMemory;
  }
  if (pageable_memory) prio.pNext = &pageable;
  const char *dev_ext[3];
  uint32_t dev_ext_count = 0;
  if (ctx->memory_priority) dev_ext[dev_ext_count++] = prio_ext;
  if (pageable_memory) dev_ext[dev_ext_count++] = pageable_ext;
  /* The specification requires it enabled wherever a device lists it (MoltenVK). */
  if (has_extension(ctx->physical, "VK_KHR_portability_subset")) dev_ext[dev_ext_count++] = "VK_KHR_portability_subset";
  VkDeviceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                             .pNext = ctx->memory_priority ? &prio : NULL,
                             .enabledExtensionCount = dev_ext_count,
                             .ppEnabledExtensionNames = dev_ext,
                             .queueCreateInfoCount = 1,
                             .pQueueCreateInfos = &q,
                             .pEnabledFeatures = &enabled};
  RC_VK_TRY(vkCreateDevice(ctx->physical, &info, NULL, &ctx->device));
  if (pageable_memory)
    ctx->set_memory_priority =
        (PFN_vkSetDeviceMemoryPriorityEXT)vkGetDeviceProcAddr(ctx->device, "vkSetDeviceMemoryPriorityEXT");
  vkGetDeviceQueue(ctx->device, ctx->queue_family, 0, &ctx->queue);
  VkCommandPoolCreateInfo pool = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
                                  .queueFamilyIndex = ctx->queue_family};
  RC_VK_TRY(vkCreateCommandPool(ctx->device, &pool, NULL, &ctx->pool));
  return RC_OK;
}

rc_status rc_vk_destroy(rc_vk_ctx *ctx) {
  if (ctx->device) {
    vkDeviceWaitIdle(ctx->device);
    vkDestroyCommandPool(ctx->device, ctx->pool, NULL);
    rc_mem_release_all(ctx);
    vkDestroyDevice(ctx->device, NULL);
  }
  if (ctx->messenger) {
    PFN_vkDestroyDebugUtilsMessengerEXT destroy = (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
        ctx->instance, "vkDestroyDebugUtilsMessengerEXT");
    if (destroy) destroy(ctx->instance, ctx->messenger, NULL);
  }
  if (ctx->instance) vkDestroyInstance(ctx->instance, NULL);
  uint32_t msgs = ctx->validation_messages;
  memset(ctx, 0, sizeof *ctx);
  if (msgs) {
    rc_error("Vulkan validation reported %u message%s", msgs, msgs == 1 ? "" : "s");
    return RC_ERR_VALIDATION;
  }
  return RC_OK;
}

rc_status rc_vk_list_devices(void) {
  rc_vk_ctx ctx = {0};
  rc_status st = create_instance(&ctx);
  VkPhysicalDevice *devs = NULL;
  uint32_t n = 0;
  if (st == RC_OK) st = enumerate(ctx.instance, &devs, &n);
  if (st == RC_OK) {
    printf("%-5s %-40s %-10s %-28s %-8s %s\n", "index", "name", "type", "driver", "api", "float64");
    for (uint32_t i = 0; i < n; i++) {
      VkPhysicalDeviceProperties p;
      VkPhysicalDeviceFeatures f;
      VkPhysicalDeviceDriverProperties drv;
      vkGetPhysicalDeviceProperties(devs[i], &p);
      vkGetPhysicalDeviceFeatures(devs[i], &f);
      driver_props(devs[i], &p, &drv);
      char driver[600], api[32];
      snprintf(driver, sizeof driver, "%s %s", drv.driverName[0] ? drv.driverName : "?", drv.driverInfo);
      snprintf(api, sizeof api, "%u.%u.%u", VK_API_VERSION_MAJOR(p.apiVersion),
               VK_API_VERSION_MINOR(p.apiVersion), VK_API_VERSION_PATCH(p.apiVersion));
      printf("%-5u %-40s %-10s %-28s %-8s %s\n", i, p.deviceName, rc_vk_device_type_str(p.deviceType),
             driver, api, f.shaderFloat64 ? "yes" : "no");
    }
  }
  free(devs);
  rc_status st2 = rc_vk_destroy(&ctx);
  return st != RC_OK ? st : st2;
}

rc_status rc_vk_submit_and_wait(rc_vk_ctx *ctx, void (*record)(VkCommandBuffer, void *), void *user) {
  VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                    .commandPool = ctx->pool,
                                    .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                    .commandBufferCount = 1};
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  RC_VK_TRY(vkAllocateCommandBuffers(ctx->device, &ai, &cmd));
  VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                 .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  VkResult r = vkBeginCommandBuffer(cmd, &bi);
  if (r == VK_SUCCESS) {
    record(cmd, user);
    r = vkEndCommandBuffer(cmd);
  }
  VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  if (r == VK_SUCCESS) r = vkCreateFence(ctx->device, &fi, NULL, &fence);
  VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
  if (r == VK_SUCCESS) r = vkQueueSubmit(ctx->queue, 1, &si, fence);
  if (r == VK_SUCCESS) r = vkWaitForFences(ctx->device, 1, &fence, VK_TRUE, UINT64_MAX);
  vkDestroyFence(ctx->device, fence, NULL);
  vkFreeCommandBuffers(ctx->device, ctx->pool, 1, &cmd);
  if (r != VK_SUCCESS) {
    rc_error("command submission failed: %s", rc_vk_result_str(r));
    return RC_ERR_VULKAN;
  }
  return RC_OK;
}
