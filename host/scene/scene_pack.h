/* scene_pack.h: the scene model (f64, world space) packed into the gpu_* arrays that both
 * renderers read. Packing is where precision is spent: every position is made relative to
 * the eye in f64 before rounding to f32 ("floating origin", docs/numerics.md §5), and the
 * camera basis and window come from f64 trigonometry. */
#ifndef RC_SCENE_PACK_H
#define RC_SCENE_PACK_H

#include "scene/scene.h"

/* A composite's closed mesh operand: quadric `leaf` (RC_QUADRIC_MESH) stands for triangles
 * [first, first + count), which follow the standalone ones. Its tree (mesh_root, mesh_end)
 * comes from rc_bvh_build_operands (bvh.h). */
typedef struct rc_mesh_operand {
  uint32_t leaf, first, count;
} rc_mesh_operand;

typedef struct rc_packed_scene {
  packed_frame frame;
  packed_sphere *spheres;
  packed_triangle *triangles;
  uint32_t triangle_total;   /* the standalone ones (frame.triangle_count), then the mesh operands' */
  packed_material *materials;
  packed_light *lights;
  packed_bvh_node *bvh_nodes; /* NULL until rc_bvh_build (bvh.h): the object tree, then the mesh operands' */
  uint32_t *bvh_prims;     /* object (mesh operands: triangle) references of the leaves, padded to a multiple of 4 */
  uint32_t bvh_node_total, bvh_prim_total; /* of both kinds of tree */
  bool bvh;                /* the object tree was built (frame.bvh_node_count of its nodes) */
  packed_transform *transforms; /* of the transformed spheres (at least one element) */
  uint32_t transform_count;
  packed_vertex_normals *normals; /* of the smooth-shaded triangles (at least one element) */
  uint32_t normal_count;
  uint32_t one_sided_triangle_count; /* with RC_TRIANGLE_ONE_SIDED */
  packed_quadric *quadrics;   /* the standalone quadrics, then the composites' leaves */
  uint32_t quadric_total;  /* both kinds (frame.quadric_count counts the standalone ones) */
  packed_csg *csg;
  uint32_t *csg_program;   /* padded to a multiple of 4 */
  uint32_t csg_program_length;
  rc_mesh_operand *mesh_operands;
  uint32_t mesh_operand_count;
  uint32_t *texels;        /* the textures, 4 words a texel: each a packed_texture, then its texels */
  uint32_t texel_count;    /* at least one element */
  uint32_t texture_count;
  uint32_t uv_count;       /* triangles with texture coordinates: their records end the texel array, */
  uint32_t uv_first;       /* from this texel on */
  uint32_t patch_first;    /* then the patches' control points (RC_QUADRIC_PATCH) from this texel on */
  dvec3 origin; /* world position of the packed space's origin (the eye) */
  double scale; /* packed units per scene unit: a power of two, 1 unless rescaled (scene_pack.c) */
  bool borrowed; /* the arrays belong to a prepared file (prepared.h): rc_packed_scene_free leaves them */
  bool bvh_copied; /* borrowed, but bvh_nodes and bvh_prims are copies (light_buffer.c): freed */
  /* The arrays' own hashes (rc_packed_scene_array_hashes) where a prepared file recorded
   * them, else NULL: rc_packed_scene_hash then hashes only the frame. */
  const uint64_t *array_hashes;
} rc_packed_scene;

rc_status rc_scene_pack(const rc_scene *scene, rc_packed_scene *packed);
/* The frame alone (camera, settings, counts; no BVH), from the scene's settings, for arrays
 * already packed at packed->origin and packed->scale: what a prepared scene (prepared.h)
 * re-derives for the command line's overrides. rc_scene_pack calls it, so the two agree
 * bit for bit. It reads the scene's scalars, its materials (which mirror) and its
 * composites' steps. */
void rc_scene_pack_frame(const rc_scene *scene, rc_packed_scene *packed);
/* Scales every position and radius by 1 + d, |d| <= 2^-22, d a hash of the seed and the
 * value: the conditioning band's re-renders (render --perturb, compare --band). */
void rc_packed_scene_perturb(rc_packed_scene *packed, uint32_t seed);
void rc_packed_scene_free(rc_packed_scene *packed);
/* Sets frame.patch_count from the packed quadrics (rc_scene_pack_frame cannot: a
 * prepared scene's frame is re-derived without the scene's quadrics). */
void rc_packed_scene_count_patches(rc_packed_scene *packed);
/* A hash of everything the renderers read (the frame and every array, the eye's world
 * position; not the BVH, which only speeds them up): the parts of one render agree on it
 * (region.h, `vkraycast merge`). */
uint64_t rc_packed_scene_hash(const rc_packed_scene *packed);
/* The hash of each array that rc_packed_scene_hash chains (spheres .. textures). */
#define RC_PACKED_ARRAYS 10
void rc_packed_scene_array_hashes(const rc_packed_scene *packed, uint64_t hashes[RC_PACKED_ARRAYS]);

#endif
