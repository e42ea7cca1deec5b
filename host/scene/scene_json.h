/* scene_json.h: the parts of the JSON scene format that live in files of their own, for
 * scene_json.c (the root and the objects list), which calls them: quadrics and composites
 * (scene_quadric.c) and mesh files (scene_json_mesh.c). Calls go one way: scene_json.c ->
 * scene_quadric.c -> scene_json_mesh.c, all reading through scene_json_read.h. */
#ifndef RC_SCENE_JSON_H
#define RC_SCENE_JSON_H

#include "scene/scene_json_read.h"

/* scene_json_mesh.c. The triangles of the mesh file o.file (relative to the scene's
 * folder), through m, appended to the scene; o.material, else `material`, else (-1) the
 * file's own materials. */
rc_status js_load_mesh(jctx *c, const cJSON *o, rc_scene *s, const rc_affine *m, int material);
/* A closed mesh as a composite's operand: its triangles, through t, go to
 * s->csg_triangles, and *q becomes its leaf (RC_QUADRIC_MESH); *intervals is the most
 * [in, out] intervals a ray line can have in it (its max_crossings / 2). */
rc_status js_parse_mesh_operand(jctx *c, const cJSON *o, rc_scene *s, int material, const rc_affine *t,
                                rc_quadric_def *q, uint32_t *intervals);

/* scene_quadric.c: whether `type` names a quadric ("quadric", "ellipsoid", "cylinder",
 * "cone", "paraboloid", "hyperboloid", "box", "plane") or a composite ("csg"); and the
 * parser of such an object into the scene. */
bool js_is_quadric_type(const char *type);
rc_status js_parse_quadric_object(jctx *c, const cJSON *o, rc_scene *s);

#endif
