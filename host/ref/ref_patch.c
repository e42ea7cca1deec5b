/* ref_patch.c: mirrors shaders/rc_patch.glsl function by function, same order, same
 * formulas (the shader has the references and the reasoning). */
#include "ref/ref_shader.h"

#include "ref/ref_real.h"
#include "ref/ref_patch.h"

#if REF_F64 /* one definition for both builds */
_Thread_local uint32_t ref_patch_stalls, ref_patch_stall_piece;
#endif

/* rc_patch.glsl's cache of the run cert_patch took last (ref_patch.h). */
_Thread_local patch_run ref_cert_patch_r;
_Thread_local real ref_cert_patch_t;

static rvec3 v3(vec3 a) { return rvec3_from(a); }

/* The shader's accessor of the texel array (rc_scene_access.glsl). */
static vec3 load_patch_point(const ref_scene *sc, uint32_t i) {
  return (vec3){sc->texels[i][0], sc->texels[i][1], sc->texels[i][2]};
}

rvec4 REF(bernstein)(real t) {
  real s = 1 - t;
  return (rvec4){s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t};
}

rvec4 REF(bernstein_slope)(real t) {
  real s = 1 - t;
  return (rvec4){-3 * s * s, 3 * s * (s - 2 * t), 3 * t * (2 * s - t), 3 * t * t};
}

real REF(weigh)(rvec4 w, rvec4 c) { return w.x * c.x + w.y * c.y + w.z * c.z + w.w * c.w; }

rvec4 REF(net_eval)(rvec4 r0, rvec4 r1, rvec4 r2, rvec4 r3, rvec4 bu, rvec4 su, rvec4 bv, rvec4 sv) {
  rvec4 along = {REF(weigh)(bu, r0), REF(weigh)(bu, r1), REF(weigh)(bu, r2), REF(weigh)(bu, r3)};
  rvec4 slope = {REF(weigh)(su, r0), REF(weigh)(su, r1), REF(weigh)(su, r2), REF(weigh)(su, r3)};
  return (rvec4){REF(weigh)(bv, along), REF(weigh)(bv, slope), REF(weigh)(sv, along), REF(weigh)(sv, slope)};
}

void REF(net_row)(const ref_scene *sc, uint32_t first, rvec3 o, rvec3 a, rvec3 b, rvec3 c, rvec4 *ra, rvec4 *rb,
                  rvec4 *rc, real *scale) {
  rvec3 p0 = RV(sub)(v3(load_patch_point(sc, first)), o);
  rvec3 p1 = RV(sub)(v3(load_patch_point(sc, first + 1u)), o);
  rvec3 p2 = RV(sub)(v3(load_patch_point(sc, first + 2u)), o);
  rvec3 p3 = RV(sub)(v3(load_patch_point(sc, first + 3u)), o);
  rvec4 xa = {RV(dot)(a, p0), RV(dot)(a, p1), RV(dot)(a, p2), RV(dot)(a, p3)};
  rvec4 xb = {RV(dot)(b, p0), RV(dot)(b, p1), RV(dot)(b, p2), RV(dot)(b, p3)};
  rvec4 xc = {RV(dot)(c, p0), RV(dot)(c, p1), RV(dot)(c, p2), RV(dot)(c, p3)};
  *ra = xa;
  *rb = xb;
  *rc = xc;
  *scale = rmax(*scale, rmax(rmax(REF(max3_abs)(p0), REF(max3_abs)(p1)), rmax(REF(max3_abs)(p2), REF(max3_abs)(p3))));
}

patch_net REF(load_patch_net)(const ref_scene *sc, uint32_t first, rvec3 o, rvec3 a, rvec3 b, rvec3 c) {
  patch_net n;
  n.scale = 0;
  REF(net_row)(sc, first, o, a, b, c, &n.a0, &n.b0, &n.c0, &n.scale);
  REF(net_row)(sc, first + 4u, o, a, b, c, &n.a1, &n.b1, &n.c1, &n.scale);
  REF(net_row)(sc, first + 8u, o, a, b, c, &n.a2, &n.b2, &n.c2, &n.scale);
  REF(net_row)(sc, first + 12u, o, a, b, c, &n.a3, &n.b3, &n.c3, &n.scale);
  return n;
}

void REF(patch_planes)(rvec3 d, rvec3 *a, rvec3 *b) {
  rvec3 w = (R_ABS(d.x) > R_ABS(d.y) && R_ABS(d.x) > R_ABS(d.z)) ? RV(make)(d.y, -d.x, 0) : RV(make)(0, d.z, -d.y);
  real len = R_SQRT(RV(dot)(w, w));
  rvec3 pa = RV(divs)(w, len);
  rvec3 pb = RV(cross)(pa, d);
  *a = pa;
  *b = pb;
}

patch_domain REF(patch_domain_of)(const packed_quadric *q) {
  patch_domain m;
  m.u0 = (real)q->diag.x;
  m.u1 = (real)q->diag.y;
  m.v0 = (real)q->off.x;
  m.v1 = (real)q->off.y;
  real mu = (real)RC_PATCH_DOMAIN_MARGIN * (m.u1 - m.u0);
  real mv = (real)RC_PATCH_DOMAIN_MARGIN * (m.v1 - m.v0);
  real edge = (real)RC_PATCH_EDGE_MARGIN;
  m.lo_u = (m.u0 == 0) ? -edge : m.u0 - mu;
  m.hi_u = (m.u1 == 1) ? 1 + edge : m.u1 + mu;
  m.lo_v = (m.v0 == 0) ? -edge : m.v0 - mv;
  m.hi_v = (m.v1 == 1) ? 1 + edge : m.v1 + mv;
  return m;
}

patch_run REF(patch_start)(patch_domain m) {
  patch_run r;
  r.u = (real)0.5 * (m.u0 + m.u1);
  r.v = (real)0.5 * (m.v0 + m.v1);
  r.bu = REF(bernstein)(r.u);
  r.bv = REF(bernstein)(r.v);
  r.residual = (real)RC_T_FAR;
  r.converged = false;
  r.nearby = true;
  return r;
}

void REF(patch_evaluate)(patch_net n, patch_run *r, rvec4 *fa, rvec4 *fb) {
  r->bu = REF(bernstein)(r->u);
  r->bv = REF(bernstein)(r->v);
  rvec4 su = REF(bernstein_slope)(r->u);
  rvec4 sv = REF(bernstein_slope)(r->v);
  *fa = REF(net_eval)(n.a0, n.a1, n.a2, n.a3, r->bu, su, r->bv, sv);
  *fb = REF(net_eval)(n.b0, n.b1, n.b2, n.b3, r->bu, su, r->bv, sv);
  r->residual = R_ABS(fa->x) + R_ABS(fb->x);
}

bool REF(newton_step)(rvec4 fa, rvec4 fb, real *u, real *v) {
  real det = fa.y * fb.z - fa.z * fb.y;
  if (det == 0) return false;
  real du = (fa.x * fb.z - fa.z * fb.x) / det;
  real dv = (fa.y * fb.x - fa.x * fb.y) / det;
  real nu = *u - du;
  real nv = *v - dv;
  *u = nu;
  *v = nv;
  return true;
}

patch_run REF(patch_newton)(patch_domain m, patch_net n) {
  real tol = (real)RC_PATCH_TOLERANCE_ULPS * RC_UNIT_ROUNDOFF * n.scale;
  real last_tol = (real)RC_PATCH_LAST_TOLERANCE * n.scale;
  real wu = m.u1 - m.u0;
  real wv = m.v1 - m.v0;
  patch_run r = REF(patch_start)(m);
  for (uint32_t i = 0; i < RC_PATCH_NEWTON_STEPS; i++) {
    ref_work++;
    rvec4 fa, fb;
    REF(patch_evaluate)(n, &r, &fa, &fb);
    bool last = i + 1u == RC_PATCH_NEWTON_STEPS;
    if (r.residual <= tol || (last && r.residual <= last_tol)) {
      r.converged = true;
      break;
    }
    if (last) break;
    if (!REF(newton_step)(fa, fb, &r.u, &r.v)) break;
    r.nearby = r.u >= m.u0 - wu && r.u <= m.u1 + wu && r.v >= m.v0 - wv && r.v <= m.v1 + wv;
    if (!r.nearby) break;
  }
  return r;
}

real REF(patch_depth)(patch_run r, patch_net n) {
  rvec4 along = {REF(weigh)(r.bu, n.c0), REF(weigh)(r.bu, n.c1), REF(weigh)(r.bu, n.c2), REF(weigh)(r.bu, n.c3)};
  return REF(weigh)(r.bv, along);
}

real REF(intersect_patch)(const ref_scene *sc, uint32_t index, const packed_quadric *q, rvec3 o, rvec3 d, real t_max,
                          rvec3 *uv) {
  const real far = (real)RC_T_FAR;
  *uv = RV(make)(0, 0, 0);
  real b_in, b_out;
  uint32_t a_in, a_out;
  REF(box_span)(v3(q->lo), v3(q->hi), RV(sub)(o, v3(q->center)), d, &b_in, &b_out, &a_in, &a_out);
  if (b_in > b_out || b_out < 0 || b_in > t_max * (real)RC_BOX_NEAR_SCALE) return far;
  patch_domain m = REF(patch_domain_of)(q);
  patch_run r;
  real t;
  if (sc->frame->certify) {
    r = ref_cert_patch_r;
    t = ref_cert_patch_t;
  } else {
    rvec3 a, b;
    REF(patch_planes)(d, &a, &b);
    patch_net n = REF(load_patch_net)(sc, q->mesh_root, o, a, b, d);
    r = REF(patch_newton)(m, n);
    t = REF(patch_depth)(r, n);
  }
  bool in_piece = r.u >= m.lo_u && r.u <= m.hi_u && r.v >= m.lo_v && r.v <= m.hi_v;
  if (!r.converged) {
    rvec3 extent = RV(sub)(v3(q->hi), v3(q->lo));
    if (in_piece && r.nearby && r.residual <= REF(max3_abs)(extent) * (real)0.015625) {
      ref_patch_stalls++;
      if (ref_patch_stall_piece == 0) ref_patch_stall_piece = 1u + index;
    }
    return far;
  }
  if (!in_piece) return far;
  if (t <= 0 || t > t_max) return far;
  *uv = RV(make)(r.u, r.v, 0);
  return t;
}

patch_net REF(patch_eval)(const ref_scene *sc, const packed_quadric *q, rvec3 uv, rvec4 *fx, rvec4 *fy, rvec4 *fz) {
  patch_net n = REF(load_patch_net)(sc, q->mesh_root, RV(make)(0, 0, 0), RV(make)(1, 0, 0), RV(make)(0, 1, 0),
                                    RV(make)(0, 0, 1));
  rvec4 bu = REF(bernstein)(uv.x);
  rvec4 su = REF(bernstein_slope)(uv.x);
  rvec4 bv = REF(bernstein)(uv.y);
  rvec4 sv = REF(bernstein_slope)(uv.y);
  *fx = REF(net_eval)(n.a0, n.a1, n.a2, n.a3, bu, su, bv, sv);
  *fy = REF(net_eval)(n.b0, n.b1, n.b2, n.b3, bu, su, bv, sv);
  *fz = REF(net_eval)(n.c0, n.c1, n.c2, n.c3, bu, su, bv, sv);
  return n;
}

rvec3 REF(patch_surface)(const ref_scene *sc, const packed_quadric *q, rvec3 uv, rvec3 *p, rvec3 *p_error) {
  rvec4 fx, fy, fz;
  patch_net n = REF(patch_eval)(sc, q, uv, &fx, &fy, &fz);
  *p = RV(make)(fx.x, fy.x, fz.x);
  real e = REF(gamma_bound)(32) * n.scale;
  *p_error = RV(make)(e, e, e);
  rvec3 pu = RV(make)(fx.y, fy.y, fz.y);
  rvec3 pv = RV(make)(fx.z, fy.z, fz.z);
  rvec3 puv = RV(make)(fx.w, fy.w, fz.w);
  real lu = RV(dot)(pu, pu);
  real lv = RV(dot)(pv, pv);
  if (lu < (real)9.094947017729282e-13 * lv) pu = (uv.y < (real)0.5) ? puv : RV(neg)(puv);
  else if (lv < (real)9.094947017729282e-13 * lu) pv = (uv.x < (real)0.5) ? puv : RV(neg)(puv);
  return RV(cross)(pu, pv);
}
