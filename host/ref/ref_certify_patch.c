/* ref_certify_patch.c: mirrors shaders/rc_certify_patch.glsl function by function (the shader
 * has the reasoning: Kantorovich's theorem for the reference's Newton run, a separating line
 * for a certain miss). GLSL's vector arithmetic on rows of the net is written out per
 * component here. */
#include "ref/ref_shader.h"

#include "ref/ref_real.h"
#include "ref/ref_patch.h"

/* rc_certify_patch.glsl's struct patch_bounds. */
typedef struct {
  real su, sv;
  real suu, suv, svv;
  real weight;
} patch_bounds;

patch_bounds REF(cert_patch_bounds)(const packed_quadric *q, real scale, real lo_u, real hi_u, real lo_v, real hi_v) {
  real ku = 1 + 2 * rmax(0, rmax(-lo_u, hi_u - 1));
  real kv = 1 + 2 * rmax(0, rmax(-lo_v, hi_v - 1));
  real turn = 1 + REF(gamma_bound)(16);
  real e = 12 * REF(gamma_bound)(4) * scale;
  real grow = 1 + REF(gamma_bound)(16);
  patch_bounds pb;
  pb.su = 3 * ku * ku * kv * kv * kv * ((real)q->linear.x * turn + e) * grow;
  pb.sv = 3 * ku * ku * ku * kv * kv * ((real)q->linear.y * turn + e) * grow;
  pb.suu = 6 * ku * kv * kv * kv * ((real)q->diag.z * turn + e) * grow;
  pb.svv = 6 * ku * ku * ku * kv * ((real)q->off.z * turn + e) * grow;
  pb.suv = 9 * ku * ku * kv * kv * ((real)q->linear.z * turn + e) * grow;
  pb.weight = ku * ku * ku * kv * kv * kv * grow;
  return pb;
}

real REF(bernstein_mass)(real u, real x) {
  real s = R_ABS(1 - u) + R_ABS(u) + 2 * x;
  return s * s * s * (1 + REF(gamma_bound)(4));
}

real REF(net_rounding)(patch_net n, real lateral) {
  return (real)1.5 * (REF(gamma_bound)(5) * (real)1.7320508075688772 * n.scale + REF(gamma_bound)(17) * lateral);
}

static real max4_abs(rvec4 a) { return rmax(rmax(R_ABS(a.x), R_ABS(a.y)), rmax(R_ABS(a.z), R_ABS(a.w))); }

real REF(net_lateral)(patch_net n) {
  return rmax(rmax(rmax(max4_abs(n.a0), max4_abs(n.a1)), rmax(max4_abs(n.a2), max4_abs(n.a3))),
              rmax(rmax(max4_abs(n.b0), max4_abs(n.b1)), rmax(max4_abs(n.b2), max4_abs(n.b3))));
}

real REF(inverse_norm)(real jf, real det) {
  real f2 = jf * jf;
  if (!(R_ABS(det) > f2 * REF(gamma_bound)(8))) return 0;
  real root = R_SQRT(rmax(f2 * f2 - 4 * det * det, 0));
  return R_SQRT((f2 + root) / (2 * det * det)) * (1 + REF(gamma_bound)(16));
}

real REF(patch_settles)(real e, real beta, real lip, real jx, real e64, real pos64, uint32_t m) {
  for (uint32_t j = 0; j < m && j < 6u; j++) {
    ref_work++;
    e = beta * lip * e * e / (2 * (1 - beta * lip * e)) + e64 * (1 + 16 * e) + pos64 +
        64 * (real)1.1102230246251565e-16 * beta * jx * e;
  }
  return (jx + (real)0.5 * lip * e) * e;
}

rvec4 REF(bernstein_curve)(real t) {
  real s = 1 - t;
  return (rvec4){6 * s, 6 * (t - 2 * s), 6 * (s - 2 * t), 6 * t};
}

real REF(net_curvature)(patch_net n, const patch_run *r, rvec4 fa, rvec4 fb) {
  rvec4 cu = REF(bernstein_curve)(r->u);
  rvec4 cv = REF(bernstein_curve)(r->v);
  real auu = REF(weigh)(r->bv, (rvec4){REF(weigh)(cu, n.a0), REF(weigh)(cu, n.a1), REF(weigh)(cu, n.a2), REF(weigh)(cu, n.a3)});
  real avv = REF(weigh)(cv, (rvec4){REF(weigh)(r->bu, n.a0), REF(weigh)(r->bu, n.a1), REF(weigh)(r->bu, n.a2), REF(weigh)(r->bu, n.a3)});
  real buu = REF(weigh)(r->bv, (rvec4){REF(weigh)(cu, n.b0), REF(weigh)(cu, n.b1), REF(weigh)(cu, n.b2), REF(weigh)(cu, n.b3)});
  real bvv = REF(weigh)(cv, (rvec4){REF(weigh)(r->bu, n.b0), REF(weigh)(r->bu, n.b1), REF(weigh)(r->bu, n.b2), REF(weigh)(r->bu, n.b3)});
  return R_SQRT(auu * auu + avv * avv + buu * buu + bvv * bvv + 2 * (fa.w * fa.w + fb.w * fb.w));
}

real REF(local_lipschitz)(const ref_scene *sc, real curv, real e_curv, real third, real rad, real lip) {
  return rmin(lip, REF(cert_factor)(sc) * (curv + e_curv + third * rad) * (1 + REF(gamma_bound)(8)));
}

real REF(grown_room)(patch_domain m, const patch_run *r) {
  real wu = m.u1 - m.u0;
  real wv = m.v1 - m.v0;
  return rmin(rmin(r->u - (m.u0 - wu), m.u1 + wu - r->u), rmin(r->v - (m.v0 - wv), m.v1 + wv - r->v));
}

/* rc_certify_patch.glsl's struct patch_anchor. */
typedef struct {
  bool set, last;
  uint32_t steps;
  real delta, g, u, v;
} patch_anchor;

bool REF(patch_anchor_end)(const ref_scene *sc, patch_anchor a, real u, real v, real beta_f, real f, real e_f, real jf,
                           real e_j, real curv, real e_curv, real third, real lip_all, real r64, real last_ref_low,
                           real tol_ref, real stay, real *rad, real *off) {
  real eta_f = beta_f * (f + e_f);
  real dist = R_SQRT((u - a.u) * (u - a.u) + (v - a.v) * (v - a.v));
  real lip = REF(local_lipschitz)(sc, curv, e_curv, third, a.delta + dist + 4 * eta_f, lip_all);
  real h_f = beta_f * lip * eta_f;
  real r0_f = 2 * eta_f / (1 + R_SQRT(rmax(1 - 2 * h_f, 0)));
  real beta_s = (beta_f * lip * r0_f < (real)0.5) ? beta_f / (1 - beta_f * lip * r0_f) : 0;
  real rho = a.delta + dist + r0_f;
  real pos64 = 4 * (real)1.1102230246251565e-16 * (R_ABS(u) + R_ABS(v) + rho);
  real settled = REF(patch_settles)(rho, beta_s, lip, jf + e_j + lip * r0_f, beta_s * r64, pos64, a.steps);
  bool stops = (a.last ? a.g : settled) * (real)1.4142135623730951 + r64 < last_ref_low;
  *off = rmax(tol_ref, a.last ? (real)1.4142135623730951 * a.g : settled);
  *rad = r0_f + 4 * beta_f * *off;
  return beta_f > 0 && h_f <= (real)0.25 && beta_s > 0 && beta_s * lip * rho <= (real)0.5 && stops &&
         stay > r0_f + rho + REF(gamma_bound)(8);
}

uint32_t REF(cert_patch_run)(const ref_scene *sc, patch_domain m, patch_net n, patch_bounds pb, real lip, patch_run *r,
                             real *rad, real *off, real *near_x, real *near_y) {
  real k = REF(cert_factor)(sc);
  real rounding = REF(net_rounding)(n, REF(net_lateral)(n));
  real slopes = pb.su + pb.sv;
  real turn = (ref_cert_ed + REF(gamma_bound)(10)) * (pb.suu + 2 * pb.suv + pb.svv);
  real third = 20 * (pb.suu + pb.svv);
  real wu = m.u1 - m.u0;
  real wv = m.v1 - m.v0;
  real tol = (real)RC_PATCH_TOLERANCE_ULPS * RC_UNIT_ROUNDOFF * n.scale;
  real last_tol = (real)RC_PATCH_LAST_TOLERANCE * n.scale;
  real tol_ref = k * (real)RC_PATCH_TOLERANCE_ULPS * (real)1.1102230246251565e-16 * (n.scale + ref_cert_eo) * 2;
  real last_ref = k * (real)RC_PATCH_LAST_TOLERANCE * (n.scale + ref_cert_eo) * (1 + REF(gamma_bound)(2));
  real last_ref_low = (real)RC_PATCH_LAST_TOLERANCE * (n.scale - k * ref_cert_eo) * (1 - REF(gamma_bound)(2));
  real e_dom = REF(gamma_bound)(8);
  *r = REF(patch_start)(m);
  *rad = 0;
  *off = 0;
  *near_x = 0;
  *near_y = 0;
  real nearest = (real)RC_T_FAR;
  uint32_t verdict = 3;
  real delta = k * REF(gamma_bound)(2) * (R_ABS(r->u) + R_ABS(r->v));
  patch_anchor coarse = {false, false, 0, 0, 0, r->u, r->v};
  patch_anchor fine = coarse;
  bool tracking = true;
  for (uint32_t i = 0; i < RC_PATCH_NEWTON_STEPS; i++) {
    ref_work++;
    rvec4 fa, fb;
    REF(patch_evaluate)(n, r, &fa, &fb);
    bool last = i + 1u == RC_PATCH_NEWTON_STEPS;
    bool converged = r->residual <= tol || (last && r->residual <= last_tol);
    real f = R_SQRT(fa.x * fa.x + fb.x * fb.x);
    if (f < nearest) {
      nearest = f;
      *near_x = fa.x;
      *near_y = fb.x;
    }
    real jf = R_SQRT(fa.y * fa.y + fa.z * fa.z + fb.y * fb.y + fb.z * fb.z);
    real mass = REF(bernstein_mass)(r->u, delta) * REF(bernstein_mass)(r->v, delta);
    real e_f = k * (rounding * mass + ref_cert_eo + (ref_cert_ed + REF(gamma_bound)(10)) * (real)1.7320508075688772 * mass * n.scale);
    real e_j = k * (12 * rounding * mass + (ref_cert_ed + REF(gamma_bound)(10)) * slopes);
    real e_curv = 4 * 36 * rounding * mass + turn;
    real curv = REF(net_curvature)(n, r, fa, fb);
    real lip_k = REF(local_lipschitz)(sc, curv, e_curv, third, delta, lip);
    real spread = e_f + (jf + e_j) * delta + (real)0.5 * lip_k * delta * delta;
    real det = fa.y * fb.z - fa.z * fb.y;
    real b_c = REF(inverse_norm)(jf, det);
    real e_k = e_j + lip_k * delta;
    real beta = (b_c * e_k < (real)0.5) ? b_c / (1 - b_c * e_k) : 0;
    real beta_f = (b_c * e_j < (real)0.5) ? b_c / (1 - b_c * e_j) : 0;
    real sl = 0;
    if (beta_f > 0) {
      real nu = fa.x * fb.z - fa.z * fb.x;
      real nv = fa.y * fb.x - fa.x * fb.y;
      sl = R_SQRT(nu * nu + nv * nv) / R_ABS(det);
    }
    real e_s = REF(gamma_bound)(8) * b_c * (2 * f + 2 * jf * sl) + REF(gamma_bound)(2) * sl;
    real r64 = 2 * rounding * mass * (real)(1.1102230246251565e-16 / RC_UNIT_ROUNDOFF);
    real crit = last ? last_ref : tol_ref;
    patch_anchor here = {true, last, RC_PATCH_NEWTON_STEPS - 1u - i, delta, f + spread, r->u, r->v};
    if (verdict == 3 && !coarse.set && (converged || !(f - spread > crit))) coarse = here;
    if (verdict == 3 && tracking && !fine.set) {
      real low = f - spread;
      if (beta_f > 0) {
        real s_low = sl - e_s - beta_f * (e_f + e_j * (sl + e_s));
        low = rmax(low, (s_low - delta) / beta_f - (real)0.5 * lip_k * delta * delta - r64);
      }
      if (converged || !(low > crit)) {
        fine = here;
      } else if (!(b_c > 0 && b_c * e_k < (real)0.5)) {
        tracking = false;
        if (!coarse.set) verdict = 0;
      }
    }
    if (verdict == 3 && converged) {
      real stay = REF(grown_room)(m, r);
      real from_fine = fine.delta + R_SQRT((r->u - fine.u) * (r->u - fine.u) + (r->v - fine.v) * (r->v - fine.v));
      real from_coarse =
          coarse.delta + R_SQRT((r->u - coarse.u) * (r->u - coarse.u) + (r->v - coarse.v) * (r->v - coarse.v));
      patch_anchor a = (fine.set && from_fine <= from_coarse) ? fine : coarse;
      bool sure = REF(patch_anchor_end)(sc, a, r->u, r->v, beta_f, f, e_f, jf, e_j, curv, e_curv, third, lip, r64,
                                        last_ref_low, tol_ref, stay, rad, off);
      *off += r->residual;
      verdict = sure ? 2 : 0;
    }
    if (verdict == 3 && last) verdict = coarse.set ? 0 : 1;
    if (converged) {
      r->converged = true;
      break;
    }
    if (last) break;
    real u_was = r->u;
    real v_was = r->v;
    if (!REF(newton_step)(fa, fb, &r->u, &r->v)) {
      if (verdict == 3) verdict = 0;
      break;
    }
    r->nearby = r->u >= m.u0 - wu && r->u <= m.u1 + wu && r->v >= m.v0 - wv && r->v <= m.v1 + wv;
    if (verdict == 3 && tracking && !fine.set) {
      real step = R_SQRT((r->u - u_was) * (r->u - u_was) + (r->v - v_was) * (r->v - v_was));
      real s_high = sl + e_s + beta * (e_f + e_j * (sl + e_s));
      real bld = beta * lip_k * delta;
      real lam = beta * lip_k * beta * (f + spread);
      if (bld < (real)0.5) lam = rmin(lam, beta * lip_k * (s_high + delta) / (1 - bld));
      delta = k * (lam * delta + beta * (e_f + e_j * step) + REF(gamma_bound)(16) * step +
                   REF(gamma_bound)(2) * (R_ABS(r->u) + R_ABS(r->v) + step));
      real stay = REF(grown_room)(m, r);
      if (!(stay > delta + e_dom)) {
        if (-stay > delta + e_dom) verdict = 1;
        else if (!coarse.set) verdict = 0;
        else tracking = false;
      }
    }
    if (verdict == 3 && coarse.set && !r->nearby) verdict = 0;
    if (!r->nearby) break;
  }
  return (verdict == 3) ? 0 : verdict;
}

rvec4 REF(cubic_on)(rvec4 c, real s, real t) {
  real ls0 = c.x + s * (c.y - c.x), ls1 = c.y + s * (c.z - c.y), ls2 = c.z + s * (c.w - c.z);
  real lt0 = c.x + t * (c.y - c.x), lt1 = c.y + t * (c.z - c.y), lt2 = c.z + t * (c.w - c.z);
  real lss0 = ls0 + s * (ls1 - ls0), lss1 = ls1 + s * (ls2 - ls1);
  real lst0 = ls0 + t * (ls1 - ls0), lst1 = ls1 + t * (ls2 - ls1);
  real ltt0 = lt0 + t * (lt1 - lt0), ltt1 = lt1 + t * (lt2 - lt1);
  return (rvec4){lss0 + s * (lss1 - lss0), lss0 + t * (lss1 - lss0), lst0 + t * (lst1 - lst0), ltt0 + t * (ltt1 - ltt0)};
}

real REF(min4)(rvec4 c) { return rmin(rmin(c.x, c.y), rmin(c.z, c.w)); }

static rvec4 weigh_rows(real wx, rvec4 a, real wy, rvec4 b) {
  return (rvec4){wx * a.x + wy * b.x, wx * a.y + wy * b.y, wx * a.z + wy * b.z, wx * a.w + wy * b.w};
}

real REF(hull_low)(patch_net n, real wx, real wy, real lo_u, real hi_u, real lo_v, real hi_v) {
  rvec4 r0 = REF(cubic_on)(weigh_rows(wx, n.a0, wy, n.b0), lo_u, hi_u);
  rvec4 r1 = REF(cubic_on)(weigh_rows(wx, n.a1, wy, n.b1), lo_u, hi_u);
  rvec4 r2 = REF(cubic_on)(weigh_rows(wx, n.a2, wy, n.b2), lo_u, hi_u);
  rvec4 r3 = REF(cubic_on)(weigh_rows(wx, n.a3, wy, n.b3), lo_u, hi_u);
  real c0 = REF(min4)(REF(cubic_on)((rvec4){r0.x, r1.x, r2.x, r3.x}, lo_v, hi_v));
  real c1 = REF(min4)(REF(cubic_on)((rvec4){r0.y, r1.y, r2.y, r3.y}, lo_v, hi_v));
  real c2 = REF(min4)(REF(cubic_on)((rvec4){r0.z, r1.z, r2.z, r3.z}, lo_v, hi_v));
  real c3 = REF(min4)(REF(cubic_on)((rvec4){r0.w, r1.w, r2.w, r3.w}, lo_v, hi_v));
  return rmin(rmin(c0, c1), rmin(c2, c3));
}

void REF(cert_patch)(const ref_scene *sc, const packed_quadric *q, rvec3 o, rvec3 d, real t_max) {
  real b_in, b_out;
  uint32_t a_in, a_out;
  REF(box_span)(rvec3_from(q->lo), rvec3_from(q->hi), RV(sub)(o, rvec3_from(q->center)), d, &b_in, &b_out, &a_in,
                &a_out);
  if (b_in > b_out || b_out < 0 || b_in > t_max * (real)RC_BOX_NEAR_SCALE) return;
  rvec3 a, b;
  REF(patch_planes)(d, &a, &b);
  patch_net n = REF(load_patch_net)(sc, q->mesh_root, o, a, b, d);
  patch_domain m = REF(patch_domain_of)(q);
  real k = REF(cert_factor)(sc);
  real wu = m.u1 - m.u0;
  real wv = m.v1 - m.v0;
  patch_bounds pb = REF(cert_patch_bounds)(q, n.scale, m.u0 - wu, m.u1 + wu, m.v0 - wv, m.v1 + wv);
  real reach = (real)1.7320508075688772 * pb.weight * n.scale;
  real lip = k * (pb.suu + 2 * pb.suv + pb.svv) * (1 + ref_cert_ed + REF(gamma_bound)(10));
  patch_run r;
  real rad, off, near_x, near_y;
  uint32_t run = REF(cert_patch_run)(sc, m, n, pb, lip, &r, &rad, &off, &near_x, &near_y);
  ref_cert_patch_r = r;
  ref_cert_patch_t = REF(patch_depth)(r, n);
  real u = r.u;
  real v = r.v;
  real e_dom = REF(gamma_bound)(8);
  if (run == 2) {
    bool inside = u - rad - m.lo_u > e_dom && m.hi_u - u - rad > e_dom && v - rad - m.lo_v > e_dom &&
                  m.hi_v - v - rad > e_dom;
    bool outside = m.lo_u - u - rad > e_dom || u - rad - m.hi_u > e_dom || m.lo_v - v - rad > e_dom ||
                   v - rad - m.hi_v > e_dom;
    if (outside) return;
    if (!inside) {
      REF(cert_fail)();
      return;
    }
    real t = ref_cert_patch_t;
    real e_t = k * (ref_cert_eo + ref_cert_ed * reach + (pb.su + pb.sv) * rad +
                    REF(gamma_bound)(40) * REF(bernstein_mass)(u, rad) * REF(bernstein_mass)(v, rad) * n.scale);
    ref_cert_bary_err = rad;
    ref_cert_off_err = off;
    REF(cert_root)(sc, t, e_t, t_max, t > 0);
    return;
  }
  if (run == 1) return;
  patch_run centre = REF(patch_start)(m);
  real uc = centre.u;
  real vc = centre.v;
  rvec4 fa, fb;
  REF(patch_evaluate)(n, &centre, &fa, &fb);
  real f0 = R_SQRT(fa.x * fa.x + fb.x * fb.x);
  if (!(f0 > 0)) {
    REF(cert_fail)();
    return;
  }
  real mass = rmax(REF(bernstein_mass)(m.lo_u, 0), REF(bernstein_mass)(m.hi_u, 0)) *
              rmax(REF(bernstein_mass)(m.lo_v, 0), REF(bernstein_mass)(m.hi_v, 0));
  real lateral = REF(net_lateral)(n);
  real rounding = REF(net_rounding)(n, lateral);
  real e_f = k * (rounding * mass + ref_cert_eo + (ref_cert_ed + REF(gamma_bound)(10)) * reach);
  real e_j = k * (12 * rounding * mass + (ref_cert_ed + REF(gamma_bound)(10)) * (pb.su + pb.sv));
  real du = rmax(uc - m.lo_u, m.hi_u - uc) + e_dom;
  real dv = rmax(vc - m.lo_v, m.hi_v - vc) + e_dom;
  real wx = fa.x / f0;
  real wy = fb.x / f0;
  real along = R_ABS(wx * fa.y + wy * fb.y) * du + R_ABS(wx * fa.z + wy * fb.z) * dv;
  real curve = (real)0.5 * (pb.suu * du * du + 2 * pb.suv * du * dv + pb.svv * dv * dv) *
               (1 + ref_cert_ed + REF(gamma_bound)(10));
  real slack = k * (curve + e_f + e_j * R_SQRT(du * du + dv * dv) + (real)RC_PATCH_LAST_TOLERANCE * (n.scale + ref_cert_eo));
  if (f0 * (1 - REF(gamma_bound)(8)) - along * (1 + REF(gamma_bound)(8)) > slack) return;
  real lo_u = m.lo_u - e_dom;
  real hi_u = m.hi_u + e_dom;
  real lo_v = m.lo_v - e_dom;
  real hi_v = m.hi_v + e_dom;
  real low = REF(hull_low)(n, wx, wy, lo_u, hi_u, lo_v, hi_v);
  real mass_hull = rmax(REF(bernstein_mass)(lo_u, 0), REF(bernstein_mass)(hi_u, 0)) *
                   rmax(REF(bernstein_mass)(lo_v, 0), REF(bernstein_mass)(hi_v, 0));
  real e_hull = REF(gamma_bound)(40) * mass_hull * (real)1.5 * lateral * (1 + REF(gamma_bound)(2));
  real slack_hull = k * (e_f + 2 * rounding * mass_hull + (real)RC_PATCH_LAST_TOLERANCE * (n.scale + ref_cert_eo) *
                         (1 + REF(gamma_bound)(2))) * (1 + REF(gamma_bound)(8));
  if (low - e_hull > slack_hull) return;
  real f_near = R_SQRT(near_x * near_x + near_y * near_y);
  if (!(f_near > 0) ||
      !(REF(hull_low)(n, near_x / f_near, near_y / f_near, lo_u, hi_u, lo_v, hi_v) - e_hull > slack_hull))
    REF(cert_fail)();
}

void REF(cert_patch_surface)(const ref_scene *sc, const packed_quadric *q, rvec3 d, rvec3 uv, real bary_err,
                             real off_err, real t, rvec3 ng, rvec3 p_error) {
  rvec4 fx, fy, fz;
  patch_net n = REF(patch_eval)(sc, q, uv, &fx, &fy, &fz);
  patch_domain m = REF(patch_domain_of)(q);
  patch_bounds pb = REF(cert_patch_bounds)(q, n.scale, m.lo_u, m.hi_u, m.lo_v, m.hi_v);
  real k = REF(cert_factor)(sc);
  rvec3 pu = RV(make)(fx.y, fy.y, fz.y);
  rvec3 pv = RV(make)(fx.z, fy.z, fz.z);
  real cosine = R_ABS(RV(dot)(ng, d));
  real e_cos = ref_cert_ed + REF(gamma_bound)(12);
  real moved = ref_cert_eo + t * ref_cert_ed + off_err;
  real along = rmin(2 * moved / rmax(cosine - e_cos, RC_SMALLEST_NORMAL), (pb.su + pb.sv) * bary_err);
  real guu = RV(dot)(pu, pu);
  real guv = RV(dot)(pu, pv);
  real gvv = RV(dot)(pv, pv);
  real gdet = guu * gvv - guv * guv;
  real tr = guu + gvv;
  real sigma2 = 2 * gdet / (tr + R_SQRT(rmax(tr * tr - 4 * gdet, 0))) * (1 - REF(gamma_bound)(16));
  real moved_uv = (sigma2 > 0) ? rmin(bary_err, along / R_SQRT(sigma2)) : bary_err;
  real e_d = 12 * REF(gamma_bound)(40) * pb.weight * n.scale;
  real e_u = k * ((pb.suu + pb.suv) * moved_uv + e_d);
  real e_v = k * ((pb.suv + pb.svv) * moved_uv + e_d);
  real lu = R_SQRT(guu);
  real lv = R_SQRT(gvv);
  real limit = (real)9.5367431640625e-07 * (real)1.0001;
  if (!(lu - e_u > limit * (lv + e_v) && lv - e_v > limit * (lu + e_u))) REF(cert_fail)();
  rvec3 g = RV(cross)(pu, pv);
  real e_g = k * (e_u * pb.sv + pb.su * e_v + REF(gamma_bound)(4) * lu * lv);
  real en = REF(gamma_bound)(12) + REF(cert_turn_of)(e_g, RV(length)(g));
  REF(cert_require)(sc, cosine, e_cos + en);
  ref_cert_ep = k * along + 2 * RV(length)(p_error);
  ref_cert_en = en;
}
