/* ref_patch.c: mirrors shaders/rc_patch.glsl function by function, same order, same
 * formulas (the shader has the references and the reasoning). */
#include "ref/ref_shader.h"

#include "ref/ref_real.h"

#if REF_F64 /* one definition for both builds */
_Thread_local uint32_t ref_patch_stalls, ref_patch_stall_piece;
#endif

/* rc_patch.glsl's struct patch_net. */
typedef struct {
  rvec4 a0, a1, a2, a3;
  rvec4 b0, b1, b2, b3;
  rvec4 c0, c1, c2, c3;
  real scale;
} patch_net;

rvec4 REF(bernstein)(real t);
rvec4 REF(bernstein_slope)(real t);
real REF(weigh)(rvec4 w, rvec4 c);
rvec4 REF(net_eval)(rvec4 r0, rvec4 r1, rvec4 r2, rvec4 r3, rvec4 bu, rvec4 su, rvec4 bv, rvec4 sv);
void REF(net_row)(const ref_scene *sc, uint32_t first, rvec3 o, rvec3 a, rvec3 b, rvec3 c, rvec4 *ra, rvec4 *rb,
                  rvec4 *rc, real *scale);
patch_net REF(load_patch_net)(const ref_scene *sc, uint32_t first, rvec3 o, rvec3 a, rvec3 b, rvec3 c);

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

real REF(intersect_patch)(const ref_scene *sc, uint32_t index, const packed_quadric *q, rvec3 o, rvec3 d, real t_max,
                          rvec3 *uv) {
  const real far = (real)RC_T_FAR;
  *uv = RV(make)(0, 0, 0);
  real b_in, b_out;
  uint32_t a_in, a_out;
  REF(box_span)(v3(q->lo), v3(q->hi), RV(sub)(o, v3(q->center)), d, &b_in, &b_out, &a_in, &a_out);
  if (b_in > b_out || b_out < 0 || b_in > t_max * (real)RC_BOX_NEAR_SCALE) return far;
  rvec3 w = (R_ABS(d.x) > R_ABS(d.y) && R_ABS(d.x) > R_ABS(d.z)) ? RV(make)(d.y, -d.x, 0) : RV(make)(0, d.z, -d.y);
  real len = R_SQRT(RV(dot)(w, w));
  rvec3 a = RV(divs)(w, len);
  rvec3 b = RV(cross)(a, d);
  patch_net n = REF(load_patch_net)(sc, q->mesh_root, o, a, b, d);
  real tol = (real)RC_PATCH_TOLERANCE_ULPS * RC_UNIT_ROUNDOFF * n.scale;
  real last_tol = (real)RC_PATCH_LAST_TOLERANCE * n.scale;
  real u0 = (real)q->diag.x;
  real u1 = (real)q->diag.y;
  real v0 = (real)q->off.x;
  real v1 = (real)q->off.y;
  real wu = u1 - u0;
  real wv = v1 - v0;
  real u = (real)0.5 * (u0 + u1);
  real v = (real)0.5 * (v0 + v1);
  real mu = (real)RC_PATCH_DOMAIN_MARGIN * wu;
  real mv = (real)RC_PATCH_DOMAIN_MARGIN * wv;
  real edge = (real)RC_PATCH_EDGE_MARGIN;
  real lo_u = (u0 == 0) ? -edge : u0 - mu;
  real hi_u = (u1 == 1) ? 1 + edge : u1 + mu;
  real lo_v = (v0 == 0) ? -edge : v0 - mv;
  real hi_v = (v1 == 1) ? 1 + edge : v1 + mv;
  rvec4 bu = REF(bernstein)(u);
  rvec4 bv = REF(bernstein)(v);
  real residual = far;
  bool converged = false;
  bool nearby = true;
  for (uint32_t i = 0; i < RC_PATCH_NEWTON_STEPS; i++) {
    ref_work++;
    bu = REF(bernstein)(u);
    bv = REF(bernstein)(v);
    rvec4 su = REF(bernstein_slope)(u);
    rvec4 sv = REF(bernstein_slope)(v);
    rvec4 fa = REF(net_eval)(n.a0, n.a1, n.a2, n.a3, bu, su, bv, sv);
    rvec4 fb = REF(net_eval)(n.b0, n.b1, n.b2, n.b3, bu, su, bv, sv);
    residual = R_ABS(fa.x) + R_ABS(fb.x);
    bool last = i + 1u == RC_PATCH_NEWTON_STEPS;
    if (residual <= tol || (last && residual <= last_tol)) {
      converged = true;
      break;
    }
    if (last) break;
    real det = fa.y * fb.z - fa.z * fb.y;
    if (det == 0) break;
    real du = (fa.x * fb.z - fa.z * fb.x) / det;
    real dv = (fa.y * fb.x - fa.x * fb.y) / det;
    u = u - du;
    v = v - dv;
    nearby = u >= u0 - wu && u <= u1 + wu && v >= v0 - wv && v <= v1 + wv;
    if (!nearby) break;
  }
  bool in_piece = u >= lo_u && u <= hi_u && v >= lo_v && v <= hi_v;
  if (!converged) {
    rvec3 extent = RV(sub)(v3(q->hi), v3(q->lo));
    if (in_piece && nearby && residual <= REF(max3_abs)(extent) * (real)0.015625) {
      ref_patch_stalls++;
      if (ref_patch_stall_piece == 0) ref_patch_stall_piece = 1u + index;
    }
    return far;
  }
  if (!in_piece) return far;
  rvec4 along = {REF(weigh)(bu, n.c0), REF(weigh)(bu, n.c1), REF(weigh)(bu, n.c2), REF(weigh)(bu, n.c3)};
  real t = REF(weigh)(bv, along);
  if (t <= 0 || t > t_max) return far;
  *uv = RV(make)(u, v, 0);
  return t;
}

rvec3 REF(patch_surface)(const ref_scene *sc, const packed_quadric *q, rvec3 uv, rvec3 *p, rvec3 *p_error) {
  patch_net n = REF(load_patch_net)(sc, q->mesh_root, RV(make)(0, 0, 0), RV(make)(1, 0, 0), RV(make)(0, 1, 0),
                                    RV(make)(0, 0, 1));
  rvec4 bu = REF(bernstein)(uv.x);
  rvec4 su = REF(bernstein_slope)(uv.x);
  rvec4 bv = REF(bernstein)(uv.y);
  rvec4 sv = REF(bernstein_slope)(uv.y);
  rvec4 fx = REF(net_eval)(n.a0, n.a1, n.a2, n.a3, bu, su, bv, sv);
  rvec4 fy = REF(net_eval)(n.b0, n.b1, n.b2, n.b3, bu, su, bv, sv);
  rvec4 fz = REF(net_eval)(n.c0, n.c1, n.c2, n.c3, bu, su, bv, sv);
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
