#include "gpu/gpu_pipeline_cache.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The file: this header, then the driver's cache data (which starts with Vulkan's own
 * VkPipelineCacheHeaderVersionOne). The checksum catches a torn or corrupted file before
 * the driver sees it; the key catches a file copied from another device. */
#define MAGIC "VKRCPC01"
typedef struct {
  char magic[8];
  uint64_t key;
  uint64_t size;     /* bytes of driver data */
  uint64_t checksum; /* FNV-1a of the driver data */
} file_header;

#define MAX_CACHE_BYTES (256u << 20)

#define FNV_OFFSET 0xcbf29ce484222325ull

static uint64_t fnv1a(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

static uint64_t checksum(const void *data, size_t n) { return fnv1a(FNV_OFFSET, data, n); }

static uint64_t cache_key(const rc_vk_ctx *ctx, rc_spirv module) {
  const VkPhysicalDeviceProperties *p = &ctx->props;
  uint64_t h = FNV_OFFSET;
  h = fnv1a(h, p->pipelineCacheUUID, VK_UUID_SIZE);
  h = fnv1a(h, &p->vendorID, sizeof p->vendorID);
  h = fnv1a(h, &p->deviceID, sizeof p->deviceID);
  h = fnv1a(h, &p->driverVersion, sizeof p->driverVersion);
  return fnv1a(h, module.words, module.size);
}

/* $XDG_CACHE_HOME/vkraycast, else $HOME/.cache/vkraycast; false if neither is set. */
static bool cache_dir(char *out, size_t n) {
  const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
  int len;
  if (xdg && xdg[0] == '/') len = snprintf(out, n, "%s/vkraycast", xdg);
  else if (home && home[0] == '/') len = snprintf(out, n, "%s/.cache/vkraycast", home);
  else return false;
  return len > 0 && (size_t)len < n;
}

/* mkdir -p for the last two components (…/.cache/vkraycast). */
static bool make_dir(const char *dir) {
  char parent[PATH_MAX];
  snprintf(parent, sizeof parent, "%s", dir);
  char *slash = strrchr(parent, '/');
  if (slash && slash != parent) {
    *slash = '\0';
    if (mkdir(parent, 0700) != 0 && errno != EEXIST) return false;
  }
  if (mkdir(dir, 0700) == 0) return true;
  struct stat st;
  if (errno != EEXIST || stat(dir, &st) != 0) return false;
  errno = ENOTDIR;
  return S_ISDIR(st.st_mode);
}

/* Reads and checks the file; returns the driver data (malloc'd) or NULL, with *why set
 * when a file existed but was unusable. */
static void *read_cache(const char *path, uint64_t key, size_t *size, const char **why) {
  *why = NULL;
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return NULL;
  struct stat st;
  file_header h;
  void *data = NULL;
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) *why = "not a regular file";
  else if (read(fd, &h, sizeof h) != (ssize_t)sizeof h || memcmp(h.magic, MAGIC, 8) != 0) *why = "not a vkraycast pipeline cache";
  else if (h.key != key) *why = "made for another device, driver or shader";
  else if (h.size == 0 || h.size > MAX_CACHE_BYTES || (uint64_t)st.st_size != sizeof h + h.size) *why = "truncated";
  else if (!(data = malloc(h.size))) *why = "out of memory";
  else if (read(fd, data, h.size) != (ssize_t)h.size || checksum(data, h.size) != h.checksum) {
    *why = "checksum mismatch";
    free(data);
    data = NULL;
  }
  close(fd);
  if (data) *size = h.size;
  return data;
}

/* The driver's own header (Vulkan spec, VkPipelineCacheHeaderVersionOne) must name this
 * device: the driver would ignore a foreign one too, but some drivers have crashed on
 * data they did not write, so it is checked before the driver sees it. */
static bool driver_header_matches(const rc_vk_ctx *ctx, const void *data, size_t size) {
  VkPipelineCacheHeaderVersionOne h;
  if (size < sizeof h) return false;
  memcpy(&h, data, sizeof h);
  return h.headerSize >= sizeof h && h.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
         h.vendorID == ctx->props.vendorID && h.deviceID == ctx->props.deviceID &&
         memcmp(h.pipelineCacheUUID, ctx->props.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

void rc_pipeline_cache_open(const rc_vk_ctx *ctx, rc_spirv module, rc_pipeline_cache *pc) {
  memset(pc, 0, sizeof *pc);
  const char *off = getenv("VKRAYCAST_PIPELINE_CACHE");
  if (off && strcmp(off, "0") == 0) return;
  pc->key = cache_key(ctx, module);
  char dir[PATH_MAX - 64];
  void *data = NULL;
  size_t size = 0;
  if (cache_dir(dir, sizeof dir)) {
    snprintf(pc->path, sizeof pc->path, "%s/%016llx.bin", dir, (unsigned long long)pc->key);
    const char *why;
    data = read_cache(pc->path, pc->key, &size, &why);
    if (data && !driver_header_matches(ctx, data, size)) why = "made for another device or driver";
    if (why) {
      rc_warning("%s: pipeline cache ignored (%s); it will be rewritten", pc->path, why);
      free(data);
      data = NULL;
      size = 0;
    }
  }
  VkPipelineCacheCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO,
                                  .initialDataSize = size,
                                  .pInitialData = data};
  if (vkCreatePipelineCache(ctx->device, &ci, NULL, &pc->cache) != VK_SUCCESS) {
    pc->cache = VK_NULL_HANDLE;
    if (data) rc_warning("%s: the driver refused the pipeline cache; compiling without it", pc->path);
  } else {
    pc->loaded = data != NULL;
    pc->loaded_checksum = data ? checksum(data, size) : 0;
  }
  free(data);
}

static bool write_all(int fd, const void *p, size_t n) {
  const char *c = p;
  while (n) {
    ssize_t w = write(fd, c, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    c += w;
    n -= (size_t)w;
  }
  return true;
}

/* Write to a temporary beside the file, fsync, rename: a reader sees the old file or the
 * new one, never a torn one. */
static void write_cache(const char *path, uint64_t key, const void *data, size_t size) {
  char dir[PATH_MAX], tmp[PATH_MAX];
  snprintf(dir, sizeof dir, "%s", path);
  char *slash = strrchr(dir, '/');
  if (slash) *slash = '\0';
  if (!make_dir(dir)) {
    rc_warning("%s: cannot create the pipeline cache folder: %s", dir, strerror(errno));
    return;
  }
  snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
  int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) {
    rc_warning("%s: cannot write the pipeline cache: %s", path, strerror(errno));
    return;
  }
  file_header h = {.key = key, .size = size, .checksum = checksum(data, size)};
  memcpy(h.magic, MAGIC, 8);
  bool ok = write_all(fd, &h, sizeof h) && write_all(fd, data, size) && fsync(fd) == 0;
  int err = errno;
  ok = close(fd) == 0 && ok;
  if (ok && rename(tmp, path) == 0) return;
  rc_warning("%s: cannot write the pipeline cache: %s", path, strerror(ok ? errno : err));
  unlink(tmp);
}

void rc_pipeline_cache_close(const rc_vk_ctx *ctx, rc_pipeline_cache *pc) {
  if (!pc->cache) return;
  size_t size = 0;
  void *data = NULL;
  if (pc->path[0] && vkGetPipelineCacheData(ctx->device, pc->cache, &size, NULL) == VK_SUCCESS && size > 0 &&
      size <= MAX_CACHE_BYTES && (data = malloc(size)) &&
      vkGetPipelineCacheData(ctx->device, pc->cache, &size, data) == VK_SUCCESS &&
      !(pc->loaded && checksum(data, size) == pc->loaded_checksum)) {
    write_cache(pc->path, pc->key, data, size);
  }
  free(data);
  vkDestroyPipelineCache(ctx->device, pc->cache, NULL);
  pc->cache = VK_NULL_HANDLE;
}
