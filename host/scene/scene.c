/* scene.c: the scene model (scene.h): adding to it, its bounds, its problems, freeing it.
 * Loading, from any format, is scene_load.c's. */
#include "scene/scene.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "math/rcm_mat3.h"

rc_status rc_scene_reserve_triangles(rc_scene *s, size_t extra) {
  if (s->triangle_count + extra <= s->triangle_capacity) return RC_OK;
  size_t cap = s->triangle_capacity ? s->triangle_capacity : 64;
  while (cap < s->triangle_count + extra) cap *= 2;
  rc_triangle_def *t = realloc(s->triangles, cap * sizeof *t);
  if (!t) {
    rc_error("out of memory: %zu triangles", cap);
    return RC_ERR_OUT_OF_MEMORY;
  }
  s->triangles = t;
  s->triangle_capacity = cap;
  return RC_OK;
}

rc_status rc_scene_add_triangle(rc_scene *s, const rc_triangle_def *t) {
  dvec3 n = rcm_cross_d(rcm_sub_d(t->v[1], t->v[0]), rcm_sub_d(t->v[2], t->v[0]));
  if (rcm_max_abs_comp_d(n) == 0.0) {
    s->degenerate_triangles++;
    return RC_OK;
  }
  rc_status st = rc_scene_reserve_triangles(s, 1);
  if (st == RC_OK) s->triangles[s->triangle_count++] = *t;
  return st;
}

dvec3 rc_affine_point(const rc_affine *a, dvec3 p) {
  const double(*m)[4] = a->m;
  return rcm_make_d(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                    m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                    m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]);
}

void rc_scene_free(rc_scene *scene) {
  for (size_t i = 0; i < scene->material_count; i++) free(scene->materials[i].name);
  free(scene->materials);
  for (size_t i = 0; i < scene->texture_count; i++) {
    free(scene->textures[i].path);
    free(scene->textures[i].rgb);
  }
  free(scene->textures);
  free(scene->lights);
  free(scene->spheres);
  free(scene->triangles);
  free(scene->quadrics);
  free(scene->patches);
  free(scene->planes);
  free(scene->csg_leaves);
  free(scene->csg_triangles);
  for (size_t i = 0; i < scene->csg_count; i++) free(scene->csgs[i].program);
  free(scene->csgs);
  free(scene->origins);
  for (size_t i = 0; i < scene->input_count; i++) free(scene->inputs[i]);
  free(scene->inputs);
  free(scene->path);
  memset(scene, 0, sizeof *scene);
}

bool rc_scene_note_input(rc_scene *s, const char *path) {
  /* A file placed many times is one input: the last few are where a repeat comes from. */
  for (size_t i = s->input_count, k = 0; i > 0 && k < 8; i--, k++)
    if (strcmp(s->inputs[i - 1], path) == 0) return true;
  if (s->input_count == s->input_capacity) {
    size_t cap = s->input_capacity ? 2 * s->input_capacity : 8;
    char **p = realloc(s->inputs, cap * sizeof *p);
    if (!p) return false;
    s->inputs = p, s->input_capacity = cap;
  }
  char *copy = strdup(path);
  if (!copy) return false;
  s->inputs[s->input_count++] = copy;
  return true;
}

/* |up x forward| <= 1e-6 |up| |forward| counts as parallel (tests/bad_input/cases.txt). */
#define RC_UP_PARALLEL_SINE 1e-6

const char *rc_scene_camera_problem(const rc_camera_def *c, const char **field) {
  dvec3 forward = rcm_sub_d(c->look_at, c->eye);
  if (rcm_max_abs_comp_d(forward) == 0.0) {
    *field = "look_at";
    return "equals eye: the view direction is undefined";
  }
  double up_len = rcm_length_d(c->up);
  if (up_len == 0.0) {
    *field = "up";
    return "must not be the zero vector";
  }
  if (rcm_length_d(rcm_cross_d(c->up, forward)) <= RC_UP_PARALLEL_SINE * up_len * rcm_length_d(forward)) {
    *field = "up";
    return "is parallel to the view direction (look_at - eye)";
  }
  if (c->projection == RC_PROJECTION_PERSPECTIVE && !(c->fov_y_deg > 0.0 && c->fov_y_deg < 180.0)) {
    *field = "fov_y_deg";
    return "must be in (0, 180) degrees";
  }
  if (c->projection == RC_PROJECTION_PARALLEL && !(c->view_height > 0.0)) {
    *field = "view_height";
    return "must be greater than 0";
  }
  return NULL;
}

const char *const rc_precision_names[] = {"auto", "f32", "f64", "certified", NULL};
const char *const rc_sphere_formula_names[] = {"geometric", "algebraic", NULL};
const char *const rc_triangle_formula_names[] = {"watertight", "moller-trumbore", "cramer", NULL};
const char *const rc_offset_names[] = {"error-bound", "ulp", "epsilon", "t-min", NULL};

rc_quality rc_quality_default(void) {
  return (rc_quality){.precision = RC_PRECISION_AUTO,
                      .sphere = RC_SPHERE_GEOMETRIC,
                      .triangle = RC_TRIANGLE_WATERTIGHT,
                      .offset = RC_OFFSET_ERROR_BOUND,
                      .offset_epsilon = RC_OFFSET_EPSILON_DEFAULT,
                      .camera_relative = true,
                      .rescale = true,
                      .shadows = true};
}

void rc_frame_box_bounds(dvec3 center, const dvec3 axis[3], dvec3 lo, dvec3 hi, dvec3 *out_lo, dvec3 *out_hi) {
  /* f = W (p - center) with W's rows the axes, so p = center + W^-1 f. W is a rotation for
   * an untransformed shape and any invertible matrix under a "transform". */
  const double w[3][3] = {{axis[0].x, axis[0].y, axis[0].z}, {axis[1].x, axis[1].y, axis[1].z},
                          {axis[2].x, axis[2].y, axis[2].z}};
  double m[3][3];
  if (!rcm_mat3_inverse_d(w, m)) { /* refused at load; f32 rounding cannot get here, but stay safe */
    *out_lo = rcm_make_d(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL);
    *out_hi = rcm_make_d(HUGE_VAL, HUGE_VAL, HUGE_VAL);
    return;
  }
  *out_lo = rcm_make_d(HUGE_VAL, HUGE_VAL, HUGE_VAL);
  *out_hi = rcm_make_d(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL);
  for (int k = 0; k < 8; k++) {
    double f[3] = {k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z};
    dvec3 p = rcm_make_d(center.x + m[0][0] * f[0] + m[0][1] * f[1] + m[0][2] * f[2],
                         center.y + m[1][0] * f[0] + m[1][1] * f[1] + m[1][2] * f[2],
                         center.z + m[2][0] * f[0] + m[2][1] * f[1] + m[2][2] * f[2]);
    out_lo->x = fmin(out_lo->x, p.x), out_lo->y = fmin(out_lo->y, p.y), out_lo->z = fmin(out_lo->z, p.z);
    out_hi->x = fmax(out_hi->x, p.x), out_hi->y = fmax(out_hi->y, p.y), out_hi->z = fmax(out_hi->z, p.z);
  }
}

void rc_quadric_world_box(const rc_quadric_def *q, dvec3 *lo, dvec3 *hi) {
  rc_frame_box_bounds(q->center, q->axis, q->lo, q->hi, lo, hi);
}

int rc_name_index(const char *const *names, const char *name) {
  for (int i = 0; names[i]; i++)
    if (strcmp(names[i], name) == 0) return i;
  return -1;
}

void rc_scene_counts(const rc_scene *s, size_t counts[RC_ORIGIN_KINDS]) {
  counts[RC_ORIGIN_SPHERE] = s->sphere_count;
  counts[RC_ORIGIN_TRIANGLE] = s->triangle_count;
  counts[RC_ORIGIN_QUADRIC] = s->quadric_count;
  counts[RC_ORIGIN_CSG] = s->csg_count;
  counts[RC_ORIGIN_LIGHT] = s->light_count;
  counts[RC_ORIGIN_MATERIAL] = s->material_count;
  counts[RC_ORIGIN_PLANE] = s->plane_count;
}

rc_status rc_scene_note_origin(rc_scene *s, const size_t before[RC_ORIGIN_KINDS], int line, int col,
                               const char *what, uint32_t item) {
  size_t now[RC_ORIGIN_KINDS];
  rc_scene_counts(s, now);
  for (uint32_t k = 0; k < RC_ORIGIN_KINDS; k++) {
    if (now[k] == before[k]) continue;
    RC_GROW(s->origins, s->origin_count, s->origin_capacity, 64);
    s->origins[s->origin_count++] =
        (rc_origin){k, (uint32_t)line, (uint32_t)col, item, what, before[k], now[k] - before[k]};
  }
  return RC_OK;
}

static void report(const rc_scene *s, const char *level, uint32_t kind, size_t index, const char *fmt, va_list ap) {
  char message[512];
  vsnprintf(message, sizeof message, fmt, ap);
  static const char *const kinds[] = {"sphere", "triangle", "quadric", "composite", "light", "material", "plane"};
  /* A scan: this runs once, for an error message. */
  const rc_origin *found = NULL;
  for (size_t i = 0; i < s->origin_count && !found; i++) {
    const rc_origin *o = &s->origins[i];
    if (o->kind == kind && index >= o->first && index - o->first < o->count) found = o;
  }
  const char *name = kind < RC_ORIGIN_KINDS ? kinds[kind] : "object";
  if (!found) {
    fprintf(stderr, "%s: %s: %s %zu: %s\n", s->path, level, name, index, message);
    return;
  }
  char field[200];
  if (found->item != UINT32_MAX)
    snprintf(field, sizeof field, "%s[%u]", found->what, found->item);
  else if (kind == RC_ORIGIN_MATERIAL && !strcmp(found->what, "materials"))
    snprintf(field, sizeof field, "materials.%.160s", s->materials[index].name);
  else
    snprintf(field, sizeof field, "%s", found->what);
  if (found->count > 1)
    snprintf(field + strlen(field), sizeof field - strlen(field), " (%s %zu of %zu)", name, index - found->first,
             found->count);
  fprintf(stderr, "%s:%u:%u: %s: %s: %s\n", s->path, found->line, found->col, level, field, message);
}

void rc_scene_error(const rc_scene *s, uint32_t kind, size_t index, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  report(s, "error", kind, index, fmt, ap);
  va_end(ap);
}

void rc_scene_warning(const rc_scene *s, uint32_t kind, size_t index, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  report(s, "warning", kind, index, fmt, ap);
  va_end(ap);
}
