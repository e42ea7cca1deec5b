// image_module.cpp: the table vkraycast-image.so exports (image_module.h). The module is
// built with hidden visibility, so its calls to image_io.cpp bind inside it.
#include "image/image_module.h"

static const rc_image_api api = {
    RC_IMAGE_API_VERSION, rc_image_writer_open,       rc_image_writer_rows,
    rc_image_writer_finish, rc_image_writer_close, rc_file_writer_open,     rc_image_writer_temp_path,
    rc_image_read_named,  rc_image_can_write,   rc_image_reader_open,
    rc_image_reader_meta, rc_image_reader_channel, rc_image_reader_rows, rc_image_reader_close,
    rc_image_writer_levels, rc_image_stores_levels,
};

extern "C" __attribute__((visibility("default"))) const rc_image_api *rc_image_module_api(void) { return &api; }
