// rc_triangle.glsl: ray/triangle tests (the watertight one and two fast variants) and
// the crossings of a ray's whole line with a closed mesh's triangles, which a composite's
// mesh operands are made of (rc_quadric.glsl). Included before the quadric code, which
// uses them.

// pbrt's gamma(n) = n u / (1 - n u): the relative error bound of n chained roundings.
real gamma_bound(real n) { return (n * RC_UNIT_ROUNDOFF) / (1.0 - n * RC_UNIT_ROUNDOFF); }

// Per-ray constants of the watertight test: the axis permutation that makes the largest
// direction component z, and the shear that maps the ray onto +z.
struct ray_shear {
  ivec3 k;
  rvec3 s;
};

ray_shear ray_shear_for(rvec3 d) {
  rvec3 a = abs(d);
  int kz = (a.x > a.y) ? ((a.x > a.z) ? 0 : 2) : ((a.y > a.z) ? 1 : 2);
  int kx = (kz + 1) % 3;
  int ky = (kx + 1) % 3;
  if (d[kz] < 0.0) {  // keep the winding, so the signs of U, V, W keep their meaning
    int tmp = kx;
    kx = ky;
    ky = tmp;
  }
  ray_shear sh;
  sh.k = ivec3(kx, ky, kz);
  sh.s = rvec3(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
  return sh;
}

rvec3 permute(rvec3 a, ivec3 k) { return rvec3(a[k.x], a[k.y], a[k.z]); }

// A triangle in the ray's sheared frame (Woop, Benthin & Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2(1), 2013): the vertices' x and y after the shear, their depths
// scaled by s.z (and unscaled, for the certificates' bounds: a division saved there), and the
// edge functions (u, v, w) of edges b->c, c->a, a->b. An edge shared
// by two triangles is evaluated from the same two projected vertices in both, and
// a*b - c*d is the exact negative of c*d - a*b, so no ray slips between them.
struct sheared_triangle {
  rvec3 x;
  rvec3 y;
  rvec3 z;
  rvec3 depth;
  rvec3 e;
};

sheared_triangle shear_triangle(rvec3 o, ray_shear sh, packed_triangle tri) {
  precise rvec3 a = permute(rvec3(tri.v0) - o, sh.k);
  precise rvec3 b = permute(rvec3(tri.v1) - o, sh.k);
  precise rvec3 c = permute(rvec3(tri.v2) - o, sh.k);
  precise real ax = a.x - sh.s.x * a.z;
  precise real ay = a.y - sh.s.y * a.z;
  precise real bx = b.x - sh.s.x * b.z;
  precise real by = b.y - sh.s.y * b.z;
  precise real cx = c.x - sh.s.x * c.z;
  precise real cy = c.y - sh.s.y * c.z;
  precise real u = cx * by - cy * bx;
  precise real v = ax * cy - ay * cx;
  precise real w = bx * ay - by * ax;
  precise rvec3 z = rvec3(sh.s.z * a.z, sh.s.z * b.z, sh.s.z * c.z);
  sheared_triangle st;
  st.x = rvec3(ax, bx, cx);
  st.y = rvec3(ay, by, cy);
  st.z = z;
  st.depth = rvec3(a.z, b.z, c.z);
  st.e = rvec3(u, v, w);
  return st;
}

// The largest magnitude of a's components.
real max3_abs(rvec3 a) {
  rvec3 m = abs(a);
  return select_max(select_max(m.x, m.y), m.z);
}

// pbrt-v4's conservative bound on the rounding error of t (shapes.cpp, IntersectTriangle).
real triangle_t_error(sheared_triangle st, real det) {
  real max_zt = max3_abs(st.z);
  real max_xt = max3_abs(st.x);
  real max_yt = max3_abs(st.y);
  real delta_z = gamma_bound(3.0) * max_zt;
  real delta_x = gamma_bound(5.0) * (max_xt + max_zt);
  real delta_y = gamma_bound(5.0) * (max_yt + max_zt);
  real delta_e = 2.0 * (gamma_bound(2.0) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  real max_e = max3_abs(st.e);
  return 3.0 * (gamma_bound(3.0) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) / abs(det);
}

// u + v + w when the edge functions (u, v, w) do not differ in sign, so that the ray
// passes inside the triangle or on its boundary; 0 when it passes outside or the triangle
// is degenerate (Woop et al.: det 0 is a miss).
real enclosing_det(rvec3 e) {
  if ((e.x < 0.0 || e.y < 0.0 || e.z < 0.0) && (e.x > 0.0 || e.y > 0.0 || e.z > 0.0)) return 0.0;
  precise real det = e.x + e.y + e.z;
  return det;
}

// The ray's t at the triangle: the depths weighted by the edge functions, over det.
real triangle_t(sheared_triangle st, real det) {
  precise real t_scaled = st.e.x * st.z.x + st.e.y * st.z.y + st.e.z * st.z.z;
  precise real t = t_scaled / det;
  return t;
}

// The watertight test: inclusive edges (a zero edge function counts as inside); a
// degenerate triangle (det 0) is missed.
real intersect_triangle(rvec3 o, ray_shear sh, packed_triangle tri, real t_max, out rvec3 bary) {
  bary = rvec3(0.0);
  sheared_triangle st = shear_triangle(o, sh, tri);
  real det = enclosing_det(st.e);
  if (det == 0.0) return real(RC_T_FAR);
  real t = triangle_t(st, det);
  if (!(t > 0.0 && t <= t_max)) return real(RC_T_FAR);
  // A hit of a spawned ray nearer than t's error bound may be the very surface the ray
  // left (or its neighbour across an edge), so it does not count; this is what lets the
  // error-bound offset stay small. The bound grows as 1/det, so it would drop slivers and
  // huge triangles seen up close: primary rays, which leave no surface, skip it.
  if (spawned_ray && t <= triangle_t_error(st, det)) return real(RC_T_FAR);
  bary = st.e / det;
  return t;
}

// Whether a zero edge function, on the edge from (x0, y0) to (x1, y1) of a triangle whose
// edge functions have the sign of det, counts the ray as crossing: as if the ray were moved
// by (eps, eps^2) in the sheared plane, the rasterizer's top-left rule. The triangle lies to
// the right of the edge taken with det's sign; two triangles on either side of a shared
// edge take it in opposite directions, so exactly one of them owns it (and, at a shared
// vertex, exactly one triangle of the fan around it).
bool edge_owned(real x0, real y0, real x1, real y1, real det) {
  real ex = (det > 0.0) ? x1 - x0 : x0 - x1;
  real ey = (det > 0.0) ? y1 - y0 : y0 - y1;
  return ey > 0.0 || (ey == 0.0 && ex < 0.0);
}

// Where the ray's whole line (t of any sign) crosses the triangle, else RC_T_FAR: the
// watertight test with owned edges (edge_owned) instead of inclusive ones, so that a line
// through an edge or vertex of a closed mesh crosses it once, never twice or not at all,
// and the parity of a mesh operand (rc_quadric.glsl, mesh_intervals) stays right. A spawned
// ray's crossing within t's error bound is the surface the ray left: it keeps its place in
// the count at t = 0, behind the origin, so it is never hit.
real triangle_crossing(rvec3 o, ray_shear sh, packed_triangle tri) {
  sheared_triangle st = shear_triangle(o, sh, tri);
  real det = enclosing_det(st.e);
  if (det == 0.0) return real(RC_T_FAR);
  if (st.e.x == 0.0 && !edge_owned(st.x.y, st.y.y, st.x.z, st.y.z, det)) return real(RC_T_FAR);
  if (st.e.y == 0.0 && !edge_owned(st.x.z, st.y.z, st.x.x, st.y.x, det)) return real(RC_T_FAR);
  if (st.e.z == 0.0 && !edge_owned(st.x.x, st.y.x, st.x.y, st.y.y, det)) return real(RC_T_FAR);
  real t = triangle_t(st, det);
  if (spawned_ray && abs(t) <= triangle_t_error(st, det)) return 0.0;
  return t;
}

// Moller & Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection", JGT 2(1), 1997,
// with the paper's |det| < 1e-6 test: a fast variant. Each triangle is solved from its own
// v0 and edges, so rays can slip between neighbours (docs/numerics.md §4), and the fixed
// epsilon drops small triangles whatever the scene's scale.
real intersect_triangle_moller_trumbore(rvec3 o, rvec3 d, packed_triangle tri, real t_max, out rvec3 bary) {
  bary = rvec3(0.0);
  rvec3 v0 = rvec3(tri.v0);
  rvec3 e1 = rvec3(tri.v1) - v0;
  rvec3 e2 = rvec3(tri.v2) - v0;
  rvec3 pv = cross(d, e2);
  real det = dot(e1, pv);
  if (abs(det) < 1.0e-6) return real(RC_T_FAR);
  real inv_det = 1.0 / det;
  rvec3 tv = o - v0;
  real u = dot(tv, pv) * inv_det;
  if (u < 0.0 || u > 1.0) return real(RC_T_FAR);
  rvec3 qv = cross(tv, e1);
  real v = dot(d, qv) * inv_det;
  if (v < 0.0 || u + v > 1.0) return real(RC_T_FAR);
  real t = dot(e2, qv) * inv_det;
  if (!(t > 0.0 && t <= t_max)) return real(RC_T_FAR);
  bary = rvec3(1.0 - u - v, u, v);
  return t;
}

// The textbook solve of o + t d = v0 + beta (v1 - v0) + gamma (v2 - v0) by Cramer's rule,
// as written in Shirley's Fundamentals of Computer Graphics (§4.4.2): a fast variant with
// no epsilon, still not watertight.
real intersect_triangle_cramer(rvec3 o, rvec3 d, packed_triangle tri, real t_max, out rvec3 bary) {
  bary = rvec3(0.0);
  rvec3 ab = rvec3(tri.v0) - rvec3(tri.v1);
  rvec3 ac = rvec3(tri.v0) - rvec3(tri.v2);
  rvec3 ao = rvec3(tri.v0) - o;
  real ei_hf = ac.y * d.z - d.y * ac.z;
  real gf_di = d.x * ac.z - ac.x * d.z;
  real dh_eg = ac.x * d.y - ac.y * d.x;
  real m = ab.x * ei_hf + ab.y * gf_di + ab.z * dh_eg;
  if (m == 0.0) return real(RC_T_FAR);
  real ak_jb = ab.x * ao.y - ao.x * ab.y;
  real jc_al = ao.x * ab.z - ab.x * ao.z;
  real bl_kc = ab.y * ao.z - ao.y * ab.z;
  real t = -(ac.z * ak_jb + ac.y * jc_al + ac.x * bl_kc) / m;
  if (!(t > 0.0 && t <= t_max)) return real(RC_T_FAR);
  real gamma = (d.z * ak_jb + d.y * jc_al + d.x * bl_kc) / m;
  if (gamma < 0.0 || gamma > 1.0) return real(RC_T_FAR);
  real beta = (ao.x * ei_hf + ao.y * gf_di + ao.z * dh_eg) / m;
  if (beta < 0.0 || beta > 1.0 - gamma) return real(RC_T_FAR);
  bary = rvec3(1.0 - beta - gamma, beta, gamma);
  return t;
}


// Whether d meets the triangle's front, the side its geometric normal cross(v1 - v0,
// v2 - v0) points to (counter-clockwise winding seen from there): a one-sided triangle
// (RC_TRIANGLE_ONE_SIDED) is there for such rays only. Edge on counts as behind.
real triangle_facing(packed_triangle tri, rvec3 d) {
  rvec3 v0 = rvec3(tri.v0);
  precise real facing = dot(d, cross(rvec3(tri.v1) - v0, rvec3(tri.v2) - v0));
  return facing;
}

bool triangle_faces_ray(packed_triangle tri, rvec3 d) { return triangle_facing(tri, d) < 0.0; }
