/* png_writer.h: the PNG writer linked into the vkraycast binary (png_write.c): a table of
 * image_module.h with its writer entries only. */
#ifndef RC_PNG_WRITER_H
#define RC_PNG_WRITER_H

#include "image/image_module.h"

const rc_image_api *rc_png_writer_api(void);

#endif
