/* ref_certify_csg.c: mirrors shaders/rc_certify_csg.glsl function by function (the shader
 * has the reasoning): a composite's certificate over the interval stack of ref_quadric.c. */
#include "ref/ref_shader.h"

#include "ref/ref_real.h"

bool REF(cert_leaf_intervals)(const ref_scene *sc, uint32_t leaf, const packed_quadric *q, rvec3 o, rvec3 d,
                              uint32_t base, uint32_t *n) {
  *n = REF(solid_intervals)(leaf, q, o, d, false, base);
  real k = REF(cert_factor)(sc);
  rvec3 f, v, ef, ev;
  real b_in, b_out, e_in, e_out;
  uint32_t sure;
  uint32_t box = REF(cert_quadric_box)(sc, q, o, d, &f, &v, &ef, &ev, &b_in, &b_out, &e_in, &e_out, &sure);
  if (box == 0 && *n == 0) return true;
  uint32_t kind;
  real t_lo, t_hi, e_r;
  if (box != 1 || !REF(cert_quadric_kind)(sc, q, f, v, ef, ev, b_in, b_out, e_in, e_out, (real)RC_T_FAR, true, &kind,
                                          &t_lo, &t_hi, &e_r)) {
    REF(cert_fail)();
    return false;
  }
  real lo0 = (kind == RC_QR_BETWEEN) ? t_lo : -(real)RC_T_FAR;
  real hi0 = (kind == RC_QR_OUTSIDE) ? t_lo : ((kind == RC_QR_BETWEEN) ? t_hi : (real)RC_T_FAR);
  uint32_t pieces = (kind == RC_QR_NONE) ? 0 : ((kind == RC_QR_OUTSIDE) ? 2 : 1);
  uint32_t m = 0;
  for (uint32_t p = 0; p < pieces; p++) {
    real lo = (p == 0) ? lo0 : t_hi;
    real hi = (p == 0) ? hi0 : (real)RC_T_FAR;
    real e_lo = (R_ABS(lo) < (real)RC_T_FAR) ? e_r : 0;
    real e_hi = (R_ABS(hi) < (real)RC_T_FAR) ? e_r : 0;
    bool box_starts = b_in >= lo;
    bool box_ends = b_out <= hi;
    bool clip_sure = (!(R_ABS(lo) < (real)RC_T_FAR) || R_ABS(b_in - lo) > k * (e_in + e_lo)) &&
                     (!(R_ABS(hi) < (real)RC_T_FAR) || R_ABS(b_out - hi) > k * (e_out + e_hi));
    bool face_sure = (!box_starts || (sure & 1u) != 0) && (!box_ends || (sure & 2u) != 0);
    real s = box_starts ? b_in : lo;
    real e = box_ends ? b_out : hi;
    real e_s = box_starts ? e_in : e_lo;
    real e_e = box_ends ? e_out : e_hi;
    if (s - e > k * (e_s + e_e)) continue;
    if (!clip_sure || !face_sure || !(e - s > k * (e_s + e_e)) || m + 2 > *n) {
      REF(cert_fail)();
      return false;
    }
    csg_e[base + m] = e_s;
    csg_e[base + m + 1] = e_e;
    m += 2;
  }
  if (m != *n) REF(cert_fail)();
  return m == *n;
}

bool REF(cert_edge_crossing)(const ref_scene *sc, uint32_t base, uint32_t n, uint32_t note0, real t0, real e0,
                             uint32_t note1, real t1, real e1, uint32_t notes) {
  if (notes != 2 || !REF(cert_edge_pair)(sc, note0, note1)) return false;
  uint32_t found = 0, at = 0;
  real t_other = 0, e_other = 0;
  for (uint32_t i = 0; i < n; i++) {
    bool first = csg_code_of[base + i] == note0 >> RC_CERT_EDGE_SHIFT;
    bool second = csg_code_of[base + i] == note1 >> RC_CERT_EDGE_SHIFT;
    if (first || second) found++, at = i, t_other = first ? t1 : t0, e_other = first ? e1 : e0;
  }
  if (found != 1) return false;
  real e = (R_ABS(csg_t[base + at] - t_other) + e_other) * (1 + REF(gamma_bound)(3));
  csg_e[base + at] = rmax(csg_e[base + at], e);
  return true;
}

bool REF(cert_mesh_intervals)(const ref_scene *sc, uint32_t csg, const packed_quadric *q, rvec3 o, rvec3 d, bool any,
                              real t_max, uint32_t base, uint32_t *n) {
  *n = 0;
  real k = REF(cert_factor)(sc);
  ref_shear sh = REF(ray_shear_for)(d);
  rvec3 ef = RV(make)(ref_cert_eo, ref_cert_eo, ref_cert_eo);
  rvec3 ev = RV(make)(ref_cert_ed, ref_cert_ed, ref_cert_ed);
  uint32_t node = q->mesh_root;
  uint32_t notes = 0, note0 = 0, note1 = 0;
  real t0 = 0, e0 = 0, t1 = 0, e1 = 0;
  uint32_t miss_end = 0;
  while (node < q->mesh_end) {
    const packed_bvh_node *b = &sc->bvh_nodes[node];
    if (!REF(line_meets_box)(rvec3_from(b->lo), rvec3_from(b->hi), o, d)) {
      real b_in, b_out, e_in, e_out;
      uint32_t sure;
      if (REF(cert_box)(sc, rvec3_from(b->lo), rvec3_from(b->hi), o, d, ef, ev, &b_in, &b_out, &e_in, &e_out, &sure) == 0) {
        node = b->skip;
        continue;
      }
      if (b->skip > miss_end) miss_end = b->skip;
    }
    if (b->leaf == 0) {
      node++;
      continue;
    }
    uint32_t first = b->leaf >> RC_BVH_LEAF_SHIFT;
    uint32_t count = b->leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u);
    for (uint32_t j = first; j < first + count; j++) {
      uint32_t tri = sc->bvh_prims[j];
      packed_triangle pt = sc->triangles[tri];
      real tc, e;
      uint32_t near;
      uint32_t crossed = REF(cert_crossing)(sc, o, &sh, pt, &tc, &e, &near);
      if (crossed == 3) {
        REF(cert_fail)();
        return false;
      }
      if (crossed == 0) continue;
      if (node < miss_end) {
        REF(cert_fail)();
        return false;
      }
      bool noted = crossed == 2 && any && near != RC_CERT_NO_EDGE && notes < 2 &&
                   !REF(cert_shadow_ignores)(sc, tc - k * e, tc + k * e, t_max);
      if (noted) { /* into slot 0, the earlier note (if any) to slot 1: the pair is unordered */
        note1 = note0, t1 = t0, e1 = e0;
        note0 = tri << RC_CERT_EDGE_SHIFT | near, t0 = tc, e0 = e;
        notes++;
      }
      if (crossed == 2 && !noted) REF(cert_maybe)(sc, tc - k * e, tc + k * e, t_max, false);
      real t = REF(triangle_crossing)(o, &sh, pt);
      if (t >= (real)RC_T_FAR) continue;
      if (*n == q->mesh_crossings) {
        REF(blame_mesh)(sc, csg);
        REF(cert_fail)();
        return false;
      }
      REF(sort_in_crossing)(base, *n, t, tri, true, e);
      (*n)++;
    }
    node = b->skip;
  }
  if (*n & 1u) {
    REF(blame_mesh)(sc, csg);
    REF(cert_fail)();
    return false;
  }
  if (notes != 0 && !REF(cert_edge_crossing)(sc, base, *n, note0, t0, e0, note1, t1, e1, notes)) {
    REF(cert_fail)();
    return false;
  }
  for (uint32_t i = 0; i < *n; i++) {
    csg_code_of[base + i] = REF(mesh_code)(csg_code_of[base + i], i, false);
    if (!(csg_e[base + i] >= 0)) {
      REF(cert_fail)();
      return false;
    }
    if (i > 0 && !(csg_t[base + i] - csg_t[base + i - 1] > k * (csg_e[base + i] + csg_e[base + i - 1])))
      REF(cert_maybe)(sc, csg_t[base + i - 1] - k * csg_e[base + i - 1], csg_t[base + i] + k * csg_e[base + i], t_max, false);
  }
  return true;
}

bool REF(cert_combine)(const ref_scene *sc, uint32_t op, uint32_t a, uint32_t na, uint32_t b, uint32_t nb,
                       uint32_t *n) {
  uint32_t out_base = RC_CSG_STACK * RC_CSG_SLOT;
  real k = REF(cert_factor)(sc);
  uint32_t i = 0;
  uint32_t j = 0;
  *n = 0;
  bool in_a = false;
  bool in_b = false;
  bool in_r = false;
  while (i < na || j < nb) {
    if (i < na && j < nb) {
      real ta = csg_t[a + i];
      real tb = csg_t[b + j];
      bool same_open = ta == tb && !(R_ABS(ta) < (real)RC_T_FAR);
      if (!same_open && !(R_ABS(ta - tb) > k * (csg_e[a + i] + csg_e[b + j]))) {
        REF(cert_fail)();
        return false;
      }
    }
    bool take_a = j >= nb || (i < na && csg_t[a + i] <= csg_t[b + j]);
    real t;
    real e;
    uint32_t code;
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
    bool in_now = REF(csg_inside)(op, in_a, in_b);
    if (in_now == in_r) continue;
    in_r = in_now;
    if (*n > 0 && csg_t[out_base + *n - 1] == t) {
      if (R_ABS(t) < (real)RC_T_FAR) {
        REF(cert_fail)();
        return false;
      }
      (*n)--;
      continue;
    }
    csg_t[out_base + *n] = t;
    csg_e[out_base + *n] = e;
    csg_code_of[out_base + *n] = code;
    (*n)++;
  }
  return true;
}

void REF(cert_first_end)(const ref_scene *sc, uint32_t n, real t_max) {
  for (uint32_t i = 0; i < n; i++) {
    real t = csg_t[i];
    if (R_ABS(t) < (real)RC_T_FAR && REF(cert_root)(sc, t, csg_e[i], t_max, t > 0)) return;
  }
}

void REF(cert_csg)(const ref_scene *sc, uint32_t index, rvec3 o, rvec3 d, bool any, real t_max) {
  const packed_csg *c = &sc->csg[index];
  uint32_t count[RC_CSG_STACK];
  uint32_t sp = 0;
  for (uint32_t k = 0; k < c->count; k++) {
    uint32_t ins = sc->csg_program[c->first + k];
    uint32_t op = ins >> RC_CSG_OP_SHIFT;
    uint32_t operand = ins & RC_CSG_OPERAND_MASK;
    if (op == RC_CSG_LEAF) {
      const packed_quadric *q = &sc->quadrics[operand];
      bool listed = ((q->flags & RC_QUADRIC_MESH) != 0)
                        ? REF(cert_mesh_intervals)(sc, index, q, o, d, any, t_max, sp * RC_CSG_SLOT, &count[sp])
                        : REF(cert_leaf_intervals)(sc, operand, q, o, d, sp * RC_CSG_SLOT, &count[sp]);
      if (!listed) return;
      sp++;
      continue;
    }
    uint32_t a = (sp - 2) * RC_CSG_SLOT;
    uint32_t n;
    if (!REF(cert_combine)(sc, op, a, count[sp - 2], (sp - 1) * RC_CSG_SLOT, count[sp - 1], &n)) return;
    for (uint32_t i = 0; i < n; i++) {
      csg_t[a + i] = csg_t[RC_CSG_STACK * RC_CSG_SLOT + i];
      csg_e[a + i] = csg_e[RC_CSG_STACK * RC_CSG_SLOT + i];
      csg_code_of[a + i] = csg_code_of[RC_CSG_STACK * RC_CSG_SLOT + i];
    }
    count[sp - 2] = n;
    sp--;
  }
  REF(cert_first_end)(sc, count[0], t_max);
}
