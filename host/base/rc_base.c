#include "base/rc_base.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

const char *rc_status_str(rc_status s) {
  switch (s) {
#define RC_STATUS_CASE(name, code, text) \
  case RC_##name:                        \
    return text;
    RC_STATUS_LIST(RC_STATUS_CASE)
#undef RC_STATUS_CASE
  }
  return "unknown status";
}

int rc_status_exit_code(rc_status s) {
  switch (s) {
#define RC_STATUS_CODE(name, code, text) \
  case RC_##name:                        \
    return code;
    RC_STATUS_LIST(RC_STATUS_CODE)
#undef RC_STATUS_CODE
  }
  return 3;
}

static void report(const char *kind, const char *fmt, va_list ap) {
  fprintf(stderr, "vkraycast: %s: ", kind);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
}

void rc_error(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  report("error", fmt, ap);
  va_end(ap);
}

static const char *scene_path;

void rc_set_scene_path(const char *path) { scene_path = path; }

void rc_refuse_scene(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  if (scene_path) {
    fprintf(stderr, "%s: error: ", scene_path);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
  } else {
    report("error", fmt, ap);
  }
  va_end(ap);
}

void rc_warning(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  report("warning", fmt, ap);
  va_end(ap);
}

void rc_assert_fail(const char *file, int line, const char *expr) {
  fprintf(stderr, "vkraycast: internal error: %s:%d: assertion failed: %s\n", file, line, expr);
  abort();
}

static double clock_ms(clockid_t id) {
  struct timespec ts;
  clock_gettime(id, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

double rc_now_ms(void) { return clock_ms(CLOCK_MONOTONIC); }
double rc_cpu_ms(void) { return clock_ms(CLOCK_PROCESS_CPUTIME_ID); }

bool rc_fault(const char *name) {
  const char *f = getenv("VKRAYCAST_FAULT");
  return f && strcmp(f, name) == 0;
}

const char *rc_fault_arg(const char *name) {
  const char *f = getenv("VKRAYCAST_FAULT");
  size_t n = strlen(name);
  return (f && strncmp(f, name, n) == 0 && f[n] == ':') ? f + n + 1 : NULL;
}

void *rc_alloc(size_t count, size_t size, const char *what) {
  if (rc_fault("host-memory") && count * size >= (1u << 20)) {
    rc_error("out of memory: %s needs %zu bytes (injected fault)", what, count * size);
    return NULL;
  }
  /* With room to round up to whole huge pages below. */
  if (count != 0 && size > (SIZE_MAX - RC_HUGE_PAGE) / count) {
    rc_error("out of memory: %s needs more than SIZE_MAX bytes", what);
    return NULL;
  }
  size_t bytes = count * size;
  void *p = NULL;
  if (bytes >= RC_HUGE_PAGE / 2) {
    /* Rounded up to whole huge pages: a block of 1-2 MiB (a band of a small image) costs
     * at most twice its size, and its first touch one fault instead of 256-512. */
    size_t whole = (bytes + RC_HUGE_PAGE - 1) & ~(RC_HUGE_PAGE - 1);
    if (posix_memalign(&p, RC_HUGE_PAGE, whole) == 0) {
      rc_advise_huge(p, whole);
      memset(p, 0, bytes);
    } else {
      p = NULL;
    }
  } else {
    p = calloc(count ? count : 1, size ? size : 1);
  }
  if (!p) rc_error("out of memory: %s needs %zu bytes", what, bytes);
  return p;
}

void rc_advise_huge(void *p, size_t size) {
  uintptr_t lo = ((uintptr_t)p + RC_HUGE_PAGE - 1) & ~(uintptr_t)(RC_HUGE_PAGE - 1);
  uintptr_t hi = ((uintptr_t)p + size) & ~(uintptr_t)(RC_HUGE_PAGE - 1);
  if (hi > lo) (void)madvise((void *)lo, hi - lo, MADV_HUGEPAGE);
}

static const char *file_kind(mode_t m) {
  if (S_ISDIR(m)) return "is a directory";
  if (S_ISFIFO(m)) return "is a FIFO (named pipe)";
  if (S_ISCHR(m)) return "is a character device";
  if (S_ISBLK(m)) return "is a block device";
  if (S_ISSOCK(m)) return "is a socket";
  return "is not a regular file";
}

static void report_input(const char *path, const char *what, const char *why) {
  fprintf(stderr, "%s: error: cannot open %s: %s\n", path, what, why);
}

/* Opens without blocking (a FIFO with no writer would block open() itself) and checks the
 * kind on the descriptor, so nothing can be swapped in between the check and the read.
 * Returns the descriptor, or -1 with *why set. */
static int open_checked(const char *path, bool allow_fifo, size_t *bytes, bool *fifo, const char **why) {
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  struct stat st;
  if (fd < 0) {
    int e = errno;
    /* A socket cannot be opened: say what it is rather than ENXIO. */
    *why = (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) ? file_kind(st.st_mode) : strerror(e);
    return -1;
  }
  bool stated = fstat(fd, &st) == 0;
  if (fifo) *fifo = stated && S_ISFIFO(st.st_mode) && allow_fifo;
  if (!stated || !(S_ISREG(st.st_mode) || (allow_fifo && S_ISFIFO(st.st_mode)))) {
    *why = stated ? file_kind(st.st_mode) : strerror(errno);
    close(fd);
    return -1;
  }
  int flags = fcntl(fd, F_GETFL);
  if (flags >= 0) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  if (bytes) *bytes = (size_t)st.st_size;
  return fd;
}

static int open_regular(const char *path, size_t *bytes, const char **why) {
  return open_checked(path, false, bytes, NULL, why);
}

/* Reads fd to its end into a malloc'ed, NUL-terminated buffer of at most max bytes. */
static rc_status read_all(int fd, const char *path, const char *what, size_t max, size_t size_hint, char **text,
                          size_t *len) {
  /* A regular file's size is known: one allocation, and one more read to see its end. */
  size_t cap = size_hint + 1 > (1 << 16) ? size_hint + 1 : (1 << 16), n = 0;
  char *buf = malloc(cap + 1);
  if (!buf) {
    rc_error("out of memory: %s needs %zu bytes", what, cap + 1);
    return RC_ERR_OUT_OF_MEMORY;
  }
  for (;;) {
    if (n == cap) {
      if (cap > max) break;
      char *grown = realloc(buf, 2 * cap + 1);
      if (!grown) {
        rc_error("out of memory: %s needs %zu bytes", what, 2 * cap + 1);
        free(buf);
        return RC_ERR_OUT_OF_MEMORY;
      }
      buf = grown, cap *= 2;
    }
    ssize_t got = read(fd, buf + n, cap - n);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      fprintf(stderr, "%s: error: cannot read %s: %s\n", path, what, strerror(errno));
      free(buf);
      return RC_ERR_IO;
    }
    if (got == 0) break;
    n += (size_t)got;
  }
  if (n > max) {
    fprintf(stderr, "%s: error: %s is more than the %zu bytes allowed\n", path, what, max);
    free(buf);
    return RC_ERR_TOO_LARGE;
  }
  buf[n] = '\0';
  *text = buf;
  *len = n;
  return RC_OK;
}

rc_status rc_read_input(const char *path, const char *what, size_t max, char **text, size_t *len) {
  *text = NULL;
  *len = 0;
  if (strcmp(path, "-") == 0) {
    if (isatty(STDIN_FILENO)) {
      fprintf(stderr, "%s: error: cannot read %s from standard input: it is a terminal (pipe or redirect a file "
              "into it)\n", RC_STDIN_NAME, what);
      return RC_ERR_IO;
    }
    return read_all(STDIN_FILENO, RC_STDIN_NAME, what, max, 0, text, len);
  }
  const char *why = NULL;
  size_t bytes = 0;
  bool fifo = false;
  int fd = open_checked(path, true, &bytes, &fifo, &why);
  if (fd < 0) {
    report_input(path, what, why);
    return RC_ERR_IO;
  }
  if (!fifo && bytes > max) {
    fprintf(stderr, "%s: error: %s is %zu bytes, more than the %zu allowed\n", path, what, bytes, max);
    close(fd);
    return RC_ERR_TOO_LARGE;
  }
  rc_status st = read_all(fd, path, what, max, fifo ? 0 : bytes, text, len);
  close(fd);
  if (st == RC_OK && fifo && *len == 0) {
    /* A FIFO nobody writes to reads as empty at once (no writer: end of file). */
    fprintf(stderr, "%s: error: cannot read %s: it is a FIFO (named pipe) and nothing was written to it\n", path,
            what);
    free(*text);
    *text = NULL;
    st = RC_ERR_INPUT;
  }
  return st;
}


FILE *rc_fopen_regular(const char *path, size_t *bytes, const char **why) {
  int fd = open_regular(path, bytes, why);
  FILE *f = fd < 0 ? NULL : fdopen(fd, "rb");
  if (fd >= 0 && !f) {
    *why = strerror(errno);
    close(fd);
  }
  return f;
}

FILE *rc_open_input(const char *path, const char *what, size_t *bytes) {
  const char *why = NULL;
  FILE *f = rc_fopen_regular(path, bytes, &why);
  if (!f) report_input(path, what, why);
  return f;
}

/* The path with its folder resolved (realpath) and its last component kept: the same for
 * every spelling of a file that may not exist yet. */
bool rc_resolve_path(const char *path, char *out, size_t cap) {
  const char *slash = strrchr(path, '/');
  char dir[4096];
  snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) : 1, slash ? (slash == path ? "/" : path) : ".");
  char *real = realpath(dir, NULL);
  if (!real) return false;
  int n = snprintf(out, cap, "%s/%s", real, slash ? slash + 1 : path);
  free(real);
  return n > 0 && (size_t)n < cap;
}

static bool same_file(const char *a, const char *b) {
  struct stat sa, sb;
  if (stat(a, &sa) == 0 && stat(b, &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  char ca[4200], cb[4200];
  return rc_resolve_path(a, ca, sizeof ca) && rc_resolve_path(b, cb, sizeof cb) && strcmp(ca, cb) == 0;
}

rc_status rc_check_distinct(const rc_file_role *f, size_t count) {
  for (size_t i = 0; i < count; i++)
    for (size_t j = 0; j < i; j++) {
      if (!f[i].path || !f[j].path || (!f[i].output && !f[j].output)) continue;
      if (!same_file(f[i].path, f[j].path)) continue;
      fprintf(stderr, "%s: error: %s and %s name the same file\n", f[i].path, f[j].role, f[i].role);
      return RC_ERR_USAGE;
    }
  return RC_OK;
}

bool rc_has_extension(const char *path, const char *ext) {
  size_t n = strlen(path), m = strlen(ext);
  return n > m && strcasecmp(path + n - m, ext) == 0;
}

bool rc_path_within(const char *dir, const char *path) {
  char *d = realpath(dir, NULL), *p = realpath(path, NULL);
  size_t n = d ? strlen(d) : 0;
  bool inside = d && p && strncmp(d, p, n) == 0 && (p[n] == '/' || p[n] == '\0' || (n == 1 && d[0] == '/'));
  bool missing = d && !p;
  free(d);
  free(p);
  return inside || missing;
}

const char *rc_input_problem(const char *path, size_t *bytes) {
  const char *why = NULL;
  int fd = open_regular(path, bytes, &why);
  if (fd >= 0) close(fd);
  return fd >= 0 ? NULL : why;
}

rc_status rc_check_input(const char *path, const char *what, size_t *bytes) {
  const char *why = rc_input_problem(path, bytes);
  if (!why) return RC_OK;
  report_input(path, what, why);
  return RC_ERR_IO;
}

rc_status rc_check_output(const char *path, const char *what) {
  struct stat st;
  if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
    fprintf(stderr, "%s: error: cannot write %s there: it %s\n", path, what, file_kind(st.st_mode));
    return RC_ERR_IO;
  }
  const char *slash = strrchr(path, '/');
  if (slash && slash != path) {
    char dir[4096];
    size_t n = (size_t)(slash - path);
    if (n >= sizeof dir) n = sizeof dir - 1;
    memcpy(dir, path, n);
    dir[n] = '\0';
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
      fprintf(stderr, "%s: error: cannot write %s: no such directory %s\n", path, what, dir);
      return RC_ERR_IO;
    }
  }
  return RC_OK;
}

size_t rc_edit_distance(const char *a, const char *b) {
  size_t n = strlen(b);
  size_t row[64];
  if (n >= sizeof row / sizeof *row) return (size_t)-1;
  for (size_t j = 0; j <= n; j++) row[j] = j;
  for (size_t i = 1; a[i - 1]; i++) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= n; j++) {
      size_t up = row[j];
      size_t best = diag + (a[i - 1] != b[j - 1]);
      if (up + 1 < best) best = up + 1;
      if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
      row[j] = best;
      diag = up;
    }
  }
  return row[n];
}

const char *rc_nearest(const char *word, const char *const *candidates, size_t count) {
  /* The same name in another case ("Plane", "POINT"): always the one meant. */
  for (size_t i = 0; i < count; i++)
    if (candidates[i] && strcasecmp(candidates[i], word) == 0) return candidates[i];
  size_t limit = strlen(word) / 3;
  if (limit < 1) limit = 1;
  if (limit > 3) limit = 3;
  const char *best = NULL;
  size_t best_d = limit + 1;
  for (size_t i = 0; i < count; i++) {
    if (!candidates[i]) continue;
    size_t d = rc_edit_distance(word, candidates[i]);
    if (d < best_d) best = candidates[i], best_d = d;
  }
  if (best) return best;
  /* A shortened name ("fov" for "fov_y_deg", "--shadow" for "--shadow-offset"): the one
   * candidate that starts with the word. */
  size_t n = strlen(word), found = 0;
  for (size_t i = 0; i < count && n >= 2; i++)
    if (candidates[i] && strncmp(candidates[i], word, n) == 0) best = candidates[i], found++;
  return found == 1 ? best : NULL;
}
