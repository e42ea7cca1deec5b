// rc_shade.glsl: the hit point, its normal, shadow rays and Phong shading (DESIGN.md §1):
//   L = ka Ia + ke + sum_i visible_i [kd E_i max(0, n.l_i) + ks E_i spec_i^p],
//   E_i = I_i / (c0 + c1 r_i + c2 r_i^2) for point lights ((0, 0, 1) by default: 1/r^2),
//   I_i for directional lights.

struct surface {
  rvec3 p;        // hit point, rebuilt from the primitive rather than o + t d
  rvec3 n;        // unit shading normal, on the side facing the incoming ray
  rvec3 ng;       // unit geometric normal, facing the incoming ray: ray origins move along it
  uint material;
};

surface surface_at(rvec3 o, rvec3 d, hit_record h) {
  surface sf;
  rvec3 n;
  if (h.kind == RC_HIT_SPHERE) {
    // Centre-relative hit: l -/+ sqrt(D) d is exact to a few ulps of r at any distance,
    // where normalize(o + t d - C) loses digits with |o - C| (ROBUSTNESS.md §2.3).
    gpu_sphere s = load_sphere(h.index);
    real r = real(s.radius);
    rvec3 oo = o;
    rvec3 dd = d;
    gpu_transform m;
    if (s.transform != RC_NO_TRANSFORM) {
      m = load_transform(s.transform);
      oo = transform_point(m, o);
      dd = normalize(transform_vector(m, d));
    }
    precise rvec3 f = oo - rvec3(s.center);
    precise real b = dot(f, dd);
    precise rvec3 l = f - b * dd;
    precise real sq = sqrt(max(r * r - dot(l, l), 0.0));
    n = normalize(l + h.side * sq * dd);
    if (s.transform == RC_NO_TRANSFORM) {
      sf.p = rvec3(s.center) + r * n;
    } else {
      // Normals go back by the transpose of object_from_packed's linear part.
      n = normalize(rvec3(m.row0.xyz) * n.x + rvec3(m.row1.xyz) * n.y + rvec3(m.row2.xyz) * n.z);
      sf.p = o + h.t * d;
    }
    sf.material = s.material;
  } else {
    gpu_triangle tri = load_triangle(h.index);
    precise rvec3 p = h.bary.x * rvec3(tri.v0) + h.bary.y * rvec3(tri.v1) + h.bary.z * rvec3(tri.v2);
    sf.p = p;
    n = normalize(cross(rvec3(tri.v1) - rvec3(tri.v0), rvec3(tri.v2) - rvec3(tri.v0)));
    sf.material = tri.material;
    if (tri.normals != RC_NO_NORMALS) {
      gpu_vertex_normals vn = load_vertex_normals(tri.normals);
      rvec3 ng = (dot(n, d) > 0.0) ? -n : n;
      rvec3 ns = normalize(h.bary.x * rvec3(vn.n0) + h.bary.y * rvec3(vn.n1) + h.bary.z * rvec3(vn.n2));
      sf.ng = ng;
      sf.n = (dot(ns, ng) < 0.0) ? -ns : ns;
      return sf;
    }
  }
  sf.n = (dot(n, d) > 0.0) ? -n : n;
  sf.ng = sf.n;
  return sf;
}

#if RC_F64
#define RC_OFFSET_INT int64_t
#define RC_OFFSET_BITS(x) doubleBitsToInt64(x)
#define RC_OFFSET_FROM_BITS(x) int64BitsToDouble(x)
#else
#define RC_OFFSET_INT int
#define RC_OFFSET_BITS(x) floatBitsToInt(x)
#define RC_OFFSET_FROM_BITS(x) intBitsToFloat(x)
#endif

real offset_coordinate(real p, real n) {
  RC_OFFSET_INT of = RC_OFFSET_INT(RC_OFFSET_INT_SCALE * n);
  real moved = RC_OFFSET_FROM_BITS(RC_OFFSET_BITS(p) + ((p < 0.0) ? -of : of));
  return (abs(p) < RC_OFFSET_ORIGIN) ? p + RC_OFFSET_FLOAT_SCALE * n : moved;
}

// Origin of a ray leaving the surface at p on the side n points to (Wächter & Binder,
// rc_shared.h): a move of a fixed number of ulps, so it scales with |p|.
rvec3 offset_ray_origin(rvec3 p, rvec3 n) {
  return rvec3(offset_coordinate(p.x, n.x), offset_coordinate(p.y, n.y), offset_coordinate(p.z, n.z));
}

// cos^p of the highlight angle. pow(0, p) and pow(x, 0) are left undefined by GLSL for
// some inputs, so both ends are explicit.
real specular_term(rvec3 n, rvec3 l, rvec3 v, float shininess) {
  real c;
  if (frame.specular_model == RC_SPECULAR_PHONG) {
    c = dot(v, 2.0 * dot(n, l) * n - l);
  } else {
    c = dot(n, normalize(l + v));
  }
  if (shininess == 0.0) return 1.0;
  return (c > 0.0) ? real(pow(float(c), shininess)) : 0.0;
}

// Direct light at the surface seen along d: ambient, then each light whose shadow ray is
// unblocked. A point light exactly on the hit point (r = 0) contributes nothing.
rvec3 shade_phong(surface sf, rvec3 d) {
  gpu_material m = load_material(sf.material);
  rvec3 color = rvec3(m.ambient) * rvec3(frame.ambient_light) + rvec3(m.emission);
  rvec3 v = -d;
  rvec3 origin = offset_ray_origin(sf.p, sf.ng);
  for (uint i = 0u; i < frame.light_count; i++) {
    if (!budget_step()) break;
    gpu_light light = load_light(i);
    rvec3 l;
    rvec3 irradiance;
    rvec3 to_light;
    real shadow_t_max;
    if (light.type == RC_LIGHT_POINT) {
      rvec3 lp = rvec3(light.position);
      rvec3 delta = lp - sf.p;
      real r2 = dot(delta, delta);
      if (r2 == 0.0) continue;
      real r = sqrt(r2);
      l = delta / r;
      rvec3 k = rvec3(light.attenuation);
      irradiance = rvec3(light.intensity) / (k.x + k.y * r + k.z * r2);
      rvec3 from_origin = lp - origin;
      real dist = length(from_origin);
      to_light = from_origin / dist;
      shadow_t_max = dist * (1.0 - RC_SHADOW_EPSILON);
    } else {
      l = -rvec3(light.position);
      irradiance = rvec3(light.intensity);
      to_light = l;
      shadow_t_max = real(RC_T_FAR);
    }
    real n_dot_l = dot(sf.n, l);
    if (n_dot_l <= 0.0) continue;
    shadow_rays++;
    if (occluded(origin, to_light, shadow_t_max)) {
      if (aov_recording && i < RC_AOV_SHADOW_LIGHTS) aov_record.shadow_bits += float(1u << i);
      continue;
    }
    color += irradiance * (rvec3(m.diffuse) * n_dot_l +
                           rvec3(m.specular) * specular_term(sf.n, l, v, m.shininess));
  }
  return color;
}
