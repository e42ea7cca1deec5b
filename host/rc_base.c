#include "rc_base.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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
  if (count != 0 && size > SIZE_MAX / count) {
    rc_error("out of memory: %s needs more than SIZE_MAX bytes", what);
    return NULL;
  }
  void *p = calloc(count ? count : 1, size ? size : 1);
  if (!p) rc_error("out of memory: %s needs %zu bytes", what, count * size);
  return p;
}
