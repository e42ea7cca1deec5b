/* scene_patch.h: bicubic Bezier patches in a JSON scene (scene_patch.c): "bezier_patch"
 * with its 16 control points, and "bezier_patches" reading a patch file (the classic
 * format of Newell's teapot: a count, then per patch its two degrees and control points).
 * Each patch is cut into pieces flat enough for Newton's method to start from their
 * centres; the pieces are quadrics of kind RC_QUADRIC_PATCH (rc_shared.h). */
#ifndef RC_SCENE_PATCH_H
#define RC_SCENE_PATCH_H

#include "scene/scene_json_read.h"

/* Limits: patches in one file, and pieces in one scene. */
#define RC_MAX_PATCHES 65536u
#define RC_MAX_PATCH_PIECES (1u << 20)
/* A piece is cut in four while its control net strays from the bilinear surface through
 * its corners by more than this fraction of its box's diagonal, at most
 * RC_PATCH_MAX_DEPTH times (256 pieces). */
#define RC_PATCH_FLATNESS 0.05
#define RC_PATCH_MAX_DEPTH 4

bool js_is_patch_type(const char *type);
rc_status js_parse_patch_object(jctx *c, const cJSON *o, rc_scene *s);
/* Adds a patch (control points p[4 r + c], row r along v, column c along u, in world
 * space) and its pieces. `where` prefixes errors ("FILE:LINE:COL: error: FIELD"). */
rc_status rc_scene_add_patch(rc_scene *s, const dvec3 p[16], uint32_t material, const char *where);
/* A patch file's patches, control points through `m`. Errors name the file and line. */
rc_status rc_patch_file_load(const char *path, const rc_affine *m, uint32_t material, rc_scene *s, const char *where);

#endif
