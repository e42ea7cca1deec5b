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
// gamma(n) = n u / (1 - n u)). Composites and patches have their own files
// (rc_certify_csg.glsl, rc_certify_patch.glsl); tests no file bounds (the fast formulas) leave
// their sample uncertified whenever a ray tests them: the host re-renders it, so the image
// stays exact.

bool cert_ok = true;          // every decision of this sample so far is certified
uint cert_stage = 0u;         // where its first uncertified decision lies (RC_UNCERTIFIED_*); 0: none
real cert_eo = 0.0;           // |o - o_ref| of the ray being traced, across it (and along it: cert_et)
real cert_et = 0.0;           // |o - o_ref| along it, where the ray's lines are known closer (mirror planes)
real cert_ed = 0.0;           // |d - d_ref|
real cert_t_err = 0.0;        // the error bound of the root the last test took
real cert_bary_err = 0.0;     // and of its barycentrics (triangles)
real cert_off_err = 0.0;      // how far its point may lie off either precision's ray (patches)
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

// Called after each part of the path (rc_trace.glsl): names it as where the sample's first
// uncertified decision lies, if one lies there (the statistics' breakdown).
void cert_note(uint stage) {
  if (!cert_ok && cert_stage == 0u) cert_stage = stage;
}

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
  cert_stage = 0u;
  cert_spawn_object = 0xffffffffu;
  cert_et = 0.0;
  if (c.projection == RC_PROJECTION_PERSPECTIVE) {
    real len = length(-real(c.focal) * rvec3(c.w) + us * rvec3(c.u) + vs * rvec3(c.v));
    cert_eo = 0.0;
    cert_ed = err / (len - err) + gamma_bound(4.0);
  } else {
    cert_eo = 2.0 * (gamma_bound(3.0) * (length(rvec3(c.eye)) + abs(us) + abs(vs)) + eus + evs);
    cert_ed = 0.0;
  }
}

// Whether a shadow ray's answer ignores a root in [lo, hi]: behind the origin or past t_max.
bool cert_shadow_ignores(real lo, real hi, real t_max) {
  real k = cert_factor();
  return hi + k * cert_et < 0.0 || lo - t_max > k * (cert_t_max_err + cert_et);
}

// A test whose hit or miss is uncertain, but whose root, if the reference finds one, lies in
// [lo, hi] (bounds already widened by cert_factor; cert_et more against 0 and t_max, as in
// cert_root_within): that decision cannot change the query's
// answer where the interval is behind the origin, past a shadow ray's t_max, or past the
// nearest hit (cert_beyond, which cert_closest checks). Where this precision took the root
// (`taken`), it can.
void cert_maybe(real lo, real hi, real t_max, bool taken) {
  if (taken) {
    cert_fail();
    return;
  }
  if (cert_any) {
    if (!cert_shadow_ignores(lo, hi, t_max)) cert_fail();
    return;
  }
  if (hi + cert_factor() * cert_et < 0.0) return;
  cert_beyond = select_min(cert_beyond, lo);
}

// Takes the decisions of a root t with bound e: t > 0 (`ahead`, the test's own verdict, which
// for a spawned ray also drops roots within t's rounding of the origin), and t against t_max.
// A root the test dropped on the object the ray leaves is certified: with the error-bound
// offset the reference's origin is off that surface by more than its own error too (pbrt's
// OffsetRayOrigin), so it drops the root as well. In a closest-hit query t_max is the nearest
// hit so far: a root past it is remembered (cert_beyond) for cert_closest. True when taken.
// The reference's root lies in [t - e_down, t + e_up] (cert_root_within), and further by its
// origin's shift along the ray (cert_et) where it is compared with 0 or t_max, not with the
// other roots of the same ray, which shift alike; a root whose bounds are the same both ways
// is cert_root's.
bool cert_root_within(real t, real e_down, real e_up, real t_max, bool ahead) {
  if (!ahead && cert_self) return false;
  real k = cert_factor();
  if (!(ahead ? t > k * (e_down + cert_et) : -t > k * (e_up + cert_et))) cert_ok = false;
  if (!ahead) return false;
  bool within = t <= t_max;
  real e_max = cert_t_max_err + cert_et;
  if (cert_any && !(within ? t_max - t > k * (e_up + e_max) : t - t_max > k * (e_down + e_max))) cert_ok = false;
  if (!within) {
    cert_beyond = select_min(cert_beyond, t - k * e_down);
    return false;
  }
  cert_t_err = select_max(e_down, e_up);
  return true;
}

bool cert_root(real t, real e, real t_max, bool ahead) { return cert_root_within(t, e, e, t_max, ahead); }

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

// Which side of a one-sided triangle the ray meets (rc_triangle.glsl, triangle_facing): the
// facing F = d . N, N = cross(a, b), a = v1 - v0, b = v2 - v0, negative at the front. Each of
// N's components is a difference of two products of rounded differences: it carries gamma(4)
// of those products' magnitudes, gamma(6) of the rounded a's and b's (the f64 reference's
// own rounding is cert_factor's). The dot adds gamma(3) of its terms, and the direction's move
// |dd| |N|, |N| at most N's rounded 1-norm plus its error (cert_facing_error). RC_SIDE_FRONT
// or RC_SIDE_BACK where F's sign is certain (F = 0 counts as behind, as in the test), else RC_SIDE_UNSURE.

// N = a x b of the rounded edges, and e_n, how far each component may lie from the exact one.
rvec3 cert_face_normal(packed_triangle tri, out rvec3 e_n) {
  rvec3 v0 = rvec3(tri.v0);
  rvec3 a = rvec3(tri.v1) - v0;
  rvec3 b = rvec3(tri.v2) - v0;
  e_n = gamma_bound(6.0) * rvec3(abs(a.y * b.z) + abs(a.z * b.y), abs(a.z * b.x) + abs(a.x * b.z),
                                 abs(a.x * b.y) + abs(a.y * b.x));
  return cross(a, b);
}

real cert_facing_error(packed_triangle tri, rvec3 d) {
  rvec3 e_n;
  rvec3 n = cert_face_normal(tri, e_n);
  rvec3 ad = abs(d);
  real n_norm = abs(n.x) + abs(n.y) + abs(n.z) + e_n.x + e_n.y + e_n.z;
  return cert_ed * n_norm + dot(ad, e_n) + gamma_bound(3.0) * dot(ad, abs(n));
}

// How far a point p lies off the plane of a triangle's vertices (exact, as the reference
// takes them), from the unit face normal ng surface_at made of them: |ng.(p - v0)| as
// computed, plus, component by component, that product's rounding and ng's error. ng is
// N / |N| within gamma(8) of each component (normalize); N = a x b lies within e_n of the
// exact cross product (cert_facing_error's bound), which turns the plane's normal by at most
// e_n.|w| / |N| against w and changes its length by rho = |e_n|_1 / |N| at most. Weighted by
// component, the bound for a floor on an axis plane is the point's own offset from it, not a
// fraction of its distance from the far vertex (docs/numerics.md §10).
real cert_triangle_plane_gap(packed_triangle tri, rvec3 ng, rvec3 p) {
  rvec3 e_n;
  rvec3 n = cert_face_normal(tri, e_n);
  precise rvec3 w = p - rvec3(tri.v0);
  real len = length(n);
  real rho = (e_n.x + e_n.y + e_n.z) / len;
  if (!(rho < 0.5)) return real(RC_T_FAR);
  real gap = abs(dot(ng, w)) + gamma_bound(16.0) * dot(abs(ng), abs(w)) + dot(e_n, abs(w)) / len;
  return gap * (1.0 + gamma_bound(8.0)) / (1.0 - rho);
}

uint cert_triangle_side(packed_triangle tri, rvec3 d) {
  real f = triangle_facing(tri, d);
  if (!(abs(f) > cert_factor() * cert_facing_error(tri, d))) return RC_SIDE_UNSURE;
  return (f < 0.0) ? RC_SIDE_FRONT : RC_SIDE_BACK;
}

// The watertight test's edge functions' bound: a sheared coordinate a.x - s.x a.z moves by
// |do| (1 + |s.x|) and |a.z| ds.x, where ds.x <= |dd| (1 + |s.x|) / |d.z|, and rounds by
// gamma(5) of its terms (pbrt's delta_x); an edge function x y' - y x' by the products of
// those and gamma(2) of its terms: for vertices whose sheared |x|, |y| and unscaled depth
// |a.z| are at most xm, ym and zr, componentwise for the three edges.
rvec3 cert_edge_bounds(ray_shear sh, rvec3 xm, rvec3 ym, rvec3 zr) {
  real inv = abs(sh.s.z);
  real sx = abs(sh.s.x);
  real sy = abs(sh.s.y);
  rvec3 dx = cert_eo * (1.0 + sx) + cert_ed * (1.0 + sx) * inv * zr + gamma_bound(5.0) * (xm + 2.0 * sx * zr);
  rvec3 dy = cert_eo * (1.0 + sy) + cert_ed * (1.0 + sy) * inv * zr + gamma_bound(5.0) * (ym + 2.0 * sy * zr);
  return 2.0 * (dx * ym + xm * dy + dx * dy) + gamma_bound(2.0) * 2.0 * xm * ym;
}

// Each edge function's bound (u: b -> c, v: c -> a, w: a -> b, cert_near_edge's numbering),
// from the magnitudes of that edge's own two vertices: an edge shared by two triangles gets
// the same bound in both, so that both find it near the ray or neither does
// (cert_edge_pair). One bound from all three vertices (before 2026-11-29) was as large as the
// largest of these. dz: the depths' bound (cert_triangle_t_error), from all three.
rvec3 cert_edge_errors(sheared_triangle st, ray_shear sh, out real dz) {
  real inv = abs(sh.s.z);
  rvec3 ax = abs(st.x);
  rvec3 ay = abs(st.y);
  rvec3 az = abs(st.depth);
  real zr = max3_abs(st.depth);
  dz = inv * (cert_eo + RC_UNIT_ROUNDOFF * zr) + cert_ed * inv * inv * zr;
  return cert_edge_bounds(sh, max(ax.yzx, ax.zxy), max(ay.yzx, ay.zxy), max(az.yzx, az.zxy));
}

// Whether two edge functions have certainly opposite signs (each beyond its bound k): the
// line certainly misses the triangle.
bool cert_edges_apart(sheared_triangle st, rvec3 k) {
  bool pos = st.e.x > k.x || st.e.y > k.y || st.e.z > k.z;
  bool neg = st.e.x < -k.x || st.e.y < -k.y || st.e.z < -k.z;
  return pos && neg;
}

// The edge of a triangle the ray passes near, as an RC_CERT_EDGE_SHIFT note's low bits: the one
// edge function within k (the edge bound) of 0, and the sign of det, which the other two
// share (they lie beyond k, and two of opposite sign would be a certain miss). RC_CERT_NO_EDGE
// where no edge or more than one is that near (a vertex).
uint cert_near_edge(rvec3 e, real sum, rvec3 k) {
  bool nx = abs(e.x) <= k.x;
  bool ny = abs(e.y) <= k.y;
  bool nz = abs(e.z) <= k.z;
  uint edge = nx ? 0u : (ny ? 1u : 2u);
  uint near = (nx ? 1u : 0u) + (ny ? 1u : 0u) + (nz ? 1u : 0u);
  return (near == 1u) ? ((edge << 1u) | (sum < 0.0 ? 1u : 0u)) : RC_CERT_NO_EDGE;
}

// Whether two notes (RC_CERT_EDGE_SHIFT) name one edge of two triangles (the same two vertices,
// exactly, in either order) that lie on its two sides as the ray sees them. Both precisions
// compute the edge's function in both triangles from the same two sheared vertices, as
// exact negatives (reversed) or the same value (one way), and each triangle's other two edge
// functions certainly have its det's sign. So where the triangles lie apart (det signs equal
// for a reversed edge, opposite for one way: not a fold, where the ray sees a silhouette)
// the edge function has the sign that puts the line in one of them, or is 0, which
// edge_owned gives to exactly one: in each precision triangle_crossing crosses exactly one of
// the two. Where it crosses then lies in either's t interval; which triangle it is does not.
// A certain det excludes an edge the ray runs along (its two projected vertices equal: det 0).
bool cert_edge_pair(uint a, uint b) {
  uint ta = a >> RC_CERT_EDGE_SHIFT;
  uint tb = b >> RC_CERT_EDGE_SHIFT;
  uint ea = (a >> 1u) & 3u;
  uint eb = (b >> 1u) & 3u;
  // Edge e runs from vertex (e + 1) mod 3 to (e + 2) mod 3: four fetches, not two triangles'
  // six, as llvmpipe runs this for every certified walk of a mesh operand, notes or none.
  vec3 pa = load_triangle_vertex(ta, (ea + 1u) % 3u);
  vec3 qa = load_triangle_vertex(ta, (ea + 2u) % 3u);
  vec3 pb = load_triangle_vertex(tb, (eb + 1u) % 3u);
  vec3 qb = load_triangle_vertex(tb, (eb + 2u) % 3u);
  bool reversed = all(equal(pa, qb)) && all(equal(qa, pb));
  bool same = all(equal(pa, pb)) && all(equal(qa, qb));
  bool neg_a = (a & 1u) != 0u;
  bool neg_b = (b & 1u) != 0u;
  return ta != tb && (reversed ? neg_a == neg_b : (same && neg_a != neg_b));
}

// The watertight test's decisions (rc_triangle.glsl, intersect_triangle), recomputed with
// cert_edge_errors' bounds. A miss is certified
// by two edge functions of certain opposite signs, a hit by three of certain sign; t's bound
// is cert_triangle_t_error's. Otherwise the ray passes near an edge, and the reference may
// take the hit where this precision does not, or not where it does; either's hit is at the
// plane's t = sum(e z) / sum(e) (det, where the signs agree), whose sum moves by the three
// edges' bounds and rounds by gamma(2) of its terms, and cert_maybe judges that interval. A
// spawned ray's root on the triangle it leaves is dropped by both, as cert_root says. t and its bound are
// computed once for both cases: llvmpipe runs every branch a SIMD vector's lanes take.
//
// side_unsure: a one-sided triangle whose side cert_triangle_side could not certify. Either
// precision may then test the triangle where the other skips it, and only a certain miss
// agrees with both.
void cert_triangle(rvec3 o, ray_shear sh, packed_triangle tri, real t_max, bool side_unsure) {
  if (triangle_formula != RC_TRIANGLE_WATERTIGHT) {
    cert_fail();
    return;
  }
  sheared_triangle st = shear_triangle(o, sh, tri);
  real dz;
  rvec3 ee = cert_edge_errors(st, sh, dz);
  rvec3 k = cert_factor() * ee;
  if (cert_edges_apart(st, k)) return;
  if (side_unsure) {
    cert_fail();
    return;
  }
  real se = abs(st.e.x) + abs(st.e.y) + abs(st.e.z);
  precise real sum = st.e.x + st.e.y + st.e.z;
  real e_sum = ee.x + ee.y + ee.z + gamma_bound(2.0) * se;
  if (!(abs(sum) > cert_factor() * e_sum)) {
    cert_fail();  // the ray runs along the plane, or the triangle is a sliver
    return;
  }
  real e_max = max3_abs(ee);
  real t = triangle_t(st, sum);
  real e_t = cert_triangle_t_error(st, t, sum, e_sum, e_max, dz, se);
  bool ahead = t > 0.0 && !(spawned_ray && t <= triangle_t_error(st, sum));
  if (abs(st.e.x) > k.x && abs(st.e.y) > k.y && abs(st.e.z) > k.z) {
    cert_bary_err = 4.0 * e_max / abs(sum);
    cert_root(t, e_t, t_max, ahead);
    return;
  }
  if (!ahead && cert_self) return;
  real det = enclosing_det(st.e);
  bool taken = det != 0.0 && ahead && t <= t_max;
  cert_maybe(t - cert_factor() * e_t, t + cert_factor() * e_t, t_max, taken);
}

// triangle_crossing's decision for the ray's whole line, certified with cert_triangle's
// bounds: 0 where the line certainly does not cross, 1 where it certainly does (t, its bound
// e), 2 where it passes within the bound of an edge: the neighbour across the edge may own
// the crossing instead (another normal), or at a silhouette both or neither cross; the
// crossing, if any, then lies in the plane's t +/- e. 3 where the triangle is edge-on (no
// interval). A spawned ray's crossing that the test pins at 0 (the surface it leaves) keeps
// that value, its bound grown by the distance it was moved.
uint cert_crossing(rvec3 o, ray_shear sh, packed_triangle tri, out real t, out real e, out uint near) {
  t = real(RC_T_FAR);
  e = 0.0;
  near = RC_CERT_NO_EDGE;
  sheared_triangle st = shear_triangle(o, sh, tri);
  real dz;
  rvec3 ee = cert_edge_errors(st, sh, dz);
  rvec3 k = cert_factor() * ee;
  if (cert_edges_apart(st, k)) return 0u;
  real se = abs(st.e.x) + abs(st.e.y) + abs(st.e.z);
  precise real sum = st.e.x + st.e.y + st.e.z;
  real e_sum = ee.x + ee.y + ee.z + gamma_bound(2.0) * se;
  if (!(abs(sum) > cert_factor() * e_sum)) return 3u;
  t = triangle_t(st, sum);
  e = cert_triangle_t_error(st, t, sum, e_sum, max3_abs(ee), dz, se);
  if (spawned_ray && abs(t) <= triangle_t_error(st, sum)) {
    e += abs(t);
    t = 0.0;
  }
  near = cert_near_edge(st.e, sum, k);
  return (abs(st.e.x) > k.x && abs(st.e.y) > k.y && abs(st.e.z) > k.z) ? 1u : 2u;
}

#if RC_QUADRICS
// The plane test's decisions (rc_quadric.glsl, intersect_plane): the denominator n.d moves by
// |n| |dd| and rounds by gamma(3) |n| |d|; the numerator n.(o - c) by |n| |do| and gamma(4)
// of |n| (|o| + |c|). The reference's root -fz / vz then has a magnitude between
// (|fz| - e_fz) / (|vz| + e_vz) and (|fz| + e_fz) / (|vz| - e_vz), and t is within its
// quotient's rounding of that: a ray nearly parallel to the plane has a root far away whose
// upper bound is far larger still, but whose lower bound, all that its decisions against
// t_max need, stays near t.
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
  real near = select_max(abs(fz) - e_fz, 0.0) / (abs(vz) + e_vz);
  real far = (abs(vz) > e_vz) ? (abs(fz) + e_fz) / (abs(vz) - e_vz) : real(RC_T_FAR);
  real rounding = gamma_bound(1.0) * abs(t);
  real e_down = ((t > 0.0) ? abs(t) - near : far - abs(t)) + rounding;
  real e_up = ((t > 0.0) ? far - abs(t) : abs(t) - near) + rounding;
  cert_root_within(t, e_down, e_up, t_max, t > 0.0);
}

// |M| v for the quadric's symmetric part and v >= 0: bounds |M w| componentwise wherever
// |w| <= v componentwise.
rvec3 cert_abs_apply(packed_quadric q, rvec3 v) {
  rvec3 D = abs(rvec3(q.diag));
  rvec3 O = abs(rvec3(q.off));
  return rvec3(D.x * v.x + O.x * v.y + O.y * v.z, O.x * v.x + D.y * v.y + O.z * v.z, O.y * v.x + O.z * v.y + D.z * v.z);
}

// How far quadric_local(q, x) can be from the reference's, componentwise, where x is at most
// e from the reference's x and its terms have magnitudes `mag`: each row r moves by |r| e and
// rounds by gamma(n) of |r|.mag (a dot product, and for a point the subtraction before it).
rvec3 cert_local_error(packed_quadric q, rvec3 mag, real e, real n) {
  rvec3 ax = rvec3(q.axis_x);
  rvec3 ay = rvec3(q.axis_y);
  rvec3 az = rvec3(q.axis_z);
  return e * rvec3(length(ax), length(ay), length(az)) +
         gamma_bound(n) * rvec3(dot(abs(ax), mag), dot(abs(ay), mag), dot(abs(az), mag));
}

// One slab of box_span, recomputed with bounds: ta = (lo - f) / v moves by the numerator's
// error (ef, and the subtraction's rounding) and by v's (ev) over |v| - ev, and rounds once
// more. The slab's entry tn and exit tx, and the larger error e. A slab whose v may have
// either sign (|v| within its bound) gives no ends (-/+ RC_T_FAR, error 0): it is
// cert_slab_parallel's. False for such a slab.
bool cert_slab(real lo, real hi, real f, real v, real ef, real ev, out real tn, out real tx, out real e) {
  tn = -real(RC_T_FAR);
  tx = real(RC_T_FAR);
  e = 0.0;
  if (!(abs(v) > cert_factor() * ev)) return false;
  precise real ta = (lo - f) / v;
  precise real tb = (hi - f) / v;
  real ea = (abs(v) > ev) ? (ef + gamma_bound(1.0) * abs(lo - f) + abs(ta) * ev) / (abs(v) - ev) + gamma_bound(1.0) * abs(ta)
                          : real(RC_T_FAR);
  real eb = (abs(v) > ev) ? (ef + gamma_bound(1.0) * abs(hi - f) + abs(tb) * ev) / (abs(v) - ev) + gamma_bound(1.0) * abs(tb)
                          : real(RC_T_FAR);
  tn = select_min(ta, tb);
  tx = select_max(ta, tb);
  e = select_max(ea, eb);
  return true;
}

// The span's end among three slabs' (the largest entry for s = 1, the smallest exit for
// s = -1) and its error e; `sure` when each other slab's end lies on the losing side by more
// than both bounds, so that the reference's end is on the same face. Otherwise the error is
// the largest of the three (a max or a min moves by no more than its arguments).
real cert_span_end(real s, real t0, real e0, real t1, real e1, real t2, real e2, out real e, out bool sure) {
  real k = cert_factor();
  real w = t0;
  e = e0;
  if (s * t1 > s * w) {
    w = t1;
    e = e1;
  }
  if (s * t2 > s * w) {
    w = t2;
    e = e2;
  }
  uint lose = 0u;
  if (t0 == w || s * (w - t0) > k * (e + e0)) lose++;
  if (t1 == w || s * (w - t1) > k * (e + e1)) lose++;
  if (t2 == w || s * (w - t2) > k * (e + e2)) lose++;
  uint wins = ((t0 == w) ? 1u : 0u) + ((t1 == w) ? 1u : 0u) + ((t2 == w) ? 1u : 0u);
  sure = lose == 3u && wins == 1u;
  if (!sure) e = select_max(e0, select_max(e1, e2));
  return w;
}

// A slab the ray runs nearly parallel to (cert_slab's left-overs). Along the span [-reach_t,
// reach_t] of the other slabs, f + t v stays within ef + reach_t (|v| + ev) of f for both
// precisions, and each one's ta, tb lie beyond the span: the slab changes nothing where f is
// inside it by more than that, and empties the span where f is outside by more. 1: inside
// (or not parallel), 0: outside, 2: uncertain.
uint cert_slab_parallel(real lo, real hi, real f, real v, real ef, real ev, real reach_t) {
  if (abs(v) > cert_factor() * ev) return 1u;
  real reach = cert_factor() * (ef + reach_t * (abs(v) + ev));
  if (f - lo > reach && hi - f > reach) return 1u;
  if (lo - f > reach || f - hi > reach) return 0u;
  return 2u;
}

// box_span's decisions for the box [lo, hi] and the ray (f, v) in its frame (a quadric's, or
// the scene's for a BVH node), f and v at most ef and ev (componentwise) from the
// reference's: the span [b_in, b_out], its ends' errors e_in and e_out, and whether the entry
// and exit faces are certain (`sure`, bits 1 and 2). Returns 0 where the box is certainly
// missed, 1 where it is certainly met, 2 where that is uncertain.
uint cert_box(rvec3 lo, rvec3 hi, rvec3 f, rvec3 v, rvec3 ef, rvec3 ev, out real b_in, out real b_out, out real e_in,
              out real e_out, out uint sure) {
  real nx, xx, ex, ny, xy, ey, nz, xz, ez;
  cert_slab(lo.x, hi.x, f.x, v.x, ef.x, ev.x, nx, xx, ex);
  cert_slab(lo.y, hi.y, f.y, v.y, ef.y, ev.y, ny, xy, ey);
  cert_slab(lo.z, hi.z, f.z, v.z, ef.z, ev.z, nz, xz, ez);
  bool sure_in, sure_out;
  b_in = cert_span_end(1.0, nx, ex, ny, ey, nz, ez, e_in, sure_in);
  b_out = cert_span_end(-1.0, xx, ex, xy, ey, xz, ez, e_out, sure_out);
  real e_span = select_max(e_in, e_out);
  sure = (sure_in ? 1u : 0u) | (sure_out ? 2u : 0u);
  real k = cert_factor();
  real reach_t = select_max(abs(b_in), abs(b_out)) + k * e_span;
  uint px = cert_slab_parallel(lo.x, hi.x, f.x, v.x, ef.x, ev.x, reach_t);
  uint py = cert_slab_parallel(lo.y, hi.y, f.y, v.y, ef.y, ev.y, reach_t);
  uint pz = cert_slab_parallel(lo.z, hi.z, f.z, v.z, ef.z, ev.z, reach_t);
  if (px == 0u || py == 0u || pz == 0u) return 0u;
  if (b_in - b_out > k * 2.0 * e_span) return 0u;
  if (px == 2u || py == 2u || pz == 2u || !(b_out - b_in > k * 2.0 * e_span)) return 2u;
  return 1u;
}

// The quadric's coefficients (quadric_roots) a, h, c and discriminant, recomputed, and their
// errors. At f32's own (f, v) the exact a = v.Mv, h = f.Mv + L.v and c = f.Mf + 2 L.f + J are
// off from the computed ones by their rounding (gamma(6), gamma(7), gamma(8) of the terms'
// magnitudes); from the reference's (f + df, v + dv) by exactly
//   da = 2 Mv.dv + dv.M dv,  dh = Mv.df + (Mf + L).dv + df.M dv,  dc = 2 (Mf + L).df + df.M df,
// bounded with |M|. The exact discriminant h^2 - a c then moves by exactly
//   2 h dh + dh^2 - a dc - c da - da dc = G_f.df + G_v.dv + 2 h df.M dv + dh^2 - a df.M df
//                                         - c dv.M dv - da dc,
// with its gradient G_f = 2 (h Mv - a (Mf + L)), G_v = 2 (h (Mf + L) - c Mv): the gradient, not
// the magnitudes of its terms, which cancel (for a sphere |G_f| = 2 |l|, the ray's distance
// from the centre, against 4 |f| term by term: the bound was ten times wider for a ray that
// meets a cylinder head-on). G is computed here, plus its rounding. The computed
// discriminant (Lagrange's form for a diagonal M, else h^2 - a c) adds the rounding of its
// own terms from f32's values. Returns the discriminant's error bound.
real cert_quadric_terms(packed_quadric q, rvec3 f, rvec3 v, rvec3 ef, rvec3 ev, out real a, out real h, out real c,
                        out real disc, out real e_a, out real e_h, out real e_c) {
  rvec3 D = rvec3(q.diag);
  rvec3 L = rvec3(q.linear);
  real J = real(q.constant);
  quadric_terms k = quadric_coefficients(q, f, v);
  a = k.a;
  h = k.h;
  c = k.c;
  disc = quadric_discriminant(q, f, v, k);
  rvec3 av = abs(v);
  rvec3 af = abs(f);
  rvec3 al = abs(L);
  rvec3 mav = cert_abs_apply(q, av);
  rvec3 maf = cert_abs_apply(q, af);
  real ra = gamma_bound(6.0) * dot(av, mav);
  real rm = gamma_bound(6.0) * dot(af, mav);
  real rld = gamma_bound(3.0) * dot(al, av);
  real rlf = gamma_bound(3.0) * dot(al, af);
  real rh = rm + rld + gamma_bound(1.0) * abs(k.h);
  real rc = gamma_bound(8.0) * (dot(af, maf) + 2.0 * dot(al, af) + abs(J));
  rvec3 gv = abs(k.mv) + gamma_bound(3.0) * mav;
  rvec3 mfl = k.mf + L;
  rvec3 gf = abs(mfl) + gamma_bound(4.0) * (maf + al);
  real pa = 2.0 * dot(gv, ev) + dot(ev, cert_abs_apply(q, ev));
  real ph = dot(gv, ef) + dot(gf, ev) + dot(ef, cert_abs_apply(q, ev));
  real pc = 2.0 * dot(gf, ef) + dot(ef, cert_abs_apply(q, ef));
  e_a = ra + pa;
  e_h = rh + ph;
  e_c = rc + pc;
  real hm = abs(k.h) + rh;
  real am = abs(k.a) + ra;
  real cm = abs(k.c) + rc;
  rvec3 grad_f = abs(2.0 * (k.h * k.mv - k.a * mfl)) + 2.0 * (rh * gv + ra * gf) + gamma_bound(8.0) * 2.0 * (abs(k.h) * gv + abs(k.a) * gf);
  rvec3 grad_v = abs(2.0 * (k.h * mfl - k.c * k.mv)) + 2.0 * (rh * gf + rc * gv) + gamma_bound(8.0) * 2.0 * (abs(k.h) * gf + abs(k.c) * gv);
  real moved = dot(grad_f, ef) + dot(grad_v, ev) + 2.0 * hm * dot(ef, cert_abs_apply(q, ev)) + ph * ph +
               am * dot(ef, cert_abs_apply(q, ef)) + cm * dot(ev, cert_abs_apply(q, ev)) + pa * pc;
  real rounded;
  if (q.off == vec3(0.0)) {
    rvec3 w = quadric_minors(f, v);
    real exy = gamma_bound(2.0) * (abs(v.x * f.y) + abs(v.y * f.x));
    real exz = gamma_bound(2.0) * (abs(v.x * f.z) + abs(v.z * f.x));
    real eyz = gamma_bound(2.0) * (abs(v.y * f.z) + abs(v.z * f.y));
    real dxy = abs(D.x * D.y);
    real dxz = abs(D.x * D.z);
    real dyz = abs(D.y * D.z);
    real terms = dxy * w.x * w.x + dxz * w.y * w.y + dyz * w.z * w.z + 2.0 * abs(k.m * k.ld) + 2.0 * abs(k.a * k.lf) + k.ld * k.ld +
                 abs(k.a * J);
    rounded = dxy * (2.0 * abs(w.x) * exy + exy * exy) + dxz * (2.0 * abs(w.y) * exz + exz * exz) +
              dyz * (2.0 * abs(w.z) * eyz + eyz * eyz) + 2.0 * (abs(k.m) * rld + abs(k.ld) * rm + rm * rld) +
              2.0 * (abs(k.a) * rlf + abs(k.lf) * ra + ra * rlf) + 2.0 * abs(k.ld) * rld + rld * rld + abs(J) * ra +
              gamma_bound(12.0) * terms;
  } else {
    rounded = 2.0 * abs(k.h) * rh + rh * rh + abs(k.a) * rc + abs(k.c) * ra + ra * rc + gamma_bound(2.0) * (k.h * k.h + abs(k.a * k.c));
  }
  return moved + rounded;
}

// An open quadric surface's root t (bound e) against the box span (intersect_quadric_surface):
// taken where it lies certainly in the box, not where certainly outside, and in between the
// reference may take it where this precision does not or the other way round (cert_maybe).
// True when this precision takes it.
bool cert_surface_root(real t, real e, real b_in, real b_out, real e_in, real e_out, real t_max) {
  real k = cert_factor();
  real m_in = t - b_in;
  real m_out = b_out - t;
  if (m_in < -k * (e + e_in) || m_out < -k * (e + e_out)) return false;
  if (m_in > k * (e + e_in) && m_out > k * (e + e_out)) return cert_root(t, e, t_max, t > 0.0);
  bool taken = t > 0.0 && t <= t_max && m_in >= 0.0 && m_out >= 0.0;
  cert_maybe(t - k * e, t + k * e, t_max, taken);
  return taken;
}

// One end t of a solid's clipped piece (solid_intervals): the box face's t (`box`, error
// e_box) or the root's (`quad`, e_quad; -/+ RC_T_FAR for an open end), whichever the clip
// keeps: where the clip's choice is certain, the chosen one's error, else the larger of
// theirs (a max or a min moves by no more than its arguments). Taken as cert_root says;
// where taken, the surface it lies on must be certain too: the clip's choice, and for a box
// face the axis that won the span (`face_sure`). True when taken.
bool cert_solid_end(real t, bool on_box, real box, real e_box, real quad, real e_quad, bool face_sure, real t_max) {
  bool side_sure = !(abs(quad) < real(RC_T_FAR)) || abs(box - quad) > cert_factor() * (e_box + e_quad);
  real e = side_sure ? (on_box ? e_box : e_quad) : select_max(e_box, e_quad);
  if (!cert_root(t, e, t_max, t > 0.0)) return false;
  if (!side_sure || (on_box && !face_sure)) cert_fail();
  return true;
}

// A solid's pieces (solid_intervals) and the first end in (0, t_max] (first_interval_end),
// for the roots [t_lo, t_hi] (error e_r) of a quadric of the given kind. A piece whose
// existence is uncertain (its ends within their bounds of each other) is cert_maybe's.
void cert_solid(uint kind, real t_lo, real t_hi, real e_r, real b_in, real b_out, real e_in, real e_out, uint sure,
                real t_max) {
  real k = cert_factor();
  real lo0 = (kind == RC_QR_BETWEEN) ? t_lo : -real(RC_T_FAR);
  real hi0 = (kind == RC_QR_OUTSIDE) ? t_lo : ((kind == RC_QR_BETWEEN) ? t_hi : real(RC_T_FAR));
  uint pieces = (kind == RC_QR_OUTSIDE) ? 2u : 1u;
  for (uint p = 0u; p < pieces; p++) {
    real lo = (p == 0u) ? lo0 : t_hi;
    real hi = (p == 0u) ? hi0 : real(RC_T_FAR);
    real e_lo = (abs(lo) < real(RC_T_FAR)) ? e_r : 0.0;
    real e_hi = (abs(hi) < real(RC_T_FAR)) ? e_r : 0.0;
    bool box_starts = b_in >= lo;
    bool box_ends = b_out <= hi;
    real s = box_starts ? b_in : lo;
    real e = box_ends ? b_out : hi;
    real e_s = select_max(e_in, e_lo);
    real e_e = select_max(e_out, e_hi);
    if (s - e > k * (e_s + e_e)) continue;
    if (!(e - s > k * (e_s + e_e))) {
      bool taken = s <= e && ((s > 0.0 && s <= t_max) || (e > 0.0 && e <= t_max));
      cert_maybe(select_min(s, e) - k * select_max(e_s, e_e), select_max(s, e) + k * select_max(e_s, e_e), t_max, taken);
      if (taken) return;
      continue;
    }
    if (cert_solid_end(s, box_starts, b_in, e_in, lo, e_lo, (sure & 1u) != 0u, t_max)) return;
    if (cert_solid_end(e, box_ends, b_out, e_out, hi, e_hi, (sure & 2u) != 0u, t_max)) return;
  }
}

// quadric_roots' kind and roots for the ray (f, v) in the quadric's frame, whose box span is
// [b_in, b_out] (errors e_in, e_out): the coefficients (cert_quadric_terms), then the roots
// as the sphere's, q = -(h + sign(h) sqrt(disc)) with sqrt's error, q / a and c / q each with
// the quotient's: t_lo <= t_hi and their bound e_r. Only the named shapes' kinds are bounded:
// a ray along which the quadric is linear (a = 0) is certain only for a box (no quadratic or
// linear part), and a grazing ray only where a > 0 (the roots, if any, near -h / a), unless
// it leaves the surface (both roots behind); a root pinned at RC_T_FAR is not bounded. Those
// two judge only the roots ahead, and are decided here (certified, cert_maybe's, or failed);
// for a composite's operand (`whole`), whose every end counts, a grazing ray fails. False
// where the decision was made here; true where the caller goes on with the kind.
bool cert_quadric_kind(packed_quadric q, rvec3 f, rvec3 v, rvec3 ef, rvec3 ev, real b_in, real b_out, real e_in,
                       real e_out, real t_max, bool whole, out uint kind, out real t_lo, out real t_hi, out real e_r) {
  real k = cert_factor();
  kind = RC_QR_NONE;
  t_lo = 0.0;
  t_hi = 0.0;
  e_r = 0.0;
  real a, h, c, disc, e_a, e_h, e_c;
  real e_disc = cert_quadric_terms(q, f, v, ef, ev, a, h, c, disc, e_a, e_h, e_c);
  if (a == 0.0 && e_a == 0.0 && h == 0.0 && e_h == 0.0) {
    cert_require(c, e_c);
    kind = (c <= 0.0) ? RC_QR_ALL : RC_QR_NONE;
    return true;
  }
  if (!(abs(a) > k * e_a)) {
    cert_fail();
    return false;
  }
  if (!whole && a > 0.0 && h > k * e_h && (c > k * e_c || (cert_self && c > 0.0))) {
    // Q(t) = a t^2 + 2 h t + c with a, h and c all positive has no root ahead: a ray leaving
    // a surface that curves towards it, from outside (c > 0 beyond its bound, or the surface
    // a spawned ray leaves, whose error-bound offset puts both precisions' origins on the
    // side its normal points to), as the sphere's leaving rays (cert_sphere_grazing).
    return false;
  }
  if (!(abs(disc) > k * e_disc)) {
    if (a < 0.0 || whole) {
      cert_fail();
      return false;
    }
    real spread = sqrt(select_max(disc, 0.0) + k * e_disc) + k * e_h;
    real a_lo = a - k * e_a;
    real a_hi = a + k * e_a;
    real lo = select_min((-h - spread) / a_lo, (-h - spread) / a_hi);
    real hi = select_max((-h + spread) / a_lo, (-h + spread) / a_hi);
    lo = select_max(lo - gamma_bound(3.0) * abs(lo), b_in - k * e_in);
    hi = select_min(hi + gamma_bound(3.0) * abs(hi), b_out + k * e_out);
    if (lo <= hi) cert_maybe(lo, hi, t_max, disc >= 0.0 && hi > 0.0 && lo <= t_max);
    return false;
  }
  if (disc < 0.0) {
    kind = (a > 0.0) ? RC_QR_NONE : RC_QR_ALL;
    return true;
  }
  precise real sq = sqrt(disc);
  precise real qq = (h >= 0.0) ? -(h + sq) : -(h - sq);
  if (qq == 0.0 || abs(qq) >= abs(a) * real(RC_T_FAR) || abs(c) >= abs(qq) * real(RC_T_FAR)) {
    cert_fail();
    return false;
  }
  precise real r0 = qq / a;
  precise real r1 = c / qq;
  real e_sq = e_disc / (sq + sqrt(select_max(disc - e_disc, 0.0))) + gamma_bound(2.0) * sq;
  real e_q = e_h + e_sq + gamma_bound(2.0) * abs(qq);
  real e_r0 = (abs(a) > e_a) ? (e_q + abs(r0) * e_a) / (abs(a) - e_a) + gamma_bound(1.0) * abs(r0) : real(RC_T_FAR);
  real e_r1 = (abs(qq) > e_q) ? (e_c + abs(r1) * e_q) / (abs(qq) - e_q) + gamma_bound(1.0) * abs(r1) : real(RC_T_FAR);
  e_r = select_max(e_r0, e_r1);
  t_lo = select_min(r0, r1);
  t_hi = select_max(r0, r1);
  kind = (a > 0.0) ? RC_QR_BETWEEN : RC_QR_OUTSIDE;
  return true;
}

// The ray in the quadric's frame, f and v with their errors ef and ev (cert_local_error: the
// ray's perturbation through the frame's rows and their rounding), and its box's decisions
// (cert_box, whose result it returns): what a bounded quadric's certificate and a
// composite leaf's both start from.
uint cert_quadric_box(packed_quadric q, rvec3 o, rvec3 d, out rvec3 f, out rvec3 v, out rvec3 ef, out rvec3 ev,
                      out real b_in, out real b_out, out real e_in, out real e_out, out uint sure) {
  f = quadric_local(q, o - rvec3(q.center));
  v = quadric_local(q, d);
  ef = cert_local_error(q, abs(o) + abs(rvec3(q.center)), cert_eo, 4.0);
  ev = cert_local_error(q, abs(d), cert_ed, 3.0);
  return cert_box(rvec3(q.lo), rvec3(q.hi), f, v, ef, ev, b_in, b_out, e_in, e_out, sure);
}

// A bounded quadric's decisions (intersect_quadric: a surface or a solid in its box), in the
// quadric's frame (cert_quadric_box: the ray there and the box); the kind and roots
// (cert_quadric_kind), then one
// inlined copy of the solid's and one of the surface's decisions: a SIMD shader runs every
// copy.
void cert_quadric(packed_quadric q, rvec3 o, rvec3 d, real t_max) {
  rvec3 f, v, ef, ev;
  real b_in, b_out, e_in, e_out;
  uint sure;
  uint box = cert_quadric_box(q, o, d, f, v, ef, ev, b_in, b_out, e_in, e_out, sure);
  if (box == 0u) return;
  if (box == 2u) {
    cert_fail();
    return;
  }
  uint kind;
  real t_lo, t_hi, e_r;
  if (!cert_quadric_kind(q, f, v, ef, ev, b_in, b_out, e_in, e_out, t_max, false, kind, t_lo, t_hi, e_r)) return;
  if (kind == RC_QR_NONE) return;
  if ((q.flags & RC_QUADRIC_SOLID) != 0u) {
    cert_solid(kind, t_lo, t_hi, e_r, b_in, b_out, e_in, e_out, sure, t_max);
    return;
  }
  if (kind == RC_QR_ALL) return;
  if (cert_surface_root(t_lo, e_r, b_in, b_out, e_in, e_out, t_max)) return;
  cert_surface_root(t_hi, e_r, b_in, b_out, e_in, e_out, t_max);
}

// How far a quadric surface's normal normalize(R^T (M R (p - c) + L)) (quadric_normal) can
// turn where p is at most ep from the reference's: f = R (p - c) moves by ||R|| ep and rounds
// as cert_local_error says, g = M f + L by ||M|| of that and gamma(4) of |M||f| + |L|, and
// R^T g by ||R|| of g's move and gamma(3) of its terms; then cert_turn_of. The spectral norms
// are bounded by Gershgorin's circles: ||M|| by M's largest absolute row sum (M symmetric),
// ||R||^2 by that of the rows' Gram matrix (1 for an orthonormal frame, where the Frobenius
// norm says sqrt(3)).
real cert_quadric_normal(packed_quadric q, rvec3 p, real ep) {
  rvec3 ax = rvec3(q.axis_x);
  rvec3 ay = rvec3(q.axis_y);
  rvec3 az = rvec3(q.axis_z);
  rvec3 L = rvec3(q.linear);
  real gx = abs(dot(ax, ax)) + abs(dot(ax, ay)) + abs(dot(ax, az));
  real gy = abs(dot(ay, ax)) + abs(dot(ay, ay)) + abs(dot(ay, az));
  real gz = abs(dot(az, ax)) + abs(dot(az, ay)) + abs(dot(az, az));
  real rn = sqrt(select_max(gx, select_max(gy, gz))) * (1.0 + gamma_bound(4.0));
  rvec3 rows = cert_abs_apply(q, rvec3(1.0));
  real mn = select_max(rows.x, select_max(rows.y, rows.z)) * (1.0 + gamma_bound(2.0));
  rvec3 f = quadric_local(q, p - rvec3(q.center));
  rvec3 g = quadric_apply(q, f) + L;
  rvec3 n = g.x * ax + g.y * ay + g.z * az;
  rvec3 ef = cert_local_error(q, abs(p) + abs(rvec3(q.center)), 0.0, 4.0);
  real eg = mn * (rn * ep + length(ef)) + gamma_bound(4.0) * length(cert_abs_apply(q, abs(f)) + abs(L));
  real e_n = rn * eg + gamma_bound(3.0) * length(abs(g.x) * abs(ax) + abs(g.y) * abs(ay) + abs(g.z) * abs(az));
  return cert_turn_of(e_n, length(n));
}
#endif
