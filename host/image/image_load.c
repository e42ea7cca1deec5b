/* image_load.c: image_io.h for the vkraycast binary, forwarding to vkraycast-image.so,
 * loaded on the first call (image_module.h says why), reading and writing .exr files
 * through vkraycast-exr.so first (below, exr_module), and reading and writing .png files
 * through the binary's own libpng reader and writer (png_read.c, png_writer). The modules
 * are looked for beside the binary (/proc/self/exe), where the build puts them. */
#include "image/image_module.h"
#include "image/png_reader.h"
#include "image/png_writer.h"

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

static const rc_image_api *api;
static char load_error[PATH_MAX + 600];
static pthread_once_t once = PTHREAD_ONCE_INIT;

/* Loads the libraries the module needs, listed in `dir`/vkraycast-image.deps (written by
 * the build from ldd: one path a line, the leaves first), one dlopen each, before the
 * module. Why: OpenImageIO's libraries are linked with -z now, so loading them resolves all
 * ~150,000 of their symbol references at once, and a reference is looked up along the
 * loading object's scope in order. Loaded together, that scope is the module's ~260
 * libraries breadth first, and OpenVDB's and GDAL's own symbols (~120,000 references)
 * lie 25 and 120 libraries deep; loaded each on its own, a library comes first in its own
 * scope. Measured on the 2-core VM: 360-506 ms of CPU to load the module alone, 196-217 ms
 * after the list (docs/performance.md, "Process start-up", finding 9). The list orders
 * what the module would load anyway: a line that does not load is skipped, and without the
 * file the module loads as before. */
static void preload_dependencies(const char *dir) {
  char path[PATH_MAX + 32], line[PATH_MAX];
  snprintf(path, sizeof path, "%s/vkraycast-image.deps", dir);
  FILE *f = fopen(path, "r");
  if (!f) return;
  while (fgets(line, sizeof line, f)) {
    line[strcspn(line, "\n")] = '\0';
    if (line[0] == '/') (void)dlopen(line, RTLD_LAZY | RTLD_LOCAL); /* kept loaded, as the module is */
  }
  fclose(f);
}

/* Loads the module `name` from beside the binary and returns its table (`symbol`), or NULL
 * with the reason in `error`. */
static const rc_image_api *load_module(const char *name, const char *symbol, bool deps, char *error, size_t len) {
  char exe[PATH_MAX], path[PATH_MAX + 32];
  ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n <= 0) {
    snprintf(error, len, "cannot find the image module: /proc/self/exe unreadable");
    return NULL;
  }
  exe[n] = '\0';
  char *slash = strrchr(exe, '/');
  if (slash) *slash = '\0';
  snprintf(path, sizeof path, "%s/%s", exe, name);
  if (deps) preload_dependencies(exe);
  void *h = dlopen(path, RTLD_LAZY | RTLD_LOCAL);
  if (!h) {
    snprintf(error, len, "cannot load the image module %s: %s", path, dlerror());
    return NULL;
  }
  const rc_image_api *(*get)(void) = (const rc_image_api *(*)(void))dlsym(h, symbol);
  const rc_image_api *a = get ? get() : NULL;
  if (!a || a->version != RC_IMAGE_API_VERSION) {
    snprintf(error, len, "the image module %s is from another build (API %u, this binary %u)", path,
             a ? a->version : 0u, RC_IMAGE_API_VERSION);
    return NULL;
  }
  return a;
}

static void load(void) {
  api = load_module("vkraycast-image.so", RC_IMAGE_MODULE_SYMBOL, true, load_error, sizeof load_error);
}

/* The table, or NULL with the reason in err. */
static const rc_image_api *module(char *err, size_t err_len) {
  pthread_once(&once, load);
  if (!api && err && err_len) snprintf(err, err_len, "%s", load_error);
  return api;
}

/* OpenEXR files through OpenEXR alone (vkraycast-exr.so: exr_read.cpp, exr_write.cpp):
 * about 2 ms to load against OpenImageIO's 0.2 s of CPU, which was most of what `compare`
 * of two EXRs, and a render to an EXR, cost. Tried first for a name ending in .exr; an EXR
 * this reader cannot read (or a missing module) goes to OpenImageIO as before, so errors
 * keep its messages. VKRAYCAST_EXR_READER=oiio reads, and VKRAYCAST_EXR_WRITER=oiio writes,
 * every EXR through OpenImageIO (ctests exr_reader and exr_writer compare the two). */
static const rc_image_api *exr_api;
static pthread_once_t exr_once = PTHREAD_ONCE_INIT;

static void load_exr(void) {
  char error[PATH_MAX + 600];
  exr_api = load_module("vkraycast-exr.so", RC_EXR_MODULE_SYMBOL, false, error, sizeof error);
}

static const rc_image_api *exr_loaded(void) {
  pthread_once(&exr_once, load_exr);
  return exr_api;
}

/* Whether `path` ends in `ext` (".exr"), in any case. */
static bool has_suffix(const char *path, const char *ext) {
  size_t n = strlen(path), k = strlen(ext);
  return n >= k && strcasecmp(path + n - k, ext) == 0;
}

/* Whether the environment variable `choice` asks for OpenImageIO. */
static bool oiio_chosen(const char *choice) {
  const char *c = getenv(choice);
  return c && strcmp(c, "oiio") == 0;
}

/* The OpenEXR module for `path`, or NULL: not an .exr name, the module missing, or
 * OpenImageIO chosen by the variable `choice`. */
static const rc_image_api *exr_module(const char *path, const char *choice) {
  return has_suffix(path, ".exr") && !oiio_chosen(choice) ? exr_loaded() : NULL;
}

#define EXR_READER "VKRAYCAST_EXR_READER"
#define EXR_WRITER "VKRAYCAST_EXR_WRITER"

/* The PNG writer linked into the binary (png_write.c) for `path`, or NULL: not a .png name,
 * not 3 unnamed channels (alpha and named channels are OpenImageIO's), or OpenImageIO chosen
 * by VKRAYCAST_PNG_WRITER=oiio. channels 3 and names NULL where only the name is known
 * (can_write, stores_levels): every PNG the renderer writes is one. */
static const rc_image_api *png_writer(const char *path, int channels, const char *const *names) {
  bool mine = has_suffix(path, ".png") && channels == 3 && !names && !oiio_chosen("VKRAYCAST_PNG_WRITER");
  return mine ? rc_png_writer_api() : NULL;
}

/* A reader or writer from any of the tables (OpenImageIO's, OpenEXR's, the PNG writer's): the
 * table that opened it travels with it. */
struct rc_image_reader {
  const rc_image_api *m;
  rc_image_reader *inner;
};
struct rc_image_writer {
  const rc_image_api *m;
  rc_image_writer *inner;
};

/* Wraps `inner`, opened by `m`; NULL (inner closed) if out of memory. */
static rc_image_writer *wrap_writer(const rc_image_api *m, rc_image_writer *inner, char *err, size_t err_len) {
  if (!inner) return NULL;
  rc_image_writer *w = malloc(sizeof *w);
  if (!w) {
    m->writer_close(inner, 0, NULL, 0);
    snprintf(err, err_len, "out of memory");
    return NULL;
  }
  w->m = m, w->inner = inner;
  return w;
}

rc_image_writer *rc_image_writer_open(const char *path, int width, int height, int channels, const char *const *names,
                                      rc_encoding enc, bool truncate, const rc_image_meta *meta, int meta_count,
                                      char *err, size_t err_len) {
  const rc_image_api *m = exr_module(path, EXR_WRITER);
  if (!m) m = png_writer(path, channels, names);
  if (!m) m = module(err, err_len);
  if (!m) return NULL;
  rc_image_writer *inner = m->writer_open(path, width, height, channels, names, enc, truncate, meta, meta_count, err, err_len);
  return wrap_writer(m, inner, err, err_len);
}

/* The whole image at once, as image_io.cpp has it: one band. */
int rc_image_write(const char *path, int width, int height, int channels, const float *pixels, rc_encoding enc,
                   bool truncate, char *err, size_t err_len) {
  rc_image_writer *w = rc_image_writer_open(path, width, height, channels, NULL, enc, truncate, NULL, 0, err, err_len);
  if (!w) return -1;
  if (rc_image_writer_rows(w, height, pixels, err, err_len) != 0) {
    rc_image_writer_close(w, 0, NULL, 0);
    return -1;
  }
  return rc_image_writer_close(w, 1, err, err_len);
}

int rc_image_writer_rows(rc_image_writer *w, int rows, const float *pixels, char *err, size_t err_len) {
  return w->m->writer_rows(w->inner, rows, pixels, err, err_len);
}

int rc_image_writer_levels(rc_image_writer *w, int rows, const unsigned char *levels, char *err, size_t err_len) {
  return w->m->writer_levels(w->inner, rows, levels, err, err_len);
}

int rc_image_writer_finish(rc_image_writer *w, char *err, size_t err_len) {
  return w->m->writer_finish(w->inner, err, err_len);
}

int rc_image_writer_close(rc_image_writer *w, int commit, char *err, size_t err_len) {
  int rc = w->m->writer_close(w->inner, commit, err, err_len);
  free(w);
  return rc;
}

/* Bytes as they are (a .vkrs): the OpenEXR module's writer, which needs no image library;
 * OpenImageIO's module only where that one is missing. */
rc_image_writer *rc_file_writer_open(const char *path, const void *bytes, size_t len, char *err, size_t err_len) {
  const rc_image_api *m = exr_loaded();
  if (!m) m = module(err, err_len);
  return m ? wrap_writer(m, m->file_writer_open(path, bytes, len, err, err_len), err, err_len) : NULL;
}

const char *rc_image_writer_temp_path(const rc_image_writer *w) { return w->m->writer_temp_path(w->inner); }

/* The reader for `path` tried before OpenImageIO: OpenEXR's for .exr names, the binary's
 * libpng reader for .png names (PNGs without alpha: png_read.c), or NULL. A file it does
 * not take goes to OpenImageIO, whose messages errors keep. VKRAYCAST_EXR_READER=oiio and
 * VKRAYCAST_PNG_READER=oiio read through OpenImageIO (ctests exr_reader and png_reader
 * compare the two). */
static const rc_image_api *first_reader(const char *path) {
  const rc_image_api *x = exr_module(path, EXR_READER);
  if (!x && has_suffix(path, ".png") && !oiio_chosen("VKRAYCAST_PNG_READER")) x = rc_png_reader_api();
  return x;
}

int rc_image_read_named(const char *path, int *width, int *height, int *channels, float **pixels, char (*names)[32],
                        int max_names, int *name_count, char *err, size_t err_len) {
  const rc_image_api *x = first_reader(path);
  if (x && x->read_named(path, width, height, channels, pixels, names, max_names, name_count, NULL, 0) == 0) return 0;
  const rc_image_api *m = module(err, err_len);
  return m ? m->read_named(path, width, height, channels, pixels, names, max_names, name_count, err, err_len) : -1;
}

/* Without the module: -1, and the reason on stderr. */
int rc_image_can_write(const char *path) {
  const rc_image_api *x = exr_module(path, EXR_WRITER);
  if (x) return x->can_write(path);
  if (png_writer(path, 3, NULL)) return 1;
  char err[sizeof load_error];
  const rc_image_api *m = module(err, sizeof err);
  if (!m) fprintf(stderr, "vkraycast: error: %s\n", err);
  return m ? m->can_write(path) : -1;
}

int rc_image_stores_levels(const char *path) {
  const rc_image_api *x = exr_module(path, EXR_WRITER);
  if (x) return x->stores_levels(path);
  if (png_writer(path, 3, NULL)) return 1;
  char err[sizeof load_error];
  const rc_image_api *m = module(err, sizeof err);
  if (!m) fprintf(stderr, "vkraycast: error: %s\n", err);
  return m ? m->stores_levels(path) : -1;
}

/* rc_image_read_named without the names, as image_io.cpp has it: one place tries the EXR
 * reader first. */
int rc_image_read(const char *path, int *width, int *height, int *channels, float **pixels, char *err, size_t err_len) {
  int n = 0;
  return rc_image_read_named(path, width, height, channels, pixels, NULL, 0, &n, err, err_len);
}

rc_image_reader *rc_image_reader_open(const char *path, int *width, int *height, int *channels, bool *float32,
                                      char *err, size_t err_len) {
  rc_image_reader *r = malloc(sizeof *r);
  if (!r) {
    snprintf(err, err_len, "out of memory");
    return NULL;
  }
  r->m = first_reader(path);
  r->inner = r->m ? r->m->reader_open(path, width, height, channels, float32, NULL, 0) : NULL;
  if (!r->inner) {
    r->m = module(err, err_len);
    r->inner = r->m ? r->m->reader_open(path, width, height, channels, float32, err, err_len) : NULL;
  }
  if (!r->inner) free(r), r = NULL;
  return r;
}

int rc_image_reader_meta(const rc_image_reader *r, const char *name, char *value, size_t len) {
  return r->m->reader_meta(r->inner, name, value, len);
}

int rc_image_reader_channel(const rc_image_reader *r, int c, char *name, size_t len) {
  return r->m->reader_channel(r->inner, c, name, len);
}

int rc_image_reader_rows(rc_image_reader *r, int y0, int y1, float *pixels, char *err, size_t err_len) {
  return r->m->reader_rows(r->inner, y0, y1, pixels, err, err_len);
}

void rc_image_reader_close(rc_image_reader *r) {
  if (!r) return;
  r->m->reader_close(r->inner);
  free(r);
}
