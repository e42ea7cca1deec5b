/* ref_shade.c: mirrors shaders/rc_shade.glsl function by function. */
#include <stdint.h>
#include <string.h>

#include "ref/ref_real.h"
#include "ref/ref_shader.h"

rvec3 REF(sphere_uv_rate)(rvec3 n, real r) {
  real rho = rmax(R_SQRT(n.x * n.x + n.z * n.z), RL(0.0009765625));
  return RV(make)(RL(0.15915494309189535) / (r * rho), RL(0.3183098861837907) / r, 0);
}

rvec3 REF(plane_uv)(const packed_quadric *q, rvec3 p) {
  rvec3 f = REF(quadric_local)(q, RV(sub)(p, rvec3_from(q->center)));
  real u = f.x * (real)q->lo.z + (real)q->lo.x;
  real v = f.y * (real)q->lo.z + (real)q->lo.y;
  return RV(make)(u, v, 0);
}

uint32_t REF(quadric_uv)(const packed_quadric *q, uint32_t code, rvec3 p, rvec3 *uv_at, rvec3 *uv_rate) {
  *uv_at = RV(make)(0, 0, 0);
  *uv_rate = RV(make)(0, 0, 0);
  uint32_t kind = (q->flags >> RC_QUADRIC_UV_SHIFT) & 3u;
  if (kind == RC_QUADRIC_UV_NONE) return RC_UV_NONE;
  rvec3 f = REF(quadric_local)(q, RV(sub)(p, rvec3_from(q->center)));
  rvec3 s = RV(div)(RV(sub)(f, rvec3_from(q->lo)), RV(sub)(rvec3_from(q->hi), rvec3_from(q->lo)));
  rvec3 axes = RV(make)(RV(length)(rvec3_from(q->axis_x)), RV(length)(rvec3_from(q->axis_y)), RV(length)(rvec3_from(q->axis_z)));
  rvec3 rate = RV(div)(axes, RV(sub)(rvec3_from(q->hi), rvec3_from(q->lo)));
  uint32_t face = (code >> 2u) & 3u;
  if (face != 0) {
    *uv_at = (face == 1u) ? RV(make)(s.y, s.z, 0) : ((face == 2u) ? RV(make)(s.z, s.x, 0) : RV(make)(s.x, s.y, 0));
    *uv_rate = (face == 1u) ? RV(make)(rate.y, rate.z, 0) : ((face == 2u) ? RV(make)(rate.z, rate.x, 0) : RV(make)(rate.x, rate.y, 0));
    return RC_UV_GIVEN;
  }
  if (kind == RC_QUADRIC_UV_ELLIPSOID) {
    rvec3 D = rvec3_from(q->diag);
    rvec3 inv_radii = RV(make)(R_SQRT(D.x), R_SQRT(D.y), R_SQRT(D.z));
    rvec3 k = RV(mul)(inv_radii, axes);
    *uv_at = RV(normalize)(RV(mul)(f, inv_radii));
    *uv_rate = REF(sphere_uv_rate)(*uv_at, 1 / rmax(rmax(k.x, k.y), k.z));
    return RC_UV_SPHERE;
  }
  if (kind == RC_QUADRIC_UV_AXIAL) {
    *uv_at = RV(make)(f.x, -f.y, s.z);
    real rho = rmax(R_SQRT(f.x * f.x + f.y * f.y), RL(1e-30));
    *uv_rate = RV(make)(RL(0.15915494309189535) * axes.x / rho, rate.z, 0);
    return RC_UV_AXIAL;
  }
  return RC_UV_NONE;
}

rvec3 REF(quadric_refine)(const packed_quadric *q, rvec3 p, rvec3 *p_error) {
  rvec3 L = rvec3_from(q->linear);
  rvec3 pc = RV(sub)(p, rvec3_from(q->center));
  rvec3 f = REF(quadric_local)(q, pc);
  rvec3 mf = REF(quadric_apply)(q, f);
  rvec3 g = RV(add)(mf, L);
  real value = RV(dot)(f, mf) + 2 * RV(dot)(L, f) + (real)q->constant;
  rvec3 gw = RV(add)(RV(add)(RV(scale)(rvec3_from(q->axis_x), g.x), RV(scale)(rvec3_from(q->axis_y), g.y)),
                     RV(scale)(rvec3_from(q->axis_z), g.z));
  real gg = RV(dot)(gw, gw);
  if (gg == 0) return p;
  rvec3 dp = RV(scale)(gw, value / (2 * gg));
  rvec3 pr = RV(sub)(p, dp);
  real value_error = REF(gamma_bound)(16) * (RV(dot)(RV(abs)(f), RV(abs)(mf)) + 2 * RV(dot)(RV(abs)(L), RV(abs)(f)) +
                                             R_ABS((real)q->constant));
  real dist = value_error / (2 * R_SQRT(gg));
  *p_error = RV(add)(RV(scale)(RV(add)(RV(abs)(pr), RV(abs)(pc)), REF(gamma_bound)(8)), RV(make)(dist, dist, dist));
  return pr;
}

/* The shader's load_vertex_uvs (rc_scene_access.glsl): 2 texels of the texel array. */
static packed_vertex_uvs load_vertex_uvs(const ref_scene *sc, uint32_t first) {
  packed_vertex_uvs t;
  memcpy(&t, sc->texels[first], sizeof t);
  return t;
}

rvec3 REF(triangle_uv)(packed_vertex_uvs t, rvec3 b) {
  real u = b.x * (real)t.u0 + b.y * (real)t.u1 + b.z * (real)t.u2;
  real v = b.x * (real)t.v0 + b.y * (real)t.v1 + b.z * (real)t.v2;
  return RV(make)(u, v, 0);
}

rvec3 REF(triangle_uv_rate)(packed_vertex_uvs t, packed_triangle tri) {
  real uv_area = R_ABS(((real)t.u1 - (real)t.u0) * ((real)t.v2 - (real)t.v0) - ((real)t.u2 - (real)t.u0) * ((real)t.v1 - (real)t.v0));
  real area = RV(length)(RV(cross)(RV(sub)(rvec3_from(tri.v1), rvec3_from(tri.v0)), RV(sub)(rvec3_from(tri.v2), rvec3_from(tri.v0))));
  real rate = (area > 0) ? R_SQRT(uv_area / area) : 0;
  return RV(make)(rate, rate, 0);
}

ref_surface REF(surface_at)(const ref_scene *sc, rvec3 o, rvec3 d, const ref_hit *h) {
  ref_surface sf;
  sf.uv_kind = RC_UV_NONE;
  sf.uv_at = RV(make)(0, 0, 0);
  sf.uv_rate = RV(make)(0, 0, 0);
  sf.footprint = 0;
  sf.curvature = 0;
  rvec3 n;
  if (h->kind == RC_HIT_SPHERE) {
    packed_sphere s = sc->spheres[h->index];
    real r = (real)s.radius;
    rvec3 oo = o, dd = d;
    real t_obj = h->t;
    const packed_transform *m = NULL;
    if (s.transform != RC_NO_TRANSFORM) {
      m = &sc->transforms[s.transform];
      oo = REF(transform_point)(m, o);
      rvec3 d_obj = REF(transform_vector)(m, d);
      t_obj = h->t * RV(length)(d_obj);
      dd = RV(normalize)(d_obj);
    }
    bool algebraic = sc->frame->sphere_formula == RC_SPHERE_ALGEBRAIC;
    if (algebraic) {
      n = RV(normalize)(RV(sub)(RV(add)(oo, RV(scale)(dd, t_obj)), rvec3_from(s.center)));
    } else {
      rvec3 f = RV(sub)(oo, rvec3_from(s.center));
      real b = RV(dot)(f, dd);
      rvec3 l = RV(sub)(f, RV(scale)(dd, b));
      real disc = r * r - RV(dot)(l, l);
      real sq = R_SQRT(disc > 0 ? disc : 0);
      n = RV(normalize)(RV(add)(l, RV(scale)(dd, h->side * sq)));
    }
    sf.uv_kind = RC_UV_SPHERE;
    sf.uv_at = n;
    sf.uv_rate = REF(sphere_uv_rate)(n, r);
    sf.curvature = 1 / r;
    if (!m && !algebraic) {
      rvec3 rn = RV(scale)(n, r);
      sf.p = RV(add)(rvec3_from(s.center), rn);
      sf.p_error = RV(scale)(RV(add)(RV(abs)(rvec3_from(s.center)), RV(abs)(rn)), REF(gamma_bound)(10));
    } else {
      if (m) {
        n = RV(normalize)(RV(add)(RV(add)(RV(scale)(rvec3_from(rcm_xyz(m->row0)), n.x), RV(scale)(rvec3_from(rcm_xyz(m->row1)), n.y)),
                                  RV(scale)(rvec3_from(rcm_xyz(m->row2)), n.z)));
        real stretch = rmax(rmax(RV(length)(rvec3_from(rcm_xyz(m->row0))), RV(length)(rvec3_from(rcm_xyz(m->row1)))),
                            RV(length)(rvec3_from(rcm_xyz(m->row2))));
        sf.uv_rate = RV(scale)(sf.uv_rate, stretch);
        sf.curvature = sf.curvature * stretch;
      }
      rvec3 td = RV(scale)(d, h->t);
      sf.p = RV(add)(o, td);
      sf.p_error = RV(scale)(RV(add)(RV(abs)(o), RV(abs)(td)), REF(gamma_bound)(32));
    }
    sf.material = s.material;
  } else if (h->kind == RC_HIT_QUADRIC || h->kind == RC_HIT_CSG) {
    rvec3 td = RV(scale)(d, h->t);
    sf.p = RV(add)(o, td);
    sf.p_error = RV(scale)(RV(add)(RV(abs)(o), RV(abs)(td)), REF(gamma_bound)(32));
    uint32_t leaf = h->part >> RC_CSG_CODE_LEAF_SHIFT;
    if (h->part & RC_CSG_CODE_MESH) {
      packed_triangle tri = sc->triangles[leaf];
      n = RV(normalize)(REF(mesh_normal)(tri, h->part, d));
      sf.material = tri.material;
    } else {
      const packed_quadric *q = &sc->quadrics[leaf];
      if ((q->flags & RC_QUADRIC_PATCH) != 0) {
        rvec3 g = REF(patch_surface)(sc, q, h->bary, &sf.p, &sf.p_error);
        n = (RV(dot)(g, g) > 0) ? RV(normalize)(g) : RV(neg)(d);
        sf.uv_kind = RC_UV_GIVEN;
        sf.uv_at = h->bary;
        real g_area = RV(length)(g);
        real rate = (g_area > 0) ? 1 / R_SQRT(g_area) : 0;
        sf.uv_rate = RV(make)(rate, rate, 0);
      } else {
        if (((h->part >> 2u) & 3u) == 0) sf.p = REF(quadric_refine)(q, sf.p, &sf.p_error);
        n = RV(normalize)(REF(quadric_normal)(q, h->part, sf.p, d));
        sf.uv_kind = REF(quadric_uv)(q, h->part, sf.p, &sf.uv_at, &sf.uv_rate);
      }
      sf.material = q->material;
      if (q->flags & RC_QUADRIC_UNBOUNDED) {
        sf.uv_kind = RC_UV_GIVEN;
        sf.uv_at = REF(plane_uv)(q, sf.p);
        sf.uv_rate = RV(make)((real)q->lo.z, (real)q->lo.z, 0);
      }
    }
  } else {
    packed_triangle tri = sc->triangles[h->index];
    rvec3 v0 = rvec3_from(tri.v0), v1 = rvec3_from(tri.v1), v2 = rvec3_from(tri.v2);
    rvec3 p0 = RV(scale)(v0, h->bary.x), p1 = RV(scale)(v1, h->bary.y), p2 = RV(scale)(v2, h->bary.z);
    sf.p = RV(add)(RV(add)(p0, p1), p2);
    sf.p_error = RV(scale)(RV(add)(RV(add)(RV(abs)(p0), RV(abs)(p1)), RV(abs)(p2)), REF(gamma_bound)(7));
    n = RV(normalize)(RV(cross)(RV(sub)(v1, v0), RV(sub)(v2, v0)));
    sf.material = tri.material;
    if ((tri.flags >> RC_TRIANGLE_UV_SHIFT) != 0) {
      packed_vertex_uvs uvs = load_vertex_uvs(sc, (tri.flags >> RC_TRIANGLE_UV_SHIFT) - 1u);
      sf.uv_kind = RC_UV_GIVEN;
      sf.uv_at = REF(triangle_uv)(uvs, h->bary);
      sf.uv_rate = REF(triangle_uv_rate)(uvs, tri);
    }
    if (tri.normals != RC_NO_NORMALS) {
      const packed_vertex_normals *vn = &sc->normals[tri.normals];
      rvec3 ng = (RV(dot)(n, d) > 0) ? RV(neg)(n) : n;
      rvec3 ns = RV(normalize)(RV(add)(RV(add)(RV(scale)(rvec3_from(vn->n0), h->bary.x), RV(scale)(rvec3_from(vn->n1), h->bary.y)),
                                       RV(scale)(rvec3_from(vn->n2), h->bary.z)));
      sf.ng = ng;
      sf.n = (RV(dot)(ns, ng) < 0) ? RV(neg)(ns) : ns;
      return sf;
    }
  }
  sf.n = (RV(dot)(n, d) > 0) ? RV(neg)(n) : n;
  sf.ng = sf.n;
  return sf;
}

bool REF(cert_point_on_ray)(const ref_scene *sc, const ref_hit *h, uint32_t transform) {
  if (transform != RC_NO_TRANSFORM) return true;
  if (h->kind == RC_HIT_QUADRIC || h->kind == RC_HIT_CSG) {
    if ((h->part & RC_CSG_CODE_MESH) != 0 || ((h->part >> 2u) & 3u) != 0) return true;
    return (sc->quadrics[h->part >> RC_CSG_CODE_LEAF_SHIFT].flags & RC_QUADRIC_UNBOUNDED) != 0;
  }
  return false;
}

void REF(cert_surface)(const ref_scene *sc, rvec3 d, const ref_hit *h, const ref_surface *sf) {
  if (h->kind == RC_HIT_QUADRIC) {
    const packed_quadric *q = &sc->quadrics[h->part >> RC_CSG_CODE_LEAF_SHIFT];
    if ((q->flags & RC_QUADRIC_PATCH) != 0) {
      REF(cert_patch_surface)(sc, q, d, h->bary, h->bary_err, h->off_err, h->t, sf->ng, sf->p_error);
      return;
    }
  }
  uint32_t transform = (h->kind == RC_HIT_SPHERE) ? sc->spheres[h->index].transform : RC_NO_TRANSFORM;
  bool along_ray = h->kind == RC_HIT_QUADRIC || h->kind == RC_HIT_CSG || transform != RC_NO_TRANSFORM;
  real ep_round = 2 * RV(length)(sf->p_error) + (along_ray ? h->err + REF(cert_factor)(sc) * ref_cert_et : 0);
  real cosine = R_ABS(RV(dot)(sf->ng, d));
  real e_cos = ref_cert_ed + REF(gamma_bound)(12);
  REF(cert_require)(sc, cosine, e_cos);
  real moved = ref_cert_eo + h->t * ref_cert_ed;
  real ep = ep_round + (REF(cert_point_on_ray)(sc, h, transform) ? moved : 2 * moved / rmax(cosine - e_cos, RC_SMALLEST_NORMAL));
  real en = REF(gamma_bound)(12);
  if (h->kind == RC_HIT_SPHERE) {
    real r = (real)sc->spheres[h->index].radius;
    if (transform == RC_NO_TRANSFORM) {
      en += (ep + RV(length)(sf->p_error)) / r;
    } else {
      real dn = 2 * ep / r;
      const packed_transform *m = &sc->transforms[transform];
      real na = REF(cert_norm)(m);
      real det = R_ABS(RV(dot)(rvec3_from(rcm_xyz(m->row0)), RV(cross)(rvec3_from(rcm_xyz(m->row1)), rvec3_from(rcm_xyz(m->row2)))));
      en += (na * na * dn + REF(gamma_bound)(4) * na) * na * na / det + REF(gamma_bound)(4);
    }
  }
  if (h->kind == RC_HIT_TRIANGLE) {
    packed_triangle tri = sc->triangles[h->index];
    if (tri.normals != RC_NO_NORMALS) {
      const packed_vertex_normals *vn = &sc->normals[tri.normals];
      rvec3 ns = RV(add)(RV(add)(RV(scale)(rvec3_from(vn->n0), h->bary.x), RV(scale)(rvec3_from(vn->n1), h->bary.y)),
                         RV(scale)(rvec3_from(vn->n2), h->bary.z));
      real spread = RV(length)(RV(sub)(rvec3_from(vn->n1), rvec3_from(vn->n0))) +
                    RV(length)(RV(sub)(rvec3_from(vn->n2), rvec3_from(vn->n0)));
      real size = RV(length)(rvec3_from(vn->n0)) + RV(length)(rvec3_from(vn->n1)) + RV(length)(rvec3_from(vn->n2));
      en += 2 * (h->bary_err * spread + REF(gamma_bound)(6) * size) / RV(length)(ns);
      REF(cert_require)(sc, RV(dot)(sf->n, sf->ng), en + REF(gamma_bound)(12));
    }
  }
  bool leaf = h->kind == RC_HIT_QUADRIC || (h->kind == RC_HIT_CSG && (h->part & RC_CSG_CODE_MESH) == 0);
  if (leaf && ((h->part >> 2u) & 3u) == 0) {
    const packed_quadric *q = &sc->quadrics[h->part >> RC_CSG_CODE_LEAF_SHIFT];
    if ((q->flags & RC_QUADRIC_UNBOUNDED) == 0) en += REF(cert_quadric_normal)(q, sf->p, ep);
  }
  ref_cert_ep = ep;
  ref_cert_en = en;
}

real REF(cert_offset)(const ref_scene *sc, const ref_surface *sf, rvec3 origin) {
  real off = RV(length)(RV(sub)(origin, sf->p));
  real moved = (sc->frame->offset_strategy == RC_OFFSET_EPSILON) ? (ref_cert_en) * off
               : (sc->frame->offset_strategy == RC_OFFSET_ERROR_BOUND)
                   ? off + (real)1.4901161193847656e-8 * (RV(length)(sf->p_error) + RV(length)(sf->p) + ref_cert_ep + off)
                   : 2 * off;
  return moved + REF(gamma_bound)(2) * (RV(length)(origin) + off);
}

real REF(cert_origin)(const ref_scene *sc, const ref_surface *sf, rvec3 origin) {
  return ref_cert_ep + REF(cert_offset)(sc, sf, origin);
}

real REF(cert_t_min_start)(const ref_scene *sc, real eo, real ed, rvec3 origin) {
  if (sc->frame->offset_strategy != RC_OFFSET_T_MIN) return eo;
  real eps = (real)sc->frame->offset_epsilon;
  return eo + eps * ed + REF(gamma_bound)(2) * (RV(length)(origin) + 2 * eps);
}

void REF(cert_shadow)(const ref_scene *sc, packed_light light, const ref_surface *sf, rvec3 origin, real n_dot_l) {
  real eo = REF(cert_origin)(sc, sf, origin);
  ref_cert_et = 0;
  if (light.type == RC_LIGHT_POINT) {
    real r = RV(length)(RV(sub)(rvec3_from(light.position), sf->p));
    real dist = RV(length)(RV(sub)(rvec3_from(light.position), origin));
    real xl = ref_cert_ep + REF(gamma_bound)(4) * r;
    REF(cert_require)(sc, n_dot_l, ref_cert_en + REF(cert_turn_of)(xl, r) + REF(gamma_bound)(4));
    real xd = eo + REF(gamma_bound)(4) * dist;
    ref_cert_ed = REF(cert_turn_of)(xd, dist);
    ref_cert_eo = REF(cert_t_min_start)(sc, eo, ref_cert_ed, origin);
    ref_cert_t_max_err = eo + REF(gamma_bound)(7) * dist;
  } else {
    REF(cert_require)(sc, n_dot_l, ref_cert_en + REF(gamma_bound)(4));
    ref_cert_ed = 0;
    ref_cert_eo = REF(cert_t_min_start)(sc, eo, ref_cert_ed, origin);
    ref_cert_t_max_err = 0;
  }
}

void REF(cert_reflect)(const ref_scene *sc, const ref_surface *sf, rvec3 origin, real ed_in, real across) {
  ref_cert_ed = REF(cert_turn)(ed_in * (1 + REF(gamma_bound)(32)) + 2 * ref_cert_en + REF(gamma_bound)(58));
  bool moved = sc->frame->offset_strategy == RC_OFFSET_T_MIN;
  ref_cert_eo = REF(cert_t_min_start)(sc, REF(cert_origin)(sc, sf, moved ? sf->p : origin), ref_cert_ed, origin);
  ref_cert_et = 0;
  if (across < 0) return;
  ref_cert_et = ref_cert_eo;
  ref_cert_eo = across + REF(cert_offset)(sc, sf, origin) + 2 * (ref_cert_et) * ref_cert_ed;
}

real REF(cert_mirror_across)(const ref_scene *sc, const ref_hit *h, const ref_surface *sf, rvec3 o, rvec3 d, real eo,
                             real ed) {
  bool planar = false;
  rvec3 q = RV(make)(0, 0, 0);
  real gap = (real)RC_T_FAR;
  if (h->kind == RC_HIT_TRIANGLE) {
    packed_triangle tri = sc->triangles[h->index];
    planar = tri.normals == RC_NO_NORMALS;
    q = rvec3_from(tri.v0);
    gap = REF(cert_triangle_plane_gap)(tri, sf->ng, sf->p);
  }
  if (h->kind == RC_HIT_QUADRIC) {
    const packed_quadric *pq = &sc->quadrics[h->index];
    planar = (pq->flags & RC_QUADRIC_UNBOUNDED) != 0;
    q = rvec3_from(pq->center);
  }
  if (!planar || sc->frame->offset_strategy == RC_OFFSET_T_MIN) return -1;
  rvec3 w = RV(sub)(sf->p, o);
  rvec3 off_plane = RV(sub)(sf->p, q);
  real line = RV(length)(RV(cross)(w, d)) + REF(gamma_bound)(8) * RV(length)(w);
  real plane = rmin(R_ABS(RV(dot)(sf->ng, off_plane)) + REF(gamma_bound)(6) * (RV(length)(sf->p) + RV(length)(q)), gap);
  return eo + h->t * ed + line + 2 * plane;
}

/* The integer of a real's width, for the Wächter-Binder ulp offset. */
#if REF_F64
typedef int64_t offset_int;
#else
typedef int32_t offset_int;
#endif

static offset_int bits_of(real x) {
  offset_int i;
  memcpy(&i, &x, sizeof i);
  return i;
}

static real from_bits(offset_int i) {
  real x;
  memcpy(&x, &i, sizeof x);
  return x;
}

real REF(offset_coordinate)(real p, real n) {
  offset_int of = (offset_int)((real)RC_OFFSET_INT_SCALE * n);
  real moved = from_bits(bits_of(p) + ((p < 0) ? -of : of));
  return (R_ABS(p) < (real)RC_OFFSET_ORIGIN) ? p + (real)RC_OFFSET_FLOAT_SCALE * n : moved;
}

rvec3 REF(offset_ray_origin)(rvec3 p, rvec3 n) {
  return RV(make)(REF(offset_coordinate)(p.x, n.x), REF(offset_coordinate)(p.y, n.y), REF(offset_coordinate)(p.z, n.z));
}

real REF(next_float)(real v, bool up) {
  if (v == 0) return up ? RC_SMALLEST_NORMAL : -RC_SMALLEST_NORMAL;
  offset_int step = ((v > 0) == up) ? 1 : -1;
  return from_bits(bits_of(v) + step);
}

real REF(round_away)(real c, real n) {
  return (n > 0) ? REF(next_float)(c, true) : ((n < 0) ? REF(next_float)(c, false) : c);
}

rvec3 REF(offset_error_bound)(rvec3 p, rvec3 n, rvec3 p_error) {
  real dist = RV(dot)(RV(abs)(n), p_error);
  rvec3 po = RV(add)(p, RV(scale)(n, dist));
  return RV(make)(REF(round_away)(po.x, n.x), REF(round_away)(po.y, n.y), REF(round_away)(po.z, n.z));
}

rvec3 REF(spawn_origin)(const ref_scene *sc, const ref_surface *sf) {
  if (sc->frame->offset_strategy == RC_OFFSET_ULP) return REF(offset_ray_origin)(sf->p, sf->ng);
  if (sc->frame->offset_strategy == RC_OFFSET_EPSILON)
    return RV(add)(sf->p, RV(scale)(sf->ng, (real)sc->frame->offset_epsilon));
  if (sc->frame->offset_strategy == RC_OFFSET_T_MIN) return sf->p;
  return REF(offset_error_bound)(sf->p, sf->ng, sf->p_error);
}

/* The t_min strategy: a ray from the hit point that ignores hits nearer than epsilon is,
 * in exact arithmetic, the ray from epsilon along its direction, ending epsilon sooner.
 * The other strategies move the origin off the surface and change nothing here. */
rvec3 REF(t_min_start)(const ref_scene *sc, rvec3 origin, rvec3 d) {
  if (sc->frame->offset_strategy == RC_OFFSET_T_MIN)
    return RV(add)(origin, RV(scale)(d, (real)sc->frame->offset_epsilon));
  return origin;
}
real REF(t_min_end)(const ref_scene *sc, real t_max) {
  if (sc->frame->offset_strategy == RC_OFFSET_T_MIN) return t_max - (real)sc->frame->offset_epsilon;
  return t_max;
}

/* The shader raises to the power in f32 (GLSL has no double pow); the f64 reference
 * keeps double, as the accuracy reference. */
real REF(specular_term)(const ref_scene *sc, rvec3 n, rvec3 l, rvec3 v, float shininess) {
  real c;
  if (sc->frame->specular_model == RC_SPECULAR_PHONG) {
    c = RV(dot)(v, RV(sub)(RV(scale)(n, 2 * RV(dot)(n, l)), l));
  } else {
    c = RV(dot)(n, RV(normalize)(RV(add)(l, v)));
  }
  if (shininess == 0.0f) return 1;
#if REF_F64
  return (c > 0) ? pow(c, (double)shininess) : 0;
#else
  return (c > 0) ? powf(c, shininess) : 0;
#endif
}

bool REF(light_at)(packed_light light, rvec3 p, rvec3 origin, rvec3 *l, rvec3 *irradiance, rvec3 *to_light,
                   real *shadow_t_max) {
  if (light.type == RC_LIGHT_POINT) {
    rvec3 lp = rvec3_from(light.position);
    rvec3 delta = RV(sub)(lp, p);
    real r2 = RV(dot)(delta, delta);
    if (r2 == 0) return false;
    real r = R_SQRT(r2);
    *l = RV(scale)(delta, 1 / r);
    rvec3 k = rvec3_from(light.attenuation);
    *irradiance = RV(scale)(rvec3_from(light.intensity), 1 / (k.x + k.y * r + k.z * r2));
    rvec3 from_origin = RV(sub)(lp, origin);
    real dist = RV(length)(from_origin);
    *to_light = RV(scale)(from_origin, 1 / dist);
    *shadow_t_max = dist * (1 - (real)RC_SHADOW_EPSILON);
  } else {
    *l = RV(neg)(rvec3_from(light.position));
    *irradiance = rvec3_from(light.intensity);
    *to_light = *l;
    *shadow_t_max = (real)RC_T_FAR;
  }
  return true;
}

/* The shader's accessors of the texel array (rc_scene_access.glsl). */
static packed_texture load_texture(const ref_scene *sc, uint32_t first) {
  packed_texture t;
  memcpy(&t, sc->texels[first], sizeof t);
  return t;
}

static vec3 load_texel_rgb(const ref_scene *sc, uint32_t i) {
  return (vec3){sc->texels[i][0], sc->texels[i][1], sc->texels[i][2]};
}

static uint32_t load_texture_level(const ref_scene *sc, uint32_t first, uint32_t level) {
  uint32_t at;
  memcpy(&at, &sc->texels[first + 2u + (level >> 2u)][level & 3u], sizeof at);
  return at;
}

rvec3 REF(texel_at)(const ref_scene *sc, uint32_t texels, uint32_t flags, int w, int hh, int x, int y) {
  if (flags & RC_TEXTURE_CLAMP) {
    x = x < 0 ? 0 : (x > w - 1 ? w - 1 : x);
    y = y < 0 ? 0 : (y > hh - 1 ? hh - 1 : y);
  } else {
    x = x < 0 ? x + w : (x >= w ? x - w : x);
    y = y < 0 ? y + hh : (y >= hh ? y - hh : y);
  }
  return rvec3_from(load_texel_rgb(sc, texels + (uint32_t)y * (uint32_t)w + (uint32_t)x));
}

rvec3 REF(lerp_color)(rvec3 a, rvec3 b, real s) { return RV(add)(a, RV(scale)(RV(sub)(b, a), s)); }

rvec3 REF(level_color)(const ref_scene *sc, uint32_t first, packed_texture t, uint32_t level, real uu, real vv) {
  int w = (int)(((t.width - 1u) >> level) + 1u);
  int hh = (int)(((t.height - 1u) >> level) + 1u);
  uint32_t texels = (level == 0u) ? t.texels : load_texture_level(sc, first, level);
  real x = uu * (real)w - (real)0.5;
  real y = (1 - vv) * (real)hh - (real)0.5;
  if ((t.flags & RC_TEXTURE_BILINEAR) == 0 && level == 0u)
    return REF(texel_at)(sc, texels, t.flags, w, hh, (int)R_FLOOR(x + (real)0.5), (int)R_FLOOR(y + (real)0.5));
  real x0 = R_FLOOR(x);
  real y0 = R_FLOOR(y);
  real fx = x - x0;
  real fy = y - y0;
  int ix = (int)x0;
  int iy = (int)y0;
  rvec3 top = REF(lerp_color)(REF(texel_at)(sc, texels, t.flags, w, hh, ix, iy),
                              REF(texel_at)(sc, texels, t.flags, w, hh, ix + 1, iy), fx);
  rvec3 bottom = REF(lerp_color)(REF(texel_at)(sc, texels, t.flags, w, hh, ix, iy + 1),
                                 REF(texel_at)(sc, texels, t.flags, w, hh, ix + 1, iy + 1), fx);
  return REF(lerp_color)(top, bottom, fy);
}

rvec3 REF(texture_color)(const ref_scene *sc, uint32_t first, real u, real v, real fu, real fv) {
  packed_texture t = load_texture(sc, first);
  real uu = u * (real)t.scale_u + (real)t.offset_u;
  real vv = v * (real)t.scale_v + (real)t.offset_v;
  if (t.flags & RC_TEXTURE_CLAMP) {
    uu = uu < 0 ? 0 : (uu > 1 ? 1 : uu);
    vv = vv < 0 ? 0 : (vv > 1 ? 1 : vv);
  } else {
    uu = uu - R_FLOOR(uu);
    vv = vv - R_FLOOR(vv);
  }
  if (!(uu >= 0 && uu <= 1)) uu = 0;
  if (!(vv >= 0 && vv <= 1)) vv = 0;
  uint32_t levels = t.flags >> RC_TEXTURE_LEVELS_SHIFT;
  real n = rmax(fu * R_ABS((real)t.scale_u) * (real)t.width, fv * R_ABS((real)t.scale_v) * (real)t.height);
  uint32_t level = 0u;
  real s = 0;
  if (levels > 1u && n > 1) {
    level = levels - 1u;
    if (n < RL(1073741824.0)) {
      int e;
      real m = R_FREXP(n, &e);
      if ((uint32_t)(e - 1) < levels - 1u) {
        level = (uint32_t)(e - 1);
        s = 2 * m - 1;
      }
    }
  }
  rvec3 c = RV(make)(0, 0, 0);
  for (uint32_t k = 0u; k < ((s > 0) ? 2u : 1u); k++) {
    rvec3 ck = REF(level_color)(sc, first, t, level + k, uu, vv);
    c = (k == 0u) ? ck : REF(lerp_color)(c, ck, s);
  }
  return c;
}

real REF(atan2_poly)(real y, real x) {
  real ax = R_ABS(x);
  real ay = R_ABS(y);
  real hi = rmax(ax, ay);
  if (hi == 0) return 0;
  real a = rmin(ax, ay) / hi;
  real s = a * a;
  real p = ((((((RL(0.0028662257) * s - RL(0.0161657367)) * s + RL(0.0429096138)) * s - RL(0.0752896400)) * s +
              RL(0.1065626393)) * s - RL(0.1420889944)) * s + RL(0.1999355085)) * s - RL(0.3333314528);
  real r = a + a * (s * p);
  if (ay > ax) r = RL(1.5707963267948966) - r;
  if (x < 0) r = RL(3.141592653589793) - r;
  return (y < 0) ? -r : r;
}

void REF(surface_uv)(const ref_surface *sf, real *u, real *v) {
  if (sf->uv_kind == RC_UV_SPHERE) {
    rvec3 n = sf->uv_at;
    real across = R_SQRT(n.x * n.x + n.z * n.z);
    real uu = RL(0.5) + REF(atan2_poly)(n.x, n.z) * RL(0.15915494309189535);
    real vv = RL(0.5) + REF(atan2_poly)(n.y, across) * RL(0.3183098861837907);
    *u = uu;
    *v = vv;
  } else if (sf->uv_kind == RC_UV_AXIAL) {
    real uu = RL(0.5) + REF(atan2_poly)(sf->uv_at.x, sf->uv_at.y) * RL(0.15915494309189535);
    *u = uu;
    *v = sf->uv_at.z;
  } else {
    *u = sf->uv_at.x;
    *v = sf->uv_at.y;
  }
}

rvec3 REF(surface_texture)(const ref_scene *sc, packed_material m, const ref_surface *sf) {
  if (m.texture == RC_NO_TEXTURE || sf->uv_kind == RC_UV_NONE) return RV(make)(1, 1, 1);
  real u, v;
  REF(surface_uv)(sf, &u, &v);
  return REF(texture_color)(sc, m.texture, u, v, sf->footprint * sf->uv_rate.x, sf->footprint * sf->uv_rate.y);
}

rvec3 REF(light_contribution)(const ref_scene *sc, packed_material m, rvec3 kd, rvec3 n, rvec3 l, rvec3 v,
                              real n_dot_l, rvec3 irradiance) {
  return RV(mul)(irradiance, RV(add)(RV(scale)(kd, n_dot_l),
                                    RV(scale)(rvec3_from(m.specular), REF(specular_term)(sc, n, l, v, m.shininess))));
}

rvec3 REF(shade_phong)(const ref_scene *sc, const ref_surface *sf, rvec3 d) {
  packed_material m = sc->materials[sf->material];
  rvec3 tex = RV(make)(1, 1, 1);
  if (m.texture != RC_NO_TEXTURE) tex = REF(surface_texture)(sc, m, sf);
  rvec3 kd = RV(mul)(tex, rvec3_from(m.diffuse));
  rvec3 color = RV(add)(RV(mul)(RV(mul)(tex, rvec3_from(m.ambient)), rvec3_from(sc->frame->ambient_light)),
                        rvec3_from(m.emission));
  rvec3 v = RV(neg)(d);
  rvec3 origin = REF(spawn_origin)(sc, sf);
  ref_spawned_ray = true;
  for (uint32_t i = 0; i < sc->frame->light_count; i++) {
    rvec3 l, irradiance, to_light;
    real shadow_t_max;
    if (!REF(light_at)(sc->lights[i], sf->p, origin, &l, &irradiance, &to_light, &shadow_t_max)) continue;
    real n_dot_l = RV(dot)(sf->n, l);
    if (sc->frame->certify) REF(cert_shadow)(sc, sc->lights[i], sf, origin, n_dot_l);
    if (n_dot_l <= 0) continue;
    if (sc->frame->shadows) ref_shadow_rays++;
    if (sc->frame->shadows &&
        REF(occluded)(sc, REF(t_min_start)(sc, origin, to_light), to_light, REF(t_min_end)(sc, shadow_t_max), i)) {
      if (ref_aov_recording && i < RC_AOV_SHADOW_LIGHTS) ref_aov_record.shadow_bits += (float)(1u << i);
      ref_note_decision(2u * i + 1u);
      continue;
    }
    color = RV(add)(color, REF(light_contribution)(sc, m, kd, sf->n, l, v, n_dot_l, irradiance));
  }
  return color;
}
