#define _GNU_SOURCE /* fopencookie */
#include "cli/safe_streams.h"

#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

static bool is_control(unsigned char c) { return (c < 0x20 && c != '\n' && c != '\t') || c == 0x7f; }

static bool write_all(int fd, const char *p, size_t n) {
  while (n) {
    ssize_t w = write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w, n -= (size_t)w;
  }
  return true;
}

/* The cookie is the descriptor itself. A failed write (a full disk, a closed pipe) fails
 * the stream, so that fflush and fclose report it as they would on the plain stream. */
static ssize_t filtered_write(void *cookie, const char *buf, size_t size) {
  int fd = (int)(intptr_t)cookie;
  char out[1024];
  size_t o = 0;
  for (size_t i = 0; i < size; i++) {
    if (o + 4 > sizeof out) {
      if (!write_all(fd, out, o)) return -1;
      o = 0;
    }
    unsigned char c = (unsigned char)buf[i];
    if (is_control(c)) {
      static const char hex[] = "0123456789abcdef";
      out[o++] = '\\', out[o++] = 'x', out[o++] = hex[c >> 4], out[o++] = hex[c & 15];
    } else {
      out[o++] = (char)c;
    }
  }
  if (o && !write_all(fd, out, o)) return -1;
  return (ssize_t)size;
}

static FILE *filtered(int fd, int mode) {
  cookie_io_functions_t io = {.write = filtered_write};
  FILE *f = fopencookie((void *)(intptr_t)fd, "w", io);
  if (f) setvbuf(f, NULL, mode, mode == _IONBF ? 0 : BUFSIZ);
  return f;
}

void rc_safe_streams_install(void) {
  fflush(stdout);
  fflush(stderr);
  FILE *out = filtered(STDOUT_FILENO, isatty(STDOUT_FILENO) ? _IOLBF : _IOFBF);
  FILE *err = filtered(STDERR_FILENO, _IONBF);
  if (out) stdout = out;
  if (err) stderr = err;
}
