#include "cli/part.h"

#include "compare/compare_header.h"
#include "scene/scene.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

/* Attribute names: a prefix of our own, which OpenImageIO's EXR writer keeps. */
#define NAME_FRAME "vkraycast:frame"
#define NAME_REGION "vkraycast:region"
#define NAME_SHARD "vkraycast:shard"
#define NAME_SCENE "vkraycast:scene_hash"
#define NAME_SETTINGS "vkraycast:settings"
#define NAME_DEVICE "vkraycast:device"

int rc_part_meta(const rc_part_info *info, rc_image_meta meta[RC_PART_FIELDS], char text[RC_PART_FIELDS][64]) {
  int n = 0;
  snprintf(text[n], sizeof text[n], "%" PRIu32 " %" PRIu32, info->width, info->height);
  meta[n] = (rc_image_meta){NAME_FRAME, text[n]}, n++;
  const rc_region r = info->region;
  snprintf(text[n], sizeof text[n], "%" PRIu32 " %" PRIu32 " %" PRIu32 " %" PRIu32, r.x0, r.y0, r.x1, r.y1);
  meta[n] = (rc_image_meta){NAME_REGION, text[n]}, n++;
  if (info->shard_count) {
    snprintf(text[n], sizeof text[n], "%" PRIu32 "/%" PRIu32, info->shard_index, info->shard_count);
    meta[n] = (rc_image_meta){NAME_SHARD, text[n]}, n++;
  }
  meta[n++] = (rc_image_meta){NAME_SCENE, info->scene_hash};
  meta[n++] = (rc_image_meta){NAME_SETTINGS, info->settings};
  meta[n++] = (rc_image_meta){NAME_DEVICE, info->device};
  return n;
}

bool rc_part_read(const rc_image_reader *r, rc_part_info *info, const char **missing) {
  memset(info, 0, sizeof *info);
  char v[64];
  char tail;
  *missing = NAME_FRAME;
  if (!rc_image_reader_meta(r, NAME_FRAME, v, sizeof v) ||
      sscanf(v, "%" SCNu32 " %" SCNu32 " %c", &info->width, &info->height, &tail) != 2)
    return false;
  *missing = NAME_REGION;
  rc_region *g = &info->region;
  if (!rc_image_reader_meta(r, NAME_REGION, v, sizeof v) ||
      sscanf(v, "%" SCNu32 " %" SCNu32 " %" SCNu32 " %" SCNu32 " %c", &g->x0, &g->y0, &g->x1, &g->y1, &tail) != 4)
    return false;
  *missing = NAME_SHARD;
  /* Present, it names a shard: render writes no count 0 (it leaves the attribute out). */
  if (rc_image_reader_meta(r, NAME_SHARD, v, sizeof v) &&
      (sscanf(v, "%" SCNu32 "/%" SCNu32 " %c", &info->shard_index, &info->shard_count, &tail) != 2 ||
       info->shard_count == 0))
    return false;
  *missing = NAME_SCENE;
  if (!rc_image_reader_meta(r, NAME_SCENE, info->scene_hash, sizeof info->scene_hash)) return false;
  *missing = NAME_SETTINGS;
  if (!rc_image_reader_meta(r, NAME_SETTINGS, info->settings, sizeof info->settings)) return false;
  *missing = NAME_DEVICE;
  if (!rc_image_reader_meta(r, NAME_DEVICE, info->device, sizeof info->device)) return false;
  *missing = NULL;
  return true;
}

/* Both through compare/compare_header.c, which reads settings strings for compare too. */
bool rc_part_settings_differ(const char *x, const char *y, char *a, size_t a_len, char *b, size_t b_len) {
  rc_setting_difference d;
  if (rc_settings_differences(x, y, &d, 1) == 0) return false;
  snprintf(a, a_len, "%s%s%s", d.a[0] ? d.name : "", d.a[0] ? "=" : "", d.a);
  snprintf(b, b_len, "%s%s%s", d.b[0] ? d.name : "", d.b[0] ? "=" : "", d.b);
  return true;
}

void rc_part_setting(const char *settings, const char *name, char *value, size_t len) {
  rc_settings_value(settings, name, value, len);
}

void rc_part_encoding_text(rc_encoding e, char *out, size_t len) {
  char curve[32];
  if (e.curve == RC_CURVE_GAMMA)
    snprintf(curve, sizeof curve, "gamma%.9g", (double)e.gamma);
  else
    snprintf(curve, sizeof curve, "%s", e.curve == RC_CURVE_SRGB ? "srgb" : "linear");
  snprintf(out, len, "encoding=%s exposure=%.9g", curve, (double)e.exposure);
}

/* A whole number text: strtod's, with nothing left over. */
static bool whole_number(const char *text, double *out) {
  char *end;
  *out = strtod(text, &end);
  return end != text && *end == '\0' && isfinite(*out);
}

bool rc_part_encoding(const char *settings, rc_encoding *e) {
  *e = rc_encoding_linear();
  char v[64];
  double x = 0;
  rc_part_setting(settings, "encoding", v, sizeof v);
  if (strcmp(v, "srgb") == 0) {
    e->curve = RC_CURVE_SRGB;
  } else if (strncmp(v, "gamma", 5) == 0) {
    if (!whole_number(v + 5, &x) || !(x >= RC_MIN_GAMMA && x <= RC_MAX_GAMMA)) return false;
    e->curve = RC_CURVE_GAMMA, e->gamma = (float)x;
  } else if (v[0] && strcmp(v, "linear") != 0) {
    return false;
  }
  rc_part_setting(settings, "exposure", v, sizeof v);
  double stops = 0;
  if (v[0] && (!whole_number(v, &stops) || fabs(stops) > RC_MAX_EXPOSURE)) return false;
  e->exposure = (float)stops;
  return true;
}
