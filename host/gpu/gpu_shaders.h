/* gpu_shaders.h: the SPIR-V modules compiled from shaders/ at build time by
 * glslangValidator and embedded in the binary (no .spv files to find at run time). */
#ifndef RC_GPU_SHADERS_H
#define RC_GPU_SHADERS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct rc_spirv {
  const uint32_t *words;
  size_t size; /* bytes */
} rc_spirv;

/* How the shader reads the scene arrays (shaders/rc_scene_access.glsl), in the order a
 * default render tries them (host/gpu/gpu_render.c). */
typedef enum {
  RC_SCENE_BUFFERS_IMAGE,   /* storage texel buffers, imageLoad (default: inline loads on llvmpipe) */
  RC_SCENE_BUFFERS_TEXEL,   /* uniform texel buffers, texelFetch */
  RC_SCENE_BUFFERS_STORAGE, /* std430 storage buffers */
} rc_scene_buffers;
/* Their names on the command line and in the statistics, in that order; NULL-terminated. */
extern const char *const rc_scene_buffer_names[];

/* The object code a module carries: none of the quadrics' (RC_QUADRICS=0), the quadrics'
 * and composites' (RC_PATCHES=0), or that and the Bezier patches' too. */
typedef enum { RC_SHADER_PLAIN, RC_SHADER_QUADRICS, RC_SHADER_PATCHES } rc_shader_kinds;

/* The arithmetic: f32, f64 (RC_F64: needs shaderFloat64 and shaderInt64), or f32 with
 * every decision certified (RC_CERTIFY, rc_certify.glsl; only that module has its code). */
typedef enum { RC_SHADER_F32, RC_SHADER_F64, RC_SHADER_CERTIFIED } rc_shader_precision;

/* raycast.comp reading the scene arrays as `buffers`, in `precision`, with `kinds`' code. */
rc_spirv rc_shader_raycast(rc_scene_buffers buffers, rc_shader_precision precision, rc_shader_kinds kinds);

#endif
