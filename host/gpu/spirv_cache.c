#include "gpu/spirv_cache.h"

#include <limits.h>
#include <spirv-tools/libspirv.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/disk_cache.h"

#define MAGIC "VKRCSP01"
#define SPIRV_MAGIC 0x07230203u

static uint64_t cache_key(rc_spirv module, const uint32_t *values, uint32_t count) {
  const char *tools = spvSoftwareVersionDetailsString();
  uint32_t passes = RC_SPIRV_SPECIALIZE_PASSES;
  uint64_t h = rc_fnv1a(RC_FNV_OFFSET, MAGIC, 8);
  h = rc_fnv1a(h, tools, strlen(tools));
  h = rc_fnv1a(h, &passes, sizeof passes);
  h = rc_fnv1a(h, &count, sizeof count);
  h = rc_fnv1a(h, values, count * sizeof *values);
  return rc_fnv1a(h, module.words, module.size);
}

bool rc_spirv_specialize_cached(rc_spirv module, const uint32_t *values, uint32_t count, rc_spirv *out, bool *hit) {
  *hit = false;
  char path[PATH_MAX];
  uint64_t key = cache_key(module, values, count);
  bool cached = rc_disk_cache_enabled() && rc_disk_cache_path(key, ".spv", path, sizeof path);
  if (cached) {
    size_t size = 0;
    uint32_t *words = rc_disk_cache_read(path, MAGIC, key, "specialized shader cache", &size);
    if (words && (size % 4 != 0 || words[0] != SPIRV_MAGIC)) {
      rc_disk_cache_ignored(path, "specialized shader cache", "not SPIR-V");
      free(words);
      words = NULL;
    }
    if (words) {
      *out = (rc_spirv){.words = words, .size = size};
      *hit = true;
      return true;
    }
  }
  if (!rc_spirv_specialize(module, values, count, out)) return false;
  if (cached) rc_disk_cache_write(path, MAGIC, key, out->words, out->size, "specialized shader cache");
  return true;
}
