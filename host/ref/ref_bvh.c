/* ref_bvh.c: mirrors shaders/rc_bvh.glsl: the same stackless traversal and box test. */
#include "ref/ref_shader.h"
#include "ref/ref_real.h"

#include <math.h>
#include <string.h>



rvec3 REF(safe_inverse)(rvec3 d) {
  const real tiny = (real)1e-30;
  return RV(div)(RV(make)(1, 1, 1), RV(make)(d.x >= 0 ? rmax(d.x, tiny) : rmin(d.x, -tiny),
                                             d.y >= 0 ? rmax(d.y, tiny) : rmin(d.y, -tiny),
                                             d.z >= 0 ? rmax(d.z, tiny) : rmin(d.z, -tiny)));
}

real REF(intersect_box)(rvec3 lo, rvec3 hi, rvec3 o, rvec3 inv_d, real t_max) {
  rvec3 t0 = RV(mul)(RV(sub)(lo, o), inv_d);
  rvec3 t1 = RV(mul)(RV(sub)(hi, o), inv_d);
  real t_enter = rmax(rmax(rmin(t0.x, t1.x), rmin(t0.y, t1.y)), rmax(rmin(t0.z, t1.z), 0));
  real t_exit = rmin(rmin(rmax(t0.x, t1.x), rmax(t0.y, t1.y)), rmax(t0.z, t1.z)) * (real)RC_BOX_FAR_SCALE;
  return (t_enter <= t_exit && t_enter <= t_max * (real)RC_BOX_NEAR_SCALE) ? t_enter : (real)RC_T_FAR;
}

uint32_t REF(loose_kinds)(const ref_scene *sc) { return sc->frame->loose_kinds; }

uint32_t REF(tree_kinds)(const ref_scene *sc) { return ~REF(loose_kinds)(sc); }

bool REF(test_leaf)(const ref_scene *sc, uint32_t first, uint32_t count, rvec3 o, rvec3 d, const ref_shear *sh, bool any,
                    real t_max, ref_hit *h) {
  for (uint32_t k = first; k < first + count; k++) {
    uint32_t object = sc->bvh_prims[k];
    real side;
    rvec3 bary;
    uint32_t part;
    real t = REF(test_object)(sc, REF(tree_kinds)(sc), object, o, d, sh, any, any ? t_max : h->t, &side, &bary, &part);
    if (sc->frame->certify && any && t < (real)RC_T_FAR && !REF(cert_blocker_ends)()) continue;
    if (any && t < (real)RC_T_FAR) return true;
    REF(consider_hit)(sc, object, t, side, bary, part, h);
  }
  return false;
}

bool REF(traverse_bvh)(const ref_scene *sc, rvec3 o, rvec3 d, bool any, real t_max, uint32_t first, uint32_t end,
                       ref_hit *h) {
  ref_shear sh = REF(ray_shear_for)(d);
  rvec3 inv_d = REF(safe_inverse)(d);
  uint32_t node = first;
  while (node < end) {
    const packed_bvh_node *n = NULL;
    uint32_t leaf = 0;
    /* The shader's walk makes the same decisions with selects and one exit (rc_bvh.glsl,
     * for SIMD lanes); on a scalar CPU the branches ran 4 % faster on the 100k mesh. */
    while (node < end) {
      n = &sc->bvh_nodes[node];
      ref_work++;
      real limit = any ? t_max : h->t;
      if (sc->frame->certify) limit = any ? REF(cert_limit)(sc, t_max, ref_cert_t_max_err) : REF(cert_limit)(sc, h->t, h->err);
      if (REF(intersect_box)(rvec3_from(n->lo), rvec3_from(n->hi), o, inv_d, limit) >= (real)RC_T_FAR) {
        node = n->skip;
      } else if (n->leaf == 0) {
        node++;
      } else {
        leaf = n->leaf;
        break;
      }
    }
    if (leaf == 0) break;
    uint32_t count = leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u);
    if (REF(test_leaf)(sc, leaf >> RC_BVH_LEAF_SHIFT, count, o, d, &sh, any, t_max, h)) return true;
    node = n->skip;
  }
  return h->kind != RC_HIT_NONE;
}

bool REF(test_planes)(const ref_scene *sc, rvec3 o, rvec3 d, bool any, real t_max, ref_hit *h) {
  const packed_frame *f = sc->frame;
  if (f->plane_count == 0) return false;
  uint32_t first = f->quadric_count - f->plane_count, first_quadric_object = f->sphere_count + f->triangle_count;
  for (uint32_t k = first; k < f->quadric_count; k++) {
    const packed_quadric *q = &sc->quadrics[k];
    if (f->certify) REF(cert_plane_object)(sc, first_quadric_object + k, q, o, d, any ? t_max : h->t);
    real t = REF(intersect_plane)(q, o, d, any ? t_max : h->t);
    if (f->certify && any && t < (real)RC_T_FAR && !REF(cert_blocker_ends)()) continue;
    if (any && t < (real)RC_T_FAR) return true;
    REF(consider_hit)(sc, first_quadric_object + k, t, 0, RV(make)(0, 0, 0), REF(csg_code)(k, 0, false, false), h);
  }
  return false;
}

bool REF(loose_hit)(const ref_scene *sc, uint32_t object, real t, real side, rvec3 bary, uint32_t part, bool any,
                    ref_hit *h) {
  if (sc->frame->certify && any && t < (real)RC_T_FAR && !REF(cert_blocker_ends)()) return false;
  if (any && t < (real)RC_T_FAR) return true;
  REF(consider_hit)(sc, object, t, side, bary, part, h);
  return false;
}

/* The first quadric's object number: spheres come first, then triangles, quadrics (the
 * planes last), composites (rc_intersect.glsl, object_kind). */
static uint32_t first_quadric(const ref_scene *sc) { return sc->frame->sphere_count + sc->frame->triangle_count; }

bool REF(test_loose_quadrics)(const ref_scene *sc, rvec3 o, rvec3 d, bool any, real t_max, ref_hit *h) {
  for (uint32_t object = first_quadric(sc); object < first_quadric(sc) + sc->frame->quadric_count - sc->frame->plane_count;
       object++) {
    if (sc->frame->certify) REF(cert_object)(sc, RC_KIND_QUADRICS, object, o, d, any, any ? t_max : h->t);
    rvec3 bary;
    uint32_t part;
    real t = REF(intersect_quadric_object)(sc, object - first_quadric(sc), o, d, any ? t_max : h->t, &bary, &part);
    if (REF(loose_hit)(sc, object, t, 0, bary, part, any, h)) return true;
  }
  return false;
}

/* The loose objects before the tree, as the shader tests them. */
bool REF(test_loose)(const ref_scene *sc, rvec3 o, rvec3 d, bool any, real t_max, ref_hit *h) {
  if ((REF(loose_kinds)(sc) & RC_KIND_QUADRICS) == 0) return false;
  return REF(test_loose_quadrics)(sc, o, d, any, t_max, h);
}

/* The node range [first, end) of a primary ray through pixel (x, y) (rc_bvh.glsl). */
void REF(eye_nodes)(const ref_scene *sc, uint32_t x, uint32_t y, uint32_t *first, uint32_t *end) {
  *first = 0, *end = sc->frame->bvh_node_count;
  if (sc->frame->light_buffers == 0) return;
  const uint32_t *entry = &sc->bvh_prims[sc->frame->light_buffers + 2 * sc->frame->light_count];
  if (entry[0] == 0) return;
  uint32_t shift = entry[1] & ((1u << RC_EYE_BUFFER_COLUMNS_SHIFT) - 1), columns = entry[1] >> RC_EYE_BUFFER_COLUMNS_SHIFT;
  const uint32_t *cell = &sc->bvh_prims[entry[0] + 2 * ((y >> shift) * columns + (x >> shift))];
  *first = cell[0], *end = cell[1];
}

bool REF(closest_hit)(const ref_scene *sc, rvec3 o, rvec3 d, uint32_t first, uint32_t end, ref_hit *h) {
  *h = REF(no_hit)();
  if (sc->frame->certify) {
    ref_cert_any = false;
    ref_cert_beyond = (real)RC_T_FAR;
  }
  if (sc->use_bvh) {
    REF(test_loose)(sc, o, d, false, (real)RC_T_FAR, h);
    REF(traverse_bvh)(sc, o, d, false, (real)RC_T_FAR, first, end, h);
    REF(test_planes)(sc, o, d, false, (real)RC_T_FAR, h);
  } else {
    REF(closest_hit_linear)(sc, o, d, h);
  }
  if (sc->frame->certify) REF(cert_closest)(sc, h);
  return h->kind != RC_HIT_NONE;
}

/* The node range [first, end) of a shadow ray towards light `light` (rc_bvh.glsl says how
 * the cell is found; the same f32 arithmetic here). */
void REF(shadow_nodes)(const ref_scene *sc, uint32_t light, rvec3 d, real t_max, uint32_t *first, uint32_t *end) {
  *first = 0, *end = sc->frame->bvh_node_count;
  if (sc->frame->light_buffers == 0) return;
  const uint32_t *entry = &sc->bvh_prims[sc->frame->light_buffers + 2 * light];
  float reach;
  memcpy(&reach, &entry[1], sizeof reach);
  if (entry[0] == 0 || !(t_max <= (real)reach)) return;
  vec3 v = {(float)d.x, (float)d.y, (float)d.z};
  vec3 a = {fabsf(v.x), fabsf(v.y), fabsf(v.z)};
  uint32_t axis = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
  float major = axis == 0 ? a.x : (axis == 1 ? a.y : a.z);
  if (!(major > 0)) return;
  float sign_of = axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
  uint32_t face = 2 * axis + (sign_of < 0 ? 1 : 0);
  float s = (axis == 0 ? v.y : v.x) / major;
  float t = (axis == 2 ? v.y : v.z) / major;
  if (!(fabsf(s) <= 1.5f && fabsf(t) <= 1.5f)) return; /* NaN */
  float res = (float)RC_LIGHT_BUFFER_RES;
  uint32_t i = (uint32_t)fminf(fmaxf(floorf((s + 1) * 0.5f * res), 0), res - 1);
  uint32_t j = (uint32_t)fminf(fmaxf(floorf((t + 1) * 0.5f * res), 0), res - 1);
  const uint32_t *cell = &sc->bvh_prims[entry[0] + 2 * ((face * RC_LIGHT_BUFFER_RES + j) * RC_LIGHT_BUFFER_RES + i)];
  *first = cell[0], *end = cell[1];
}

bool REF(occluded)(const ref_scene *sc, rvec3 o, rvec3 d, real t_max, uint32_t light) {
  bool ok = ref_cert_ok;
  if (sc->frame->certify) {
    ref_cert_any = true;
    ref_cert_blocked_later = false;
    ref_cert_blocker_certain = false;
  }
  bool blocked;
  if (!sc->use_bvh) {
    blocked = REF(occluded_linear)(sc, o, d, t_max);
  } else {
    ref_hit h = REF(no_hit)();
    uint32_t first, end;
    REF(shadow_nodes)(sc, light, d, t_max, &first, &end);
    blocked = REF(test_loose)(sc, o, d, true, t_max, &h) || REF(traverse_bvh)(sc, o, d, true, t_max, first, end, &h) ||
              REF(test_planes)(sc, o, d, true, t_max, &h);
  }
  if (sc->frame->certify) {
    blocked = blocked || ref_cert_blocked_later;
    REF(cert_blocked)(blocked, ok);
  }
  return blocked;
}
