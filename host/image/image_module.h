/* image_module.h: the image module's table. OpenImageIO brings about 260 shared libraries
 * with it (its format plugins' codecs: OpenEXR, libraw, FFmpeg, GDAL, DCMTK, OpenVDB, ...),
 * and loading them costs ~0.5 s of CPU before main; `vkraycast` therefore loads image_io.cpp
 * as a module (vkraycast-image.so, beside the binary) the first time it reads or writes an
 * image that neither vkraycast-exr.so (OpenEXR) nor the binary's PNG writer (png_write.c)
 * handles (image_load.c), so that --help, --version, `devices`, every refusal of bad input
 * and renders to .exr and .png start in milliseconds. Tests and tools link image_io.cpp
 * directly (rc_image). The table serves all three. */
#ifndef RC_IMAGE_MODULE_H
#define RC_IMAGE_MODULE_H

#include "image/image_io.h"

#include <stdint.h>

#define RC_IMAGE_API_VERSION 7u
#define RC_IMAGE_MODULE_SYMBOL "rc_image_module_api"
/* vkraycast-exr.so (exr_read.cpp, exr_write.cpp): the same table for .exr files, and the
 * plain file writer. */
#define RC_EXR_MODULE_SYMBOL "rc_exr_module_api"

typedef struct rc_image_api {
  uint32_t version; /* RC_IMAGE_API_VERSION: a module from another build is refused */
  rc_image_writer *(*writer_open)(const char *path, int width, int height, int channels, const char *const *names,
                                  rc_encoding enc, bool truncate, const rc_image_meta *meta, int meta_count, char *err,
                                  size_t err_len);
  int (*writer_rows)(rc_image_writer *w, int rows, const float *pixels, char *err, size_t err_len);
  int (*writer_finish)(rc_image_writer *w, char *err, size_t err_len);
  int (*writer_close)(rc_image_writer *w, int commit, char *err, size_t err_len);
  rc_image_writer *(*file_writer_open)(const char *path, const void *bytes, size_t len, char *err, size_t err_len);
  const char *(*writer_temp_path)(const rc_image_writer *w);
  int (*read_named)(const char *path, int *width, int *height, int *channels, float **pixels, char (*names)[32],
                    int max_names, int *name_count, char *err, size_t err_len);
  int (*can_write)(const char *path);
  rc_image_reader *(*reader_open)(const char *path, int *width, int *height, int *channels, bool *float32, char *err,
                                  size_t err_len);
  int (*reader_meta)(const rc_image_reader *r, const char *name, char *value, size_t len);
  int (*reader_channel)(const rc_image_reader *r, int c, char *name, size_t len);
  int (*reader_rows)(rc_image_reader *r, int y0, int y1, float *pixels, char *err, size_t err_len);
  void (*reader_close)(rc_image_reader *r);
  int (*writer_levels)(rc_image_writer *w, int rows, const unsigned char *levels, char *err, size_t err_len);
  int (*stores_levels)(const char *path);
} rc_image_api;

#ifdef __cplusplus
extern "C" {
#endif
/* The module's one exported symbol. */
const rc_image_api *rc_image_module_api(void);
#ifdef __cplusplus
}
#endif

#endif
