#include "aov.h"

#include <stdlib.h>
#include <string.h>

const char *const rc_aov_channel_names[RC_AOV_CHANNELS] = {"R", "G", "B", "hit", "object", "t",
                                                           "N.X", "N.Y", "N.Z", "shadow"};

void rc_aov_pack(const float *rgb, const gpu_aov *aov, size_t count, float *out) {
  for (size_t i = 0; i < count; i++) {
    const gpu_aov *a = &aov[i];
    const float v[RC_AOV_CHANNELS] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], a->hit,      a->object,
                                      a->t,       a->normal.x,    a->normal.y,    a->normal.z, a->shadow_bits};
    memcpy(out + i * RC_AOV_CHANNELS, v, sizeof v);
  }
}

static int find(char names[][32], int count, const char *name) {
  for (int i = 0; i < count; i++)
    if (strcmp(names[i], name) == 0) return i;
  return -1;
}

bool rc_aov_find_channels(char names[][32], int count, rc_aov_layout *layout) {
  for (int i = 0; i < RC_AOV_CHANNELS; i++)
    if (find(names, count, rc_aov_channel_names[i]) < 0) return false;
  layout->hit = find(names, count, "hit");
  layout->object = find(names, count, "object");
  layout->shadow = find(names, count, "shadow");
  return true;
}

void rc_aov_compare_decisions(const float *a, const rc_aov_layout *la, const float *b, const rc_aov_layout *lb, int w,
                              int h, int c, rc_compare_result *r) {
  r->decisions = true;
  for (size_t i = 0; i < (size_t)w * h; i++) {
    const float *x = a + i * c, *y = b + i * c;
    bool same_hit = x[la->hit] == y[lb->hit];
    bool same_object = same_hit && x[la->object] == y[lb->object];
    r->hit_mismatch += !same_hit;
    r->object_mismatch += same_hit && !same_object;
    r->shadow_mismatch += same_object && x[la->shadow] != y[lb->shadow];
  }
}
