// rc_certify_patch.glsl: certified decisions of Bezier patch pieces (intersect_patch;
// docs/numerics.md §10). A patch has no closed-form root whose error a bound could follow:
// both precisions run Newton's method from the piece's centre, and the question is where the
// reference's run ends. Kantorovich's theorem answers it (Ortega & Rheinboldt, "Iterative
// Solution of Nonlinear Equations in Several Variables", 12.6.2; in the affine-invariant form
// of Deuflhard, "Newton Methods for Nonlinear Problems", 2.1): with beta >= |J(x0)^-1|,
// eta >= |J(x0)^-1 F(x0)| and L a Lipschitz constant of J on the ball B(x0, r0),
// h = beta L eta <= 1/2 makes Newton's iterates from x0 stay in that ball, r0 =
// 2 eta / (1 + sqrt(1 - 2 h)), and converge to its one root x*. The reference's F is not this
// one: its ray's two planes are other planes through another ray. But Newton's iterates do
// not change when F is turned by a constant rotation, and turned, the reference's F is this
// F (computed exactly) plus what the ray's move (cert_eo, cert_ed) and the rounding change:
// those are the bounds e_f and e_j on F and J below. So where h <= 1/4 (the rest of the way
// to 1/2 covers f64's own rounding of its steps), the reference's run converges to x*, within
// its 12 steps, and never gives up. Where this precision's run converged at x_f, x* is near:
// F(x) = A (x - x*) with |J(x0)^-1 A - I| <= beta L max(|x - x0|, |x* - x0|) = kappa, so
// |x - x*| <= beta |F(x)| / (1 - kappa); the same holds for the reference's accepted point.
// The hit or miss is then the domain's decision on a point known within that radius, and t
// a root whose bound follows. Where Newton's theorem does not hold (no root near, or a ray
// that grazes the piece), a miss is still certain where every point of the domain's surface
// lies farther from the reference's ray than its acceptance: a first-order bound from the
// piece's centre along the direction of F there (a separating line in the ray's plane).

// Bounds over a square of a patch's parameters: the largest first and second derivatives of
// S there (in scene units per unit of u or v), and the largest sum of the Bernstein weights'
// magnitudes.
struct patch_bounds {
  real su; real sv;
  real suu; real suv; real svv;
  real weight;
};

// S = sum B_j(v) B_i(u) P_ij, so dS/du = 3 sum B_j(v) B2_i(u) (P_i+1,j - P_ij), d2S/du2 = 6 sum
// B_j(v) B1_i(u) (second differences), d2S/dudv = 9 sum B2_j(v) B2_i(u) (mixed differences):
// each at most its weights' magnitudes' sum times the largest difference. On [0, 1] a degree-n
// Bernstein basis sums to 1 and is positive; a square that reaches x outside [0, 1] has
// (|1 - u| + |u|)^n = (1 + 2 x)^n. The largest differences are the piece's (rc_shared.h,
// RC_QUADRIC_PATCH: lengths of the net's, rounded up on the host). In a ray's frame (net_row)
// a difference is turned by the frame, whose rows are unit and perpendicular within gamma(10),
// so lengthened by at most 1 + gamma(16); the frame's coordinates round by gamma(4) of sqrt(3)
// scale each, so a difference of up to four of them, in three coordinates, moves by 12 gamma(4)
// scale; the bounds' own rounding is gamma(16) of them.
patch_bounds cert_patch_bounds(packed_quadric q, real scale, real lo_u, real hi_u, real lo_v, real hi_v) {
  real ku = 1.0 + 2.0 * select_max(0.0, select_max(-lo_u, hi_u - 1.0));
  real kv = 1.0 + 2.0 * select_max(0.0, select_max(-lo_v, hi_v - 1.0));
  real turn = 1.0 + gamma_bound(16.0);
  real e = 12.0 * gamma_bound(4.0) * scale;
  real grow = 1.0 + gamma_bound(16.0);
  patch_bounds pb;
  pb.su = 3.0 * ku * ku * kv * kv * kv * (real(q.linear.x) * turn + e) * grow;
  pb.sv = 3.0 * ku * ku * ku * kv * kv * (real(q.linear.y) * turn + e) * grow;
  pb.suu = 6.0 * ku * kv * kv * kv * (real(q.diag.z) * turn + e) * grow;
  pb.svv = 6.0 * ku * ku * ku * kv * (real(q.off.z) * turn + e) * grow;
  pb.suv = 9.0 * ku * ku * kv * kv * (real(q.linear.z) * turn + e) * grow;
  pb.weight = ku * ku * ku * kv * kv * kv * grow;
  return pb;
}

// The sum of the magnitudes of a cubic Bernstein basis at u, grown by x: (|1 - u| + |u| +
// 2 x)^3, 1 on [0, 1] (where x = 0). A weighing of values within s rounds within gamma of
// that times s.
real bernstein_mass(real u, real x) {
  precise real s = abs(1.0 - u) + abs(u) + 2.0 * x;
  return s * s * s * (1.0 + gamma_bound(4.0));
}

// The rounding of a weighing of the net's a and b coordinates at a point where the weights'
// magnitudes sum to mass (per unit scale): each coordinate, a dot product of P - o (whose
// components are within scale) with a unit vector, rounds within gamma(4) sqrt(3) scale; two
// weighings of four with rounded weights add gamma(16) of the coordinates' largest
// magnitude. The sum, for F's two components (sqrt(2) < 1.5) or J's four slopes, whose weights'
// magnitudes sum to 6 of a value's (Frobenius: 2 x 6).
real net_rounding(patch_net n, real lateral) {
  return 1.5 * (gamma_bound(5.0) * 1.7320508075688772 * n.scale + gamma_bound(17.0) * lateral);
}

// The largest magnitude of the net's a and b coordinates: the patch's extent across the ray.
real net_lateral(patch_net n) {
  rvec4 m = max(max(max(abs(n.a0), abs(n.a1)), max(abs(n.a2), abs(n.a3))),
                max(max(abs(n.b0), abs(n.b1)), max(abs(n.b2), abs(n.b3))));
  return select_max(select_max(m.x, m.y), select_max(m.z, m.w));
}

// |J^-1| for a 2 x 2 matrix J: 1 / sigma_min, sigma_min^2 = 2 det^2 / (|J|_F^2 + sqrt(|J|_F^4 -
// 4 det^2)), grown by its rounding; 0 where J is singular within its rounding.
real inverse_norm(real jf, real det) {
  real f2 = jf * jf;
  if (!(abs(det) > f2 * gamma_bound(8.0))) return 0.0;
  real root = sqrt(select_max(f2 * f2 - 4.0 * det * det, 0.0));
  return sqrt((f2 + root) / (2.0 * det * det)) * (1.0 + gamma_bound(16.0));
}

// Where the reference's run settles about G's root x*, from within e of it: with |J(x*)^-1| <=
// beta and theta = beta L e <= 1/2, a Newton step lands within beta L e^2 / (2 (1 - beta L e))
// of x* (the local convergence of Newton's method: Dennis & Schnabel, "Numerical Methods for
// Unconstrained Optimization and Nonlinear Equations", 5.2.1), so the distance halves at least
// and then squares, plus the step's own rounding in f64: e64 (beta times G's rounding, and
// J's, 12 times that, over a step of at most 2 e), the solve's (10 u64 of the step times
// |J(x*)| beta, counted as 64) and the point's (pos64). After m steps (six counted at most:
// more only shrink it), |G| <= (|J(x*)| + L e / 2) e.
// Each step is a step of the lane's budget (rc_budget.glsl; the planner counts six).
real patch_settles(real e, real beta, real lip, real jx, real e64, real pos64, uint m) {
  for (uint j = 0u; j < m && j < 6u; j++) {
    if (!budget_step()) break;
    e = beta * lip * e * e / (2.0 * (1.0 - beta * lip * e)) + e64 * (1.0 + 16.0 * e) + pos64 +
        64.0 * 1.1102230246251565e-16 * beta * jx * e;
  }
  return (jx + 0.5 * lip * e) * e;
}

// The second derivatives of the cubic Bernstein weights at t: 6 (B1[i-2] - 2 B1[i-1] + B1[i])
// with B1 the linear weights s, t.
rvec4 bernstein_curve(real t) {
  real s = 1.0 - t;
  return rvec4(6.0 * s, 6.0 * (t - 2.0 * s), 6.0 * (s - 2.0 * t), 6.0 * t);
}

// |D2F| at the run's point (patch_evaluate's weights; F_uv is net_eval's mixed slope): for a
// unit h, D2F[h] is the 2 x 2 matrix of rows (F_uu h_u + F_uv h_v, F_uv h_u + F_vv h_v), one
// per coordinate, whose norm is at most its Frobenius norm, at most sqrt(F_uu^2 + 2 F_uv^2 +
// F_vv^2) summed over both (Cauchy-Schwarz).
real net_curvature(patch_net n, patch_run r, rvec4 fa, rvec4 fb) {
  rvec4 cu = bernstein_curve(r.u);
  rvec4 cv = bernstein_curve(r.v);
  real auu = weigh(r.bv, rvec4(weigh(cu, n.a0), weigh(cu, n.a1), weigh(cu, n.a2), weigh(cu, n.a3)));
  real avv = weigh(cv, rvec4(weigh(r.bu, n.a0), weigh(r.bu, n.a1), weigh(r.bu, n.a2), weigh(r.bu, n.a3)));
  real buu = weigh(r.bv, rvec4(weigh(cu, n.b0), weigh(cu, n.b1), weigh(cu, n.b2), weigh(cu, n.b3)));
  real bvv = weigh(cv, rvec4(weigh(r.bu, n.b0), weigh(r.bu, n.b1), weigh(r.bu, n.b2), weigh(r.bu, n.b3)));
  return sqrt(auu * auu + avv * avv + buu * buu + bvv * bvv + 2.0 * (fa.w * fa.w + fb.w * fb.w));
}

// J's Lipschitz constant on a ball of radius rad about the run's point, for the reference's G:
// |D2F| there as computed (curv), plus its rounding and the turn of the ray's planes (e_curv),
// plus the third derivatives over the radius (third), and never more than the whole square's
// (lip). A ray's Newton steps see only the patch near their points, where the second
// derivatives are often a third of their largest over the square the run may wander in.
real local_lipschitz(real curv, real e_curv, real third, real rad, real lip) {
  return select_min(lip, cert_factor() * (curv + e_curv + third * rad) * (1.0 + gamma_bound(8.0)));
}

// How far the run's point lies inside the square it may wander in (the piece grown by its
// width on every side; patch_newton's nearby): negative outside.
real grown_room(patch_domain m, patch_run r) {
  real wu = m.u1 - m.u0;
  real wv = m.v1 - m.v0;
  return select_min(select_min(r.u - (m.u0 - wu), m.u1 + wu - r.u), select_min(r.v - (m.v0 - wv), m.v1 + wv - r.v));
}

// A step where the reference's run may stop first: this run's point there, the reference's
// distance from it and its residual's bound there, whether it is the last step and how many
// steps follow.
struct patch_anchor {
  bool set; bool last; uint steps;
  real delta; real g; real u; real v;
};

// Where the reference's run ends, from an anchor a, where this run converged at (u, v):
// Kantorovich's theorem about (u, v) (eta = beta |G|, h = beta L eta <= 1/4) puts G's root x*
// within r0 = 2 eta / (1 + sqrt(1 - 2 h)), where |J(x*)^-1| <= beta* = beta / (1 - beta L r0);
// the reference's point at the anchor is within rho = delta_a + |x_a - x_f| + r0 of x*, and
// where beta* L rho <= 1/2 Newton's method converges from there (patch_settles). L is
// local_lipschitz's on the ball of radius rho + r0 about (u, v), which holds all of it (r0 <=
// 2 eta where h <= 1/2). True where certain; rad and off as cert_patch_run's.
bool patch_anchor_end(patch_anchor a, real u, real v, real beta_f, real f, real e_f, real jf, real e_j, real curv,
                      real e_curv, real third, real lip_all, real r64, real last_ref_low, real tol_ref, real stay,
                      out real rad, out real off) {
  real eta_f = beta_f * (f + e_f);
  real dist = length(rvec2(u - a.u, v - a.v));
  real lip = local_lipschitz(curv, e_curv, third, a.delta + dist + 4.0 * eta_f, lip_all);
  real h_f = beta_f * lip * eta_f;
  real r0_f = 2.0 * eta_f / (1.0 + sqrt(select_max(1.0 - 2.0 * h_f, 0.0)));
  real beta_s = (beta_f * lip * r0_f < 0.5) ? beta_f / (1.0 - beta_f * lip * r0_f) : 0.0;
  real rho = a.delta + dist + r0_f;
  real pos64 = 4.0 * 1.1102230246251565e-16 * (abs(u) + abs(v) + rho);
  real settled = patch_settles(rho, beta_s, lip, jf + e_j + lip * r0_f, beta_s * r64, pos64, a.steps);
  // At the last step the reference stops where its residual, |G.x| + |G.y| as computed,
  // is under its last criterion.
  bool stops = (a.last ? a.g : settled) * 1.4142135623730951 + r64 < last_ref_low;
  // The reference's residual where it stops bounds its point's distance from x*: within
  // 2 beta* of it, beta* <= 2 beta_f.
  off = select_max(tol_ref, a.last ? 1.4142135623730951 * a.g : settled);
  rad = r0_f + 4.0 * beta_f * off;
  return beta_f > 0.0 && h_f <= 0.25 && beta_s > 0.0 && beta_s * lip * rho <= 0.5 && stops &&
         stay > r0_f + rho + gamma_bound(8.0);
}

// Where the reference's run ends, against this one's (patch_newton's steps, taken again). G,
// the reference's F turned into this ray's planes, is within e_f of F and its Jacobian within
// e_j of J (on a ball of radius delta, within e_j + L delta): the rounding of this run's
// weighings, where the weights' magnitudes sum to bernstein_mass, and the ray's move, which
// shifts F by eo + ed |S - o| and turns J's columns by ed (this ray's planes are unit and
// perpendicular within gamma(10)). The reference's run starts at the same centre and stays
// within delta_k of this one's point x_k: the Newton map N(y) = y - s(y), s = J^-1 G, has the
// derivative J^-1 (dJ) s, at most beta L |s(y)| (where |J(y)^-1| <= beta on the ball), and
// |s(y)| <= |s(x_k)| + delta + |N(y) - N(x_k)| makes it at most beta L (|s(x_k)| + delta) /
// (1 - beta L delta) (also at most beta L beta |G|); at x_k the map differs from this run's
// computed step by beta (e_f + e_j |step|) plus the step's rounding. L is local_lipschitz's
// on that ball. Its check that it stays near the piece must go as this one's: both stay, or
// both leave (both miss). The reference may stop at a step only where its residual may lie
// under its criterion: the coarse anchor is the first step where |G| >= |F| - e_f - (|J| +
// e_j) delta - L delta^2 / 2 does not put it above; the fine anchor the first where
// |G| >= (|s| - delta) / beta - L delta^2 / 2 (s the exact step of G at x_k: the ball of
// radius delta about it maps into G + J(ball) + the curvature's, and J^-1 shortens nothing
// below |.| / beta) does not either, while delta still tracks the reference. The fine anchor is
// later, where this run is nearer its end, but is set only while the tracking holds. Where
// this run converges at x_f, patch_anchor_end takes the reference to its end from the anchor
// whose delta and distance from x_f are the smaller (the coarse one where there is no fine). This run must converge in the piece's neighbourhood too:
// leaving it, or ending unconverged, it fails. Where this run stops unconverged at its last
// step and the reference's residual is certainly above its last criterion, both miss. Returns
// 0 where the reference's run may end otherwise than this one's, 1 where both certainly miss,
// 2 where both converged: (u, v) this run's point, rad the distance within which the
// reference's lies, off the sum of the two points' distances from their rays, and near the
// direction of F at the run's point nearest the ray (cert_patch's separating line).
uint cert_patch_run(patch_domain m, patch_net n, patch_bounds pb, real lip, out patch_run r, out real rad,
                    out real off, out rvec2 near) {
  real k = cert_factor();
  real rounding = net_rounding(n, net_lateral(n));
  real slopes = pb.su + pb.sv;
  // D2F's bound's rounding and turn, and the third derivatives' bound: each third difference
  // of the net at most twice its largest second one, so |S_uuu| <= 2 |S_uu|, |S_uuv| <= 6 |S_uu|
  // and so on over the square, 20 (|S_uu| + |S_vv|) for D3S on unit vectors.
  real turn = (cert_ed + gamma_bound(10.0)) * (pb.suu + 2.0 * pb.suv + pb.svv);
  real third = 20.0 * (pb.suu + pb.svv);
  real wu = m.u1 - m.u0;
  real wv = m.v1 - m.v0;
  precise real tol = real(RC_PATCH_TOLERANCE_ULPS) * RC_UNIT_ROUNDOFF * n.scale;
  precise real last_tol = real(RC_PATCH_LAST_TOLERANCE) * n.scale;
  // The reference's criteria: f64's unit roundoff, and its scale, within eo of this one's.
  real tol_ref = k * real(RC_PATCH_TOLERANCE_ULPS) * 1.1102230246251565e-16 * (n.scale + cert_eo) * 2.0;
  real last_ref = k * real(RC_PATCH_LAST_TOLERANCE) * (n.scale + cert_eo) * (1.0 + gamma_bound(2.0));
  real last_ref_low = real(RC_PATCH_LAST_TOLERANCE) * (n.scale - k * cert_eo) * (1.0 - gamma_bound(2.0));
  real e_dom = gamma_bound(8.0);
  // patch_newton's run, step for step (intersect_patch takes it: cert_patch_r).
  r = patch_start(m);
  rad = 0.0;
  off = 0.0;
  near = rvec2(0.0);
  real nearest = real(RC_T_FAR);
  // 3 while the reference's end is not yet known.
  uint verdict = 3u;
  real delta = k * gamma_bound(2.0) * (abs(r.u) + abs(r.v));
  patch_anchor coarse = patch_anchor(false, false, 0u, 0.0, 0.0, r.u, r.v);
  patch_anchor fine = coarse;
  // Whether delta still bounds the reference's distance from this run's point.
  bool tracking = true;
  for (uint i = 0u; i < RC_PATCH_NEWTON_STEPS; i++) {
    if (!budget_step()) break;
    rvec4 fa, fb;
    patch_evaluate(n, r, fa, fb);
    bool last = i + 1u == RC_PATCH_NEWTON_STEPS;
    bool converged = r.residual <= tol || (last && r.residual <= last_tol);
    real f = length(rvec2(fa.x, fb.x));
    if (f < nearest) {
      nearest = f;
      near = rvec2(fa.x, fb.x);
    }
    real jf = length(rvec4(fa.y, fa.z, fb.y, fb.z));
    real mass = bernstein_mass(r.u, delta) * bernstein_mass(r.v, delta);
    real e_f = k * (rounding * mass + cert_eo + (cert_ed + gamma_bound(10.0)) * 1.7320508075688772 * mass * n.scale);
    real e_j = k * (12.0 * rounding * mass + (cert_ed + gamma_bound(10.0)) * slopes);
    // D2F's rounding: the weights' magnitudes sum to at most 36 of a value's (F_uv's, 6 x 6).
    real e_curv = 4.0 * 36.0 * rounding * mass + turn;
    real curv = net_curvature(n, r, fa, fb);
    real lip_k = local_lipschitz(curv, e_curv, third, delta, lip);
    real spread = e_f + (jf + e_j) * delta + 0.5 * lip_k * delta * delta;
    // Through an error E, |(J + E)^-1| <= beta / (1 - beta |E|).
    real det = fa.y * fb.z - fa.z * fb.y;
    real b_c = inverse_norm(jf, det);
    real e_k = e_j + lip_k * delta;
    real beta = (b_c * e_k < 0.5) ? b_c / (1.0 - b_c * e_k) : 0.0;
    real beta_f = (b_c * e_j < 0.5) ? b_c / (1.0 - b_c * e_j) : 0.0;
    // The Newton step's length as newton_step computes it, and its rounding (Cramer's rule:
    // gamma(2) of each product's magnitudes, |det| >= jf / (sqrt(2) beta)).
    real sl = (beta_f > 0.0) ? length(rvec2(fa.x * fb.z - fa.z * fb.x, fa.y * fb.x - fa.x * fb.y)) / abs(det) : 0.0;
    real e_s = gamma_bound(8.0) * b_c * (2.0 * f + 2.0 * jf * sl) + gamma_bound(2.0) * sl;
    real r64 = 2.0 * rounding * mass * (1.1102230246251565e-16 / RC_UNIT_ROUNDOFF);
    real crit = last ? last_ref : tol_ref;
    patch_anchor here = patch_anchor(true, last, RC_PATCH_NEWTON_STEPS - 1u - i, delta, f + spread, r.u, r.v);
    if (verdict == 3u && !coarse.set && (converged || !(f - spread > crit))) coarse = here;
    if (verdict == 3u && tracking && !fine.set) {
      real low = f - spread;
      if (beta_f > 0.0) {
        real s_low = sl - e_s - beta_f * (e_f + e_j * (sl + e_s));
        low = select_max(low, (s_low - delta) / beta_f - 0.5 * lip_k * delta * delta - r64);
      }
      if (converged || !(low > crit)) {
        fine = here;
      } else if (!(b_c > 0.0 && b_c * e_k < 0.5)) {
        tracking = false;
        if (!coarse.set) verdict = 0u;
      }
    }
    if (verdict == 3u && converged) {
      real stay = grown_room(m, r);
      // From the anchor whose point the reference is nearer x_f from: one end taken, since
      // llvmpipe would run a second one's code for every lane (docs/performance.md).
      real from_fine = fine.delta + length(rvec2(r.u - fine.u, r.v - fine.v));
      real from_coarse = coarse.delta + length(rvec2(r.u - coarse.u, r.v - coarse.v));
      patch_anchor a = (fine.set && from_fine <= from_coarse) ? fine : coarse;
      bool sure = patch_anchor_end(a, r.u, r.v, beta_f, f, e_f, jf, e_j, curv, e_curv, third, lip, r64, last_ref_low,
                                   tol_ref, stay, rad, off);
      off += r.residual;
      verdict = sure ? 2u : 0u;
    }
    if (verdict == 3u && last) verdict = coarse.set ? 0u : 1u;
    if (converged) {
      r.converged = true;
      break;
    }
    if (last) break;
    real u_was = r.u;
    real v_was = r.v;
    if (!newton_step(fa, fb, r.u, r.v)) {
      if (verdict == 3u) verdict = 0u;
      break;
    }
    r.nearby = r.u >= m.u0 - wu && r.u <= m.u1 + wu && r.v >= m.v0 - wv && r.v <= m.v1 + wv;
    if (verdict == 3u && tracking && !fine.set) {
      real step = length(rvec2(r.u - u_was, r.v - v_was));
      real s_high = sl + e_s + beta * (e_f + e_j * (sl + e_s));
      real bld = beta * lip_k * delta;
      real lam = beta * lip_k * beta * (f + spread);
      if (bld < 0.5) lam = select_min(lam, beta * lip_k * (s_high + delta) / (1.0 - bld));
      delta = k * (lam * delta + beta * (e_f + e_j * step) + gamma_bound(16.0) * step +
                   gamma_bound(2.0) * (abs(r.u) + abs(r.v) + step));
      real stay = grown_room(m, r);
      // Past the coarse anchor the reference may have stopped: an uncertain leave ends only
      // the tracking then, and the coarse anchor's certificate stays.
      if (!(stay > delta + e_dom)) {
        if (-stay > delta + e_dom) verdict = 1u;
        else if (!coarse.set) verdict = 0u;
        else tracking = false;
      }
    }
    // Anchored, this run must converge as the reference's does: leaving, it would miss.
    if (verdict == 3u && coarse.set && !r.nearby) verdict = 0u;
    if (!r.nearby) break;
  }
  return (verdict == 3u) ? 0u : verdict;
}

// A cubic's Bernstein coefficients on [s, t]: its blossom at (s, s, s), (s, s, t), (s, t, t) and
// (t, t, t), de Casteljau's steps at s and at t (Ramshaw, "Blossoms are polar forms", 1989).
rvec4 cubic_on(rvec4 c, real s, real t) {
  rvec3 ls = c.xyz + s * (c.yzw - c.xyz);
  rvec3 lt = c.xyz + t * (c.yzw - c.xyz);
  rvec2 lss = ls.xy + s * (ls.yz - ls.xy);
  rvec2 lst = ls.xy + t * (ls.yz - ls.xy);
  rvec2 ltt = lt.xy + t * (lt.yz - lt.xy);
  return rvec4(lss.x + s * (lss.y - lss.x), lss.x + t * (lss.y - lss.x), lst.x + t * (lst.y - lst.x),
               ltt.x + t * (ltt.y - ltt.x));
}

real min4(rvec4 c) { return select_min(select_min(c.x, c.y), select_min(c.z, c.w)); }

// The least of the Bezier coefficients of w.F (F's two coordinates weighed by w) on the square
// [lo_u, hi_u] x [lo_v, hi_v]: w.F is at least that everywhere on it (the convex hull property
// of the Bernstein basis), so a positive least is a line that separates the piece's surface
// from the ray.
real hull_low(patch_net n, rvec2 w, real lo_u, real hi_u, real lo_v, real hi_v) {
  rvec4 r0 = cubic_on(w.x * n.a0 + w.y * n.b0, lo_u, hi_u);
  rvec4 r1 = cubic_on(w.x * n.a1 + w.y * n.b1, lo_u, hi_u);
  rvec4 r2 = cubic_on(w.x * n.a2 + w.y * n.b2, lo_u, hi_u);
  rvec4 r3 = cubic_on(w.x * n.a3 + w.y * n.b3, lo_u, hi_u);
  real c0 = min4(cubic_on(rvec4(r0.x, r1.x, r2.x, r3.x), lo_v, hi_v));
  real c1 = min4(cubic_on(rvec4(r0.y, r1.y, r2.y, r3.y), lo_v, hi_v));
  real c2 = min4(cubic_on(rvec4(r0.z, r1.z, r2.z, r3.z), lo_v, hi_v));
  real c3 = min4(cubic_on(rvec4(r0.w, r1.w, r2.w, r3.w), lo_v, hi_v));
  return select_min(select_min(c0, c1), select_min(c2, c3));
}

// The decisions of intersect_patch: a hit or a miss, and the hit's t against 0 and t_max.
void cert_patch(packed_quadric q, rvec3 o, rvec3 d, real t_max) {
  real b_in, b_out;
  uint a_in, a_out;
  box_span(rvec3(q.lo), rvec3(q.hi), o - rvec3(q.center), d, b_in, b_out, a_in, a_out);
  // A box this ray misses is taken as missed by the reference's too, as a BVH node's.
  if (b_in > b_out || b_out < 0.0 || b_in > t_max * real(RC_BOX_NEAR_SCALE)) return;
  rvec3 a, b;
  patch_planes(d, a, b);
  patch_net n = load_patch_net(q.mesh_root, o, a, b, d);
  patch_domain m = patch_domain_of(q);
  real k = cert_factor();
  real wu = m.u1 - m.u0;
  real wv = m.v1 - m.v0;
  // Where a run may go before it gives up: the piece grown by its width on every side.
  patch_bounds pb = cert_patch_bounds(q, n.scale, m.u0 - wu, m.u1 + wu, m.v0 - wv, m.v1 + wv);
  // |S - o| there: the net's points are within sqrt(3) scale of o.
  real reach = 1.7320508075688772 * pb.weight * n.scale;
  // J's Lipschitz constant: |J(x) - J(y)| <= (|S_uu| + 2 |S_uv| + |S_vv|) |x - y|.
  real lip = k * (pb.suu + 2.0 * pb.suv + pb.svv) * (1.0 + cert_ed + gamma_bound(10.0));
  patch_run r;
  real rad, off;
  rvec2 near;
  uint run = cert_patch_run(m, n, pb, lip, r, rad, off, near);
  // The test that follows (intersect_patch, the same ray) takes this run.
  cert_patch_r = r;
  cert_patch_t = patch_depth(r, n);
  real u = r.u;
  real v = r.v;
  real e_dom = gamma_bound(8.0);
  if (run == 2u) {
    bool inside = u - rad - m.lo_u > e_dom && m.hi_u - u - rad > e_dom && v - rad - m.lo_v > e_dom &&
                  m.hi_v - v - rad > e_dom;
    bool outside = m.lo_u - u - rad > e_dom || u - rad - m.hi_u > e_dom || m.lo_v - v - rad > e_dom ||
                   v - rad - m.hi_v > e_dom;
    if (outside) return;
    if (!inside) {
      cert_fail();
      return;
    }
    // t = d.(S - o): S moves by |S_u| + |S_v| times rad, d and o by the ray's move.
    real t = cert_patch_t;
    real e_t = k * (cert_eo + cert_ed * reach + (pb.su + pb.sv) * rad +
                    gamma_bound(40.0) * bernstein_mass(u, rad) * bernstein_mass(v, rad) * n.scale);
    cert_bary_err = rad;
    cert_off_err = off;
    cert_root(t, e_t, t_max, t > 0.0);
    return;
  }
  if (run == 1u) return;
  // No point of the domain's surface within the reference's acceptance of its ray: along
  // w = F(x0) / |F(x0)|, w.F(x) >= w.F(x0) - |w.J_u| |du| - |w.J_v| |dv| - (second order).
  // (This run did not converge, or not certainly as the reference's: where this bound holds
  // it cannot have converged in the domain either.)
  patch_run centre = patch_start(m);
  real uc = centre.u;
  real vc = centre.v;
  rvec4 fa, fb;
  patch_evaluate(n, centre, fa, fb);
  real f0 = length(rvec2(fa.x, fb.x));
  if (!(f0 > 0.0)) {
    cert_fail();
    return;
  }
  // The bounds over the domain, which reaches at most its margin outside [0, 1].
  real mass = select_max(bernstein_mass(m.lo_u, 0.0), bernstein_mass(m.hi_u, 0.0)) *
              select_max(bernstein_mass(m.lo_v, 0.0), bernstein_mass(m.hi_v, 0.0));
  real lateral = net_lateral(n);
  real rounding = net_rounding(n, lateral);
  real e_f = k * (rounding * mass + cert_eo + (cert_ed + gamma_bound(10.0)) * reach);
  real e_j = k * (12.0 * rounding * mass + (cert_ed + gamma_bound(10.0)) * (pb.su + pb.sv));
  real du = select_max(uc - m.lo_u, m.hi_u - uc) + e_dom;
  real dv = select_max(vc - m.lo_v, m.hi_v - vc) + e_dom;
  rvec2 w = rvec2(fa.x, fb.x) / f0;
  real along = abs(w.x * fa.y + w.y * fb.y) * du + abs(w.x * fa.z + w.y * fb.z) * dv;
  real curve = 0.5 * (pb.suu * du * du + 2.0 * pb.suv * du * dv + pb.svv * dv * dv) * (1.0 + cert_ed + gamma_bound(10.0));
  real slack = k * (curve + e_f + e_j * length(rvec2(du, dv)) + real(RC_PATCH_LAST_TOLERANCE) * (n.scale + cert_eo));
  if (f0 * (1.0 - gamma_bound(8.0)) - along * (1.0 + gamma_bound(8.0)) > slack) return;
  // Else the same line against the hull of the piece's own Bezier net (hull_low), where the
  // second-order term above takes the whole patch's second differences at their largest.
  // Where the line along F at the centre fails, the line along F at the run's point nearest the
  // ray is tried: at a silhouette F there points across the piece's outline.
  // w.F's coefficients, at most 1.5 lateral, round within gamma(2) of that; each step
  // x + s (y - x) of the subdivision within 5 u of the largest value (|s| <= 1 + 2 e_dom),
  // six levels, where the weights' magnitudes sum to mass_hull: gamma(40) of it in all. So
  // w.F of the net's rounded coordinates is at least the least less e_hull, and |F| at
  // least that less their rounding (rounding mass_hull), over |w| <= 1 + gamma(8). The
  // reference accepts no point where |G|, at least |F| less the ray's move (e_f) and less
  // its own rounding (within this one's), is above its last criterion.
  real lo_u = m.lo_u - e_dom;
  real hi_u = m.hi_u + e_dom;
  real lo_v = m.lo_v - e_dom;
  real hi_v = m.hi_v + e_dom;
  real low = hull_low(n, w, lo_u, hi_u, lo_v, hi_v);
  real mass_hull = select_max(bernstein_mass(lo_u, 0.0), bernstein_mass(hi_u, 0.0)) *
                   select_max(bernstein_mass(lo_v, 0.0), bernstein_mass(hi_v, 0.0));
  real e_hull = gamma_bound(40.0) * mass_hull * 1.5 * lateral * (1.0 + gamma_bound(2.0));
  real slack_hull = k * (e_f + 2.0 * rounding * mass_hull + real(RC_PATCH_LAST_TOLERANCE) * (n.scale + cert_eo) *
                         (1.0 + gamma_bound(2.0))) * (1.0 + gamma_bound(8.0));
  if (low - e_hull > slack_hull) return;
  real f_near = length(near);
  if (!(f_near > 0.0) || !(hull_low(n, near / f_near, lo_u, hi_u, lo_v, hi_v) - e_hull > slack_hull)) cert_fail();
}

// A patch hit's point and normal (cert_surface). Each precision's point is a surface point
// within its residual of its ray (off_err bounds the sum: cert_patch_run), so the two lie
// within that plus the rays' move (eo + t ed) over the cosine of the exact meet, along the
// surface (first order, as the other kinds' points), plus the rounding of S;
// cert_patch bounds the reference's (u, v) within bary_err of this one's too, and the point
// moves by at most (|S_u| + |S_v|) bary_err: the smaller bound holds. A move e of the point is
// a move of (u, v) of at most e / sigma_min([S_u S_v]) (first order again), so the derivatives
// move by |S_uu| + |S_uv| (and |S_uv| + |S_vv|) times the smaller of that and bary_err, and the
// normal g = S_u x S_v by |dS_u| |S_v| + |S_u| |dS_v| plus the cross product's rounding. Where
// one derivative is within its move of 2^-20 of the other, whether patch_surface stands the
// mixed derivative in for it is uncertain: not bounded.
void cert_patch_surface(packed_quadric q, rvec3 d, rvec3 uv, real bary_err, real off_err, real t, rvec3 ng,
                        rvec3 p_error) {
  rvec4 fx, fy, fz;
  patch_net n = patch_eval(q, uv, fx, fy, fz);
  patch_domain m = patch_domain_of(q);
  patch_bounds pb = cert_patch_bounds(q, n.scale, m.lo_u, m.hi_u, m.lo_v, m.hi_v);
  real k = cert_factor();
  rvec3 pu = rvec3(fx.y, fy.y, fz.y);
  rvec3 pv = rvec3(fx.z, fy.z, fz.z);
  real cosine = abs(dot(ng, d));
  real e_cos = cert_ed + gamma_bound(12.0);
  real moved = cert_eo + t * cert_ed + off_err;
  real along = select_min(2.0 * moved / select_max(cosine - e_cos, RC_SMALLEST_NORMAL), (pb.su + pb.sv) * bary_err);
  // sigma_min^2 of [S_u S_v]: 2 det / (tr + sqrt(tr^2 - 4 det)) of its Gram matrix.
  real guu = dot(pu, pu);
  real guv = dot(pu, pv);
  real gvv = dot(pv, pv);
  real gdet = guu * gvv - guv * guv;
  real tr = guu + gvv;
  real sigma2 = 2.0 * gdet / (tr + sqrt(select_max(tr * tr - 4.0 * gdet, 0.0))) * (1.0 - gamma_bound(16.0));
  real moved_uv = (sigma2 > 0.0) ? select_min(bary_err, along / sqrt(sigma2)) : bary_err;
  real e_d = 12.0 * gamma_bound(40.0) * pb.weight * n.scale;
  real e_u = k * ((pb.suu + pb.suv) * moved_uv + e_d);
  real e_v = k * ((pb.suv + pb.svv) * moved_uv + e_d);
  real lu = sqrt(guu);
  real lv = sqrt(gvv);
  real limit = 9.5367431640625e-07 * 1.0001;
  if (!(lu - e_u > limit * (lv + e_v) && lv - e_v > limit * (lu + e_u))) cert_fail();
  rvec3 g = cross(pu, pv);
  real e_g = k * (e_u * pb.sv + pb.su * e_v + gamma_bound(4.0) * lu * lv);
  real en = gamma_bound(12.0) + cert_turn_of(e_g, length(g));
  // The side the normal is flipped to (surface_at) is a decision on n.d.
  cert_require(cosine, e_cos + en);
  cert_ep = k * along + 2.0 * length(p_error);
  cert_en = en;
}
