#include "cli/output.h"

#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "compare/aov.h"

/* Temporary files and the old files' backups (hard links kept while a commit is under
 * way) that the signal thread must unlink; written before any signal can need them. */
static char pending[3][4096], backups[3][4200];

/* Every asynchronous signal whose default action ends the process (signal(7)), SIGPIPE
 * aside: that one is sent to the thread that wrote to a closed pipe, and keeps a handler
 * of its own. Faults (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGSYS, SIGTRAP) are left
 * to their default and to the sanitizers' reports: where the temporary is unnamed
 * (O_TMPFILE, image_io.cpp) even they, and SIGKILL, leave nothing behind. */
static const int fatal_signals[] = {SIGHUP,  SIGINT,  SIGQUIT, SIGALRM, SIGTERM, SIGUSR1, SIGUSR2,
                                    SIGVTALRM, SIGPROF, SIGXCPU, SIGIO,   SIGPWR,  SIGSTKFLT};
static sigset_t fatal_set;
/* Held while the files of a run are renamed into place: the signal thread waits for it,
 * so that a signal lands before the first rename or after the last, never between. */
static pthread_mutex_t commit_lock = PTHREAD_MUTEX_INITIALIZER;

static void unlink_pending(void) {
  for (int i = 0; i < 3; i++) {
    if (pending[i][0]) unlink(pending[i]);
    if (backups[i][0]) unlink(backups[i]);
  }
}

static void on_pipe(int sig) {
  unlink_pending();
  signal(sig, SIG_DFL);
  raise(sig);
}

/* The one thread that takes the process's asynchronous signals: every other thread
 * blocks them (the mask is set before any thread starts: the driver's, the reference's,
 * the importer's inherit it). It waits for a commit under way, removes the temporaries,
 * and ends the process by the same signal. */
static void *signal_thread(void *unused) {
  (void)unused;
  int sig = 0;
  while (sigwait(&fatal_set, &sig) != 0) {
  }
  pthread_mutex_lock(&commit_lock);
  unlink_pending();
  signal(sig, SIG_DFL);
  sigset_t one;
  sigemptyset(&one);
  sigaddset(&one, sig);
  pthread_sigmask(SIG_UNBLOCK, &one, NULL);
  raise(sig);
  _exit(128 + sig);
}

void rc_output_install_signal_handlers(void) {
  static bool installed;
  if (installed) return;
  installed = true;
  sigemptyset(&fatal_set);
  for (size_t i = 0; i < sizeof fatal_signals / sizeof *fatal_signals; i++) sigaddset(&fatal_set, fatal_signals[i]);
  for (int s = SIGRTMIN; s <= SIGRTMAX; s++) sigaddset(&fatal_set, s);
  pthread_sigmask(SIG_BLOCK, &fatal_set, NULL);
  pthread_t t;
  if (pthread_create(&t, NULL, signal_thread, NULL) == 0) pthread_detach(t);
  struct sigaction sa = {.sa_handler = on_pipe};
  sigfillset(&sa.sa_mask);
  sigaction(SIGPIPE, &sa, NULL);
  signal(SIGXFSZ, SIG_IGN); /* a file size limit becomes a write error (EFBIG) */
}

struct rc_output {
  rc_image_writer *image, *aov, *stats;
  const char *image_path, *aov_path, *stats_path;
  uint32_t width;
  double length_unit; /* the AOV depth's scene units per packed unit */
  float *aov_band; /* rows * width * RC_AOV_CHANNELS */
  uint32_t aov_band_rows;
  uint32_t bands; /* bands written so far */
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

rc_status rc_output_check_format_early(const char *path) {
  static const char *const common[] = {".png", ".exr", ".tif", ".tiff", ".jpg", ".jpeg", ".hdr", ".bmp", ".ppm"};
  for (size_t i = 0; i < sizeof common / sizeof *common; i++)
    if (rc_has_extension(path, common[i])) return RC_OK;
  return rc_output_check_format(path);
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
  if (image_path) {
    o->image = rc_image_writer_open(image_path, (int)width, (int)height, 3, NULL, enc, truncate, meta, meta_count, err,
                                    sizeof err);
    if (!o->image) {
      rc_error("%s: cannot write image: %s", image_path, err);
      free(o);
      return RC_ERR_IO;
    }
    remember(0, o->image);
  }
  if (aov_path) {
    o->aov = rc_image_writer_open(aov_path, (int)width, (int)height, RC_AOV_CHANNELS, rc_aov_channel_names,
                                  rc_encoding_linear(), false, meta, meta_count, err, sizeof err);
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
  return rc_output_attach_bytes(o, path, text, strlen(text), "statistics");
}

rc_status rc_output_attach_bytes(rc_output *o, const char *path, const void *bytes, size_t len, const char *what) {
  char err[512];
  o->stats = rc_file_writer_open(path, bytes, len, err, sizeof err);
  if (!o->stats) {
    rc_error("%s: cannot write %s: %s", path, what, err);
    return RC_ERR_IO;
  }
  o->stats_path = path;
  remember(2, o->stats);
  return RC_OK;
}

rc_status rc_output_discard(uint32_t y0, uint32_t rows, const float *rgb, const uint8_t *levels,
                            const packed_aov *aov, void *unused) {
  (void)y0, (void)rows, (void)rgb, (void)levels, (void)aov, (void)unused;
  return RC_OK;
}

void rc_output_set_length_unit(rc_output *o, double unit) { o->length_unit = unit; }

rc_status rc_output_band(uint32_t y0, uint32_t rows, const float *rgb, const uint8_t *levels,
                         const packed_aov *aov, void *output) {
  (void)y0; /* bands arrive in order */
  rc_output *o = output;
  double t0 = rc_now_ms();
  char err[512];
  /* Levels come from a renderer that encoded them (--gpu-encode), which records no AOVs. */
  RC_ASSERT(!levels || !(o->aov && aov));
  int failed = !o->image ? 0
               : levels  ? rc_image_writer_levels(o->image, (int)rows, levels, err, sizeof err)
                         : rc_image_writer_rows(o->image, (int)rows, rgb, err, sizeof err);
  /* VKRAYCAST_FAULT=write-band:N fails band N (from 0) as a full disk would: how the tests
   * make a write fail while the next band renders (gpu_render.c, host_work). */
  const char *fault = rc_fault_arg("write-band");
  if (!failed && fault && (uint32_t)atoi(fault) == o->bands) {
    snprintf(err, sizeof err, "write failed: %s (injected)", strerror(ENOSPC));
    failed = 1;
  }
  o->bands++;
  if (failed) {
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

rc_status rc_output_aov_rows(rc_output *o, uint32_t rows, const float *channels) {
  double t0 = rc_now_ms();
  char err[512];
  if (rc_image_writer_rows(o->aov, (int)rows, channels, err, sizeof err) != 0) {
    rc_error("%s: cannot write the AOV file: %s", o->aov_path, err);
    return RC_ERR_IO;
  }
  o->write_ms += rc_now_ms() - t0;
  return RC_OK;
}

typedef struct {
  rc_image_writer *w;
  const char *path, *what;
} commit_file;

/* The backup's name: a hidden link beside the file, unique to this process. */
static void backup_name(const char *path, char *out, size_t cap) {
  const char *slash = strrchr(path, '/');
  int dir = slash ? (int)(slash - path + 1) : 0;
  snprintf(out, cap, "%.*s.%s.vkraycast-old-%ld", dir, path, slash ? slash + 1 : path, (long)getpid());
}

/* The rename of file `step` (0 image, 1 AOV, 2 statistics) fails when VKRAYCAST_FAULT is
 * commit:STEP: how the tests make a commit fail halfway, as a full disk or a lost
 * folder would. */
static bool injected(int step) {
  const char *arg = rc_fault_arg("commit");
  return arg && atoi(arg) == step;
}

/* Renames the written files into place, all or none: each old file is kept as a hard
 * link until every rename has succeeded; after a failure the files renamed so far are
 * put back (the old one restored, or the new one removed where there was none). Signals
 * wait for it to end (commit_lock). */
static rc_status commit_all(commit_file *files, int n) {
  char err[512];
  bool existed[3] = {false}, renamed[3] = {false};
  rc_status st = RC_OK;
  pthread_mutex_lock(&commit_lock);
  for (int i = 0; i < n; i++) {
    if (!files[i].w) continue;
    backup_name(files[i].path, backups[i], sizeof backups[i]);
    unlink(backups[i]);
    struct stat sb;
    existed[i] = lstat(files[i].path, &sb) == 0;
    if (existed[i] && link(files[i].path, backups[i]) != 0) {
      rc_error("%s: cannot keep the old %s while the new one is renamed into place: %s", files[i].path,
               files[i].what, strerror(errno));
      backups[i][0] = '\0';
      st = RC_ERR_IO;
      break;
    }
    if (!existed[i]) backups[i][0] = '\0';
  }
  for (int i = 0; i < n; i++) {
    if (!files[i].w) continue;
    bool ok = st == RC_OK;
    if (ok && injected(i)) {
      rc_error("%s: cannot write %s: injected fault (VKRAYCAST_FAULT=commit:%d)", files[i].path, files[i].what, i);
      ok = false;
    }
    if (rc_image_writer_close(files[i].w, ok, err, sizeof err) != 0 && ok) {
      rc_error("%s: cannot write %s: %s", files[i].path, files[i].what, err);
      ok = false;
    }
    renamed[i] = ok;
    if (!ok) st = RC_ERR_IO;
    /* VKRAYCAST_FAULT=commit-pause:STEP holds the commit after that rename for two
     * seconds: the tests send a signal then, which must wait for the commit's end. */
    const char *pause = rc_fault_arg("commit-pause");
    if (ok && pause && atoi(pause) == i) sleep(2);
  }
  for (int i = 0; i < n; i++) {
    if (st != RC_OK && renamed[i]) {
      /* Put back what was there: the old file, or nothing. */
      bool back = existed[i] ? rename(backups[i], files[i].path) == 0 : unlink(files[i].path) == 0;
      if (!back)
        rc_error("%s: cannot restore the old %s after the failure: %s (the old one is %s)", files[i].path,
                 files[i].what, strerror(errno), existed[i] ? backups[i] : "absent");
      else if (existed[i])
        backups[i][0] = '\0';
    }
    if (backups[i][0]) unlink(backups[i]);
    backups[i][0] = '\0';
  }
  pthread_mutex_unlock(&commit_lock);
  return st;
}

rc_status rc_output_close(rc_output *o, bool commit) {
  if (!o) return RC_OK;
  rc_status st = RC_OK;
  char err[512];
  double t0 = rc_now_ms();
  /* One transaction: every file is written and fsynced before any is renamed, and a
   * failure of any discards all, so an AOV or statistics file that cannot be written
   * leaves the old image in place too. */
  commit_file files[3] = {{o->image, o->image_path, "image"},
                {o->aov, o->aov_path, "the AOV file"},
                {o->stats, o->stats_path, "statistics"}};
  for (int i = 0; commit && i < 3; i++) {
    if (files[i].w && rc_image_writer_finish(files[i].w, err, sizeof err) != 0) {
      rc_error("%s: cannot write %s: %s", files[i].path, files[i].what, err);
      st = RC_ERR_IO;
      commit = false;
    }
  }
  if (commit) st = commit_all(files, 3);
  for (int i = 0; !commit && i < 3; i++)
    if (files[i].w) rc_image_writer_close(files[i].w, false, err, sizeof err);
  o->write_ms += rc_now_ms() - t0;
  pending[0][0] = pending[1][0] = pending[2][0] = '\0';
  free(o->aov_band);
  free(o);
  return st;
}

double rc_output_write_ms(const rc_output *o) { return o ? o->write_ms : 0; }
