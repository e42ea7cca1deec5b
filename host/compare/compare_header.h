/* compare_header.h: what an image says about the render that made it. `vkraycast
 * render` writes the scene hash and every setting that changes a pixel into each image's
 * header (cli/part.h: EXR and PNG keep them); `compare` reads them to say when two files
 * come from different scenes or settings, naming each difference. */
#ifndef RC_COMPARE_HEADER_H
#define RC_COMPARE_HEADER_H

#include <stdbool.h>
#include <stddef.h>

typedef struct rc_image_header {
  bool present;          /* the file has vkraycast's attributes */
  char scene_hash[24];   /* 16 hex digits of the packed scene */
  char settings[512];    /* "backend=gpu precision=f32 spp=4 ..." */
  char device[256];
} rc_image_header;

/* One setting whose value differs: its name and both values ("" where absent). */
typedef struct rc_setting_difference {
  char name[32], a[64], b[64];
} rc_setting_difference;

/* The settings of x and y that differ, in x's order then y's extra names; at most max
 * (the count returned may be larger: all of them are counted). */
int rc_settings_differences(const char *x, const char *y, rc_setting_difference *out, int max);

/* The value of setting `name` in settings into value (truncated to len); false, with
 * value "", when absent. */
bool rc_settings_value(const char *settings, const char *name, char *value, size_t len);

#endif
