/* ref_triangle.c: mirrors shaders/rc_triangle.glsl function by function, same order, same
 * formulas (the shader has the papers and the reasoning). Built with -ffp-contract=off. */
#include "ref/ref_shader.h"

#include "ref/ref_real.h"

real REF(gamma_bound)(real n) { return (n * RC_UNIT_ROUNDOFF) / (1 - n * RC_UNIT_ROUNDOFF); }

ref_shear REF(ray_shear_for)(rvec3 d) {
  rvec3 a = RV(abs)(d);
  int kz = (a.x > a.y) ? ((a.x > a.z) ? 0 : 2) : ((a.y > a.z) ? 1 : 2);
  int kx = (kz + 1) % 3;
  int ky = (kx + 1) % 3;
  if (rv_get(d, kz) < 0) {
    int tmp = kx;
    kx = ky;
    ky = tmp;
  }
  ref_shear sh = {{kx, ky, kz}, RV(make)(rv_get(d, kx) / rv_get(d, kz), rv_get(d, ky) / rv_get(d, kz), 1 / rv_get(d, kz))};
  return sh;
}

rvec3 REF(permute)(rvec3 a, const int k[3]) { return RV(make)(rv_get(a, k[0]), rv_get(a, k[1]), rv_get(a, k[2])); }

ref_sheared REF(shear_triangle)(rvec3 o, const ref_shear *sh, packed_triangle tri) {
  rvec3 a = REF(permute)(RV(sub)(rvec3_from(tri.v0), o), sh->k);
  rvec3 b = REF(permute)(RV(sub)(rvec3_from(tri.v1), o), sh->k);
  rvec3 c = REF(permute)(RV(sub)(rvec3_from(tri.v2), o), sh->k);
  real ax = a.x - sh->s.x * a.z;
  real ay = a.y - sh->s.y * a.z;
  real bx = b.x - sh->s.x * b.z;
  real by = b.y - sh->s.y * b.z;
  real cx = c.x - sh->s.x * c.z;
  real cy = c.y - sh->s.y * c.z;
  real u = cx * by - cy * bx;
  real v = ax * cy - ay * cx;
  real w = bx * ay - by * ax;
  rvec3 z = RV(make)(sh->s.z * a.z, sh->s.z * b.z, sh->s.z * c.z);
  ref_sheared st;
  st.x = RV(make)(ax, bx, cx);
  st.y = RV(make)(ay, by, cy);
  st.z = z;
  st.depth = RV(make)(a.z, b.z, c.z);
  st.e = RV(make)(u, v, w);
  return st;
}

real REF(max3_abs)(rvec3 a) {
  rvec3 m = RV(abs)(a);
  return rmax(rmax(m.x, m.y), m.z);
}

real REF(triangle_t_error)(const ref_sheared *st, real det) {
  real max_zt = REF(max3_abs)(st->z);
  real max_xt = REF(max3_abs)(st->x);
  real max_yt = REF(max3_abs)(st->y);
  real delta_z = REF(gamma_bound)(3) * max_zt;
  real delta_x = REF(gamma_bound)(5) * (max_xt + max_zt);
  real delta_y = REF(gamma_bound)(5) * (max_yt + max_zt);
  real delta_e = 2 * (REF(gamma_bound)(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  real max_e = REF(max3_abs)(st->e);
  return 3 * (REF(gamma_bound)(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) / R_ABS(det);
}

real REF(enclosing_det)(rvec3 e) {
  if ((e.x < 0 || e.y < 0 || e.z < 0) && (e.x > 0 || e.y > 0 || e.z > 0)) return 0;
  return e.x + e.y + e.z;
}

real REF(triangle_t)(const ref_sheared *st, real det) {
  real t_scaled = st->e.x * st->z.x + st->e.y * st->z.y + st->e.z * st->z.z;
  return t_scaled / det;
}

real REF(intersect_triangle)(rvec3 o, const ref_shear *sh, packed_triangle tri, real t_max, rvec3 *bary) {
  *bary = RV(make)(0, 0, 0);
  ref_sheared st = REF(shear_triangle)(o, sh, tri);
  real det = REF(enclosing_det)(st.e);
  if (det == 0) return (real)RC_T_FAR;
  real t = REF(triangle_t)(&st, det);
  if (!(t > 0 && t <= t_max)) return (real)RC_T_FAR;
  if (ref_spawned_ray && t <= REF(triangle_t_error)(&st, det)) return (real)RC_T_FAR;
  *bary = RV(divs)(st.e, det);
  return t;
}

bool REF(edge_owned)(real x0, real y0, real x1, real y1, real det) {
  real ex = det > 0 ? x1 - x0 : x0 - x1;
  real ey = det > 0 ? y1 - y0 : y0 - y1;
  return ey > 0 || (ey == 0 && ex < 0);
}

real REF(triangle_crossing)(rvec3 o, const ref_shear *sh, packed_triangle tri) {
  ref_sheared st = REF(shear_triangle)(o, sh, tri);
  real det = REF(enclosing_det)(st.e);
  if (det == 0) return (real)RC_T_FAR;
  if (st.e.x == 0 && !REF(edge_owned)(st.x.y, st.y.y, st.x.z, st.y.z, det)) return (real)RC_T_FAR;
  if (st.e.y == 0 && !REF(edge_owned)(st.x.z, st.y.z, st.x.x, st.y.x, det)) return (real)RC_T_FAR;
  if (st.e.z == 0 && !REF(edge_owned)(st.x.x, st.y.x, st.x.y, st.y.y, det)) return (real)RC_T_FAR;
  real t = REF(triangle_t)(&st, det);
  if (ref_spawned_ray && R_ABS(t) <= REF(triangle_t_error)(&st, det)) return 0;
  return t;
}

real REF(intersect_triangle_moller_trumbore)(rvec3 o, rvec3 d, packed_triangle tri, real t_max, rvec3 *bary) {
  *bary = RV(make)(0, 0, 0);
  rvec3 v0 = rvec3_from(tri.v0);
  rvec3 e1 = RV(sub)(rvec3_from(tri.v1), v0);
  rvec3 e2 = RV(sub)(rvec3_from(tri.v2), v0);
  rvec3 pv = RV(cross)(d, e2);
  real det = RV(dot)(e1, pv);
  if (R_ABS(det) < (real)1.0e-6) return (real)RC_T_FAR;
  real inv_det = 1 / det;
  rvec3 tv = RV(sub)(o, v0);
  real u = RV(dot)(tv, pv) * inv_det;
  if (u < 0 || u > 1) return (real)RC_T_FAR;
  rvec3 qv = RV(cross)(tv, e1);
  real v = RV(dot)(d, qv) * inv_det;
  if (v < 0 || u + v > 1) return (real)RC_T_FAR;
  real t = RV(dot)(e2, qv) * inv_det;
  if (!(t > 0 && t <= t_max)) return (real)RC_T_FAR;
  *bary = RV(make)(1 - u - v, u, v);
  return t;
}

real REF(intersect_triangle_cramer)(rvec3 o, rvec3 d, packed_triangle tri, real t_max, rvec3 *bary) {
  *bary = RV(make)(0, 0, 0);
  rvec3 ab = RV(sub)(rvec3_from(tri.v0), rvec3_from(tri.v1));
  rvec3 ac = RV(sub)(rvec3_from(tri.v0), rvec3_from(tri.v2));
  rvec3 ao = RV(sub)(rvec3_from(tri.v0), o);
  real ei_hf = ac.y * d.z - d.y * ac.z;
  real gf_di = d.x * ac.z - ac.x * d.z;
  real dh_eg = ac.x * d.y - ac.y * d.x;
  real m = ab.x * ei_hf + ab.y * gf_di + ab.z * dh_eg;
  if (m == 0) return (real)RC_T_FAR;
  real ak_jb = ab.x * ao.y - ao.x * ab.y;
  real jc_al = ao.x * ab.z - ab.x * ao.z;
  real bl_kc = ab.y * ao.z - ao.y * ab.z;
  real t = -(ac.z * ak_jb + ac.y * jc_al + ac.x * bl_kc) / m;
  if (!(t > 0 && t <= t_max)) return (real)RC_T_FAR;
  real gamma = (d.z * ak_jb + d.y * jc_al + d.x * bl_kc) / m;
  if (gamma < 0 || gamma > 1) return (real)RC_T_FAR;
  real beta = (ao.x * ei_hf + ao.y * gf_di + ao.z * dh_eg) / m;
  if (beta < 0 || beta > 1 - gamma) return (real)RC_T_FAR;
  *bary = RV(make)(1 - beta - gamma, beta, gamma);
  return t;
}

/* Whether d meets the triangle's front, the side its geometric normal cross(v1 - v0,
 * v2 - v0) points to (counter-clockwise winding seen from there): a one-sided triangle
 * (RC_TRIANGLE_ONE_SIDED) is there for such rays only. Edge on counts as behind. */
real REF(triangle_facing)(packed_triangle tri, rvec3 d) {
  rvec3 v0 = rvec3_from(tri.v0);
  real facing = RV(dot)(d, RV(cross)(RV(sub)(rvec3_from(tri.v1), v0), RV(sub)(rvec3_from(tri.v2), v0)));
  return facing;
}

bool REF(triangle_faces_ray)(packed_triangle tri, rvec3 d) { return REF(triangle_facing)(tri, d) < 0; }
