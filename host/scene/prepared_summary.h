/* prepared_summary.h: the summary section of a prepared scene (prepared.h): the scene's
 * settings, counts, materials, composites' step bounds, output rules, inputs and origins,
 * and the packed scene's scalars, as a sequence of fixed-width values (in the writer's
 * byte order) and length-prefixed, NUL-terminated strings. Internal to prepared.c. */
#ifndef RC_PREPARED_SUMMARY_H
#define RC_PREPARED_SUMMARY_H

#include "scene/bvh.h"
#include "scene/scene.h"
#include "scene/scene_pack.h"

/* A growing buffer; `failed` once memory ran out (every later put is dropped). */
typedef struct rc_blob {
  unsigned char *data;
  size_t len, cap;
  bool failed;
} rc_blob;
void rc_blob_put(rc_blob *b, const void *bytes, size_t len);
/* Zero bytes up to a multiple of `align`. */
void rc_blob_align(rc_blob *b, size_t align);

/* What the tree added that the frame does not re-derive: the object tree's node count
 * (frame.bvh_node_count) and the mesh operands' steps (added to frame.csg_max_steps). */
typedef struct rc_prepared_tree {
  rc_bvh_stats stats;
  uint32_t object_nodes;
  uint32_t loose_kinds; /* frame.loose_kinds: the kinds the object tree leaves out */
  uint64_t operand_steps;
} rc_prepared_tree;

void rc_summary_encode(rc_blob *b, const rc_scene *s, const rc_packed_scene *p, const rc_prepared_tree *tree);
/* Fills *s (owned arrays: materials, composites without programs, inputs, origins whose
 * names point into `bytes`) and p's scalars (no arrays). NULL, or the reason the summary
 * is malformed (a static string; *s is then freed). */
const char *rc_summary_decode(const unsigned char *bytes, size_t len, rc_scene *s, rc_packed_scene *p,
                              rc_prepared_tree *tree);

#endif
