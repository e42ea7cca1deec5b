/* prepared_check.h: the consistency of a prepared scene's arrays (prepared.h): every index
 * a renderer follows (materials, transforms, vertex normals, composite programs and their
 * operands, mesh operands, BVH links and leaves) lies inside its array, and every tree
 * link moves forward, so that traversal ends. Internal to prepared.c. */
#ifndef RC_PREPARED_CHECK_H
#define RC_PREPARED_CHECK_H

#include "scene/scene_pack.h"

/* NULL, or what is inconsistent (written into why). `object_nodes`: the object tree's
 * node count (frame.bvh_node_count). The frame's counts must already be set. */
const char *rc_packed_arrays_problem(const rc_packed_scene *p, uint32_t object_nodes, char *why, size_t cap);

#endif
