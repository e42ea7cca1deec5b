// rc_intersect.glsl: ray/primitive tests, closest hit and shadow-ray occlusion, in pbrt's
// layers: the tests return t (and what shading needs to rebuild the hit exactly), shading
// happens once for the winner (rc_shade.glsl). Directions are unit length. Every result is
// `precise` so no driver contracts or reorders the arithmetic (ROBUSTNESS.md §1.3, §3).

struct hit_record {
  real t;
  uint kind;   // RC_HIT_*
  uint index;  // into the sphere or triangle array
  rvec3 bary;  // triangle: weights of v0, v1, v2
  real side;   // sphere: -1 entry root (ray from outside), +1 exit root
};

// Ray/sphere after Haines, Günther & Akenine-Möller, "Precision Improvements for
// Ray/Sphere Intersection" (Ray Tracing Gems ch. 7, 2019): the Hearn-Baker discriminant
// r^2 - |l|^2 (l = centre-to-ray-line offset) instead of b^2 - 4ac, and the stable root
// pair q = -(b + sign(b) sqrt(D)), t0 = c/q, t1 = q (Press et al.). Nearest root in
// (0, t_max), else RC_T_FAR.
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
  if (t_near > 0.0 && t_near < t_max) {
    side = -1.0;
    return t_near;
  }
  if (t_exit > 0.0 && t_exit < t_max) {
    side = 1.0;
    return t_exit;
  }
  return real(RC_T_FAR);
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
  if (!(t > 0.0 && t < t_max)) return real(RC_T_FAR);
  bary = rvec3(u, v, w) / det;
  return t;
}

// Nearest hit over every primitive; on equal t the lower index wins, spheres before
// triangles (strict <), the same rule on both backends.
bool closest_hit(rvec3 o, rvec3 d, out hit_record h) {
  h.t = real(RC_T_FAR);
  h.kind = RC_HIT_NONE;
  h.index = 0u;
  h.bary = rvec3(0.0);
  h.side = 0.0;
  for (uint i = 0u; i < frame.sphere_count; i++) {
    if (!budget_step()) break;
    real side;
    real t = intersect_sphere(o, d, load_sphere(i), h.t, side);
    if (t < h.t) {
      h.t = t;
      h.kind = RC_HIT_SPHERE;
      h.index = i;
      h.side = side;
    }
  }
  ray_shear sh = ray_shear_for(d);
  for (uint i = 0u; i < frame.triangle_count; i++) {
    if (!budget_step()) break;
    rvec3 bary;
    real t = intersect_triangle(o, sh, load_triangle(i), h.t, bary);
    if (t < h.t) {
      h.t = t;
      h.kind = RC_HIT_TRIANGLE;
      h.index = i;
      h.bary = bary;
    }
  }
  return h.kind != RC_HIT_NONE;
}

// Any hit in (0, t_max): the shadow-ray query, with an early exit.
bool occluded(rvec3 o, rvec3 d, real t_max) {
  for (uint i = 0u; i < frame.sphere_count; i++) {
    if (!budget_step()) return false;
    real side;
    if (intersect_sphere(o, d, load_sphere(i), t_max, side) < t_max) return true;
  }
  ray_shear sh = ray_shear_for(d);
  for (uint i = 0u; i < frame.triangle_count; i++) {
    if (!budget_step()) return false;
    rvec3 bary;
    if (intersect_triangle(o, sh, load_triangle(i), t_max, bary) < t_max) return true;
  }
  return false;
}
