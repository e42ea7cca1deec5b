/* gpu_pipeline.c: the compute pipeline, specialized to the scene (rc_shared.h, RC_SPEC_*:
 * what the scene lacks is compiled out), and the descriptor set that binds the scene
 * arrays and the output buffers to it. */
#include <stdlib.h>
#include <string.h>

#include "gpu/gpu_pipeline_cache.h"
#include "gpu/gpu_renderer.h"
#include "gpu/gpu_shaders.h"
#include "gpu/spirv_cache.h"

/* The descriptor set layout (the scene arrays as the chosen buffer kind) and the pipeline
 * layout with the push constants. */
static rc_status create_layouts(rc_gpu_renderer *r) {
  rc_vk_ctx *ctx = r->ctx;
  VkDescriptorType array_type = rc_gpu_kind_descriptor(r->opts.scene_buffers);
  VkDescriptorSetLayoutBinding b[RC_BINDING_COUNT];
  for (uint32_t i = 0; i < RC_BINDING_COUNT; i++) {
    b[i] = (VkDescriptorSetLayoutBinding){.binding = i,
                                          .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                          .descriptorCount = 1,
                                          .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT};
  }
  b[RC_BINDING_FRAME].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  for (int i = 0; i < SCENE_ARRAYS; i++) b[rc_gpu_array_bindings[i]].descriptorType = array_type;

  VkDescriptorSetLayoutCreateInfo sli = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                         .bindingCount = RC_BINDING_COUNT,
                                         .pBindings = b};
  RC_VK_TRY(vkCreateDescriptorSetLayout(ctx->device, &sli, NULL, &r->set_layout));
  VkPushConstantRange pcr = {.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .size = sizeof(packed_push)};
  VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                    .setLayoutCount = 1,
                                    .pSetLayouts = &r->set_layout,
                                    .pushConstantRangeCount = 1,
                                    .pPushConstantRanges = &pcr};
  RC_VK_TRY(vkCreatePipelineLayout(ctx->device, &pli, NULL, &r->pipeline_layout));
  return RC_OK;
}

/* The specialization constants, by id (rc_shared.h, RC_SPEC_*): the workgroup, the loop
 * budget, the formulas, and the scene's features, so that what the scene lacks is
 * compiled out; a generic pipeline reads the features from the frame instead. A bool is 4
 * bytes (VkBool32), a float its 4 bytes. */
static void specialization(const rc_gpu_renderer *r, uint32_t v[RC_SPEC_COUNT]) {
  const packed_frame *f = &r->frame;
  bool generic = r->opts.generic_pipeline;
  /* Only the epsilon and t-min strategies read the offset; for the others a scene's own
   * (which packing units scale: numerics.md §1) would make a pipeline of its own for
   * nothing, so they get the default, the shader's too. */
  const bool offset_used = f->offset_strategy == RC_OFFSET_EPSILON || f->offset_strategy == RC_OFFSET_T_MIN;
  float epsilon = offset_used ? f->offset_epsilon : (float)RC_OFFSET_EPSILON_DEFAULT;
  v[RC_SPEC_LOCAL_SIZE_X] = r->local_x;
  v[RC_SPEC_LOCAL_SIZE_Y] = r->local_y;
  v[RC_SPEC_LOOP_BUDGET] = r->budget;
  v[RC_SPEC_AOV] = r->opts.aov ? VK_TRUE : VK_FALSE;
  v[RC_SPEC_BVH] = r->opts.bvh_depth ? VK_TRUE : VK_FALSE;
  v[RC_SPEC_SPHERE_FORMULA] = f->sphere_formula;
  v[RC_SPEC_TRIANGLE_FORMULA] = f->triangle_formula;
  v[RC_SPEC_OFFSET_STRATEGY] = f->offset_strategy;
  memcpy(&v[RC_SPEC_OFFSET_EPSILON], &epsilon, sizeof epsilon);
  /* A plane is tested by the quadric test only in brute force: with the BVH, test_planes
   * tests it (rc_bvh.glsl), so a scene whose quadrics are all planes leaves the quadric
   * test out of the leaf loop. */
  const bool quadric_test = f->quadric_count > f->plane_count || (f->plane_count && !r->opts.bvh_depth);
  v[RC_SPEC_KINDS] = generic ? RC_KIND_ALL
                             : (f->sphere_count ? RC_KIND_SPHERES : 0) | (f->triangle_count ? RC_KIND_TRIANGLES : 0) |
                                   (quadric_test ? RC_KIND_QUADRICS : 0) |
                                   (f->csg_count ? RC_KIND_CSG : 0) |
                                   (f->plane_count ? RC_KIND_PLANES : 0) | (r->mesh_operands ? RC_KIND_CSG_MESHES : 0) |
                                   (r->sphere_transforms ? RC_KIND_SPHERE_TRANSFORMS : 0) |
                                   (r->vertex_normals ? RC_KIND_VERTEX_NORMALS : 0) |
                                   (r->one_sided_triangles ? RC_KIND_ONE_SIDED_TRIANGLES : 0) |
                                   (r->textures ? RC_KIND_TEXTURES : 0) | (r->patches ? RC_KIND_PATCHES : 0) |
                                   (r->opts.bvh_depth && (f->loose_kinds & RC_KIND_QUADRICS) ? RC_KIND_LOOSE_QUADRICS : 0);
  v[RC_SPEC_LIGHT_COUNT] = generic ? RC_LIGHTS_FROM_FRAME : f->light_count;
  v[RC_SPEC_SHADOWS] = generic ? RC_SHADOWS_FROM_FRAME : f->shadows;
  v[RC_SPEC_SPECULAR_MODEL] = generic ? RC_SPECULAR_FROM_FRAME : f->specular_model;
  v[RC_SPEC_REFLECTION_DEPTH] = generic ? RC_DEPTH_FROM_FRAME : f->reflection_depth;
  /* One sample a pixel has code of its own (no random offsets: rc_random.glsl); any other
   * count is read from the frame, so that the same scene at another count (tradeoff's spp
   * sweep, a test's --spp) finds its pipeline in the driver's cache instead of compiling
   * one: the count is only the sample loop's bound, read once per pixel. */
  v[RC_SPEC_SAMPLES] = generic || f->samples_per_pixel != 1 ? RC_SAMPLES_FROM_FRAME : 1;
  v[RC_SPEC_LIGHT_PASSES] = r->light_passes ? VK_TRUE : VK_FALSE;
  v[RC_SPEC_LEVELS] = r->opts.levels ? 1 + r->opts.level_curve : 0;
}

rc_status rc_gpu_create_pipeline(rc_gpu_renderer *r, rc_gpu_stats *stats) {
  rc_vk_ctx *ctx = r->ctx;
  RC_TRY(create_layouts(r));

  /* The module without quadric code where the scene has none, and without patch code where
   * it has no patch (unless the pipeline is the generic one): lavapipe compiles the whole
   * module before specializing it. */
  rc_shader_kinds kinds = r->opts.generic_pipeline || r->frame.patch_count ? RC_SHADER_PATCHES
                          : r->frame.quadric_count || r->frame.csg_count  ? RC_SHADER_QUADRICS
                                                                           : RC_SHADER_PLAIN;
  rc_shader_precision precision = r->frame.certify != RC_CERTIFY_OFF ? RC_SHADER_CERTIFIED
                                  : r->opts.f64                     ? RC_SHADER_F64
                                                                    : RC_SHADER_F32;
  rc_spirv code = rc_shader_raycast(r->opts.scene_buffers, precision, kinds);
  uint32_t spec_values[RC_SPEC_COUNT];
  VkSpecializationMapEntry entries[RC_SPEC_COUNT];
  specialization(r, spec_values);
  /* The constants applied here (spirv_specialize.h), or left to the driver. */
  rc_spirv specialized = {0};
  double t0 = rc_now_ms();
  stats->host_specialized = !r->opts.driver_spec_constants &&
                            rc_spirv_specialize_cached(code, spec_values, RC_SPEC_COUNT, &specialized,
                                                       &stats->spec_cache_hit);
  stats->specialize_ms = rc_now_ms() - t0;
  if (stats->host_specialized) code = specialized;
  VkShaderModuleCreateInfo smi = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                  .codeSize = code.size,
                                  .pCode = code.words};
  VkShaderModule module;
  VkResult made = vkCreateShaderModule(ctx->device, &smi, NULL, &module);
  if (made != VK_SUCCESS) {
    free((void *)specialized.words);
    RC_VK_TRY(made);
  }
  for (uint32_t i = 0; i < RC_SPEC_COUNT; i++) entries[i] = (VkSpecializationMapEntry){i, 4 * i, 4};
  VkSpecializationInfo spec = {.mapEntryCount = RC_SPEC_COUNT, .pMapEntries = entries, .dataSize = sizeof spec_values,
                               .pData = spec_values};
  VkComputePipelineCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
                                    .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                                              .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                                              .module = module,
                                              .pName = "main",
                                              .pSpecializationInfo = stats->host_specialized ? NULL : &spec},
                                    .layout = r->pipeline_layout};
  rc_pipeline_cache cache;
  rc_pipeline_cache_open(ctx, code, &cache);
  stats->pipeline_cache_hit = cache.loaded;
  VkResult res = vkCreateComputePipelines(ctx->device, cache.cache, 1, &ci, NULL, &r->pipeline);
  if (res == VK_SUCCESS) rc_pipeline_cache_close(ctx, &cache);
  else if (cache.cache) vkDestroyPipelineCache(ctx->device, cache.cache, NULL);
  vkDestroyShaderModule(ctx->device, module, NULL);
  free((void *)specialized.words);
  if (res == VK_SUCCESS && rc_fault("pipeline")) {
    vkDestroyPipeline(ctx->device, r->pipeline, NULL);
    r->pipeline = VK_NULL_HANDLE;
    res = VK_ERROR_INITIALIZATION_FAILED;
  }
  if (res != VK_SUCCESS) {
    rc_error("the device could not create the compute pipeline (%s); its driver may not support this shader",
             rc_vk_result_str(res));
    return RC_ERR_VULKAN;
  }
  return RC_OK;
}


rc_status rc_gpu_create_descriptors(rc_gpu_renderer *r) {
  rc_vk_ctx *ctx = r->ctx;
  bool texel = rc_gpu_is_texel_kind(r->opts.scene_buffers);
  VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                   {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, texel ? 3 : 3 + SCENE_ARRAYS},
                                   {rc_gpu_kind_descriptor(r->opts.scene_buffers), SCENE_ARRAYS}};
  VkDescriptorPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                   .maxSets = 1,
                                   .poolSizeCount = texel ? 3 : 2,
                                   .pPoolSizes = sizes};
  RC_VK_TRY(vkCreateDescriptorPool(ctx->device, &pi, NULL, &r->descriptor_pool));
  VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                    .descriptorPool = r->descriptor_pool,
                                    .descriptorSetCount = 1,
                                    .pSetLayouts = &r->set_layout};
  RC_VK_TRY(vkAllocateDescriptorSets(ctx->device, &ai, &r->set));

  VkDescriptorBufferInfo infos[RC_BINDING_COUNT] = {0};
  VkWriteDescriptorSet w[RC_BINDING_COUNT];
  const rc_buffer *bufs[RC_BINDING_COUNT] = {0};
  bufs[RC_BINDING_FRAME] = &r->frame_buf;
  bufs[RC_BINDING_ACCUM] = &r->accum;
  bufs[RC_BINDING_STATUS] = &r->status;
  bufs[RC_BINDING_AOV] = &r->aov;
  for (int i = 0; i < SCENE_ARRAYS; i++) bufs[rc_gpu_array_bindings[i]] = &r->arrays[i];
  for (uint32_t i = 0; i < RC_BINDING_COUNT; i++) {
    infos[i] = (VkDescriptorBufferInfo){.buffer = bufs[i]->buffer, .range = VK_WHOLE_SIZE};
    w[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                  .dstSet = r->set,
                                  .dstBinding = i,
                                  .descriptorCount = 1,
                                  .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                  .pBufferInfo = &infos[i]};
  }
  w[RC_BINDING_FRAME].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  for (int i = 0; i < SCENE_ARRAYS; i++) {
    VkWriteDescriptorSet *x = &w[rc_gpu_array_bindings[i]];
    if (texel) {
      x->descriptorType = rc_gpu_kind_descriptor(r->opts.scene_buffers);
      x->pBufferInfo = NULL;
      x->pTexelBufferView = &r->views[i];
    }
  }
  vkUpdateDescriptorSets(ctx->device, RC_BINDING_COUNT, w, 0, NULL);
  return RC_OK;
}
