/* png_writer.h: the PNG writer linked into the vkraycast binary (png_write.c): a table of
 * image_module.h with its writer entries only. */
#ifndef RC_PNG_WRITER_H
#define RC_PNG_WRITER_H

#include "image/image_module.h"

/* How both PNG writers (this one and image_io.cpp's, through OpenImageIO) compress, so that
 * their files are the same bytes: libpng's default adaptive filtering at zlib level 6 took
 * 27.5 ms to encode the showcase; the Sub filter alone at level 5 writes files no larger
 * than 1 % above the default's (93.9 against 96.3 KB there; shadows and transforms
 * measured too) in 35-40 % of the time (docs/performance.md, "Writing the image"). */
#define RC_PNG_ZLIB_LEVEL 5
#define RC_PNG_FILTER_SUB 0x10 /* libpng's PNG_FILTER_SUB (png.h), which OpenImageIO passes through */

const rc_image_api *rc_png_writer_api(void);

#endif
