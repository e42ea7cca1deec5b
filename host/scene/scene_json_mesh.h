/* scene_json_mesh.h: mesh files in a JSON scene (scene_json_mesh.c), for the objects list
 * (scene_json.c) and the composites' operands (scene_quadric.c). */
#ifndef RC_SCENE_JSON_MESH_H
#define RC_SCENE_JSON_MESH_H

#include "scene/scene_json_read.h"

/* The triangles of the mesh file o.file (relative to the scene's folder), through m,
 * appended to the scene; o.material, else `material`, else (-1) the file's own materials. */
rc_status js_load_mesh(jctx *c, const cJSON *o, rc_scene *s, const rc_affine *m, int material);
/* A closed mesh as a composite's operand: its triangles, through t, go to
 * s->csg_triangles, and *q becomes its leaf (RC_QUADRIC_MESH); *intervals is the most
 * [in, out] intervals a ray line can have in it (its max_crossings / 2). */
rc_status js_parse_mesh_operand(jctx *c, const cJSON *o, rc_scene *s, int material, const rc_affine *t,
                                rc_quadric_def *q, uint32_t *intervals);

#endif
