/* ref_shader.h: the CPU twins of the shader's camera, random, shading and trace includes,
 * for both precisions (ref_real.h). The shader's globals become a ref_scene argument (the
 * uniform `frame` and the scene arrays) and thread-local ray counters. */
#ifndef RC_REF_SHADER_H
#define RC_REF_SHADER_H

#include "ref/ref_intersect.h"

typedef struct { float x, y; } ref_vec2;

/* rc_random.glsl: f32 and integer arithmetic only, the same in both precisions. */
uint32_t ref_hash_pcg(uint32_t v);
float ref_hash_to_unit(uint32_t h);
ref_vec2 ref_sample_offset(const ref_scene *sc, uint32_t px, uint32_t py, uint32_t s);

/* The shader's per-invocation globals; here per thread (ref_render.c sums and copies). */
extern _Thread_local uint64_t ref_shadow_rays, ref_reflection_rays;
/* Loop steps taken (BVH nodes visited, objects tested): the shard cost estimate. */
extern _Thread_local uint64_t ref_work;
extern _Thread_local bool ref_aov_enabled, ref_aov_recording;
extern _Thread_local packed_aov ref_aov_record;
/* raycast.comp's decision digest (packed_aov.decisions): the sample and bounce being
 * traced, the digest of the sample's decisions so far, and what adds one to it. */
extern _Thread_local uint32_t ref_decision_key, ref_sample_decisions;
uint32_t ref_decision_hash(uint32_t x);
void ref_note_decision(uint32_t value);

#define REF_DECLARE_SHADER(S, R, V)                                                             \
  typedef struct ref_surface_##S { V p, n, ng, p_error; uint32_t material; uint32_t uv_kind; V uv_at, uv_rate; R footprint, curvature; } ref_surface_##S; \
  void ref_camera_ray_##S(const ref_scene *sc, ref_vec2 raster, V *origin, V *dir);            \
  V ref_plane_uv_##S(const packed_quadric *q, V p);                                             \
  uint32_t ref_quadric_uv_##S(const packed_quadric *q, uint32_t code, V p, V *uv_at, V *uv_rate); \
  V ref_sphere_uv_rate_##S(V n, R r);                                                           \
  V ref_triangle_uv_rate_##S(packed_vertex_uvs t, packed_triangle tri);                         \
  V ref_quadric_refine_##S(const packed_quadric *q, V p, V *p_error);                              \
  V ref_triangle_uv_##S(packed_vertex_uvs t, V b);                                              \
  ref_surface_##S ref_surface_at_##S(const ref_scene *sc, V o, V d, const ref_hit_##S *h);      \
  R ref_offset_coordinate_##S(R p, R n);                                                        \
  V ref_offset_ray_origin_##S(V p, V n);                                                        \
  R ref_next_float_##S(R v, bool up);                                                           \
  R ref_round_away_##S(R c, R n);                                                               \
  V ref_offset_error_bound_##S(V p, V n, V p_error);                                            \
  V ref_spawn_origin_##S(const ref_scene *sc, const ref_surface_##S *sf);                       \
  V ref_t_min_start_##S(const ref_scene *sc, V origin, V d);                                     \
  R ref_t_min_end_##S(const ref_scene *sc, R t_max);                                            \
  R ref_specular_term_##S(const ref_scene *sc, V n, V l, V v, float shininess);                 \
  bool ref_light_at_##S(packed_light light, V p, V origin, V *l, V *irradiance, V *to_light, R *shadow_t_max); \
  V ref_texel_at_##S(const ref_scene *sc, uint32_t texels, uint32_t flags, int w, int hh, int x, int y); \
  V ref_lerp_color_##S(V a, V b, R s);                                                          \
  V ref_level_color_##S(const ref_scene *sc, uint32_t first, packed_texture t, uint32_t level, R uu, R vv); \
  V ref_texture_color_##S(const ref_scene *sc, uint32_t first, R u, R v, R fu, R fv);           \
  R ref_atan2_poly_##S(R y, R x);                                                               \
  void ref_surface_uv_##S(const ref_surface_##S *sf, R *u, R *v);                               \
  V ref_surface_texture_##S(const ref_scene *sc, packed_material m, const ref_surface_##S *sf); \
  V ref_light_contribution_##S(const ref_scene *sc, packed_material m, V kd, V n, V l, V v, R n_dot_l, V irradiance); \
  V ref_shade_phong_##S(const ref_scene *sc, const ref_surface_##S *sf, V d);                   \
  void ref_aov_begin_##S(const ref_scene *sc, const ref_hit_##S *h);                            \
  V ref_trace_sample_##S(const ref_scene *sc, uint32_t px, uint32_t py, uint32_t s);              \
  void ref_cert_camera_##S(const ref_scene *sc, ref_vec2 raster);                               \
  bool ref_cert_point_on_ray_##S(const ref_scene *sc, const ref_hit_##S *h, uint32_t transform); \
  void ref_cert_surface_##S(const ref_scene *sc, V d, const ref_hit_##S *h, const ref_surface_##S *sf); \
  R ref_cert_offset_##S(const ref_scene *sc, const ref_surface_##S *sf, V origin);              \
  R ref_cert_origin_##S(const ref_scene *sc, const ref_surface_##S *sf, V origin);              \
  R ref_cert_t_min_start_##S(const ref_scene *sc, R eo, R ed, V origin);                        \
  void ref_cert_shadow_##S(const ref_scene *sc, packed_light light, const ref_surface_##S *sf, V origin, R n_dot_l); \
  void ref_cert_reflect_##S(const ref_scene *sc, const ref_surface_##S *sf, V origin, R ed_in, R across); \
  R ref_cert_mirror_across_##S(const ref_scene *sc, const ref_hit_##S *h, const ref_surface_##S *sf, V o, V d, R eo, R ed);

REF_DECLARE_SHADER(d, double, dvec3)
REF_DECLARE_SHADER(f, float, vec3)

/* In a file compiled for one precision (ref_real.h), the plain names. */
#ifdef REF_F64
#if REF_F64
typedef ref_hit_d ref_hit;
typedef ref_shear_d ref_shear;
typedef ref_sheared_d ref_sheared;
typedef ref_quadric_terms_d ref_quadric_terms;
typedef ref_solid_line_d ref_solid_line;
typedef ref_surface_d ref_surface;
#else
typedef ref_hit_f ref_hit;
typedef ref_shear_f ref_shear;
typedef ref_sheared_f ref_sheared;
typedef ref_quadric_terms_f ref_quadric_terms;
typedef ref_solid_line_f ref_solid_line;
typedef ref_surface_f ref_surface;
#endif
#endif

#endif
