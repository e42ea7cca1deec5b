/* ref_certify.c: mirrors shaders/rc_certify.glsl (see the shader for the bounds and their
 * sources). The shader's globals are per thread here; those in the working precision are
 * per precision as well (ref_intersect.h names them). */
#include "ref/ref_shader.h"

#include "ref/ref_real.h"

_Thread_local bool ref_cert_ok = true, ref_cert_any, ref_cert_self, ref_cert_hit_ok, ref_cert_blocked_later,
    ref_cert_blocker_certain;
_Thread_local uint32_t ref_cert_spawn_object = 0xffffffffu, ref_cert_stage;
_Thread_local real ref_cert_eo, ref_cert_et, ref_cert_ed, ref_cert_t_err, ref_cert_bary_err, ref_cert_off_err, ref_cert_beyond = (real)RC_T_FAR,
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

void REF(cert_note)(uint32_t stage) {
  if (!ref_cert_ok && ref_cert_stage == 0) ref_cert_stage = stage;
}

void REF(cert_camera)(const ref_scene *sc, ref_vec2 raster) {
  const packed_camera *c = &sc->frame->camera;
  real us = (real)c->left + ((real)c->right - (real)c->left) * (real)raster.x / (real)c->width;
  real vs = (real)c->bottom + ((real)c->top - (real)c->bottom) * (real)raster.y / (real)c->height;
  real eus = REF(gamma_bound)(4) * (R_ABS((real)c->left) + R_ABS((real)c->right) + R_ABS(us));
  real evs = REF(gamma_bound)(4) * (R_ABS((real)c->bottom) + R_ABS((real)c->top) + R_ABS(vs));
  real mag = R_ABS((real)c->focal) + R_ABS(us) + R_ABS(vs);
  real err = REF(gamma_bound)(3) * mag + eus + evs;
  ref_cert_ok = true;
  ref_cert_stage = 0;
  ref_cert_spawn_object = 0xffffffffu;
  ref_cert_et = 0;
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

bool REF(cert_shadow_ignores)(const ref_scene *sc, real lo, real hi, real t_max) {
  real k = REF(cert_factor)(sc);
  return hi + k * ref_cert_et < 0 || lo - t_max > k * (ref_cert_t_max_err + ref_cert_et);
}

void REF(cert_maybe)(const ref_scene *sc, real lo, real hi, real t_max, bool taken) {
  if (taken) {
    REF(cert_fail)();
    return;
  }
  if (ref_cert_any) {
    if (!REF(cert_shadow_ignores)(sc, lo, hi, t_max)) REF(cert_fail)();
    return;
  }
  if (hi + REF(cert_factor)(sc) * ref_cert_et < 0) return;
  ref_cert_beyond = rmin(ref_cert_beyond, lo);
}

bool REF(cert_root_within)(const ref_scene *sc, real t, real e_down, real e_up, real t_max, bool ahead) {
  if (!ahead && ref_cert_self) return false;
  real k = REF(cert_factor)(sc);
  if (!(ahead ? t > k * (e_down + ref_cert_et) : -t > k * (e_up + ref_cert_et))) ref_cert_ok = false;
  if (!ahead) return false;
  bool within = t <= t_max;
  real e_max = ref_cert_t_max_err + ref_cert_et;
  if (ref_cert_any && !(within ? t_max - t > k * (e_up + e_max) : t - t_max > k * (e_down + e_max))) ref_cert_ok = false;
  if (!within) {
    ref_cert_beyond = rmin(ref_cert_beyond, t - k * e_down);
    return false;
  }
  ref_cert_t_err = rmax(e_down, e_up);
  return true;
}

bool REF(cert_root)(const ref_scene *sc, real t, real e, real t_max, bool ahead) {
  return REF(cert_root_within)(sc, t, e, e, t_max, ahead);
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


rvec3 REF(cert_face_normal)(packed_triangle tri, rvec3 *e_n) {
  rvec3 v0 = rvec3_from(tri.v0);
  rvec3 a = RV(sub)(rvec3_from(tri.v1), v0);
  rvec3 b = RV(sub)(rvec3_from(tri.v2), v0);
  *e_n = RV(scale)(RV(make)(R_ABS(a.y * b.z) + R_ABS(a.z * b.y), R_ABS(a.z * b.x) + R_ABS(a.x * b.z),
                            R_ABS(a.x * b.y) + R_ABS(a.y * b.x)),
                   REF(gamma_bound)(6));
  return RV(cross)(a, b);
}

real REF(cert_facing_error)(packed_triangle tri, rvec3 d) {
  rvec3 e_n;
  rvec3 n = REF(cert_face_normal)(tri, &e_n);
  rvec3 ad = RV(abs)(d);
  real n_norm = R_ABS(n.x) + R_ABS(n.y) + R_ABS(n.z) + e_n.x + e_n.y + e_n.z;
  return (ref_cert_ed) * n_norm + RV(dot)(ad, e_n) + REF(gamma_bound)(3) * RV(dot)(ad, RV(abs)(n));
}

real REF(cert_triangle_plane_gap)(packed_triangle tri, rvec3 ng, rvec3 p) {
  rvec3 e_n;
  rvec3 n = REF(cert_face_normal)(tri, &e_n);
  rvec3 w = RV(sub)(p, rvec3_from(tri.v0));
  real len = RV(length)(n);
  real rho = (e_n.x + e_n.y + e_n.z) / len;
  if (!(rho < (real)0.5)) return (real)RC_T_FAR;
  real gap = R_ABS(RV(dot)(ng, w)) + REF(gamma_bound)(16) * RV(dot)(RV(abs)(ng), RV(abs)(w)) + RV(dot)(e_n, RV(abs)(w)) / len;
  return gap * (1 + REF(gamma_bound)(8)) / (1 - rho);
}

uint32_t REF(cert_triangle_side)(const ref_scene *sc, packed_triangle tri, rvec3 d) {
  real f = REF(triangle_facing)(tri, d);
  if (!(R_ABS(f) > REF(cert_factor)(sc) * REF(cert_facing_error)(tri, d))) return RC_SIDE_UNSURE;
  return (f < 0) ? RC_SIDE_FRONT : RC_SIDE_BACK;
}

static real REF(cert_edge_bound)(const ref_shear *sh, real xm, real ym, real zr) {
  real inv = R_ABS(sh->s.z);
  real sx = R_ABS(sh->s.x);
  real sy = R_ABS(sh->s.y);
  real dx = (ref_cert_eo) * (1 + sx) + (ref_cert_ed) * (1 + sx) * inv * zr + REF(gamma_bound)(5) * (xm + 2 * sx * zr);
  real dy = (ref_cert_eo) * (1 + sy) + (ref_cert_ed) * (1 + sy) * inv * zr + REF(gamma_bound)(5) * (ym + 2 * sy * zr);
  return 2 * (dx * ym + xm * dy + dx * dy) + REF(gamma_bound)(2) * 2 * xm * ym;
}

rvec3 REF(cert_edge_bounds)(const ref_shear *sh, rvec3 xm, rvec3 ym, rvec3 zr) {
  return RV(make)(REF(cert_edge_bound)(sh, xm.x, ym.x, zr.x), REF(cert_edge_bound)(sh, xm.y, ym.y, zr.y),
                  REF(cert_edge_bound)(sh, xm.z, ym.z, zr.z));
}

rvec3 REF(cert_edge_errors)(const ref_sheared *st, const ref_shear *sh, real *dz) {
  real inv = R_ABS(sh->s.z);
  rvec3 ax = RV(abs)(st->x);
  rvec3 ay = RV(abs)(st->y);
  rvec3 az = RV(abs)(st->depth);
  real zr = REF(max3_abs)(st->depth);
  *dz = inv * (ref_cert_eo + RC_UNIT_ROUNDOFF * zr) + (ref_cert_ed) * inv * inv * zr;
  /* Edge u joins vertices 1 and 2, v 2 and 0, w 0 and 1 (GLSL's max(a.yzx, a.zxy)). */
  return REF(cert_edge_bounds)(sh, RV(make)(rmax(ax.y, ax.z), rmax(ax.z, ax.x), rmax(ax.x, ax.y)),
                               RV(make)(rmax(ay.y, ay.z), rmax(ay.z, ay.x), rmax(ay.x, ay.y)),
                               RV(make)(rmax(az.y, az.z), rmax(az.z, az.x), rmax(az.x, az.y)));
}

bool REF(cert_edges_apart)(const ref_sheared *st, rvec3 k) {
  bool pos = st->e.x > k.x || st->e.y > k.y || st->e.z > k.z;
  bool neg = st->e.x < -k.x || st->e.y < -k.y || st->e.z < -k.z;
  return pos && neg;
}

uint32_t REF(cert_near_edge)(rvec3 e, real sum, rvec3 k) {
  bool nx = R_ABS(e.x) <= k.x;
  bool ny = R_ABS(e.y) <= k.y;
  bool nz = R_ABS(e.z) <= k.z;
  uint32_t edge = nx ? 0 : (ny ? 1 : 2);
  uint32_t near = (nx ? 1 : 0) + (ny ? 1 : 0) + (nz ? 1 : 0);
  return (near == 1) ? ((edge << 1) | (sum < 0 ? 1u : 0u)) : RC_CERT_NO_EDGE;
}

static vec3 REF(load_triangle_vertex)(const ref_scene *sc, uint32_t i, uint32_t k) {
  return k == 0 ? sc->triangles[i].v0 : (k == 1 ? sc->triangles[i].v1 : sc->triangles[i].v2);
}

static bool REF(same_point)(vec3 a, vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

bool REF(cert_edge_pair)(const ref_scene *sc, uint32_t a, uint32_t b) {
  uint32_t ta = a >> RC_CERT_EDGE_SHIFT, tb = b >> RC_CERT_EDGE_SHIFT;
  uint32_t ea = (a >> 1) & 3u, eb = (b >> 1) & 3u;
  vec3 pa = REF(load_triangle_vertex)(sc, ta, (ea + 1) % 3);
  vec3 qa = REF(load_triangle_vertex)(sc, ta, (ea + 2) % 3);
  vec3 pb = REF(load_triangle_vertex)(sc, tb, (eb + 1) % 3);
  vec3 qb = REF(load_triangle_vertex)(sc, tb, (eb + 2) % 3);
  bool reversed = REF(same_point)(pa, qb) && REF(same_point)(qa, pb);
  bool same = REF(same_point)(pa, pb) && REF(same_point)(qa, qb);
  bool neg_a = (a & 1u) != 0, neg_b = (b & 1u) != 0;
  return ta != tb && (reversed ? neg_a == neg_b : (same && neg_a != neg_b));
}

void REF(cert_triangle)(const ref_scene *sc, rvec3 o, const ref_shear *sh, packed_triangle tri, real t_max,
                        bool side_unsure) {
  if (sc->frame->triangle_formula != RC_TRIANGLE_WATERTIGHT) {
    REF(cert_fail)();
    return;
  }
  ref_sheared st = REF(shear_triangle)(o, sh, tri);
  real dz;
  rvec3 ee = REF(cert_edge_errors)(&st, sh, &dz);
  rvec3 k = RV(scale)(ee, REF(cert_factor)(sc));
  if (REF(cert_edges_apart)(&st, k)) return;
  if (side_unsure) {
    REF(cert_fail)();
    return;
  }
  real se = R_ABS(st.e.x) + R_ABS(st.e.y) + R_ABS(st.e.z);
  real sum = st.e.x + st.e.y + st.e.z;
  real e_sum = ee.x + ee.y + ee.z + REF(gamma_bound)(2) * se;
  if (!(R_ABS(sum) > REF(cert_factor)(sc) * e_sum)) {
    REF(cert_fail)();
    return;
  }
  real e_max = REF(max3_abs)(ee);
  real t = REF(triangle_t)(&st, sum);
  real e_t = REF(cert_triangle_t_error)(&st, t, sum, e_sum, e_max, dz, se);
  bool ahead = t > 0 && !(ref_spawned_ray && t <= REF(triangle_t_error)(&st, sum));
  if (R_ABS(st.e.x) > k.x && R_ABS(st.e.y) > k.y && R_ABS(st.e.z) > k.z) {
    ref_cert_bary_err = 4 * e_max / R_ABS(sum);
    REF(cert_root)(sc, t, e_t, t_max, ahead);
    return;
  }
  if (!ahead && ref_cert_self) return;
  real det = REF(enclosing_det)(st.e);
  bool taken = det != 0 && ahead && t <= t_max;
  REF(cert_maybe)(sc, t - REF(cert_factor)(sc) * e_t, t + REF(cert_factor)(sc) * e_t, t_max, taken);
}

uint32_t REF(cert_crossing)(const ref_scene *sc, rvec3 o, const ref_shear *sh, packed_triangle tri, real *t, real *e,
                            uint32_t *near) {
  *t = (real)RC_T_FAR;
  *e = 0;
  *near = RC_CERT_NO_EDGE;
  ref_sheared st = REF(shear_triangle)(o, sh, tri);
  real dz;
  rvec3 ee = REF(cert_edge_errors)(&st, sh, &dz);
  rvec3 k = RV(scale)(ee, REF(cert_factor)(sc));
  if (REF(cert_edges_apart)(&st, k)) return 0;
  real se = R_ABS(st.e.x) + R_ABS(st.e.y) + R_ABS(st.e.z);
  real sum = st.e.x + st.e.y + st.e.z;
  real e_sum = ee.x + ee.y + ee.z + REF(gamma_bound)(2) * se;
  if (!(R_ABS(sum) > REF(cert_factor)(sc) * e_sum)) return 3;
  *t = REF(triangle_t)(&st, sum);
  *e = REF(cert_triangle_t_error)(&st, *t, sum, e_sum, REF(max3_abs)(ee), dz, se);
  if (ref_spawned_ray && R_ABS(*t) <= REF(triangle_t_error)(&st, sum)) {
    *e += R_ABS(*t);
    *t = 0;
  }
  *near = REF(cert_near_edge)(st.e, sum, k);
  return (R_ABS(st.e.x) > k.x && R_ABS(st.e.y) > k.y && R_ABS(st.e.z) > k.z) ? 1 : 2;
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
  real near = rmax(R_ABS(fz) - e_fz, 0) / (R_ABS(vz) + e_vz);
  real far = (R_ABS(vz) > e_vz) ? (R_ABS(fz) + e_fz) / (R_ABS(vz) - e_vz) : (real)RC_T_FAR;
  real rounding = REF(gamma_bound)(1) * R_ABS(t);
  real e_down = ((t > 0) ? R_ABS(t) - near : far - R_ABS(t)) + rounding;
  real e_up = ((t > 0) ? far - R_ABS(t) : R_ABS(t) - near) + rounding;
  REF(cert_root_within)(sc, t, e_down, e_up, t_max, t > 0);
}

rvec3 REF(cert_abs_apply)(const packed_quadric *q, rvec3 v) {
  rvec3 D = RV(abs)(rvec3_from(q->diag));
  rvec3 O = RV(abs)(rvec3_from(q->off));
  return RV(make)(D.x * v.x + O.x * v.y + O.y * v.z, O.x * v.x + D.y * v.y + O.z * v.z, O.y * v.x + O.z * v.y + D.z * v.z);
}

rvec3 REF(cert_local_error)(const packed_quadric *q, rvec3 mag, real e, real n) {
  rvec3 ax = rvec3_from(q->axis_x);
  rvec3 ay = rvec3_from(q->axis_y);
  rvec3 az = rvec3_from(q->axis_z);
  return RV(add)(RV(scale)(RV(make)(RV(length)(ax), RV(length)(ay), RV(length)(az)), e),
                 RV(scale)(RV(make)(RV(dot)(RV(abs)(ax), mag), RV(dot)(RV(abs)(ay), mag), RV(dot)(RV(abs)(az), mag)),
                           REF(gamma_bound)(n)));
}

bool REF(cert_slab)(const ref_scene *sc, real lo, real hi, real f, real v, real ef, real ev, real *tn, real *tx, real *e) {
  *tn = -(real)RC_T_FAR;
  *tx = (real)RC_T_FAR;
  *e = 0;
  if (!(R_ABS(v) > REF(cert_factor)(sc) * ev)) return false;
  real ta = (lo - f) / v;
  real tb = (hi - f) / v;
  real ea = (R_ABS(v) > ev) ? (ef + REF(gamma_bound)(1) * R_ABS(lo - f) + R_ABS(ta) * ev) / (R_ABS(v) - ev) +
                                  REF(gamma_bound)(1) * R_ABS(ta)
                            : (real)RC_T_FAR;
  real eb = (R_ABS(v) > ev) ? (ef + REF(gamma_bound)(1) * R_ABS(hi - f) + R_ABS(tb) * ev) / (R_ABS(v) - ev) +
                                  REF(gamma_bound)(1) * R_ABS(tb)
                            : (real)RC_T_FAR;
  *tn = rmin(ta, tb);
  *tx = rmax(ta, tb);
  *e = rmax(ea, eb);
  return true;
}

real REF(cert_span_end)(const ref_scene *sc, real s, real t0, real e0, real t1, real e1, real t2, real e2, real *e,
                        bool *sure) {
  real k = REF(cert_factor)(sc);
  real w = t0;
  *e = e0;
  if (s * t1 > s * w) {
    w = t1;
    *e = e1;
  }
  if (s * t2 > s * w) {
    w = t2;
    *e = e2;
  }
  uint32_t lose = 0;
  if (t0 == w || s * (w - t0) > k * (*e + e0)) lose++;
  if (t1 == w || s * (w - t1) > k * (*e + e1)) lose++;
  if (t2 == w || s * (w - t2) > k * (*e + e2)) lose++;
  uint32_t wins = ((t0 == w) ? 1u : 0u) + ((t1 == w) ? 1u : 0u) + ((t2 == w) ? 1u : 0u);
  *sure = lose == 3u && wins == 1u;
  if (!*sure) *e = rmax(e0, rmax(e1, e2));
  return w;
}

uint32_t REF(cert_slab_parallel)(const ref_scene *sc, real lo, real hi, real f, real v, real ef, real ev, real reach_t) {
  if (R_ABS(v) > REF(cert_factor)(sc) * ev) return 1;
  real reach = REF(cert_factor)(sc) * (ef + reach_t * (R_ABS(v) + ev));
  if (f - lo > reach && hi - f > reach) return 1;
  if (lo - f > reach || f - hi > reach) return 0;
  return 2;
}

uint32_t REF(cert_box)(const ref_scene *sc, rvec3 lo, rvec3 hi, rvec3 f, rvec3 v, rvec3 ef, rvec3 ev, real *b_in,
                       real *b_out, real *e_in, real *e_out, uint32_t *sure) {
  real nx, xx, ex, ny, xy, ey, nz, xz, ez;
  REF(cert_slab)(sc, lo.x, hi.x, f.x, v.x, ef.x, ev.x, &nx, &xx, &ex);
  REF(cert_slab)(sc, lo.y, hi.y, f.y, v.y, ef.y, ev.y, &ny, &xy, &ey);
  REF(cert_slab)(sc, lo.z, hi.z, f.z, v.z, ef.z, ev.z, &nz, &xz, &ez);
  bool sure_in, sure_out;
  *b_in = REF(cert_span_end)(sc, 1, nx, ex, ny, ey, nz, ez, e_in, &sure_in);
  *b_out = REF(cert_span_end)(sc, -1, xx, ex, xy, ey, xz, ez, e_out, &sure_out);
  real e_span = rmax(*e_in, *e_out);
  *sure = (sure_in ? 1u : 0u) | (sure_out ? 2u : 0u);
  real k = REF(cert_factor)(sc);
  real reach_t = rmax(R_ABS(*b_in), R_ABS(*b_out)) + k * e_span;
  uint32_t px = REF(cert_slab_parallel)(sc, lo.x, hi.x, f.x, v.x, ef.x, ev.x, reach_t);
  uint32_t py = REF(cert_slab_parallel)(sc, lo.y, hi.y, f.y, v.y, ef.y, ev.y, reach_t);
  uint32_t pz = REF(cert_slab_parallel)(sc, lo.z, hi.z, f.z, v.z, ef.z, ev.z, reach_t);
  if (px == 0 || py == 0 || pz == 0) return 0;
  if (*b_in - *b_out > k * 2 * e_span) return 0;
  if (px == 2 || py == 2 || pz == 2 || !(*b_out - *b_in > k * 2 * e_span)) return 2;
  return 1;
}

real REF(cert_quadric_terms)(const packed_quadric *q, rvec3 f, rvec3 v, rvec3 ef, rvec3 ev, real *a, real *h, real *c,
                             real *disc, real *e_a, real *e_h, real *e_c) {
  rvec3 D = rvec3_from(q->diag);
  rvec3 L = rvec3_from(q->linear);
  real J = (real)q->constant;
  ref_quadric_terms k = REF(quadric_coefficients)(q, f, v);
  *a = k.a;
  *h = k.h;
  *c = k.c;
  *disc = REF(quadric_discriminant)(q, f, v, &k);
  rvec3 av = RV(abs)(v);
  rvec3 af = RV(abs)(f);
  rvec3 al = RV(abs)(L);
  rvec3 mav = REF(cert_abs_apply)(q, av);
  rvec3 maf = REF(cert_abs_apply)(q, af);
  real ra = REF(gamma_bound)(6) * RV(dot)(av, mav);
  real rm = REF(gamma_bound)(6) * RV(dot)(af, mav);
  real rld = REF(gamma_bound)(3) * RV(dot)(al, av);
  real rlf = REF(gamma_bound)(3) * RV(dot)(al, af);
  real rh = rm + rld + REF(gamma_bound)(1) * R_ABS(k.h);
  real rc = REF(gamma_bound)(8) * (RV(dot)(af, maf) + 2 * RV(dot)(al, af) + R_ABS(J));
  rvec3 gv = RV(add)(RV(abs)(k.mv), RV(scale)(mav, REF(gamma_bound)(3)));
  rvec3 mfl = RV(add)(k.mf, L);
  rvec3 gf = RV(add)(RV(abs)(mfl), RV(scale)(RV(add)(maf, al), REF(gamma_bound)(4)));
  real pa = 2 * RV(dot)(gv, ev) + RV(dot)(ev, REF(cert_abs_apply)(q, ev));
  real ph = RV(dot)(gv, ef) + RV(dot)(gf, ev) + RV(dot)(ef, REF(cert_abs_apply)(q, ev));
  real pc = 2 * RV(dot)(gf, ef) + RV(dot)(ef, REF(cert_abs_apply)(q, ef));
  *e_a = ra + pa;
  *e_h = rh + ph;
  *e_c = rc + pc;
  real hm = R_ABS(k.h) + rh;
  real am = R_ABS(k.a) + ra;
  real cm = R_ABS(k.c) + rc;
  rvec3 grad_f = RV(add)(RV(add)(RV(abs)(RV(scale)(RV(sub)(RV(scale)(k.mv, k.h), RV(scale)(mfl, k.a)), 2)),
                                 RV(scale)(RV(add)(RV(scale)(gv, rh), RV(scale)(gf, ra)), 2)),
                         RV(scale)(RV(add)(RV(scale)(gv, R_ABS(k.h)), RV(scale)(gf, R_ABS(k.a))), REF(gamma_bound)(8) * 2));
  rvec3 grad_v = RV(add)(RV(add)(RV(abs)(RV(scale)(RV(sub)(RV(scale)(mfl, k.h), RV(scale)(k.mv, k.c)), 2)),
                                 RV(scale)(RV(add)(RV(scale)(gf, rh), RV(scale)(gv, rc)), 2)),
                         RV(scale)(RV(add)(RV(scale)(gf, R_ABS(k.h)), RV(scale)(gv, R_ABS(k.c))), REF(gamma_bound)(8) * 2));
  real moved = RV(dot)(grad_f, ef) + RV(dot)(grad_v, ev) + 2 * hm * RV(dot)(ef, REF(cert_abs_apply)(q, ev)) + ph * ph +
               am * RV(dot)(ef, REF(cert_abs_apply)(q, ef)) + cm * RV(dot)(ev, REF(cert_abs_apply)(q, ev)) + pa * pc;
  real rounded;
  if (rcm_eq_f(q->off, rcm_make_f(0, 0, 0))) {
    rvec3 w = REF(quadric_minors)(f, v);
    real exy = REF(gamma_bound)(2) * (R_ABS(v.x * f.y) + R_ABS(v.y * f.x));
    real exz = REF(gamma_bound)(2) * (R_ABS(v.x * f.z) + R_ABS(v.z * f.x));
    real eyz = REF(gamma_bound)(2) * (R_ABS(v.y * f.z) + R_ABS(v.z * f.y));
    real dxy = R_ABS(D.x * D.y);
    real dxz = R_ABS(D.x * D.z);
    real dyz = R_ABS(D.y * D.z);
    real terms = dxy * w.x * w.x + dxz * w.y * w.y + dyz * w.z * w.z + 2 * R_ABS(k.m * k.ld) + 2 * R_ABS(k.a * k.lf) + k.ld * k.ld +
                 R_ABS(k.a * J);
    rounded = dxy * (2 * R_ABS(w.x) * exy + exy * exy) + dxz * (2 * R_ABS(w.y) * exz + exz * exz) +
              dyz * (2 * R_ABS(w.z) * eyz + eyz * eyz) + 2 * (R_ABS(k.m) * rld + R_ABS(k.ld) * rm + rm * rld) +
              2 * (R_ABS(k.a) * rlf + R_ABS(k.lf) * ra + ra * rlf) + 2 * R_ABS(k.ld) * rld + rld * rld + R_ABS(J) * ra +
              REF(gamma_bound)(12) * terms;
  } else {
    rounded = 2 * R_ABS(k.h) * rh + rh * rh + R_ABS(k.a) * rc + R_ABS(k.c) * ra + ra * rc +
              REF(gamma_bound)(2) * (k.h * k.h + R_ABS(k.a * k.c));
  }
  return moved + rounded;
}

bool REF(cert_surface_root)(const ref_scene *sc, real t, real e, real b_in, real b_out, real e_in, real e_out,
                            real t_max) {
  real k = REF(cert_factor)(sc);
  real m_in = t - b_in;
  real m_out = b_out - t;
  if (m_in < -k * (e + e_in) || m_out < -k * (e + e_out)) return false;
  if (m_in > k * (e + e_in) && m_out > k * (e + e_out)) return REF(cert_root)(sc, t, e, t_max, t > 0);
  bool taken = t > 0 && t <= t_max && m_in >= 0 && m_out >= 0;
  REF(cert_maybe)(sc, t - k * e, t + k * e, t_max, taken);
  return taken;
}

bool REF(cert_solid_end)(const ref_scene *sc, real t, bool on_box, real box, real e_box, real quad, real e_quad,
                         bool face_sure, real t_max) {
  bool side_sure = !(R_ABS(quad) < (real)RC_T_FAR) || R_ABS(box - quad) > REF(cert_factor)(sc) * (e_box + e_quad);
  real e = side_sure ? (on_box ? e_box : e_quad) : rmax(e_box, e_quad);
  if (!REF(cert_root)(sc, t, e, t_max, t > 0)) return false;
  if (!side_sure || (on_box && !face_sure)) REF(cert_fail)();
  return true;
}

void REF(cert_solid)(const ref_scene *sc, uint32_t kind, real t_lo, real t_hi, real e_r, real b_in, real b_out,
                     real e_in, real e_out, uint32_t sure, real t_max) {
  real k = REF(cert_factor)(sc);
  real lo0 = (kind == RC_QR_BETWEEN) ? t_lo : -(real)RC_T_FAR;
  real hi0 = (kind == RC_QR_OUTSIDE) ? t_lo : ((kind == RC_QR_BETWEEN) ? t_hi : (real)RC_T_FAR);
  uint32_t pieces = (kind == RC_QR_OUTSIDE) ? 2 : 1;
  for (uint32_t p = 0; p < pieces; p++) {
    real lo = (p == 0) ? lo0 : t_hi;
    real hi = (p == 0) ? hi0 : (real)RC_T_FAR;
    real e_lo = (R_ABS(lo) < (real)RC_T_FAR) ? e_r : 0;
    real e_hi = (R_ABS(hi) < (real)RC_T_FAR) ? e_r : 0;
    bool box_starts = b_in >= lo;
    bool box_ends = b_out <= hi;
    real s = box_starts ? b_in : lo;
    real e = box_ends ? b_out : hi;
    real e_s = rmax(e_in, e_lo);
    real e_e = rmax(e_out, e_hi);
    if (s - e > k * (e_s + e_e)) continue;
    if (!(e - s > k * (e_s + e_e))) {
      bool taken = s <= e && ((s > 0 && s <= t_max) || (e > 0 && e <= t_max));
      REF(cert_maybe)(sc, rmin(s, e) - k * rmax(e_s, e_e), rmax(s, e) + k * rmax(e_s, e_e), t_max, taken);
      if (taken) return;
      continue;
    }
    if (REF(cert_solid_end)(sc, s, box_starts, b_in, e_in, lo, e_lo, (sure & 1u) != 0, t_max)) return;
    if (REF(cert_solid_end)(sc, e, box_ends, b_out, e_out, hi, e_hi, (sure & 2u) != 0, t_max)) return;
  }
}

bool REF(cert_quadric_kind)(const ref_scene *sc, const packed_quadric *q, rvec3 f, rvec3 v, rvec3 ef, rvec3 ev,
                            real b_in, real b_out, real e_in, real e_out, real t_max, bool whole, uint32_t *kind,
                            real *t_lo, real *t_hi, real *e_r) {
  real k = REF(cert_factor)(sc);
  *kind = RC_QR_NONE;
  *t_lo = 0;
  *t_hi = 0;
  *e_r = 0;
  real a, h, c, disc, e_a, e_h, e_c;
  real e_disc = REF(cert_quadric_terms)(q, f, v, ef, ev, &a, &h, &c, &disc, &e_a, &e_h, &e_c);
  if (a == 0 && e_a == 0 && h == 0 && e_h == 0) {
    REF(cert_require)(sc, c, e_c);
    *kind = (c <= 0) ? RC_QR_ALL : RC_QR_NONE;
    return true;
  }
  if (!(R_ABS(a) > k * e_a)) {
    REF(cert_fail)();
    return false;
  }
  if (!whole && a > 0 && h > k * e_h && (c > k * e_c || (ref_cert_self && c > 0))) {
    return false;
  }
  if (!(R_ABS(disc) > k * e_disc)) {
    if (a < 0 || whole) {
      REF(cert_fail)();
      return false;
    }
    real spread = R_SQRT(rmax(disc, 0) + k * e_disc) + k * e_h;
    real a_lo = a - k * e_a;
    real a_hi = a + k * e_a;
    real lo = rmin((-h - spread) / a_lo, (-h - spread) / a_hi);
    real hi = rmax((-h + spread) / a_lo, (-h + spread) / a_hi);
    lo = rmax(lo - REF(gamma_bound)(3) * R_ABS(lo), b_in - k * e_in);
    hi = rmin(hi + REF(gamma_bound)(3) * R_ABS(hi), b_out + k * e_out);
    if (lo <= hi) REF(cert_maybe)(sc, lo, hi, t_max, disc >= 0 && hi > 0 && lo <= t_max);
    return false;
  }
  if (disc < 0) {
    *kind = (a > 0) ? RC_QR_NONE : RC_QR_ALL;
    return true;
  }
  real sq = R_SQRT(disc);
  real qq = (h >= 0) ? -(h + sq) : -(h - sq);
  if (qq == 0 || R_ABS(qq) >= R_ABS(a) * (real)RC_T_FAR || R_ABS(c) >= R_ABS(qq) * (real)RC_T_FAR) {
    REF(cert_fail)();
    return false;
  }
  real r0 = qq / a;
  real r1 = c / qq;
  real e_sq = e_disc / (sq + R_SQRT(rmax(disc - e_disc, 0))) + REF(gamma_bound)(2) * sq;
  real e_q = e_h + e_sq + REF(gamma_bound)(2) * R_ABS(qq);
  real e_r0 = (R_ABS(a) > e_a) ? (e_q + R_ABS(r0) * e_a) / (R_ABS(a) - e_a) + REF(gamma_bound)(1) * R_ABS(r0)
                               : (real)RC_T_FAR;
  real e_r1 = (R_ABS(qq) > e_q) ? (e_c + R_ABS(r1) * e_q) / (R_ABS(qq) - e_q) + REF(gamma_bound)(1) * R_ABS(r1)
                                : (real)RC_T_FAR;
  *e_r = rmax(e_r0, e_r1);
  *t_lo = rmin(r0, r1);
  *t_hi = rmax(r0, r1);
  *kind = (a > 0) ? RC_QR_BETWEEN : RC_QR_OUTSIDE;
  return true;
}

uint32_t REF(cert_quadric_box)(const ref_scene *sc, const packed_quadric *q, rvec3 o, rvec3 d, rvec3 *f, rvec3 *v,
                               rvec3 *ef, rvec3 *ev, real *b_in, real *b_out, real *e_in, real *e_out, uint32_t *sure) {
  *f = REF(quadric_local)(q, RV(sub)(o, rvec3_from(q->center)));
  *v = REF(quadric_local)(q, d);
  *ef = REF(cert_local_error)(q, RV(add)(RV(abs)(o), RV(abs)(rvec3_from(q->center))), ref_cert_eo, 4);
  *ev = REF(cert_local_error)(q, RV(abs)(d), ref_cert_ed, 3);
  return REF(cert_box)(sc, rvec3_from(q->lo), rvec3_from(q->hi), *f, *v, *ef, *ev, b_in, b_out, e_in, e_out, sure);
}

void REF(cert_quadric)(const ref_scene *sc, const packed_quadric *q, rvec3 o, rvec3 d, real t_max) {
  rvec3 f, v, ef, ev;
  real b_in, b_out, e_in, e_out;
  uint32_t sure;
  uint32_t box = REF(cert_quadric_box)(sc, q, o, d, &f, &v, &ef, &ev, &b_in, &b_out, &e_in, &e_out, &sure);
  if (box == 0) return;
  if (box == 2) {
    REF(cert_fail)();
    return;
  }
  uint32_t kind;
  real t_lo, t_hi, e_r;
  if (!REF(cert_quadric_kind)(sc, q, f, v, ef, ev, b_in, b_out, e_in, e_out, t_max, false, &kind, &t_lo, &t_hi, &e_r))
    return;
  if (kind == RC_QR_NONE) return;
  if ((q->flags & RC_QUADRIC_SOLID) != 0) {
    REF(cert_solid)(sc, kind, t_lo, t_hi, e_r, b_in, b_out, e_in, e_out, sure, t_max);
    return;
  }
  if (kind == RC_QR_ALL) return;
  if (REF(cert_surface_root)(sc, t_lo, e_r, b_in, b_out, e_in, e_out, t_max)) return;
  REF(cert_surface_root)(sc, t_hi, e_r, b_in, b_out, e_in, e_out, t_max);
}

real REF(cert_quadric_normal)(const packed_quadric *q, rvec3 p, real ep) {
  rvec3 ax = rvec3_from(q->axis_x);
  rvec3 ay = rvec3_from(q->axis_y);
  rvec3 az = rvec3_from(q->axis_z);
  rvec3 L = rvec3_from(q->linear);
  real gx = R_ABS(RV(dot)(ax, ax)) + R_ABS(RV(dot)(ax, ay)) + R_ABS(RV(dot)(ax, az));
  real gy = R_ABS(RV(dot)(ay, ax)) + R_ABS(RV(dot)(ay, ay)) + R_ABS(RV(dot)(ay, az));
  real gz = R_ABS(RV(dot)(az, ax)) + R_ABS(RV(dot)(az, ay)) + R_ABS(RV(dot)(az, az));
  real rn = R_SQRT(rmax(gx, rmax(gy, gz))) * (1 + REF(gamma_bound)(4));
  rvec3 rows = REF(cert_abs_apply)(q, RV(make)(1, 1, 1));
  real mn = rmax(rows.x, rmax(rows.y, rows.z)) * (1 + REF(gamma_bound)(2));
  rvec3 f = REF(quadric_local)(q, RV(sub)(p, rvec3_from(q->center)));
  rvec3 g = RV(add)(REF(quadric_apply)(q, f), L);
  rvec3 n = RV(add)(RV(add)(RV(scale)(ax, g.x), RV(scale)(ay, g.y)), RV(scale)(az, g.z));
  rvec3 ef = REF(cert_local_error)(q, RV(add)(RV(abs)(p), RV(abs)(rvec3_from(q->center))), 0, 4);
  real eg = mn * (rn * ep + RV(length)(ef)) +
            REF(gamma_bound)(4) * RV(length)(RV(add)(REF(cert_abs_apply)(q, RV(abs)(f)), RV(abs)(L)));
  real e_n = rn * eg + REF(gamma_bound)(3) * RV(length)(RV(add)(RV(add)(RV(scale)(RV(abs)(ax), R_ABS(g.x)),
                                                                         RV(scale)(RV(abs)(ay), R_ABS(g.y))),
                                                                 RV(scale)(RV(abs)(az), R_ABS(g.z))));
  return REF(cert_turn_of)(e_n, RV(length)(n));
}
