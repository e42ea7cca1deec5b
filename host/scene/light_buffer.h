/* light_buffer.h: light buffers (Haines & Greenberg 1986) and the eye buffer: the
 * lecture's "project volume onto the image", for shadow rays and for primary rays. Each
 * point light gets a cube of cells around it, and the image a grid of tiles; the objects
 * are projected onto them (from the light; through the camera), and each cell keeps the
 * BVH nodes that hold every object a ray through that cell can meet (rc_shared.h,
 * RC_LIGHT_BUFFER_*, RC_EYE_BUFFER_*). A ray in an empty cell traverses nothing, one in a
 * cell of a few objects tests just those, and one elsewhere enters the tree below its top
 * levels. Both renderers read the same buffers (rc_bvh.glsl, ref_bvh.c: shadow_nodes,
 * eye_nodes), and every decision stays the tree's: a cell is conservative, so a ray skips
 * only objects whose boxes it cannot enter (docs/numerics.md §9 gives the bound). */
#ifndef RC_LIGHT_BUFFER_H
#define RC_LIGHT_BUFFER_H

#include "scene/scene_pack.h"

/* The point lights given a buffer: the first this many (a light past them traverses the
 * tree from its root, as without buffers). */
#define RC_LIGHT_BUFFERS_MAX 8u

typedef struct rc_light_buffer_stats {
  double build_ms;
  uint32_t lights;                      /* point lights with a buffer */
  uint64_t cells, empty, lists, subtrees; /* their cells, and what each names */
  uint32_t eye_tile;                    /* the eye buffer's tiles, pixels a side; 0: none */
  uint64_t eye_cells, eye_empty, eye_lists, eye_subtrees; /* its tiles, and what each names */
  uint64_t bytes;                       /* added to the BVH's nodes and references */
} rc_light_buffer_stats;

/* Appends the buffers of the scene's first RC_LIGHT_BUFFERS_MAX point lights (lights_on,
 * with shadows) and the eye buffer (eye_on: the objects' boxes projected onto the image's
 * tiles, rc_shared.h) to the BVH's node and reference arrays and sets frame.light_buffers.
 * Nothing without the object tree. A prepared scene's borrowed arrays are copied first
 * (rc_packed_scene_free frees the copies). */
rc_status rc_light_buffers_build(rc_packed_scene *packed, bool lights_on, bool eye_on, rc_light_buffer_stats *stats);

#endif
