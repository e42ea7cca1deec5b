#define _GNU_SOURCE /* pipe2 */
#include "scene/mesh_import.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

#define IMPORTER "vkraycast-mesh-import"

/* VKRAYCAST_MESH_IMPORTER; else beside the running binary (vkraycast, as the image module
 * is found); else where this build put it (tests and tools run from elsewhere). */
static bool find_importer(char *path, size_t len) {
  const char *env = getenv("VKRAYCAST_MESH_IMPORTER");
  if (env && env[0]) return snprintf(path, len, "%s", env) < (int)len;
  char exe[PATH_MAX];
  ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (slash) *slash = '\0';
    if (snprintf(path, len, "%s/" IMPORTER, exe) < (int)len && access(path, X_OK) == 0) return true;
  }
#ifdef RC_MESH_IMPORTER_BUILD_PATH
  return snprintf(path, len, "%s", RC_MESH_IMPORTER_BUILD_PATH) < (int)len && access(path, X_OK) == 0;
#else
  return false;
#endif
}

static double now_s(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Reads fd to its end into a malloc'd buffer, until `deadline` (now_s). Returns 0, or
 * ETIMEDOUT, ENOMEM or the read's errno. */
static int read_all(int fd, double deadline, char **buffer, size_t *len) {
  size_t cap = 1 << 16, n = 0;
  char *b = malloc(cap);
  if (!b) return ENOMEM;
  for (;;) {
    double left = deadline - now_s();
    if (left <= 0) {
      free(b);
      return ETIMEDOUT;
    }
    struct pollfd p = {.fd = fd, .events = POLLIN};
    int ready = poll(&p, 1, left > 1e6 ? 1000000000 : (int)(left * 1000) + 1);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;
    if (n == cap) {
      char *grown = cap > SIZE_MAX / 2 ? NULL : realloc(b, cap * 2);
      if (!grown) {
        free(b);
        return ENOMEM;
      }
      b = grown, cap *= 2;
    }
    ssize_t got = ready < 0 ? -1 : read(fd, b + n, cap - n);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      int e = errno;
      free(b);
      return e;
    }
    if (got == 0) break;
    n += (size_t)got;
  }
  *buffer = b, *len = n;
  return 0;
}

rc_status rc_mesh_import(const char *file, const char *root, bool libraries, size_t bytes, rc_mesh_data *data,
                         char *why, size_t len) {
  memset(data, 0, sizeof *data);
  char importer[PATH_MAX];
  if (!find_importer(importer, sizeof importer)) {
    snprintf(why, len, "cannot find the mesh importer " IMPORTER " (beside this binary, or VKRAYCAST_MESH_IMPORTER)");
    return RC_ERR_INSTALL;
  }
  int pipe_fd[2];
  if (pipe2(pipe_fd, O_CLOEXEC) != 0) {
    snprintf(why, len, "cannot start the mesh importer: %s", strerror(errno));
    return RC_ERR_IO;
  }
  /* The importer's stdout is the pipe and its stdin nothing; its stderr is ours (silent,
   * but where a sanitizer build reports). Signals as a new process has them. */
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attr;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawnattr_init(&attr);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  char parent[24];
  snprintf(parent, sizeof parent, "%ld", (long)getpid());
  char *argv[] = {importer, (char *)file, (char *)(root ? root : ""), libraries ? "1" : "0", parent, NULL};
  pid_t pid;
  int spawned = posix_spawn(&pid, importer, &actions, &attr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  close(pipe_fd[1]);
  if (spawned != 0) {
    close(pipe_fd[0]);
    snprintf(why, len, "cannot start the mesh importer %s: %s", importer, strerror(spawned));
    return RC_ERR_INSTALL;
  }

  /* assimp 5.2.4 can loop forever on a malformed file (fuzz_mesh found a 171-byte ASCII
   * PLY that spins in fread at end of file): the import gets 20 s + 1 s per MiB. */
  long limit_s = 20 + (long)(bytes >> 20);
  const char *env = getenv("VKRAYCAST_MESH_TIMEOUT_S");
  if (env && atol(env) > 0) limit_s = atol(env);
  char *answer = NULL;
  size_t answer_len = 0;
  int read_error = read_all(pipe_fd[0], now_s() + (double)limit_s, &answer, &answer_len);
  close(pipe_fd[0]);
  if (read_error) kill(pid, SIGKILL);
  int wstatus = 0;
  while (waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  if (read_error == ETIMEDOUT) {
    snprintf(why, len, "the importer (assimp) did not finish within %ld s (a malformed file?)", limit_s);
    return RC_ERR_INPUT;
  }
  if (read_error) {
    snprintf(why, len, "cannot read the mesh importer's answer: %s", strerror(read_error));
    return read_error == ENOMEM ? RC_ERR_OUT_OF_MEMORY : RC_ERR_IO;
  }
  if (WIFSIGNALED(wstatus) || !WIFEXITED(wstatus) || WEXITSTATUS(wstatus) != 0) {
    free(answer);
    if (WIFSIGNALED(wstatus))
      snprintf(why, len, "the importer (assimp) crashed on it (signal %d, %s): the file is malformed",
               WTERMSIG(wstatus), strsignal(WTERMSIG(wstatus)));
    else
      snprintf(why, len, "the importer (assimp) failed on it (exit status %d): the file is malformed",
               WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1);
    return RC_ERR_INPUT;
  }
  const char *wrong = rc_mesh_wire_parse(answer, answer_len, data);
  if (wrong) {
    snprintf(why, len, "the mesh importer's answer is not whole: %s", wrong);
    rc_mesh_data_free(data);
    return RC_ERR_IO;
  }
  return RC_OK;
}
