// rc_certify.glsl: certified decisions (--precision certified; docs/numerics.md §10). While a
// sample is traced in f32, every decision its path makes (a hit or a miss, which of two hits
// is nearer, a shadow ray blocked or not, the side a normal faces) is checked against a bound
// on how far the f32 arithmetic can be from the f64 reference's: the decision is certified
// when its quantity (a discriminant, an edge function, a root against 0 or against t_max...)
// is farther from its threshold than the bound (cert_factor). A sample whose every decision is certified makes the
// reference's decisions; the host re-renders the others in f64.
//
// The f32 ray is not the reference's ray: the camera, each hit point and each spawned origin
// round differently. Each ray therefore carries cert_eo and cert_ed, bounds on the distance
// between its origin and unit direction and the reference's, and each bound below adds what
// that perturbation can change (first order, as pbrt's running error bounds: Pharr, Jakob &
// Humphreys, PBR 4th ed. §6.8; Higham, Accuracy and Stability of Numerical Algorithms §3.1,
// gamma(n) = n u / (1 - n u)). Tests this file has no bound for (bounded quadrics, composites,
// patches, the fast formulas, one-sided triangles) leave their sample
// uncertified whenever a ray tests them: the host re-renders it, so the image stays exact.

bool cert_ok = true;          // every decision of this sample so far is certified
real cert_eo = 0.0;           // |o - o_ref| of the ray being traced
real cert_ed = 0.0;           // |d - d_ref|
real cert_t_err = 0.0;        // the error bound of the root the last test took
real cert_bary_err = 0.0;     // and of its barycentrics (triangles)
real cert_beyond = real(RC_T_FAR);  // the lowest t - bound of roots found past the nearest hit
bool cert_any = false;        // the query is a shadow ray's (any hit up to t_max)
real cert_t_max_err = 0.0;    // the error bound of that t_max
uint cert_spawn_object = 0xffffffffu; // the object the ray leaves (spawned rays)
bool cert_self = false;       // the object being tested is that one
real cert_ep = 0.0;           // |p - p_ref| of the last surface point
real cert_en = 0.0;           // |n - n_ref| of its shading normal
bool cert_hit_ok = false;     // a shadow ray's last object test was certified
bool cert_blocked_later = false; // a shadow ray found an uncertain blocker and looks on
bool cert_blocker_certain = false; // and then found one whose test is certified

// The bound, widened by 2^-20 for the reference's own error, which is the same arithmetic's
// 2^-29 times smaller; half of it or none where frame.certify injects those faults.
real cert_factor() {
  if (frame.certify == RC_CERTIFY_HALVED) return 0.5;
  return (frame.certify == RC_CERTIFY_ZERO) ? 0.0 : 1.00000095367431640625;
}

// The decision `margin > 0` (or `<= 0`) is certified when |margin| exceeds the factor times
// bound; NaN never is.
void cert_require(real margin, real bound) {
  if (!(abs(margin) > cert_factor() * bound)) cert_ok = false;
}

// How far normalize(b) can be from a / |a| when |b - a| <= x |a|, x < 1: the angle between
// them has a sine of at most x, so the chord is at most x / sqrt(1 - x^2) (not the 2 x of
// |b / |b| - a / |a|| <= 2 |b - a| / |a|), plus normalize's own rounding, whose length is
// 1 +/- gamma(8) (a dot product, an inversesqrt of 2 ulp, a product); 2, the most two unit
// vectors can differ by, where x is not small.
real cert_turn(real x) {
  return (x < 0.5) ? x / sqrt(1.0 - x * x) + gamma_bound(8.0) : 2.0;
}

// The same for a vector b of length len at most e from the reference's a, whose length is
// then at least len - e: x = e / (len - e), and 2 where len does not exceed e (no division
// by 0, which a shader may not rely on to give Inf).
real cert_turn_of(real e, real len) { return (len > e) ? cert_turn(e / (len - e)) : 2.0; }

// A decision this file cannot bound.
void cert_fail() { cert_ok = false; }

// The primary ray's perturbation (rc_camera.glsl): the window coordinates us, vs carry
// gamma(4) of |left| + |right| + |us|; the perspective direction -f w + us u + vs v carries
// gamma(3) of its terms' magnitudes (|u| = |v| = |w| = 1) plus those errors, and turns by
// at most that over its length, plus normalize's own rounding; the parallel origin eye + us u + vs v likewise. The basis is the
// reference's too (the same f32 values).
void cert_camera(vec2 raster) {
  packed_camera c = frame.camera;
  real us = real(c.left) + (real(c.right) - real(c.left)) * real(raster.x) / real(c.width);
  real vs = real(c.bottom) + (real(c.top) - real(c.bottom)) * real(raster.y) / real(c.height);
  real eus = gamma_bound(4.0) * (abs(real(c.left)) + abs(real(c.right)) + abs(us));
  real evs = gamma_bound(4.0) * (abs(real(c.bottom)) + abs(real(c.top)) + abs(vs));
  real mag = abs(real(c.focal)) + abs(us) + abs(vs);
  real err = gamma_bound(3.0) * mag + eus + evs;
  cert_ok = true;
  cert_spawn_object = 0xffffffffu;
  if (c.projection == RC_PROJECTION_PERSPECTIVE) {
    real len = length(-real(c.focal) * rvec3(c.w) + us * rvec3(c.u) + vs * rvec3(c.v));
    cert_eo = 0.0;
    cert_ed = err / (len - err) + gamma_bound(4.0);
  } else {
    cert_eo = 2.0 * (gamma_bound(3.0) * (length(rvec3(c.eye)) + abs(us) + abs(vs)) + eus + evs);
    cert_ed = 0.0;
  }
}

// A test whose hit or miss is uncertain, but whose root, if the reference finds one, lies in
// [lo, hi] (bounds already widened by cert_factor): that decision cannot change the query's
// answer where the interval is behind the origin, past a shadow ray's t_max, or past the
// nearest hit (cert_beyond, which cert_closest checks). Where this precision took the root
// (`taken`), it can.
void cert_maybe(real lo, real hi, real t_max, bool taken) {
  if (taken) {
    cert_fail();
    return;
  }
  if (hi < 0.0) return;
  if (cert_any) {
    if (!(lo - t_max > cert_factor() * cert_t_max_err)) cert_fail();
    return;
  }
  cert_beyond = select_min(cert_beyond, lo);
}

// Takes the decisions of a root t with bound e: t > 0 (`ahead`, the test's own verdict, which
// for a spawned ray also drops roots within t's rounding of the origin), and t against t_max.
// A root the test dropped on the object the ray leaves is certified: with the error-bound
// offset the reference's origin is off that surface by more than its own error too (pbrt's
// OffsetRayOrigin), so it drops the root as well. In a closest-hit query t_max is the nearest
// hit so far: a root past it is remembered (cert_beyond) for cert_closest. True when taken.
bool cert_root(real t, real e, real t_max, bool ahead) {
  if (!ahead && cert_self) return false;
  cert_require(t, e);
  if (!ahead) return false;
  if (cert_any) cert_require(t - t_max, e + cert_t_max_err);
  if (!(t <= t_max)) {
    cert_beyond = select_min(cert_beyond, t - cert_factor() * e);
    return false;
  }
  cert_t_err = e;
  return true;
}

// A sphere the ray grazes: the discriminant's sign is uncertain, so the reference may find
// roots where this precision finds none, or none where it finds two. Its roots, if any, are
// -b_ref -/+ sqrt(D_ref) with |b_ref - b| <= e_b and 0 <= D_ref <= D + e_D: near -b. They
// cannot be hit where the ray certainly leaves a sphere it starts outside of (b = f.d > 0
// and c = |f|^2 - r^2 > 0, or the sphere is the one a spawned ray leaves, which both
// precisions' offsets start outside of: both roots behind it), nor where cert_maybe finds
// that interval outside the query. This precision's own roots are those of
// intersect_sphere_geometric.
void cert_sphere_grazing(real disc, real b, real c, real e_disc, real e_b, real e_c, real t_max, real t_near,
                         real t_exit, bool roots, real scale, real rel) {
  real k = cert_factor();
  // This precision's roots, compared with t_max in packed space, with room for a
  // transformed sphere's rounding of the comparison in object space (intersect_any_sphere).
  real reach = t_max + abs(t_max) * 9.5367431640625e-07;
  bool taken = disc >= 0.0 && roots && ((t_near > 0.0 && t_near <= reach) || (t_exit > 0.0 && t_exit <= reach));
  if (!taken && b > k * e_b && (cert_self || c > k * e_c)) return;
  real spread = sqrt(select_max(disc, 0.0) + k * e_disc) + k * e_b;
  real lo = (-b - spread) * scale;
  real hi = (-b + spread) * scale;
  cert_maybe(lo - abs(lo) * rel, hi + abs(hi) * rel, t_max, taken);
}

// The geometric sphere test's decisions (rc_intersect.glsl, intersect_sphere_geometric),
// recomputed, for the ray (o, d) in the sphere's own space. l, the centre's offset from the
// ray's line, moves by |do| + 2 |f| |dd| under the perturbation and by gamma(8) 2 |f| under
// rounding; the discriminant r^2 - |l|^2 by 2 |l| dl + dl^2 and gamma(4) of its terms. The
// root q = -(b + sign(b) sqrt D) carries b's and sqrt's errors, c / q adds c's (which cancels
// for an origin on the sphere). The roots are judged in packed space: times `scale`, their
// bounds too, plus `rel` of them (a transformed sphere's 1 / len and its error). A
// discriminant of uncertain sign is cert_sphere_grazing's to judge.
void cert_sphere_roots(rvec3 o, rvec3 d, packed_sphere s, real t_max, real scale, real rel) {
  real r = real(s.radius);
  precise rvec3 f = o - rvec3(s.center);
  precise real b = dot(f, d);
  precise rvec3 l = f - b * d;
  precise real ll = dot(l, l);
  precise real disc = r * r - ll;
  precise real ff = dot(f, f);
  precise real c = ff - r * r;
  real fm = sqrt(ff);
  real lm = sqrt(ll);
  real el = cert_eo + 2.0 * fm * cert_ed + gamma_bound(8.0) * 2.0 * fm;
  real e_disc = 2.0 * lm * el + el * el + gamma_bound(4.0) * (r * r + ll);
  real e_b = cert_eo + fm * cert_ed + cert_eo * cert_ed + gamma_bound(4.0) * fm;
  real e_c = 2.0 * fm * cert_eo + cert_eo * cert_eo + gamma_bound(4.0) * (ff + r * r);
  bool certain = abs(disc) > cert_factor() * e_disc;
  if (certain && disc < 0.0) return;
  // The test's roots (where disc >= 0), computed once for both cases below: llvmpipe runs
  // every branch a SIMD vector's lanes take, so shared work is work saved.
  precise real sq = sqrt(select_max(disc, 0.0));
  precise real q = (b >= 0.0) ? -(b + sq) : -(b - sq);
  precise real t0 = c / q;
  real t_near = select_min(t0, q) * scale;
  real t_exit = select_max(t0, q) * scale;
  if (!certain) {
    cert_sphere_grazing(disc, b, c, e_disc, e_b, e_c, t_max, t_near, t_exit, q != 0.0, scale, rel);
    return;
  }
  if (q == 0.0) {
    cert_fail();
    return;
  }
  real e_sq = e_disc / (sq + sqrt(select_max(disc - e_disc, 0.0))) + gamma_bound(2.0) * sq;
  real e_q = e_b + e_sq + gamma_bound(2.0) * abs(q);
  real e_t0 = (abs(q) > e_q) ? (e_c + abs(t0) * e_q) / (abs(q) - e_q) + gamma_bound(1.0) * abs(t0) : real(RC_T_FAR);
  real e = select_max(e_q, e_t0);
  if (cert_root(t_near, e * scale + abs(t_near) * rel, t_max, t_near > 0.0)) return;
  cert_root(t_exit, e * scale + abs(t_exit) * rel, t_max, t_exit > 0.0);
}

// Frobenius norm of a transform's linear part: it bounds how far A stretches a vector.
real cert_norm(packed_transform m) {
  return sqrt(dot(rvec3(m.row0.xyz), rvec3(m.row0.xyz)) + dot(rvec3(m.row1.xyz), rvec3(m.row1.xyz)) +
              dot(rvec3(m.row2.xyz), rvec3(m.row2.xyz)));
}

// The error bound of a triangle's t = sum(e z) / det (rc_triangle.glsl, triangle_t), where
// each edge function is off from the reference's by at most ee (the ray's move and rounding),
// each depth by dz (and its own rounding, gamma(3)), and det by e_det. With the reference's
// e + delta and z + zeta, exactly (t' - t)(det + sum delta) = sum delta (z - t) + sum (e +
// delta) zeta: the edge functions' errors weigh the depths' spread about t, not the depths
// themselves, as a bound on the numerator alone (pbrt's) has it. For a small triangle seen
// from afar that is hundreds of times less. Then the numerator's rounding, gamma(3) of its
// terms, and the quotient's and det's, over det.
real cert_triangle_t_error(sheared_triangle st, real t, real det, real e_det, real ee, real dz, real se) {
  if (!(abs(det) > e_det)) return real(RC_T_FAR);
  real sz = abs(st.z.x) + abs(st.z.y) + abs(st.z.z);
  real zt = abs(st.z.x - t) + abs(st.z.y - t) + abs(st.z.z - t) + gamma_bound(8.0) * (sz + 3.0 * abs(t));
  real ez = abs(st.e.x * st.z.x) + abs(st.e.y * st.z.y) + abs(st.e.z * st.z.z);
  real zeta = dz + gamma_bound(3.0) * max3_abs(st.z);
  return (ee * zt + (se + 3.0 * ee) * zeta) / (abs(det) - e_det) + gamma_bound(3.0) * (ez + abs(t) * se) / abs(det);
}

// The watertight test's decisions (rc_triangle.glsl, intersect_triangle), recomputed. A
// sheared coordinate a.x - s.x a.z moves by |do| (1 + |s.x|) and |a.z| ds.x, where ds.x <=
// |dd| (1 + |s.x|) / |d.z|, and rounds by gamma(5) of its terms (pbrt's delta_x); an edge
// function x y' - y x' by the products of those and gamma(2) of its terms. A miss is certified
// by two edge functions of certain opposite signs, a hit by three of certain sign; t's bound
// is cert_triangle_t_error's. Otherwise the ray passes near an edge, and the reference may
// take the hit where this precision does not, or not where it does; either's hit is at the
// plane's t = sum(e z) / sum(e) (det, where the signs agree), whose sum moves by 3 ee and
// rounds by gamma(2) of its terms, and cert_maybe judges that interval. A spawned ray's root
// on the triangle it leaves is dropped by both, as cert_root says. t and its bound are
// computed once for both cases: llvmpipe runs every branch a SIMD vector's lanes take.
void cert_triangle(rvec3 o, ray_shear sh, packed_triangle tri, real t_max) {
  if (triangle_formula != RC_TRIANGLE_WATERTIGHT || (tri.flags & RC_TRIANGLE_ONE_SIDED) != 0u) {
    cert_fail();
    return;
  }
  sheared_triangle st = shear_triangle(o, sh, tri);
  real inv = abs(sh.s.z);
  real sx = abs(sh.s.x);
  real sy = abs(sh.s.y);
  real zr = max3_abs(st.z) / inv;
  real xm = max3_abs(st.x);
  real ym = max3_abs(st.y);
  real dx = cert_eo * (1.0 + sx) + cert_ed * (1.0 + sx) * inv * zr + gamma_bound(5.0) * (xm + 2.0 * sx * zr);
  real dy = cert_eo * (1.0 + sy) + cert_ed * (1.0 + sy) * inv * zr + gamma_bound(5.0) * (ym + 2.0 * sy * zr);
  real ee = 2.0 * (dx * ym + xm * dy + dx * dy) + gamma_bound(2.0) * 2.0 * xm * ym;
  real k = cert_factor() * ee;
  bool pos = st.e.x > k || st.e.y > k || st.e.z > k;
  bool neg = st.e.x < -k || st.e.y < -k || st.e.z < -k;
  if (pos && neg) return;
  real dz = inv * (cert_eo + RC_UNIT_ROUNDOFF * zr) + cert_ed * inv * inv * zr;
  real se = abs(st.e.x) + abs(st.e.y) + abs(st.e.z);
  precise real sum = st.e.x + st.e.y + st.e.z;
  real e_sum = 3.0 * ee + gamma_bound(2.0) * se;
  if (!(abs(sum) > cert_factor() * e_sum)) {
    cert_fail();  // the ray runs along the plane, or the triangle is a sliver
    return;
  }
  real t = triangle_t(st, sum);
  real e_t = cert_triangle_t_error(st, t, sum, e_sum, ee, dz, se);
  bool ahead = t > 0.0 && !(spawned_ray && t <= triangle_t_error(st, sum));
  if (select_min(select_min(abs(st.e.x), abs(st.e.y)), abs(st.e.z)) > k) {
    cert_bary_err = 4.0 * ee / abs(sum);
    cert_root(t, e_t, t_max, ahead);
    return;
  }
  if (!ahead && cert_self) return;
  real det = enclosing_det(st.e);
  bool taken = det != 0.0 && ahead && t <= t_max;
  cert_maybe(t - cert_factor() * e_t, t + cert_factor() * e_t, t_max, taken);
}

#if RC_QUADRICS
// The plane test's decisions (rc_quadric.glsl, intersect_plane): the denominator n.d moves by
// |n| |dd| and rounds by gamma(3) |n| |d|; the numerator n.(o - c) by |n| |do| and gamma(4)
// of |n| (|o| + |c|); t = -fz / vz by both over |vz|.
void cert_plane(packed_quadric q, rvec3 o, rvec3 d, real t_max) {
  rvec3 n = rvec3(q.axis_z);
  real nm = length(n);
  precise rvec3 oc = o - rvec3(q.center);
  precise real fz = dot(n, oc);
  precise real vz = dot(n, d);
  real e_vz = nm * cert_ed + gamma_bound(4.0) * nm;
  real e_fz = nm * cert_eo + gamma_bound(4.0) * dot(abs(n), abs(o) + abs(rvec3(q.center)));
  cert_require(vz, e_vz);
  bool facing = ((q.flags & RC_QUADRIC_ONE_SIDED) == 0u) || vz < 0.0;
  if (vz == 0.0 || !facing || abs(fz) >= abs(vz) * real(RC_T_FAR)) return;
  precise real t = -fz / vz;
  real e_t = (abs(vz) > e_vz) ? (e_fz + abs(t) * e_vz) / (abs(vz) - e_vz) + gamma_bound(1.0) * abs(t) : real(RC_T_FAR);
  cert_root(t, e_t, t_max, t > 0.0);
}
#endif
