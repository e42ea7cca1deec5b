/* image_io.h: image files through OpenImageIO, behind a C API (image_io.cpp is the
 * project's only C++). Pixels are linear float RGB, rows top to bottom. */
#ifndef RC_IMAGE_IO_H
#define RC_IMAGE_IO_H

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* How 8-bit formats store a linear value v: the curve applied to v * 2^exposure clamped
 * to [0, 1]. Float formats (EXR, HDR, TIFF) store v itself: exposure and curve are a
 * display's, not the render's. */
typedef enum {
  RC_CURVE_LINEAR, /* the clamped value as it is (classic ray casters) */
  RC_CURVE_SRGB,   /* the sRGB transfer curve (IEC 61966-2-1) */
  RC_CURVE_GAMMA,  /* a pure power, c^(1/gamma), as course frameworks encode (gamma 2.2) */
} rc_curve;
typedef struct rc_encoding {
  rc_curve curve;
  float gamma;    /* RC_CURVE_GAMMA's exponent's inverse; > 0 */
  float exposure; /* in stops: v is scaled by 2^exposure first */
} rc_encoding;

static inline rc_encoding rc_encoding_linear(void) {
  rc_encoding e = {RC_CURVE_LINEAR, 1.0f, 0.0f};
  return e;
}

/* A named string attribute of an image file (EXR header attributes): how the parts of a
 * render carry their region, scene hash and settings (region.h). */
typedef struct rc_image_meta {
  const char *name, *value;
} rc_image_meta;

/* Writes `path` in the format its extension names: float pixels for EXR, HDR, TIFF with
 * ".exr/.hdr/.tif" and 8 bits for PNG, JPEG, BMP, PPM..., rounded to the nearest level or,
 * with `truncate`, truncated (int)(255 c) as the CSE167 format specifies. The file is written to a temporary
 * name in the same directory and renamed into place, so an existing image is never left
 * half overwritten. Returns 0, or -1 with a message in err. */
int rc_image_write(const char *path, int width, int height, int channels, const float *pixels, rc_encoding enc,
                   bool truncate, char *err, size_t err_len);

/* A writer that takes the image in bands of rows, top to bottom, so that no whole frame
 * need ever be in memory (16384 x 16384 renders). The file is written to a temporary in
 * the folder of `path`: unnamed (O_TMPFILE) where the filesystem allows, else a short
 * hidden name. Every byte goes through a proxy that checks each write, whatever the
 * format plugin does with errors; close(commit = 1) flushes, fsyncs, names the file and
 * renames it into place, then fsyncs the folder, and fails (-1, with the reason) if any
 * write failed; close(commit = 0) discards it. names: NULL, or one name per channel
 * (float formats only). meta: meta_count attributes for the file's header (formats
 * without such headers drop them). */
typedef struct rc_image_writer rc_image_writer;
rc_image_writer *rc_image_writer_open(const char *path, int width, int height, int channels, const char *const *names,
                                      rc_encoding enc, bool truncate, const rc_image_meta *meta, int meta_count,
                                      char *err, size_t err_len);
int rc_image_writer_rows(rc_image_writer *w, int rows, const float *pixels, char *err, size_t err_len);
/* Rows already encoded, `channels` levels a pixel, by the table the writer's encoding
 * makes (levels8.h: the GPU encodes in the shader); an 8-bit format only. */
int rc_image_writer_levels(rc_image_writer *w, int rows, const unsigned char *levels, char *err, size_t err_len);
/* Everything written and fsynced, not yet named: after this succeeds for every file of a
 * run, their closes with commit = 1 only rename (one transaction over several files). */
int rc_image_writer_finish(rc_image_writer *w, char *err, size_t err_len);
int rc_image_writer_close(rc_image_writer *w, int commit, char *err, size_t err_len);
/* A writer of a whole file given in memory (the statistics JSON), through the same
 * temporary as an image: written and fsynced here, named by close(commit = 1), so that it
 * joins the image's transaction. */
rc_image_writer *rc_file_writer_open(const char *path, const void *bytes, size_t len, char *err, size_t err_len);
/* The temporary file's name while the writer is open, for a signal handler to unlink;
 * empty while the temporary has no name. */
const char *rc_image_writer_temp_path(const rc_image_writer *w);

/* Like rc_image_read, also returning up to max_names channel names (31 chars each). */
int rc_image_read_named(const char *path, int *width, int *height, int *channels, float **pixels, char (*names)[32],
                        int max_names, int *name_count, char *err, size_t err_len);

/* 1 if OpenImageIO can write a file of this name (by its extension), else 0; in the
 * vkraycast binary, -1 when its image module cannot be loaded (the reason on stderr). */
int rc_image_can_write(const char *path);
/* 1 if a file of this name stores 8-bit levels (PNG, JPEG, BMP, PPM...), 0 if floats or
 * none can be written; in the vkraycast binary, -1 when the module cannot be loaded. */
int rc_image_stores_levels(const char *path);

/* A reader that hands out rows on demand, so that `vkraycast merge` streams its parts
 * however large the frame. *float32: every channel is stored as 32-bit float (the
 * parts' pixels come back bit for bit). */
typedef struct rc_image_reader rc_image_reader;
rc_image_reader *rc_image_reader_open(const char *path, int *width, int *height, int *channels, bool *float32,
                                      char *err, size_t err_len);
/* The string attribute `name` into value (truncated to len): 1, or 0 when absent. */
int rc_image_reader_meta(const rc_image_reader *r, const char *name, char *value, size_t len);
/* The name of channel c into name (truncated to len): 1, or 0 when c is out of range. */
int rc_image_reader_channel(const rc_image_reader *r, int c, char *name, size_t len);
/* Rows [y0, y1), all channels, as float. */
int rc_image_reader_rows(rc_image_reader *r, int y0, int y1, float *pixels, char *err, size_t err_len);
void rc_image_reader_close(rc_image_reader *r);

/* Reads any image OpenImageIO reads, as float. *pixels is malloc'ed (free()). */
int rc_image_read(const char *path, int *width, int *height, int *channels, float **pixels, char *err,
                  size_t err_len);

#ifdef __cplusplus
}
#endif

#endif
