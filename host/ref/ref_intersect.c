/* ref_intersect.c: mirrors shaders/rc_intersect.glsl function by function, same order,
 * same formulas (see the shader for the papers). Built with -ffp-contract=off, so the
 * `precise` of the shader is the default here. */
#include "ref/ref_shader.h"

#include "ref/ref_real.h"

real REF(first_root)(real t_near, real t_exit, real t_max, real *side) {
  *side = 0;
  if (t_near > 0 && t_near <= t_max) {
    *side = -1;
    return t_near;
  }
  if (t_exit > 0 && t_exit <= t_max) {
    *side = 1;
    return t_exit;
  }
  return (real)RC_T_FAR;
}

real REF(intersect_sphere_geometric)(rvec3 o, rvec3 d, packed_sphere s, real t_max, real *side) {
  *side = 0;
  real r = (real)s.radius;
  rvec3 f = RV(sub)(o, rvec3_from(s.center));
  real b = RV(dot)(f, d);
  rvec3 l = RV(sub)(f, RV(scale)(d, b));
  real disc = r * r - RV(dot)(l, l);
  if (disc < 0) return (real)RC_T_FAR;
  real sq = R_SQRT(disc);
  real q = (b >= 0) ? -(b + sq) : -(b - sq);
  if (q == 0) return (real)RC_T_FAR;
  real c = RV(dot)(f, f) - r * r;
  real t0 = c / q;
  return REF(first_root)(rmin(t0, q), rmax(t0, q), t_max, side);
}

real REF(intersect_sphere_algebraic)(rvec3 o, rvec3 d, packed_sphere s, real t_max, real *side) {
  *side = 0;
  real r = (real)s.radius;
  rvec3 f = RV(sub)(o, rvec3_from(s.center));
  real a = RV(dot)(d, d);
  real b = 2 * RV(dot)(f, d);
  real c = RV(dot)(f, f) - r * r;
  real disc = b * b - 4 * a * c;
  if (disc < 0) return (real)RC_T_FAR;
  real sq = R_SQRT(disc);
  return REF(first_root)((-b - sq) / (2 * a), (-b + sq) / (2 * a), t_max, side);
}

real REF(intersect_sphere)(const ref_scene *sc, rvec3 o, rvec3 d, packed_sphere s, real t_max, real *side) {
  if (sc->frame->sphere_formula == RC_SPHERE_ALGEBRAIC) return REF(intersect_sphere_algebraic)(o, d, s, t_max, side);
  return REF(intersect_sphere_geometric)(o, d, s, t_max, side);
}

rvec3 REF(transform_point)(const packed_transform *m, rvec3 p) {
  return RV(make)(RV(dot)(rvec3_from(rcm_xyz(m->row0)), p) + (real)m->row0.w,
                  RV(dot)(rvec3_from(rcm_xyz(m->row1)), p) + (real)m->row1.w,
                  RV(dot)(rvec3_from(rcm_xyz(m->row2)), p) + (real)m->row2.w);
}

rvec3 REF(transform_vector)(const packed_transform *m, rvec3 v) {
  return RV(make)(RV(dot)(rvec3_from(rcm_xyz(m->row0)), v), RV(dot)(rvec3_from(rcm_xyz(m->row1)), v),
                  RV(dot)(rvec3_from(rcm_xyz(m->row2)), v));
}

real REF(intersect_any_sphere)(const ref_scene *sc, rvec3 o, rvec3 d, packed_sphere s, real t_max, real *side) {
  if (s.transform == RC_NO_TRANSFORM) return REF(intersect_sphere)(sc, o, d, s, t_max, side);
  const packed_transform *m = &sc->transforms[s.transform];
  rvec3 d_obj = REF(transform_vector)(m, d);
  real len = RV(length)(d_obj);
  real t = REF(intersect_sphere)(sc, REF(transform_point)(m, o), RV(scale)(d_obj, 1 / len), s, t_max * len, side);
  return (t >= (real)RC_T_FAR) ? t : t / len;
}

uint32_t REF(object_kind)(const ref_scene *sc, uint32_t object, uint32_t *index) {
  const packed_frame *f = sc->frame;
  uint32_t first_quadric = f->sphere_count + f->triangle_count;
  uint32_t first_csg = first_quadric + f->quadric_count;
  *index = (object < f->sphere_count) ? object
           : (object < first_quadric) ? object - f->sphere_count
           : (object < first_csg)     ? object - first_quadric
                                      : object - first_csg;
  return (object < f->sphere_count) ? RC_HIT_SPHERE
         : (object < first_quadric) ? RC_HIT_TRIANGLE
         : (object < first_csg)     ? RC_HIT_QUADRIC
                                    : RC_HIT_CSG;
}

real REF(intersect_quadric_object)(const ref_scene *sc, uint32_t index, rvec3 o, rvec3 d, real t_max, rvec3 *bary,
                                   uint32_t *part) {
  *bary = RV(make)(0, 0, 0);
  *part = 0;
  const packed_quadric *q = &sc->quadrics[index];
  if ((q->flags & RC_QUADRIC_PATCH) != 0) {
    *part = REF(csg_code)(index, 0, false, false);
    return REF(intersect_patch)(sc, index, q, o, d, t_max, bary);
  }
  return REF(intersect_quadric)(sc, index, o, d, t_max, part);
}

real REF(intersect_triangle_object)(const ref_scene *sc, packed_triangle tri, rvec3 o, rvec3 d, const ref_shear *sh,
                                    real t_max, rvec3 *bary) {
  *bary = RV(make)(0, 0, 0);
  if ((tri.flags & RC_TRIANGLE_ONE_SIDED) != 0 && !REF(triangle_faces_ray)(tri, d)) return (real)RC_T_FAR;
  if (sc->frame->triangle_formula == RC_TRIANGLE_MOLLER_TRUMBORE)
    return REF(intersect_triangle_moller_trumbore)(o, d, tri, t_max, bary);
  if (sc->frame->triangle_formula == RC_TRIANGLE_CRAMER) return REF(intersect_triangle_cramer)(o, d, tri, t_max, bary);
  return REF(intersect_triangle)(o, sh, tri, t_max, bary);
}

real REF(intersect_other_object)(const ref_scene *sc, uint32_t kinds, uint32_t kind, uint32_t index, rvec3 o, rvec3 d,
                                 real t_max, rvec3 *bary, uint32_t *part) {
  *bary = RV(make)(0, 0, 0);
  *part = 0;
  if ((kinds & RC_KIND_QUADRICS) != 0 && kind == RC_HIT_QUADRIC)
    return REF(intersect_quadric_object)(sc, index, o, d, t_max, bary, part);
  if ((kinds & RC_KIND_CSG) != 0 && kind == RC_HIT_CSG) return REF(intersect_csg)(sc, index, o, d, t_max, part);
  return (real)RC_T_FAR;
}

real REF(intersect_object)(const ref_scene *sc, uint32_t kinds, uint32_t object, rvec3 o, rvec3 d, const ref_shear *sh,
                           real t_max, real *side, rvec3 *bary, uint32_t *part) {
  ref_work++;
  *side = 0;
  *bary = RV(make)(0, 0, 0);
  *part = 0;
  uint32_t index;
  uint32_t kind = REF(object_kind)(sc, object, &index);
  if ((kinds & RC_KIND_SPHERES) != 0 && kind == RC_HIT_SPHERE)
    return REF(intersect_any_sphere)(sc, o, d, sc->spheres[index], t_max, side);
  if ((kinds & RC_KIND_TRIANGLES) != 0 && kind == RC_HIT_TRIANGLE)
    return REF(intersect_triangle_object)(sc, sc->triangles[index], o, d, sh, t_max, bary);
  return REF(intersect_other_object)(sc, kinds, kind, index, o, d, t_max, bary, part);
}

real REF(cert_limit)(const ref_scene *sc, real t, real e) {
  if (!(t < (real)RC_T_FAR)) return t;
  return t + 2 * REF(cert_factor)(sc) * (e + ref_cert_eo + t * ref_cert_ed);
}

void REF(cert_order)(const ref_scene *sc, real t, uint32_t object, const ref_hit *h) {
  if (t < h->t || (t == h->t && object < h->object)) {
    if (h->kind != RC_HIT_NONE) ref_cert_beyond = rmin(ref_cert_beyond, h->t - REF(cert_factor)(sc) * h->err);
    return;
  }
  ref_cert_beyond = rmin(ref_cert_beyond, t - REF(cert_factor)(sc) * ref_cert_t_err);
}

void REF(consider_hit)(const ref_scene *sc, uint32_t object, real t, real side, rvec3 bary, uint32_t part, ref_hit *h) {
  if (t >= (real)RC_T_FAR) return;
  if (sc->frame->certify) REF(cert_order)(sc, t, object, h);
  if (t < h->t || (t == h->t && object < h->object)) {
    h->t = t;
    h->object = object;
    h->kind = REF(object_kind)(sc, object, &h->index);
    h->side = side;
    h->bary = bary;
    h->part = part;
    if (sc->frame->certify) {
      h->err = ref_cert_t_err;
      h->bary_err = ref_cert_bary_err;
      h->off_err = ref_cert_off_err;
    }
  }
}

ref_hit REF(no_hit)(void) {
  ref_hit h;
  h.t = (real)RC_T_FAR;
  h.kind = RC_HIT_NONE;
  h.index = 0u;
  h.object = 0xffffffffu;
  h.bary = RV(make)(0, 0, 0);
  h.side = 0;
  h.part = 0u;
  h.err = 0;
  h.bary_err = 0;
  h.off_err = 0;
  return h;
}

uint32_t REF(surface_object)(const ref_scene *sc, uint32_t object) {
  uint32_t index;
  if (REF(object_kind)(sc, object, &index) == RC_HIT_QUADRIC) {
    const packed_quadric *q = &sc->quadrics[index];
    if ((q->flags & RC_QUADRIC_PATCH) != 0) return sc->frame->sphere_count + sc->frame->triangle_count + q->mesh_end;
  }
  return object;
}

void REF(cert_sphere)(const ref_scene *sc, rvec3 o, rvec3 d, packed_sphere s, real t_max) {
  if (sc->frame->sphere_formula != RC_SPHERE_GEOMETRIC) {
    REF(cert_fail)();
    return;
  }
  if (s.transform == RC_NO_TRANSFORM) {
    REF(cert_sphere_roots)(sc, o, d, s, t_max, 1, 0);
    return;
  }
  const packed_transform *m = &sc->transforms[s.transform];
  rvec3 d_obj = REF(transform_vector)(m, d);
  real len = RV(length)(d_obj);
  real na = REF(cert_norm)(m);
  real eo = ref_cert_eo;
  real ed = ref_cert_ed;
  real err = na * ed + REF(gamma_bound)(4) * na;
  ref_cert_eo = na * eo + REF(gamma_bound)(4) * (na * RV(length)(o) + RV(length)(RV(make)(m->row0.w, m->row1.w, m->row2.w)));
  ref_cert_ed = err / (len - err) + REF(gamma_bound)(4);
  REF(cert_sphere_roots)(sc, REF(transform_point)(m, o), RV(scale)(d_obj, 1 / len), s, t_max, 1 / len,
                         err / (len - err) + REF(gamma_bound)(3));
  ref_cert_eo = eo;
  ref_cert_ed = ed;
}

bool REF(cert_test_begin)(const ref_scene *sc, uint32_t object) {
  bool ok = ref_cert_ok;
  ref_cert_ok = true;
  ref_cert_self = ref_spawned_ray && sc->frame->offset_strategy == RC_OFFSET_ERROR_BOUND &&
                  REF(surface_object)(sc, object) == ref_cert_spawn_object;
  return ok;
}

void REF(cert_test_end)(bool ok) {
  ref_cert_hit_ok = ref_cert_ok;
  ref_cert_ok = ok && ref_cert_ok;
}

void REF(cert_triangle_object)(const ref_scene *sc, packed_triangle tri, rvec3 o, rvec3 d, const ref_shear *sh,
                               real t_max) {
  uint32_t side = RC_SIDE_FRONT;
  if ((tri.flags & RC_TRIANGLE_ONE_SIDED) != 0) side = REF(cert_triangle_side)(sc, tri, d);
  if (side != RC_SIDE_BACK) REF(cert_triangle)(sc, o, sh, tri, t_max, side == RC_SIDE_UNSURE);
}

void REF(cert_other_object_tests)(const ref_scene *sc, uint32_t kinds, uint32_t kind, uint32_t index, rvec3 o, rvec3 d,
                                  bool any, real t_max) {
  if ((kinds & (RC_KIND_QUADRICS | RC_KIND_CSG)) != 0) {
    if ((kinds & RC_KIND_CSG) != 0 && kind == RC_HIT_CSG) {
      REF(cert_csg)(sc, index, o, d, any, t_max);
      return;
    }
    if ((kinds & RC_KIND_QUADRICS) != 0 && kind == RC_HIT_QUADRIC) {
      const packed_quadric *q = &sc->quadrics[index];
      if ((q->flags & RC_QUADRIC_UNBOUNDED) != 0) {
        REF(cert_plane)(sc, q, o, d, t_max);
        return;
      }
      if ((q->flags & (RC_QUADRIC_PATCH | RC_QUADRIC_MESH)) == 0) {
        REF(cert_quadric)(sc, q, o, d, t_max);
        return;
      }
      if ((q->flags & RC_QUADRIC_PATCH) != 0) {
        REF(cert_patch)(sc, q, o, d, t_max);
        return;
      }
    }
    REF(cert_fail)();
  }
}

void REF(cert_object)(const ref_scene *sc, uint32_t kinds, uint32_t object, rvec3 o, rvec3 d, bool any, real t_max) {
  bool ok = REF(cert_test_begin)(sc, object);
  real eo = ref_cert_eo;
  ref_cert_eo += ref_cert_et;
  uint32_t index;
  uint32_t kind = REF(object_kind)(sc, object, &index);
  REF(cert_other_object_tests)(sc, kinds, kind, index, o, d, any, t_max);
  ref_cert_eo = eo;
  REF(cert_test_end)(ok);
}

void REF(cert_plane_object)(const ref_scene *sc, uint32_t object, const packed_quadric *q, rvec3 o, rvec3 d, real t_max) {
  bool ok = REF(cert_test_begin)(sc, object);
  real eo = ref_cert_eo;
  ref_cert_eo += ref_cert_et;
  REF(cert_plane)(sc, q, o, d, t_max);
  ref_cert_eo = eo;
  REF(cert_test_end)(ok);
}

void REF(cert_closest)(const ref_scene *sc, const ref_hit *h) {
  bool certain = (h->kind == RC_HIT_NONE) ? !(ref_cert_beyond < (real)RC_T_FAR)
                                          : ref_cert_beyond > h->t + REF(cert_factor)(sc) * h->err;
  if (!certain) ref_cert_ok = false;
}

/* No loop budget here to stop the search short of (the shader's): the CPU has no dispatch
 * to time out. */
bool REF(cert_blocker_ends)(void) {
  if (ref_cert_hit_ok) {
    ref_cert_blocker_certain = true;
    return true;
  }
  ref_cert_blocked_later = true;
  return false;
}

void REF(cert_blocked)(bool blocked, bool ok) {
  if (blocked && ref_cert_blocker_certain) ref_cert_ok = ok;
}

real REF(test_object)(const ref_scene *sc, uint32_t kinds, uint32_t object, rvec3 o, rvec3 d, const ref_shear *sh, bool any,
                      real t_max, real *side, rvec3 *bary, uint32_t *part) {
  if (sc->frame->certify) {
    ref_work++;
    *side = 0;
    *bary = RV(make)(0, 0, 0);
    *part = 0;
    uint32_t index;
    uint32_t kind = REF(object_kind)(sc, object, &index);
    bool ok = REF(cert_test_begin)(sc, object);
    real eo = ref_cert_eo;
    real t;
    if ((kinds & RC_KIND_SPHERES) != 0 && kind == RC_HIT_SPHERE) {
      packed_sphere s = sc->spheres[index];
      ref_cert_eo += ref_cert_et;
      REF(cert_sphere)(sc, o, d, s, t_max);
      ref_cert_eo = eo;
      t = REF(intersect_any_sphere)(sc, o, d, s, t_max, side);
    } else if ((kinds & RC_KIND_TRIANGLES) != 0 && kind == RC_HIT_TRIANGLE) {
      packed_triangle tri = sc->triangles[index];
      REF(cert_triangle_object)(sc, tri, o, d, sh, t_max);
      t = REF(intersect_triangle_object)(sc, tri, o, d, sh, t_max, bary);
    } else {
      ref_cert_eo += ref_cert_et;
      REF(cert_other_object_tests)(sc, kinds, kind, index, o, d, any, t_max);
      ref_cert_eo = eo;
      t = REF(intersect_other_object)(sc, kinds, kind, index, o, d, t_max, bary, part);
    }
    REF(cert_test_end)(ok);
    return t;
  }
  return REF(intersect_object)(sc, kinds, object, o, d, sh, t_max, side, bary, part);
}

void REF(closest_hit_linear)(const ref_scene *sc, rvec3 o, rvec3 d, ref_hit *h) {
  ref_shear sh = REF(ray_shear_for)(d);
  for (uint32_t i = 0; i < sc->frame->object_count; i++) {
    real side;
    rvec3 bary;
    uint32_t part;
    real t = REF(test_object)(sc, RC_KIND_ALL, i, o, d, &sh, false, h->t, &side, &bary, &part);
    REF(consider_hit)(sc, i, t, side, bary, part, h);
  }
}

bool REF(occluded_linear)(const ref_scene *sc, rvec3 o, rvec3 d, real t_max) {
  ref_shear sh = REF(ray_shear_for)(d);
  for (uint32_t i = 0; i < sc->frame->object_count; i++) {
    real side;
    rvec3 bary;
    uint32_t part;
    bool blocks = REF(test_object)(sc, RC_KIND_ALL, i, o, d, &sh, true, t_max, &side, &bary, &part) < (real)RC_T_FAR;
    if (sc->frame->certify && blocks && !REF(cert_blocker_ends)()) continue;
    if (blocks) return true;
  }
  return false;
}
