/* png_reader.h: the PNG readers linked into the vkraycast binary (png_read.c): a table of
 * image_module.h with its reader entries only. */
#ifndef RC_PNG_READER_H
#define RC_PNG_READER_H

#include "image/image_module.h"

/* Its read_named and reader_open return -1 and NULL, with no message, for a file they do
 * not take (not a regular file, not a PNG, alpha, a damaged stream...): OpenImageIO then
 * reads it or says why not. */
const rc_image_api *rc_png_reader_api(void);

#endif
