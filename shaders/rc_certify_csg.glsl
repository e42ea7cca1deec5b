// rc_certify_csg.glsl: certified decisions of composite solids (intersect_csg; docs/numerics.md
// §10). The certificate reruns the composite's program over interval lists whose ends carry
// error bounds (csg_e): each leaf's list must have the reference's shape (the same ends on the
// same surfaces, cert_leaf_intervals), each merge must take the ends in the reference's order
// (cert_combine), and the first end ahead is then judged as any root (cert_first_end). A leaf's
// ends behind the ray count too: they decide whether the ray starts inside. A mesh
// operand's list is its crossings' (cert_mesh_intervals).

// A leaf's intervals (solid_intervals, whose ends it writes at `base`), each end's bound in
// csg_e: a box face's that of its span end (cert_box), a root's the roots' (cert_quadric_kind),
// an open end none (RC_T_FAR is the same constant in both precisions). False, the test
// failed, where the list's shape is uncertain: whether the box is met, the quadric's kind,
// which of a box face and a root a clip keeps, whether a piece exists, which face wins a span.
bool cert_leaf_intervals(uint leaf, packed_quadric q, rvec3 o, rvec3 d, uint base, out uint n) {
  n = solid_intervals(leaf, q, o, d, false, base);
  real k = cert_factor();
  rvec3 f, v, ef, ev;
  real b_in, b_out, e_in, e_out;
  uint sure;
  uint box = cert_quadric_box(q, o, d, f, v, ef, ev, b_in, b_out, e_in, e_out, sure);
  if (box == 0u && n == 0u) return true;
  uint kind;
  real t_lo, t_hi, e_r;
  if (box != 1u || !cert_quadric_kind(q, f, v, ef, ev, b_in, b_out, e_in, e_out, real(RC_T_FAR), true, kind, t_lo,
                                      t_hi, e_r)) {
    cert_fail();
    return false;
  }
  real lo0 = (kind == RC_QR_BETWEEN) ? t_lo : -real(RC_T_FAR);
  real hi0 = (kind == RC_QR_OUTSIDE) ? t_lo : ((kind == RC_QR_BETWEEN) ? t_hi : real(RC_T_FAR));
  uint pieces = (kind == RC_QR_NONE) ? 0u : ((kind == RC_QR_OUTSIDE) ? 2u : 1u);
  uint m = 0u;
  for (uint p = 0u; p < pieces; p++) {
    if (!budget_step()) return false;
    real lo = (p == 0u) ? lo0 : t_hi;
    real hi = (p == 0u) ? hi0 : real(RC_T_FAR);
    real e_lo = (abs(lo) < real(RC_T_FAR)) ? e_r : 0.0;
    real e_hi = (abs(hi) < real(RC_T_FAR)) ? e_r : 0.0;
    bool box_starts = b_in >= lo;
    bool box_ends = b_out <= hi;
    bool clip_sure = (!(abs(lo) < real(RC_T_FAR)) || abs(b_in - lo) > k * (e_in + e_lo)) &&
                     (!(abs(hi) < real(RC_T_FAR)) || abs(b_out - hi) > k * (e_out + e_hi));
    bool face_sure = (!box_starts || (sure & 1u) != 0u) && (!box_ends || (sure & 2u) != 0u);
    real s = box_starts ? b_in : lo;
    real e = box_ends ? b_out : hi;
    real e_s = box_starts ? e_in : e_lo;
    real e_e = box_ends ? e_out : e_hi;
    if (s - e > k * (e_s + e_e)) continue;
    if (!clip_sure || !face_sure || !(e - s > k * (e_s + e_e)) || m + 2u > n) {
      cert_fail();
      return false;
    }
    csg_e[base + m] = e_s;
    csg_e[base + m + 1u] = e_e;
    m += 2u;
  }
  if (m != n) cert_fail();
  return m == n;
}

// A shadow ray's crossings near an edge (cert_mesh_intervals' notes, t within e): certain where
// they are two, the two sides of one edge (cert_edge_pair). Each precision then lists exactly
// one of the two triangles, the reference at a t in either's interval, so the listed end's
// bound grows to cover the other's interval too (k >= 1 outside the fault modes). Which
// triangle it is, and so the normal, is uncertain: only a shadow ray, which asks for none,
// notes crossings. The list holds triangle indices still, not mesh codes.
bool cert_edge_crossing(uint base, uint n, uint note0, real t0, real e0, uint note1, real t1, real e1, uint notes) {
  if (notes != 2u || !cert_edge_pair(note0, note1)) return false;
  uint found = 0u;
  uint at = 0u;
  real t_other = 0.0;
  real e_other = 0.0;
  for (uint i = 0u; i < n; i++) {  // n <= q.mesh_crossings: no budget needed
    bool first = csg_code_of[base + i] == (note0 >> RC_CERT_EDGE_SHIFT);
    bool second = csg_code_of[base + i] == (note1 >> RC_CERT_EDGE_SHIFT);
    if (first || second) {
      found++;
      at = i;
      t_other = first ? t1 : t0;
      e_other = first ? e1 : e0;
    }
  }
  if (found != 1u) return false;
  real e = (abs(csg_t[base + at] - t_other) + e_other) * (1.0 + gamma_bound(3.0));
  csg_e[base + at] = select_max(csg_e[base + at], e);
  return true;
}

// A mesh operand's crossings, listed as mesh_intervals lists them (at `base`, the same ends
// in the same order with the same codes), each end's bound in csg_e, in one walk of its BVH:
// a second walk after mesh_intervals' cost the composite's certified test a third of its
// time (docs/performance.md, "One walk of a certified mesh operand"). Every BVH node the test
// skips must be certainly missed by the reference's line (cert_box, in the scene's frame),
// and every triangle it tests certainly crossed or not (cert_crossing), except near an edge:
// there the reference may cross the neighbour instead, or at a silhouette cross twice where
// this precision crosses not at all (or the other way round), but only within the plane's
// interval, which must then be behind the origin or past the query (cert_maybe): the mesh is
// closed, so such differences come in pairs and leave the parity, inside or outside, alike at
// the origin, and what lies past t_max (or past the nearest hit, which cert_maybe keeps)
// cannot change the first end before it. Two crossings nearer each other than their bounds
// likewise. In a shadow query (`any`, a constant in each inlined copy of the test) a crossing
// near one edge inside the segment is noted instead, and two notes on the sides of one edge
// make one certain crossing (cert_edge_crossing). False, the test failed, where a triangle
// is edge-on, or where mesh_intervals would blame the composite (crossing_blame, which its
// test sets again).
bool cert_mesh_intervals(uint csg, packed_quadric q, rvec3 o, rvec3 d, bool any, real t_max, uint base, out uint n) {
  n = 0u;
  real k = cert_factor();
  ray_shear sh = ray_shear_for(d);
  rvec3 ef = rvec3(cert_eo, cert_eo, cert_eo);
  rvec3 ev = rvec3(cert_ed, cert_ed, cert_ed);
  uint node = q.mesh_root;
  // A shadow ray's crossings near one edge, up to two (cert_edge_crossing).
  uint notes = 0u;
  uint note0 = 0u;
  uint note1 = 0u;
  real t0 = 0.0;
  real e0 = 0.0;
  real t1 = 0.0;
  real e1 = 0.0;
  // A box this ray's line misses but the reference's may meet is walked too, up to its skip
  // link (miss_end): under it every triangle must be certainly missed, and mesh_intervals,
  // which skips it, lists none of them.
  uint miss_end = 0u;
  while (node < q.mesh_end) {
    if (!budget_step()) return false;
    packed_bvh_node b = load_bvh_node(node);
    if (!line_meets_box(rvec3(b.lo), rvec3(b.hi), o, d)) {
      real b_in, b_out, e_in, e_out;
      uint sure;
      if (cert_box(rvec3(b.lo), rvec3(b.hi), o, d, ef, ev, b_in, b_out, e_in, e_out, sure) == 0u) {
        node = b.skip;
        continue;
      }
      if (b.skip > miss_end) miss_end = b.skip;
    }
    if (b.leaf == 0u) {
      node++;
      continue;
    }
    uint first = b.leaf >> RC_BVH_LEAF_SHIFT;
    uint count = b.leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u);
    if (!budget_take(count)) return false;
    for (uint j = first; j < first + count; j++) {
      uint tri = load_bvh_prim(j);
      packed_triangle pt = load_triangle(tri);
      real tc, e;
      uint near;
      uint crossed = cert_crossing(o, sh, pt, tc, e, near);
      if (crossed == 3u) {
        cert_fail();
        return false;
      }
      if (crossed == 0u) continue;
      if (node < miss_end) {
        cert_fail();
        return false;
      }
      bool noted = crossed == 2u && any && near != RC_CERT_NO_EDGE && notes < 2u &&
                   !cert_shadow_ignores(tc - k * e, tc + k * e, t_max);
      if (noted) {  // into slot 0, the earlier note (if any) to slot 1: the pair is unordered
        note1 = note0;
        t1 = t0;
        e1 = e0;
        note0 = (tri << RC_CERT_EDGE_SHIFT) | near;
        t0 = tc;
        e0 = e;
        notes++;
      }
      if (crossed == 2u && !noted) cert_maybe(tc - k * e, tc + k * e, t_max, false);
      // mesh_intervals' entry: its crossing, sorted in as it comes.
      real t = triangle_crossing(o, sh, pt);
      if (t >= real(RC_T_FAR)) continue;
      if (n == q.mesh_crossings) {
        blame_mesh(csg);
        cert_fail();
        return false;
      }
      if (!budget_take(n)) return false;
      sort_in_crossing(base, n, t, tri, true, e);
      n++;
    }
    node = b.skip;
  }
  if ((n & 1u) != 0u) {
    blame_mesh(csg);
    cert_fail();
    return false;
  }
  if (notes != 0u && !cert_edge_crossing(base, n, note0, t0, e0, note1, t1, e1, notes)) {
    cert_fail();
    return false;
  }
  if (!budget_take(n)) return false;
  for (uint i = 0u; i < n; i++) {
    csg_code_of[base + i] = mesh_code(csg_code_of[base + i], i, false);
    if (!(csg_e[base + i] >= 0.0)) {
      cert_fail();
      return false;
    }
    if (i > 0u && !(csg_t[base + i] - csg_t[base + i - 1u] > k * (csg_e[base + i] + csg_e[base + i - 1u])))
      cert_maybe(csg_t[base + i - 1u] - k * csg_e[base + i - 1u], csg_t[base + i] + k * csg_e[base + i], t_max, false);
  }
  return true;
}

// combine_intervals' walk, certified: of the two lists' next ends, the one taken first must
// lie before the other by more than both bounds, or be the same open end (exact in both
// precisions); an end dropped with the one before it must be such an open end too (two
// finite ends equal here need not be equal in the reference). Each end's bound goes with it.
// False, the test failed, where an order is uncertain.
bool cert_combine(uint op, uint a, uint na, uint b, uint nb, out uint n) {
  uint out_base = RC_CSG_STACK * RC_CSG_SLOT;
  real k = cert_factor();
  uint i = 0u;
  uint j = 0u;
  n = 0u;
  bool in_a = false;
  bool in_b = false;
  bool in_r = false;
  while (i < na || j < nb) {
    if (!budget_step()) return false;
    if (i < na && j < nb) {
      real ta = csg_t[a + i];
      real tb = csg_t[b + j];
      bool same_open = ta == tb && !(abs(ta) < real(RC_T_FAR));
      if (!same_open && !(abs(ta - tb) > k * (csg_e[a + i] + csg_e[b + j]))) {
        cert_fail();
        return false;
      }
    }
    bool take_a = j >= nb || (i < na && csg_t[a + i] <= csg_t[b + j]);
    real t;
    real e;
    uint code;
    if (take_a) {
      t = csg_t[a + i];
      e = csg_e[a + i];
      code = csg_code_of[a + i];
      in_a = !in_a;
      i++;
    } else {
      t = csg_t[b + j];
      e = csg_e[b + j];
      code = csg_code_of[b + j] ^ ((op == RC_CSG_DIFFERENCE) ? 1u : 0u);
      in_b = !in_b;
      j++;
    }
    bool in_now = csg_inside(op, in_a, in_b);
    if (in_now == in_r) continue;
    in_r = in_now;
    if (n > 0u && csg_t[out_base + n - 1u] == t) {
      if (abs(t) < real(RC_T_FAR)) {
        cert_fail();
        return false;
      }
      n--;
      continue;
    }
    csg_t[out_base + n] = t;
    csg_e[out_base + n] = e;
    csg_code_of[out_base + n] = code;
    n++;
  }
  return true;
}

// first_interval_end's decision: each finite end in turn is a root (cert_root: behind the ray
// beyond its bound, or the surface a spawned ray leaves; ahead, and within t_max or past it)
// until one is taken.
void cert_first_end(uint n, real t_max) {
  for (uint i = 0u; i < n; i++) {
    if (!budget_step()) return;
    real t = csg_t[i];
    if (abs(t) < real(RC_T_FAR) && cert_root(t, csg_e[i], t_max, t > 0.0)) return;
  }
}

// A composite's decisions (intersect_csg): its program over certified lists, then its first
// end ahead. The end's code (the leaf, the face, entry or exit, the flip) is then the
// reference's: every list's shape and every merge's order are.
void cert_csg(uint index, rvec3 o, rvec3 d, bool any, real t_max) {
  packed_csg c = load_csg(index);
  uint count[RC_CSG_STACK];
  uint sp = 0u;
  for (uint k = 0u; k < c.count; k++) {
    if (!budget_step()) return;
    uint ins = load_csg_instruction(c.first + k);
    uint op = ins >> RC_CSG_OP_SHIFT;
    uint operand = ins & RC_CSG_OPERAND_MASK;
    if (op == RC_CSG_LEAF) {
      packed_quadric q = load_quadric(operand);
      bool listed = (has_kind(RC_KIND_CSG_MESHES) && (q.flags & RC_QUADRIC_MESH) != 0u)
                        ? cert_mesh_intervals(index, q, o, d, any, t_max, sp * RC_CSG_SLOT, count[sp])
                        : cert_leaf_intervals(operand, q, o, d, sp * RC_CSG_SLOT, count[sp]);
      if (!listed) return;
      sp++;
      continue;
    }
    uint a = (sp - 2u) * RC_CSG_SLOT;
    uint n;
    if (!cert_combine(op, a, count[sp - 2u], (sp - 1u) * RC_CSG_SLOT, count[sp - 1u], n)) return;
    for (uint i = 0u; i < n; i++) {
      if (!budget_step()) return;
      csg_t[a + i] = csg_t[RC_CSG_STACK * RC_CSG_SLOT + i];
      csg_e[a + i] = csg_e[RC_CSG_STACK * RC_CSG_SLOT + i];
      csg_code_of[a + i] = csg_code_of[RC_CSG_STACK * RC_CSG_SLOT + i];
    }
    count[sp - 2u] = n;
    sp--;
  }
  cert_first_end(count[0], t_max);
}
