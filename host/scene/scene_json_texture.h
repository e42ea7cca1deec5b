/* scene_json_texture.h: a material's texture in a JSON scene (scene_json_texture.c), for
 * the materials (scene_json.c). */
#ifndef RC_SCENE_JSON_TEXTURE_H
#define RC_SCENE_JSON_TEXTURE_H

#include "scene/scene_json_read.h"

/* Members "texture" (the image file, relative to the scene's folder), "texture_filter",
 * "texture_wrap", "texture_scale" and "texture_offset" of material m: a texture appended
 * to s->textures and *slot = its index + 1; *slot = 0 when m names no texture (the
 * others are then refused: they would do nothing). The image is read later (cli). */
rc_status js_parse_texture(jctx *c, const cJSON *m, rc_scene *s, uint32_t *slot);
/* Member "uvs" of a triangle object: three [u, v], the texture coordinates at its vertices
 * (t->has_uv set); absent: none. */
rc_status js_get_triangle_uvs(jctx *c, const cJSON *o, rc_triangle_def *t);

#endif
