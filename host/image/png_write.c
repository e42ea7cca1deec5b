/* png_write.c: the writer of image_io.h for 8-bit RGB PNGs, through libpng alone, linked
 * into the vkraycast binary (libpng and zlib load in about a millisecond; OpenImageIO's 260
 * libraries cost a render about 0.2 s of CPU and wall time: docs/performance.md, "Process
 * start-up", finding 15). It writes the file OpenImageIO 2.4's PNG writer made of the same
 * call, byte for byte (ctest png_writer): the same chunks in the same order (gAMA, and sRGB
 * and cHRM for sRGB, as its colour space attribute asks; oFFs at 0, 0; tEXt for
 * oiio:ColorSpace, Software and the caller's attributes), the same levels (levels8.h), and
 * the same deflate stream (zlib level 5 with libpng's Sub filter, png_writer.h says why).
 * image_load.c sends it what OpenImageIO's writer would write as 3 channels of 8 bits;
 * anything else (alpha, named channels) stays OpenImageIO's. */
#include "image/image_module.h"
#include "image/levels8.h"
#include "image/png_writer.h"
#include "image/staged_file.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <zlib.h>

_Static_assert(RC_PNG_FILTER_SUB == PNG_FILTER_SUB, "png_writer.h names libpng's Sub filter");

typedef struct png_writer {
  rc_staged staged;
  png_structp png;
  png_infop info;
  int width, height, next_row;
  int error;     /* errno of the first failed write */
  char why[256]; /* libpng's message, where it gave up */
  rc_levels levels;
  unsigned char *row;
} png_writer;

static void set_error(char *err, size_t len, const char *what) {
  if (err && len) snprintf(err, len, "%s", what);
}

static void on_write(png_structp png, png_bytep data, size_t n) {
  png_writer *w = png_get_io_ptr(png);
  if (n && fwrite(data, 1, n, w->staged.file) != n && !w->error) w->error = errno ? errno : EIO;
}

static void on_flush(png_structp png) { (void)png; }

static void on_error(png_structp png, png_const_charp msg) {
  png_writer *w = png_get_error_ptr(png);
  snprintf(w->why, sizeof w->why, "libpng: %s", msg);
  png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg) { (void)png, (void)msg; }

/* Why the file failed: a failed write's errno first, else libpng's message. */
static void failure(const png_writer *w, char *err, size_t len) {
  if (w->error) {
    if (err && len) snprintf(err, len, "write failed: %s", strerror(w->error));
  } else {
    set_error(err, len, w->why[0] ? w->why : "the PNG writer failed");
  }
}

static void discard(png_writer *w) {
  if (w->png) png_destroy_write_struct(&w->png, &w->info);
  rc_staged_discard(&w->staged);
  free(w->row);
  free(w);
}

/* The colour space as OpenImageIO names and records it: its attribute's text, and gAMA
 * (with sRGB and cHRM for sRGB) from the same text, "Gamma" and %g of the exponent read
 * back as a float, as OpenImageIO reads it. */
static void colour_space(png_structp png, png_infop info, rc_encoding enc, char *name, size_t len) {
  if (enc.curve == RC_CURVE_SRGB) {
    snprintf(name, len, "sRGB");
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
  } else if (enc.curve == RC_CURVE_GAMMA) {
    snprintf(name, len, "Gamma%g", (double)enc.gamma);
    float g = strtof(name + 5, NULL);
    png_set_gAMA(png, info, 1.0f / g);
  } else {
    snprintf(name, len, "Linear");
    png_set_gAMA(png, info, 1.0);
  }
}

static rc_image_writer *writer_open(const char *path, int width, int height, int channels, const char *const *names,
                                    rc_encoding enc, bool truncate, const rc_image_meta *meta, int meta_count,
                                    char *err, size_t err_len) {
  if (channels != 3 || names) {
    set_error(err, err_len, "the PNG writer takes 3 unnamed channels");
    return NULL;
  }
  png_writer *w = calloc(1, sizeof *w);
  png_text *text = calloc((size_t)meta_count + 2, sizeof *text);
  if (w) w->row = malloc((size_t)width * 3);
  if (!w || !text || !w->row) {
    free(text);
    if (w) free(w->row);
    free(w);
    set_error(err, err_len, "out of memory");
    return NULL;
  }
  w->width = width, w->height = height;
  rc_levels_make(enc, truncate, &w->levels);
  if (rc_staged_open(&w->staged, path, err, err_len) != 0) {
    free(text), free(w->row), free(w);
    return NULL;
  }
  w->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, w, on_error, on_warning);
  if (w->png) w->info = png_create_info_struct(w->png);
  if (!w->png || !w->info) {
    free(text);
    discard(w);
    set_error(err, err_len, "out of memory");
    return NULL;
  }
  char space[32];
  if (setjmp(png_jmpbuf(w->png))) {
    free(text);
    failure(w, err, err_len);
    discard(w);
    return NULL;
  }
  png_set_write_fn(w->png, w, on_write, on_flush);
  png_set_compression_level(w->png, RC_PNG_ZLIB_LEVEL);
  png_set_compression_strategy(w->png, Z_DEFAULT_STRATEGY);
  png_set_filter(w->png, PNG_FILTER_TYPE_BASE, RC_PNG_FILTER_SUB);
  png_set_IHDR(w->png, w->info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  colour_space(w->png, w->info, enc, space, sizeof space);
  png_set_oFFs(w->png, w->info, 0, 0, PNG_OFFSET_PIXEL);
  text[0] = (png_text){.compression = PNG_TEXT_COMPRESSION_NONE, .key = "oiio:ColorSpace", .text = space};
  text[1] = (png_text){.compression = PNG_TEXT_COMPRESSION_NONE, .key = "Software", .text = "vkraycast"};
  for (int i = 0; i < meta_count; i++)
    text[2 + i] = (png_text){.compression = PNG_TEXT_COMPRESSION_NONE, .key = (char *)meta[i].name,
                             .text = (char *)meta[i].value};
  png_set_text(w->png, w->info, text, meta_count + 2);
  png_write_info(w->png, w->info);
  free(text);
  if (w->error) {
    failure(w, err, err_len);
    discard(w);
    return NULL;
  }
  return (rc_image_writer *)w;
}

/* Rows of levels, 3 a pixel, or of floats turned into levels by the table. */
static int write_rows(png_writer *w, int rows, const float *pixels, const unsigned char *levels, char *err,
                      size_t err_len) {
  if (rows <= 0) return 0;
  if (w->next_row + rows > w->height) {
    set_error(err, err_len, "more rows than the image has");
    return -1;
  }
  if (setjmp(png_jmpbuf(w->png))) {
    failure(w, err, err_len);
    return -1;
  }
  const size_t n = (size_t)w->width * 3;
  for (int y = 0; y < rows; y++) {
    const unsigned char *row = levels ? levels + (size_t)y * n : w->row;
    if (!levels)
      for (size_t i = 0; i < n; i++) w->row[i] = rc_level_of(&w->levels, pixels[(size_t)y * n + i]);
    png_write_row(w->png, row);
    if (w->error) {
      failure(w, err, err_len);
      return -1;
    }
  }
  w->next_row += rows;
  return 0;
}

static int writer_rows(rc_image_writer *iw, int rows, const float *pixels, char *err, size_t err_len) {
  return write_rows((png_writer *)iw, rows, pixels, NULL, err, err_len);
}

static int writer_levels(rc_image_writer *iw, int rows, const unsigned char *levels, char *err, size_t err_len) {
  return write_rows((png_writer *)iw, rows, NULL, levels, err, err_len);
}

/* The end of the image (IEND) and every byte on disk before the file gets its name. */
static int writer_finish(rc_image_writer *iw, char *err, size_t err_len) {
  png_writer *w = (png_writer *)iw;
  if (w->next_row != w->height) {
    set_error(err, err_len, "the image is incomplete");
    return -1;
  }
  if (!w->png) return 0; /* finished before */
  if (setjmp(png_jmpbuf(w->png))) {
    failure(w, err, err_len);
    return -1;
  }
  png_write_end(w->png, w->info);
  png_destroy_write_struct(&w->png, &w->info);
  if (w->error) {
    failure(w, err, err_len);
    return -1;
  }
  return rc_staged_sync(&w->staged, err, err_len);
}

static int writer_close(rc_image_writer *iw, int commit, char *err, size_t err_len) {
  png_writer *w = (png_writer *)iw;
  if (!commit || writer_finish(iw, err, err_len) != 0) {
    discard(w);
    return commit ? -1 : 0;
  }
  int rc = rc_staged_commit(&w->staged, err, err_len);
  discard(w);
  return rc;
}

static const char *writer_temp_path(const rc_image_writer *iw) {
  return rc_staged_temp_path(&((const png_writer *)iw)->staged);
}

const rc_image_api *rc_png_writer_api(void) {
  static const rc_image_api table = {
      .version = RC_IMAGE_API_VERSION,
      .writer_open = writer_open,
      .writer_rows = writer_rows,
      .writer_levels = writer_levels,
      .writer_finish = writer_finish,
      .writer_close = writer_close,
      .writer_temp_path = writer_temp_path,
  };
  return &table;
}
