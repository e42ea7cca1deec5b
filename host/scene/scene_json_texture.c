#include "scene/scene_json_texture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* [u, v], the value at the top of the path: two finite numbers. */
static rc_status pair_value(jctx *c, const cJSON *v, double out[2]) {
  if (!cJSON_IsArray(v)) return js_fail(c, "expected [u, v], got %s", js_type_name(v));
  if (cJSON_GetArraySize(v) != 2) return js_fail(c, "expected [u, v], 2 numbers, got %d", cJSON_GetArraySize(v));
  for (int i = 0; i < 2; i++) {
    js_push_index(c, (size_t)i);
    RC_TRY(js_number_value(c, cJSON_GetArrayItem(v, i), &out[i]));
    if (!isfinite(out[i]) || fabs(out[i]) > 1e30) return js_fail(c, "must be finite, at most 1e30 in magnitude");
    js_pop(c);
  }
  return RC_OK;
}

/* Member `key`: [u, v]; `def` for both when absent. */
static rc_status get_pair(jctx *c, const cJSON *m, const char *key, double def, double out[2]) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(m, key);
  out[0] = out[1] = def;
  if (!v) return RC_OK;
  js_push_key(c, key);
  RC_TRY(pair_value(c, v, out));
  js_pop(c);
  return RC_OK;
}

rc_status js_parse_texture(jctx *c, const cJSON *m, rc_scene *s, uint32_t *slot) {
  *slot = 0;
  const cJSON *f = cJSON_GetObjectItemCaseSensitive(m, "texture");
  if (!f) {
    static const char *const options[] = {"texture_filter", "texture_wrap", "texture_scale", "texture_offset",
                                          "texture_mipmap"};
    for (size_t i = 0; i < sizeof options / sizeof *options; i++)
      if (cJSON_GetObjectItemCaseSensitive(m, options[i])) {
        js_push_key(c, options[i]);
        return js_fail(c, "the material has no \"texture\" for it to apply to");
      }
    return RC_OK;
  }
  rc_texture_def t = {0};
  static const char *const filters[] = {"bilinear", "nearest", NULL};
  static const char *const wraps[] = {"repeat", "clamp", NULL};
  uint32_t filter, wrap;
  RC_TRY(js_get_enum(c, m, "texture_filter", filters, 0, &filter));
  RC_TRY(js_get_enum(c, m, "texture_wrap", wraps, 0, &wrap));
  RC_TRY(get_pair(c, m, "texture_scale", 1.0, t.scale));
  RC_TRY(get_pair(c, m, "texture_offset", 0.0, t.offset));
  RC_TRY(js_get_bool(c, m, "texture_mipmap", true, &t.mipmap));
  t.bilinear = filter == 0, t.clamp = wrap == 1;
  js_push_key(c, "texture");
  char path[4096], folder[4096];
  RC_TRY(js_scene_file(c, f, "an image file name", path, folder));
  int line, col;
  js_line_col(c, js_offset(c), &line, &col);
  char field[256];
  js_format_path(c, field, sizeof field);
  snprintf(t.where, sizeof t.where, "%s:%d:%d: error: %s", c->file, line, col, field);
  js_pop(c);
  rc_texture_def *grown = realloc(s->textures, (s->texture_count + 1) * sizeof *grown);
  if (!grown) return RC_ERR_OUT_OF_MEMORY;
  s->textures = grown;
  if (!(t.path = strdup(path)) || !rc_scene_note_input(s, path)) {
    free(t.path);
    return RC_ERR_OUT_OF_MEMORY;
  }
  s->textures[s->texture_count++] = t;
  *slot = (uint32_t)s->texture_count;
  return RC_OK;
}

rc_status js_get_triangle_uvs(jctx *c, const cJSON *o, rc_triangle_def *t) {
  const cJSON *uvs = cJSON_GetObjectItemCaseSensitive(o, "uvs");
  if (!uvs) return RC_OK;
  js_push_key(c, "uvs");
  if (!cJSON_IsArray(uvs) || cJSON_GetArraySize(uvs) != 3)
    return js_fail(c, "expected 3 pairs [u, v], one for each vertex");
  for (int k = 0; k < 3; k++) {
    js_push_index(c, (size_t)k);
    RC_TRY(pair_value(c, cJSON_GetArrayItem(uvs, k), t->uv[k]));
    js_pop(c);
  }
  js_pop(c);
  t->has_uv = true;
  return RC_OK;
}
