/* ref_intersect.h: CPU twins of shaders/rc_intersect.glsl, declared for both precisions. */
#ifndef RC_REF_INTERSECT_H
#define RC_REF_INTERSECT_H

#include "math/rcm_vec3.h"
#include "rc_base.h"

/* The scene the reference reads: the very arrays the GPU gets (scene_pack.h). */
typedef struct ref_scene {
  const gpu_frame *frame;
  const gpu_sphere *spheres;
  const gpu_triangle *triangles;
  const gpu_material *materials;
  const gpu_light *lights;
  const gpu_bvh_node *bvh_nodes;
  const uint32_t *bvh_prims;
  const gpu_transform *transforms;
  const gpu_vertex_normals *normals;
  bool use_bvh;
} ref_scene;

/* The shader's `spawned_ray` global: the ray being traced left a surface. Per thread. */
extern _Thread_local bool ref_spawned_ray;

#define REF_DECLARE_INTERSECT(S, R, V)                                                          \
  typedef struct ref_hit_##S { R t; uint32_t kind, index, object; V bary; R side; } ref_hit_##S; \
  typedef struct ref_shear_##S { int k[3]; V s; } ref_shear_##S;                                \
  R ref_gamma_bound_##S(R n);                                                                   \
  R ref_first_root_##S(R t_near, R t_exit, R t_max, R *side);                                   \
  R ref_intersect_sphere_geometric_##S(V o, V d, gpu_sphere s, R t_max, R *side);               \
  R ref_intersect_sphere_algebraic_##S(V o, V d, gpu_sphere s, R t_max, R *side);               \
  R ref_intersect_sphere_##S(const ref_scene *sc, V o, V d, gpu_sphere s, R t_max, R *side);    \
  V ref_transform_point_##S(const gpu_transform *m, V p);                                       \
  V ref_transform_vector_##S(const gpu_transform *m, V v);                                      \
  R ref_intersect_any_sphere_##S(const ref_scene *sc, V o, V d, gpu_sphere s, R t_max, R *side); \
  ref_shear_##S ref_ray_shear_for_##S(V d);                                                     \
  V ref_permute_##S(V a, const int k[3]);                                                       \
  R ref_intersect_triangle_##S(V o, const ref_shear_##S *sh, gpu_triangle tri, R t_max, V *bary); \
  R ref_intersect_triangle_moller_trumbore_##S(V o, V d, gpu_triangle tri, R t_max, V *bary);   \
  R ref_intersect_triangle_cramer_##S(V o, V d, gpu_triangle tri, R t_max, V *bary);            \
  R ref_intersect_object_##S(const ref_scene *sc, uint32_t object, V o, V d, const ref_shear_##S *sh, R t_max,  \
                             R *side, V *bary);                                                 \
  void ref_consider_hit_##S(const ref_scene *sc, uint32_t object, R t, R side, V bary, ref_hit_##S *h); \
  ref_hit_##S ref_no_hit_##S(void);                                                             \
  void ref_closest_hit_linear_##S(const ref_scene *sc, V o, V d, ref_hit_##S *h);               \
  bool ref_occluded_linear_##S(const ref_scene *sc, V o, V d, R t_max);                         \
  V ref_safe_inverse_##S(V d);                                                                  \
  R ref_intersect_box_##S(V lo, V hi, V o, V inv_d, R t_max);                                   \
  bool ref_test_leaf_##S(const ref_scene *sc, uint32_t first, uint32_t count, V o, V d, const ref_shear_##S *sh,       \
                          bool any, R t_max, ref_hit_##S *h);                                   \
  bool ref_traverse_bvh_##S(const ref_scene *sc, V o, V d, bool any, R t_max, ref_hit_##S *h);  \
  bool ref_closest_hit_##S(const ref_scene *sc, V o, V d, ref_hit_##S *h);                      \
  bool ref_occluded_##S(const ref_scene *sc, V o, V d, R t_max);

REF_DECLARE_INTERSECT(d, double, dvec3)
REF_DECLARE_INTERSECT(f, float, vec3)

#endif
