/* ref_intersect.h: CPU twins of shaders/rc_intersect.glsl, declared for both precisions. */
#ifndef RC_REF_INTERSECT_H
#define RC_REF_INTERSECT_H

#include "math/rcm_vec3.h"
#include "base/rc_base.h"

/* The scene the reference reads: the very arrays the GPU gets (scene_pack.h). */
typedef struct ref_scene {
  const packed_frame *frame;
  const packed_sphere *spheres;
  const packed_triangle *triangles;
  const packed_material *materials;
  const packed_light *lights;
  const packed_bvh_node *bvh_nodes;
  const uint32_t *bvh_prims;
  const packed_transform *transforms;
  const packed_vertex_normals *normals;
  const packed_quadric *quadrics;
  const packed_csg *csg;
  const uint32_t *csg_program;
  const float (*texels)[4]; /* the textures: each a packed_texture (2 texels), then RGBA texels */
  bool use_bvh;
} ref_scene;

/* The shader's `spawned_ray` global: the ray being traced left a surface. Per thread. */
extern _Thread_local bool ref_spawned_ray;
/* The shader's `crossing_blame` (rc_quadric.glsl): 1 + the composite whose mesh operand a
 * ray line crossed too often or an odd number of times. Per thread. */
extern _Thread_local uint32_t ref_crossing_blame;

#define REF_DECLARE_INTERSECT(S, R, V)                                                          \
  typedef struct ref_hit_##S { R t; uint32_t kind, index, object; V bary; R side; uint32_t part; R err, bary_err, off_err; } ref_hit_##S; \
  typedef struct ref_shear_##S { int k[3]; V s; } ref_shear_##S;                                \
  R ref_gamma_bound_##S(R n);                                                                   \
  R ref_first_root_##S(R t_near, R t_exit, R t_max, R *side);                                   \
  R ref_intersect_sphere_geometric_##S(V o, V d, packed_sphere s, R t_max, R *side);               \
  R ref_intersect_sphere_algebraic_##S(V o, V d, packed_sphere s, R t_max, R *side);               \
  R ref_intersect_sphere_##S(const ref_scene *sc, V o, V d, packed_sphere s, R t_max, R *side);    \
  V ref_transform_point_##S(const packed_transform *m, V p);                                       \
  V ref_transform_vector_##S(const packed_transform *m, V v);                                      \
  R ref_intersect_any_sphere_##S(const ref_scene *sc, V o, V d, packed_sphere s, R t_max, R *side); \
  ref_shear_##S ref_ray_shear_for_##S(V d);                                                     \
  V ref_permute_##S(V a, const int k[3]);                                                       \
  typedef struct ref_sheared_##S { V x, y, z, depth, e; } ref_sheared_##S;                      \
  ref_sheared_##S ref_shear_triangle_##S(V o, const ref_shear_##S *sh, packed_triangle tri);       \
  R ref_max3_abs_##S(V a);                                                                      \
  R ref_triangle_t_error_##S(const ref_sheared_##S *st, R det);                                 \
  R ref_enclosing_det_##S(V e);                                                                 \
  R ref_triangle_t_##S(const ref_sheared_##S *st, R det);                                       \
  bool ref_edge_owned_##S(R x0, R y0, R x1, R y1, R det);                                       \
  R ref_triangle_crossing_##S(V o, const ref_shear_##S *sh, packed_triangle tri);                  \
  R ref_intersect_triangle_##S(V o, const ref_shear_##S *sh, packed_triangle tri, R t_max, V *bary); \
  R ref_intersect_triangle_moller_trumbore_##S(V o, V d, packed_triangle tri, R t_max, V *bary);   \
  R ref_intersect_triangle_cramer_##S(V o, V d, packed_triangle tri, R t_max, V *bary);            \
  R ref_triangle_facing_##S(packed_triangle tri, V d);                                          \
  bool ref_triangle_faces_ray_##S(packed_triangle tri, V d);                                      \
  uint32_t ref_object_kind_##S(const ref_scene *sc, uint32_t object, uint32_t *index);           \
  uint32_t ref_surface_object_##S(const ref_scene *sc, uint32_t object);                        \
  R ref_intersect_quadric_object_##S(const ref_scene *sc, uint32_t index, V o, V d, R t_max, V *bary,    \
                                     uint32_t *part);                                           \
  R ref_intersect_triangle_object_##S(const ref_scene *sc, packed_triangle tri, V o, V d, const ref_shear_##S *sh, \
                                      R t_max, V *bary);                                        \
  R ref_intersect_other_object_##S(const ref_scene *sc, uint32_t kinds, uint32_t kind, uint32_t index, V o, V d, \
                                   R t_max, V *bary, uint32_t *part);                           \
  void ref_cert_other_object_tests_##S(const ref_scene *sc, uint32_t kinds, uint32_t kind, uint32_t index, V o, V d, \
                                       bool any, R t_max);                                                \
  R ref_test_object_##S(const ref_scene *sc, uint32_t kinds, uint32_t object, V o, V d, const ref_shear_##S *sh, \
                        bool any, R t_max, R *side, V *bary, uint32_t *part);                             \
  void ref_cert_triangle_object_##S(const ref_scene *sc, packed_triangle tri, V o, V d, const ref_shear_##S *sh, \
                                    R t_max);                                                   \
  R ref_intersect_object_##S(const ref_scene *sc, uint32_t kinds, uint32_t object, V o, V d, const ref_shear_##S *sh, \
                             R t_max,                                                           \
                             R *side, V *bary, uint32_t *part);                                 \
  void ref_consider_hit_##S(const ref_scene *sc, uint32_t object, R t, R side, V bary, uint32_t part, ref_hit_##S *h); \
  ref_hit_##S ref_no_hit_##S(void);                                                             \
  R ref_cert_limit_##S(const ref_scene *sc, R t, R e);                                          \
  void ref_cert_order_##S(const ref_scene *sc, R t, uint32_t object, const ref_hit_##S *h);       \
  void ref_cert_object_##S(const ref_scene *sc, uint32_t kinds, uint32_t object, V o, V d, bool any, R t_max); \
  void ref_cert_plane_object_##S(const ref_scene *sc, uint32_t object, const packed_quadric *q, V o, V d, R t_max); \
  void ref_cert_closest_##S(const ref_scene *sc, const ref_hit_##S *h);                           \
  void ref_cert_blocked_##S(bool blocked, bool ok);                                             \
  bool ref_cert_blocker_ends_##S(void);                                                         \
  bool ref_cert_test_begin_##S(const ref_scene *sc, uint32_t object);                            \
  void ref_cert_test_end_##S(bool ok);                                                          \
  /* ref_certify.c, the twin of rc_certify.glsl, and its per-thread state. */                    \
  extern _Thread_local bool ref_cert_ok_##S, ref_cert_any_##S, ref_cert_self_##S, ref_cert_hit_ok_##S, \
      ref_cert_blocked_later_##S, ref_cert_blocker_certain_##S;                                 \
  extern _Thread_local uint32_t ref_cert_spawn_object_##S, ref_cert_stage_##S;                  \
  extern _Thread_local R ref_cert_eo_##S, ref_cert_et_##S, ref_cert_ed_##S, ref_cert_t_err_##S, ref_cert_bary_err_##S, \
      ref_cert_off_err_##S, ref_cert_beyond_##S, ref_cert_t_max_err_##S, ref_cert_ep_##S, ref_cert_en_##S;            \
  R ref_cert_factor_##S(const ref_scene *sc);                                                   \
  void ref_cert_require_##S(const ref_scene *sc, R margin, R bound);                            \
  void ref_cert_fail_##S(void);                                                                 \
  void ref_cert_note_##S(uint32_t stage);                                                       \
  R ref_cert_turn_##S(R x);                                                                     \
  R ref_cert_turn_of_##S(R e, R len);                                                           \
  bool ref_cert_root_within_##S(const ref_scene *sc, R t, R e_down, R e_up, R t_max, bool ahead); \
  bool ref_cert_root_##S(const ref_scene *sc, R t, R e, R t_max, bool ahead);                   \
  bool ref_cert_shadow_ignores_##S(const ref_scene *sc, R lo, R hi, R t_max);                   \
  void ref_cert_maybe_##S(const ref_scene *sc, R lo, R hi, R t_max, bool taken);                \
  void ref_cert_sphere_grazing_##S(const ref_scene *sc, R disc, R b, R c, R e_disc, R e_b, R e_c, R t_max, R t_near, \
                                   R t_exit, bool roots, R scale, R rel);                       \
  R ref_cert_triangle_t_error_##S(const ref_sheared_##S *st, R t, R det, R e_det, R ee, R dz, R se); \
  void ref_cert_sphere_roots_##S(const ref_scene *sc, V o, V d, packed_sphere s, R t_max, R scale, R rel); \
  R ref_cert_norm_##S(const packed_transform *m);                                               \
  void ref_cert_sphere_##S(const ref_scene *sc, V o, V d, packed_sphere s, R t_max);            \
  V ref_cert_face_normal_##S(packed_triangle tri, V *e_n);                                       \
  R ref_cert_facing_error_##S(packed_triangle tri, V d);                                        \
  R ref_cert_triangle_plane_gap_##S(packed_triangle tri, V ng, V p);                            \
  V ref_cert_edge_bounds_##S(const ref_shear_##S *sh, V xm, V ym, V zr);                        \
  V ref_cert_edge_errors_##S(const ref_sheared_##S *st, const ref_shear_##S *sh, R *dz);         \
  bool ref_cert_edges_apart_##S(const ref_sheared_##S *st, V k);                                 \
  uint32_t ref_cert_near_edge_##S(V e, R sum, V k);                                             \
  bool ref_cert_edge_pair_##S(const ref_scene *sc, uint32_t a, uint32_t b);                     \
  uint32_t ref_cert_triangle_side_##S(const ref_scene *sc, packed_triangle tri, V d);           \
  void ref_cert_triangle_##S(const ref_scene *sc, V o, const ref_shear_##S *sh, packed_triangle tri, R t_max, \
                             bool side_unsure);                                                  \
  uint32_t ref_cert_crossing_##S(const ref_scene *sc, V o, const ref_shear_##S *sh, packed_triangle tri, R *t, R *e, \
                                 uint32_t *near);                                               \
  void ref_cert_plane_##S(const ref_scene *sc, const packed_quadric *q, V o, V d, R t_max);     \
  bool ref_cert_leaf_intervals_##S(const ref_scene *sc, uint32_t leaf, const packed_quadric *q, V o, V d, \
                                   uint32_t base, uint32_t *n);                                  \
  bool ref_cert_edge_crossing_##S(const ref_scene *sc, uint32_t base, uint32_t n, uint32_t note0, R t0, R e0, \
                                  uint32_t note1, R t1, R e1, uint32_t notes);                  \
  bool ref_cert_mesh_intervals_##S(const ref_scene *sc, uint32_t csg, const packed_quadric *q, V o, V d, bool any, R t_max, \
                                   uint32_t base, uint32_t *n);                                  \
  bool ref_cert_combine_##S(const ref_scene *sc, uint32_t op, uint32_t a, uint32_t na, uint32_t b, uint32_t nb, \
                            uint32_t *n);                                                        \
  void ref_cert_first_end_##S(const ref_scene *sc, uint32_t n, R t_max);                        \
  void ref_cert_csg_##S(const ref_scene *sc, uint32_t index, V o, V d, bool any, R t_max);       \
  V ref_cert_abs_apply_##S(const packed_quadric *q, V v);                                       \
  V ref_cert_local_error_##S(const packed_quadric *q, V mag, R e, R n);                         \
  bool ref_cert_slab_##S(const ref_scene *sc, R lo, R hi, R f, R v, R ef, R ev, R *tn, R *tx, R *e); \
  R ref_cert_span_end_##S(const ref_scene *sc, R s, R t0, R e0, R t1, R e1, R t2, R e2, R *e, bool *sure); \
  uint32_t ref_cert_slab_parallel_##S(const ref_scene *sc, R lo, R hi, R f, R v, R ef, R ev, R reach_t); \
  uint32_t ref_cert_box_##S(const ref_scene *sc, V lo, V hi, V f, V v, V ef, V ev, R *b_in, R *b_out, \
                            R *e_in, R *e_out, uint32_t *sure);                                  \
  R ref_cert_quadric_terms_##S(const packed_quadric *q, V f, V v, V ef, V ev, R *a, R *h, R *c, R *disc, R *e_a, \
                               R *e_h, R *e_c);                                                  \
  bool ref_cert_surface_root_##S(const ref_scene *sc, R t, R e, R b_in, R b_out, R e_in, R e_out, R t_max); \
  bool ref_cert_solid_end_##S(const ref_scene *sc, R t, bool on_box, R box, R e_box, R quad, R e_quad, \
                              bool face_sure, R t_max);                                          \
  void ref_cert_solid_##S(const ref_scene *sc, uint32_t kind, R t_lo, R t_hi, R e_r, R b_in, R b_out, R e_in, \
                          R e_out, uint32_t sure, R t_max);                                      \
  uint32_t ref_cert_quadric_box_##S(const ref_scene *sc, const packed_quadric *q, V o, V d, V *f, V *v, V *ef, V *ev, \
                                    R *b_in, R *b_out, R *e_in, R *e_out, uint32_t *sure);       \
  bool ref_cert_quadric_kind_##S(const ref_scene *sc, const packed_quadric *q, V f, V v, V ef, V ev, R b_in, R b_out, \
                                 R e_in, R e_out, R t_max, bool whole, uint32_t *kind, R *t_lo, R *t_hi, R *e_r); \
  void ref_cert_quadric_##S(const ref_scene *sc, const packed_quadric *q, V o, V d, R t_max);   \
  R ref_cert_quadric_normal_##S(const packed_quadric *q, V p, R ep);                            \
  void ref_closest_hit_linear_##S(const ref_scene *sc, V o, V d, ref_hit_##S *h);               \
  bool ref_occluded_linear_##S(const ref_scene *sc, V o, V d, R t_max);                         \
  V ref_safe_inverse_##S(V d);                                                                  \
  R ref_intersect_box_##S(V lo, V hi, V o, V inv_d, R t_max);                                   \
  uint32_t ref_loose_kinds_##S(const ref_scene *sc);                                            \
  uint32_t ref_tree_kinds_##S(const ref_scene *sc);                                             \
  bool ref_test_leaf_##S(const ref_scene *sc, uint32_t first, uint32_t count, V o, V d, const ref_shear_##S *sh,       \
                          bool any, R t_max, ref_hit_##S *h);                                   \
  bool ref_traverse_bvh_##S(const ref_scene *sc, V o, V d, bool any, R t_max, uint32_t first, uint32_t end, \
                            ref_hit_##S *h);                                                    \
  bool ref_test_planes_##S(const ref_scene *sc, V o, V d, bool any, R t_max, ref_hit_##S *h);   \
  bool ref_loose_hit_##S(const ref_scene *sc, uint32_t object, R t, R side, V bary, uint32_t part, bool any, \
                         ref_hit_##S *h);                                                      \
  bool ref_test_loose_quadrics_##S(const ref_scene *sc, V o, V d, bool any, R t_max, ref_hit_##S *h); \
  bool ref_test_loose_##S(const ref_scene *sc, V o, V d, bool any, R t_max, ref_hit_##S *h);    \
  void ref_eye_nodes_##S(const ref_scene *sc, uint32_t x, uint32_t y, uint32_t *first, uint32_t *end); \
  bool ref_closest_hit_##S(const ref_scene *sc, V o, V d, uint32_t first, uint32_t end, ref_hit_##S *h); \
  void ref_shadow_nodes_##S(const ref_scene *sc, uint32_t light, V d, R t_max, uint32_t *first, uint32_t *end); \
  bool ref_occluded_##S(const ref_scene *sc, V o, V d, R t_max, uint32_t light);

/* ref_quadric.c, the twin of rc_quadric.glsl. */
#define REF_DECLARE_QUADRIC(S, R, V)                                                            \
  extern _Thread_local R ref_csg_t_##S[(RC_CSG_STACK + 1u) * RC_CSG_SLOT];                       \
  extern _Thread_local uint32_t ref_csg_code_of_##S[(RC_CSG_STACK + 1u) * RC_CSG_SLOT];           \
  extern _Thread_local R ref_csg_e_##S[(RC_CSG_STACK + 1u) * RC_CSG_SLOT];                       \
  uint32_t ref_csg_code_##S(uint32_t leaf, uint32_t face, bool leaf_exit, bool flip);           \
  V ref_quadric_local_##S(const packed_quadric *q, V v);                                           \
  V ref_quadric_apply_##S(const packed_quadric *q, V v);                                           \
  typedef struct ref_quadric_terms_##S { V mv, mf; R m, ld, lf, a, h, c; } ref_quadric_terms_##S; \
  ref_quadric_terms_##S ref_quadric_coefficients_##S(const packed_quadric *q, V f, V v);           \
  V ref_quadric_minors_##S(V f, V v);                                                             \
  R ref_quadric_discriminant_##S(const packed_quadric *q, V f, V v, const ref_quadric_terms_##S *k); \
  uint32_t ref_quadric_roots_##S(const packed_quadric *q, V f, V v, R *t_lo, R *t_hi);             \
  void ref_box_slab_##S(R lo, R hi, R o, R d, uint32_t k, R *t_in, R *t_out, uint32_t *axis_in, uint32_t *axis_out); \
  void ref_box_span_##S(V lo, V hi, V o, V d, R *t_in, R *t_out, uint32_t *axis_in, uint32_t *axis_out); \
  typedef struct ref_solid_line_##S { R b_in, b_out; uint32_t a_in, a_out; R lo0, hi0, t_hi; uint32_t pieces; } ref_solid_line_##S; \
  ref_solid_line_##S ref_solid_line_of_##S(const packed_quadric *q, V o, V d);                     \
  void ref_solid_piece_##S(const ref_solid_line_##S *l, uint32_t k, R *s, R *e, bool *box_starts, bool *box_ends); \
  uint32_t ref_solid_intervals_##S(uint32_t leaf, const packed_quadric *q, V o, V d, bool flip, uint32_t base); \
  R ref_intersect_quadric_surface_##S(const packed_quadric *q, V o, V d, R t_max);                 \
  R ref_first_interval_end_##S(uint32_t base, uint32_t n, R t_max, uint32_t *code);             \
  R ref_solid_first_end_##S(uint32_t leaf, const packed_quadric *q, V o, V d, R t_max, uint32_t *code); \
  R ref_intersect_plane_##S(const packed_quadric *q, V o, V d, R t_max);                              \
  R ref_intersect_quadric_##S(const ref_scene *sc, uint32_t index, V o, V d, R t_max, uint32_t *code); \
  bool ref_csg_inside_##S(uint32_t op, bool in_a, bool in_b);                                  \
  uint32_t ref_combine_intervals_##S(uint32_t op, uint32_t a, uint32_t na, uint32_t b, uint32_t nb); \
  bool ref_line_meets_box_##S(V lo, V hi, V o, V d);                                            \
  void ref_blame_mesh_##S(const ref_scene *sc, uint32_t csg);                                   \
  void ref_sort_in_crossing_##S(uint32_t base, uint32_t n, R t, uint32_t tri, bool bounded, R e); \
  uint32_t ref_mesh_code_##S(uint32_t tri, uint32_t i, bool flip);                             \
  uint32_t ref_mesh_intervals_##S(const ref_scene *sc, uint32_t csg, const packed_quadric *q, V o, V d, bool flip, \
                                  uint32_t base);                                               \
  R ref_intersect_csg_##S(const ref_scene *sc, uint32_t index, V o, V d, R t_max, uint32_t *code); \
  V ref_quadric_normal_##S(const packed_quadric *q, uint32_t code, V p, V d);                      \
  V ref_mesh_normal_##S(packed_triangle tri, uint32_t code, V d);

/* ref_patch.c, the twin of rc_patch.glsl, and ref_certify_patch.c, of rc_certify_patch.glsl: the
 * functions the rest of the reference calls.
 * ref_patch_stalls, ref_patch_stall_piece: the shader's patch_stalls, patch_stall_piece. */
extern _Thread_local uint32_t ref_patch_stalls, ref_patch_stall_piece;
#define REF_DECLARE_PATCH(S, R, V)                                                              \
  R ref_intersect_patch_##S(const ref_scene *sc, uint32_t index, const packed_quadric *q, V o, V d, R t_max, V *uv); \
  V ref_patch_surface_##S(const ref_scene *sc, const packed_quadric *q, V uv, V *p, V *p_error);           \
  void ref_cert_patch_##S(const ref_scene *sc, const packed_quadric *q, V o, V d, R t_max);                                 \
  void ref_cert_patch_surface_##S(const ref_scene *sc, const packed_quadric *q, V d, V uv, R bary_err, \
                                  R off_err, R t, V ng, V p_error);
REF_DECLARE_PATCH(d, double, dvec3)
REF_DECLARE_PATCH(f, float, vec3)

REF_DECLARE_QUADRIC(d, double, dvec3)
REF_DECLARE_QUADRIC(f, float, vec3)

REF_DECLARE_INTERSECT(d, double, dvec3)
REF_DECLARE_INTERSECT(f, float, vec3)

#endif
