/* scene_json.c: scene format v1 (docs/scene-format.md), JSON through cJSON. Every field
 * is checked for type, range and finiteness; unknown and duplicate fields are errors, so
 * a typo never passes silently. Messages: FILE:LINE:COL: error: FIELD.PATH: what (value). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "math/rcm_mat3.h"
#include "scene/json_locate.h"
#include "scene/mesh.h"
#include "scene/scene_json.h"
#include "scene/scene.h"


void js_push_key(jctx *c, const char *key) {
  RC_ASSERT(c->depth < RC_JSON_MAX_DEPTH);
  c->path[c->depth].key = key;
  c->path[c->depth].index = 0;
  c->depth++;
}

/* The key on top of the path is a repeat: errors point at its second occurrence. */
static void js_mark_repeat(jctx *c) { c->path[c->depth - 1].index = 1; }

void js_push_index(jctx *c, size_t index) {
  RC_ASSERT(c->depth < RC_JSON_MAX_DEPTH);
  c->path[c->depth].key = NULL;
  c->path[c->depth].index = index;
  c->depth++;
}

void js_pop(jctx *c) { c->depth--; }

void js_format_path(const jctx *c, char *out, size_t cap) {
  size_t n = 0;
  out[0] = '\0';
  for (size_t i = 0; i < c->depth && n < cap; i++) {
    if (c->path[i].key)
      n += (size_t)snprintf(out + n, cap - n, "%s%s", i ? "." : "", c->path[i].key);
    else
      n += (size_t)snprintf(out + n, cap - n, "[%zu]", c->path[i].index);
  }
  if (c->depth == 0) snprintf(out, cap, "(scene)");
}

/* Prints the error at the current path; the value shown is the source token there. */
rc_status js_fail(jctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
rc_status js_fail(jctx *c, const char *fmt, ...) {
  char path[256], what[256];
  js_format_path(c, path, sizeof path);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  size_t off = rc_json_locate(c->text, c->len, c->path, c->depth);
  int line, col;
  rc_json_line_col(c->text, c->len, off, &line, &col);
  size_t tok = rc_json_token_length(c->text, c->len, off);
  if (tok > 60) tok = 60;
  if (tok)
    fprintf(stderr, "%s:%d:%d: error: %s: %s (%.*s)\n", c->file, line, col, path, what, (int)tok,
            c->text + off);
  else
    fprintf(stderr, "%s:%d:%d: error: %s: %s\n", c->file, line, col, path, what);
  return RC_ERR_INPUT;
}

const char *js_type_name(const cJSON *v) {
  if (cJSON_IsNumber(v)) return "a number";
  if (cJSON_IsString(v)) return "a string";
  if (cJSON_IsBool(v)) return "a boolean";
  if (cJSON_IsNull(v)) return "null";
  if (cJSON_IsArray(v)) return "an array";
  if (cJSON_IsObject(v)) return "an object";
  return "invalid";
}

/* Rejects members not in `allowed` (NULL-terminated) and repeated members. */
rc_status js_check_members(jctx *c, const cJSON *obj, const char *const *allowed) {
  for (const cJSON *m = obj->child; m; m = m->next) {
    bool known = false;
    for (const char *const *a = allowed; *a; a++) known |= strcmp(*a, m->string) == 0;
    js_push_key(c, m->string);
    if (!known) {
      size_t n = 0;
      while (allowed[n]) n++;
      const char *near = rc_nearest(m->string, allowed, n);
      if (near) return js_fail(c, "unknown field (did you mean \"%s\"?)", near);
      return js_fail(c, "unknown field");
    }
    for (const cJSON *p = obj->child; p != m; p = p->next)
      if (strcmp(p->string, m->string) == 0) {
        js_mark_repeat(c);
        return js_fail(c, "field given twice");
      }
    js_pop(c);
  }
  return RC_OK;
}

rc_status js_expect_object(jctx *c, const cJSON *v) {
  return cJSON_IsObject(v) ? RC_OK : js_fail(c, "expected an object, got %s", js_type_name(v));
}

rc_status js_number_value(jctx *c, const cJSON *v, double *out) {
  if (!cJSON_IsNumber(v)) return js_fail(c, "expected a number, got %s", js_type_name(v));
  if (!isfinite(v->valuedouble)) return js_fail(c, "number is not finite");
  *out = v->valuedouble;
  return RC_OK;
}

/* Member `key` of `obj`: a finite number in [lo, hi]; `def` when absent unless required. */
rc_status js_get_number(jctx *c, const cJSON *obj, const char *key, bool required, double def,
                            double lo, double hi, double *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    if (required) return js_fail(c, "missing field \"%s\"", key);
    *out = def;
    return RC_OK;
  }
  js_push_key(c, key);
  rc_status st = js_number_value(c, v, out);
  if (st != RC_OK) return st;
  if (*out < lo || *out > hi) return js_fail(c, "must be in [%g, %g]", lo, hi);
  js_pop(c);
  return RC_OK;
}

/* Like get_number, with an exclusive lower bound (radius > 0, view_height > 0). */
rc_status js_get_positive(jctx *c, const cJSON *obj, const char *key, bool required,
                              double def, double *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    if (required) return js_fail(c, "missing field \"%s\"", key);
    *out = def;
    return RC_OK;
  }
  js_push_key(c, key);
  rc_status st = js_number_value(c, v, out);
  if (st != RC_OK) return st;
  if (!(*out > 0.0)) return js_fail(c, "must be greater than 0");
  js_pop(c);
  return RC_OK;
}

rc_status js_get_uint(jctx *c, const cJSON *obj, const char *key, bool required, uint32_t def,
                          uint32_t lo, uint32_t hi, uint32_t *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    if (required) return js_fail(c, "missing field \"%s\"", key);
    *out = def;
    return RC_OK;
  }
  js_push_key(c, key);
  double x;
  rc_status st = js_number_value(c, v, &x);
  if (st != RC_OK) return st;
  if (x != floor(x)) return js_fail(c, "expected a whole number");
  if (x < lo || x > hi) return js_fail(c, "must be in [%u, %u]", lo, hi);
  *out = (uint32_t)x;
  js_pop(c);
  return RC_OK;
}

rc_status js_vec3_value(jctx *c, const cJSON *v, double lo, dvec3 *out) {
  if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 3)
    return js_fail(c, "expected an array of 3 numbers, got %s", cJSON_IsArray(v) ? "another length" : js_type_name(v));
  double xyz[3];
  for (int i = 0; i < 3; i++) {
    js_push_index(c, (size_t)i);
    rc_status st = js_number_value(c, cJSON_GetArrayItem(v, i), &xyz[i]);
    if (st != RC_OK) return st;
    if (xyz[i] < lo) return js_fail(c, "must not be negative");
    js_pop(c);
  }
  *out = rcm_make_d(xyz[0], xyz[1], xyz[2]);
  return RC_OK;
}

/* Member `key`: [x, y, z]; lo = 0 for colours and coefficients, -HUGE_VAL for positions. */
rc_status js_get_vec3(jctx *c, const cJSON *obj, const char *key, bool required, dvec3 def,
                          double lo, dvec3 *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    if (required) return js_fail(c, "missing field \"%s\"", key);
    *out = def;
    return RC_OK;
  }
  js_push_key(c, key);
  rc_status st = js_vec3_value(c, v, lo, out);
  if (st != RC_OK) return st;
  js_pop(c);
  return RC_OK;
}

/* A colour that may also be written as one number for all three channels (mirror). */
static rc_status get_color_or_scalar(jctx *c, const cJSON *obj, const char *key, dvec3 *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (v && cJSON_IsNumber(v)) {
    double x;
    rc_status st = js_get_number(c, obj, key, true, 0, 0, HUGE_VAL, &x);
    *out = rcm_make_d(x, x, x);
    return st;
  }
  if (v && !(cJSON_IsArray(v) && cJSON_GetArraySize(v) == 3)) {
    js_push_key(c, key);
    return js_fail(c, "expected a number or an array of 3 numbers, got %s",
                   cJSON_IsArray(v) ? "another length" : js_type_name(v));
  }
  return js_get_vec3(c, obj, key, false, rcm_make_d(0, 0, 0), 0.0, out);
}

rc_status js_get_enum(jctx *c, const cJSON *obj, const char *key, const char *const *names,
                          uint32_t def, uint32_t *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    *out = def;
    return RC_OK;
  }
  js_push_key(c, key);
  if (!cJSON_IsString(v)) return js_fail(c, "expected a string, got %s", js_type_name(v));
  for (uint32_t i = 0; names[i]; i++) {
    if (strcmp(names[i], v->valuestring) == 0) {
      *out = i;
      js_pop(c);
      return RC_OK;
    }
  }
  char list[256] = "";
  for (uint32_t i = 0; names[i]; i++)
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s\"%s\"", i ? ", " : "", names[i]);
  return js_fail(c, "expected one of %s", list);
}

static rc_status parse_image(jctx *c, const cJSON *root, rc_scene *s) {
  const cJSON *img = cJSON_GetObjectItemCaseSensitive(root, "image");
  if (!img) return js_fail(c, "missing field \"image\"");
  js_push_key(c, "image");
  TRY(js_expect_object(c, img));
  static const char *const allowed[] = {"width", "height", "samples_per_pixel", "encoding", "quantize", NULL};
  TRY(js_check_members(c, img, allowed));
  TRY(js_get_uint(c, img, "width", true, 0, 1, RC_MAX_IMAGE_SIDE, &s->width));
  TRY(js_get_uint(c, img, "height", true, 0, 1, RC_MAX_IMAGE_SIDE, &s->height));
  TRY(js_get_uint(c, img, "samples_per_pixel", false, 1, 1, RC_MAX_SAMPLES_PER_PIXEL, &s->samples_per_pixel));
  /* How 8-bit outputs store a linear value (render --encoding and --quantize override). */
  static const char *const encodings[] = {"linear", "srgb", NULL}, *const quantizers[] = {"round", "truncate", NULL};
  uint32_t k;
  TRY(js_get_enum(c, img, "encoding", encodings, 0, &k));
  s->srgb_8bit = k == 1;
  TRY(js_get_enum(c, img, "quantize", quantizers, 0, &k));
  s->truncate_8bit = k == 1;
  js_pop(c);
  return RC_OK;
}

static rc_status parse_camera(jctx *c, const cJSON *root, rc_scene *s) {
  const cJSON *cam = cJSON_GetObjectItemCaseSensitive(root, "camera");
  if (!cam) return js_fail(c, "missing field \"camera\"");
  js_push_key(c, "camera");
  TRY(js_expect_object(c, cam));
  static const char *const allowed[] = {"projection", "eye", "look_at", "up", "fov_y_deg", "view_height", NULL};
  TRY(js_check_members(c, cam, allowed));
  static const char *const projections[] = {"perspective", "parallel", NULL};
  rc_camera_def *k = &s->camera;
  TRY(js_get_enum(c, cam, "projection", projections, RC_PROJECTION_PERSPECTIVE, &k->projection));
  TRY(js_get_vec3(c, cam, "eye", true, rcm_make_d(0, 0, 0), -HUGE_VAL, &k->eye));
  TRY(js_get_vec3(c, cam, "look_at", true, rcm_make_d(0, 0, 0), -HUGE_VAL, &k->look_at));
  TRY(js_get_vec3(c, cam, "up", false, rcm_make_d(0, 1, 0), -HUGE_VAL, &k->up));
  if (k->projection == RC_PROJECTION_PERSPECTIVE) {
    if (cJSON_GetObjectItemCaseSensitive(cam, "view_height")) {
      js_push_key(c, "view_height");
      return js_fail(c, "applies to the parallel projection only");
    }
    TRY(js_get_number(c, cam, "fov_y_deg", false, 45.0, -HUGE_VAL, HUGE_VAL, &k->fov_y_deg));
  } else {
    if (cJSON_GetObjectItemCaseSensitive(cam, "fov_y_deg")) {
      js_push_key(c, "fov_y_deg");
      return js_fail(c, "applies to the perspective projection only");
    }
    TRY(js_get_positive(c, cam, "view_height", true, 0, &k->view_height));
  }
  const char *field = NULL;
  const char *problem = rc_scene_camera_problem(k, &field);
  if (problem) {
    js_push_key(c, field);
    return js_fail(c, "%s", problem);
  }
  js_pop(c);
  return RC_OK;
}

static rc_status parse_materials(jctx *c, const cJSON *root, rc_scene *s) {
  const cJSON *mats = cJSON_GetObjectItemCaseSensitive(root, "materials");
  if (!mats) return RC_OK;
  js_push_key(c, "materials");
  TRY(js_expect_object(c, mats));
  size_t n = (size_t)cJSON_GetArraySize(mats);
  s->materials = rc_alloc(n, sizeof *s->materials, "materials");
  if (!s->materials) return RC_ERR_OUT_OF_MEMORY;
  size_t off = 0;
  for (const cJSON *m = mats->child; m; m = m->next) {
    js_push_key(c, m->string);
    off = m == mats->child ? js_offset(c) : rc_json_next_value(c->text, c->len, off, true);
    size_t before[RC_ORIGIN_KINDS];
    rc_scene_counts(s, before);
    uint32_t index;
    bool twice;
    if (!rc_name_table_insert(&c->materials, m->string, strlen(m->string), (uint32_t)s->material_count, &index,
                              &twice))
      return RC_ERR_OUT_OF_MEMORY;
    if (twice) {
      js_mark_repeat(c);
      return js_fail(c, "material defined twice");
    }
    TRY(js_expect_object(c, m));
    static const char *const allowed[] = {"ambient", "diffuse", "specular", "shininess", "mirror", "emission", NULL};
    TRY(js_check_members(c, m, allowed));
    rc_material_def *d = &s->materials[s->material_count];
    d->name = strdup(m->string);
    if (!d->name) return RC_ERR_OUT_OF_MEMORY;
    s->material_count++;
    dvec3 zero = rcm_make_d(0, 0, 0);
    TRY(js_get_vec3(c, m, "ambient", false, zero, 0.0, &d->ambient));
    TRY(js_get_vec3(c, m, "diffuse", false, zero, 0.0, &d->diffuse));
    TRY(js_get_vec3(c, m, "specular", false, zero, 0.0, &d->specular));
    TRY(js_get_number(c, m, "shininess", false, 1.0, 0.0, HUGE_VAL, &d->shininess));
    TRY(get_color_or_scalar(c, m, "mirror", &d->mirror));
    TRY(js_get_vec3(c, m, "emission", false, zero, 0.0, &d->emission));
    TRY(js_note_origin(c, s, before, off, "materials", UINT32_MAX));
    js_pop(c);
  }
  js_pop(c);
  return RC_OK;
}

static rc_status parse_lights(jctx *c, const cJSON *root, rc_scene *s) {
  const cJSON *lights = cJSON_GetObjectItemCaseSensitive(root, "lights");
  if (!lights) return RC_OK;
  js_push_key(c, "lights");
  if (!cJSON_IsArray(lights)) return js_fail(c, "expected an array, got %s", js_type_name(lights));
  size_t n = (size_t)cJSON_GetArraySize(lights);
  s->lights = rc_alloc(n, sizeof *s->lights, "lights");
  if (!s->lights) return RC_ERR_OUT_OF_MEMORY;
  size_t i = 0, off = 0;
  for (const cJSON *l = lights->child; l; l = l->next, i++) {
    js_push_index(c, i);
    off = i == 0 ? js_offset(c) : rc_json_next_value(c->text, c->len, off, false);
    size_t before[RC_ORIGIN_KINDS];
    rc_scene_counts(s, before);
    TRY(js_expect_object(c, l));
    rc_light_def *d = &s->lights[s->light_count++];
    static const char *const types[] = {"point", "directional", NULL};
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(l, "type");
    if (!type) return js_fail(c, "missing field \"type\"");
    TRY(js_get_enum(c, l, "type", types, 0, &d->type));
    static const char *const point_fields[] = {"type", "position", "intensity", "attenuation", NULL};
    static const char *const dir_fields[] = {"type", "direction", "intensity", NULL};
    bool point = d->type == RC_LIGHT_POINT;
    TRY(js_check_members(c, l, point ? point_fields : dir_fields));
    dvec3 zero = rcm_make_d(0, 0, 0);
    if (point) {
      TRY(js_get_vec3(c, l, "position", true, zero, -HUGE_VAL, &d->position));
      TRY(js_get_vec3(c, l, "attenuation", false, rcm_make_d(0, 0, 1), 0.0, &d->attenuation));
      if (rcm_max_abs_comp_d(d->attenuation) == 0.0) {
        js_push_key(c, "attenuation");
        return js_fail(c, "must not be all zero (the light would be infinitely bright)");
      }
    } else {
      TRY(js_get_vec3(c, l, "direction", true, zero, -HUGE_VAL, &d->direction));
      if (rcm_max_abs_comp_d(d->direction) == 0.0) {
        js_push_key(c, "direction");
        return js_fail(c, "must not be the zero vector");
      }
    }
    TRY(js_get_vec3(c, l, "intensity", true, zero, 0.0, &d->intensity));
    TRY(js_note_origin(c, s, before, off, "lights", (uint32_t)i));
    js_pop(c);
  }
  js_pop(c);
  return RC_OK;
}

size_t js_offset(const jctx *c) { return rc_json_locate(c->text, c->len, c->path, c->depth); }

rc_status js_note_origin(jctx *c, rc_scene *s, const size_t before[RC_ORIGIN_KINDS], size_t off, const char *what,
                         uint32_t item) {
  if (off < c->lc_off || c->lc_line == 0) c->lc_off = 0, c->lc_line = 1, c->lc_col = 1;
  for (size_t i = c->lc_off; i < off && i < c->len; i++) {
    if (c->text[i] == '\n') c->lc_line++, c->lc_col = 1;
    else c->lc_col++;
  }
  c->lc_off = off;
  return rc_scene_note_origin(s, before, c->lc_line, c->lc_col, what, item);
}

rc_status js_get_bool(jctx *c, const cJSON *obj, const char *key, bool def, bool *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  *out = def;
  if (!v) return RC_OK;
  js_push_key(c, key);
  if (!cJSON_IsBool(v)) return js_fail(c, "expected true or false, got %s", js_type_name(v));
  *out = cJSON_IsTrue(v);
  js_pop(c);
  return RC_OK;
}

rc_status js_get_material_ref(jctx *c, const cJSON *obj, uint32_t *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "material");
  if (!v) return js_fail(c, "missing field \"material\"");
  js_push_key(c, "material");
  if (!cJSON_IsString(v)) return js_fail(c, "expected a material name, got %s", js_type_name(v));
  if (!rc_name_table_find(&c->materials, v->valuestring, strlen(v->valuestring), out))
    return js_fail(c, "unknown material");
  js_pop(c);
  return RC_OK;
}

void js_affine_identity(rc_affine *a) {
  memset(a, 0, sizeof *a);
  a->m[0][0] = a->m[1][1] = a->m[2][2] = 1;
}

/* a = a * b (b applied first to points). */
void js_affine_multiply(rc_affine *a, const rc_affine *b) {
  rc_affine r;
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 4; j++) {
      r.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] + a->m[i][2] * b->m[2][j] + (j == 3 ? a->m[i][3] : 0);
    }
  }
  *a = r;
}

static rc_affine rotation(dvec3 axis, double deg) {
  double r[3][3];
  rcm_mat3_rotation_d(axis, deg, r);
  rc_affine a = {{{r[0][0], r[0][1], r[0][2], 0}, {r[1][0], r[1][1], r[1][2], 0}, {r[2][0], r[2][1], r[2][2], 0}}};
  return a;
}

/* "transform": {"matrix", "translate", "rotate_deg", "scale"}, composed so that points
 * are scaled first, then rotated, translated, and last taken through the raw matrix:
 * M = matrix * T * R * S. rotate_deg is {"axis": [x, y, z], "angle": a} or Euler angles
 * [x, y, z] applied about X, then Y, then Z. */
rc_status js_get_transform(jctx *c, const cJSON *obj, rc_affine *out, bool *present) {
  js_affine_identity(out);
  const cJSON *t = cJSON_GetObjectItemCaseSensitive(obj, "transform");
  *present = t != NULL;
  if (!t) return RC_OK;
  js_push_key(c, "transform");
  TRY(js_expect_object(c, t));
  static const char *const allowed[] = {"matrix", "translate", "rotate_deg", "scale", NULL};
  TRY(js_check_members(c, t, allowed));
  const cJSON *m = cJSON_GetObjectItemCaseSensitive(t, "matrix");
  if (m) {
    js_push_key(c, "matrix");
    if (!cJSON_IsArray(m) || cJSON_GetArraySize(m) != 4) return js_fail(c, "expected 4 rows of 4 numbers");
    for (int i = 0; i < 4; i++) {
      js_push_index(c, (size_t)i);
      const cJSON *row = cJSON_GetArrayItem(m, i);
      if (!cJSON_IsArray(row) || cJSON_GetArraySize(row) != 4) return js_fail(c, "expected a row of 4 numbers");
      for (int j = 0; j < 4; j++) {
        js_push_index(c, (size_t)j);
        double x;
        TRY(js_number_value(c, cJSON_GetArrayItem(row, j), &x));
        if (i < 3) out->m[i][j] = x;
        else if (x != (j == 3 ? 1.0 : 0.0)) return js_fail(c, "the last row must be [0, 0, 0, 1] (affine transforms only)");
        js_pop(c);
      }
      js_pop(c);
    }
    js_pop(c);
  }
  dvec3 v;
  if (cJSON_GetObjectItemCaseSensitive(t, "translate")) {
    TRY(js_get_vec3(c, t, "translate", true, rcm_make_d(0, 0, 0), -HUGE_VAL, &v));
    rc_affine tr;
    js_affine_identity(&tr);
    tr.m[0][3] = v.x, tr.m[1][3] = v.y, tr.m[2][3] = v.z;
    js_affine_multiply(out, &tr);
  }
  const cJSON *r = cJSON_GetObjectItemCaseSensitive(t, "rotate_deg");
  if (r) {
    js_push_key(c, "rotate_deg");
    if (cJSON_IsObject(r)) {
      static const char *const rfields[] = {"axis", "angle", NULL};
      TRY(js_check_members(c, r, rfields));
      double angle;
      TRY(js_get_vec3(c, r, "axis", true, rcm_make_d(0, 0, 0), -HUGE_VAL, &v));
      TRY(js_get_number(c, r, "angle", true, 0, -HUGE_VAL, HUGE_VAL, &angle));
      if (rcm_max_abs_comp_d(v) == 0) {
        js_push_key(c, "axis");
        return js_fail(c, "must not be the zero vector");
      }
      rc_affine rot = rotation(rcm_normalize_d(v), angle);
      js_affine_multiply(out, &rot);
    } else {
      TRY(js_vec3_value(c, r, -HUGE_VAL, &v));
      rc_affine rz = rotation(rcm_make_d(0, 0, 1), v.z), ry = rotation(rcm_make_d(0, 1, 0), v.y),
                rx = rotation(rcm_make_d(1, 0, 0), v.x);
      js_affine_multiply(out, &rz);
      js_affine_multiply(out, &ry);
      js_affine_multiply(out, &rx);
    }
    js_pop(c);
  }
  const cJSON *sc = cJSON_GetObjectItemCaseSensitive(t, "scale");
  if (sc) {
    if (cJSON_IsNumber(sc)) {
      double k;
      TRY(js_get_number(c, t, "scale", true, 1, -HUGE_VAL, HUGE_VAL, &k));
      v = rcm_make_d(k, k, k);
    } else {
      TRY(js_get_vec3(c, t, "scale", true, rcm_make_d(1, 1, 1), -HUGE_VAL, &v));
    }
    if (v.x == 0 || v.y == 0 || v.z == 0) {
      js_push_key(c, "scale");
      return js_fail(c, "a zero scale makes the object vanish");
    }
    rc_affine s3;
    js_affine_identity(&s3);
    s3.m[0][0] = v.x, s3.m[1][1] = v.y, s3.m[2][2] = v.z;
    js_affine_multiply(out, &s3);
  }
  /* A singular linear part flattens the object onto a plane or a line (a raw matrix can
   * be singular with every scale non-zero); so does one whose inverse overflows. */
  double a[3][3], inv[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) a[i][j] = out->m[i][j];
  if (!rcm_mat3_inverse_d(a, inv)) return js_fail(c, "is singular (determinant %g): the object would vanish", rcm_mat3_det_d(a));
  js_pop(c);
  return RC_OK;
}

/* A mesh object: the file relative to the scene file's folder. */
rc_status js_load_mesh(jctx *c, const cJSON *o, rc_scene *s, const rc_affine *m, int material) {
  const cJSON *f = cJSON_GetObjectItemCaseSensitive(o, "file");
  if (!f) return js_fail(c, "missing field \"file\"");
  js_push_key(c, "file");
  if (!cJSON_IsString(f) || !f->valuestring[0]) return js_fail(c, "expected a file name");
  char path[4096], folder[4096];
  const char *slash = strrchr(c->file, '/');
  int nf = snprintf(folder, sizeof folder, "%.*s", slash ? (int)(slash - c->file) : 1, slash ? c->file : ".");
  int np = f->valuestring[0] == '/' || !slash ? snprintf(path, sizeof path, "%s", f->valuestring)
                                              : snprintf(path, sizeof path, "%s/%s", folder, f->valuestring);
  if (nf < 0 || np < 0 || (size_t)nf >= sizeof folder || (size_t)np >= sizeof path) return js_fail(c, "path too long");
  if (!c->allow_outside_paths && !rc_path_within(folder, path))
    return js_fail(c, "lies outside the scene's folder %s (--allow-outside-paths allows it)", folder);
  size_t off = rc_json_locate(c->text, c->len, c->path, c->depth);
  int line, col;
  rc_json_line_col(c->text, c->len, off, &line, &col);
  char where[4400];
  char fpath[256];
  js_format_path(c, fpath, sizeof fpath);
  snprintf(where, sizeof where, "%s:%d:%d: error: %s", c->file, line, col, fpath);
  js_pop(c);
  if (cJSON_GetObjectItemCaseSensitive(o, "material")) {
    uint32_t id;
    TRY(js_get_material_ref(c, o, &id));
    material = (int)id;
  }
  return rc_mesh_load(path, c->allow_outside_paths ? NULL : folder, m, material, s, where);
}

static rc_status parse_objects(jctx *c, const cJSON *root, rc_scene *s) {
  const cJSON *objs = cJSON_GetObjectItemCaseSensitive(root, "objects");
  if (!objs) return RC_OK;
  js_push_key(c, "objects");
  if (!cJSON_IsArray(objs)) return js_fail(c, "expected an array, got %s", js_type_name(objs));
  size_t n = (size_t)cJSON_GetArraySize(objs);
  s->spheres = rc_alloc(n, sizeof *s->spheres, "spheres");
  if (!s->spheres) return RC_ERR_OUT_OF_MEMORY;
  size_t i = 0, off = 0;
  for (const cJSON *o = objs->child; o; o = o->next, i++) {
    js_push_index(c, i);
    off = i == 0 ? js_offset(c) : rc_json_next_value(c->text, c->len, off, false);
    size_t before[RC_ORIGIN_KINDS];
    rc_scene_counts(s, before);
    TRY(js_expect_object(c, o));
    static const char *const types[] = {"sphere",     "triangle",    "mesh", "quadric", "ellipsoid", "cylinder", "cone",
                                        "paraboloid", "hyperboloid", "box",  "csg",     "plane", NULL};
    const cJSON *tv = cJSON_GetObjectItemCaseSensitive(o, "type");
    if (!tv) return js_fail(c, "missing field \"type\"");
    if (cJSON_IsString(tv) && js_is_quadric_type(tv->valuestring)) {
      TRY(js_parse_quadric_object(c, o, s));
      TRY(js_note_origin(c, s, before, off, "objects", (uint32_t)i));
      js_pop(c);
      continue;
    }
    uint32_t type;
    TRY(js_get_enum(c, o, "type", types, 0, &type));
    dvec3 zero = rcm_make_d(0, 0, 0);
    rc_affine m;
    bool transformed;
    if (type == 0) {
      static const char *const allowed[] = {"type", "center", "radius", "material", "transform", NULL};
      TRY(js_check_members(c, o, allowed));
      rc_sphere_def *d = &s->spheres[s->sphere_count++];
      TRY(js_get_vec3(c, o, "center", true, zero, -HUGE_VAL, &d->center));
      TRY(js_get_positive(c, o, "radius", true, 0, &d->radius));
      TRY(js_get_material_ref(c, o, &d->material));
      TRY(js_get_transform(c, o, &m, &transformed));
      d->transformed = transformed;
      d->world_from_object = m;
    } else if (type == 1) {
      static const char *const allowed[] = {"type", "vertices", "material", "transform", NULL};
      TRY(js_check_members(c, o, allowed));
      rc_triangle_def d = {0};
      const cJSON *vs = cJSON_GetObjectItemCaseSensitive(o, "vertices");
      if (!vs) return js_fail(c, "missing field \"vertices\"");
      js_push_key(c, "vertices");
      if (!cJSON_IsArray(vs) || cJSON_GetArraySize(vs) != 3)
        return js_fail(c, "expected an array of 3 points");
      for (int k = 0; k < 3; k++) {
        js_push_index(c, (size_t)k);
        TRY(js_vec3_value(c, cJSON_GetArrayItem(vs, k), -HUGE_VAL, &d.v[k]));
        js_pop(c);
      }
      js_pop(c);
      TRY(js_get_material_ref(c, o, &d.material));
      TRY(js_get_transform(c, o, &m, &transformed));
      for (int k = 0; k < 3; k++) d.v[k] = rc_affine_point(&m, d.v[k]);
      TRY(rc_scene_add_triangle(s, &d));
    } else {
      static const char *const allowed[] = {"type", "file", "material", "transform", NULL};
      TRY(js_check_members(c, o, allowed));
      TRY(js_get_transform(c, o, &m, &transformed));
      TRY(js_load_mesh(c, o, s, &m, -1));
    }
    TRY(js_note_origin(c, s, before, off, "objects", (uint32_t)i));
    js_pop(c);
  }
  js_pop(c);
  return RC_OK;
}

static rc_status parse_root(jctx *c, const cJSON *root, rc_scene *s) {
  TRY(js_expect_object(c, root));
  static const char *const allowed[] = {"version", "image", "camera", "background", "ambient_light",
                                        "specular_model", "seed", "quality", "materials", "lights",
                                        "objects", NULL};
  TRY(js_check_members(c, root, allowed));
  uint32_t version;
  TRY(js_get_uint(c, root, "version", false, 1, 1, 1, &version));
  TRY(parse_image(c, root, s));
  TRY(parse_camera(c, root, s));
  TRY(js_get_vec3(c, root, "background", false, rcm_make_d(0, 0, 0), 0.0, &s->background));
  TRY(js_get_vec3(c, root, "ambient_light", false, rcm_make_d(1, 1, 1), 0.0, &s->ambient_light));
  static const char *const models[] = {"blinn-phong", "phong", NULL};
  TRY(js_get_enum(c, root, "specular_model", models, RC_SPECULAR_BLINN_PHONG, &s->specular_model));
  TRY(js_get_uint(c, root, "seed", false, 0, 0, UINT32_MAX, &s->seed));
  s->reflection_depth = 5;
  s->quality = rc_quality_default();
  const cJSON *q = cJSON_GetObjectItemCaseSensitive(root, "quality");
  if (q) {
    js_push_key(c, "quality");
    TRY(js_expect_object(c, q));
    static const char *const qfields[] = {"reflection_depth", "precision", "sphere_intersection",
                                          "triangle_intersection", "shadow_offset", "shadow_epsilon",
                                          "camera_relative", "shadows", NULL};
    TRY(js_check_members(c, q, qfields));
    rc_quality *k = &s->quality;
    TRY(js_get_uint(c, q, "reflection_depth", false, 5, 0, RC_MAX_REFLECTION_DEPTH, &s->reflection_depth));
    TRY(js_get_enum(c, q, "precision", rc_precision_names, k->precision, &k->precision));
    TRY(js_get_enum(c, q, "sphere_intersection", rc_sphere_formula_names, k->sphere, &k->sphere));
    TRY(js_get_enum(c, q, "triangle_intersection", rc_triangle_formula_names, k->triangle, &k->triangle));
    TRY(js_get_enum(c, q, "shadow_offset", rc_offset_names, k->offset, &k->offset));
    TRY(js_get_positive(c, q, "shadow_epsilon", false, k->offset_epsilon, &k->offset_epsilon));
    TRY(js_get_bool(c, q, "camera_relative", k->camera_relative, &k->camera_relative));
    TRY(js_get_bool(c, q, "shadows", k->shadows, &k->shadows));
    js_pop(c);
  }
  TRY(parse_materials(c, root, s));
  TRY(parse_lights(c, root, s));
  TRY(parse_objects(c, root, s));
  return RC_OK;
}

rc_status rc_scene_parse_json(const char *path, const char *text, size_t len, const rc_load_options *options,
                              rc_scene *scene) {
  memset(scene, 0, sizeof *scene);
  scene->path = strdup(path);
  jctx c = {.file = path, .text = text, .len = len, .allow_outside_paths = options && options->allow_outside_paths};
  if (rc_scene_check_text(path, text, len) != RC_OK) return RC_ERR_INPUT;
  size_t nul = rc_json_find_nul_escape(text, len);
  if (nul < len) {
    int line, col;
    rc_json_line_col(text, len, nul, &line, &col);
    fprintf(stderr, "%s:%d:%d: error: a \\u0000 escape: names and strings may not hold a NUL character\n", path,
            line, col);
    return RC_ERR_INPUT;
  }
  const char *end = NULL;
  cJSON *root = cJSON_ParseWithLengthOpts(text, len, &end, false);
  if (!root) {
    size_t off = end ? (size_t)(end - text) : 0;
    if (off > len) off = len;
    int line, col;
    rc_json_line_col(text, len, off, &line, &col);
    size_t opened = 0;
    if (off >= len || rc_json_truncated(text, len, off, &opened)) {
      /* The file ends inside a value: say so at its end, and where the value began. */
      rc_json_line_col(text, len, len, &line, &col);
      if (off >= len && opened == len) {
        fprintf(stderr, "%s:%d:%d: error: JSON syntax: unexpected end of file\n", path, line, col);
      } else {
        int oline, ocol;
        rc_json_line_col(text, len, opened, &oline, &ocol);
        fprintf(stderr, "%s:%d:%d: error: JSON syntax: unexpected end of input inside the %s opened at %d:%d "
                "(is the file cut short?)\n", path, line, col, text[opened] == '[' ? "array" : text[opened] == '"' ?
                "string" : "object", oline, ocol);
      }
    } else {
      char snippet[64];
      rc_json_quote(text + off, len - off, 12, snippet, sizeof snippet);
      fprintf(stderr, "%s:%d:%d: error: JSON syntax: unexpected %s\n", path, line, col, snippet);
    }
    return RC_ERR_INPUT;
  }
  /* Anything after the top-level value other than white space is a syntax error too. */
  size_t off = (size_t)(end - text);
  while (off < len && strchr(" \t\r\n", text[off]) && text[off]) off++;
  rc_status st;
  if (off < len) {
    int line, col;
    rc_json_line_col(text, len, off, &line, &col);
    fprintf(stderr, "%s:%d:%d: error: JSON syntax: text after the scene object\n", path, line, col);
    st = RC_ERR_INPUT;
  } else {
    st = parse_root(&c, root, scene);
  }
  cJSON_Delete(root);
  rc_name_table_free(&c.materials);
  return st;
}
