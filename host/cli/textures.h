/* textures.h: the images of a loaded scene's textures, read through the image module
 * (OpenImageIO: any format it reads) into rc_texture_def.rgb, for packing. The scene
 * stage names the files; reading images is the command's (the stages: docs/design.md). */
#ifndef RC_TEXTURES_H
#define RC_TEXTURES_H

#include "scene/scene.h"

/* Each texture's image as linear RGB floats, as stored (an 8-bit image's level / 255;
 * gray is repeated, alpha dropped), each file once (rc_texture_def.image). Refused, naming the scene's line, the field and the
 * file (exit status 2): an image that cannot be read, one wider or taller than
 * RC_MAX_TEXTURE_SIDE, textures of more than RC_MAX_TEXELS texels in all, and a texel
 * that is negative, NaN or infinite. */
#define RC_MAX_TEXELS (1u << 26)
rc_status rc_scene_read_textures(rc_scene *scene);

#endif
