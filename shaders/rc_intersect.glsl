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
  real err;    // with certify: the error bound of t (rc_certify.glsl)
  real bary_err; // and of the barycentrics
  real off_err;  // and how far the point may lie off the rays (patches: rc_certify_patch.glsl)
};

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
real intersect_sphere_geometric(rvec3 o, rvec3 d, packed_sphere s, real t_max, out real side) {
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
  return first_root(select_min(t0, q), select_max(t0, q), t_max, side);
}

// The textbook quadratic a t^2 + b t + c = 0, a = d.d, b = 2 f.d, c = f.f - r^2: the fast
// variant, kept to measure what the geometric form buys (docs/accuracy.md). b^2 and 4ac
// cancel once the sphere is far compared to its radius (docs/numerics.md §2). Not `precise`:
// as shipped in textbooks, the driver may contract it.
real intersect_sphere_algebraic(rvec3 o, rvec3 d, packed_sphere s, real t_max, out real side) {
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

real intersect_sphere(rvec3 o, rvec3 d, packed_sphere s, real t_max, out real side) {
  if (sphere_formula == RC_SPHERE_ALGEBRAIC) return intersect_sphere_algebraic(o, d, s, t_max, side);
  return intersect_sphere_geometric(o, d, s, t_max, side);
}

// A point and a direction taken into a transformed sphere's object space.
rvec3 transform_point(packed_transform m, rvec3 p) {
  return rvec3(dot(rvec3(m.row0.xyz), p) + real(m.row0.w), dot(rvec3(m.row1.xyz), p) + real(m.row1.w),
               dot(rvec3(m.row2.xyz), p) + real(m.row2.w));
}

rvec3 transform_vector(packed_transform m, rvec3 v) {
  return rvec3(dot(rvec3(m.row0.xyz), v), dot(rvec3(m.row1.xyz), v), dot(rvec3(m.row2.xyz), v));
}

// A sphere, transformed or not. Through a transform the ray is intersected in object
// space with its direction renormalised, and t scaled back by the direction's length, so
// t stays the packed-space t (and t_max keeps its meaning).
real intersect_any_sphere(rvec3 o, rvec3 d, packed_sphere s, real t_max, out real side) {
  if (!has_kind(RC_KIND_SPHERE_TRANSFORMS) || s.transform == RC_NO_TRANSFORM) return intersect_sphere(o, d, s, t_max, side);
  packed_transform m = load_transform(s.transform);
  rvec3 d_obj = transform_vector(m, d);
  real len = length(d_obj);
  real t = intersect_sphere(transform_point(m, o), d_obj / len, s, t_max * len, side);
  return (t >= real(RC_T_FAR)) ? t : t / len;
}

// The kind of object `object` (RC_HIT_*) and its index in its own array.
uint object_kind(uint object, out uint index) {
  index = (object < first_triangle_object) ? object
          : (object < first_quadric_object) ? object - first_triangle_object
          : (object < first_csg_object) ? object - first_quadric_object : object - first_csg_object;
  return (object < first_triangle_object) ? RC_HIT_SPHERE
         : (object < first_quadric_object) ? RC_HIT_TRIANGLE
         : (object < first_csg_object) ? RC_HIT_QUADRIC : RC_HIT_CSG;
}

#if RC_QUADRICS
// A standalone bounded quadric or patch piece, `index` in the quadric array:
// intersect_object's test of one, and a loose quadric's (rc_bvh.glsl, test_loose).
real intersect_quadric_object(uint index, rvec3 o, rvec3 d, real t_max, out rvec3 bary, out uint part) {
  bary = rvec3(0.0);
  part = 0u;
#if RC_PATCHES
  if (has_kind(RC_KIND_PATCHES)) {
    packed_quadric q = load_quadric(index);
    if ((q.flags & RC_QUADRIC_PATCH) != 0u) {
      part = csg_code(index, 0u, false, false);
      return intersect_patch(index, q, o, d, t_max, bary);
    }
  }
#endif
  if (!has_kind(RC_KIND_QUADRICS)) return real(RC_T_FAR);  // patch pieces only
  return intersect_quadric(index, o, d, t_max, part);
}
#endif

// A triangle object, loaded: a one-sided one the ray meets from behind is a miss, else the
// chosen formula's test.
real intersect_triangle_object(packed_triangle tri, rvec3 o, rvec3 d, ray_shear sh, real t_max, out rvec3 bary) {
  bary = rvec3(0.0);
  if (has_kind(RC_KIND_ONE_SIDED_TRIANGLES) && (tri.flags & RC_TRIANGLE_ONE_SIDED) != 0u && !triangle_faces_ray(tri, d))
    return real(RC_T_FAR);
  if (triangle_formula == RC_TRIANGLE_MOLLER_TRUMBORE) return intersect_triangle_moller_trumbore(o, d, tri, t_max, bary);
  if (triangle_formula == RC_TRIANGLE_CRAMER) return intersect_triangle_cramer(o, d, tri, t_max, bary);
  return intersect_triangle(o, sh, tri, t_max, bary);
}

// An object of the other kinds (a quadric, a patch piece, a composite), as intersect_object
// finds it (`kind`, `index`), or of a kind `kinds` leaves out: RC_T_FAR.
real intersect_other_object(uint kinds, uint kind, uint index, rvec3 o, rvec3 d, real t_max, out rvec3 bary,
                            out uint part) {
  bary = rvec3(0.0);
  part = 0u;
#if RC_QUADRICS
  if ((kinds & RC_KIND_QUADRICS) != 0u && kind == RC_HIT_QUADRIC)
    return intersect_quadric_object(index, o, d, t_max, bary, part);
  if (has_kind(RC_KIND_CSG) && (kinds & RC_KIND_CSG) != 0u && kind == RC_HIT_CSG)
    return intersect_csg(index, o, d, t_max, part);
#endif
  return real(RC_T_FAR);
}

// The ray against object `object`; t as above. Kinds the scene lacks are compiled out
// (has_kind, a specialization constant), and so are those the caller's objects cannot be:
// `kinds` (RC_KIND_*) is a constant at each call, RC_KIND_ALL in brute force and the
// tree's kinds in its leaves (rc_bvh.glsl, tree_kinds). A SIMD shader runs every test an
// object could need, so a leaf that might hold a sphere, a box or a composite paid for all
// three on each of a mesh's triangles (docs/performance.md, "Loose objects").
real intersect_object(uint kinds, uint object, rvec3 o, rvec3 d, ray_shear sh, real t_max, out real side,
                      out rvec3 bary, out uint part) {
  side = 0.0;
  bary = rvec3(0.0);
  part = 0u;
  uint index;
  uint kind = object_kind(object, index);
  if (has_kind(RC_KIND_SPHERES) && (kinds & RC_KIND_SPHERES) != 0u && kind == RC_HIT_SPHERE)
    return intersect_any_sphere(o, d, load_sphere(index), t_max, side);
  if (has_kind(RC_KIND_TRIANGLES) && (kinds & RC_KIND_TRIANGLES) != 0u && kind == RC_HIT_TRIANGLE)
    return intersect_triangle_object(load_triangle(index), o, d, sh, t_max, bary);
  return intersect_other_object(kinds, kind, index, o, d, t_max, bary, part);
}

#if RC_CERTIFY
// Where a closest-hit traversal may stop looking: a box entered up to the nearest hit's t plus
// its bound, and the perturbation's reach there, may hold a root the reference finds nearer.
real cert_limit(real t, real e) {
  if (!(t < real(RC_T_FAR))) return t;
  return t + 2.0 * cert_factor() * (e + cert_eo + t * cert_ed);
}

// The nearest-hit decision: the winner's interval [t - k e, t + k e] below every other root
// found (cert_beyond, which cert_order and cert_root keep).
void cert_order(real t, uint object, inout hit_record h) {
  if (t < h.t || (t == h.t && object < h.object)) {
    if (h.kind != RC_HIT_NONE) cert_beyond = select_min(cert_beyond, h.t - cert_factor() * h.err);
    return;
  }
  cert_beyond = select_min(cert_beyond, t - cert_factor() * cert_t_err);
}
#endif

// The tie rule of both backends and both traversals: the nearer hit wins, and on equal
// t the lower object number, whatever order the objects were visited in.
void consider_hit(uint object, real t, real side, rvec3 bary, uint part, inout hit_record h) {
  if (t >= real(RC_T_FAR)) return;
#if RC_CERTIFY
  if (certify) cert_order(t, object, h);
#endif
  if (t < h.t || (t == h.t && object < h.object)) {
    h.t = t;
    h.object = object;
    h.kind = object_kind(object, h.index);
    h.side = side;
    h.bary = bary;
    h.part = part;
#if RC_CERTIFY
    if (certify) {
      h.err = cert_t_err;
      h.bary_err = cert_bary_err;
      h.off_err = cert_off_err;
    }
#endif
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
  h.err = 0.0;
  h.bary_err = 0.0;
  h.off_err = 0.0;
  return h;
}

// The surface a hit on `object` lies on: a patch piece's is its patch's, named by its first
// piece (the pieces of a patch are one surface: the AOV names it so, and a spawned ray
// leaves all of them).
uint surface_object(uint object) {
#if RC_PATCHES
  uint index;
  if (has_kind(RC_KIND_PATCHES) && object_kind(object, index) == RC_HIT_QUADRIC) {
    packed_quadric q = load_quadric(index);
    if ((q.flags & RC_QUADRIC_PATCH) != 0u) return first_quadric_object + q.mesh_end;
  }
#endif
  return object;
}

#if RC_CERTIFY
// A sphere's decisions (intersect_any_sphere). A transformed one is tested in object space, along d_obj = A d normalized, and t = t_obj / |d_obj|: the ray's
// perturbation goes there as |A| do and |A| dd over |d_obj|, with gamma(4) of the terms of
// A o + b and A d; the roots come back scaled by 1 / |d_obj|, whose error is that of |d_obj|
// relative to it, plus the rounding of the scaling and of t_max |d_obj|.
void cert_sphere(rvec3 o, rvec3 d, packed_sphere s, real t_max) {
  if (sphere_formula != RC_SPHERE_GEOMETRIC) {
    cert_fail();
    return;
  }
  if (!has_kind(RC_KIND_SPHERE_TRANSFORMS) || s.transform == RC_NO_TRANSFORM) {
    cert_sphere_roots(o, d, s, t_max, 1.0, 0.0);
    return;
  }
  packed_transform m = load_transform(s.transform);
  rvec3 d_obj = transform_vector(m, d);
  real len = length(d_obj);
  real na = cert_norm(m);
  real eo = cert_eo;
  real ed = cert_ed;
  real err = na * ed + gamma_bound(4.0) * na;
  cert_eo = na * eo + gamma_bound(4.0) * (na * length(o) + length(rvec3(m.row0.w, m.row1.w, m.row2.w)));
  cert_ed = err / (len - err) + gamma_bound(4.0);
  cert_sphere_roots(transform_point(m, o), d_obj / len, s, t_max, 1.0 / len, err / (len - err) + gamma_bound(3.0));
  cert_eo = eo;
  cert_ed = ed;
}

// Where an object's test begins: its decisions are judged apart from the path's so far (a
// shadow ray's blocker by its own test's, cert_hit_ok, for cert_blocked), and a spawned
// ray's root on the object it leaves is cert_root's to drop (cert_self). Returns the path's
// certificate so far, which cert_test_end joins again.
bool cert_test_begin(uint object) {
  bool ok = cert_ok;
  cert_ok = true;
  cert_self = spawned_ray && offset_strategy == RC_OFFSET_ERROR_BOUND && surface_object(object) == cert_spawn_object;
  return ok;
}

void cert_test_end(bool ok) {
  cert_hit_ok = cert_ok;
  cert_ok = ok && cert_ok;
}

// A triangle object's decisions (intersect_triangle_object). The watertight test's sheared
// x and y do not change when the origin moves along the ray, and its t moves by as much:
// cert_eo (across) alone, and cert_et where t meets 0.
void cert_triangle_object(packed_triangle tri, rvec3 o, rvec3 d, ray_shear sh, real t_max) {
  uint side = RC_SIDE_FRONT;
  if (has_kind(RC_KIND_ONE_SIDED_TRIANGLES) && (tri.flags & RC_TRIANGLE_ONE_SIDED) != 0u) side = cert_triangle_side(tri, d);
  if (side != RC_SIDE_BACK) cert_triangle(o, sh, tri, t_max, side == RC_SIDE_UNSURE);
}

// The decisions of intersect_other_object. An object these kinds' certificates do not cover
// fails, where `kinds` has the other kinds at all.
void cert_other_object_tests(uint kinds, uint kind, uint index, rvec3 o, rvec3 d, bool any, real t_max) {
  if ((kinds & (RC_KIND_QUADRICS | RC_KIND_CSG)) != 0u) {
#if RC_QUADRICS
    if (has_kind(RC_KIND_CSG) && (kinds & RC_KIND_CSG) != 0u && kind == RC_HIT_CSG) {
      cert_csg(index, o, d, any, t_max);
      return;
    }
    if ((kinds & RC_KIND_QUADRICS) != 0u && kind == RC_HIT_QUADRIC) {
      packed_quadric q = load_quadric(index);
      // Without RC_KIND_QUADRICS the only quadric objects a test meets are patch pieces
      // (gpu_pipeline.c: planes have test_planes' loop): the leaves of a scene of patches or
      // of composites beside planes need neither test's certificate (intersect_quadric_object).
      if (has_kind(RC_KIND_QUADRICS) && (q.flags & RC_QUADRIC_UNBOUNDED) != 0u) {
        cert_plane(q, o, d, t_max);
        return;
      }
      if (has_kind(RC_KIND_QUADRICS) && (q.flags & (RC_QUADRIC_PATCH | RC_QUADRIC_MESH)) == 0u) {
        cert_quadric(q, o, d, t_max);
        return;
      }
#if RC_PATCHES
      if (has_kind(RC_KIND_PATCHES) && (q.flags & RC_QUADRIC_PATCH) != 0u) {
        cert_patch(q, o, d, t_max);
        return;
      }
#endif
    }
#endif
    cert_fail();
  }
}

// The decisions of testing object `object` of the other kinds (intersect_other_object; the
// loose quadrics' loop): those of the kinds rc_certify.glsl bounds, none of the others.
// Spheres and triangles are test_object's, which certifies and tests them from one fetch.
void cert_object(uint kinds, uint object, rvec3 o, rvec3 d, bool any, real t_max) {
  bool ok = cert_test_begin(object);
  // The other kinds' bounds take the origin's move in any direction: along the ray too.
  real eo = cert_eo;
  cert_eo += cert_et;
  uint index;
  uint kind = object_kind(object, index);
  cert_other_object_tests(kinds, kind, index, o, d, any, t_max);
  cert_eo = eo;
  cert_test_end(ok);
}

#if RC_QUADRICS
// cert_object for test_planes' loop, whose objects are all planes: the plane's certificate
// alone. cert_object there inlined every kind's into the loop, and a SIMD shader runs them
// all: with the bounded quadrics' it cost room.json's certified frame 1.5x (commit message).
void cert_plane_object(uint object, packed_quadric q, rvec3 o, rvec3 d, real t_max) {
  bool ok = cert_test_begin(object);
  real eo = cert_eo;
  cert_eo += cert_et;
  cert_plane(q, o, d, t_max);
  cert_eo = eo;
  cert_test_end(ok);
}
#endif

// The nearest-hit decision, and with no hit, that no uncertain test may have one
// (cert_maybe).
void cert_closest(hit_record h) {
  bool certain = (h.kind == RC_HIT_NONE) ? !(cert_beyond < real(RC_T_FAR)) : cert_beyond > h.t + cert_factor() * h.err;
  if (!certain) cert_ok = false;
}

// A shadow ray's blocker (the object just tested hit within t_max) ends the query, unless
// certified mode must look on: past a blocker whose own test is uncertain, for one whose
// test is certain. The answer is blocked either way; only the certificate depends on the
// search, which therefore stops short of the loop budget (cert_blocked_later) rather than
// exhaust it. True when it ends here.
bool cert_blocker_ends() {
  if (cert_hit_ok) {
    cert_blocker_certain = true;
    return true;
  }
  cert_blocked_later = true;
  return false;
}

// A shadow ray's answer. Blocked by an object whose own test is certified, the reference is
// blocked too (by that object, if by no other), whatever the tests before it decided: the
// query is as certain as the path was before it (`ok`).
void cert_blocked(bool blocked, bool ok) {
  if (blocked && cert_blocker_certain) cert_ok = ok;
}
#endif

// The ray against object `object` (intersect_object), its decisions certified first in the
// module that certifies (cert_object). A sphere or a triangle is loaded once for both:
// llvmpipe does not merge two masked fetches of the same texels, and each certified leaf
// loop fetched every triangle twice (docs/performance.md, "One fetch of a certified
// triangle"). Each kind's test and certificate appear once here, together in the kind's
// branch, and not behind `if (certify)`: the driver inlines every call before it folds a
// constant, so each copy cost the pipeline's creation its compile time, and certificates
// and tests in two chains of branches cost the frame what the shared fetch saved.
real test_object(uint kinds, uint object, rvec3 o, rvec3 d, ray_shear sh, bool any, real t_max, out real side, out rvec3 bary,
                 out uint part) {
#if RC_CERTIFY
  side = 0.0;
  bary = rvec3(0.0);
  part = 0u;
  uint index;
  uint kind = object_kind(object, index);
  bool ok = cert_test_begin(object);
  real eo = cert_eo;
  real t;
  if (has_kind(RC_KIND_SPHERES) && (kinds & RC_KIND_SPHERES) != 0u && kind == RC_HIT_SPHERE) {
    packed_sphere s = load_sphere(index);
    cert_eo += cert_et;  // as cert_object: the other kinds' bounds take the move along the ray
    cert_sphere(o, d, s, t_max);
    cert_eo = eo;
    t = intersect_any_sphere(o, d, s, t_max, side);
  } else if (has_kind(RC_KIND_TRIANGLES) && (kinds & RC_KIND_TRIANGLES) != 0u && kind == RC_HIT_TRIANGLE) {
    packed_triangle tri = load_triangle(index);
    cert_triangle_object(tri, o, d, sh, t_max);
    t = intersect_triangle_object(tri, o, d, sh, t_max, bary);
  } else {
    cert_eo += cert_et;
    cert_other_object_tests(kinds, kind, index, o, d, any, t_max);
    cert_eo = eo;
    t = intersect_other_object(kinds, kind, index, o, d, t_max, bary, part);
  }
  cert_test_end(ok);
  return t;
#else
  return intersect_object(kinds, object, o, d, sh, t_max, side, bary, part);
#endif
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
    real t = test_object(RC_KIND_ALL, i, o, d, sh, false, h.t, side, bary, part);
    consider_hit(i, t, side, bary, part, h);
  }
}

// Any hit in (0, t_max]: the shadow-ray query, with an early exit. (A miss is RC_T_FAR,
// which a directional light's t_max equals: only a real hit blocks.)
bool occluded_linear(rvec3 o, rvec3 d, real t_max) {
  ray_shear sh = ray_shear_for(d);
  for (uint i = 0u; i < frame.object_count; i++) {
#if RC_CERTIFY
    if (certify && cert_blocked_later && budget_steps + 1u > loop_budget) break;
#endif
    if (!budget_step()) {
      budget_blame = 1u + i;
      return false;
    }
    real side;
    rvec3 bary;
    uint part;
    bool blocks = test_object(RC_KIND_ALL, i, o, d, sh, true, t_max, side, bary, part) < real(RC_T_FAR);
#if RC_CERTIFY
    if (certify && blocks && !cert_blocker_ends()) continue;
#endif
    if (blocks) return true;
  }
  return false;
}
