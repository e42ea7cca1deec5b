/* scene_quadric.h: quadrics and composites in a JSON scene (scene_quadric.c), for the
 * objects list (scene_json.c). */
#ifndef RC_SCENE_QUADRIC_H
#define RC_SCENE_QUADRIC_H

#include "scene/scene_json_read.h"

/* Whether `type` names a quadric ("quadric", "ellipsoid", "cylinder", "cone",
 * "paraboloid", "hyperboloid", "box", "plane") or a composite ("csg"); and the parser of
 * such an object into the scene. */
bool js_is_quadric_type(const char *type);
rc_status js_parse_quadric_object(jctx *c, const cJSON *o, rc_scene *s);

#endif
