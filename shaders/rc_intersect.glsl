// rc_intersect.glsl: ray/primitive tests, closest hit and shadow-ray occlusion, in pbrt's
// layers: the tests return t (and what shading needs to rebuild the hit exactly), shading
// happens once for the winner (rc_shade.glsl). Directions are unit length. Every result is
// `precise` so no driver contracts or reorders the arithmetic (ROBUSTNESS.md §1.3, §3).

struct hit_record {
  real t;
  uint kind;   // RC_HIT_*
  uint index;  // into the sphere or triangle array
  uint object; // spheres 0..S-1, then triangles S..S+T-1: the tie-breaking order
  rvec3 bary;  // triangle: weights of v0, v1, v2
  real side;   // sphere: -1 entry root (ray from outside), +1 exit root
};

// Ray/sphere after Haines, Günther & Akenine-Möller, "Precision Improvements for
// Ray/Sphere Intersection" (Ray Tracing Gems ch. 7, 2019): the Hearn-Baker discriminant
// r^2 - |l|^2 (l = centre-to-ray-line offset) instead of b^2 - 4ac, and the stable root
// pair q = -(b + sign(b) sqrt(D)), t0 = c/q, t1 = q (Press et al.). Nearest root in
// (0, t_max], else RC_T_FAR. (t_max is inclusive so that a BVH, visiting objects out of
// order, still sees equal-t hits and can apply the tie rule.)
real intersect_sphere(rvec3 o, rvec3 d, gpu_sphere s, real t_max, out real side) {
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
  real t_near = min(t0, q);
  real t_exit = max(t0, q);
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
  bary = rvec3(u, v, w) / det;
  return t;
}

// The ray against object `object` (spheres first, then triangles); t as above.
real intersect_object(uint object, rvec3 o, rvec3 d, ray_shear sh, real t_max, out real side, out rvec3 bary) {
  side = 0.0;
  bary = rvec3(0.0);
  if (object < frame.sphere_count) return intersect_any_sphere(o, d, load_sphere(object), t_max, side);
  return intersect_triangle(o, sh, load_triangle(object - frame.sphere_count), t_max, bary);
}

// The tie rule of both backends and both traversals: the nearer hit wins, and on equal
// t the lower object number, whatever order the objects were visited in.
void consider_hit(uint object, real t, real side, rvec3 bary, inout hit_record h) {
  if (t >= real(RC_T_FAR)) return;
  if (t < h.t || (t == h.t && object < h.object)) {
    h.t = t;
    h.object = object;
    h.kind = (object < frame.sphere_count) ? RC_HIT_SPHERE : RC_HIT_TRIANGLE;
    h.index = (object < frame.sphere_count) ? object : object - frame.sphere_count;
    h.side = side;
    h.bary = bary;
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
  return h;
}

// Brute force: every object, in order.
void closest_hit_linear(rvec3 o, rvec3 d, inout hit_record h) {
  ray_shear sh = ray_shear_for(d);
  for (uint i = 0u; i < frame.object_count; i++) {
    if (!budget_step()) break;
    real side;
    rvec3 bary;
    real t = intersect_object(i, o, d, sh, h.t, side, bary);
    consider_hit(i, t, side, bary, h);
  }
}

// Any hit in (0, t_max]: the shadow-ray query, with an early exit. (A miss is RC_T_FAR,
// which a directional light's t_max equals: only a real hit blocks.)
bool occluded_linear(rvec3 o, rvec3 d, real t_max) {
  ray_shear sh = ray_shear_for(d);
  for (uint i = 0u; i < frame.object_count; i++) {
    if (!budget_step()) return false;
    real side;
    rvec3 bary;
    if (intersect_object(i, o, d, sh, t_max, side, bary) < real(RC_T_FAR)) return true;
  }
  return false;
}
