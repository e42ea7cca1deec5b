/* rcm_vec3.h: cglm-style 3-vectors by value, named after the GLSL built-ins so that a
 * shader line translates to one C line. Two instantiations from one template:
 *   vec3  (float, the type of rc_shared.h)  -> rcm_<op>_f
 *   dvec3 (double)                          -> rcm_<op>_d
 * Functions: make, add, sub, mul, div, divs (by a scalar), scale, neg, abs, dot, cross, eq,
 * length, normalize, reflect, max_abs_comp; and rcm_xyz, rcm_to_f, rcm_to_d. */
#ifndef RCM_VEC3_H
#define RCM_VEC3_H

#include <math.h>
#include <stdbool.h>

#include "rc_shared.h"

typedef struct { double x, y, z; } dvec3;

#define RCM_DEFINE_VEC3(V, R, S, SQRT, FABS)                                                  \
  static inline V rcm_make_##S(R x, R y, R z) { V r = {x, y, z}; return r; }                  \
  static inline V rcm_add_##S(V a, V b) { return rcm_make_##S(a.x + b.x, a.y + b.y, a.z + b.z); } \
  static inline V rcm_sub_##S(V a, V b) { return rcm_make_##S(a.x - b.x, a.y - b.y, a.z - b.z); } \
  static inline V rcm_mul_##S(V a, V b) { return rcm_make_##S(a.x * b.x, a.y * b.y, a.z * b.z); } \
  static inline V rcm_div_##S(V a, V b) { return rcm_make_##S(a.x / b.x, a.y / b.y, a.z / b.z); } \
  /* GLSL's v / s: three divisions (not a product with 1 / s). */                            \
  static inline V rcm_divs_##S(V a, R s) { return rcm_make_##S(a.x / s, a.y / s, a.z / s); }  \
  static inline V rcm_scale_##S(V a, R s) { return rcm_make_##S(a.x * s, a.y * s, a.z * s); }   \
  static inline V rcm_neg_##S(V a) { return rcm_make_##S(-a.x, -a.y, -a.z); }                 \
  static inline V rcm_abs_##S(V a) { return rcm_make_##S(FABS(a.x), FABS(a.y), FABS(a.z)); }   \
  static inline R rcm_dot_##S(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }         \
  static inline V rcm_cross_##S(V a, V b) {                                                    \
    return rcm_make_##S(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);  \
  }                                                                                            \
  /* GLSL's a == b: every component equal. */                                               \
  static inline bool rcm_eq_##S(V a, V b) { return a.x == b.x && a.y == b.y && a.z == b.z; }  \
  static inline R rcm_length_##S(V a) { return SQRT(rcm_dot_##S(a, a)); }                     \
  static inline V rcm_normalize_##S(V a) { return rcm_scale_##S(a, (R)1 / rcm_length_##S(a)); } \
  /* GLSL reflect(): d - 2 dot(n, d) n, n unit. */                                             \
  static inline V rcm_reflect_##S(V d, V n) {                                                  \
    return rcm_sub_##S(d, rcm_scale_##S(n, (R)2 * rcm_dot_##S(n, d)));                         \
  }                                                                                            \
  static inline R rcm_max_abs_comp_##S(V a) {                                                  \
    R m = FABS(a.x);                                                                           \
    if (FABS(a.y) > m) m = FABS(a.y);                                                          \
    if (FABS(a.z) > m) m = FABS(a.z);                                                          \
    return m;                                                                                  \
  }

RCM_DEFINE_VEC3(vec3, float, f, sqrtf, fabsf)
RCM_DEFINE_VEC3(dvec3, double, d, sqrt, fabs)

static inline vec3 rcm_xyz(vec4 a) { vec3 r = {a.x, a.y, a.z}; return r; }
static inline vec3 rcm_to_f(dvec3 a) { vec3 r = {(float)a.x, (float)a.y, (float)a.z}; return r; }
static inline dvec3 rcm_to_d(vec3 a) { dvec3 r = {a.x, a.y, a.z}; return r; }

#endif
