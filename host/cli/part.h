/* part.h: what an image file says about the render it came from, so that `vkraycast
 * merge` can put the parts of a frame together and refuse parts of different renders
 * (docs/cluster.md). Every image `render` writes carries it as string attributes of its
 * header; EXR keeps them (other formats may drop them, so parts are EXR files). */
#ifndef RC_PART_H
#define RC_PART_H

#include "image/image_io.h"
#include "base/region.h"

#define RC_PART_FIELDS 8

typedef struct rc_part_info {
  uint32_t width, height;               /* the full frame */
  rc_region region;                     /* the pixels this file holds */
  uint32_t shard_index, shard_count;    /* --shard I/N; count 0: not a shard */
  char scene_hash[24];                  /* rc_packed_scene_hash, 16 hex digits */
  char settings[512];                   /* every setting that changes a pixel, "name=value ..." */
  char device[256];                     /* what rendered it (a note: merge warns on a mix) */
} rc_part_info;

/* The header attributes of `info`, pointing into `text` (which must outlive them). */
int rc_part_meta(const rc_part_info *info, rc_image_meta meta[RC_PART_FIELDS], char text[RC_PART_FIELDS][64]);

/* Reads `info` from an image's header: true, or false with the first missing or
 * malformed attribute's name in *missing. */
bool rc_part_read(const rc_image_reader *r, rc_part_info *info, const char **missing);

/* The first setting ("name=value") in which two settings strings differ, into a and b;
 * false when they are equal. */
bool rc_part_settings_differ(const char *x, const char *y, char *a, size_t a_len, char *b, size_t b_len);

/* The value of setting `name` ("srgb" for "encoding" in "... encoding=srgb ...") into
 * value (truncated to len); "" when absent. */
void rc_part_setting(const char *settings, const char *name, char *value, size_t len);

/* An 8-bit encoding as settings say it: "encoding=linear|srgb|gammaG exposure=E", and
 * back (a setting absent, as in parts of older builds: linear, exposure 0); false when
 * what the settings say is not an encoding render writes. */
void rc_part_encoding_text(rc_encoding e, char *out, size_t len);
bool rc_part_encoding(const char *settings, rc_encoding *e);

#endif
