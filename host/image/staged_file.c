/* staged_file.c: staged_file.h. */
#define _GNU_SOURCE /* O_TMPFILE, linkat */
#include "image/staged_file.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void errno_text(char *err, size_t len, const char *what, int e) {
  if (err && len) snprintf(err, len, "%s: %s", what, strerror(e));
}

static char *dup_dir(const char *path) {
  const char *slash = strrchr(path, '/');
  if (!slash) return strdup(".");
  if (slash == path) return strdup("/");
  return strndup(path, (size_t)(slash - path));
}

/* A short temporary name beside the target: its length does not grow with the target's (a
 * valid 250-character name must still work under a 255-byte NAME_MAX). The counter is per
 * module and the modules share a pid, so a name taken (EEXIST) is passed over. */
static char *temp_name(const char *dir) {
  static unsigned counter;
  char name[PATH_MAX + 64];
  snprintf(name, sizeof name, "%s/.vkraycast-%ld-%u.tmp", dir, (long)getpid(), __atomic_fetch_add(&counter, 1, __ATOMIC_RELAXED));
  return strdup(name);
}

void rc_staged_discard(rc_staged *s) {
  if (s->file) fclose(s->file);
  s->file = NULL;
  if (s->tmp) remove(s->tmp);
  free(s->tmp), free(s->dir), free(s->path);
  s->tmp = s->dir = s->path = NULL;
}

/* VKRAYCAST_FAULT=no-tmpfile (rc_base.h's fault injection; the image modules link nothing
 * of the host's, so it is read here): the filesystem refuses O_TMPFILE, as some do, and the
 * temporary gets a name, which tests can then watch being removed. */
static int no_tmpfile_fault(void) {
  const char *f = getenv("VKRAYCAST_FAULT");
  return f && strcmp(f, "no-tmpfile") == 0;
}

int rc_staged_open(rc_staged *s, const char *path, char *err, size_t err_len) {
  memset(s, 0, sizeof *s);
  s->path = strdup(path);
  s->dir = dup_dir(path);
  if (!s->path || !s->dir) {
    if (err && err_len) snprintf(err, err_len, "out of memory");
    rc_staged_discard(s);
    return -1;
  }
  int fd = open(s->dir, O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd >= 0 && no_tmpfile_fault()) close(fd), fd = -1, errno = EOPNOTSUPP;
  if (fd < 0 && (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL)) {
    for (int tries = 0; fd < 0 && tries < 100; tries++) {
      free(s->tmp);
      s->tmp = temp_name(s->dir);
      fd = s->tmp ? open(s->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666) : -1;
      if (fd < 0 && errno != EEXIST) break;
    }
  }
  if (fd < 0) {
    int e = errno;
    free(s->tmp), s->tmp = NULL;
    char what[PATH_MAX + 32];
    snprintf(what, sizeof what, e == ENOENT || e == ENOTDIR ? "no such directory %s" : "%s", s->dir);
    errno_text(err, err_len, what, e);
    rc_staged_discard(s);
    return -1;
  }
  s->file = fdopen(fd, "wb");
  if (!s->file) {
    errno_text(err, err_len, "fdopen", errno);
    close(fd);
    rc_staged_discard(s);
    return -1;
  }
  return 0;
}

int rc_staged_sync(rc_staged *s, char *err, size_t err_len) {
  if (fflush(s->file) != 0) {
    errno_text(err, err_len, "write failed", errno);
    return -1;
  }
  if (fsync(fileno(s->file)) != 0) {
    errno_text(err, err_len, "fsync failed", errno);
    return -1;
  }
  return 0;
}

int rc_staged_write_all(rc_staged *s, const void *bytes, size_t len, char *err, size_t err_len) {
  if (fwrite(bytes, 1, len, s->file) != len) {
    errno_text(err, err_len, "write failed", errno);
    return -1;
  }
  return rc_staged_sync(s, err, err_len);
}

/* An unnamed temporary, by linkat through /proc/self/fd; a name taken is passed over. */
static int link_unnamed(rc_staged *s, char *err, size_t err_len) {
  char self[64];
  snprintf(self, sizeof self, "/proc/self/fd/%d", fileno(s->file));
  for (int tries = 0; tries < 100; tries++) {
    s->tmp = temp_name(s->dir);
    if (s->tmp && linkat(AT_FDCWD, self, AT_FDCWD, s->tmp, AT_SYMLINK_FOLLOW) == 0) return 0;
    int e = s->tmp ? errno : ENOMEM;
    free(s->tmp), s->tmp = NULL;
    if (e != EEXIST) {
      char what[PATH_MAX + 64];
      snprintf(what, sizeof what, "cannot give the finished image a name in %s", s->dir);
      errno_text(err, err_len, what, e);
      return -1;
    }
  }
  errno_text(err, err_len, "cannot give the finished image a name", EEXIST);
  return -1;
}

/* Signals wait meanwhile, so that no handler runs between linkat and rename, nor before a
 * failed name is removed. */
int rc_staged_commit(rc_staged *s, char *err, size_t err_len) {
  sigset_t all, old;
  sigfillset(&all);
  sigprocmask(SIG_BLOCK, &all, &old);
  int ok = !s->tmp ? link_unnamed(s, err, err_len) == 0 : 1;
  if (fclose(s->file) != 0 && ok) {
    errno_text(err, err_len, "write failed", errno);
    ok = 0;
  }
  s->file = NULL;
  if (ok && rename(s->tmp, s->path) != 0) {
    errno_text(err, err_len, "cannot rename the finished image into place", errno);
    ok = 0;
  }
  if (ok) {
    free(s->tmp), s->tmp = NULL;
    int dfd = open(s->dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
      fsync(dfd);
      close(dfd);
    }
  }
  rc_staged_discard(s); /* removes a temporary that did not get the target's name */
  sigprocmask(SIG_SETMASK, &old, NULL);
  return ok ? 0 : -1;
}

const char *rc_staged_temp_path(const rc_staged *s) { return s->tmp ? s->tmp : ""; }
