#include "cli/textures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image/image_io.h"

/* The image's pixels as RGB: gray (1 or 2 channels) repeated, channels past 3 dropped. */
static float *to_rgb(const float *pixels, size_t count, int channels) {
  float *rgb = malloc(count * 3 * sizeof *rgb);
  if (!rgb) return NULL;
  for (size_t k = 0; k < count; k++)
    for (int c = 0; c < 3; c++) rgb[3 * k + c] = pixels[k * (size_t)channels + (channels >= 3 ? c : 0)];
  return rgb;
}

static rc_status read_one(rc_texture_def *t, size_t *total) {
  size_t bytes = 0;
  const char *why = rc_input_problem(t->path, &bytes);
  if (why) {
    fprintf(stderr, "%s: cannot read texture %s: %s\n", t->where, t->path, why);
    return RC_ERR_IO;
  }
  int w = 0, h = 0, channels = 0;
  float *pixels = NULL;
  char err[512];
  if (rc_image_read(t->path, &w, &h, &channels, &pixels, err, sizeof err) != 0) {
    fprintf(stderr, "%s: cannot read texture %s: %s\n", t->where, t->path, err);
    return RC_ERR_IO;
  }
  rc_status st = RC_OK;
  if (w < 1 || h < 1 || (uint32_t)w > RC_MAX_TEXTURE_SIDE || (uint32_t)h > RC_MAX_TEXTURE_SIDE) {
    fprintf(stderr, "%s: texture %s is %d x %d pixels; a texture is 1 to %u on a side\n", t->where, t->path, w, h,
            RC_MAX_TEXTURE_SIDE);
    st = RC_ERR_TOO_LARGE;
  } else if ((*total += (size_t)w * (size_t)h) > RC_MAX_TEXELS) {
    fprintf(stderr, "%s: texture %s brings the scene's textures to %zu texels, more than the %u they may have in all\n",
            t->where, t->path, *total, RC_MAX_TEXELS);
    st = RC_ERR_TOO_LARGE;
  }
  size_t count = (size_t)w * (size_t)h;
  for (size_t k = 0; st == RC_OK && k < count * (size_t)channels; k++) {
    float v = pixels[k];
    if (!(v >= 0) || isinf(v)) {
      size_t px = k / (size_t)channels;
      fprintf(stderr, "%s: texture %s has the value %g at pixel (%zu, %zu): a texel is a finite colour, at least 0\n",
              t->where, t->path, v, px % (size_t)w, px / (size_t)w);
      st = RC_ERR_INPUT;
    }
  }
  if (st == RC_OK && !(t->rgb = to_rgb(pixels, count, channels))) st = RC_ERR_OUT_OF_MEMORY;
  if (st == RC_OK) t->width = (uint32_t)w, t->height = (uint32_t)h;
  free(pixels);
  return st;
}

rc_status rc_scene_read_textures(rc_scene *scene) {
  size_t total = 0;
  for (size_t i = 0; i < scene->texture_count; i++) {
    rc_texture_def *t = &scene->textures[i];
    /* A file several materials name is read, and packed, once. */
    t->image = (uint32_t)i;
    for (size_t k = 0; k < i && t->image == i; k++)
      if (strcmp(scene->textures[k].path, t->path) == 0) t->image = (uint32_t)k;
    if (t->image != i) {
      t->width = scene->textures[t->image].width, t->height = scene->textures[t->image].height;
      continue;
    }
    RC_TRY(read_one(t, &total));
  }
  return RC_OK;
}
