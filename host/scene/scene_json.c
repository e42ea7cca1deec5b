/* scene_json.c: scene format v1 (docs/scene-format.md), JSON through cJSON: the root, the
 * image, camera, materials, lights and the objects list; quadrics and composites are
 * scene_quadric.c's, mesh files scene_json_mesh.c's, and every field is read through
 * scene_json_read.c. Unknown and duplicate fields are errors, so a typo never passes
 * silently. Messages: FILE:LINE:COL: error: FIELD.PATH: what (value). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "math/rcm_mat3.h"
#include "scene/json_locate.h"
#include "scene/scene.h"
#include "scene/scene_json_mesh.h"
#include "scene/scene_json_texture.h"
#include "scene/scene_patch.h"
#include "scene/scene_quadric.h"

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

static rc_status parse_image(jctx *c, const cJSON *root, rc_scene *s) {
  const cJSON *img = cJSON_GetObjectItemCaseSensitive(root, "image");
  if (!img) return js_fail(c, "missing field \"image\"");
  js_push_key(c, "image");
  RC_TRY(js_expect_object(c, img));
  static const char *const allowed[] = {"width",    "height",   "samples_per_pixel", "encoding", "gamma",
                                        "exposure", "quantize", NULL};
  RC_TRY(js_check_members(c, img, allowed));
  RC_TRY(js_get_uint(c, img, "width", true, 0, 1, RC_MAX_IMAGE_SIDE, &s->width));
  RC_TRY(js_get_uint(c, img, "height", true, 0, 1, RC_MAX_IMAGE_SIDE, &s->height));
  RC_TRY(js_get_uint(c, img, "samples_per_pixel", false, 1, 1, RC_MAX_SAMPLES_PER_PIXEL, &s->samples_per_pixel));
  /* How 8-bit outputs store a linear value (render --encoding and --quantize override). */
  static const char *const encodings[] = {"linear", "srgb", "gamma", NULL},
                           *const quantizers[] = {"round", "truncate", NULL};
  uint32_t k;
  RC_TRY(js_get_enum(c, img, "encoding", encodings, RC_SCENE_ENCODING_LINEAR, &s->encoding_8bit));
  if (s->encoding_8bit != RC_SCENE_ENCODING_GAMMA && cJSON_GetObjectItemCaseSensitive(img, "gamma")) {
    js_push_key(c, "gamma");
    return js_fail(c, "applies only with \"encoding\": \"gamma\"");
  }
  RC_TRY(js_get_number(c, img, "gamma", false, RC_DEFAULT_GAMMA, RC_MIN_GAMMA, RC_MAX_GAMMA, &s->gamma_8bit));
  RC_TRY(js_get_number(c, img, "exposure", false, 0, -RC_MAX_EXPOSURE, RC_MAX_EXPOSURE, &s->exposure_8bit));
  RC_TRY(js_get_enum(c, img, "quantize", quantizers, 0, &k));
  s->truncate_8bit = k == 1;
  js_pop(c);
  return RC_OK;
}

static rc_status parse_camera(jctx *c, const cJSON *root, rc_scene *s) {
  const cJSON *cam = cJSON_GetObjectItemCaseSensitive(root, "camera");
  if (!cam) return js_fail(c, "missing field \"camera\"");
  js_push_key(c, "camera");
  RC_TRY(js_expect_object(c, cam));
  static const char *const allowed[] = {"projection", "eye", "look_at", "up", "fov_y_deg", "view_height", NULL};
  RC_TRY(js_check_members(c, cam, allowed));
  static const char *const projections[] = {"perspective", "parallel", NULL};
  rc_camera_def *k = &s->camera;
  RC_TRY(js_get_enum(c, cam, "projection", projections, RC_PROJECTION_PERSPECTIVE, &k->projection));
  RC_TRY(js_get_vec3(c, cam, "eye", true, rcm_make_d(0, 0, 0), -HUGE_VAL, &k->eye));
  RC_TRY(js_get_vec3(c, cam, "look_at", true, rcm_make_d(0, 0, 0), -HUGE_VAL, &k->look_at));
  RC_TRY(js_get_vec3(c, cam, "up", false, rcm_make_d(0, 1, 0), -HUGE_VAL, &k->up));
  if (k->projection == RC_PROJECTION_PERSPECTIVE) {
    if (cJSON_GetObjectItemCaseSensitive(cam, "view_height")) {
      js_push_key(c, "view_height");
      return js_fail(c, "applies to the parallel projection only");
    }
    RC_TRY(js_get_number(c, cam, "fov_y_deg", false, 45.0, -HUGE_VAL, HUGE_VAL, &k->fov_y_deg));
  } else {
    if (cJSON_GetObjectItemCaseSensitive(cam, "fov_y_deg")) {
      js_push_key(c, "fov_y_deg");
      return js_fail(c, "applies to the perspective projection only");
    }
    RC_TRY(js_get_positive(c, cam, "view_height", true, 0, &k->view_height));
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
  RC_TRY(js_expect_object(c, mats));
  c->material_defs = mats;
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
    RC_TRY(js_expect_object(c, m));
    static const char *const allowed[] = {"ambient",        "diffuse",      "specular",      "shininess",
                                          "mirror",         "emission",     "texture",       "texture_filter",
                                          "texture_wrap",   "texture_scale", "texture_offset", "texture_mipmap",
                                          NULL};
    RC_TRY(js_check_members(c, m, allowed));
    rc_material_def *d = &s->materials[s->material_count];
    d->name = strdup(m->string);
    if (!d->name) return RC_ERR_OUT_OF_MEMORY;
    s->material_count++;
    dvec3 zero = rcm_make_d(0, 0, 0);
    RC_TRY(js_get_vec3(c, m, "ambient", false, zero, 0.0, &d->ambient));
    RC_TRY(js_get_vec3(c, m, "diffuse", false, zero, 0.0, &d->diffuse));
    RC_TRY(js_get_vec3(c, m, "specular", false, zero, 0.0, &d->specular));
    RC_TRY(js_get_number(c, m, "shininess", false, 1.0, 0.0, HUGE_VAL, &d->shininess));
    RC_TRY(get_color_or_scalar(c, m, "mirror", &d->mirror));
    RC_TRY(js_get_vec3(c, m, "emission", false, zero, 0.0, &d->emission));
    RC_TRY(js_parse_texture(c, m, s, &d->texture));
    RC_TRY(js_note_origin(c, s, before, off, "materials", UINT32_MAX));
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
    RC_TRY(js_expect_object(c, l));
    rc_light_def *d = &s->lights[s->light_count++];
    static const char *const types[] = {"point", "directional", NULL};
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(l, "type");
    if (!type) return js_fail(c, "missing field \"type\"");
    RC_TRY(js_get_enum(c, l, "type", types, 0, &d->type));
    static const char *const point_fields[] = {"type", "position", "intensity", "attenuation", NULL};
    static const char *const dir_fields[] = {"type", "direction", "intensity", NULL};
    bool point = d->type == RC_LIGHT_POINT;
    RC_TRY(js_check_members(c, l, point ? point_fields : dir_fields));
    dvec3 zero = rcm_make_d(0, 0, 0);
    if (point) {
      RC_TRY(js_get_vec3(c, l, "position", true, zero, -HUGE_VAL, &d->position));
      RC_TRY(js_get_vec3(c, l, "attenuation", false, rcm_make_d(0, 0, 1), 0.0, &d->attenuation));
      if (rcm_max_abs_comp_d(d->attenuation) == 0.0) {
        js_push_key(c, "attenuation");
        return js_fail(c, "must not be all zero (the light would be infinitely bright)");
      }
    } else {
      RC_TRY(js_get_vec3(c, l, "direction", true, zero, -HUGE_VAL, &d->direction));
      if (rcm_max_abs_comp_d(d->direction) == 0.0) {
        js_push_key(c, "direction");
        return js_fail(c, "must not be the zero vector");
      }
    }
    RC_TRY(js_get_vec3(c, l, "intensity", true, zero, 0.0, &d->intensity));
    RC_TRY(js_note_origin(c, s, before, off, "lights", (uint32_t)i));
    js_pop(c);
  }
  js_pop(c);
  return RC_OK;
}

/* A one-sided triangle's front is the side its file or its vertex order faces, counter-
 * clockwise (docs/scene-format.md): a transform that mirrors (negative determinant)
 * turns that winding clockwise, so the winding is turned back. */
static bool mirrors(const rc_affine *m) {
  double a[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) a[i][j] = m->m[i][j];
  return rcm_mat3_det_d(a) < 0;
}
static void keep_front(rc_triangle_def *t) {
  dvec3 v = t->v[1], n = t->n[1];
  double uv[2] = {t->uv[1][0], t->uv[1][1]};
  t->v[1] = t->v[2], t->n[1] = t->n[2];
  t->v[2] = v, t->n[2] = n;
  memcpy(t->uv[1], t->uv[2], sizeof uv);
  memcpy(t->uv[2], uv, sizeof uv);
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
    c->base_off = off, c->base_depth = c->depth, c->base_index = i;
    size_t before[RC_ORIGIN_KINDS];
    rc_scene_counts(s, before);
    RC_TRY(js_expect_object(c, o));
    static const char *const types[] = {"sphere",     "triangle",    "mesh", "quadric", "ellipsoid", "cylinder", "cone",
                                        "paraboloid", "hyperboloid", "box",  "csg",     "plane", "bezier_patch",
                                        "bezier_patches", NULL};
    const cJSON *tv = cJSON_GetObjectItemCaseSensitive(o, "type");
    if (!tv) return js_fail(c, "missing field \"type\"");
    if (cJSON_IsString(tv) && (js_is_quadric_type(tv->valuestring) || js_is_patch_type(tv->valuestring))) {
      RC_TRY(js_is_patch_type(tv->valuestring) ? js_parse_patch_object(c, o, s) : js_parse_quadric_object(c, o, s));
      RC_TRY(js_note_origin(c, s, before, off, "objects", (uint32_t)i));
      js_pop(c);
      continue;
    }
    uint32_t type;
    RC_TRY(js_get_enum(c, o, "type", types, 0, &type));
    dvec3 zero = rcm_make_d(0, 0, 0);
    rc_affine m;
    bool transformed;
    if (type == 0) {
      static const char *const allowed[] = {"type", "center", "radius", "material", "transform", NULL};
      RC_TRY(js_check_members(c, o, allowed));
      rc_sphere_def *d = &s->spheres[s->sphere_count++];
      RC_TRY(js_get_vec3(c, o, "center", true, zero, -HUGE_VAL, &d->center));
      RC_TRY(js_get_positive(c, o, "radius", true, 0, &d->radius));
      RC_TRY(js_get_material_ref(c, o, &d->material));
      RC_TRY(js_get_transform(c, o, &m, &transformed));
      d->transformed = transformed;
      d->world_from_object = m;
    } else if (type == 1) {
      static const char *const allowed[] = {"type", "vertices", "uvs", "material", "one_sided", "transform", NULL};
      RC_TRY(js_check_members(c, o, allowed));
      rc_triangle_def d = {0};
      RC_TRY(js_get_triangle_uvs(c, o, &d));
      const cJSON *vs = cJSON_GetObjectItemCaseSensitive(o, "vertices");
      if (!vs) return js_fail(c, "missing field \"vertices\"");
      js_push_key(c, "vertices");
      if (!cJSON_IsArray(vs) || cJSON_GetArraySize(vs) != 3)
        return js_fail(c, "expected an array of 3 points");
      for (int k = 0; k < 3; k++) {
        js_push_index(c, (size_t)k);
        RC_TRY(js_vec3_value(c, cJSON_GetArrayItem(vs, k), -HUGE_VAL, &d.v[k]));
        js_pop(c);
      }
      js_pop(c);
      RC_TRY(js_get_material_ref(c, o, &d.material));
      RC_TRY(js_get_bool(c, o, "one_sided", false, &d.one_sided));
      RC_TRY(js_get_transform(c, o, &m, &transformed));
      for (int k = 0; k < 3; k++) d.v[k] = rc_affine_point(&m, d.v[k]);
      if (d.one_sided && mirrors(&m)) keep_front(&d);
      RC_TRY(rc_scene_add_triangle(s, &d));
    } else {
      static const char *const allowed[] = {"type", "file", "material", "one_sided", "transform", NULL};
      RC_TRY(js_check_members(c, o, allowed));
      bool one_sided;
      RC_TRY(js_get_bool(c, o, "one_sided", false, &one_sided));
      RC_TRY(js_get_transform(c, o, &m, &transformed));
      size_t first = s->triangle_count;
      RC_TRY(js_load_mesh(c, o, s, &m, -1));
      const bool flip = one_sided && mirrors(&m);
      for (size_t t = first; one_sided && t < s->triangle_count; t++) {
        s->triangles[t].one_sided = true;
        if (flip) keep_front(&s->triangles[t]);
      }
    }
    RC_TRY(js_note_origin(c, s, before, off, "objects", (uint32_t)i));
    js_pop(c);
  }
  js_pop(c);
  return RC_OK;
}

static rc_status parse_root(jctx *c, const cJSON *root, rc_scene *s) {
  RC_TRY(js_expect_object(c, root));
  static const char *const allowed[] = {"version", "image", "camera", "background", "ambient_light",
                                        "specular_model", "seed", "quality", "materials", "lights",
                                        "objects", NULL};
  RC_TRY(js_check_members(c, root, allowed));
  uint32_t version;
  RC_TRY(js_get_uint(c, root, "version", false, 1, 1, 1, &version));
  RC_TRY(parse_image(c, root, s));
  RC_TRY(parse_camera(c, root, s));
  RC_TRY(js_get_vec3(c, root, "background", false, rcm_make_d(0, 0, 0), 0.0, &s->background));
  RC_TRY(js_get_vec3(c, root, "ambient_light", false, rcm_make_d(1, 1, 1), 0.0, &s->ambient_light));
  static const char *const models[] = {"blinn-phong", "phong", NULL};
  RC_TRY(js_get_enum(c, root, "specular_model", models, RC_SPECULAR_BLINN_PHONG, &s->specular_model));
  RC_TRY(js_get_uint(c, root, "seed", false, 0, 0, UINT32_MAX, &s->seed));
  s->reflection_depth = 5;
  s->quality = rc_quality_default();
  const cJSON *q = cJSON_GetObjectItemCaseSensitive(root, "quality");
  if (q) {
    js_push_key(c, "quality");
    RC_TRY(js_expect_object(c, q));
    static const char *const qfields[] = {"reflection_depth", "precision", "sphere_intersection",
                                          "triangle_intersection", "shadow_offset", "shadow_epsilon",
                                          "camera_relative", "rescale", "shadows", NULL};
    RC_TRY(js_check_members(c, q, qfields));
    rc_quality *k = &s->quality;
    RC_TRY(js_get_uint(c, q, "reflection_depth", false, 5, 0, RC_MAX_REFLECTION_DEPTH, &s->reflection_depth));
    RC_TRY(js_get_enum(c, q, "precision", rc_precision_names, k->precision, &k->precision));
    RC_TRY(js_get_enum(c, q, "sphere_intersection", rc_sphere_formula_names, k->sphere, &k->sphere));
    RC_TRY(js_get_enum(c, q, "triangle_intersection", rc_triangle_formula_names, k->triangle, &k->triangle));
    RC_TRY(js_get_enum(c, q, "shadow_offset", rc_offset_names, k->offset, &k->offset));
    RC_TRY(js_get_positive(c, q, "shadow_epsilon", false, k->offset_epsilon, &k->offset_epsilon));
    RC_TRY(js_get_bool(c, q, "camera_relative", k->camera_relative, &k->camera_relative));
    RC_TRY(js_get_bool(c, q, "rescale", k->rescale, &k->rescale));
    RC_TRY(js_get_bool(c, q, "shadows", k->shadows, &k->shadows));
    js_pop(c);
  }
  RC_TRY(parse_materials(c, root, s));
  RC_TRY(parse_lights(c, root, s));
  RC_TRY(parse_objects(c, root, s));
  return RC_OK;
}

/* A syntax error at `off` (where cJSON stopped), pointing at the offending token: for the
 * mistakes people make most, at their own place with what JSON wants instead. */
static void report_syntax_error(const char *path, const char *text, size_t len, size_t off) {
  int line, col;
  size_t before = off;
  while (before > 0 && strchr(" \t\r\n", text[before - 1])) before--;
  if (before > 0 && text[before - 1] == ',' && (text[off] == ']' || text[off] == '}')) {
    /* A trailing comma: cJSON stops at the bracket, maybe lines later; the comma is it. */
    rc_json_line_col(text, len, before - 1, &line, &col);
    fprintf(stderr, "%s:%d:%d: error: JSON syntax: a comma before '%c' (JSON allows none after the last %s)\n",
            path, line, col, text[off], text[off] == ']' ? "element" : "member");
    return;
  }
  /* cJSON stops one character into a bad token ('x', //, an unquoted key): back to its
   * start, so that the column is the token's. */
  size_t stop = off > 64 ? off - 64 : 0;
  while (off > stop && !strchr(" \t\r\n{}[],:\"", text[off - 1])) off--;
  rc_json_line_col(text, len, off, &line, &col);
  before = off;
  while (before > 0 && strchr(" \t\r\n", text[before - 1])) before--;
  const char *hint = "";
  if (text[off] == '\'') hint = " (JSON strings take double quotes)";
  else if (text[off] == '/' && off + 1 < len && (text[off + 1] == '/' || text[off + 1] == '*'))
    hint = " (JSON has no comments)";
  else if (strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_", text[off]) && before > 0 &&
           (text[before - 1] == '{' || text[before - 1] == ','))
    hint = " (a key needs double quotes)";
  /* The token and what follows it on its line, not the lines after. */
  size_t n = strcspn(text + off, "\r\n");
  char snippet[64];
  rc_json_quote(text + off, n ? n : 1, 12, snippet, sizeof snippet);
  fprintf(stderr, "%s:%d:%d: error: JSON syntax: unexpected %s%s\n", path, line, col, snippet, hint);
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
      report_syntax_error(path, text, len, off);
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
