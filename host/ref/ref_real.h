/* ref_real.h: the working precision of the CPU reference, mirroring rc_real.glsl. Every
 * ref_*.c file is compiled twice: REF_F64=1 (the accuracy reference, double) and REF_F64=0
 * (float: the GPU's arithmetic, to tell driver effects from precision effects). REF(name)
 * gives each build its own symbols: REF(intersect_sphere) is ref_intersect_sphere_d or
 * ref_intersect_sphere_f, the twin of the shader's intersect_sphere. */
#ifndef RC_REF_REAL_H
#define RC_REF_REAL_H

#include <math.h>

#include "math/rcm_vec3.h"

#if REF_F64
typedef double real;
typedef dvec3 rvec3;
#define REF(name) ref_##name##_d
#define RV(op) rcm_##op##_d
#define R_SQRT sqrt
#define R_ABS fabs
#define R_FLOOR floor
#define R_FREXP frexp
#define RC_UNIT_ROUNDOFF 1.1102230246251565e-16
#define RC_SMALLEST_NORMAL 2.2250738585072014e-308
static inline rvec3 rvec3_from(vec3 a) { return rcm_to_d(a); }
/* GLSL's vec3(v) of an rvec3: rounded to float (the AOV's f32 fields). */
static inline vec3 vec3_from(rvec3 a) { return rcm_to_f(a); }
#else
typedef float real;
typedef vec3 rvec3;
#define REF(name) ref_##name##_f
#define RV(op) rcm_##op##_f
#define R_SQRT sqrtf
#define R_ABS fabsf
#define R_FLOOR floorf
#define R_FREXP frexpf
#define RC_UNIT_ROUNDOFF 5.9604644775390625e-8f
#define RC_SMALLEST_NORMAL 1.17549435e-38f
static inline rvec3 rvec3_from(vec3 a) { return a; }
static inline vec3 vec3_from(rvec3 a) { return a; }
#endif

/* rc_certify.glsl's globals, this precision's (ref_intersect.h). */
#define ref_cert_ok REF(cert_ok)
#define ref_cert_any REF(cert_any)
#define ref_cert_self REF(cert_self)
#define ref_cert_spawn_object REF(cert_spawn_object)
#define ref_cert_stage REF(cert_stage)
#define ref_cert_eo REF(cert_eo)
#define ref_cert_ed REF(cert_ed)
#define ref_cert_et REF(cert_et)
#define ref_cert_t_err REF(cert_t_err)
#define ref_cert_bary_err REF(cert_bary_err)
#define ref_cert_off_err REF(cert_off_err)
#define ref_cert_beyond REF(cert_beyond)
#define ref_cert_t_max_err REF(cert_t_max_err)
#define ref_cert_ep REF(cert_ep)
#define ref_cert_en REF(cert_en)
#define ref_cert_hit_ok REF(cert_hit_ok)
#define ref_cert_blocked_later REF(cert_blocked_later)
#define ref_cert_blocker_certain REF(cert_blocker_certain)

/* rc_quadric.glsl's interval stack, this precision's (ref_intersect.h). */
#define csg_t REF(csg_t)
#define csg_code_of REF(csg_code_of)
#define csg_e REF(csg_e)

/* GLSL's rvec4 (rc_patch.glsl's rows of four control points), a plain struct here. */
typedef struct { real x, y, z, w; } rvec4;

static inline real rv_get(rvec3 a, int i) { return i == 0 ? a.x : (i == 1 ? a.y : a.z); }
/* Min and max of two reals by comparison: the twins of the shader's select_min and
 * select_max (rc_real.glsl), not of GLSL's min and max, whose result for a NaN operand
 * the specification leaves open. */
/* rc_real.glsl's RL(x): the literal rounded to f32, then widened to the working precision. */
#define RL(x) ((real)(float)(x))
static inline real rmin(real a, real b) { return a < b ? a : b; }
static inline real rmax(real a, real b) { return a > b ? a : b; }

#endif
