// rc_patch.glsl: pieces of bicubic Bezier patches (RC_QUADRIC_PATCH, rc_shared.h). A ray is
// the meet of two planes through it (Kajiya, "Ray Tracing Parametric Patches", SIGGRAPH
// 1982); their signed distances to the patch point S(u, v) are two functions of (u, v)
// whose common zero Newton's method finds from the piece's centre (Martin et al.,
// "Practical Ray Tracing of Trimmed NURBS Surfaces", JGT 5(1), 2000). The net is moved to
// the ray's origin and projected on the planes' normals once, so every iteration works on
// 2 x 16 numbers. The bound and the criteria are in docs/numerics.md §8.

// Newton runs that stayed in their piece without converging (rc_shared.h, packed_status):
// how many, and 1 + the first piece's quadric index. Per invocation.
uint patch_stalls = 0u;
uint patch_stall_piece = 0u;

// The cubic Bernstein weights at t.
rvec4 bernstein(real t) {
  precise real s = 1.0 - t;
  precise rvec4 w = rvec4(s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t);
  return w;
}

// Their derivatives: 3 (B2[i-1] - B2[i]) with B2 the quadratic weights s^2, 2 t s, t^2.
rvec4 bernstein_slope(real t) {
  precise real s = 1.0 - t;
  precise rvec4 w = rvec4(-3.0 * s * s, 3.0 * s * (s - 2.0 * t), 3.0 * t * (2.0 * s - t), 3.0 * t * t);
  return w;
}

// A row of four values weighted, in a fixed order (no dot: its order is the driver's).
real weigh(rvec4 w, rvec4 c) {
  precise real r = w.x * c.x + w.y * c.y + w.z * c.z + w.w * c.w;
  return r;
}

// One coordinate of the net (row r = 0..3 along v, each four values along u) at (u, v):
// its value, its slopes along u and v, and the mixed slope, from the weights bu, bv and
// their derivatives su, sv.
rvec4 net_eval(rvec4 r0, rvec4 r1, rvec4 r2, rvec4 r3, rvec4 bu, rvec4 su, rvec4 bv, rvec4 sv) {
  rvec4 along = rvec4(weigh(bu, r0), weigh(bu, r1), weigh(bu, r2), weigh(bu, r3));
  rvec4 slope = rvec4(weigh(su, r0), weigh(su, r1), weigh(su, r2), weigh(su, r3));
  return rvec4(weigh(bv, along), weigh(bv, slope), weigh(sv, along), weigh(sv, slope));
}

// A patch's net relative to o along the axes a, b and c: three coordinates of 4 rows each,
// and the largest coordinate of any control point relative to o (the scale of the
// arithmetic's rounding).
struct patch_net {
  rvec4 a0; rvec4 a1; rvec4 a2; rvec4 a3;
  rvec4 b0; rvec4 b1; rvec4 b2; rvec4 b3;
  rvec4 c0; rvec4 c1; rvec4 c2; rvec4 c3;
  real scale;
};

// Row `first` .. first + 3 of the net (texels of the texel array), relative to o, on a, b, c.
void net_row(uint first, rvec3 o, rvec3 a, rvec3 b, rvec3 c, out rvec4 ra, out rvec4 rb, out rvec4 rc,
             inout real scale) {
  precise rvec3 p0 = rvec3(load_patch_point(first)) - o;
  precise rvec3 p1 = rvec3(load_patch_point(first + 1u)) - o;
  precise rvec3 p2 = rvec3(load_patch_point(first + 2u)) - o;
  precise rvec3 p3 = rvec3(load_patch_point(first + 3u)) - o;
  precise rvec4 xa = rvec4(dot(a, p0), dot(a, p1), dot(a, p2), dot(a, p3));
  precise rvec4 xb = rvec4(dot(b, p0), dot(b, p1), dot(b, p2), dot(b, p3));
  precise rvec4 xc = rvec4(dot(c, p0), dot(c, p1), dot(c, p2), dot(c, p3));
  ra = xa;
  rb = xb;
  rc = xc;
  scale = select_max(scale, select_max(select_max(max3_abs(p0), max3_abs(p1)), select_max(max3_abs(p2), max3_abs(p3))));
}

patch_net load_patch_net(uint first, rvec3 o, rvec3 a, rvec3 b, rvec3 c) {
  patch_net n;
  n.scale = 0.0;
  net_row(first, o, a, b, c, n.a0, n.b0, n.c0, n.scale);
  net_row(first + 4u, o, a, b, c, n.a1, n.b1, n.c1, n.scale);
  net_row(first + 8u, o, a, b, c, n.a2, n.b2, n.c2, n.scale);
  net_row(first + 12u, o, a, b, c, n.a3, n.b3, n.c3, n.scale);
  return n;
}

// The ray as the meet of two planes (Kajiya): unit normals a and b = a x d, a perpendicular
// to d. Unit by a division by sqrt, not normalize (whose inverse square root a driver may
// approximate): the planes are the same on both backends.
void patch_planes(rvec3 d, out rvec3 a, out rvec3 b) {
  rvec3 w = (abs(d.x) > abs(d.y) && abs(d.x) > abs(d.z)) ? rvec3(d.y, -d.x, 0.0) : rvec3(0.0, d.z, -d.y);
  precise real len = sqrt(dot(w, w));
  precise rvec3 pa = w / len;
  precise rvec3 pb = cross(pa, d);
  a = pa;
  b = pb;
}

// A piece's square [u0, u1] x [v0, v1] of its patch's parameters, and the square a converged
// point must lie in to be a hit: the piece grown by RC_PATCH_DOMAIN_MARGIN of its width, or
// by RC_PATCH_EDGE_MARGIN at the patch's own edges.
struct patch_domain {
  real u0; real u1; real v0; real v1;
  real lo_u; real hi_u; real lo_v; real hi_v;
};

patch_domain patch_domain_of(packed_quadric q) {
  patch_domain m;
  m.u0 = real(q.diag.x);
  m.u1 = real(q.diag.y);
  m.v0 = real(q.off.x);
  m.v1 = real(q.off.y);
  precise real mu = real(RC_PATCH_DOMAIN_MARGIN) * (m.u1 - m.u0);
  precise real mv = real(RC_PATCH_DOMAIN_MARGIN) * (m.v1 - m.v0);
  real edge = real(RC_PATCH_EDGE_MARGIN);
  m.lo_u = (m.u0 == 0.0) ? -edge : m.u0 - mu;
  m.hi_u = (m.u1 == 1.0) ? 1.0 + edge : m.u1 + mu;
  m.lo_v = (m.v0 == 0.0) ? -edge : m.v0 - mv;
  m.hi_v = (m.v1 == 1.0) ? 1.0 + edge : m.v1 + mv;
  return m;
}

// Where Newton's run ended: (u, v), the residual |F.x| + |F.y| there, whether it converged and
// whether it stayed near the piece, and the weights at (u, v).
struct patch_run {
  real u; real v; real residual;
  bool converged; bool nearby;
  rvec4 bu; rvec4 bv;
};

// A run at the piece's centre, where Newton's method starts.
patch_run patch_start(patch_domain m) {
  patch_run r;
  r.u = 0.5 * (m.u0 + m.u1);
  r.v = 0.5 * (m.v0 + m.v1);
  r.bu = bernstein(r.u);
  r.bv = bernstein(r.v);
  r.residual = real(RC_T_FAR);
  r.converged = false;
  r.nearby = true;
  return r;
}

// F and its Jacobian at the run's point (net_eval's value and slopes of the a and b
// coordinates), and |F.x| + |F.y|; the run keeps the weights (patch_depth's).
void patch_evaluate(patch_net n, inout patch_run r, out rvec4 fa, out rvec4 fb) {
  r.bu = bernstein(r.u);
  r.bv = bernstein(r.v);
  rvec4 su = bernstein_slope(r.u);
  rvec4 sv = bernstein_slope(r.v);
  fa = net_eval(n.a0, n.a1, n.a2, n.a3, r.bu, su, r.bv, sv);
  fb = net_eval(n.b0, n.b1, n.b2, n.b3, r.bu, su, r.bv, sv);
  r.residual = abs(fa.x) + abs(fb.x);
}

// One Newton step from (u, v), F and its Jacobian there in fa and fb (net_eval's value and
// slopes), by Cramer's rule: false where the Jacobian is singular.
bool newton_step(rvec4 fa, rvec4 fb, inout real u, inout real v) {
  precise real det = fa.y * fb.z - fa.z * fb.y;
  if (det == 0.0) return false;
  precise real du = (fa.x * fb.z - fa.z * fb.x) / det;
  precise real dv = (fa.y * fb.x - fa.x * fb.y) / det;
  precise real nu = u - du;
  precise real nv = v - dv;
  u = nu;
  v = nv;
  return true;
}

// The run cert_patch (rc_certify_patch.glsl) took on the piece it certified last, with its t:
// intersect_patch takes it instead of running it again. In the module that certifies, every
// patch test follows its certificate, with the same ray and t_max (test_object; cert_object
// before test_loose_quadrics' test), and the two enter the piece's box alike.
patch_run cert_patch_r;
real cert_patch_t = 0.0;

// Newton's method on F(u, v) = (a.(S - o), b.(S - o)), a and b the ray's planes, from the
// piece's centre: it stops when |F.x| + |F.y| is within RC_PATCH_TOLERANCE_ULPS ulps of the
// net's scale (at the last step RC_PATCH_LAST_TOLERANCE of it), when its Jacobian is
// singular, or when (u, v) leaves the piece by more than the piece's width.
patch_run patch_newton(patch_domain m, patch_net n) {
  precise real tol = real(RC_PATCH_TOLERANCE_ULPS) * RC_UNIT_ROUNDOFF * n.scale;
  precise real last_tol = real(RC_PATCH_LAST_TOLERANCE) * n.scale;
  precise real wu = m.u1 - m.u0;
  precise real wv = m.v1 - m.v0;
  patch_run r = patch_start(m);
  for (uint i = 0u; i < RC_PATCH_NEWTON_STEPS; i++) {
    if (!budget_step()) break;
    rvec4 fa, fb;
    patch_evaluate(n, r, fa, fb);
    bool last = i + 1u == RC_PATCH_NEWTON_STEPS;
    if (r.residual <= tol || (last && r.residual <= last_tol)) {
      r.converged = true;
      break;
    }
    if (last) break;
    if (!newton_step(fa, fb, r.u, r.v)) break;
    r.nearby = r.u >= m.u0 - wu && r.u <= m.u1 + wu && r.v >= m.v0 - wv && r.v <= m.v1 + wv;
    if (!r.nearby) break;
  }
  return r;
}

// t = d.(S - o) at the run's end (the net's third coordinate is along d).
real patch_depth(patch_run r, patch_net n) {
  rvec4 along = rvec4(weigh(r.bu, n.c0), weigh(r.bu, n.c1), weigh(r.bu, n.c2), weigh(r.bu, n.c3));
  precise real t = weigh(r.bv, along);
  return t;
}

// The ray against a patch piece: t of the converged point in (0, t_max], with (u, v, 0),
// else RC_T_FAR. Only a converged point inside the piece's domain is a hit: never a point off
// the ray or off the patch. A run that ends still inside the piece, near the ray, and
// unconverged is counted (patch_stalls) and taken as a miss.
real intersect_patch(uint index, packed_quadric q, rvec3 o, rvec3 d, real t_max, out rvec3 uv) {
  uv = rvec3(0.0);
  real b_in, b_out;
  uint a_in, a_out;
  box_span(rvec3(q.lo), rvec3(q.hi), o - rvec3(q.center), d, b_in, b_out, a_in, a_out);
  if (b_in > b_out || b_out < 0.0 || b_in > t_max * real(RC_BOX_NEAR_SCALE)) return real(RC_T_FAR);
  patch_domain m = patch_domain_of(q);
  patch_run r;
  real t;
  // Not `certify && ` the piece's index, as it was: a SIMD shader ran the other arm's Newton
  // run, masked, in every certified leaf (docs/performance.md, "Patch bounds packed").
  if (certify) {
    r = cert_patch_r;
    t = cert_patch_t;
  } else {
    rvec3 a, b;
    patch_planes(d, a, b);
    patch_net n = load_patch_net(q.mesh_root, o, a, b, d);
    r = patch_newton(m, n);
    t = patch_depth(r, n);
  }
  bool in_piece = r.u >= m.lo_u && r.u <= m.hi_u && r.v >= m.lo_v && r.v <= m.hi_v;
  if (!r.converged) {
    // Near the ray (within a 64th of the piece's box) and inside the piece: a run that
    // Newton's steps did not settle, where a hit may be.
    precise rvec3 extent = rvec3(q.hi) - rvec3(q.lo);
    if (in_piece && r.nearby && r.residual <= max3_abs(extent) * 0.015625) {
      patch_stalls++;
      if (patch_stall_piece == 0u) patch_stall_piece = 1u + index;
    }
    return real(RC_T_FAR);
  }
  if (!in_piece) return real(RC_T_FAR);
  if (t <= 0.0 || t > t_max) return real(RC_T_FAR);
  uv = rvec3(r.u, r.v, 0.0);
  return t;
}

// The patch in the packed space at (u, v): each coordinate's value, slopes along u and v and
// mixed slope (net_eval's), and the net (its scale bounds their rounding).
patch_net patch_eval(packed_quadric q, rvec3 uv, out rvec4 fx, out rvec4 fy, out rvec4 fz) {
  patch_net n = load_patch_net(q.mesh_root, rvec3(0.0), rvec3(1.0, 0.0, 0.0), rvec3(0.0, 1.0, 0.0), rvec3(0.0, 0.0, 1.0));
  rvec4 bu = bernstein(uv.x);
  rvec4 su = bernstein_slope(uv.x);
  rvec4 bv = bernstein(uv.y);
  rvec4 sv = bernstein_slope(uv.y);
  fx = net_eval(n.a0, n.a1, n.a2, n.a3, bu, su, bv, sv);
  fy = net_eval(n.b0, n.b1, n.b2, n.b3, bu, su, bv, sv);
  fz = net_eval(n.c0, n.c1, n.c2, n.c3, bu, su, bv, sv);
  return n;
}

// The patch point at (u, v) in the packed space, its rounding-error bound, and the normal
// dS/du x dS/dv (not normalized). Where one derivative vanishes (a net row or column
// collapsed to a point: the teapot's lid and bottom centres) the normal is the limit along
// the other parameter: dS/du ~ (v - v_edge) d2S/dudv, so d2S/dudv stands in for it, turned
// to point into the patch from that edge; the same for dS/dv.
rvec3 patch_surface(packed_quadric q, rvec3 uv, out rvec3 p, out rvec3 p_error) {
  rvec4 fx, fy, fz;
  patch_net n = patch_eval(q, uv, fx, fy, fz);
  p = rvec3(fx.x, fy.x, fz.x);
  // Two weighings of 4 terms with weights summing to 1 (plus the weights' own rounding):
  // within gamma(16) of the net's largest coordinate, doubled for headroom.
  precise real e = gamma_bound(32.0) * n.scale;
  p_error = rvec3(e, e, e);
  rvec3 pu = rvec3(fx.y, fy.y, fz.y);
  rvec3 pv = rvec3(fx.z, fy.z, fz.z);
  rvec3 puv = rvec3(fx.w, fy.w, fz.w);
  // "Vanishes": below 2^-20 (2^-40 squared: 9.09e-13) of the other derivative, where its own rounding rules it.
  precise real lu = dot(pu, pu);
  precise real lv = dot(pv, pv);
  if (lu < 9.094947017729282e-13 * lv) pu = (uv.y < 0.5) ? puv : -puv;
  else if (lv < 9.094947017729282e-13 * lu) pv = (uv.x < 0.5) ? puv : -puv;
  precise rvec3 g = cross(pu, pv);
  return g;
}
