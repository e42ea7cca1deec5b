/* ref_quadric.c: mirrors shaders/rc_quadric.glsl function by function, same order, same
 * formulas (the shader has the references and the reasoning). The interval stack is
 * per thread, like the shader's per-invocation arrays. */
#include "ref/ref_shader.h"

#include "ref/ref_real.h"

_Thread_local real csg_t[(RC_CSG_STACK + 1u) * RC_CSG_SLOT];
_Thread_local uint32_t csg_code_of[(RC_CSG_STACK + 1u) * RC_CSG_SLOT];
_Thread_local real csg_e[(RC_CSG_STACK + 1u) * RC_CSG_SLOT];

static rvec3 v3(vec3 a) { return rvec3_from(a); }

#if REF_F64 /* one definition for both builds */
_Thread_local uint32_t ref_crossing_blame;
#endif

uint32_t REF(csg_code)(uint32_t leaf, uint32_t face, bool leaf_exit, bool flip) {
  return (leaf << RC_CSG_CODE_LEAF_SHIFT) | (face << 2u) | (leaf_exit ? 2u : 0u) | (flip ? 1u : 0u);
}

rvec3 REF(quadric_local)(const packed_quadric *q, rvec3 v) {
  return RV(make)(RV(dot)(v3(q->axis_x), v), RV(dot)(v3(q->axis_y), v), RV(dot)(v3(q->axis_z), v));
}

rvec3 REF(quadric_apply)(const packed_quadric *q, rvec3 v) {
  rvec3 D = v3(q->diag), O = v3(q->off);
  return RV(make)(D.x * v.x + O.x * v.y + O.y * v.z, O.x * v.x + D.y * v.y + O.z * v.z,
                  O.y * v.x + O.z * v.y + D.z * v.z);
}

ref_quadric_terms REF(quadric_coefficients)(const packed_quadric *q, rvec3 f, rvec3 v) {
  rvec3 L = v3(q->linear);
  rvec3 mv = REF(quadric_apply)(q, v);
  rvec3 mf = REF(quadric_apply)(q, f);
  real m = RV(dot)(f, mv);
  real ld = RV(dot)(L, v);
  real lf = RV(dot)(L, f);
  real a = RV(dot)(v, mv);
  real h = m + ld;
  real c = RV(dot)(f, mf) + 2 * lf + (real)q->constant;
  return (ref_quadric_terms){mv, mf, m, ld, lf, a, h, c};
}

rvec3 REF(quadric_minors)(rvec3 f, rvec3 v) {
  return RV(make)(v.x * f.y - v.y * f.x, v.x * f.z - v.z * f.x, v.y * f.z - v.z * f.y);
}

real REF(quadric_discriminant)(const packed_quadric *q, rvec3 f, rvec3 v, const ref_quadric_terms *k) {
  rvec3 D = v3(q->diag);
  real J = (real)q->constant;
  real disc;
  if (rcm_eq_f(q->off, rcm_make_f(0, 0, 0))) {
    rvec3 w = REF(quadric_minors)(f, v);
    disc = -(D.x * D.y * w.x * w.x + D.x * D.z * w.y * w.y + D.y * D.z * w.z * w.z) + 2 * k->m * k->ld -
           2 * k->a * k->lf + k->ld * k->ld - k->a * J;
  } else {
    disc = k->h * k->h - k->a * k->c;
  }
  return disc;
}

uint32_t REF(quadric_roots)(const packed_quadric *q, rvec3 f, rvec3 v, real *t_lo, real *t_hi) {
  const real far = (real)RC_T_FAR;
  *t_lo = -far;
  *t_hi = far;
  ref_quadric_terms k = REF(quadric_coefficients)(q, f, v);
  real a = k.a;
  real h = k.h;
  real c = k.c;
  if (a == 0) {
    if (h == 0) return c <= 0 ? RC_QR_ALL : RC_QR_NONE;
    real root = R_ABS(c) >= R_ABS(2 * h) * (real)RC_T_FAR ? ((c > 0) == (h > 0) ? -(real)RC_T_FAR : (real)RC_T_FAR)
                                                          : -c / (2 * h);
    if (h > 0) *t_hi = root;
    else *t_lo = root;
    return RC_QR_BETWEEN;
  }
  real disc = REF(quadric_discriminant)(q, f, v, &k);
  if (disc < 0) return a > 0 ? RC_QR_NONE : RC_QR_ALL;
  real sq = R_SQRT(disc);
  real qq = (h >= 0) ? -(h + sq) : -(h - sq);
  real r0 = 0, r1 = 0;
  if (qq != 0) {
    r0 = (R_ABS(qq) >= R_ABS(a) * far) ? ((qq > 0) == (a > 0) ? far : -far) : qq / a;
    r1 = (R_ABS(c) >= R_ABS(qq) * far) ? ((c > 0) == (qq > 0) ? far : -far) : c / qq;
  }
  *t_lo = rmin(r0, r1);
  *t_hi = rmax(r0, r1);
  return a > 0 ? RC_QR_BETWEEN : RC_QR_OUTSIDE;
}

void REF(box_slab)(real lo, real hi, real o, real d, uint32_t k, real *t_in, real *t_out, uint32_t *axis_in,
                   uint32_t *axis_out) {
  if (d == 0) {
    if (o < lo || o > hi) *t_in = (real)RC_T_FAR;
    return;
  }
  real ta = (lo - o) / d;
  real tb = (hi - o) / d;
  if (rmin(ta, tb) > *t_in) {
    *t_in = rmin(ta, tb);
    *axis_in = k;
  }
  if (rmax(ta, tb) < *t_out) {
    *t_out = rmax(ta, tb);
    *axis_out = k;
  }
}

void REF(box_span)(rvec3 lo, rvec3 hi, rvec3 o, rvec3 d, real *t_in, real *t_out, uint32_t *axis_in,
                   uint32_t *axis_out) {
  *t_in = -(real)RC_T_FAR;
  *t_out = (real)RC_T_FAR;
  *axis_in = 1;
  *axis_out = 1;
  REF(box_slab)(lo.x, hi.x, o.x, d.x, 1, t_in, t_out, axis_in, axis_out);
  REF(box_slab)(lo.y, hi.y, o.y, d.y, 2, t_in, t_out, axis_in, axis_out);
  REF(box_slab)(lo.z, hi.z, o.z, d.z, 3, t_in, t_out, axis_in, axis_out);
}

ref_solid_line REF(solid_line_of)(const packed_quadric *q, rvec3 o, rvec3 d) {
  const real far = (real)RC_T_FAR;
  ref_solid_line l;
  l.pieces = 0;
  l.lo0 = 0;
  l.hi0 = 0;
  l.t_hi = 0;
  rvec3 f = REF(quadric_local)(q, RV(sub)(o, v3(q->center)));
  rvec3 v = REF(quadric_local)(q, d);
  REF(box_span)(v3(q->lo), v3(q->hi), f, v, &l.b_in, &l.b_out, &l.a_in, &l.a_out);
  if (l.b_in > l.b_out) return l;
  real t_lo;
  uint32_t kind = REF(quadric_roots)(q, f, v, &t_lo, &l.t_hi);
  if (kind == RC_QR_NONE) return l;
  l.lo0 = (kind == RC_QR_BETWEEN) ? t_lo : -far;
  l.hi0 = (kind == RC_QR_OUTSIDE) ? t_lo : ((kind == RC_QR_BETWEEN) ? l.t_hi : far);
  l.pieces = (kind == RC_QR_OUTSIDE) ? 2 : 1;
  return l;
}

void REF(solid_piece)(const ref_solid_line *l, uint32_t k, real *s, real *e, bool *box_starts, bool *box_ends) {
  const real far = (real)RC_T_FAR;
  real lo = (k == 0) ? l->lo0 : l->t_hi;
  real hi = (k == 0) ? l->hi0 : far;
  *box_starts = l->b_in >= lo;
  *box_ends = l->b_out <= hi;
  *s = *box_starts ? l->b_in : lo;
  *e = *box_ends ? l->b_out : hi;
}

uint32_t REF(solid_intervals)(uint32_t leaf, const packed_quadric *q, rvec3 o, rvec3 d, bool flip, uint32_t base) {
  ref_solid_line l = REF(solid_line_of)(q, o, d);
  uint32_t n = 0;
  for (uint32_t k = 0; k < l.pieces; k++) {
    real s, e;
    bool box_starts, box_ends;
    REF(solid_piece)(&l, k, &s, &e, &box_starts, &box_ends);
    if (s > e) continue;
    csg_t[base + n] = s;
    csg_code_of[base + n] = REF(csg_code)(leaf, box_starts ? l.a_in : 0, false, flip);
    csg_t[base + n + 1] = e;
    csg_code_of[base + n + 1] = REF(csg_code)(leaf, box_ends ? l.a_out : 0, true, flip);
    n += 2;
  }
  return n;
}

bool REF(line_meets_box)(rvec3 lo, rvec3 hi, rvec3 o, rvec3 d) {
  real t_in, t_out;
  uint32_t a_in, a_out;
  REF(box_span)(lo, hi, o, d, &t_in, &t_out, &a_in, &a_out);
  if (t_in >= (real)RC_T_FAR) return false;
  return t_in <= t_out + 2 * REF(gamma_bound)(3) * (R_ABS(t_in) + R_ABS(t_out));
}

void REF(blame_mesh)(const ref_scene *sc, uint32_t csg) {
  const packed_frame *f = sc->frame;
  ref_crossing_blame = 1 + f->sphere_count + f->triangle_count + f->quadric_count + csg;
}

void REF(sort_in_crossing)(uint32_t base, uint32_t n, real t, uint32_t tri, bool bounded, real e) {
  uint32_t i = n;
  for (; i > 0 && csg_t[base + i - 1] > t; i--) {
    csg_t[base + i] = csg_t[base + i - 1];
    csg_code_of[base + i] = csg_code_of[base + i - 1];
    if (bounded) csg_e[base + i] = csg_e[base + i - 1];
  }
  csg_t[base + i] = t;
  csg_code_of[base + i] = tri;
  if (bounded) csg_e[base + i] = e;
}

uint32_t REF(mesh_code)(uint32_t tri, uint32_t i, bool flip) {
  return REF(csg_code)(tri, 0, (i & 1u) != 0, flip) | RC_CSG_CODE_MESH;
}

uint32_t REF(mesh_intervals)(const ref_scene *sc, uint32_t csg, const packed_quadric *q, rvec3 o, rvec3 d, bool flip,
                             uint32_t base) {
  ref_shear sh = REF(ray_shear_for)(d);
  uint32_t n = 0;
  uint32_t node = q->mesh_root;
  while (node < q->mesh_end) {
    const packed_bvh_node *b = &sc->bvh_nodes[node];
    if (!REF(line_meets_box)(v3(b->lo), v3(b->hi), o, d)) {
      node = b->skip;
      continue;
    }
    if (b->leaf == 0) {
      node++;
      continue;
    }
    uint32_t first = b->leaf >> RC_BVH_LEAF_SHIFT;
    uint32_t count = b->leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u);
    for (uint32_t k = first; k < first + count; k++) {
      uint32_t tri = sc->bvh_prims[k];
      real t = REF(triangle_crossing)(o, &sh, sc->triangles[tri]);
      if (t >= (real)RC_T_FAR) continue;
      if (n == q->mesh_crossings) {
        REF(blame_mesh)(sc, csg);
        return 0;
      }
      REF(sort_in_crossing)(base, n, t, tri, false, 0);
      n++;
    }
    node = b->skip;
  }
  if (n & 1u) {
    REF(blame_mesh)(sc, csg);
    return 0;
  }
  for (uint32_t i = 0; i < n; i++) csg_code_of[base + i] = REF(mesh_code)(csg_code_of[base + i], i, flip);
  return n;
}

real REF(intersect_quadric_surface)(const packed_quadric *q, rvec3 o, rvec3 d, real t_max) {
  const real far = (real)RC_T_FAR;
  rvec3 f = REF(quadric_local)(q, RV(sub)(o, v3(q->center)));
  rvec3 v = REF(quadric_local)(q, d);
  real t_lo, t_hi;
  uint32_t kind = REF(quadric_roots)(q, f, v, &t_lo, &t_hi);
  if (kind == RC_QR_NONE || kind == RC_QR_ALL) return far;
  real b_in, b_out;
  uint32_t a_in, a_out;
  REF(box_span)(v3(q->lo), v3(q->hi), f, v, &b_in, &b_out, &a_in, &a_out);
  bool lo_ok = t_lo > 0 && t_lo <= t_max && R_ABS(t_lo) < far && t_lo >= b_in && t_lo <= b_out;
  bool hi_ok = t_hi > 0 && t_hi <= t_max && R_ABS(t_hi) < far && t_hi >= b_in && t_hi <= b_out;
  return lo_ok ? t_lo : (hi_ok ? t_hi : far);
}

real REF(first_interval_end)(uint32_t base, uint32_t n, real t_max, uint32_t *code) {
  *code = 0;
  for (uint32_t i = 0; i < n; i++) {
    real t = csg_t[base + i];
    if (t > 0 && t <= t_max && t < (real)RC_T_FAR) {
      *code = csg_code_of[base + i];
      return t;
    }
  }
  return (real)RC_T_FAR;
}

real REF(solid_first_end)(uint32_t leaf, const packed_quadric *q, rvec3 o, rvec3 d, real t_max, uint32_t *code) {
  const real far = (real)RC_T_FAR;
  *code = 0;
  ref_solid_line l = REF(solid_line_of)(q, o, d);
  for (uint32_t k = 0; k < l.pieces; k++) {
    real s, e;
    bool box_starts, box_ends;
    REF(solid_piece)(&l, k, &s, &e, &box_starts, &box_ends);
    if (s > e) continue;
    if (s > 0 && s <= t_max && s < far) {
      *code = REF(csg_code)(leaf, box_starts ? l.a_in : 0, false, false);
      return s;
    }
    if (e > 0 && e <= t_max && e < far) {
      *code = REF(csg_code)(leaf, box_ends ? l.a_out : 0, true, false);
      return e;
    }
  }
  return far;
}

real REF(intersect_plane)(const packed_quadric *q, rvec3 o, rvec3 d, real t_max) {
  const real far = (real)RC_T_FAR;
  real fz = RV(dot)(v3(q->axis_z), RV(sub)(o, v3(q->center)));
  real vz = RV(dot)(v3(q->axis_z), d);
  bool facing = ((q->flags & RC_QUADRIC_ONE_SIDED) == 0) || vz < 0;
  if (vz == 0 || !facing || R_ABS(fz) >= R_ABS(vz) * far) return far;
  real t = -fz / vz;
  return t > 0 && t <= t_max ? t : far;
}

real REF(intersect_quadric)(const ref_scene *sc, uint32_t index, rvec3 o, rvec3 d, real t_max, uint32_t *code) {
  *code = 0;
  const packed_quadric *q = &sc->quadrics[index];
  if (q->flags & RC_QUADRIC_UNBOUNDED) {
    *code = REF(csg_code)(index, 0, false, false);
    return REF(intersect_plane)(q, o, d, t_max);
  }
  if ((q->flags & RC_QUADRIC_SOLID) == 0) {
    *code = REF(csg_code)(index, 0, false, false);
    return REF(intersect_quadric_surface)(q, o, d, t_max);
  }
  return REF(solid_first_end)(index, q, o, d, t_max, code);
}

bool REF(csg_inside)(uint32_t op, bool in_a, bool in_b) {
  return op == RC_CSG_UNION ? (in_a || in_b) : (op == RC_CSG_INTERSECTION ? (in_a && in_b) : (in_a && !in_b));
}

uint32_t REF(combine_intervals)(uint32_t op, uint32_t a, uint32_t na, uint32_t b, uint32_t nb) {
  uint32_t out_base = RC_CSG_STACK * RC_CSG_SLOT;
  uint32_t i = 0, j = 0, n = 0;
  bool in_a = false, in_b = false, in_r = false;
  while (i < na || j < nb) {
    bool take_a = j >= nb || (i < na && csg_t[a + i] <= csg_t[b + j]);
    real t;
    uint32_t code;
    if (take_a) {
      t = csg_t[a + i];
      code = csg_code_of[a + i];
      in_a = !in_a;
      i++;
    } else {
      t = csg_t[b + j];
      code = csg_code_of[b + j] ^ (op == RC_CSG_DIFFERENCE ? 1u : 0u);
      in_b = !in_b;
      j++;
    }
    bool in_now = REF(csg_inside)(op, in_a, in_b);
    if (in_now == in_r) continue;
    in_r = in_now;
    if (n > 0 && csg_t[out_base + n - 1] == t) {
      n--;
      continue;
    }
    csg_t[out_base + n] = t;
    csg_code_of[out_base + n] = code;
    n++;
  }
  return n;
}

real REF(intersect_csg)(const ref_scene *sc, uint32_t index, rvec3 o, rvec3 d, real t_max, uint32_t *code) {
  *code = 0;
  const packed_csg *c = &sc->csg[index];
  uint32_t count[RC_CSG_STACK];
  uint32_t sp = 0;
  for (uint32_t k = 0; k < c->count; k++) {
    uint32_t ins = sc->csg_program[c->first + k];
    uint32_t op = ins >> RC_CSG_OP_SHIFT;
    uint32_t operand = ins & RC_CSG_OPERAND_MASK;
    if (op == RC_CSG_LEAF) {
      const packed_quadric *q = &sc->quadrics[operand];
      if (q->flags & RC_QUADRIC_MESH) {
        count[sp] = REF(mesh_intervals)(sc, index, q, o, d, false, sp * RC_CSG_SLOT);
        if (ref_crossing_blame != 0) return (real)RC_T_FAR;
      } else {
        count[sp] = REF(solid_intervals)(operand, q, o, d, false, sp * RC_CSG_SLOT);
      }
      sp++;
      continue;
    }
    uint32_t a = (sp - 2) * RC_CSG_SLOT;
    uint32_t n = REF(combine_intervals)(op, a, count[sp - 2], (sp - 1) * RC_CSG_SLOT, count[sp - 1]);
    for (uint32_t i = 0; i < n; i++) {
      csg_t[a + i] = csg_t[RC_CSG_STACK * RC_CSG_SLOT + i];
      csg_code_of[a + i] = csg_code_of[RC_CSG_STACK * RC_CSG_SLOT + i];
    }
    count[sp - 2] = n;
    sp--;
  }
  return REF(first_interval_end)(0, count[0], t_max, code);
}

rvec3 REF(quadric_normal)(const packed_quadric *q, uint32_t code, rvec3 p, rvec3 d) {
  uint32_t face = (code >> 2u) & 3u;
  rvec3 g;
  if (face == 0) {
    g = RV(add)(REF(quadric_apply)(q, REF(quadric_local)(q, RV(sub)(p, v3(q->center)))), v3(q->linear));
  } else {
    int k = (int)face - 1;
    real s = (((code & 2u) != 0) == (rv_get(REF(quadric_local)(q, d), k) > 0)) ? 1 : -1;
    g = RV(make)(k == 0 ? s : 0, k == 1 ? s : 0, k == 2 ? s : 0);
  }
  rvec3 n = RV(add)(RV(add)(RV(scale)(v3(q->axis_x), g.x), RV(scale)(v3(q->axis_y), g.y)), RV(scale)(v3(q->axis_z), g.z));
  return (code & 1u) ? RV(neg)(n) : n;
}

rvec3 REF(mesh_normal)(packed_triangle tri, uint32_t code, rvec3 d) {
  rvec3 g = RV(cross)(RV(sub)(v3(tri.v1), v3(tri.v0)), RV(sub)(v3(tri.v2), v3(tri.v0)));
  bool leaving = (code & 2u) != 0;
  if ((RV(dot)(g, d) > 0) != leaving) g = RV(neg)(g);
  return (code & 1u) ? RV(neg)(g) : g;
}
