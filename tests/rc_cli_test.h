/* rc_cli_test.h: helpers for tests that run the vkraycast binary: run it with printf-style
 * arguments (stderr to TMP/stderr.txt), search its stderr, read JSON it wrote. The test
 * sets `bin` (the binary) and `tmp` (a scratch folder) first. */
#ifndef RC_CLI_TEST_H
#define RC_CLI_TEST_H

#include <cjson/cJSON.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

static const char *bin;
static char tmp[256];

/* Runs vkraycast with the arguments (a printf format); returns its exit status. */
static inline int run(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static inline int run(const char *fmt, ...) {
  char args[2048], cmd[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(args, sizeof args, fmt, ap);
  va_end(ap);
  snprintf(cmd, sizeof cmd, "'%s' %s 2>%s/stderr.txt", bin, args, tmp);
  int st = system(cmd);
  int code = WIFEXITED(st) ? WEXITSTATUS(st) : 128;
  if (code != 0) {
    printf("  `vkraycast %s` exited %d; stderr:\n", args, code);
    char show[4096];
    snprintf(show, sizeof show, "sed 's/^/    /' %s/stderr.txt", tmp);
    if (system(show) != 0) printf("    (no stderr)\n");
  }
  return code;
}

static inline bool stderr_contains(const char *text) {
  char buf[8192] = "";
  char path[300];
  snprintf(path, sizeof path, "%s/stderr.txt", tmp);
  FILE *f = fopen(path, "r");
  if (!f) return false;
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  buf[n] = '\0';
  fclose(f);
  return strstr(buf, text) != NULL;
}

static inline cJSON *load_json(const char *name) {
  char path[300];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  FILE *f = fopen(path, "r");
  if (!f) return NULL;
  char buf[16384];
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  buf[n] = '\0';
  fclose(f);
  return cJSON_Parse(buf);
}

static inline double json_number(const cJSON *o, const char *key) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
  return cJSON_IsNumber(v) ? v->valuedouble : -1.0;
}

#endif
