/* disk_cache.h: the files vkraycast keeps under $XDG_CACHE_HOME/vkraycast/ (else
 * ~/.cache/vkraycast/) between runs: the driver's pipeline cache (gpu_pipeline_cache.h) and
 * the shader module specialized on the host (spirv_cache.h). Each file is a header (a
 * magic naming its kind, the key it was made for, the payload's size and checksum) and a
 * payload. A file is written to a temporary beside it and renamed, so a reader sees a whole
 * file or none; one that is missing, torn, corrupt or made for another key is ignored, and
 * one that cannot be written costs a warning: a cache never fails a render.
 * VKRAYCAST_PIPELINE_CACHE=0 turns every one of them off. */
#ifndef RC_GPU_DISK_CACHE_H
#define RC_GPU_DISK_CACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define RC_DISK_CACHE_MAX_BYTES (256u << 20)

/* FNV-1a, 64-bit, continued from h (start from RC_FNV_OFFSET). */
#define RC_FNV_OFFSET 0xcbf29ce484222325ull
uint64_t rc_fnv1a(uint64_t h, const void *data, size_t n);

/* False when VKRAYCAST_PIPELINE_CACHE=0. */
bool rc_disk_cache_enabled(void);

/* The path of the file named `<key as 16 hex digits><suffix>` in the cache folder; false
 * when there is no folder to keep it in (neither XDG_CACHE_HOME nor HOME absolute). */
bool rc_disk_cache_path(uint64_t key, const char *suffix, char *out, size_t n);

/* The payload of the file at `path` if it is a whole file of this magic (8 bytes) and key
 * (malloc'd, its size in *size), else NULL: no file, or one that exists and is not usable,
 * which rc_disk_cache_ignored reports. `what` names the cache ("pipeline cache", ...). */
void *rc_disk_cache_read(const char *path, const char *magic, uint64_t key, const char *what, size_t *size);

/* Warns that the file at `path` is ignored, and why: for a caller's own checks of a
 * payload rc_disk_cache_read returned. */
void rc_disk_cache_ignored(const char *path, const char *what, const char *why);

/* Writes the file; on failure warns, naming `what` ("pipeline cache", ...). */
void rc_disk_cache_write(const char *path, const char *magic, uint64_t key, const void *data, size_t size,
                         const char *what);

#endif
