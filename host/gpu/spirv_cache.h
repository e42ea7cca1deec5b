/* spirv_cache.h: the module specialized on the host (spirv_specialize.h) kept on disk, one
 * file per module and set of constant values (disk_cache.h; `<key>.spv` beside the
 * pipeline caches), so that a render whose specialization was made before skips SPIRV-Tools:
 * 30-230 ms of CPU per process on the example scenes (docs/performance.md, "Process
 * start-up", finding 11). The key hashes the module, the values, SPIRV-Tools' version and
 * RC_SPIRV_SPECIALIZE_PASSES; a file that does not hold SPIR-V is ignored with a warning
 * and rewritten. */
#ifndef RC_GPU_SPIRV_CACHE_H
#define RC_GPU_SPIRV_CACHE_H

#include "gpu/spirv_specialize.h"

/* rc_spirv_specialize through the cache: *hit says whether the file was used. */
bool rc_spirv_specialize_cached(rc_spirv module, const uint32_t *values, uint32_t count, rc_spirv *out, bool *hit);

#endif
