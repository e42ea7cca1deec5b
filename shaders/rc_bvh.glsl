// rc_bvh.glsl: BVH traversal (host/scene/bvh.c builds the tree) and the closest-hit and
// occlusion queries the shading code calls.

// 1/d with zero components replaced by a huge finite value: Vulkan lets shaders assume no
// Inf (the SPIR-V environment of the Vulkan specification), and a huge finite slope gives
// the same slab answer.
rvec3 safe_inverse(rvec3 d) {
  const real tiny = real(1e-30);
  return rvec3(1.0) / rvec3(d.x >= 0.0 ? max(d.x, tiny) : min(d.x, -tiny),
                            d.y >= 0.0 ? max(d.y, tiny) : min(d.y, -tiny),
                            d.z >= 0.0 ? max(d.z, tiny) : min(d.z, -tiny));
}

// Entry distance of the ray into the box [lo, hi] if it enters before t_max, else
// RC_T_FAR. The far distance is scaled up by RC_BOX_FAR_SCALE so rounding never culls a
// touched box, and t_max by RC_BOX_NEAR_SCALE so rounding never culls an object that
// ties with the hit t_max came from.
real intersect_box(rvec3 lo, rvec3 hi, rvec3 o, rvec3 inv_d, real t_max) {
  precise rvec3 t0 = (lo - o) * inv_d;
  precise rvec3 t1 = (hi - o) * inv_d;
  real t_enter = select_max(select_max(select_min(t0.x, t1.x), select_min(t0.y, t1.y)),
                            select_max(select_min(t0.z, t1.z), 0.0));
  real t_exit = select_min(select_min(select_max(t0.x, t1.x), select_max(t0.y, t1.y)), select_max(t0.z, t1.z)) *
                real(RC_BOX_FAR_SCALE);
  return (t_enter <= t_exit && t_enter <= t_max * real(RC_BOX_NEAR_SCALE)) ? t_enter : real(RC_T_FAR);
}

// Whether the pipeline has the loose quadrics' loop (the generic pipeline has it, and its
// frame says whether it runs): a constant that the host's specialization folds.
const bool loose_quadrics = (scene_kinds & RC_KIND_LOOSE_QUADRICS) != 0u;

// The kinds (RC_KIND_*) of the objects frame.loose_kinds keeps out of the tree: the
// specialization's where the pipeline was specialized, else the frame's.
uint loose_kinds() {
  return scene_kinds == RC_KIND_ALL ? frame.loose_kinds : (loose_quadrics ? RC_KIND_QUADRICS : 0u);
}

// The kinds the tree's leaves can hold, a constant for intersect_object: those the scene has
// but the loose ones, where the quadrics' include the patch pieces. The generic pipeline's
// leaves keep every kind's test, as its one module must serve every frame.
uint tree_kinds() { return scene_kinds == RC_KIND_ALL ? RC_KIND_ALL : ~loose_kinds(); }

// Tests the objects of one leaf; true when `any` and one of them blocks. The caller has
// taken the loop's steps from the budget (budget_take).
bool test_leaf(uint first, uint count, rvec3 o, rvec3 d, ray_shear sh, bool any, real t_max, inout hit_record h) {
  for (uint k = first; k < first + count; k++) {
    uint object = load_bvh_prim(k);
    real side;
    rvec3 bary;
    uint part;
    real t = test_object(tree_kinds(), object, o, d, sh, any, any ? t_max : h.t, side, bary, part);
#if RC_CERTIFY
    if (certify && any && t < real(RC_T_FAR) && !cert_blocker_ends()) continue;
#endif
    if (any && t < real(RC_T_FAR)) return true;
    consider_hit(object, t, side, bary, part, h);
  }
  return false;
}

// Closest hit through the BVH (any = false), or the first hit within t_max (any = true).
// Stackless: nodes are in depth-first order, so a node whose box the ray enters (before
// the nearest hit so far) continues at the next node, its first child, and a missed box
// or a tested leaf continues at `skip`, past its subtree. No per-lane stack in private
// memory (llvmpipe lowers such arrays to scratch with per-lane gathers and scatters, and
// a real GPU spills them), one box and one fetch of two texels per step. Children are
// ordered near-to-far from the eye at build time (host/scene/bvh.c), which is what a primary
// ray needs; the tie rule (consider_hit) makes the result independent of the order.
// The walk covers the nodes [first, end): the whole object tree, or the range a light
// buffer's cell names (shadow_nodes), which is a subtree or a leaf made for the cell.
bool traverse_bvh(rvec3 o, rvec3 d, bool any, real t_max, uint first, uint end, inout hit_record h) {
  ray_shear sh = ray_shear_for(d);
  rvec3 inv_d = safe_inverse(d);
  uint node = first;
  uint node_count = end;
  while (node < node_count) {
    // "While-while" (Aila & Laine, "Understanding the Efficiency of Ray Traversal on
    // GPUs", HPG 2009): walk boxes until this ray holds a leaf, then test it. A SIMD
    // vector runs the union of its lanes' work, and alternating one box and one leaf per
    // iteration made nearly every iteration pay for a leaf test some lane needed.
    // The walk has one exit, its condition (budget included): each break or return out
    // of a loop costs llvmpipe mask bookkeeping on every iteration (finding 11).
    uint leaf = 0u;
    while (node < node_count && leaf == 0u && budget_steps < loop_budget) {
      budget_steps++;
      packed_bvh_node n = load_bvh_node(node);
      real limit = any ? t_max : h.t;
#if RC_CERTIFY
      if (certify) limit = any ? cert_limit(t_max, cert_t_max_err) : cert_limit(h.t, h.err);
#endif
      bool enters = intersect_box(rvec3(n.lo), rvec3(n.hi), o, inv_d, limit) < real(RC_T_FAR);
      // An entered inner node continues at its first child, the next node; a missed box
      // continues past its subtree, and so does an entered leaf once it is tested.
      node = (enters && n.leaf == 0u) ? node + 1u : n.skip;
      leaf = enters ? n.leaf : 0u;
    }
    if (leaf == 0u) {
      bool stopped = node < node_count;  // by the budget
#if RC_CERTIFY
      stopped = stopped && !(certify && cert_blocked_later);  // not where the answer is known
#endif
      if (stopped) budget_exhausted = true;
      break;
    }
    uint count = leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u);
#if RC_CERTIFY
    if (certify && cert_blocked_later && budget_steps + count > loop_budget) break;
#endif
    if (!budget_take(count)) {
      budget_blame = 1u + load_bvh_prim(leaf >> RC_BVH_LEAF_SHIFT);
      return false;
    }
    if (test_leaf(leaf >> RC_BVH_LEAF_SHIFT, count, o, d, sh, any, t_max, h)) return true;
  }
  return !budget_exhausted && h.kind != RC_HIT_NONE;
}

// The infinite planes, the last frame.plane_count standalone quadrics, have no box and no
// place in the tree: after the traversal every ray tests each of them. True when `any`
// and one blocks.
bool test_planes(rvec3 o, rvec3 d, bool any, real t_max, inout hit_record h) {
#if RC_QUADRICS
  if (!has_kind(RC_KIND_PLANES)) return false;  // compiled out where the scene has none
  uint first = frame.quadric_count - frame.plane_count;  // in the quadric array
#if RC_CERTIFY
  if (certify && cert_blocked_later && budget_steps + frame.plane_count > loop_budget) return false;
#endif
  if (!budget_take(frame.plane_count)) {
    budget_blame = 1u + first_quadric_object + first;
    return false;
  }
  // intersect_plane itself, not intersect_object: a SIMD shader inlines everything, and
  // another copy of the whole object dispatch (composites included) here cost the
  // quadric and CSG scenes 25-40 % of their frame time; even this loop, never entered,
  // cost 6 % until RC_KIND_PLANES compiled it out.
  for (uint k = first; k < frame.quadric_count; k++) {
    packed_quadric q = load_quadric(k);
#if RC_CERTIFY
    if (certify) cert_plane_object(first_quadric_object + k, q, o, d, any ? t_max : h.t);
#endif
    real t = intersect_plane(q, o, d, any ? t_max : h.t);
#if RC_CERTIFY
    if (certify && any && t < real(RC_T_FAR) && !cert_blocker_ends()) continue;
#endif
    if (any && t < real(RC_T_FAR)) return true;
    consider_hit(first_quadric_object + k, t, 0.0, rvec3(0.0), csg_code(k, 0u, false, false), h);
  }
#endif
  return false;
}

// A loose object's test ended at t: true when `any` and it blocks (test_leaf's rule).
bool loose_hit(uint object, real t, real side, rvec3 bary, uint part, bool any, inout hit_record h) {
#if RC_CERTIFY
  if (certify && any && t < real(RC_T_FAR) && !cert_blocker_ends()) return false;
#endif
  if (any && t < real(RC_T_FAR)) return true;
  consider_hit(object, t, side, bary, part, h);
  return false;
}

#if RC_QUADRICS
// The bounded standalone quadrics (the planes have their own loop, test_planes), each by
// its own test, called directly: a SIMD shader runs every test a loop body holds, and the
// driver inlines every call before it folds a constant argument, so intersect_object here
// would cost the loop every kind's code (and the pipeline's creation its compile time).
// True when `any` and one blocks.
bool test_loose_quadrics(rvec3 o, rvec3 d, bool any, real t_max, inout hit_record h) {
  for (uint object = first_quadric_object; object < first_quadric_object + frame.quadric_count - frame.plane_count;
       object++) {
#if RC_CERTIFY
    if (certify) cert_object(RC_KIND_QUADRICS, object, o, d, any, any ? t_max : h.t);
#endif
    rvec3 bary;
    uint part;
    real t = intersect_quadric_object(object - first_quadric_object, o, d, any ? t_max : h.t, bary, part);
    if (loose_hit(object, t, 0.0, bary, part, any, h)) return true;
  }
  return false;
}
#endif

// The loose objects (frame.loose_kinds, host/scene/bvh.c: a few bounded quadrics beside
// composites): every ray tests them before the tree, so that the composites' leaves do not
// run the quadric test under a SIMD mask. Before the tree: a hit here shortens the walk,
// and a blocker ends a shadow ray's query. True when `any` and one blocks.
bool test_loose(rvec3 o, rvec3 d, bool any, real t_max, inout hit_record h) {
#if RC_QUADRICS
  // Under a constant alone in its `if`, which the host's specialization folds
  // (host/gpu/spirv_specialize.cpp; an `&&` would hide it behind a short circuit): a
  // pipeline without loose objects has no code for them.
  if (loose_quadrics) {
    if ((loose_kinds() & RC_KIND_QUADRICS) == 0u) return false;
    uint count = frame.quadric_count - frame.plane_count;
#if RC_CERTIFY
    if (certify && cert_blocked_later && budget_steps + count > loop_budget) return false;
#endif
    if (!budget_take(count)) {
      budget_blame = 1u + first_quadric_object;
      return false;
    }
    return test_loose_quadrics(o, d, any, t_max, h);
  }
#endif
  return false;
}

// The nodes a primary ray through `pixel` must walk: its tile of the eye buffer
// (rc_shared.h, RC_EYE_BUFFER_*; host/scene/light_buffer.h), or the whole tree.
uvec2 eye_nodes(uvec2 pixel) {
  uvec2 whole = uvec2(0u, frame.bvh_node_count);
  if (frame.light_buffers == 0u) return whole;
  uvec2 entry = load_bvh_prim_pair(frame.light_buffers + 2u * frame.light_count);
  if (entry.x == 0u) return whole;
  uint shift = entry.y & ((1u << RC_EYE_BUFFER_COLUMNS_SHIFT) - 1u);
  uint columns = entry.y >> RC_EYE_BUFFER_COLUMNS_SHIFT;
  return load_bvh_prim_pair(entry.x + 2u * ((pixel.y >> shift) * columns + (pixel.x >> shift)));
}

// The queries shading uses: the BVH or brute force, as the pipeline was specialized.
// `nodes` is the part of the tree the ray can meet: eye_nodes for a primary ray, else all.
bool closest_hit(rvec3 o, rvec3 d, uvec2 nodes, out hit_record h) {
  h = no_hit();
#if RC_CERTIFY
  if (certify) {
    cert_any = false;
    cert_beyond = real(RC_T_FAR);
  }
#endif
  if (use_bvh) {
    test_loose(o, d, false, real(RC_T_FAR), h);
    traverse_bvh(o, d, false, real(RC_T_FAR), nodes.x, nodes.y, h);
    test_planes(o, d, false, real(RC_T_FAR), h);
  } else {
    closest_hit_linear(o, d, h);
  }
#if RC_CERTIFY
  if (certify) cert_closest(h);
#endif
  return h.kind != RC_HIT_NONE;
}

// The nodes a shadow ray along d towards light `light` must walk, at most t_max long: its
// light buffer's cell (RC_LIGHT_BUFFER_RES, host/scene/light_buffer.h), or the whole tree
// where the light has no buffer or the ray starts beyond the buffer's reach. The cell is
// the face of d's largest component and d's other two over it, in f32 on both backends (the
// buffer is conservative by more than that rounding: docs/numerics.md §9).
uvec2 shadow_nodes(uint light, rvec3 d, real t_max) {
  uvec2 whole = uvec2(0u, frame.bvh_node_count);
  if (frame.light_buffers == 0u) return whole;
  uvec2 entry = load_bvh_prim_pair(frame.light_buffers + 2u * light);
  if (entry.x == 0u || !(t_max <= real(uintBitsToFloat(entry.y)))) return whole;
  vec3 v = vec3(d);
  vec3 a = abs(v);
  uint axis = (a.x >= a.y && a.x >= a.z) ? 0u : (a.y >= a.z ? 1u : 2u);
  float major = axis == 0u ? a.x : (axis == 1u ? a.y : a.z);
  if (!(major > 0.0)) return whole;
  float sign_of = axis == 0u ? v.x : (axis == 1u ? v.y : v.z);
  uint face = 2u * axis + (sign_of < 0.0 ? 1u : 0u);
  float s = (axis == 0u ? v.y : v.x) / major;
  float t = (axis == 2u ? v.y : v.z) / major;
  if (!(abs(s) <= 1.5 && abs(t) <= 1.5)) return whole;  // NaN
  float res = float(RC_LIGHT_BUFFER_RES);
  uint i = uint(clamp(floor((s + 1.0) * 0.5 * res), 0.0, res - 1.0));
  uint j = uint(clamp(floor((t + 1.0) * 0.5 * res), 0.0, res - 1.0));
  return load_bvh_prim_pair(entry.x + 2u * ((face * RC_LIGHT_BUFFER_RES + j) * RC_LIGHT_BUFFER_RES + i));
}

bool occluded(rvec3 o, rvec3 d, real t_max, uint light) {
#if RC_CERTIFY
  bool ok = cert_ok;
  if (certify) {
    cert_any = true;
    cert_blocked_later = false;
    cert_blocker_certain = false;
  }
#endif
  bool blocked;
  if (!use_bvh) {
    blocked = occluded_linear(o, d, t_max);
  } else {
    hit_record h = no_hit();
    uvec2 nodes = shadow_nodes(light, d, t_max);
    blocked = test_loose(o, d, true, t_max, h) || traverse_bvh(o, d, true, t_max, nodes.x, nodes.y, h) ||
              test_planes(o, d, true, t_max, h);
  }
#if RC_CERTIFY
  if (certify) {
    blocked = blocked || cert_blocked_later;
    cert_blocked(blocked, ok);
  }
#endif
  return blocked;
}
