/* png_read.c: the readers of image_io.h for PNGs without alpha, through libpng alone, linked
 * into the vkraycast binary. Textures, course reference images and the renders `compare`
 * reads are such files, and OpenImageIO's 260 libraries cost each process that reads one
 * about 0.2 s of CPU to load (docs/performance.md, "Process start-up", finding 16). They
 * return what OpenImageIO 2.4's PNG reader returns for them, float for float (ctest
 * png_reader): the file's channels (Y for grey, R, G, B; a palette expanded to RGB, grey
 * of 1, 2 or 4 bits to 8), each level times 1/255 or 1/65,535 in float, as OpenImageIO
 * converts, and no gamma applied (the gAMA and sRGB chunks only describe the file); the
 * row reader adds the tEXt attributes before the pixels (the render's scene hash and
 * settings, which `compare` reads). A file with alpha (an alpha channel or a tRNS chunk)
 * stays OpenImageIO's, which associates its alpha on reading; so does anything these
 * readers refuse, so that errors keep OpenImageIO's messages (image_load.c). */
#include "image/png_reader.h"

#include <fcntl.h>
#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static void on_error(png_structp png, png_const_charp msg) {
  (void)msg;
  png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg) { (void)png, (void)msg; }

/* An open file, its header read and the expansions set. Reached through a pointer, so a
 * longjmp from libpng loses none of it. */
struct rc_image_reader {
  FILE *file;
  png_structp png;
  png_infop info;
  png_textp text;
  int text_count;
  int width, height, channels, bits, passes, next_row;
  size_t rowbytes;
  png_bytep rows; /* one row, or the whole image where interlaced */
  char path[];
};

static void release(rc_image_reader *r) {
  if (!r) return;
  if (r->png) png_destroy_read_struct(&r->png, r->info ? &r->info : NULL, NULL);
  if (r->file) fclose(r->file);
  free(r->rows);
  free(r);
}

/* Opens a regular file only: a FIFO opened without O_NONBLOCK would wait for a writer. */
static FILE *open_regular(const char *path) {
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return NULL;
  struct stat st;
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    close(fd);
    return NULL;
  }
  FILE *f = fdopen(fd, "rb");
  if (!f) close(fd);
  return f;
}

static int read_header(rc_image_reader *r) {
  r->file = open_regular(r->path);
  if (!r->file) return -1;
  unsigned char sig[8];
  if (fread(sig, 1, sizeof sig, r->file) != sizeof sig || png_sig_cmp(sig, 0, sizeof sig) != 0) return -1;
  r->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, on_error, on_warning);
  if (!r->png) return -1;
  r->info = png_create_info_struct(r->png);
  if (!r->info) return -1;
  if (setjmp(png_jmpbuf(r->png))) return -1;
  png_init_io(r->png, r->file);
  png_set_sig_bytes(r->png, sizeof sig);
  png_read_info(r->png, r->info);
  int type = png_get_color_type(r->png, r->info), depth = png_get_bit_depth(r->png, r->info);
  if ((type & PNG_COLOR_MASK_ALPHA) || png_get_valid(r->png, r->info, PNG_INFO_tRNS)) return -1;
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(r->png);
  if (type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(r->png);
  r->passes = png_set_interlace_handling(r->png);
  png_read_update_info(r->png, r->info);
  png_uint_32 w = png_get_image_width(r->png, r->info), h = png_get_image_height(r->png, r->info);
  r->channels = png_get_channels(r->png, r->info), r->bits = png_get_bit_depth(r->png, r->info);
  r->rowbytes = png_get_rowbytes(r->png, r->info);
  if (w == 0 || h == 0 || w > INT32_MAX || h > INT32_MAX || (r->channels != 1 && r->channels != 3) ||
      (r->bits != 8 && r->bits != 16))
    return -1;
  r->width = (int)w, r->height = (int)h;
  png_get_text(r->png, r->info, &r->text, &r->text_count);
  /* Interlaced rows are final only after the last pass: the whole image is read at once. */
  size_t n = r->passes > 1 ? r->rowbytes * h : r->rowbytes;
  if (r->passes > 1 && n / h != r->rowbytes) return -1;
  r->rows = malloc(n);
  if (!r->rows) return -1;
  if (r->passes > 1) {
    for (int pass = 0; pass < r->passes; pass++)
      for (png_uint_32 y = 0; y < h; y++) png_read_row(r->png, r->rows + r->rowbytes * y, NULL);
  }
  return 0;
}

static rc_image_reader *reader_new(const char *path) {
  size_t len = strlen(path) + 1;
  rc_image_reader *r = calloc(1, sizeof *r + len);
  if (!r) return NULL;
  memcpy(r->path, path, len);
  if (read_header(r) != 0) {
    release(r);
    return NULL;
  }
  return r;
}

/* Rows [y0, y1) as float, the rows before y0 skipped; a row already passed is not read
 * again (-1): the callers read a file from the top once. */
static int read_rows(rc_image_reader *r, int y0, int y1, float *pixels) {
  if (y0 < 0 || y1 > r->height || y0 > y1) return -1;
  if (r->passes == 1 && y0 < r->next_row) return -1;
  if (setjmp(png_jmpbuf(r->png))) return -1;
  const size_t per_row = (size_t)r->width * r->channels;
  const float scale = r->bits == 16 ? 1.0f / 65535.0f : 1.0f / 255.0f;
  for (int y = r->passes > 1 ? y0 : r->next_row; y < y1; y++) {
    png_bytep row = r->rows;
    if (r->passes > 1) row += r->rowbytes * y;
    else png_read_row(r->png, row, NULL);
    r->next_row = y + 1;
    if (y < y0) continue;
    float *out = pixels + (size_t)(y - y0) * per_row;
    if (r->bits == 8)
      for (size_t i = 0; i < per_row; i++) out[i] = (float)row[i] * scale;
    else
      for (size_t i = 0; i < per_row; i++) out[i] = (float)(row[2 * i] << 8 | row[2 * i + 1]) * scale;
  }
  return 0;
}

static const char *channel_name(const rc_image_reader *r, int c) {
  static const char *const rgb[] = {"R", "G", "B"};
  return r->channels == 1 ? "Y" : rgb[c];
}

static rc_image_reader *reader_open(const char *path, int *width, int *height, int *channels, bool *float32,
                                    char *err, size_t err_len) {
  (void)err, (void)err_len;
  rc_image_reader *r = reader_new(path);
  if (!r) return NULL;
  *width = r->width, *height = r->height, *channels = r->channels, *float32 = false;
  return r;
}

static int reader_meta(const rc_image_reader *r, const char *name, char *value, size_t len) {
  for (int i = 0; i < r->text_count; i++)
    if (r->text[i].key && strcmp(r->text[i].key, name) == 0) {
      snprintf(value, len, "%s", r->text[i].text ? r->text[i].text : "");
      return 1;
    }
  return 0;
}

static int reader_channel(const rc_image_reader *r, int c, char *name, size_t len) {
  if (c < 0 || c >= r->channels) return 0;
  snprintf(name, len, "%s", channel_name(r, c));
  return 1;
}

static int reader_rows(rc_image_reader *r, int y0, int y1, float *pixels, char *err, size_t err_len) {
  if (read_rows(r, y0, y1, pixels) == 0) return 0;
  if (err && err_len) snprintf(err, err_len, "%s: cannot read rows %d to %d of the PNG", r->path, y0, y1);
  return -1;
}

static void reader_close(rc_image_reader *r) { release(r); }

static int read_named(const char *path, int *width, int *height, int *channels, float **pixels, char (*names)[32],
                      int max_names, int *name_count, char *err, size_t err_len) {
  (void)err, (void)err_len;
  *pixels = NULL;
  rc_image_reader *r = reader_new(path);
  if (!r) return -1;
  size_t count = (size_t)r->width * r->height * r->channels;
  float *px = count <= SIZE_MAX / sizeof *px ? malloc(count * sizeof *px) : NULL;
  if (!px || read_rows(r, 0, r->height, px) != 0) {
    free(px);
    release(r);
    return -1;
  }
  *name_count = 0;
  for (int c = 0; c < r->channels && c < max_names; c++) {
    snprintf(names[c], 32, "%s", channel_name(r, c));
    *name_count = c + 1;
  }
  *width = r->width, *height = r->height, *channels = r->channels, *pixels = px;
  release(r);
  return 0;
}

const rc_image_api *rc_png_reader_api(void) {
  static const rc_image_api table = {
      .version = RC_IMAGE_API_VERSION,
      .read_named = read_named,
      .reader_open = reader_open,
      .reader_meta = reader_meta,
      .reader_channel = reader_channel,
      .reader_rows = reader_rows,
      .reader_close = reader_close,
  };
  return &table;
}
