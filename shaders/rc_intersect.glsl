// rc_intersect.glsl: ray/primitive tests, closest hit and shadow-ray occlusion, in pbrt's
// layers: the tests return t (and what shading needs to rebuild the hit exactly), shading
// happens once for the winner (rc_shade.glsl). Directions are unit length. Every result is
// `precise` so no driver contracts or reorders the arithmetic (docs/numerics.md §1, §4).

struct hit_record {
  real t;
  uint kind;   // RC_HIT_*
  uint index;  // into the sphere or triangle array
  uint object; // spheres 0..S-1, then triangles, quadrics, composites: the tie-breaking order
  rvec3 bary;  // triangle: weights of v0, v1, v2
  real side;   // sphere: -1 entry root (ray from outside), +1 exit root
  uint part;   // quadric or composite: the csg_code of the surface hit (rc_quadric.glsl)
};

// pbrt's gamma(n) = n u / (1 - n u): the relative error bound of n chained roundings.
real gamma_bound(real n) { return (n * RC_UNIT_ROUNDOFF) / (1.0 - n * RC_UNIT_ROUNDOFF); }

// The first root of a sphere in (0, t_max]: the entry (side -1, the ray comes from
// outside), else the exit (side +1), else RC_T_FAR.
real first_root(real t_near, real t_exit, real t_max, out real side) {
  side = 0.0;
  if (t_near > 0.0 && t_near <= t_max) {
    side = -1.0;
    return t_near;
  }
  if (t_exit > 0.0 && t_exit <= t_max) {
    side = 1.0;
    return t_exit;
  }
  return real(RC_T_FAR);
}

// Ray/sphere after Haines, Günther & Akenine-Möller, "Precision Improvements for
// Ray/Sphere Intersection" (Ray Tracing Gems ch. 7, 2019): the Hearn-Baker discriminant
// r^2 - |l|^2 (l = centre-to-ray-line offset) instead of b^2 - 4ac, and the stable root
// pair q = -(b + sign(b) sqrt(D)), t0 = c/q, t1 = q (Press et al.). Nearest root in
// (0, t_max], else RC_T_FAR. (t_max is inclusive so that a BVH, visiting objects out of
// order, still sees equal-t hits and can apply the tie rule.)
real intersect_sphere_geometric(rvec3 o, rvec3 d, gpu_sphere s, real t_max, out real side) {
  side = 0.0;
  real r = real(s.radius);
  precise rvec3 f = o - rvec3(s.center);
  precise real b = dot(f, d);
  precise rvec3 l = f - b * d;
  precise real disc = r * r - dot(l, l);
  if (disc < 0.0) return real(RC_T_FAR);
  precise real sq = sqrt(disc);
  precise real q = (b >= 0.0) ? -(b + sq) : -(b - sq);
  if (q == 0.0) return real(RC_T_FAR);  // origin exactly at the tangent point
  precise real c = dot(f, f) - r * r;
  precise real t0 = c / q;
  return first_root(min(t0, q), max(t0, q), t_max, side);
}

// The textbook quadratic a t^2 + b t + c = 0, a = d.d, b = 2 f.d, c = f.f - r^2: the fast
// variant, kept to measure what the geometric form buys (docs/accuracy.md). b^2 and 4ac
// cancel once the sphere is far compared to its radius (docs/numerics.md §2). Not `precise`:
// as shipped in textbooks, the driver may contract it.
real intersect_sphere_algebraic(rvec3 o, rvec3 d, gpu_sphere s, real t_max, out real side) {
  side = 0.0;
  real r = real(s.radius);
  rvec3 f = o - rvec3(s.center);
  real a = dot(d, d);
  real b = 2.0 * dot(f, d);
  real c = dot(f, f) - r * r;
  real disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return real(RC_T_FAR);
  real sq = sqrt(disc);
  return first_root((-b - sq) / (2.0 * a), (-b + sq) / (2.0 * a), t_max, side);
}

real intersect_sphere(rvec3 o, rvec3 d, gpu_sphere s, real t_max, out real side) {
  if (sphere_formula == RC_SPHERE_ALGEBRAIC) return intersect_sphere_algebraic(o, d, s, t_max, side);
  return intersect_sphere_geometric(o, d, s, t_max, side);
}

// A point and a direction taken into a transformed sphere's object space.
rvec3 transform_point(gpu_transform m, rvec3 p) {
  return rvec3(dot(rvec3(m.row0.xyz), p) + real(m.row0.w), dot(rvec3(m.row1.xyz), p) + real(m.row1.w),
               dot(rvec3(m.row2.xyz), p) + real(m.row2.w));
}

rvec3 transform_vector(gpu_transform m, rvec3 v) {
  return rvec3(dot(rvec3(m.row0.xyz), v), dot(rvec3(m.row1.xyz), v), dot(rvec3(m.row2.xyz), v));
}

// A sphere, transformed or not. Through a transform the ray is intersected in object
// space with its direction renormalised, and t scaled back by the direction's length, so
// t stays the packed-space t (and t_max keeps its meaning).
real intersect_any_sphere(rvec3 o, rvec3 d, gpu_sphere s, real t_max, out real side) {
  if (s.transform == RC_NO_TRANSFORM) return intersect_sphere(o, d, s, t_max, side);
  gpu_transform m = load_transform(s.transform);
  rvec3 d_obj = transform_vector(m, d);
  real len = length(d_obj);
  real t = intersect_sphere(transform_point(m, o), d_obj / len, s, t_max * len, side);
  return (t >= real(RC_T_FAR)) ? t : t / len;
}

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

// Woop, Benthin & Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013. An edge
// shared by two triangles is evaluated from the same two projected vertices in both, and
// a*b - c*d is the exact negative of c*d - a*b, so no ray slips between them. Inclusive
// edges (a zero edge function counts as inside); a degenerate triangle (det 0) is missed.
real intersect_triangle(rvec3 o, ray_shear sh, gpu_triangle tri, real t_max, out rvec3 bary) {
  bary = rvec3(0.0);
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
  if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return real(RC_T_FAR);
  precise real det = u + v + w;
  if (det == 0.0) return real(RC_T_FAR);
  precise real t_scaled = u * (sh.s.z * a.z) + v * (sh.s.z * b.z) + w * (sh.s.z * c.z);
  precise real t = t_scaled / det;
  if (!(t > 0.0 && t <= t_max)) return real(RC_T_FAR);
  // pbrt-v4's conservative bound on the rounding error of t (shapes.cpp, IntersectTriangle):
  // a hit of a spawned ray nearer than it may be the very surface the ray left (or its
  // neighbour across an edge), so it does not count; this is what lets the error-bound
  // offset stay small. The bound grows as 1/det, so it would drop slivers and huge
  // triangles seen up close: primary rays, which leave no surface, skip it.
  real max_zt = max(max(abs(sh.s.z * a.z), abs(sh.s.z * b.z)), abs(sh.s.z * c.z));
  real max_xt = max(max(abs(ax), abs(bx)), abs(cx));
  real max_yt = max(max(abs(ay), abs(by)), abs(cy));
  real delta_z = gamma_bound(3.0) * max_zt;
  real delta_x = gamma_bound(5.0) * (max_xt + max_zt);
  real delta_y = gamma_bound(5.0) * (max_yt + max_zt);
  real delta_e = 2.0 * (gamma_bound(2.0) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  real max_e = max(max(abs(u), abs(v)), abs(w));
  real delta_t = 3.0 * (gamma_bound(3.0) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) / abs(det);
  if (spawned_ray && t <= delta_t) return real(RC_T_FAR);
  bary = rvec3(u, v, w) / det;
  return t;
}

// Moller & Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection", JGT 2(1), 1997,
// with the paper's |det| < 1e-6 test: a fast variant. Each triangle is solved from its own
// v0 and edges, so rays can slip between neighbours (docs/numerics.md §4), and the fixed
// epsilon drops small triangles whatever the scene's scale.
real intersect_triangle_moller_trumbore(rvec3 o, rvec3 d, gpu_triangle tri, real t_max, out rvec3 bary) {
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
real intersect_triangle_cramer(rvec3 o, rvec3 d, gpu_triangle tri, real t_max, out rvec3 bary) {
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

// The kind of object `object` (RC_HIT_*) and its index in its own array.
uint object_kind(uint object, out uint index) {
  uint first_quadric = frame.sphere_count + frame.triangle_count;
  uint first_csg = first_quadric + frame.quadric_count;
  index = (object < frame.sphere_count) ? object
          : (object < first_quadric) ? object - frame.sphere_count
          : (object < first_csg) ? object - first_quadric : object - first_csg;
  return (object < frame.sphere_count) ? RC_HIT_SPHERE
         : (object < first_quadric) ? RC_HIT_TRIANGLE
         : (object < first_csg) ? RC_HIT_QUADRIC : RC_HIT_CSG;
}

// The ray against object `object`; t as above. Kinds the scene lacks are compiled out
// (has_kind, a specialization constant).
real intersect_object(uint object, rvec3 o, rvec3 d, ray_shear sh, real t_max, out real side, out rvec3 bary,
                      out uint part) {
  side = 0.0;
  bary = rvec3(0.0);
  part = 0u;
  uint index;
  uint kind = object_kind(object, index);
  if (has_kind(RC_KIND_SPHERES) && kind == RC_HIT_SPHERE) return intersect_any_sphere(o, d, load_sphere(index), t_max, side);
  if (has_kind(RC_KIND_TRIANGLES) && kind == RC_HIT_TRIANGLE) {
    gpu_triangle tri = load_triangle(index);
    if (triangle_formula == RC_TRIANGLE_MOLLER_TRUMBORE) return intersect_triangle_moller_trumbore(o, d, tri, t_max, bary);
    if (triangle_formula == RC_TRIANGLE_CRAMER) return intersect_triangle_cramer(o, d, tri, t_max, bary);
    return intersect_triangle(o, sh, tri, t_max, bary);
  }
#if RC_QUADRICS
  if (has_kind(RC_KIND_QUADRICS) && kind == RC_HIT_QUADRIC) return intersect_quadric(index, o, d, t_max, part);
  if (has_kind(RC_KIND_CSG) && kind == RC_HIT_CSG) return intersect_csg(index, o, d, t_max, part);
#endif
  return real(RC_T_FAR);
}

// The tie rule of both backends and both traversals: the nearer hit wins, and on equal
// t the lower object number, whatever order the objects were visited in.
void consider_hit(uint object, real t, real side, rvec3 bary, uint part, inout hit_record h) {
  if (t >= real(RC_T_FAR)) return;
  if (t < h.t || (t == h.t && object < h.object)) {
    h.t = t;
    h.object = object;
    h.kind = object_kind(object, h.index);
    h.side = side;
    h.bary = bary;
    h.part = part;
  }
}

hit_record no_hit() {
  hit_record h;
  h.t = real(RC_T_FAR);
  h.kind = RC_HIT_NONE;
  h.index = 0u;
  h.object = 0xffffffffu;
  h.bary = rvec3(0.0);
  h.side = 0.0;
  h.part = 0u;
  return h;
}

// Brute force: every object, in order.
void closest_hit_linear(rvec3 o, rvec3 d, inout hit_record h) {
  ray_shear sh = ray_shear_for(d);
  for (uint i = 0u; i < frame.object_count; i++) {
    if (!budget_step()) {
      budget_blame = 1u + i;
      break;
    }
    real side;
    rvec3 bary;
    uint part;
    real t = intersect_object(i, o, d, sh, h.t, side, bary, part);
    consider_hit(i, t, side, bary, part, h);
  }
}

// Any hit in (0, t_max]: the shadow-ray query, with an early exit. (A miss is RC_T_FAR,
// which a directional light's t_max equals: only a real hit blocks.)
bool occluded_linear(rvec3 o, rvec3 d, real t_max) {
  ray_shear sh = ray_shear_for(d);
  for (uint i = 0u; i < frame.object_count; i++) {
    if (!budget_step()) {
      budget_blame = 1u + i;
      return false;
    }
    real side;
    rvec3 bary;
    uint part;
    if (intersect_object(i, o, d, sh, t_max, side, bary, part) < real(RC_T_FAR)) return true;
  }
  return false;
}
