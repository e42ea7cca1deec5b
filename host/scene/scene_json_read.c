/* scene_json_read.c: the field readers of the JSON scene format (scene_json_read.h): every
 * field is checked for type, range and finiteness, and a failure names the file, line,
 * column and the field's path. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "math/rcm_mat3.h"
#include "scene/json_locate.h"
#include "scene/scene_json_read.h"

void js_push_key(jctx *c, const char *key) {
  RC_ASSERT(c->depth < RC_JSON_MAX_DEPTH);
  c->path[c->depth].key = key;
  c->path[c->depth].index = 0;
  c->depth++;
}

/* The key on top of the path is a repeat: errors point at its second occurrence. */
void js_mark_repeat(jctx *c) { c->path[c->depth - 1].index = 1; }

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

/* Member `key` of `obj` as a finite number, with the key pushed onto the path (the caller
 * pops it once the value passes its own check). Absent: *present is false and nothing is
 * pushed; an error if required. */
static rc_status member_number(jctx *c, const cJSON *obj, const char *key, bool required, bool *present,
                               double *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  *present = v != NULL;
  if (!v) return required ? js_fail(c, "missing field \"%s\"", key) : RC_OK;
  js_push_key(c, key);
  return js_number_value(c, v, out);
}

/* Member `key` of `obj`: a finite number in [lo, hi]; `def` when absent unless required. */
rc_status js_get_number(jctx *c, const cJSON *obj, const char *key, bool required, double def,
                            double lo, double hi, double *out) {
  bool present;
  RC_TRY(member_number(c, obj, key, required, &present, out));
  if (!present) {
    *out = def;
    return RC_OK;
  }
  if (*out < lo || *out > hi) return js_fail(c, "must be in [%g, %g]", lo, hi);
  js_pop(c);
  return RC_OK;
}

/* Like get_number, with an exclusive lower bound (radius > 0, view_height > 0). */
rc_status js_get_positive(jctx *c, const cJSON *obj, const char *key, bool required,
                              double def, double *out) {
  bool present;
  RC_TRY(member_number(c, obj, key, required, &present, out));
  if (!present) {
    *out = def;
    return RC_OK;
  }
  if (!(*out > 0.0)) return js_fail(c, "must be greater than 0");
  js_pop(c);
  return RC_OK;
}

rc_status js_get_uint(jctx *c, const cJSON *obj, const char *key, bool required, uint32_t def,
                          uint32_t lo, uint32_t hi, uint32_t *out) {
  bool present;
  double x = 0; /* set whenever present (GCC -O2 cannot tell) */
  RC_TRY(member_number(c, obj, key, required, &present, &x));
  if (!present) {
    *out = def;
    return RC_OK;
  }
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
  size_t count = 0;
  for (uint32_t i = 0; names[i]; i++, count++)
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s\"%s\"", i ? ", " : "", names[i]);
  const char *near = rc_nearest(v->valuestring, names, count);
  if (near) return js_fail(c, "expected one of %s; did you mean \"%s\"?", list, near);
  return js_fail(c, "expected one of %s", list);
}

size_t js_offset(const jctx *c) { return rc_json_locate(c->text, c->len, c->path, c->depth); }

size_t js_offset_near(const jctx *c) {
  bool inside = c->base_depth > 0 && c->depth >= c->base_depth && !c->path[c->base_depth - 1].key &&
                c->path[c->base_depth - 1].index == c->base_index;
  if (!inside) return js_offset(c);
  return rc_json_locate_from(c->text, c->len, c->base_off, c->path + c->base_depth, c->depth - c->base_depth);
}

void js_line_col(jctx *c, size_t off, int *line, int *col) {
  if (c->lc_line == 0) c->lc_off = 0, c->lc_line = 1, c->lc_col = 1;
  if (off < c->lc_off) {
    /* Back a little (an object's own place after a mesh file inside it): uncount the
     * lines between; the column from the line's start only when a line was crossed. */
    bool crossed = false;
    for (size_t i = off; i < c->lc_off; i++)
      if (c->text[i] == '\n') c->lc_line--, crossed = true;
    if (crossed) {
      size_t b = off;
      while (b > 0 && c->text[b - 1] != '\n') b--;
      c->lc_col = (int)(off - b) + 1;
    } else {
      c->lc_col -= (int)(c->lc_off - off);
    }
    c->lc_off = off;
  }
  for (size_t i = c->lc_off; i < off && i < c->len; i++) {
    if (c->text[i] == '\n') c->lc_line++, c->lc_col = 1;
    else c->lc_col++;
  }
  c->lc_off = off;
  *line = c->lc_line, *col = c->lc_col;
}

rc_status js_note_origin(jctx *c, rc_scene *s, const size_t before[RC_ORIGIN_KINDS], size_t off, const char *what,
                         uint32_t item) {
  int line, col;
  js_line_col(c, off, &line, &col);
  return rc_scene_note_origin(s, before, line, col, what, item);
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
  if (!rc_name_table_find(&c->materials, v->valuestring, strlen(v->valuestring), out)) {
    /* The nearest defined name, on this error path only (a scene may define 200,000). */
    size_t n = 0;
    for (const cJSON *m = c->material_defs ? c->material_defs->child : NULL; m; m = m->next) n++;
    const char **names = n ? malloc(n * sizeof *names) : NULL;
    size_t k = 0;
    for (const cJSON *m = names ? c->material_defs->child : NULL; m; m = m->next) names[k++] = m->string;
    const char *near = names ? rc_nearest(v->valuestring, names, k) : NULL;
    rc_status st = near ? js_fail(c, "unknown material; did you mean \"%s\"?", near)
                 : n    ? js_fail(c, "unknown material; the scene defines %zu under \"materials\"", n)
                        : js_fail(c, "unknown material: the scene has no \"materials\"");
    free(names);
    return st;
  }
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
  RC_TRY(js_expect_object(c, t));
  static const char *const allowed[] = {"matrix", "translate", "rotate_deg", "scale", NULL};
  RC_TRY(js_check_members(c, t, allowed));
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
        double x = 0;
        RC_TRY(js_number_value(c, cJSON_GetArrayItem(row, j), &x));
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
    RC_TRY(js_get_vec3(c, t, "translate", true, rcm_make_d(0, 0, 0), -HUGE_VAL, &v));
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
      RC_TRY(js_check_members(c, r, rfields));
      double angle;
      RC_TRY(js_get_vec3(c, r, "axis", true, rcm_make_d(0, 0, 0), -HUGE_VAL, &v));
      RC_TRY(js_get_number(c, r, "angle", true, 0, -HUGE_VAL, HUGE_VAL, &angle));
      if (rcm_max_abs_comp_d(v) == 0) {
        js_push_key(c, "axis");
        return js_fail(c, "must not be the zero vector");
      }
      rc_affine rot = rotation(rcm_normalize_d(v), angle);
      js_affine_multiply(out, &rot);
    } else {
      RC_TRY(js_vec3_value(c, r, -HUGE_VAL, &v));
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
      RC_TRY(js_get_number(c, t, "scale", true, 1, -HUGE_VAL, HUGE_VAL, &k));
      v = rcm_make_d(k, k, k);
    } else {
      RC_TRY(js_get_vec3(c, t, "scale", true, rcm_make_d(1, 1, 1), -HUGE_VAL, &v));
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

rc_status js_scene_file(jctx *c, const cJSON *v, const char *what, char path[4096], char folder[4096]) {
  if (!cJSON_IsString(v) || !v->valuestring[0]) return js_fail(c, "expected %s", what);
  const char *slash = strrchr(c->file, '/');
  int nf = snprintf(folder, 4096, "%.*s", slash ? (int)(slash - c->file) : 1, slash ? c->file : ".");
  int np = v->valuestring[0] == '/' || !slash ? snprintf(path, 4096, "%s", v->valuestring)
                                              : snprintf(path, 4096, "%s/%s", folder, v->valuestring);
  if (nf < 0 || np < 0 || nf >= 4096 || np >= 4096) return js_fail(c, "path too long");
  if (!c->allow_outside_paths && !rc_path_within(folder, path))
    return js_fail(c, "lies outside the scene's folder %s (--allow-outside-paths allows it)", folder);
  return RC_OK;
}
