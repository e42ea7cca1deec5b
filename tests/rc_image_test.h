/* rc_image_test.h: images that a test had vkraycast write, read back as float through the
 * project's own reader (image/image_io.h). Include after rc_cli_test.h (it reads `tmp`). */
#ifndef RC_IMAGE_TEST_H
#define RC_IMAGE_TEST_H

#include <stdio.h>

#include "image/image_io.h"

typedef struct {
  int w, h, c;
  float *px; /* malloc'ed, w * h * c floats, rows top to bottom; NULL if unreadable */
} image;

/* TMP/name, or an image with px NULL after printing why. */
static inline image load(const char *name) {
  image im = {0};
  char path[512], err[256];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  if (rc_image_read(path, &im.w, &im.h, &im.c, &im.px, err, sizeof err) != 0) printf("  cannot read %s: %s\n", path, err);
  return im;
}

#endif
