/* ref_certify.c: mirrors shaders/rc_certify.glsl (see the shader for the bounds and their
 * sources). The shader's globals are per thread here; those in the working precision are
 * per precision as well (ref_intersect.h names them). */
#include "ref/ref_shader.h"

#include "ref/ref_real.h"

_Thread_local bool ref_cert_ok = true, ref_cert_any, ref_cert_self, ref_cert_hit_ok, ref_cert_blocked_later,
    ref_cert_blocker_certain;
_Thread_local uint32_t ref_cert_spawn_object = 0xffffffffu;
_Thread_local real ref_cert_eo, ref_cert_ed, ref_cert_t_err, ref_cert_bary_err, ref_cert_beyond = (real)RC_T_FAR,
    ref_cert_t_max_err, ref_cert_ep, ref_cert_en;

real REF(cert_factor)(const ref_scene *sc) {
  if (sc->frame->certify == RC_CERTIFY_HALVED) return RL(0.5);
  return (sc->frame->certify == RC_CERTIFY_ZERO) ? 0 : RL(1.00000095367431640625);
}

void REF(cert_require)(const ref_scene *sc, real margin, real bound) {
  if (!(R_ABS(margin) > REF(cert_factor)(sc) * bound)) ref_cert_ok = false;
}

real REF(cert_turn)(real x) { return (x < (real)0.5) ? x / R_SQRT(1 - x * x) + REF(gamma_bound)(8) : 2; }

real REF(cert_turn_of)(real e, real len) { return (len > e) ? REF(cert_turn)(e / (len - e)) : 2; }

void REF(cert_fail)(void) { ref_cert_ok = false; }

void REF(cert_camera)(const ref_scene *sc, ref_vec2 raster) {
  const packed_camera *c = &sc->frame->camera;
  real us = (real)c->left + ((real)c->right - (real)c->left) * (real)raster.x / (real)c->width;
  real vs = (real)c->bottom + ((real)c->top - (real)c->bottom) * (real)raster.y / (real)c->height;
  real eus = REF(gamma_bound)(4) * (R_ABS((real)c->left) + R_ABS((real)c->right) + R_ABS(us));
  real evs = REF(gamma_bound)(4) * (R_ABS((real)c->bottom) + R_ABS((real)c->top) + R_ABS(vs));
  real mag = R_ABS((real)c->focal) + R_ABS(us) + R_ABS(vs);
  real err = REF(gamma_bound)(3) * mag + eus + evs;
  ref_cert_ok = true;
  ref_cert_spawn_object = 0xffffffffu;
  if (c->projection == RC_PROJECTION_PERSPECTIVE) {
    real len = RV(length)(RV(add)(RV(add)(RV(scale)(rvec3_from(c->w), -(real)c->focal), RV(scale)(rvec3_from(c->u), us)),
                                  RV(scale)(rvec3_from(c->v), vs)));
    ref_cert_eo = 0;
    ref_cert_ed = err / (len - err) + REF(gamma_bound)(4);
  } else {
    ref_cert_eo = 2 * (REF(gamma_bound)(3) * (RV(length)(rvec3_from(c->eye)) + R_ABS(us) + R_ABS(vs)) + eus + evs);
    ref_cert_ed = 0;
  }
}

void REF(cert_maybe)(const ref_scene *sc, real lo, real hi, real t_max, bool taken) {
  if (taken) {
    REF(cert_fail)();
    return;
  }
  if (hi < 0) return;
  if (ref_cert_any) {
    if (!(lo - t_max > REF(cert_factor)(sc) * ref_cert_t_max_err)) REF(cert_fail)();
    return;
  }
  ref_cert_beyond = rmin(ref_cert_beyond, lo);
}

bool REF(cert_root)(const ref_scene *sc, real t, real e, real t_max, bool ahead) {
  if (!ahead && ref_cert_self) return false;
  REF(cert_require)(sc, t, e);
  if (!ahead) return false;
  if (ref_cert_any) REF(cert_require)(sc, t - t_max, e + ref_cert_t_max_err);
  if (!(t <= t_max)) {
    ref_cert_beyond = rmin(ref_cert_beyond, t - REF(cert_factor)(sc) * e);
    return false;
  }
  ref_cert_t_err = e;
  return true;
}

void REF(cert_sphere_grazing)(const ref_scene *sc, real disc, real b, real c, real e_disc, real e_b, real e_c,
                              real t_max, real t_near, real t_exit, bool roots, real scale, real rel) {
  real k = REF(cert_factor)(sc);
  real reach = t_max + R_ABS(t_max) * (real)9.5367431640625e-07;
  bool taken = disc >= 0 && roots && ((t_near > 0 && t_near <= reach) || (t_exit > 0 && t_exit <= reach));
  if (!taken && b > k * e_b && (ref_cert_self || c > k * e_c)) return;
  real spread = R_SQRT(rmax(disc, 0) + k * e_disc) + k * e_b;
  real lo = (-b - spread) * scale;
  real hi = (-b + spread) * scale;
  REF(cert_maybe)(sc, lo - R_ABS(lo) * rel, hi + R_ABS(hi) * rel, t_max, taken);
}

void REF(cert_sphere_roots)(const ref_scene *sc, rvec3 o, rvec3 d, packed_sphere s, real t_max, real scale, real rel) {
  real r = (real)s.radius;
  rvec3 f = RV(sub)(o, rvec3_from(s.center));
  real b = RV(dot)(f, d);
  rvec3 l = RV(sub)(f, RV(scale)(d, b));
  real ll = RV(dot)(l, l);
  real disc = r * r - ll;
  real ff = RV(dot)(f, f);
  real c = ff - r * r;
  real fm = R_SQRT(ff);
  real lm = R_SQRT(ll);
  real el = ref_cert_eo + 2 * fm * ref_cert_ed + REF(gamma_bound)(8) * 2 * fm;
  real e_disc = 2 * lm * el + el * el + REF(gamma_bound)(4) * (r * r + ll);
  real e_b = ref_cert_eo + fm * ref_cert_ed + (ref_cert_eo) * ref_cert_ed + REF(gamma_bound)(4) * fm;
  real e_c = 2 * fm * ref_cert_eo + (ref_cert_eo) * ref_cert_eo + REF(gamma_bound)(4) * (ff + r * r);
  bool certain = R_ABS(disc) > REF(cert_factor)(sc) * e_disc;
  if (certain && disc < 0) return;
  real sq = R_SQRT(rmax(disc, 0));
  real q = (b >= 0) ? -(b + sq) : -(b - sq);
  real t0 = c / q;
  real t_near = rmin(t0, q) * scale;
  real t_exit = rmax(t0, q) * scale;
  if (!certain) {
    REF(cert_sphere_grazing)(sc, disc, b, c, e_disc, e_b, e_c, t_max, t_near, t_exit, q != 0, scale, rel);
    return;
  }
  if (q == 0) {
    REF(cert_fail)();
    return;
  }
  real e_sq = e_disc / (sq + R_SQRT(rmax(disc - e_disc, 0))) + REF(gamma_bound)(2) * sq;
  real e_q = e_b + e_sq + REF(gamma_bound)(2) * R_ABS(q);
  real e_t0 = (R_ABS(q) > e_q) ? (e_c + R_ABS(t0) * e_q) / (R_ABS(q) - e_q) + REF(gamma_bound)(1) * R_ABS(t0)
                               : (real)RC_T_FAR;
  real e = rmax(e_q, e_t0);
  if (REF(cert_root)(sc, t_near, e * scale + R_ABS(t_near) * rel, t_max, t_near > 0)) return;
  REF(cert_root)(sc, t_exit, e * scale + R_ABS(t_exit) * rel, t_max, t_exit > 0);
}

real REF(cert_norm)(const packed_transform *m) {
  return R_SQRT(RV(dot)(rvec3_from(rcm_xyz(m->row0)), rvec3_from(rcm_xyz(m->row0))) +
                RV(dot)(rvec3_from(rcm_xyz(m->row1)), rvec3_from(rcm_xyz(m->row1))) +
                RV(dot)(rvec3_from(rcm_xyz(m->row2)), rvec3_from(rcm_xyz(m->row2))));
}

real REF(cert_triangle_t_error)(const ref_sheared *st, real t, real det, real e_det, real ee, real dz, real se) {
  if (!(R_ABS(det) > e_det)) return (real)RC_T_FAR;
  real sz = R_ABS(st->z.x) + R_ABS(st->z.y) + R_ABS(st->z.z);
  real zt = R_ABS(st->z.x - t) + R_ABS(st->z.y - t) + R_ABS(st->z.z - t) + REF(gamma_bound)(8) * (sz + 3 * R_ABS(t));
  real ez = R_ABS(st->e.x * st->z.x) + R_ABS(st->e.y * st->z.y) + R_ABS(st->e.z * st->z.z);
  real zeta = dz + REF(gamma_bound)(3) * REF(max3_abs)(st->z);
  return (ee * zt + (se + 3 * ee) * zeta) / (R_ABS(det) - e_det) + REF(gamma_bound)(3) * (ez + R_ABS(t) * se) / R_ABS(det);
}


void REF(cert_triangle)(const ref_scene *sc, rvec3 o, const ref_shear *sh, packed_triangle tri, real t_max) {
  if (sc->frame->triangle_formula != RC_TRIANGLE_WATERTIGHT || (tri.flags & RC_TRIANGLE_ONE_SIDED) != 0) {
    REF(cert_fail)();
    return;
  }
  ref_sheared st = REF(shear_triangle)(o, sh, tri);
  real inv = R_ABS(sh->s.z);
  real sx = R_ABS(sh->s.x);
  real sy = R_ABS(sh->s.y);
  real zr = REF(max3_abs)(st.z) / inv;
  real xm = REF(max3_abs)(st.x);
  real ym = REF(max3_abs)(st.y);
  real dx = (ref_cert_eo) * (1 + sx) + (ref_cert_ed) * (1 + sx) * inv * zr + REF(gamma_bound)(5) * (xm + 2 * sx * zr);
  real dy = (ref_cert_eo) * (1 + sy) + (ref_cert_ed) * (1 + sy) * inv * zr + REF(gamma_bound)(5) * (ym + 2 * sy * zr);
  real ee = 2 * (dx * ym + xm * dy + dx * dy) + REF(gamma_bound)(2) * 2 * xm * ym;
  real k = REF(cert_factor)(sc) * ee;
  bool pos = st.e.x > k || st.e.y > k || st.e.z > k;
  bool neg = st.e.x < -k || st.e.y < -k || st.e.z < -k;
  if (pos && neg) return;
  real dz = inv * (ref_cert_eo + RC_UNIT_ROUNDOFF * zr) + (ref_cert_ed) * inv * inv * zr;
  real se = R_ABS(st.e.x) + R_ABS(st.e.y) + R_ABS(st.e.z);
  real sum = st.e.x + st.e.y + st.e.z;
  real e_sum = 3 * ee + REF(gamma_bound)(2) * se;
  if (!(R_ABS(sum) > REF(cert_factor)(sc) * e_sum)) {
    REF(cert_fail)();
    return;
  }
  real t = REF(triangle_t)(&st, sum);
  real e_t = REF(cert_triangle_t_error)(&st, t, sum, e_sum, ee, dz, se);
  bool ahead = t > 0 && !(ref_spawned_ray && t <= REF(triangle_t_error)(&st, sum));
  if (rmin(rmin(R_ABS(st.e.x), R_ABS(st.e.y)), R_ABS(st.e.z)) > k) {
    ref_cert_bary_err = 4 * ee / R_ABS(sum);
    REF(cert_root)(sc, t, e_t, t_max, ahead);
    return;
  }
  if (!ahead && ref_cert_self) return;
  real det = REF(enclosing_det)(st.e);
  bool taken = det != 0 && ahead && t <= t_max;
  REF(cert_maybe)(sc, t - REF(cert_factor)(sc) * e_t, t + REF(cert_factor)(sc) * e_t, t_max, taken);
}

void REF(cert_plane)(const ref_scene *sc, const packed_quadric *q, rvec3 o, rvec3 d, real t_max) {
  rvec3 n = rvec3_from(q->axis_z);
  real nm = RV(length)(n);
  rvec3 oc = RV(sub)(o, rvec3_from(q->center));
  real fz = RV(dot)(n, oc);
  real vz = RV(dot)(n, d);
  real e_vz = nm * ref_cert_ed + REF(gamma_bound)(4) * nm;
  real e_fz = nm * ref_cert_eo + REF(gamma_bound)(4) * RV(dot)(RV(abs)(n), RV(add)(RV(abs)(o), RV(abs)(rvec3_from(q->center))));
  REF(cert_require)(sc, vz, e_vz);
  bool facing = ((q->flags & RC_QUADRIC_ONE_SIDED) == 0) || vz < 0;
  if (vz == 0 || !facing || R_ABS(fz) >= R_ABS(vz) * (real)RC_T_FAR) return;
  real t = -fz / vz;
  real e_t = (R_ABS(vz) > e_vz) ? (e_fz + R_ABS(t) * e_vz) / (R_ABS(vz) - e_vz) + REF(gamma_bound)(1) * R_ABS(t)
                                : (real)RC_T_FAR;
  REF(cert_root)(sc, t, e_t, t_max, t > 0);
}
