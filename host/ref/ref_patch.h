/* ref_patch.h: rc_patch.glsl's structs and the functions of ref_patch.c that its certificate
 * (ref_certify_patch.c) calls. Included after ref_real.h, once per precision. */
#ifndef RC_REF_PATCH_H
#define RC_REF_PATCH_H

/* rc_patch.glsl's struct patch_net. */
typedef struct {
  rvec4 a0, a1, a2, a3;
  rvec4 b0, b1, b2, b3;
  rvec4 c0, c1, c2, c3;
  real scale;
} patch_net;

/* rc_patch.glsl's struct patch_domain. */
typedef struct {
  real u0, u1, v0, v1;
  real lo_u, hi_u, lo_v, hi_v;
} patch_domain;

/* rc_patch.glsl's struct patch_run. */
typedef struct {
  real u, v, residual;
  bool converged, nearby;
  rvec4 bu, bv;
} patch_run;

/* The run cert_patch took last, with its t, which intersect_patch takes (rc_patch.glsl). */
#define ref_cert_patch_r REF(cert_patch_r)
#define ref_cert_patch_t REF(cert_patch_t)
extern _Thread_local patch_run ref_cert_patch_r;
extern _Thread_local real ref_cert_patch_t;

rvec4 REF(bernstein)(real t);
rvec4 REF(bernstein_slope)(real t);
real REF(weigh)(rvec4 w, rvec4 c);
rvec4 REF(net_eval)(rvec4 r0, rvec4 r1, rvec4 r2, rvec4 r3, rvec4 bu, rvec4 su, rvec4 bv, rvec4 sv);
void REF(net_row)(const ref_scene *sc, uint32_t first, rvec3 o, rvec3 a, rvec3 b, rvec3 c, rvec4 *ra, rvec4 *rb,
                  rvec4 *rc, real *scale);
patch_net REF(load_patch_net)(const ref_scene *sc, uint32_t first, rvec3 o, rvec3 a, rvec3 b, rvec3 c);
void REF(patch_planes)(rvec3 d, rvec3 *a, rvec3 *b);
patch_domain REF(patch_domain_of)(const packed_quadric *q);
patch_run REF(patch_start)(patch_domain m);
void REF(patch_evaluate)(patch_net n, patch_run *r, rvec4 *fa, rvec4 *fb);
bool REF(newton_step)(rvec4 fa, rvec4 fb, real *u, real *v);
patch_run REF(patch_newton)(patch_domain m, patch_net n);
real REF(patch_depth)(patch_run r, patch_net n);
patch_net REF(patch_eval)(const ref_scene *sc, const packed_quadric *q, rvec3 uv, rvec4 *fx, rvec4 *fy, rvec4 *fz);

#endif
