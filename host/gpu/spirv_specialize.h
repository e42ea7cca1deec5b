/* spirv_specialize.h: raycast.comp's specialization constants applied on the host, by
 * SPIRV-Tools' optimizer, before the driver sees the module.
 *
 * Why: a driver may compile the whole module and specialize after; lavapipe (Mesa 22.3)
 * does. It translates every function of the module into NIR, inlines them at every call
 * site and only then folds the constants and drops the dead branches: for a 72 x 48
 * render of the showcase, 236-397 ms of vkCreateComputePipelines against 86-131 ms for
 * the same module with its constants frozen and its dead code gone (docs/performance.md,
 * "Process start-up", finding 10). The passes only substitute the constants' values and
 * remove the code they make unreachable or unused, so the specialized module computes what
 * the driver's specialization of the original would: ctest's spec_constants compares the
 * two (`--spec-constants host|driver`) bit for bit. After that, the function-local
 * variables glslang makes (a copy of every argument, every local) become SSA values:
 * lavapipe's own lowering of them cost more than SPIRV-Tools' (finding 11). */
#ifndef RC_SPIRV_SPECIALIZE_H
#define RC_SPIRV_SPECIALIZE_H

#include "gpu/gpu_shaders.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Names the pass list below for the on-disk cache's key (spirv_cache.h): change it with
 * the passes. */
#define RC_SPIRV_SPECIALIZE_PASSES 2u

/* `module` with spec constant i (SpecId i, a 32-bit scalar: uint, bool as VkBool32, or
 * float as its bits) set to values[i] and made a constant, and the code that no longer
 * runs removed. On success *out holds malloc'd words (free(out->words)); false where the
 * optimizer refused the module, and the caller hands the driver the original. */
bool rc_spirv_specialize(rc_spirv module, const uint32_t *values, uint32_t count, rc_spirv *out);

#ifdef __cplusplus
}
#endif

#endif
