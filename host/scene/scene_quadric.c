/* scene_quadric.c: the quadric object types and composites (CSG) of the scene format
 * (docs/scene-format.md). Each shape is built in f64 in its own frame (rc_quadric_def):
 * the named shapes in their principal frame, centred, so that the shader's products stay
 * small (docs/numerics.md §3); a general matrix recentred on its bounds. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "math/rcm_mat3.h"
#include "scene/scene_json_mesh.h"
#include "scene/scene_quadric.h"

/* The clip box of a closed shape reaches this fraction beyond its surface, so that a box
 * face never grazes the surface it bounds (the box would cut a flat spot into it). */
#define BOX_MARGIN (1.0 / 1024.0)

static const char *const quadric_types[] = {"quadric", "ellipsoid", "cylinder", "cone",
                                             "paraboloid", "hyperboloid", "box", "csg", NULL};
enum { T_QUADRIC, T_ELLIPSOID, T_CYLINDER, T_CONE, T_PARABOLOID, T_HYPERBOLOID, T_BOX, T_CSG, T_SPHERE, T_MESH };

bool js_is_quadric_type(const char *type) { return rc_name_index(quadric_types, type) >= 0 || !strcmp(type, "plane"); }

static void identity_frame(dvec3 axis[3]) {
  axis[0] = rcm_make_d(1, 0, 0), axis[1] = rcm_make_d(0, 1, 0), axis[2] = rcm_make_d(0, 0, 1);
}

/* Right-handed axes with `z` (unit) as the third. */
static void frame_from_axis(dvec3 z, dvec3 axis[3]) {
  dvec3 a = fabs(z.x) < 0.9 ? rcm_make_d(1, 0, 0) : rcm_make_d(0, 1, 0);
  dvec3 x = rcm_normalize_d(rcm_sub_d(a, rcm_scale_d(z, rcm_dot_d(a, z))));
  axis[0] = x;
  axis[1] = rcm_cross_d(z, x);
  axis[2] = z;
}

/* Q and k Q (k > 0) have the same surface and inside: scaling the largest second-order
 * coefficient to 1 keeps the coefficients in the f32 range whatever the scene's units. */
static void normalize_coefficients(rc_quadric_def *q) {
  double m = fmax(fmax(fabs(q->diag.x), fabs(q->diag.y)), fmax(fabs(q->diag.z), rcm_max_abs_comp_d(q->off)));
  if (m == 0) m = rcm_max_abs_comp_d(q->linear);
  if (m == 0) m = fabs(q->constant);
  if (m == 0) return;
  q->diag = rcm_scale_d(q->diag, 1 / m);
  q->off = rcm_scale_d(q->off, 1 / m);
  q->linear = rcm_scale_d(q->linear, 1 / m);
  q->constant /= m;
}

static rc_status get_axis(jctx *c, const cJSON *o, dvec3 *out) {
  dvec3 a;
  RC_TRY(js_get_vec3(c, o, "axis", false, rcm_make_d(0, 1, 0), -HUGE_VAL, &a));
  if (rcm_max_abs_comp_d(a) == 0) {
    js_push_key(c, "axis");
    return js_fail(c, "must not be the zero vector");
  }
  *out = rcm_normalize_d(a);
  return RC_OK;
}

/* {"type": "quadric", "matrix": 4x4 symmetric, "bounds": {"min", "max"}, "solid"}. */
static rc_status parse_general(jctx *c, const cJSON *o, rc_quadric_def *q, bool *solid) {
  static const char *const allowed[] = {"type", "matrix", "bounds", "material", "solid", "transform", NULL};
  RC_TRY(js_check_members(c, o, allowed));
  const cJSON *m = cJSON_GetObjectItemCaseSensitive(o, "matrix");
  if (!m) return js_fail(c, "missing field \"matrix\"");
  js_push_key(c, "matrix");
  if (!cJSON_IsArray(m) || cJSON_GetArraySize(m) != 4) return js_fail(c, "expected 4 rows of 4 numbers");
  double Q[4][4];
  for (int i = 0; i < 4; i++) {
    const cJSON *row = cJSON_GetArrayItem(m, i);
    js_push_index(c, (size_t)i);
    if (!cJSON_IsArray(row) || cJSON_GetArraySize(row) != 4) return js_fail(c, "expected a row of 4 numbers");
    for (int j = 0; j < 4; j++) {
      js_push_index(c, (size_t)j);
      RC_TRY(js_number_value(c, cJSON_GetArrayItem(row, j), &Q[i][j]));
      js_pop(c);
    }
    js_pop(c);
  }
  double big = 0;
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) big = fmax(big, fabs(Q[i][j]));
  if (big == 0) return js_fail(c, "is all zeros: no surface");
  for (int i = 0; i < 4; i++)
    for (int j = i + 1; j < 4; j++)
      if (fabs(Q[i][j] - Q[j][i]) > 1e-12 * big) {
        js_push_index(c, (size_t)i);
        js_push_index(c, (size_t)j);
        return js_fail(c, "the matrix must be symmetric: [%d][%d] = %g, [%d][%d] = %g", i, j, Q[i][j], j, i, Q[j][i]);
      }
  js_pop(c);
  const cJSON *b = cJSON_GetObjectItemCaseSensitive(o, "bounds");
  if (!b) return js_fail(c, "missing field \"bounds\" (a quadric is clipped to a box)");
  js_push_key(c, "bounds");
  RC_TRY(js_expect_object(c, b));
  static const char *const bfields[] = {"min", "max", NULL};
  RC_TRY(js_check_members(c, b, bfields));
  dvec3 zero = rcm_make_d(0, 0, 0), lo, hi;
  RC_TRY(js_get_vec3(c, b, "min", true, zero, -HUGE_VAL, &lo));
  RC_TRY(js_get_vec3(c, b, "max", true, zero, -HUGE_VAL, &hi));
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) {
    js_push_key(c, "max");
    return js_fail(c, "must exceed min in every coordinate");
  }
  js_pop(c);
  RC_TRY(js_get_bool(c, o, "solid", false, solid));
  /* Recentred on the bounds: f = p - c, Q = f^T M f + 2 (M c + l).f + (c^T M c + 2 l.c + J). */
  dvec3 ctr = rcm_scale_d(rcm_add_d(lo, hi), 0.5);
  double cv[3] = {ctr.x, ctr.y, ctr.z}, lin[3], mc[3];
  for (int i = 0; i < 3; i++) mc[i] = Q[i][0] * cv[0] + Q[i][1] * cv[1] + Q[i][2] * cv[2];
  for (int i = 0; i < 3; i++) lin[i] = mc[i] + Q[i][3];
  q->center = ctr;
  identity_frame(q->axis);
  q->diag = rcm_make_d(Q[0][0], Q[1][1], Q[2][2]);
  q->off = rcm_make_d(Q[0][1], Q[0][2], Q[1][2]);
  q->linear = rcm_make_d(lin[0], lin[1], lin[2]);
  q->constant = cv[0] * mc[0] + cv[1] * mc[1] + cv[2] * mc[2] + 2 * (Q[0][3] * cv[0] + Q[1][3] * cv[1] + Q[2][3] * cv[2]) +
                Q[3][3];
  q->lo = rcm_sub_d(lo, ctr);
  q->hi = rcm_sub_d(hi, ctr);
  return RC_OK;
}

/* The named shapes; *closable: whether "capped" applies; *intervals: the most [in, out]
 * intervals a ray can have in the solid (2 where Q is indefinite: a cone's two nappes, a
 * hyperboloid's waist). */
static rc_status parse_ellipsoid(jctx *c, const cJSON *o, rc_quadric_def *q) {
  dvec3 zero = rcm_make_d(0, 0, 0);
  static const char *const allowed[] = {"type", "center", "radii", "material", "transform", NULL};
  RC_TRY(js_check_members(c, o, allowed));
  dvec3 r;
  RC_TRY(js_get_vec3(c, o, "center", true, zero, -HUGE_VAL, &q->center));
  RC_TRY(js_get_vec3(c, o, "radii", true, zero, -HUGE_VAL, &r));
  if (!(r.x > 0 && r.y > 0 && r.z > 0)) {
    js_push_key(c, "radii");
    return js_fail(c, "must all be greater than 0");
  }
  identity_frame(q->axis);
  q->diag = rcm_make_d(1 / (r.x * r.x), 1 / (r.y * r.y), 1 / (r.z * r.z));
  q->constant = -1;
  q->hi = rcm_scale_d(r, 1 + BOX_MARGIN);
  q->lo = rcm_scale_d(q->hi, -1);
  return RC_OK;
}

/* Only as a composite's operand (a standalone sphere has its own type): the solid
 * ellipsoid with three equal radii. */
static rc_status parse_sphere_operand(jctx *c, const cJSON *o, rc_quadric_def *q) {
  dvec3 zero = rcm_make_d(0, 0, 0);
  /* Only as a composite's operand (a standalone sphere has its own type): the solid
   * ellipsoid with three equal radii. */
  static const char *const allowed[] = {"type", "center", "radius", "material", "transform", NULL};
  RC_TRY(js_check_members(c, o, allowed));
  double r;
  RC_TRY(js_get_vec3(c, o, "center", true, zero, -HUGE_VAL, &q->center));
  RC_TRY(js_get_positive(c, o, "radius", true, 0, &r));
  identity_frame(q->axis);
  q->diag = rcm_make_d(1, 1, 1);
  q->constant = -r * r;
  q->hi = rcm_make_d(r * (1 + BOX_MARGIN), r * (1 + BOX_MARGIN), r * (1 + BOX_MARGIN));
  q->lo = rcm_scale_d(q->hi, -1);
  return RC_OK;
}

static rc_status parse_box(jctx *c, const cJSON *o, rc_quadric_def *q) {
  dvec3 zero = rcm_make_d(0, 0, 0);
  static const char *const allowed[] = {"type", "min", "max", "material", "transform", NULL};
  RC_TRY(js_check_members(c, o, allowed));
  dvec3 lo, hi;
  RC_TRY(js_get_vec3(c, o, "min", true, zero, -HUGE_VAL, &lo));
  RC_TRY(js_get_vec3(c, o, "max", true, zero, -HUGE_VAL, &hi));
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) {
    js_push_key(c, "max");
    return js_fail(c, "must exceed min in every coordinate");
  }
  q->center = rcm_scale_d(rcm_add_d(lo, hi), 0.5);
  identity_frame(q->axis);
  q->diag = zero;
  q->constant = -1; /* inside everywhere: the solid is the box */
  q->lo = rcm_sub_d(lo, q->center);
  q->hi = rcm_sub_d(hi, q->center);
  return RC_OK;
}

/* The axial shapes, in their frame (z along the axis, the origin at the centre, apex or
 * vertex), after their common members: the height h along the axis. */
static rc_status axial_cylinder(jctx *c, const cJSON *o, double h, rc_quadric_def *q) {
  double r;
  RC_TRY(js_get_positive(c, o, "radius", true, 0, &r));
  q->diag = rcm_make_d(1 / (r * r), 1 / (r * r), 0); /* (x^2 + y^2) / r^2 - 1 */
  q->constant = -1;
  q->hi = rcm_make_d(r * (1 + BOX_MARGIN), r * (1 + BOX_MARGIN), h / 2);
  q->lo = rcm_scale_d(q->hi, -1);
  return RC_OK;
}

static rc_status axial_cone(jctx *c, const cJSON *o, double h, rc_quadric_def *q) {
  double deg;
  RC_TRY(js_get_number(c, o, "angle_deg", true, 0, 0, 90, &deg));
  if (!(deg > 0 && deg < 90)) {
    js_push_key(c, "angle_deg");
    return js_fail(c, "must be in (0, 90) degrees");
  }
  double k = tan(deg * M_PI / 180);
  q->diag = rcm_make_d(1, 1, -k * k); /* x^2 + y^2 - (z tan)^2, the apex at 0, z along the axis */
  q->constant = 0;
  q->hi = rcm_make_d(h * k * (1 + BOX_MARGIN), h * k * (1 + BOX_MARGIN), h);
  q->lo = rcm_make_d(-q->hi.x, -q->hi.y, 0);
  return RC_OK;
}

static rc_status axial_paraboloid(jctx *c, const cJSON *o, double h, rc_quadric_def *q) {
  double r;
  RC_TRY(js_get_positive(c, o, "radius", true, 0, &r));
  q->diag = rcm_make_d(1, 1, 0); /* x^2 + y^2 - (r^2 / h) z: radius r at height h */
  q->linear = rcm_make_d(0, 0, -r * r / (2 * h));
  q->constant = 0;
  q->hi = rcm_make_d(r * (1 + BOX_MARGIN), r * (1 + BOX_MARGIN), h);
  q->lo = rcm_make_d(-q->hi.x, -q->hi.y, 0);
  return RC_OK;
}

static rc_status axial_hyperboloid_two_sheets(jctx *c, const cJSON *o, double h, rc_quadric_def *q) {
  double g, e;
  RC_TRY(js_get_positive(c, o, "gap", true, 0, &g));
  RC_TRY(js_get_positive(c, o, "end_radius", true, 0, &e));
  if (!(h > g)) {
    js_push_key(c, "height");
    return js_fail(c, "must exceed gap (the distance between the two sheets' vertices)");
  }
  /* Two sheets: (x^2 + y^2) / a^2 - z^2 / s^2 + 1, vertices at z = +-s (s = gap / 2), radius
   * e at z = +-h/2; Q < 0 inside the two cups. */
  double s2 = (g / 2) * (g / 2), a2 = e * e / ((h / 2) * (h / 2) / s2 - 1);
  q->diag = rcm_make_d(1 / a2, 1 / a2, -1 / s2);
  q->constant = 1;
  q->hi = rcm_make_d(e * (1 + BOX_MARGIN), e * (1 + BOX_MARGIN), h / 2);
  q->lo = rcm_scale_d(q->hi, -1);
  return RC_OK;
}

static rc_status axial_hyperboloid_one_sheet(jctx *c, const cJSON *o, double h, rc_quadric_def *q) {
  double a, e;
  RC_TRY(js_get_positive(c, o, "radius", true, 0, &a));
  RC_TRY(js_get_positive(c, o, "end_radius", true, 0, &e));
  if (!(e > a)) {
    js_push_key(c, "end_radius");
    return js_fail(c, "must exceed radius (the waist) for a hyperboloid of one sheet");
  }
  /* (x^2 + y^2) / a^2 - z^2 / s^2 - 1, with radius e at z = +-h/2. */
  double s2 = (h / 2) * (h / 2) / ((e / a) * (e / a) - 1);
  q->diag = rcm_make_d(1 / (a * a), 1 / (a * a), -1 / s2);
  q->constant = -1;
  q->hi = rcm_make_d(e * (1 + BOX_MARGIN), e * (1 + BOX_MARGIN), h / 2);
  q->lo = rcm_scale_d(q->hi, -1);
  return RC_OK;
}

/* The axial shapes' common members (origin, axis, height, capped), then the shape's own. */
static rc_status parse_axial(jctx *c, const cJSON *o, uint32_t type, rc_quadric_def *q, bool *solid,
                             uint32_t *intervals) {
  static const char *const cyl[] = {"type", "center", "axis", "radius", "height", "capped", "material", "transform", NULL};
  static const char *const cone[] = {"type", "apex", "axis", "angle_deg", "height", "capped", "material", "transform",
                                     NULL};
  static const char *const para[] = {"type", "vertex", "axis", "radius", "height", "capped", "material", "transform",
                                     NULL};
  static const char *const hyp[] = {"type", "center", "axis", "radius", "end_radius", "height", "capped", "material",
                                    "transform", "sheets", NULL};
  static const char *const hyp2[] = {"type", "center", "axis", "gap", "end_radius", "height", "capped", "material",
                                     "transform", "sheets", NULL};
  dvec3 zero = rcm_make_d(0, 0, 0);
  uint32_t sheets = 1;
  if (type == T_HYPERBOLOID) RC_TRY(js_get_uint(c, o, "sheets", false, 1, 1, 2, &sheets));
  const char *const *allowed = type == T_CYLINDER ? cyl : type == T_CONE ? cone : type == T_PARABOLOID ? para : sheets == 1 ? hyp : hyp2;
  RC_TRY(js_check_members(c, o, allowed));
  const char *origin = type == T_CONE ? "apex" : type == T_PARABOLOID ? "vertex" : "center";
  dvec3 z = rcm_make_d(0, 0, 1);
  double h;
  RC_TRY(js_get_vec3(c, o, origin, true, zero, -HUGE_VAL, &q->center));
  RC_TRY(get_axis(c, o, &z));
  RC_TRY(js_get_positive(c, o, "height", true, 0, &h));
  RC_TRY(js_get_bool(c, o, "capped", true, solid));
  frame_from_axis(z, q->axis);
  /* A cone's and a hyperboloid's surface meets a line twice inside the box. */
  *intervals = type == T_CYLINDER || type == T_PARABOLOID ? 1 : 2;
  if (type == T_CYLINDER) return axial_cylinder(c, o, h, q);
  if (type == T_CONE) return axial_cone(c, o, h, q);
  if (type == T_PARABOLOID) return axial_paraboloid(c, o, h, q);
  if (sheets == 2) return axial_hyperboloid_two_sheets(c, o, h, q);
  return axial_hyperboloid_one_sheet(c, o, h, q);
}

static rc_status parse_named(jctx *c, const cJSON *o, uint32_t type, rc_quadric_def *q, bool *solid,
                             uint32_t *intervals) {
  dvec3 zero = rcm_make_d(0, 0, 0);
  *intervals = 1;
  *solid = true;
  q->off = zero;
  q->linear = zero;
  q->uv = type == T_ELLIPSOID || type == T_SPHERE ? RC_QUADRIC_UV_ELLIPSOID
          : type == T_BOX                        ? RC_QUADRIC_UV_BOX
                                                 : RC_QUADRIC_UV_AXIAL;
  if (type == T_ELLIPSOID) return parse_ellipsoid(c, o, q);
  if (type == T_SPHERE) return parse_sphere_operand(c, o, q);
  if (type == T_BOX) return parse_box(c, o, q);
  return parse_axial(c, o, type, q, solid, intervals);
}

/* The object's own "transform" after the enclosing composites' (outer, applied last):
 * *t = outer * own. */
static rc_status get_composed_transform(jctx *c, const cJSON *o, const rc_affine *outer, rc_affine *t) {
  bool present;
  RC_TRY(js_get_transform(c, o, t, &present));
  rc_affine own = *t;
  *t = *outer;
  js_affine_multiply(t, &own);
  return RC_OK;
}

/* Carries a shape built in its frame (centre c, world-to-frame rows W) through
 * world_from_object t = (A, b): the centre to A c + b and the rows to W A^-1, so that the
 * frame coordinates of a moved point are those of the point before: W A^-1 (A p + b - A c
 * - b) = W (p - c). Its box, coefficients and t along a ray are unchanged; W stops being a
 * rotation under a scale or shear (docs/scene-format.md, "Transforms"). */
static rc_status transform_quadric(jctx *c, const rc_affine *t, rc_quadric_def *q) {
  double a[3][3], inv[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) a[i][j] = t->m[i][j];
  if (!rcm_mat3_inverse_d(a, inv)) return js_fail(c, "the transforms of this object and its composites compose to a singular one");
  q->center = rc_affine_point(t, q->center);
  for (int k = 0; k < 3; k++) {
    dvec3 w = q->axis[k];
    q->axis[k] = rcm_make_d(w.x * inv[0][0] + w.y * inv[1][0] + w.z * inv[2][0], w.x * inv[0][1] + w.y * inv[1][1] + w.z * inv[2][1],
                            w.x * inv[0][2] + w.y * inv[1][2] + w.z * inv[2][2]);
  }
  return RC_OK;
}

/* One quadric object (any type but csg) into *q, moved by outer (the enclosing composites'
 * transforms) after its own; *intervals as for parse_named. */
static rc_status parse_quadric(jctx *c, const cJSON *o, uint32_t type, int inherited, const rc_affine *outer,
                               rc_quadric_def *q, uint32_t *intervals) {
  memset(q, 0, sizeof *q);
  bool solid = true;
  *intervals = 2;
  if (type == T_QUADRIC)
    RC_TRY(parse_general(c, o, q, &solid));
  else
    RC_TRY(parse_named(c, o, type, q, &solid, intervals));
  rc_affine t;
  RC_TRY(get_composed_transform(c, o, outer, &t));
  RC_TRY(transform_quadric(c, &t, q));
  q->solid = solid;
  normalize_coefficients(q);
  if (cJSON_GetObjectItemCaseSensitive(o, "material") || inherited < 0) {
    RC_TRY(js_get_material_ref(c, o, &q->material));
  } else {
    q->material = (uint32_t)inherited;
  }
  return RC_OK;
}

#define GROW(array, count, cap) RC_GROW(array, count, cap, 8)

typedef struct {
  uint32_t *code;
  size_t length, capacity;
} program;

/* What a subtree needs: stack lists while it runs, intervals in its result, and shader
 * loop steps (rc_quadric.glsl: one per instruction, per clipped piece of a leaf, per
 * interval end merged and copied back). */
typedef struct {
  uint32_t stack, intervals, steps;
  dvec3 lo, hi;
} csg_need;

/* A leaf (need->intervals set): into the scene's leaves and the program. A mesh leaf's
 * traversal steps are counted once its tree is built (bvh.c, rc_bvh_build). */
static rc_status add_leaf(rc_scene *s, const rc_quadric_def *q, program *p, csg_need *need) {
  need->stack = 1;
  need->steps = 1 + need->intervals;
  rc_quadric_world_box(q, &need->lo, &need->hi);
  GROW(s->csg_leaves, s->csg_leaf_count, s->csg_leaf_capacity);
  s->csg_leaves[s->csg_leaf_count] = *q;
  GROW(p->code, p->length, p->capacity);
  p->code[p->length++] = (RC_CSG_LEAF << RC_CSG_OP_SHIFT) | (uint32_t)s->csg_leaf_count++;
  return RC_OK;
}

static rc_status parse_csg_node(jctx *c, const cJSON *o, rc_scene *s, int inherited, const rc_affine *outer,
                                program *p, csg_need *need) {
  RC_TRY(js_expect_object(c, o));
  const cJSON *t = cJSON_GetObjectItemCaseSensitive(o, "type");
  if (!t) return js_fail(c, "missing field \"type\"");
  if (cJSON_IsString(t) && !strcmp(t->valuestring, "plane")) {
    js_push_key(c, "type");
    return js_fail(c, "a plane is infinite, not a composite's operand (a large box makes a half-space)");
  }
  uint32_t type;
  static const char *const leaf_types[] = {"quadric", "ellipsoid", "cylinder", "cone", "paraboloid",
                                           "hyperboloid", "box", "csg", "sphere", "mesh", NULL};
  RC_TRY(js_get_enum(c, o, "type", leaf_types, 0, &type));
  rc_quadric_def q;
  if (type == T_MESH) {
    rc_affine t;
    RC_TRY(get_composed_transform(c, o, outer, &t));
    RC_TRY(js_parse_mesh_operand(c, o, s, inherited, &t, &q, &need->intervals));
    return add_leaf(s, &q, p, need);
  }
  if (type == T_CSG) {
    if (c->depth + 4 >= RC_JSON_MAX_DEPTH) return js_fail(c, "composites nested too deeply");
    static const char *const allowed[] = {"type", "op", "left", "right", "material", "transform", NULL};
    RC_TRY(js_check_members(c, o, allowed));
    static const char *const ops[] = {"union", "intersection", "difference", NULL};
    if (!cJSON_GetObjectItemCaseSensitive(o, "op")) return js_fail(c, "missing field \"op\"");
    uint32_t op;
    RC_TRY(js_get_enum(c, o, "op", ops, 0, &op));
    int material = inherited;
    if (cJSON_GetObjectItemCaseSensitive(o, "material")) {
      uint32_t id;
      RC_TRY(js_get_material_ref(c, o, &id));
      material = (int)id;
    }
    rc_affine t;
    RC_TRY(get_composed_transform(c, o, outer, &t));
    csg_need l, r;
    const char *sides[2] = {"left", "right"};
    for (int k = 0; k < 2; k++) {
      const cJSON *child = cJSON_GetObjectItemCaseSensitive(o, sides[k]);
      if (!child) return js_fail(c, "missing field \"%s\"", sides[k]);
      js_push_key(c, sides[k]);
      RC_TRY(parse_csg_node(c, child, s, material, &t, p, k ? &r : &l));
      js_pop(c);
    }
    /* Postfix: the left list waits on the stack while the right one is built. */
    need->stack = l.stack > r.stack + 1 ? l.stack : r.stack + 1;
    need->intervals = op == 1 ? l.intervals + r.intervals - 1 : l.intervals + r.intervals;
    need->steps = l.steps + r.steps + 1 + 2 * (l.intervals + r.intervals) + 2 * need->intervals;
    if (need->stack > RC_CSG_STACK || need->intervals > RC_CSG_MAX_INTERVALS)
      return js_fail(c, "composite too deep for the GPU's fixed interval lists: it needs %u lists of up to %u "
                        "intervals, the limit is %u lists of %u (nest the deeper operand on the left)",
                     need->stack, need->intervals, RC_CSG_STACK, RC_CSG_MAX_INTERVALS);
    if (op == 0) {
      need->lo = rcm_make_d(fmin(l.lo.x, r.lo.x), fmin(l.lo.y, r.lo.y), fmin(l.lo.z, r.lo.z));
      need->hi = rcm_make_d(fmax(l.hi.x, r.hi.x), fmax(l.hi.y, r.hi.y), fmax(l.hi.z, r.hi.z));
    } else if (op == 1) {
      need->lo = rcm_make_d(fmax(l.lo.x, r.lo.x), fmax(l.lo.y, r.lo.y), fmax(l.lo.z, r.lo.z));
      need->hi = rcm_make_d(fmin(l.hi.x, r.hi.x), fmin(l.hi.y, r.hi.y), fmin(l.hi.z, r.hi.z));
    } else {
      need->lo = l.lo, need->hi = l.hi;
    }
    GROW(p->code, p->length, p->capacity);
    p->code[p->length++] = ((op + 1) << RC_CSG_OP_SHIFT);
    return RC_OK;
  }
  RC_TRY(parse_quadric(c, o, type, inherited, outer, &q, &need->intervals));
  if (!q.solid) return js_fail(c, "a composite's operands must be closed solids (\"capped\" or \"solid\": true)");
  return add_leaf(s, &q, p, need);
}

/* The extent of a plane's frame: finite (Vulkan lets shaders assume no Inf), and unused,
 * since RC_QUADRIC_UNBOUNDED skips the clip box. */
#define PLANE_EXTENT 1e30

/* {"type": "plane", "point", "normal", "material", "one_sided", "transform"}: Q = 2 f.z in a
 * frame whose z is the unit normal, centred on the given point (packing moves the centre to
 * the plane's point nearest the eye: rc_scene_pack). */
static rc_status parse_plane(jctx *c, const cJSON *o, rc_scene *s) {
  static const char *const allowed[] = {"type", "point", "normal", "material", "one_sided", "transform", NULL};
  RC_TRY(js_check_members(c, o, allowed));
  dvec3 zero = rcm_make_d(0, 0, 0), point, normal;
  RC_TRY(js_get_vec3(c, o, "point", true, zero, -HUGE_VAL, &point));
  RC_TRY(js_get_vec3(c, o, "normal", true, zero, -HUGE_VAL, &normal));
  if (rcm_max_abs_comp_d(normal) == 0) {
    js_push_key(c, "normal");
    return js_fail(c, "must not be the zero vector");
  }
  rc_affine t;
  bool present;
  RC_TRY(js_get_transform(c, o, &t, &present));
  double a[3][3], inv[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) a[i][j] = t.m[i][j];
  if (!rcm_mat3_inverse_d(a, inv)) return js_fail(c, "its transform is singular");
  /* Points go through the transform, normals through its inverse transpose. */
  point = rc_affine_point(&t, point);
  normal = rcm_make_d(inv[0][0] * normal.x + inv[1][0] * normal.y + inv[2][0] * normal.z,
                      inv[0][1] * normal.x + inv[1][1] * normal.y + inv[2][1] * normal.z,
                      inv[0][2] * normal.x + inv[1][2] * normal.y + inv[2][2] * normal.z);
  dvec3 n = rcm_normalize_d(normal);
  rc_quadric_def q = {0};
  q.center = point;
  frame_from_axis(n, q.axis);
  q.linear = rcm_make_d(0, 0, 1);
  q.hi = rcm_make_d(PLANE_EXTENT, PLANE_EXTENT, PLANE_EXTENT);
  q.lo = rcm_scale_d(q.hi, -1);
  RC_TRY(js_get_bool(c, o, "one_sided", false, &q.one_sided));
  RC_TRY(js_get_material_ref(c, o, &q.material));
  GROW(s->planes, s->plane_count, s->plane_capacity);
  s->planes[s->plane_count++] = q;
  return RC_OK;
}

rc_status js_parse_quadric_object(jctx *c, const cJSON *o, rc_scene *s) {
  const cJSON *tv = cJSON_GetObjectItemCaseSensitive(o, "type");
  if (cJSON_IsString(tv) && !strcmp(tv->valuestring, "plane")) return parse_plane(c, o, s);
  rc_affine identity;
  js_affine_identity(&identity);
  uint32_t type;
  RC_TRY(js_get_enum(c, o, "type", quadric_types, 0, &type));
  if (type != T_CSG) {
    GROW(s->quadrics, s->quadric_count, s->quadric_capacity);
    uint32_t intervals;
    RC_TRY(parse_quadric(c, o, type, -1, &identity, &s->quadrics[s->quadric_count], &intervals));
    s->quadric_count++;
    return RC_OK;
  }
  GROW(s->csgs, s->csg_count, s->csg_capacity); /* first, while there is nothing to free */
  program p = {0};
  csg_need need;
  rc_status st = parse_csg_node(c, o, s, -1, &identity, &p, &need);
  if (st == RC_OK && !(need.lo.x <= need.hi.x && need.lo.y <= need.hi.y && need.lo.z <= need.hi.z))
    st = js_fail(c, "the operands of this intersection do not overlap: the composite is empty");
  if (st != RC_OK) {
    free(p.code);
    return st;
  }
  /* + the scan for the first interval end in front of the ray. */
  s->csgs[s->csg_count++] = (rc_csg_def){
      .program = p.code, .length = (uint32_t)p.length, .steps = need.steps + 2 * need.intervals, .lo = need.lo, .hi = need.hi};
  return RC_OK;
}
