/* scene_json_read.h: the JSON scene reader's context and its field readers, used by every
 * part of the JSON format (scene_json.c, scene_quadric.c, scene_json_mesh.c). Every reader
 * prints FILE:LINE:COL: error: FIELD.PATH: what (value) and returns RC_ERR_INPUT on bad
 * input. */
#ifndef RC_SCENE_JSON_READ_H
#define RC_SCENE_JSON_READ_H

#include <cjson/cJSON.h>

#include "scene/json_locate.h"
#include "scene/name_table.h"
#include "scene/scene.h"

#define RC_JSON_MAX_DEPTH 24

typedef struct {
  const char *file;
  const char *text;
  size_t len;
  rc_json_step path[RC_JSON_MAX_DEPTH];
  size_t depth;
  rc_name_table materials; /* material name -> index into rc_scene.materials */
  const cJSON *material_defs; /* the "materials" object: names for did-you-mean */
  bool allow_outside_paths; /* rc_load_options */
  size_t lc_off;            /* js_line_col's counter: where it stopped */
  int lc_line, lc_col;
  /* The object being parsed (objects[base_index], at base_off, the path base_depth deep):
   * places inside it are found from it (js_offset_near), not from the file's start. */
  size_t base_off, base_depth, base_index;
} jctx;

void js_push_key(jctx *c, const char *key);
/* The key on top of the path is a repeat: errors point at its second occurrence. */
void js_mark_repeat(jctx *c);
void js_push_index(jctx *c, size_t index);
void js_pop(jctx *c);
void js_format_path(const jctx *c, char *out, size_t cap);
rc_status js_fail(jctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
const char *js_type_name(const cJSON *v);
/* Rejects members not in `allowed` (NULL-terminated) and repeated members. */
rc_status js_check_members(jctx *c, const cJSON *obj, const char *const *allowed);
rc_status js_expect_object(jctx *c, const cJSON *v);
rc_status js_number_value(jctx *c, const cJSON *v, double *out);
/* Member `key`: a finite number in [lo, hi]; `def` when absent unless required. */
rc_status js_get_number(jctx *c, const cJSON *obj, const char *key, bool required, double def, double lo, double hi,
                        double *out);
/* Like js_get_number, with an exclusive lower bound of 0. */
rc_status js_get_positive(jctx *c, const cJSON *obj, const char *key, bool required, double def, double *out);
rc_status js_get_uint(jctx *c, const cJSON *obj, const char *key, bool required, uint32_t def, uint32_t lo,
                      uint32_t hi, uint32_t *out);
rc_status js_vec3_value(jctx *c, const cJSON *v, double lo, dvec3 *out);
/* Member `key`: [x, y, z]; lo = 0 for colours and coefficients, -HUGE_VAL for positions. */
rc_status js_get_vec3(jctx *c, const cJSON *obj, const char *key, bool required, dvec3 def, double lo, dvec3 *out);
rc_status js_get_enum(jctx *c, const cJSON *obj, const char *key, const char *const *names, uint32_t def,
                      uint32_t *out);
/* Member `key`: true or false; `def` when absent. */
rc_status js_get_bool(jctx *c, const cJSON *obj, const char *key, bool def, bool *out);
rc_status js_get_material_ref(jctx *c, const cJSON *obj, uint32_t *out);
/* Member "transform" ({"matrix", "translate", "rotate_deg", "scale"}: docs/scene-format.md)
 * as world_from_object, the identity when absent; a singular one is refused. */
rc_status js_get_transform(jctx *c, const cJSON *obj, rc_affine *out, bool *present);
void js_affine_identity(rc_affine *a);
/* a = a * b (b applied first to points). */
void js_affine_multiply(rc_affine *a, const rc_affine *b);
/* Offset in the text of the value at the current path (rc_json_locate). */
size_t js_offset(const jctx *c);
/* js_offset, found from the current object where the path lies inside it. */
size_t js_offset_near(const jctx *c);
/* A file a scene names (the string value `v`, at the top of the path): `path`, relative to
 * the scene file's folder (`folder`) unless absolute, and inside that folder unless
 * --allow-outside-paths. Mesh files and textures are found so. */
rc_status js_scene_file(jctx *c, const cJSON *v, const char *what, char path[4096], char folder[4096]);
/* Line and column of an offset, counted on from the last offset asked for when it is
 * not before it: walking a file's places in order costs the file once. */
void js_line_col(jctx *c, size_t off, int *line, int *col);
/* Records that what was added to the scene since `before` comes from the value at `off`
 * (an element of array `what`, or with item UINT32_MAX a member of object `what`). Lines
 * are counted on from the previous call, so values noted in file order cost the file once. */
rc_status js_note_origin(jctx *c, rc_scene *s, const size_t before[RC_ORIGIN_KINDS], size_t off, const char *what,
                         uint32_t item);

#endif
