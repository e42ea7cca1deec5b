// rc_bvh.glsl: BVH traversal (host/bvh.c builds the tree) and the closest-hit and
// occlusion queries the shading code calls. Nearest child first with a short stack: each
// node holds both children's boxes, so one node fetch orders them; a popped entry whose
// box starts beyond the current nearest hit is skipped.

// 1/d with zero components replaced by a huge finite value: Vulkan lets shaders assume no
// Inf (ROBUSTNESS.md §1.3), and a huge finite slope gives the same slab answer.
rvec3 safe_inverse(rvec3 d) {
  const real tiny = real(1e-30);
  return rvec3(1.0) / rvec3(d.x >= 0.0 ? max(d.x, tiny) : min(d.x, -tiny),
                            d.y >= 0.0 ? max(d.y, tiny) : min(d.y, -tiny),
                            d.z >= 0.0 ? max(d.z, tiny) : min(d.z, -tiny));
}

// Entry distance of the ray into the box [lo, hi] if it enters before t_max, else
// RC_T_FAR. The far distance is scaled up by RC_BOX_FAR_SCALE so rounding never culls a
// touched box.
real intersect_box(rvec3 lo, rvec3 hi, rvec3 o, rvec3 inv_d, real t_max) {
  precise rvec3 t0 = (lo - o) * inv_d;
  precise rvec3 t1 = (hi - o) * inv_d;
  rvec3 near = min(t0, t1);
  rvec3 far = max(t0, t1);
  real t_enter = max(max(near.x, near.y), max(near.z, 0.0));
  real t_exit = min(min(far.x, far.y), far.z) * real(RC_BOX_FAR_SCALE);
  return (t_enter <= t_exit && t_enter <= t_max) ? t_enter : real(RC_T_FAR);
}

// Tests the objects of one leaf; true when `any` and one of them blocks.
bool test_leaf(uint first, uint count, rvec3 o, rvec3 d, ray_shear sh, bool any, real t_max, inout hit_record h) {
  for (uint k = first; k < first + count; k++) {
    if (!budget_step()) return false;
    uint object = load_bvh_prim(k);
    real side;
    rvec3 bary;
    uint part;
    real t = intersect_object(object, o, d, sh, any ? t_max : h.t, side, bary, part);
    if (any && t < real(RC_T_FAR)) return true;
    consider_hit(object, t, side, bary, part, h);
  }
  return false;
}

// Closest hit through the BVH (any = false), or the first hit within t_max (any = true).
// Leaves are tested as soon as their box is entered; interior children are visited
// nearest first. (No loop over the two children: llvmpipe does not unroll even a
// two-iteration loop, and every loop iteration counts against its cap.)
bool traverse_bvh(rvec3 o, rvec3 d, bool any, real t_max, inout hit_record h) {
  if (frame.bvh_node_count == 0u) return false;
  ray_shear sh = ray_shear_for(d);
  rvec3 inv_d = safe_inverse(d);
  uint stack_node[RC_BVH_STACK_SIZE];
  real stack_t[RC_BVH_STACK_SIZE];
  uint sp = 0u;
  uint node = 0u;
  while (true) {
    if (!budget_step()) return false;
    gpu_bvh_node n = load_bvh_node(node);
    real limit = any ? t_max : h.t;
    real ta = intersect_box(rvec3(n.lo0), rvec3(n.hi0), o, inv_d, limit);
    real tb = intersect_box(rvec3(n.lo1), rvec3(n.hi1), o, inv_d, limit);
    if (n.count0 != 0u && ta < real(RC_T_FAR) && test_leaf(n.child0, n.count0, o, d, sh, any, t_max, h)) return true;
    if (n.count1 != 0u && tb < real(RC_T_FAR) && test_leaf(n.child1, n.count1, o, d, sh, any, t_max, h)) return true;
    if (budget_exhausted) return false;
    // A missed box is RC_T_FAR, which the limit also is until something is hit: compare
    // with both.
    limit = any ? t_max : h.t;
    bool go_a = n.count0 == 0u && ta < real(RC_T_FAR) && ta <= limit;
    bool go_b = n.count1 == 0u && tb < real(RC_T_FAR) && tb <= limit;
    if (go_a && go_b) {
      bool a_first = ta <= tb;
      stack_node[sp] = a_first ? n.child1 : n.child0;
      stack_t[sp] = a_first ? tb : ta;
      sp++;
      node = a_first ? n.child0 : n.child1;
    } else if (go_a) {
      node = n.child0;
    } else if (go_b) {
      node = n.child1;
    } else {
      bool found = false;
      while (sp > 0u && !found) {
        if (!budget_step()) return false;
        sp--;
        found = stack_t[sp] <= (any ? t_max : h.t);
        node = stack_node[sp];
      }
      if (!found) break;
    }
  }
  return h.kind != RC_HIT_NONE;
}

// The queries shading uses: the BVH or brute force, as the pipeline was specialized.
bool closest_hit(rvec3 o, rvec3 d, out hit_record h) {
  h = no_hit();
  if (use_bvh) {
    traverse_bvh(o, d, false, real(RC_T_FAR), h);
  } else {
    closest_hit_linear(o, d, h);
  }
  return h.kind != RC_HIT_NONE;
}

bool occluded(rvec3 o, rvec3 d, real t_max) {
  if (!use_bvh) return occluded_linear(o, d, t_max);
  hit_record h = no_hit();
  return traverse_bvh(o, d, true, t_max, h);
}
