/* bvh.h: the bounding volume hierarchy over all objects (every primitive kind together),
 * built on the host in the packed (camera-relative f32) space and flattened in
 * depth-first order, near child first as seen from the eye, into packed_bvh_node[] with skip
 * links plus the leaves' object references, which both renderers traverse without a
 * stack (rc_bvh.glsl, ref/ref_bvh.c).
 *
 * Build: top-down binned SAH (Wald, "On fast Construction of SAH-based Bounding Volume
 * Hierarchies", RT 2007): 16 to 1024 centroid bins per axis (a quarter of the node's
 * objects, bvh.c says why), all three axes tried, cost = 1 per node visit + 1 per object
 * test weighted by the children's surface areas; a node
 * becomes a leaf when splitting costs more than testing its objects (at most 8), and
 * below RC_BVH_MAX_DEPTH - log2(n) levels the split falls back to halving by count so
 * that the tree depth (and the build's recursion) stays bounded. */
#ifndef RC_BVH_H
#define RC_BVH_H

#include "scene/scene_pack.h"

typedef struct rc_bvh_stats {
  double build_ms;
  uint32_t nodes, leaves, depth, max_leaf;
  uint32_t repeats; /* objects left out: bit-for-bit repeats of an earlier one's geometry */
  uint32_t loose;   /* objects left out: of the kinds frame.loose_kinds names */
} rc_bvh_stats;

/* The kinds whose objects the object tree leaves out, for every ray to test in a loop of
 * their own (frame.loose_kinds): RC_KIND_QUADRICS, the bounded quadrics, where composites
 * are the main kind and the quadrics at most RC_LOOSE_MAX and fewer than half of them;
 * else 0. bvh.c says why. */
uint32_t rc_loose_kinds(const packed_frame *f);
/* The number of objects of the kinds f->loose_kinds names. */
uint32_t rc_loose_objects(const packed_frame *f);

/* Builds into packed->bvh_nodes / bvh_prims: the object tree when `objects` (setting
 * frame.bvh_node_count; without it both renderers test every object), then always a tree
 * for each of the composites' mesh operands (their mesh_root, mesh_end), which adds their
 * worst-case steps to frame.csg_max_steps. */
rc_status rc_bvh_build(rc_packed_scene *packed, bool objects, rc_bvh_stats *stats);

/* The box the object tree bounds object `object` by (a plane's is empty): f32, rounded
 * outwards so that it holds every point the renderers can find on the object. */
void rc_bvh_object_box(const rc_packed_scene *packed, uint32_t object, float lo[3], float hi[3]);

#endif
