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

// The geometric sphere test's decisions (rc_intersect.glsl, intersect_sphere_geometric),
// recomputed, for the ray (o, d) in the sphere's own space. l, the centre's offset from the
// ray's line, moves by |do| + 2 |f| |dd| under the perturbation and by gamma(8) 2 |f| under
// rounding; the discriminant r^2 - |l|^2 by 2 |l| dl + dl^2 and gamma(4) of its terms. The
// root q = -(b + sign(b) sqrt D) carries b's and sqrt's errors, c / q adds c's (which cancels
// for an origin on the sphere). The roots are judged in packed space: times `scale`, their
// bounds too, plus `rel` of them (a transformed sphere's 1 / len and its error).
void cert_sphere_roots(rvec3 o, rvec3 d, packed_sphere s, real t_max, real scale, real rel) {
  real r = real(s.radius);
  precise rvec3 f = o - rvec3(s.center);
  precise real b = dot(f, d);
  precise rvec3 l = f - b * d;
  precise real ll = dot(l, l);
  precise real disc = r * r - ll;
  precise real ff = dot(f, f);
  real fm = sqrt(ff);
  real lm = sqrt(ll);
  real el = cert_eo + 2.0 * fm * cert_ed + gamma_bound(8.0) * 2.0 * fm;
  real e_disc = 2.0 * lm * el + el * el + gamma_bound(4.0) * (r * r + ll);
  cert_require(disc, e_disc);
  if (disc < 0.0) return;
  precise real sq = sqrt(disc);
  precise real q = (b >= 0.0) ? -(b + sq) : -(b - sq);
  if (q == 0.0) {
    cert_fail();
    return;
  }
  precise real c = ff - r * r;
  precise real t0 = c / q;
  real e_sq = e_disc / (sq + sqrt(select_max(disc - e_disc, 0.0))) + gamma_bound(2.0) * sq;
  real e_q = cert_eo + fm * cert_ed + gamma_bound(4.0) * fm + e_sq + gamma_bound(2.0) * abs(q);
  real e_c = 2.0 * fm * cert_eo + cert_eo * cert_eo + gamma_bound(4.0) * (ff + r * r);
  real e_t0 = (abs(q) > e_q) ? (e_c + abs(t0) * e_q) / (abs(q) - e_q) + gamma_bound(1.0) * abs(t0) : real(RC_T_FAR);
  real e = select_max(e_q, e_t0);
  real t_near = select_min(t0, q) * scale;
  real t_exit = select_max(t0, q) * scale;
  if (cert_root(t_near, e * scale + abs(t_near) * rel, t_max, t_near > 0.0)) return;
  cert_root(t_exit, e * scale + abs(t_exit) * rel, t_max, t_exit > 0.0);
}

// Frobenius norm of a transform's linear part: it bounds how far A stretches a vector.
real cert_norm(packed_transform m) {
  return sqrt(dot(rvec3(m.row0.xyz), rvec3(m.row0.xyz)) + dot(rvec3(m.row1.xyz), rvec3(m.row1.xyz)) +
              dot(rvec3(m.row2.xyz), rvec3(m.row2.xyz)));
}

// The watertight test's decisions (rc_triangle.glsl, intersect_triangle), recomputed. A
// sheared coordinate a.x - s.x a.z moves by |do| (1 + |s.x|) and |a.z| ds.x, where ds.x <=
// |dd| (1 + |s.x|) / |d.z|, and rounds by gamma(5) of its terms (pbrt's delta_x); an edge
// function x y' - y x' by the products of those and gamma(2) of its terms. A miss is certified
// by two edge functions of certain opposite signs, a hit by three of certain sign. t = sum(e
// z) / det moves with the edge functions and depths, on top of pbrt's rounding bound.
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
  cert_require(select_min(select_min(abs(st.e.x), abs(st.e.y)), abs(st.e.z)), ee);
  real det = enclosing_det(st.e);
  if (det == 0.0) {
    cert_fail();
    return;
  }
  real t = triangle_t(st, det);
  real dz = inv * (cert_eo + RC_UNIT_ROUNDOFF * zr) + cert_ed * inv * inv * zr;
  real se = abs(st.e.x) + abs(st.e.y) + abs(st.e.z);
  real sz = abs(st.z.x) + abs(st.z.y) + abs(st.z.z);
  real e_t = (se * dz + ee * sz + abs(t) * 3.0 * ee) / abs(det) + triangle_t_error(st, det);
  cert_bary_err = 4.0 * ee / abs(det);
  cert_root(t, e_t, t_max, t > 0.0 && !(spawned_ray && t <= triangle_t_error(st, det)));
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
