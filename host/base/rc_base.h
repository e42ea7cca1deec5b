/* rc_base.h: status codes, diagnostics and timing shared by every host module.
 * Functions return rc_status; the place that detects an error prints it once, with the
 * context it has (file, line, field, value); only main() turns a status into an exit code
 * (README, "Exit status": 0 ok, 1 compare beyond thresholds, 2 bad input or usage, 3 device). */
#ifndef RC_BASE_H
#define RC_BASE_H

#include <stdbool.h>
#include <stdio.h>
#include <stddef.h>
#include <stdint.h>

#define RC_STATUS_LIST(X)                                           \
  X(OK, 0, "ok")                                                    \
  X(DONE, 0, "nothing more to do (--help shown)")                   \
  X(MISMATCH, 1, "images differ beyond the thresholds")             \
  X(ERR_USAGE, 2, "bad usage")                                      \
  X(ERR_INPUT, 2, "bad input")                                      \
  X(ERR_IO, 2, "file error")                                        \
  X(ERR_TOO_LARGE, 2, "request too large")                          \
  X(ERR_DEVICE, 3, "no usable Vulkan device")                       \
  X(ERR_OUT_OF_MEMORY, 3, "out of memory")                          \
  X(ERR_VULKAN, 3, "Vulkan call failed")                            \
  X(ERR_VALIDATION, 3, "Vulkan validation reported errors")        \
  X(ERR_INSTALL, 3, "the installation is incomplete")

typedef enum {
#define RC_STATUS_ENUM(name, code, text) RC_##name,
  RC_STATUS_LIST(RC_STATUS_ENUM)
#undef RC_STATUS_ENUM
} rc_status;

const char *rc_status_str(rc_status s);
int rc_status_exit_code(rc_status s);

/* "vkraycast: error: ..." on stderr. */
void rc_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void rc_warning(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* A refusal of the scene being rendered as a whole (too large for the device, for brute
 * force, for the BVH): "SCENE: error: ...", naming the file set by rc_set_scene_path, or
 * "vkraycast: error: ..." before one is set. */
void rc_set_scene_path(const char *path);
void rc_refuse_scene(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Programmer errors: always checked, release builds included. */
/* Returns the status of `expr` from the calling function unless it is RC_OK. */
#define RC_TRY(expr)              \
  do {                            \
    rc_status st_ = (expr);       \
    if (st_ != RC_OK) return st_; \
  } while (0)

#define RC_ASSERT(cond)                                                            \
  do {                                                                             \
    if (!(cond)) rc_assert_fail(__FILE__, __LINE__, #cond);                        \
  } while (0)
_Noreturn void rc_assert_fail(const char *file, int line, const char *expr);

/* Monotonic wall clock and process CPU time, in milliseconds. */
double rc_now_ms(void);
double rc_cpu_ms(void);

/* calloc that reports failure with the size asked for; NULL on failure (callers return
 * RC_ERR_OUT_OF_MEMORY, exit status 3). Blocks of half RC_HUGE_PAGE or more are rounded up
 * to whole huge pages, backed by transparent huge pages where the kernel offers them
 * (rc_advise_huge) and zeroed here, so their first touch is one fault per 2 MiB, not one
 * per 4 KiB page. */
void *rc_alloc(size_t count, size_t size, const char *what);

/* Asks the kernel for transparent huge pages over the 2 MiB-aligned part of [p, p+size)
 * (madvise MADV_HUGEPAGE; Debian's default THP mode honours it). On the project's CI VM
 * a first touch costs about 3 ms per MiB in 4 KiB pages and 0.05 ms in huge pages
 * (docs/performance.md, finding 7). Advisory: memory the kernel cannot back so (a device
 * mapping) stays as it was. */
#define RC_HUGE_PAGE ((size_t)2 << 20)
void rc_advise_huge(void *p, size_t size);

/* Grows `array` (count used of cap) to room for one more: doubling, `first` elements the
 * first time. Returns RC_ERR_OUT_OF_MEMORY from the calling function on failure. */
#define RC_GROW(array, count, cap, first)                \
  do {                                                   \
    if ((count) == (cap)) {                              \
      size_t n_ = (cap) ? 2 * (cap) : (first);           \
      void *p_ = realloc((array), n_ * sizeof *(array)); \
      if (!p_) return RC_ERR_OUT_OF_MEMORY;              \
      (array) = p_;                                      \
      (cap) = n_;                                        \
    }                                                    \
  } while (0)

/* Files given on the command line or named by a scene. Neither blocks nor spins on a
 * special file: an input is opened with O_NONBLOCK and fstat()ed before anything reads
 * it, so a FIFO, a device, a socket or a folder is refused with what it is ("is a
 * FIFO"). rc_open_input returns a FILE* for reading, or NULL after printing
 * "PATH: error: cannot open WHAT: REASON"; rc_check_input only checks (for files other
 * libraries open by name, such as images), rc_input_problem returns the reason (NULL
 * when fine) for callers with their own message; each fills *bytes if not NULL.
 * rc_check_output refuses, before any rendering, an output that exists and is not a
 * regular file (writing renames over it: -o /dev/null must not replace the device), and
 * one whose folder does not exist. */
FILE *rc_open_input(const char *path, const char *what, size_t *bytes);
/* rc_open_input without the message: NULL with *why set. */
FILE *rc_fopen_regular(const char *path, size_t *bytes, const char **why);
rc_status rc_check_input(const char *path, const char *what, size_t *bytes);
/* The whole of an input that may be a stream: "-" (standard input, named RC_STDIN_NAME in
 * messages; refused when it is a terminal), a pipe or FIFO (/dev/stdin, a shell's
 * <(...)), read to its end, or a regular file; at most max bytes, else RC_ERR_TOO_LARGE.
 * *text is malloc'ed and NUL-terminated. Messages are printed here. */
#define RC_STDIN_NAME "<stdin>"
/* The absolute path with its folder resolved (realpath: links, "..") and its last
 * component kept, for a file that may not exist; false when the folder does not. */
bool rc_resolve_path(const char *path, char *out, size_t cap);
rc_status rc_read_input(const char *path, const char *what, size_t max, char **text, size_t *len);
const char *rc_input_problem(const char *path, size_t *bytes);
rc_status rc_check_output(const char *path, const char *what);
/* A run's files, checked before anything is read or written: each output must name a
 * file of its own, neither another output nor an input (symbolic links, "./" and ".."
 * resolved; an existing file by its device and inode). `roles` name them in the message
 * "PATH: error: ROLE and ROLE name the same file". */
typedef struct rc_file_role {
  const char *path; /* NULL: not used this run */
  const char *role; /* "the image", "the scene file", ... */
  bool output;
} rc_file_role;
rc_status rc_check_distinct(const rc_file_role *files, size_t count);
/* Whether `path`, symbolic links resolved, lies inside the folder `dir`: the check that
 * keeps a scene from reading files outside its own folder (--allow-outside-paths). A path
 * that does not exist counts as inside; opening it then fails with its own message. */
bool rc_path_within(const char *dir, const char *path);
/* Whether the file name ends in `ext` (".test"), in any case, after at least one other
 * character: the one test every reader and command uses, so that they agree on a name. */
bool rc_has_extension(const char *path, const char *ext);

/* Fault injection for the tests of the error paths: true when VKRAYCAST_FAULT names this
 * fault ("device-lost", "device-memory", "pipeline", "host-memory"; "no-tmpfile" is read by
 * the image modules themselves, image/staged_file.c). The real handling
 * code then runs as if the driver or the allocator had failed. */
bool rc_fault(const char *name);
/* VKRAYCAST_FAULT=NAME:ARGS: ARGS for a fault that takes values, else NULL. */
const char *rc_fault_arg(const char *name);

/* Levenshtein distance (bytes), for did-you-mean: options (cli/options.c), commands,
 * scene fields (scene_json.c). */
size_t rc_edit_distance(const char *a, const char *b);
/* The candidate nearest to word when it is near enough to be a likely typo (distance at
 * most a third of the word's length, at least 1, at most 3), else NULL. */
const char *rc_nearest(const char *word, const char *const *candidates, size_t count);

#endif
