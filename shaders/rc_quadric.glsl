// rc_quadric.glsl: quadric surfaces and solids (packed_quadric) and composite solids
// (packed_csg). A ray meets a solid in depth-ordered [in, out] intervals; a composite combines
// its operands' interval lists (Roth, "Ray Casting for Modeling Solids", CGIP 18(2),
// 1982) and its surface is the first interval end in front of the ray.
//
// An interval end is a t and a code naming the surface it lies on (csg_code): the leaf
// quadric or mesh triangle, the face (0: the quadric surface, 1..3: the leaf's box face
// normal to x, y, z), whether it was the leaf's exit, and whether it comes from a
// subtracted solid (its outward normal is then reversed).

// The interval stack (RC_CSG_SLOT, rc_shared.h); in certified mode, each end's error bound
// beside it (rc_certify_csg.glsl).
real csg_t[(RC_CSG_STACK + 1u) * RC_CSG_SLOT];
uint csg_code_of[(RC_CSG_STACK + 1u) * RC_CSG_SLOT];
#if RC_CERTIFY
real csg_e[(RC_CSG_STACK + 1u) * RC_CSG_SLOT];
#endif

// 1 + the composite whose mesh operand a ray line crossed more often than its bound, or
// an odd number of times (a hole): raycast.comp reports it and the render fails.
uint crossing_blame = 0u;

uint csg_code(uint leaf, uint face, bool leaf_exit, bool flip) {
  return (leaf << RC_CSG_CODE_LEAF_SHIFT) | (face << 2u) | (leaf_exit ? 2u : 0u) | (flip ? 1u : 0u);
}

// A point or direction in the quadric's frame (centre-relative, rotated; for a point,
// pass p - center). Forming a, b, c there keeps the products small (docs/numerics.md §3).
rvec3 quadric_local(packed_quadric q, rvec3 v) {
  precise rvec3 l = rvec3(dot(rvec3(q.axis_x), v), dot(rvec3(q.axis_y), v), dot(rvec3(q.axis_z), v));
  return l;
}

// M v for the quadric's symmetric 3x3 part.
rvec3 quadric_apply(packed_quadric q, rvec3 v) {
  rvec3 D = rvec3(q.diag);
  rvec3 O = rvec3(q.off);
  precise rvec3 r = rvec3(D.x * v.x + O.x * v.y + O.y * v.z, O.x * v.x + D.y * v.y + O.z * v.z,
                          O.y * v.x + O.z * v.y + D.z * v.z);
  return r;
}

// The quadratic a t^2 + 2 h t + c of Q along f + t v (the ray in the quadric's frame):
// a = v.Mv, h = f.Mv + L.v, c = f.Mf + 2 L.f + J, and the products they are made of, which
// the discriminant and the certificate's bounds (rc_certify.glsl) reuse.
struct quadric_terms {
  rvec3 mv;  // M v
  rvec3 mf;  // M f
  real m;    // f.Mv
  real ld;   // L.v
  real lf;   // L.f
  real a;
  real h;
  real c;
};

quadric_terms quadric_coefficients(packed_quadric q, rvec3 f, rvec3 v) {
  rvec3 L = rvec3(q.linear);
  precise rvec3 mv = quadric_apply(q, v);
  precise rvec3 mf = quadric_apply(q, f);
  precise real m = dot(f, mv);
  precise real ld = dot(L, v);
  precise real lf = dot(L, f);
  precise real a = dot(v, mv);
  precise real h = m + ld;
  precise real c = dot(f, mf) + 2.0 * lf + real(q.constant);
  return quadric_terms(mv, mf, m, ld, lf, a, h, c);
}

// The 2x2 minors v_i f_j - v_j f_i (xy, xz, yz) of Lagrange's identity below.
rvec3 quadric_minors(rvec3 f, rvec3 v) {
  precise rvec3 w = rvec3(v.x * f.y - v.y * f.x, v.x * f.z - v.z * f.x, v.y * f.z - v.z * f.y);
  return w;
}

// h^2 - a c. For a diagonal M (the named shapes) it is formed by Lagrange's identity, the
// Hearn-Baker form of the sphere test generalized (D = diag, L = linear, J = constant):
//   h^2 - a c = -sum_{i<j} D_i D_j (v_i f_j - v_j f_i)^2 + 2 (sum D_i v_i f_i)(L.v)
//               - 2 a (L.f) + (L.v)^2 - a J,
// with no cancellation between two large squares when the quadric is far away; a general
// matrix uses h^2 - a c as it stands.
real quadric_discriminant(packed_quadric q, rvec3 f, rvec3 v, quadric_terms k) {
  rvec3 D = rvec3(q.diag);
  real J = real(q.constant);
  precise real disc;
  if (q.off == vec3(0.0)) {
    precise rvec3 w = quadric_minors(f, v);
    disc = -(D.x * D.y * w.x * w.x + D.x * D.z * w.y * w.y + D.y * D.z * w.z * w.z) + 2.0 * k.m * k.ld -
           2.0 * k.a * k.lf + k.ld * k.ld - k.a * J;
  } else {
    disc = k.h * k.h - k.a * k.c;
  }
  return disc;
}

// The roots of the quadratic (quadric_coefficients), classified. They are the stable pair
// c/q, q/a with q = -(h + sign(h) sqrt(disc)); a = 0 (a ray parallel to a cylinder's or
// paraboloid's axis) has its own branch, and a root beyond RC_T_FAR (a tiny a) is pinned
// there instead of dividing (docs/numerics.md §3).
uint quadric_roots(packed_quadric q, rvec3 f, rvec3 v, out real t_lo, out real t_hi) {
  t_lo = -real(RC_T_FAR);
  t_hi = real(RC_T_FAR);
  quadric_terms k = quadric_coefficients(q, f, v);
  real a = k.a;
  real h = k.h;
  real c = k.c;
  if (a == 0.0) {
    if (h == 0.0) return (c <= 0.0) ? RC_QR_ALL : RC_QR_NONE;
    // A grazing ray (a plane's tiny v.z) puts the root beyond RC_T_FAR: pinned, not divided.
    precise real root = (abs(c) >= abs(2.0 * h) * real(RC_T_FAR)) ? (((c > 0.0) == (h > 0.0)) ? -real(RC_T_FAR) : real(RC_T_FAR))
                                                                  : -c / (2.0 * h);
    if (h > 0.0) t_hi = root;  // Q falls with t: inside before the root
    else t_lo = root;
    return RC_QR_BETWEEN;
  }
  real disc = quadric_discriminant(q, f, v, k);
  if (disc < 0.0) return (a > 0.0) ? RC_QR_NONE : RC_QR_ALL;
  precise real sq = sqrt(disc);
  precise real qq = (h >= 0.0) ? -(h + sq) : -(h - sq);
  real r0 = 0.0;
  real r1 = 0.0;
  if (qq != 0.0) {
    r0 = (abs(qq) >= abs(a) * real(RC_T_FAR)) ? ((qq > 0.0) == (a > 0.0) ? real(RC_T_FAR) : -real(RC_T_FAR)) : qq / a;
    r1 = (abs(c) >= abs(qq) * real(RC_T_FAR)) ? ((c > 0.0) == (qq > 0.0) ? real(RC_T_FAR) : -real(RC_T_FAR)) : c / qq;
  }
  t_lo = min(r0, r1);
  t_hi = max(r0, r1);
  return (a > 0.0) ? RC_QR_BETWEEN : RC_QR_OUTSIDE;
}

// One slab of box_span: narrows [t_in, t_out] to the ray's span between the planes lo and
// hi of axis k (1..3). A ray parallel to them (d = 0) keeps the span, or empties it when
// its origin lies outside, without dividing by 0.
void box_slab(real lo, real hi, real o, real d, uint k, inout real t_in, inout real t_out, inout uint axis_in,
              inout uint axis_out) {
  if (d == 0.0) {
    if (o < lo || o > hi) t_in = real(RC_T_FAR);
    return;
  }
  precise real ta = (lo - o) / d;
  precise real tb = (hi - o) / d;
  if (min(ta, tb) > t_in) {
    t_in = min(ta, tb);
    axis_in = k;
  }
  if (max(ta, tb) < t_out) {
    t_out = max(ta, tb);
    axis_out = k;
  }
}

// The ray's span inside the box [lo, hi] (all in the quadric's frame): entry and exit t, and the axes (1..3) whose
// faces they lie on; a miss gives t_in > t_out. (Three calls, not a loop: llvmpipe counts
// every loop iteration against its cap, rc_budget.glsl.)
void box_span(rvec3 lo, rvec3 hi, rvec3 o, rvec3 d, out real t_in, out real t_out, out uint axis_in, out uint axis_out) {
  t_in = -real(RC_T_FAR);
  t_out = real(RC_T_FAR);
  axis_in = 1u;
  axis_out = 1u;
  box_slab(lo.x, hi.x, o.x, d.x, 1u, t_in, t_out, axis_in, axis_out);
  box_slab(lo.y, hi.y, o.y, d.y, 2u, t_in, t_out, axis_in, axis_out);
  box_slab(lo.z, hi.z, o.z, d.z, 3u, t_in, t_out, axis_in, axis_out);
}

// The solid {Q <= 0} along the ray's whole line, in the quadric's frame: the box's span
// [b_in, b_out] and the axes (1..3) of the faces it starts and ends on, and the inside
// pieces of the line before clipping to the box, [lo0, hi0] and, for OUTSIDE, [t_hi, +inf)
// (-/+ RC_T_FAR for an open end); `pieces` 0 where the line misses the box or the solid.
struct solid_line {
  real b_in;
  real b_out;
  uint a_in;
  uint a_out;
  real lo0;
  real hi0;
  real t_hi;
  uint pieces;
};

solid_line solid_line_of(packed_quadric q, rvec3 o, rvec3 d) {
  solid_line l;
  l.pieces = 0u;
  l.lo0 = 0.0;
  l.hi0 = 0.0;
  l.t_hi = 0.0;
  rvec3 f = quadric_local(q, o - rvec3(q.center));
  rvec3 v = quadric_local(q, d);
  box_span(rvec3(q.lo), rvec3(q.hi), f, v, l.b_in, l.b_out, l.a_in, l.a_out);
  if (l.b_in > l.b_out) return l;
  real t_lo;
  uint kind = quadric_roots(q, f, v, t_lo, l.t_hi);
  if (kind == RC_QR_NONE) return l;
  l.lo0 = (kind == RC_QR_BETWEEN) ? t_lo : -real(RC_T_FAR);
  l.hi0 = (kind == RC_QR_OUTSIDE) ? t_lo : ((kind == RC_QR_BETWEEN) ? l.t_hi : real(RC_T_FAR));
  l.pieces = (kind == RC_QR_OUTSIDE) ? 2u : 1u;
  return l;
}

// Piece k of the line clipped to the box, [s, e] (s > e: nothing left): it starts on the box
// face where the box starts later, else on Q = 0, and ends likewise.
void solid_piece(solid_line l, uint k, out real s, out real e, out bool box_starts, out bool box_ends) {
  real lo = (k == 0u) ? l.lo0 : l.t_hi;
  real hi = (k == 0u) ? l.hi0 : real(RC_T_FAR);
  box_starts = l.b_in >= lo;
  box_ends = l.b_out <= hi;
  s = box_starts ? l.b_in : lo;
  e = box_ends ? l.b_out : hi;
}

// The solid {Q <= 0} inside its box along the ray: up to two intervals, written to the
// interval stack at `base` (csg_t, csg_code_of). Returns the number of interval ends.
uint solid_intervals(uint leaf, packed_quadric q, rvec3 o, rvec3 d, bool flip, uint base) {
  solid_line l = solid_line_of(q, o, d);
  uint n = 0u;
  for (uint k = 0u; k < l.pieces; k++) {
    if (!budget_step()) return n;
    real s, e;
    bool box_starts, box_ends;
    solid_piece(l, k, s, e, box_starts, box_ends);
    if (s > e) continue;
    csg_t[base + n] = s;
    csg_code_of[base + n] = csg_code(leaf, box_starts ? l.a_in : 0u, false, flip);
    csg_t[base + n + 1u] = e;
    csg_code_of[base + n + 1u] = csg_code(leaf, box_ends ? l.a_out : 0u, true, flip);
    n += 2u;
  }
  return n;
}

// Whether the ray's whole line meets the box, with a margin for the rounding of the slab
// distances: a mesh operand's BVH box culled by rounding would lose a crossing.
bool line_meets_box(rvec3 lo, rvec3 hi, rvec3 o, rvec3 d) {
  real t_in, t_out;
  uint a_in, a_out;
  box_span(lo, hi, o, d, t_in, t_out, a_in, a_out);
  if (t_in >= real(RC_T_FAR)) return false;  // parallel to a slab, outside it
  return t_in <= t_out + 2.0 * gamma_bound(3.0) * (abs(t_in) + abs(t_out));
}

// Fails the composite `csg` loudly: a mesh operand's line crossed it more often than its bound
// allows, or an odd number of times (mesh_intervals).
void blame_mesh(uint csg) { crossing_blame = 1u + first_csg_object + csg; }

// Sorts a mesh operand's crossing, t of triangle `tri`, into its list of n ends at `base`, by
// t as the crossings come; in certified mode (`bounded`, a constant at each call) with its
// bound e beside it (cert_mesh_intervals). The caller has made room for it.
void sort_in_crossing(uint base, uint n, real t, uint tri, bool bounded, real e) {
  uint i = n;
  for (; i > 0u && csg_t[base + i - 1u] > t; i--) {
    csg_t[base + i] = csg_t[base + i - 1u];
    csg_code_of[base + i] = csg_code_of[base + i - 1u];
#if RC_CERTIFY
    if (bounded) csg_e[base + i] = csg_e[base + i - 1u];
#endif
  }
  csg_t[base + i] = t;
  csg_code_of[base + i] = tri;
#if RC_CERTIFY
  if (bounded) csg_e[base + i] = e;
#endif
}

// The code of end i of a mesh operand's sorted crossings, triangle `tri`: by parity, even
// ends enter and odd ends leave.
uint mesh_code(uint tri, uint i, bool flip) { return csg_code(tri, 0u, (i & 1u) != 0u, flip) | RC_CSG_CODE_MESH; }

// A closed mesh operand (RC_QUADRIC_MESH) along the ray: every crossing of the ray's whole
// line with its triangles (its own BVH, stackless like the object tree), sorted by t as they
// come; by parity the crossings pair up into [in, out] intervals (Roth 1982 with a mesh for
// a solid). More crossings than q.mesh_crossings, or an odd number, fail the composite
// `csg` loudly (crossing_blame), never a wrong pixel in silence.
uint mesh_intervals(uint csg, packed_quadric q, rvec3 o, rvec3 d, bool flip, uint base) {
  ray_shear sh = ray_shear_for(d);
  uint n = 0u;
  uint node = q.mesh_root;
  while (node < q.mesh_end) {
    if (!budget_step()) return 0u;
    packed_bvh_node b = load_bvh_node(node);
    if (!line_meets_box(rvec3(b.lo), rvec3(b.hi), o, d)) {
      node = b.skip;
      continue;
    }
    if (b.leaf == 0u) {
      node++;
      continue;
    }
    uint first = b.leaf >> RC_BVH_LEAF_SHIFT;
    uint count = b.leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u);
    if (!budget_take(count)) return 0u;
    for (uint k = first; k < first + count; k++) {
      uint tri = load_bvh_prim(k);
      real t = triangle_crossing(o, sh, load_triangle(tri));
      if (t >= real(RC_T_FAR)) continue;
      if (n == q.mesh_crossings) {
        blame_mesh(csg);
        return 0u;
      }
      if (!budget_take(n)) return 0u;
      sort_in_crossing(base, n, t, tri, false, 0.0);
      n++;
    }
    node = b.skip;
  }
  if ((n & 1u) != 0u) {
    blame_mesh(csg);
    return 0u;
  }
  if (!budget_take(n)) return 0u;
  for (uint i = 0u; i < n; i++) csg_code_of[base + i] = mesh_code(csg_code_of[base + i], i, flip);
  return n;
}

// An open quadric surface (no RC_QUADRIC_SOLID): the nearest root in (0, t_max] whose
// point lies in the box, else RC_T_FAR.
real intersect_quadric_surface(packed_quadric q, rvec3 o, rvec3 d, real t_max) {
  rvec3 f = quadric_local(q, o - rvec3(q.center));
  rvec3 v = quadric_local(q, d);
  real t_lo, t_hi;
  uint kind = quadric_roots(q, f, v, t_lo, t_hi);
  if (kind == RC_QR_NONE || kind == RC_QR_ALL) return real(RC_T_FAR);
  real b_in, b_out;
  uint a_in, a_out;
  box_span(rvec3(q.lo), rvec3(q.hi), f, v, b_in, b_out, a_in, a_out);
  bool lo_ok = t_lo > 0.0 && t_lo <= t_max && abs(t_lo) < real(RC_T_FAR) && t_lo >= b_in && t_lo <= b_out;
  bool hi_ok = t_hi > 0.0 && t_hi <= t_max && abs(t_hi) < real(RC_T_FAR) && t_hi >= b_in && t_hi <= b_out;
  return lo_ok ? t_lo : (hi_ok ? t_hi : real(RC_T_FAR));
}

// The first interval end of the list at `base` (n ends) in (0, t_max], else RC_T_FAR.
real first_interval_end(uint base, uint n, real t_max, out uint code) {
  code = 0u;
  for (uint i = 0u; i < n; i++) {
    if (!budget_step()) break;
    real t = csg_t[base + i];
    if (t > 0.0 && t <= t_max && t < real(RC_T_FAR)) {
      code = csg_code_of[base + i];
      return t;
    }
  }
  return real(RC_T_FAR);
}

// A standalone solid's first interval end in (0, t_max] (RC_T_FAR if none) and its code:
// first_interval_end over solid_intervals' list, in the same order, without writing the list.
// llvmpipe keeps the interval stack in scratch memory, a store there a scatter lane by lane,
// and every quadric a ray tested wrote four.
real solid_first_end(uint leaf, packed_quadric q, rvec3 o, rvec3 d, real t_max, out uint code) {
  code = 0u;
  solid_line l = solid_line_of(q, o, d);
  for (uint k = 0u; k < l.pieces; k++) {
    if (!budget_step()) break;
    real s, e;
    bool box_starts, box_ends;
    solid_piece(l, k, s, e, box_starts, box_ends);
    if (s > e) continue;
    if (s > 0.0 && s <= t_max && s < real(RC_T_FAR)) {
      code = csg_code(leaf, box_starts ? l.a_in : 0u, false, false);
      return s;
    }
    if (e > 0.0 && e <= t_max && e < real(RC_T_FAR)) {
      code = csg_code(leaf, box_ends ? l.a_out : 0u, true, false);
      return e;
    }
  }
  return real(RC_T_FAR);
}

// An infinite plane (RC_QUADRIC_UNBOUNDED): Q = 2 f.z, so the root is t = -f.z / v.z, the
// value quadric_roots finds with a = 0, without its products; a one-sided plane is met
// only by rays moving against its normal. A root beyond RC_T_FAR is a miss, not a division.
real intersect_plane(packed_quadric q, rvec3 o, rvec3 d, real t_max) {
  precise real fz = dot(rvec3(q.axis_z), o - rvec3(q.center));
  precise real vz = dot(rvec3(q.axis_z), d);
  bool facing = ((q.flags & RC_QUADRIC_ONE_SIDED) == 0u) || vz < 0.0;
  if (vz == 0.0 || !facing || abs(fz) >= abs(vz) * real(RC_T_FAR)) return real(RC_T_FAR);
  precise real t = -fz / vz;
  return (t > 0.0 && t <= t_max) ? t : real(RC_T_FAR);
}

// A standalone quadric, open or solid: t and the code of the surface hit.
real intersect_quadric(uint index, rvec3 o, rvec3 d, real t_max, out uint code) {
  code = 0u;
  packed_quadric q = load_quadric(index);
  if ((q.flags & RC_QUADRIC_UNBOUNDED) != 0u) {
    code = csg_code(index, 0u, false, false);
    return intersect_plane(q, o, d, t_max);
  }
  if ((q.flags & RC_QUADRIC_SOLID) == 0u) {
    code = csg_code(index, 0u, false, false);
    return intersect_quadric_surface(q, o, d, t_max);
  }
  return solid_first_end(index, q, o, d, t_max, code);
}

// Whether a point is inside op(A, B), inside A or not and B or not.
bool csg_inside(uint op, bool in_a, bool in_b) {
  return (op == RC_CSG_UNION) ? (in_a || in_b) : ((op == RC_CSG_INTERSECTION) ? (in_a && in_b) : (in_a && !in_b));
}

// Combines the lists at `a` (na ends) and `b` (nb ends) by `op` into the scratch slot:
// one walk over both lists in t order, keeping the ends where op(in a, in b) changes.
// Ends of the subtracted list get the flip bit. Zero-length intervals are dropped and
// touching ones merged, so a tie never leaves a surface of no thickness.
uint combine_intervals(uint op, uint a, uint na, uint b, uint nb) {
  uint out_base = RC_CSG_STACK * RC_CSG_SLOT;
  uint i = 0u;
  uint j = 0u;
  uint n = 0u;
  bool in_a = false;
  bool in_b = false;
  bool in_r = false;
  while (i < na || j < nb) {
    if (!budget_step()) return n;
    bool take_a = j >= nb || (i < na && csg_t[a + i] <= csg_t[b + j]);
    real t;
    uint code;
    if (take_a) {
      t = csg_t[a + i];
      code = csg_code_of[a + i];
      in_a = !in_a;
      i++;
    } else {
      t = csg_t[b + j];
      code = csg_code_of[b + j] ^ ((op == RC_CSG_DIFFERENCE) ? 1u : 0u);
      in_b = !in_b;
      j++;
    }
    bool in_now = csg_inside(op, in_a, in_b);
    if (in_now == in_r) continue;
    in_r = in_now;
    if (n > 0u && csg_t[out_base + n - 1u] == t) {
      n--;  // an interval of no length, or two that touch: drop the shared end
      continue;
    }
    csg_t[out_base + n] = t;
    csg_code_of[out_base + n] = code;
    n++;
  }
  return n;
}

// A composite: runs its postfix program over the interval stack and returns the first
// end of the result in (0, t_max].
real intersect_csg(uint index, rvec3 o, rvec3 d, real t_max, out uint code) {
  code = 0u;
  packed_csg c = load_csg(index);
  uint count[RC_CSG_STACK];
  uint sp = 0u;
  for (uint k = 0u; k < c.count; k++) {
    if (!budget_step()) return real(RC_T_FAR);
    uint ins = load_csg_instruction(c.first + k);
    uint op = ins >> RC_CSG_OP_SHIFT;
    uint operand = ins & RC_CSG_OPERAND_MASK;
    if (op == RC_CSG_LEAF) {
      packed_quadric q = load_quadric(operand);
      if (has_kind(RC_KIND_CSG_MESHES) && (q.flags & RC_QUADRIC_MESH) != 0u) {
        count[sp] = mesh_intervals(index, q, o, d, false, sp * RC_CSG_SLOT);
        if (crossing_blame != 0u) return real(RC_T_FAR);
      } else {
        count[sp] = solid_intervals(operand, q, o, d, false, sp * RC_CSG_SLOT);
      }
      sp++;
      continue;
    }
    uint a = (sp - 2u) * RC_CSG_SLOT;
    uint n = combine_intervals(op, a, count[sp - 2u], (sp - 1u) * RC_CSG_SLOT, count[sp - 1u]);
    for (uint i = 0u; i < n; i++) {
      if (!budget_step()) return real(RC_T_FAR);
      csg_t[a + i] = csg_t[RC_CSG_STACK * RC_CSG_SLOT + i];
      csg_code_of[a + i] = csg_code_of[RC_CSG_STACK * RC_CSG_SLOT + i];
    }
    count[sp - 2u] = n;
    sp--;
  }
  return first_interval_end(0u, count[0], t_max, code);
}

// The outward normal (not normalized) of the surface a code names, at p: grad Q / 2 =
// M f + L in the quadric's frame, or the box face's axis, rotated back to the packed
// space; reversed for the surface of a subtracted solid.
rvec3 quadric_normal(packed_quadric q, uint code, rvec3 p, rvec3 d) {
  uint face = (code >> 2u) & 3u;
  rvec3 g;
  if (face == 0u) {
    g = quadric_apply(q, quadric_local(q, p - rvec3(q.center))) + rvec3(q.linear);
  } else {
    int k = int(face) - 1;
    g = rvec3(0.0);
    // An entry face faces against the ray, an exit face along it.
    g[k] = (((code & 2u) != 0u) == (quadric_local(q, d)[k] > 0.0)) ? 1.0 : -1.0;
  }
  rvec3 n = g.x * rvec3(q.axis_x) + g.y * rvec3(q.axis_y) + g.z * rvec3(q.axis_z);
  return ((code & 1u) != 0u) ? -n : n;
}

// The outward normal (not normalized) of a mesh operand's triangle at an interval end with
// code `code`: the geometric normal turned against the ray at an entry and along it at an
// exit (parity, not the file's winding, tells inside from outside), reversed for a
// subtracted solid.
rvec3 mesh_normal(packed_triangle tri, uint code, rvec3 d) {
  rvec3 g = cross(rvec3(tri.v1) - rvec3(tri.v0), rvec3(tri.v2) - rvec3(tri.v0));
  bool leaving = (code & 2u) != 0u;
  if ((dot(g, d) > 0.0) != leaving) g = -g;
  return ((code & 1u) != 0u) ? -g : g;
}
