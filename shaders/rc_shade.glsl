// rc_shade.glsl: the hit point, its normal, shadow rays and Phong shading (docs/design.md §1):
//   L = ka Ia + ke + sum_i visible_i [kd E_i max(0, n.l_i) + ks E_i spec_i^p],
//   E_i = I_i / (c0 + c1 r_i + c2 r_i^2) for point lights ((0, 0, 1) by default: 1/r^2),
//   I_i for directional lights.

struct surface {
  rvec3 p;        // hit point, rebuilt from the primitive rather than o + t d
  rvec3 n;        // unit shading normal, on the side facing the incoming ray
  rvec3 ng;       // unit geometric normal, facing the incoming ray: ray origins move along it
  rvec3 p_error;  // per-coordinate bound on |p - exact hit point| (pbrt's pError), for spawning
  uint material;
  uint uv_kind;   // RC_UV_*: where its texture coordinates come from (surface_uv)
  rvec3 uv_at;    // a sphere's unit normal in its own frame; else (u, v, 0)
  rvec3 uv_rate;  // how fast u and v change along the surface, per packed unit (texture_color)
  real footprint; // the ray cone's width at the hit over |cos| of its incidence, packed units
  real curvature; // 1 / the radius of curvature where known (a sphere's), else 0 (flat)
};

// How fast a sphere's (u, v) change along its surface, at unit normal n on a sphere of
// radius r: the longitude by 1 / (2 pi r rho) (rho = |n.xz|, the distance from the axis
// over r, kept from 0 at the poles, where u spins), the latitude by 1 / (pi r).
rvec3 sphere_uv_rate(rvec3 n, real r) {
  real rho = select_max(sqrt(n.x * n.x + n.z * n.z), RL(0.0009765625));
  return rvec3(RL(0.15915494309189535) / (r * rho), RL(0.3183098861837907) / r, 0.0);
}

#if RC_QUADRICS
// A plane's texture coordinates (u, v, 0): the hit's frame coordinates from the packed
// centre, in scene units (lo.z per packed unit), from the point the scene gave (lo.xy;
// scene_pack.c).
rvec3 plane_uv(packed_quadric q, rvec3 p) {
  precise rvec3 f = quadric_local(q, p - rvec3(q.center));
  precise real u = f.x * real(q.lo.z) + real(q.lo.x);
  precise real v = f.y * real(q.lo.z) + real(q.lo.y);
  return rvec3(u, v, 0.0);
}

// A named quadric's texture coordinates at the surface point p of the part `code` names,
// in its own frame f (so they follow its transform); returns their kind (RC_UV_*). A box
// face (a cap): across the box, u from the face's next axis and v from the one after (x
// face: y, z; y face: z, x; z face: x, y). An ellipsoid's surface: the sphere's (the
// normalized point f / radii). An axial shape's side: u around frame z, 0.5 facing frame
// -y and growing towards +x (a vertical shape's 0.5 faces +z, as a sphere's does), v up
// the axis across the box, 0 at its base.
// uv_rate: how fast they change per packed unit (surface.uv_rate): s's rate along each
// frame axis is that axis's length (frame units per packed unit) over the box's side; an
// ellipsoid's is a sphere's of its smallest radius; an axial shape's u turns by 1 / (2 pi
// rho) at distance rho from its axis.
uint quadric_uv(packed_quadric q, uint code, rvec3 p, out rvec3 uv_at, out rvec3 uv_rate) {
  uv_at = rvec3(0.0);
  uv_rate = rvec3(0.0);
  uint kind = (q.flags >> RC_QUADRIC_UV_SHIFT) & 3u;
  // Compiled out where no material has a texture (the coordinates would go unused).
  if (!has_kind(RC_KIND_TEXTURES) || kind == RC_QUADRIC_UV_NONE) return RC_UV_NONE;
  precise rvec3 f = quadric_local(q, p - rvec3(q.center));
  precise rvec3 s = (f - rvec3(q.lo)) / (rvec3(q.hi) - rvec3(q.lo));
  rvec3 axes = rvec3(length(rvec3(q.axis_x)), length(rvec3(q.axis_y)), length(rvec3(q.axis_z)));
  rvec3 rate = axes / (rvec3(q.hi) - rvec3(q.lo));
  uint face = (code >> 2u) & 3u;
  if (face != 0u) {
    uv_at = (face == 1u) ? rvec3(s.y, s.z, 0.0) : ((face == 2u) ? rvec3(s.z, s.x, 0.0) : rvec3(s.x, s.y, 0.0));
    uv_rate = (face == 1u) ? rvec3(rate.y, rate.z, 0.0) : ((face == 2u) ? rvec3(rate.z, rate.x, 0.0) : rvec3(rate.x, rate.y, 0.0));
    return RC_UV_GIVEN;
  }
  if (kind == RC_QUADRIC_UV_ELLIPSOID) {
    rvec3 inv_radii = sqrt(rvec3(q.diag));
    rvec3 k = inv_radii * axes;
    uv_at = normalize(f * inv_radii);
    uv_rate = sphere_uv_rate(uv_at, 1.0 / select_max(select_max(k.x, k.y), k.z));
    return RC_UV_SPHERE;
  }
  if (kind == RC_QUADRIC_UV_AXIAL) {
    uv_at = rvec3(f.x, -f.y, s.z);
    real rho = select_max(sqrt(f.x * f.x + f.y * f.y), RL(1e-30));
    uv_rate = rvec3(RL(0.15915494309189535) * axes.x / rho, rate.z, 0.0);
    return RC_UV_AXIAL;
  }
  return RC_UV_NONE;
}
#endif


#if RC_QUADRICS
// The hit point o + t d moved onto the quadric surface a code names (face 0) by one Newton
// step along the gradient, and its error bound. A root's t is ill-conditioned where the
// ray grazes the surface (along a cone's generator, near a silhouette), and o + t d can
// then lie further off the surface than any bound on t's own rounding would admit, so
// shadow rays leave from below it (acne). After the step the point's distance to the
// surface is Q's rounding error over |grad Q| (pbrt re-projects its quadrics' hit points
// for the same reason, pbrt-v4 shapes.h); the error bound is that distance plus the
// rounding of p - c (which Q saw) and of the step.
rvec3 quadric_refine(packed_quadric q, rvec3 p, inout rvec3 p_error) {
  rvec3 L = rvec3(q.linear);
  precise rvec3 pc = p - rvec3(q.center);
  precise rvec3 f = quadric_local(q, pc);
  precise rvec3 mf = quadric_apply(q, f);
  precise rvec3 g = mf + L;
  precise real value = dot(f, mf) + 2.0 * dot(L, f) + real(q.constant);
  // grad Q / 2 in packed space is R^T g (R the frame's rows: a rotation, or any invertible
  // matrix under a transform), and Newton's step along it is Q / |grad Q|^2 grad Q. Only
  // the (small) step is carried out of the frame: a round trip of p itself through f32
  // rows would move it by their rounding times |p - c|.
  precise rvec3 gw = g.x * rvec3(q.axis_x) + g.y * rvec3(q.axis_y) + g.z * rvec3(q.axis_z);
  real gg = dot(gw, gw);
  if (gg == 0.0) return p;  // a singular point (a cone's apex): keep o + t d and its bound
  precise rvec3 dp = (value / (2.0 * gg)) * gw;
  precise rvec3 pr = p - dp;
  real value_error = gamma_bound(16.0) * (dot(abs(f), abs(mf)) + 2.0 * dot(abs(L), abs(f)) + abs(real(q.constant)));
  p_error = gamma_bound(8.0) * (abs(pr) + abs(pc)) + rvec3(value_error / (2.0 * sqrt(gg)));
  return pr;
}
#endif

// A triangle's texture coordinates (u, v, 0) at barycentrics b, from its vertices'.
rvec3 triangle_uv(packed_vertex_uvs t, rvec3 b) {
  precise real u = b.x * real(t.u0) + b.y * real(t.u1) + b.z * real(t.u2);
  precise real v = b.x * real(t.v0) + b.y * real(t.v1) + b.z * real(t.v2);
  return rvec3(u, v, 0.0);
}

// How fast a triangle's (u, v) change along it: sqrt(its area in (u, v) over its area),
// both directions alike (the ray cone's texel-to-surface ratio, Akenine-Moller et al.,
// "Texture Level of Detail Strategies for Real-Time Ray Tracing", Ray Tracing Gems, 2019).
rvec3 triangle_uv_rate(packed_vertex_uvs t, packed_triangle tri) {
  real uv_area = abs((real(t.u1) - real(t.u0)) * (real(t.v2) - real(t.v0)) - (real(t.u2) - real(t.u0)) * (real(t.v1) - real(t.v0)));
  real area = length(cross(rvec3(tri.v1) - rvec3(tri.v0), rvec3(tri.v2) - rvec3(tri.v0)));
  real rate = (area > 0.0) ? sqrt(uv_area / area) : 0.0;
  return rvec3(rate, rate, 0.0);
}

surface surface_at(rvec3 o, rvec3 d, hit_record h) {
  surface sf;
  sf.uv_kind = RC_UV_NONE;
  sf.uv_at = rvec3(0.0);
  sf.uv_rate = rvec3(0.0);
  sf.footprint = 0.0;
  sf.curvature = 0.0;
  rvec3 n;
  if (has_kind(RC_KIND_SPHERES) && h.kind == RC_HIT_SPHERE) {
    packed_sphere s = load_sphere(h.index);
    real r = real(s.radius);
    rvec3 oo = o;
    rvec3 dd = d;
    real t_obj = h.t;
    packed_transform m;
    if (has_kind(RC_KIND_SPHERE_TRANSFORMS) && s.transform != RC_NO_TRANSFORM) {
      m = load_transform(s.transform);
      oo = transform_point(m, o);
      rvec3 d_obj = transform_vector(m, d);
      t_obj = h.t * length(d_obj);
      dd = normalize(d_obj);
    }
    if (sphere_formula == RC_SPHERE_ALGEBRAIC) {
      // The textbook normal from the hit point; its error grows with |o - C| (docs/numerics.md §2).
      n = normalize(oo + t_obj * dd - rvec3(s.center));
    } else {
      // Centre-relative hit: l -/+ sqrt(D) d is exact to a few ulps of r at any distance,
      // where normalize(o + t d - C) loses digits with |o - C|.
      precise rvec3 f = oo - rvec3(s.center);
      precise real b = dot(f, dd);
      precise rvec3 l = f - b * dd;
      precise real sq = sqrt(max(r * r - dot(l, l), 0.0));
      n = normalize(l + h.side * sq * dd);
    }
    sf.uv_kind = RC_UV_SPHERE;
    sf.uv_at = n;
    sf.uv_rate = sphere_uv_rate(n, r);
    sf.curvature = 1.0 / r;
    if ((!has_kind(RC_KIND_SPHERE_TRANSFORMS) || s.transform == RC_NO_TRANSFORM) && sphere_formula == RC_SPHERE_GEOMETRIC) {
      precise rvec3 rn = r * n;
      sf.p = rvec3(s.center) + rn;
      // pbrt bounds its re-projected sphere point by gamma(5)|p| in object space; here p is
      // assembled in packed space from C and r n, and n went through a GPU sqrt and
      // normalize (not correctly rounded, docs/numerics.md §1): both terms, with headroom.
      sf.p_error = gamma_bound(10.0) * (abs(rvec3(s.center)) + abs(rn));
    } else {
      if (has_kind(RC_KIND_SPHERE_TRANSFORMS) && s.transform != RC_NO_TRANSFORM) {
        // Normals go back by the transpose of object_from_packed's linear part; its largest
        // row stretches a packed step the most (an estimate of its norm).
        n = normalize(n.x * rvec3(m.row0.xyz) + n.y * rvec3(m.row1.xyz) + n.z * rvec3(m.row2.xyz));
        real stretch = select_max(select_max(length(rvec3(m.row0.xyz)), length(rvec3(m.row1.xyz))), length(rvec3(m.row2.xyz)));
        sf.uv_rate = sf.uv_rate * stretch;
        sf.curvature = sf.curvature * stretch;
      }
      precise rvec3 td = h.t * d;
      sf.p = o + td;
      // o + t d carries t's own error, which no short formula bounds; 32 roundings' worth
      // of |o| + |t d| is a measured, not derived, margin (docs/accuracy.md).
      sf.p_error = gamma_bound(32.0) * (abs(o) + abs(td));
    }
    sf.material = s.material;
#if RC_QUADRICS
  } else if (h.kind == RC_HIT_QUADRIC || h.kind == RC_HIT_CSG) {
    precise rvec3 td = h.t * d;
    sf.p = o + td;
    // A box face (a plane) is hit as well as o + t d allows, as for transformed spheres;
    // a quadric surface point is re-projected onto the surface.
    sf.p_error = gamma_bound(32.0) * (abs(o) + abs(td));
    uint leaf = h.part >> RC_CSG_CODE_LEAF_SHIFT;  // the surface's leaf (rc_quadric.glsl, csg_code)
    if ((h.part & RC_CSG_CODE_MESH) != 0u) {
      packed_triangle tri = load_triangle(leaf);
      n = normalize(mesh_normal(tri, h.part, d));
      sf.material = tri.material;
    } else {
      packed_quadric q = load_quadric(leaf);
#if RC_PATCHES
      if (has_kind(RC_KIND_PATCHES) && (q.flags & RC_QUADRIC_PATCH) != 0u) {
        // The point and normal at the converged (u, v), which are also the texture's.
        rvec3 g = patch_surface(q, h.bary, sf.p, sf.p_error);
        n = (dot(g, g) > 0.0) ? normalize(g) : -d;  // a net collapsed to a curve: no normal
        sf.uv_kind = RC_UV_GIVEN;
        sf.uv_at = h.bary;
        // |g| = |dS/du x dS/dv|: a unit square of (u, v) covers |g| of surface.
        real g_area = length(g);
        real rate = (g_area > 0.0) ? 1.0 / sqrt(g_area) : 0.0;
        sf.uv_rate = rvec3(rate, rate, 0.0);
      } else
#endif
      {
        if (((h.part >> 2u) & 3u) == 0u) sf.p = quadric_refine(q, sf.p, sf.p_error);
        n = normalize(quadric_normal(q, h.part, sf.p, d));
        sf.uv_kind = quadric_uv(q, h.part, sf.p, sf.uv_at, sf.uv_rate);
      }
      sf.material = q.material;
      if ((q.flags & RC_QUADRIC_UNBOUNDED) != 0u) {
        sf.uv_kind = RC_UV_GIVEN;
        sf.uv_at = plane_uv(q, sf.p);
        sf.uv_rate = rvec3(real(q.lo.z), real(q.lo.z), 0.0);
      }
    }
#endif
  } else {
    packed_triangle tri = load_triangle(h.index);
    precise rvec3 p0 = h.bary.x * rvec3(tri.v0);
    precise rvec3 p1 = h.bary.y * rvec3(tri.v1);
    precise rvec3 p2 = h.bary.z * rvec3(tri.v2);
    sf.p = p0 + p1 + p2;
    // pbrt-v4 (shapes.h, Triangle): gamma(7) (|b0 p0| + |b1 p1| + |b2 p2|).
    sf.p_error = gamma_bound(7.0) * (abs(p0) + abs(p1) + abs(p2));
    n = normalize(cross(rvec3(tri.v1) - rvec3(tri.v0), rvec3(tri.v2) - rvec3(tri.v0)));
    sf.material = tri.material;
    if (has_kind(RC_KIND_TEXTURES) && (tri.flags >> RC_TRIANGLE_UV_SHIFT) != 0u) {
      packed_vertex_uvs uvs = load_vertex_uvs((tri.flags >> RC_TRIANGLE_UV_SHIFT) - 1u);
      sf.uv_kind = RC_UV_GIVEN;
      sf.uv_at = triangle_uv(uvs, h.bary);
      sf.uv_rate = triangle_uv_rate(uvs, tri);
    }
    if (has_kind(RC_KIND_VERTEX_NORMALS) && tri.normals != RC_NO_NORMALS) {
      packed_vertex_normals vn = load_vertex_normals(tri.normals);
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

#if RC_CERTIFY
// Whether the hit point is o + t d, or that point's projection onto a plane (quadric_refine's
// Newton step is one there): a transformed sphere's, a box face's, a plane's, a mesh
// operand's. Not a curved quadric surface's, which the step moves along its curvature, nor a
// triangle's or a sphere's, computed on the surface.
bool cert_point_on_ray(hit_record h, uint transform) {
  if (transform != RC_NO_TRANSFORM) return true;
#if RC_QUADRICS
  if (h.kind == RC_HIT_QUADRIC || h.kind == RC_HIT_CSG) {
    if ((h.part & RC_CSG_CODE_MESH) != 0u || ((h.part >> 2u) & 3u) != 0u) return true;
    return (load_quadric(h.part >> RC_CSG_CODE_LEAF_SHIFT).flags & RC_QUADRIC_UNBOUNDED) != 0u;
  }
#endif
  return false;
}

// The surface's decisions and the perturbation of its point and normal (rc_shade.glsl,
// surface_at). The exact hit point of a ray moved by (do, dd) moves by (|do| + t |dd|) / |cos|
// along the surface (cos = n.d), on top of both points' rounding (p_error, and where the point
// is o + t d, t's own error, which p_error leaves out). Where the point is o + t d (or its
// projection onto a plane, which moves no two points further apart), it is closer: o + t d
// against o_ref + t_ref d_ref differs by at most |do| + t |dd| + |t - t_ref|, and t's bound
// (h.err) already holds the rays' move. A sphere's normal n, with p = C + r n
// rounded by p_error, moves by p's move plus that rounding, over r; through a transform A
// (where p is o + t d instead) by |A| times twice p's move over r, and normalize(A^T n) by
// |A| / sigma_min(A) of it, sigma_min(A) >= 2 |det A| / |A|_F^2. The side the normal is
// flipped to is a decision on n.d.
void cert_surface(rvec3 d, hit_record h, surface sf) {
#if RC_PATCHES
  if (has_kind(RC_KIND_PATCHES) && h.kind == RC_HIT_QUADRIC) {
    packed_quadric q = load_quadric(h.part >> RC_CSG_CODE_LEAF_SHIFT);
    if ((q.flags & RC_QUADRIC_PATCH) != 0u) {
      cert_patch_surface(q, d, h.bary, h.bary_err, h.off_err, h.t, sf.ng, sf.p_error);
      return;
    }
  }
#endif
  uint transform = (has_kind(RC_KIND_SPHERE_TRANSFORMS) && h.kind == RC_HIT_SPHERE) ? load_sphere(h.index).transform
                                                                                    : RC_NO_TRANSFORM;
  bool along_ray = h.kind == RC_HIT_QUADRIC || h.kind == RC_HIT_CSG || transform != RC_NO_TRANSFORM;
  // (A point o + t d moves by t's bound and by the origin's shift along the ray, which t's
  // bound, taken against the other roots, leaves out: cert_et.)
  real ep_round = 2.0 * length(sf.p_error) + (along_ray ? h.err + cert_factor() * cert_et : 0.0);
  real cosine = abs(dot(sf.ng, d));
  real e_cos = cert_ed + gamma_bound(12.0);
  cert_require(cosine, e_cos);
  real moved = cert_eo + h.t * cert_ed;
  real ep = ep_round + (cert_point_on_ray(h, transform) ? moved : 2.0 * moved / select_max(cosine - e_cos, RC_SMALLEST_NORMAL));
  real en = gamma_bound(12.0);
  if (h.kind == RC_HIT_SPHERE) {
    real r = real(load_sphere(h.index).radius);
    if (transform == RC_NO_TRANSFORM) {
      en += (ep + length(sf.p_error)) / r;
    } else {
      real dn = 2.0 * ep / r;
      packed_transform m = load_transform(transform);
      real na = cert_norm(m);
      real det = abs(dot(rvec3(m.row0.xyz), cross(rvec3(m.row1.xyz), rvec3(m.row2.xyz))));
      en += (na * na * dn + gamma_bound(4.0) * na) * na * na / det + gamma_bound(4.0);
    }
  }
  if (h.kind == RC_HIT_TRIANGLE) {
    packed_triangle tri = load_triangle(h.index);
    if (has_kind(RC_KIND_VERTEX_NORMALS) && tri.normals != RC_NO_NORMALS) {
      // The interpolated normal moves with the barycentrics; its flip towards ng is a decision.
      packed_vertex_normals vn = load_vertex_normals(tri.normals);
      rvec3 ns = h.bary.x * rvec3(vn.n0) + h.bary.y * rvec3(vn.n1) + h.bary.z * rvec3(vn.n2);
      // The barycentrics sum to 1, so their errors move ns by the normals' differences.
      real spread = length(rvec3(vn.n1) - rvec3(vn.n0)) + length(rvec3(vn.n2) - rvec3(vn.n0));
      real size = length(rvec3(vn.n0)) + length(rvec3(vn.n1)) + length(rvec3(vn.n2));
      en += 2.0 * (h.bary_err * spread + gamma_bound(6.0) * size) / length(ns);
      cert_require(dot(sf.n, sf.ng), en + gamma_bound(12.0));
    }
  }
#if RC_QUADRICS
  // A quadric's surface, alone or a composite's leaf (not a mesh operand's triangle, whose
  // face normal only rounds).
  bool leaf = h.kind == RC_HIT_QUADRIC || (h.kind == RC_HIT_CSG && (h.part & RC_CSG_CODE_MESH) == 0u);
  if (leaf && ((h.part >> 2u) & 3u) == 0u) {
    packed_quadric q = load_quadric(h.part >> RC_CSG_CODE_LEAF_SHIFT);
    if ((q.flags & RC_QUADRIC_UNBOUNDED) == 0u) en += cert_quadric_normal(q, sf.p, ep);
  }
#endif
  cert_ep = ep;
  cert_en = en;
}

// The perturbation of a spawned ray's origin (spawn_origin) beyond its point's: the two
// offsets' difference, and the rounding. The epsilon offset lies along the geometric normal, which turns
// by at most cert_en (ng is n, or a triangle's face normal whose only error is rounding). The
// error-bound offset is the point's error bound along ng and an ulp; the reference's is f64's,
// whose p_error is the same magnitudes times f64's gamma, 2^-29 of ours, so it is at most
// 2^-26 (|p_error| + |p| + ep + off) long, its ulp included: the two differ by at most this
// one's length and that. The ulp offset moves a coordinate near 0 by a fixed amount in either
// precision, so it keeps the bound of twice this one's length. The t-min strategy's origin is
// the point; its start, epsilon along the ray, is cert_t_min_start's.
real cert_offset(surface sf, rvec3 origin) {
  real off = length(origin - sf.p);
  real moved = (offset_strategy == RC_OFFSET_EPSILON) ? cert_en * off
               : (offset_strategy == RC_OFFSET_ERROR_BOUND)
                   ? off + real(1.4901161193847656e-8) * (length(sf.p_error) + length(sf.p) + cert_ep + off)
                   : 2.0 * off;
  return moved + gamma_bound(2.0) * (length(origin) + off);
}

// The point's move and the offsets' (cert_offset: how far the two origins' moves off their
// points differ).
real cert_origin(surface sf, rvec3 origin) { return cert_ep + cert_offset(sf, origin); }

// The t-min strategy's start origin + epsilon d (t_min_start), for a direction ed from the
// reference's: the offset turns by epsilon ed and rounds with the sum, whose terms are at most
// |origin| + 2 epsilon for an origin up to epsilon from the point. The other strategies start
// at their origin.
real cert_t_min_start(real eo, real ed, rvec3 origin) {
  if (offset_strategy != RC_OFFSET_T_MIN) return eo;
  real eps = real(offset_epsilon);
  return eo + eps * ed + gamma_bound(2.0) * (length(origin) + 2.0 * eps);
}

// A shadow ray's perturbation (rc_shade.glsl, light_at and shade_phong) and its decision to be
// cast (n.l > 0): towards a point light its direction turns as its origin's move (and the
// subtraction's rounding) over the distance allows (cert_turn), and t_max moves by as much
// (and t_min_end's rounding).
void cert_shadow(packed_light light, surface sf, rvec3 origin, real n_dot_l) {
  real eo = cert_origin(sf, origin);
  cert_et = 0.0;
  if (light.type == RC_LIGHT_POINT) {
    real r = length(rvec3(light.position) - sf.p);
    real dist = length(rvec3(light.position) - origin);
    real xl = cert_ep + gamma_bound(4.0) * r;
    cert_require(n_dot_l, cert_en + cert_turn_of(xl, r) + gamma_bound(4.0));
    real xd = eo + gamma_bound(4.0) * dist;
    cert_ed = cert_turn_of(xd, dist);
    cert_eo = cert_t_min_start(eo, cert_ed, origin);
    cert_t_max_err = eo + gamma_bound(7.0) * dist;
  } else {
    cert_require(n_dot_l, cert_en + gamma_bound(4.0));
    cert_ed = 0.0;
    cert_eo = cert_t_min_start(eo, cert_ed, origin);
    cert_t_max_err = 0.0;
  }
}

// A mirror bounce's perturbation (rc_trace.glsl): the origin as a shadow ray's; the direction
// r = d - 2 (d.n) n = (I - 2 n n^T) d. Against the reference's unit d_ref, n_ref:
// r - r_ref = (I - 2 n n^T)(d - d_ref) - 2 (n n^T - n_ref n_ref^T) d_ref. The first term is at
// most dd times the reflection's norm, 1 + 4 eta for |n| = 1 + eta (eta <= gamma(8) after
// normalize, cert_turn); for unit vectors |n n^T - m m^T| is the sine of their angle, at most
// |n - m|, and n / |n| is eta farther from n_ref than n, while |n|^2 - 1 adds 4 eta |d.n|: the
// second term is at most 2 dn + 6 eta. The reflection rounds by about gamma(9) (a dot
// product, two products, a difference). normalize turns r by cert_turn of the sum, r_ref
// being a unit vector.
// The origin passed is the start: for the t-min strategy, the point moved along r. Off a
// plane mirror (`across` >= 0, cert_mirror_across) the two rays' lines are closer than their
// origins: across them the origins differ by `across` and the offsets' difference, and along
// them by the origins' whole bound (cert_et), which moves only where t meets 0; the shift
// along the reference's direction rather than this one adds et ed.
void cert_reflect(surface sf, rvec3 origin, real ed_in, real across) {
  cert_ed = cert_turn(ed_in * (1.0 + gamma_bound(32.0)) + 2.0 * cert_en + gamma_bound(58.0));
  bool moved = offset_strategy == RC_OFFSET_T_MIN;
  cert_eo = cert_t_min_start(cert_origin(sf, moved ? sf.p : origin), cert_ed, origin);
  cert_et = 0.0;
  if (across < 0.0) return;
  cert_et = cert_eo;
  cert_eo = across + cert_offset(sf, origin) + 2.0 * cert_et * cert_ed;
}

// A plane mirror (docs/numerics.md §10): reflection in the mirror's plane is an isometry that
// maps each precision's incident line onto its reflected line, so at s along the reflected
// rays the two lines are as far apart as the incident ones at t + s along theirs, eo +
// (t + s) ed, where the exact reflections start; this point (the reflected ray's start before
// its offset) lies off this incident line by |(p - o) x d| and off the plane by |n.(p - q)|,
// whose mirror image moves it by twice that. Returns the lines' distance at the point, or -1
// where the mirror is not a plane both precisions reflect in alike: a plane, or a triangle with
// its face normal (not with vertex normals, not a composite's face, not under t-min, whose
// origin is the point moved along the ray). eo and ed are the incident ray's.
real cert_mirror_across(hit_record h, surface sf, rvec3 o, rvec3 d, real eo, real ed) {
  bool planar = false;
  rvec3 q = rvec3(0.0);
  real gap = real(RC_T_FAR);
  if (h.kind == RC_HIT_TRIANGLE) {
    packed_triangle tri = load_triangle(h.index);
    planar = !has_kind(RC_KIND_VERTEX_NORMALS) || tri.normals == RC_NO_NORMALS;
    q = rvec3(tri.v0);
    gap = cert_triangle_plane_gap(tri, sf.ng, sf.p);
  }
#if RC_QUADRICS
  if (h.kind == RC_HIT_QUADRIC) {
    packed_quadric pq = load_quadric(h.index);
    planar = (pq.flags & RC_QUADRIC_UNBOUNDED) != 0u;
    q = rvec3(pq.center);
  }
#endif
  if (!planar || offset_strategy == RC_OFFSET_T_MIN) return -1.0;
  precise rvec3 w = sf.p - o;
  precise rvec3 off_plane = sf.p - q;
  real line = length(cross(w, d)) + gamma_bound(8.0) * length(w);
  // A triangle's gap bound is the tighter where its normal lies near an axis (a floor).
  real plane = select_min(abs(dot(sf.ng, off_plane)) + gamma_bound(6.0) * (length(sf.p) + length(q)), gap);
  return eo + h.t * ed + line + 2.0 * plane;
}
#endif

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

// The neighbouring float of v away from 0 in the direction `up` (pbrt's NextFloatUp/Down).
real next_float(real v, bool up) {
  if (v == 0.0) return up ? RC_SMALLEST_NORMAL : -RC_SMALLEST_NORMAL;
  RC_OFFSET_INT step = ((v > 0.0) == up) ? RC_OFFSET_INT(1) : RC_OFFSET_INT(-1);
  return RC_OFFSET_FROM_BITS(RC_OFFSET_BITS(v) + step);
}

// A coordinate moved one float further along the normal's component n.
real round_away(real c, real n) { return (n > 0.0) ? next_float(c, true) : ((n < 0.0) ? next_float(c, false) : c); }

// pbrt's OffsetRayOrigin (pbrt-v4 ray.h): out of the error box of p along n, by
// |n| . p_error, then one more float away so that rounding cannot land back inside it.
rvec3 offset_error_bound(rvec3 p, rvec3 n, rvec3 p_error) {
  precise real dist = dot(abs(n), p_error);
  precise rvec3 po = p + dist * n;
  return rvec3(round_away(po.x, n.x), round_away(po.y, n.y), round_away(po.z, n.z));
}

// The origin of a shadow or reflection ray leaving the surface, by the chosen strategy.
rvec3 spawn_origin(surface sf) {
  if (offset_strategy == RC_OFFSET_ULP) return offset_ray_origin(sf.p, sf.ng);
  if (offset_strategy == RC_OFFSET_EPSILON) return sf.p + real(offset_epsilon) * sf.ng;
  if (offset_strategy == RC_OFFSET_T_MIN) return sf.p;
  return offset_error_bound(sf.p, sf.ng, sf.p_error);
}

// The t_min strategy: a ray from the hit point that ignores hits nearer than epsilon is,
// in exact arithmetic, the ray from epsilon along its direction, ending epsilon sooner.
// The other strategies move the origin off the surface and change nothing here.
rvec3 t_min_start(rvec3 origin, rvec3 d) {
  if (offset_strategy == RC_OFFSET_T_MIN) return origin + real(offset_epsilon) * d;
  return origin;
}
real t_min_end(real t_max) {
  if (offset_strategy == RC_OFFSET_T_MIN) return t_max - real(offset_epsilon);
  return t_max;
}

// cos^p of the highlight angle. pow(0, p) and pow(x, 0) are left undefined by GLSL for
// some inputs, so both ends are explicit.
real specular_term(rvec3 n, rvec3 l, rvec3 v, float shininess) {
  real c;
  if (scene_specular_model() == RC_SPECULAR_PHONG) {
    c = dot(v, (2.0 * dot(n, l)) * n - l);
  } else {
    c = dot(n, normalize(l + v));
  }
  if (shininess == 0.0) return 1.0;
  return (c > 0.0) ? real(pow(float(c), shininess)) : 0.0;
}

// Light `light` seen from the surface point p, whose shadow rays leave from origin: the
// unit direction l towards it, the irradiance it delivers there (a point light's intensity
// over its attenuation c0 + c1 r + c2 r^2), and the shadow ray's direction and extent
// (short of the light by RC_SHADOW_EPSILON, so the light's own position never blocks).
// False for a point light exactly at p (r = 0), which contributes nothing.
bool light_at(packed_light light, rvec3 p, rvec3 origin, out rvec3 l, out rvec3 irradiance, out rvec3 to_light,
              out real shadow_t_max) {
  if (light.type == RC_LIGHT_POINT) {
    rvec3 lp = rvec3(light.position);
    rvec3 delta = lp - p;
    real r2 = dot(delta, delta);
    if (r2 == 0.0) return false;
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
  return true;
}

// Texel (x, y) of a level of w x hh texels from `texels` on, the column and row wrapped
// (repeat) or clamped (flags, packed_texture) onto it. level_color passes -1 <= x <= w and
// -1 <= y <= hh (its coordinates are wrapped to [0, 1] first), so one period wraps them: a
// select, where `%` is an integer division that llvmpipe scalarises, eight a vector
// (docs/performance.md, "Texels without division").
rvec3 texel_at(uint texels, uint flags, int w, int hh, int x, int y) {
  if ((flags & RC_TEXTURE_CLAMP) != 0u) {
    x = x < 0 ? 0 : (x > w - 1 ? w - 1 : x);
    y = y < 0 ? 0 : (y > hh - 1 ? hh - 1 : y);
  } else {
    x = x < 0 ? x + w : (x >= w ? x - w : x);
    y = y < 0 ? y + hh : (y >= hh ? y - hh : y);
  }
  return rvec3(load_texel_rgb(texels + uint(y) * uint(w) + uint(x)));
}

// a + (b - a) s: exactly a where b = a, so a constant texture gives exactly its colour.
rvec3 lerp_color(rvec3 a, rvec3 b, real s) {
  precise rvec3 c = a + s * (b - a);
  return c;
}

// Mip level `level` of the texture at `first` (header t) at (uu, vv) in [0, 1]: u across
// the image from its left edge, v up from its bottom edge. In texel units x = uu W - 1/2,
// y = (1 - vv) H - 1/2 put texel centres on integers: nearest rounds, bilinear blends the
// four around (x, y). Nearest is level 0's alone (a magnification filter, as OpenGL's mag
// filter is): the levels past it are means, read bilinearly, so that a minified lookup
// stays continuous in the hit point and its nearest texels fade out as its footprint
// grows from one texel to two.
rvec3 level_color(uint first, packed_texture t, uint level, real uu, real vv) {
  int w = int(((t.width - 1u) >> level) + 1u);
  int hh = int(((t.height - 1u) >> level) + 1u);
  uint texels = (level == 0u) ? t.texels : load_texture_level(first, level);
  precise real x = uu * real(w) - 0.5;
  precise real y = (1.0 - vv) * real(hh) - 0.5;
  if ((t.flags & RC_TEXTURE_BILINEAR) == 0u && level == 0u)
    return texel_at(texels, t.flags, w, hh, int(floor(x + 0.5)), int(floor(y + 0.5)));
  real x0 = floor(x);
  real y0 = floor(y);
  precise real fx = x - x0;
  precise real fy = y - y0;
  int ix = int(x0);
  int iy = int(y0);
  rvec3 top = lerp_color(texel_at(texels, t.flags, w, hh, ix, iy), texel_at(texels, t.flags, w, hh, ix + 1, iy), fx);
  rvec3 bottom = lerp_color(texel_at(texels, t.flags, w, hh, ix, iy + 1), texel_at(texels, t.flags, w, hh, ix + 1, iy + 1), fx);
  return lerp_color(top, bottom, fy);
}

// The texture's colour at surface coordinates (u, v) (packed_texture), where a ray cone's
// footprint moves them by about fu and fv: u' = u scale_u + offset_u across the image, v' =
// v scale_v + offset_v up it; repeat takes the fraction, clamp the nearest edge. A footprint
// of n > 1 level-0 texels reads mip level log2 n, linear between the two levels around it
// (a trilinear lookup; docs/scene-format.md, "Textures"): the mean of the texels it covers,
// where a lookup of level 0 alone would alias, and would change with a hit point's last
// bits. log2 n is taken linear within each octave, n = m 2^e with m in [1/2, 1) (frexp,
// exact): both backends find the same level and weight, and the colour is continuous in n.
rvec3 texture_color(uint first, real u, real v, real fu, real fv) {
  packed_texture t = load_texture(first);
  precise real uu = u * real(t.scale_u) + real(t.offset_u);
  precise real vv = v * real(t.scale_v) + real(t.offset_v);
  if ((t.flags & RC_TEXTURE_CLAMP) != 0u) {
    uu = uu < 0.0 ? 0.0 : (uu > 1.0 ? 1.0 : uu);
    vv = vv < 0.0 ? 0.0 : (vv > 1.0 ? 1.0 : vv);
  } else {
    uu = uu - floor(uu);
    vv = vv - floor(vv);
  }
  if (!(uu >= 0.0 && uu <= 1.0)) uu = 0.0;  // NaN: a surface point at infinity
  if (!(vv >= 0.0 && vv <= 1.0)) vv = 0.0;
  uint levels = t.flags >> RC_TEXTURE_LEVELS_SHIFT;
  precise real n = select_max(fu * abs(real(t.scale_u)) * real(t.width), fv * abs(real(t.scale_v)) * real(t.height));
  uint level = 0u;  // magnified (n <= 1), or n NaN: level 0 alone
  real s = 0.0;     // the weight of level + 1
  if (levels > 1u && n > 1.0) {
    level = levels - 1u;  // past every level, or n too large for an int exponent
    if (n < RL(1073741824.0)) {
      int e;
      real m = frexp(n, e);
      if (uint(e - 1) < levels - 1u) {
        level = uint(e - 1);
        s = 2.0 * m - 1.0;
      }
    }
  }
  // One lookup site for both levels: inlined twice, the bilinear lookup's registers stay
  // live across the whole shader (docs/performance.md, "Mip levels and ray cones").
  rvec3 c = rvec3(0.0);
  [[dont_unroll]] for (uint k = 0u; k < ((s > 0.0) ? 2u : 1u); k++) {
    rvec3 ck = level_color(first, t, level + k, uu, vv);
    c = (k == 0u) ? ck : lerp_color(c, ck, s);
  }
  return c;
}

// atan2(y, x) in [-pi, pi] from +, *, / alone, so that the shader and the reference compute
// the same bits where their arithmetic is IEEE (lavapipe; GLSL's atan is an approximation
// of the driver's own): the octant reduced to a = min/max in [0, 1], then Abramowitz &
// Stegun 4.4.49, atan a = a (1 + a2 a^2 + ... + a16 a^16), |error| <= 2e-8.
real atan2_poly(real y, real x) {
  real ax = abs(x);
  real ay = abs(y);
  real hi = select_max(ax, ay);
  if (hi == 0.0) return 0.0;
  precise real a = select_min(ax, ay) / hi;
  precise real s = a * a;
  precise real p = ((((((RL(0.0028662257) * s - RL(0.0161657367)) * s + RL(0.0429096138)) * s - RL(0.0752896400)) * s +
                      RL(0.1065626393)) * s - RL(0.1420889944)) * s + RL(0.1999355085)) * s - RL(0.3333314528);
  precise real r = a + a * (s * p);
  if (ay > ax) r = RL(1.5707963267948966) - r;
  if (x < 0.0) r = RL(3.141592653589793) - r;
  return (y < 0.0) ? -r : r;
}

// The surface's texture coordinates. A sphere's, from its unit normal n in its own frame:
// longitude u = 1/2 + atan2(n.x, n.z) / 2 pi, 0.5 facing +z and growing towards +x;
// latitude v = 1/2 + atan2(n.y, |n.xz|) / pi, 1 at the +y pole (docs/scene-format.md,
// "Textures"). A plane's were found with its hit (plane_uv).
void surface_uv(surface sf, out real u, out real v) {
  if (sf.uv_kind == RC_UV_SPHERE) {
    rvec3 n = sf.uv_at;
    precise real across = sqrt(n.x * n.x + n.z * n.z);
    precise real uu = RL(0.5) + atan2_poly(n.x, n.z) * RL(0.15915494309189535);
    precise real vv = RL(0.5) + atan2_poly(n.y, across) * RL(0.3183098861837907);
    u = uu;
    v = vv;
  } else if (sf.uv_kind == RC_UV_AXIAL) {
    precise real uu = RL(0.5) + atan2_poly(sf.uv_at.x, sf.uv_at.y) * RL(0.15915494309189535);
    u = uu;
    v = sf.uv_at.z;
  } else {
    u = sf.uv_at.x;
    v = sf.uv_at.y;
  }
}

// The surface's texture colour, 1 where its material has none or it has no (u, v).
rvec3 surface_texture(packed_material m, surface sf) {
  if (m.texture == RC_NO_TEXTURE || sf.uv_kind == RC_UV_NONE) return rvec3(1.0);
  real u;
  real v;
  surface_uv(sf, u, v);
  return texture_color(m.texture, u, v, sf.footprint * sf.uv_rate.x, sf.footprint * sf.uv_rate.y);
}

// What an unblocked light adds: Lambert diffuse plus the specular lobe, scaled by its
// irradiance (n_dot_l = dot(n, l) > 0); kd is the diffuse colour, textured.
rvec3 light_contribution(packed_material m, rvec3 kd, rvec3 n, rvec3 l, rvec3 v, real n_dot_l, rvec3 irradiance) {
  return irradiance * (n_dot_l * kd + specular_term(n, l, v, m.shininess) * rvec3(m.specular));
}

// Direct light at the surface seen along d: ambient, then each light whose shadow ray is
// unblocked (in a light pass, the pass's lights only: raycast.comp).
rvec3 shade_phong(surface sf, rvec3 d) {
  packed_material m = load_material(sf.material);
  rvec3 tex = rvec3(1.0);
  if (has_kind(RC_KIND_TEXTURES) && m.texture != RC_NO_TEXTURE) tex = surface_texture(m, sf);
  rvec3 kd = tex * rvec3(m.diffuse);
  rvec3 color = tex * rvec3(m.ambient) * rvec3(frame.ambient_light) + rvec3(m.emission);
  if (light_pass_begin() != 0u) color = rvec3(0.0);
  rvec3 v = -d;
  rvec3 origin = spawn_origin(sf);
  spawned_ray = true; // every shadow ray below leaves the surface
  for (uint i = light_pass_begin(); i < light_pass_end(); i++) {
    if (!budget_step()) break;
    rvec3 l;
    rvec3 irradiance;
    rvec3 to_light;
    real shadow_t_max;
    if (!light_at(load_light(i), sf.p, origin, l, irradiance, to_light, shadow_t_max)) continue;
    real n_dot_l = dot(sf.n, l);
#if RC_CERTIFY
    if (certify) cert_shadow(load_light(i), sf, origin, n_dot_l);
#endif
    if (n_dot_l <= 0.0) continue;
    if (scene_shadows()) shadow_rays++;
    if (scene_shadows() && occluded(t_min_start(origin, to_light), to_light, t_min_end(shadow_t_max), i)) {
      if (aov_recording && i < RC_AOV_SHADOW_LIGHTS) aov_record.shadow_bits += float(1u << i);
      note_decision(2u * i + 1u);
      continue;
    }
    color += light_contribution(m, kd, sf.n, l, v, n_dot_l, irradiance);
  }
  return color;
}
