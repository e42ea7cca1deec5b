#include "cli/output.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "compare/aov.h"

/* Temporary files the signal handler must unlink; written before any signal can need
 * them, read only by the handler (unlink() is async-signal-safe). */
static char pending[3][4096];

static void on_fatal_signal(int sig) {
  for (int i = 0; i < 3; i++)
    if (pending[i][0]) unlink(pending[i]);
  signal(sig, SIG_DFL);
  raise(sig);
}

/* Every asynchronous signal whose default action ends the process (signal(7)). Faults
 * (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGSYS, SIGTRAP) are left to their default
 * and to the sanitizers' reports: where the temporary is unnamed (O_TMPFILE, image_io.cpp)
 * even they, and SIGKILL, leave nothing behind. */
static const int fatal_signals[] = {SIGHUP,  SIGINT,    SIGQUIT, SIGPIPE, SIGALRM, SIGTERM, SIGUSR1,
                                    SIGUSR2, SIGVTALRM, SIGPROF, SIGXCPU, SIGIO,   SIGPWR,  SIGSTKFLT};

void rc_output_install_signal_handlers(void) {
  struct sigaction sa = {.sa_handler = on_fatal_signal};
  sigfillset(&sa.sa_mask); /* one handler at a time */
  for (size_t i = 0; i < sizeof fatal_signals / sizeof *fatal_signals; i++) sigaction(fatal_signals[i], &sa, NULL);
  for (int s = SIGRTMIN; s <= SIGRTMAX; s++) sigaction(s, &sa, NULL);
  signal(SIGXFSZ, SIG_IGN); /* a file size limit becomes a write error (EFBIG) */
}

struct rc_output {
  rc_image_writer *image, *aov, *stats;
  const char *image_path, *aov_path, *stats_path;
  uint32_t width;
  double length_unit; /* the AOV depth's scene units per packed unit */
  float *aov_band; /* rows * width * RC_AOV_CHANNELS */
  uint32_t aov_band_rows;
  double write_ms;
};

rc_status rc_output_check_format(const char *path) {
  int can = rc_image_can_write(path);
  if (can < 0) return RC_ERR_INSTALL;
  if (!can) {
    rc_error("%s: no image format for this file name (use .png, .exr, .tif, .jpg, ...)", path);
    return RC_ERR_USAGE;
  }
  return RC_OK;
}

static void remember(int slot, rc_image_writer *w) {
  const char *p = w ? rc_image_writer_temp_path(w) : "";
  snprintf(pending[slot], sizeof pending[slot], "%s", p);
}

rc_status rc_output_open(const char *image_path, const char *aov_path, uint32_t width, uint32_t height,
                         rc_encoding enc, bool truncate, const rc_image_meta *meta, int meta_count, rc_output **out) {
  rc_output *o = calloc(1, sizeof *o);
  if (!o) return RC_ERR_OUT_OF_MEMORY;
  o->image_path = image_path, o->aov_path = aov_path, o->width = width, o->length_unit = 1;
  char err[512];
  o->image = rc_image_writer_open(image_path, (int)width, (int)height, 3, NULL, enc, truncate, meta, meta_count, err,
                                  sizeof err);
  if (!o->image) {
    rc_error("%s: cannot write image: %s", image_path, err);
    free(o);
    return RC_ERR_IO;
  }
  remember(0, o->image);
  if (aov_path) {
    o->aov = rc_image_writer_open(aov_path, (int)width, (int)height, RC_AOV_CHANNELS, rc_aov_channel_names,
                                  RC_ENCODING_LINEAR, false, meta, meta_count, err, sizeof err);
    if (!o->aov) {
      rc_error("%s: cannot write the AOV file: %s", aov_path, err);
      rc_output_close(o, false);
      return RC_ERR_IO;
    }
    remember(1, o->aov);
  }
  *out = o;
  return RC_OK;
}

rc_status rc_output_attach(rc_output *o, const char *path, const char *text) {
  char err[512];
  o->stats = rc_file_writer_open(path, text, strlen(text), err, sizeof err);
  if (!o->stats) {
    rc_error("%s: cannot write statistics: %s", path, err);
    return RC_ERR_IO;
  }
  o->stats_path = path;
  remember(2, o->stats);
  return RC_OK;
}

rc_status rc_output_discard(uint32_t y0, uint32_t rows, const float *rgb, const gpu_aov *aov, void *unused) {
  (void)y0, (void)rows, (void)rgb, (void)aov, (void)unused;
  return RC_OK;
}

void rc_output_set_length_unit(rc_output *o, double unit) { o->length_unit = unit; }

rc_status rc_output_band(uint32_t y0, uint32_t rows, const float *rgb, const gpu_aov *aov, void *output) {
  (void)y0; /* bands arrive in order */
  rc_output *o = output;
  double t0 = rc_now_ms();
  char err[512];
  if (rc_image_writer_rows(o->image, (int)rows, rgb, err, sizeof err) != 0) {
    rc_error("%s: cannot write image: %s", o->image_path, err);
    return RC_ERR_IO;
  }
  if (o->aov && aov) {
    if (rows > o->aov_band_rows) {
      free(o->aov_band);
      o->aov_band = rc_alloc((size_t)rows * o->width * RC_AOV_CHANNELS, sizeof(float), "one band of AOVs");
      o->aov_band_rows = o->aov_band ? rows : 0;
      if (!o->aov_band) return RC_ERR_OUT_OF_MEMORY;
    }
    rc_aov_pack(rgb, aov, (size_t)rows * o->width, o->length_unit, o->aov_band);
    if (rc_image_writer_rows(o->aov, (int)rows, o->aov_band, err, sizeof err) != 0) {
      rc_error("%s: cannot write the AOV file: %s", o->aov_path, err);
      return RC_ERR_IO;
    }
  }
  o->write_ms += rc_now_ms() - t0;
  return RC_OK;
}

rc_status rc_output_close(rc_output *o, bool commit) {
  if (!o) return RC_OK;
  rc_status st = RC_OK;
  char err[512];
  double t0 = rc_now_ms();
  /* One transaction: every file is written and fsynced before any is renamed, and a
   * failure of any discards all, so an AOV or statistics file that cannot be written
   * leaves the old image in place too. */
  struct {
    rc_image_writer *w;
    const char *path, *what;
  } files[3] = {{o->image, o->image_path, "image"},
                {o->aov, o->aov_path, "the AOV file"},
                {o->stats, o->stats_path, "statistics"}};
  for (int i = 0; commit && i < 3; i++) {
    if (files[i].w && rc_image_writer_finish(files[i].w, err, sizeof err) != 0) {
      rc_error("%s: cannot write %s: %s", files[i].path, files[i].what, err);
      st = RC_ERR_IO;
      commit = false;
    }
  }
  for (int i = 0; i < 3; i++) {
    if (files[i].w && rc_image_writer_close(files[i].w, commit, err, sizeof err) != 0) {
      rc_error("%s: cannot write %s: %s", files[i].path, files[i].what, err);
      st = RC_ERR_IO;
      commit = false;
    }
  }
  o->write_ms += rc_now_ms() - t0;
  pending[0][0] = pending[1][0] = pending[2][0] = '\0';
  free(o->aov_band);
  free(o);
  return st;
}

double rc_output_write_ms(const rc_output *o) { return o ? o->write_ms : 0; }
