#include "gpu/disk_cache.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/rc_base.h"

typedef struct {
  char magic[8];
  uint64_t key;
  uint64_t size;     /* bytes of payload */
  uint64_t checksum; /* FNV-1a of the payload */
} file_header;

uint64_t rc_fnv1a(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

bool rc_disk_cache_enabled(void) {
  const char *off = getenv("VKRAYCAST_PIPELINE_CACHE");
  return !(off && strcmp(off, "0") == 0);
}

bool rc_disk_cache_path(uint64_t key, const char *suffix, char *out, size_t n) {
  const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
  int len;
  if (xdg && xdg[0] == '/') len = snprintf(out, n, "%s/vkraycast/%016llx%s", xdg, (unsigned long long)key, suffix);
  else if (home && home[0] == '/')
    len = snprintf(out, n, "%s/.cache/vkraycast/%016llx%s", home, (unsigned long long)key, suffix);
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

void *rc_disk_cache_read(const char *path, const char *magic, uint64_t key, const char *what, size_t *size) {
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return NULL;
  struct stat st;
  file_header h;
  void *data = NULL;
  const char *why = NULL;
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) why = "not a regular file";
  else if (read(fd, &h, sizeof h) != (ssize_t)sizeof h || memcmp(h.magic, magic, 8) != 0) why = "not a vkraycast cache file";
  else if (h.key != key) why = "made for another device, driver, shader or set of constants";
  else if (h.size == 0 || h.size > RC_DISK_CACHE_MAX_BYTES || (uint64_t)st.st_size != sizeof h + h.size)
    why = "truncated";
  else if (!(data = malloc(h.size))) why = "out of memory";
  else if (read(fd, data, h.size) != (ssize_t)h.size || rc_fnv1a(RC_FNV_OFFSET, data, h.size) != h.checksum) {
    why = "checksum mismatch";
    free(data);
    data = NULL;
  }
  close(fd);
  if (why) rc_disk_cache_ignored(path, what, why);
  if (data) *size = h.size;
  return data;
}

void rc_disk_cache_ignored(const char *path, const char *what, const char *why) {
  rc_warning("%s: %s ignored (%s); it will be rewritten", path, what, why);
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
void rc_disk_cache_write(const char *path, const char *magic, uint64_t key, const void *data, size_t size,
                         const char *what) {
  char dir[PATH_MAX], tmp[PATH_MAX];
  snprintf(dir, sizeof dir, "%s", path);
  char *slash = strrchr(dir, '/');
  if (slash) *slash = '\0';
  if (!make_dir(dir)) {
    rc_warning("%s: cannot create the %s folder: %s", dir, what, strerror(errno));
    return;
  }
  snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
  int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) {
    rc_warning("%s: cannot write the %s: %s", path, what, strerror(errno));
    return;
  }
  file_header h = {.key = key, .size = size, .checksum = rc_fnv1a(RC_FNV_OFFSET, data, size)};
  memcpy(h.magic, magic, 8);
  bool ok = write_all(fd, &h, sizeof h) && write_all(fd, data, size) && fsync(fd) == 0;
  int err = errno;
  ok = close(fd) == 0 && ok;
  if (ok && rename(tmp, path) == 0) return;
  rc_warning("%s: cannot write the %s: %s", path, what, strerror(ok ? errno : err));
  unlink(tmp);
}
