/* cmd_tradeoff.c: `vkraycast tradeoff SCENE... --out DIR`: what accuracy costs on the
 * user's own scenes. Every point (scene x variant x spp) is a `vkraycast render` of its
 * own process, so that one variant that fails or is refused costs its point, not the
 * sweep, and so that each is timed as a user's render is; the references (CPU f64, the
 * same samples for decisions, --reference-spp samples for colour) are rendered once a
 * scene and spp into DIR/work. Nothing is written outside DIR. */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"
#include "cli/options.h"
#include "cli/tradeoff.h"
#include "compare/aov.h"
#include "compare/compare.h"
#include "scene/scene.h"
#include "image/image_io.h"

extern char **environ;

#define MAX_SCENES 64

/* The documented variants (docs/accuracy.md), from the fastest formulas to f64. Each
 * fixes every knob it names; the rest are the defaults. --precision pins what auto
 * would choose, so that a variant is one arithmetic on every scene. */
static const rc_tradeoff_variant builtin_variants[] = {
    {"fast", "algebraic sphere, Moller-Trumbore, fixed epsilon offset, world coordinates, f32",
     "--sphere algebraic --triangle moller-trumbore --shadow-offset epsilon --camera-relative off --precision f32"},
    {"geometric", "geometric sphere, Moller-Trumbore, fixed epsilon offset, world coordinates, f32",
     "--sphere geometric --triangle moller-trumbore --shadow-offset epsilon --camera-relative off --precision f32"},
    {"watertight", "geometric sphere, watertight triangles, fixed epsilon offset, world coordinates, f32",
     "--sphere geometric --triangle watertight --shadow-offset epsilon --camera-relative off --precision f32"},
    {"ulp-offset", "as watertight, offset by ulps of the hit point (Wachter-Binder), f32",
     "--sphere geometric --triangle watertight --shadow-offset ulp --camera-relative off --precision f32"},
    {"error-bound", "as watertight, offset by the rounding-error bound (pbrt), world coordinates, f32",
     "--sphere geometric --triangle watertight --shadow-offset error-bound --camera-relative off --precision f32"},
    {"default", "the defaults: as error-bound, positions relative to the eye, f32", "--precision f32"},
    {"certified", "the defaults in f32, each decision certified, the rest re-rendered in f64 on the CPU",
     "--precision certified"},
    {"f64", "the defaults in f64", "--precision f64"},
};
#define BUILTIN_COUNT (sizeof builtin_variants / sizeof *builtin_variants)

typedef struct {
  const char *scenes[MAX_SCENES];
  const char *out, *spp_list, *variant_names, *render_args, *backend;
  rc_opt_list custom; /* --variant "NAME: OPTIONS" */
  uint32_t width, height, repeat, reference_spp;
  int point; /* --point I; -1: all */
  bool gather, count, quiet, keep;
} tradeoff_args;

#define ARG(field) offsetof(tradeoff_args, field)
static const rc_option tradeoff_options[] = {
    {"--out", NULL, RC_OPT_STRING, ARG(out), "DIR", .flags = RC_OPT_REQUIRED, .what = "output folder",
     .help = "where tradeoff.csv, tradeoff-summary.csv and tradeoff.svg go (created if\n"
             "missing; renders go to DIR/work and are removed point by point)"},
    {"--width", NULL, RC_OPT_UINT, ARG(width), "W", 1, 16384, .help = "render at this width (default: each scene's)"},
    {"--height", NULL, RC_OPT_UINT, ARG(height), "H", 1, 16384, .help = "render at this height (default: each scene's)"},
    {"--spp-list", NULL, RC_OPT_STRING, ARG(spp_list), "N,N,...",
     .help = "samples per pixel to measure each variant at (default 1,4,16); scene:\n"
             "each scene's own"},
    {"--repeat", NULL, RC_OPT_UINT, ARG(repeat), "N", 2, 100,
     .help = "frames per render; times are the median of frames 2..N (default 3)"},
    {"--reference-spp", NULL, RC_OPT_UINT, ARG(reference_spp), "N", 1, 1024,
     .help = "samples of the CPU f64 render that colour is measured against\n(default 256)"},
    {"--variants", NULL, RC_OPT_STRING, ARG(variant_names), "A,B,...",
     .help = "measure only these built-in variants (default all): fast, geometric,\n"
             "watertight, ulp-offset, error-bound, default, f64"},
    {"--variant", NULL, RC_OPT_LIST, ARG(custom), "'NAME: OPTIONS'",
     .help = "a variant of your own: render OPTIONS (space-separated) under NAME;\n"
             "repeatable; given, it replaces the built-in set unless --variants is\n"
             "given too"},
    {"--backend", NULL, RC_OPT_STRING, ARG(backend), "gpu|cpu",
     .help = "what renders the measured points (default gpu); references are\nalways the CPU in f64"},
    {"--render-args", NULL, RC_OPT_STRING, ARG(render_args), "'OPTIONS'",
     .help = "options added to every render, references included (e.g.\n"
             "--render-args='--allow-outside-paths --tile 160': the = keeps the\n"
             "value from being read as an option)"},
    {"--keep-renders", NULL, RC_OPT_FLAG, ARG(keep), .help = "keep every point's images in DIR/work"},
    {"--quiet", "-q", RC_OPT_FLAG, ARG(quiet), .help = "no progress lines"},
    {"--points", NULL, RC_OPT_FLAG, ARG(count), .heading = "render farms (tools/slurm/sweep.sh):",
     .help = "print the number of points and exit"},
    {"--point", NULL, RC_OPT_INT, ARG(point), "I", 0, 1000000,
     .help = "measure point I only (into DIR/points), for a job array"},
    {"--gather", NULL, RC_OPT_FLAG, ARG(gather),
     .help = "render nothing: write the CSV files and the plot from DIR/points"},
};
#undef ARG

static const char *const tradeoff_positional[] = {"scene"};
const rc_command_spec rc_tradeoff_spec = {
    .name = "tradeoff",
    .synopsis = "SCENE... --out DIR [options]",
    .summary = "Measures what accuracy costs on your scenes: each variant (formulas, offsets,\n"
               "camera-relative packing, precision) at each spp, timed, its first-sample\n"
               "decisions against the CPU f64 reference of the same samples and its colour\n"
               "against a CPU f64 render of --reference-spp samples. Writes DIR/tradeoff.csv\n"
               "(one row a point), DIR/tradeoff-summary.csv (per variant and spp, with the\n"
               "Pareto front), DIR/tradeoff.svg (time against decision mismatches), and prints\n"
               "the summary as a table. Scene paths are relative to the current folder.",
    .epilogue = "Exit status: 0 every point measured; 1 some point failed (its row says why);\n"
                "2 bad usage or a reference that cannot be rendered.\n",
    .min_positional = 0,
    .max_positional = MAX_SCENES,
    .positional_offset = offsetof(tradeoff_args, scenes),
    .positional_names = tradeoff_positional,
    .options = tradeoff_options,
    .option_count = sizeof tradeoff_options / sizeof *tradeoff_options,
};

typedef struct {
  tradeoff_args a;
  rc_tradeoff_variant variants[RC_TRADEOFF_MAX_VARIANTS];
  char custom_names[RC_OPT_LIST_MAX][64];
  size_t variant_count, scene_count;
  unsigned spps[RC_TRADEOFF_MAX_SPPS];
  size_t spp_count;
  char self[PATH_MAX], work[PATH_MAX], points_dir[PATH_MAX], log[PATH_MAX];
  char scene_names[MAX_SCENES][128];
} sweep;

static rc_status parse_spps(sweep *s) {
  const char *p = s->a.spp_list ? s->a.spp_list : "1,4,16";
  while (*p) {
    char *end;
    errno = 0;
    unsigned long v = strtoul(p, &end, 10);
    if (strncmp(p, "scene", 5) == 0 && (p[5] == ',' || !p[5])) v = 0, end = (char *)p + 5; /* each scene's own */
    else if (v < 1) end = (char *)p;
    if (end == p || errno || v > RC_MAX_SAMPLES_PER_PIXEL || (*end && *end != ',') ||
        s->spp_count == RC_TRADEOFF_MAX_SPPS) {
      rc_usage_error(&rc_tradeoff_spec,
                     "--spp-list: expected up to %d numbers in [1, %d] (or scene: each scene's own) separated by "
                     "commas, got '%s'", RC_TRADEOFF_MAX_SPPS, RC_MAX_SAMPLES_PER_PIXEL, s->a.spp_list);
      return RC_ERR_USAGE;
    }
    s->spps[s->spp_count++] = (unsigned)v;
    p = *end ? end + 1 : end;
  }
  return RC_OK;
}

/* Whether `name` is in the comma-separated list. */
static bool listed(const char *list, const char *name) {
  size_t n = strlen(name);
  for (const char *p = list; p && *p;) {
    const char *comma = strchr(p, ',');
    size_t len = comma ? (size_t)(comma - p) : strlen(p);
    if (len == n && strncmp(p, name, n) == 0) return true;
    p = comma ? comma + 1 : p + len;
  }
  return false;
}

static rc_status parse_variants(sweep *s) {
  const char *names = s->a.variant_names;
  for (const char *p = names; p && *p;) {
    const char *comma = strchr(p, ',');
    size_t len = comma ? (size_t)(comma - p) : strlen(p);
    bool known = false;
    for (size_t i = 0; i < BUILTIN_COUNT; i++)
      known |= strlen(builtin_variants[i].name) == len && strncmp(builtin_variants[i].name, p, len) == 0;
    if (!known) {
      const char *all[BUILTIN_COUNT];
      for (size_t i = 0; i < BUILTIN_COUNT; i++) all[i] = builtin_variants[i].name;
      char word[64];
      snprintf(word, sizeof word, "%.*s", (int)len, p);
      const char *near = rc_nearest(word, all, BUILTIN_COUNT);
      rc_usage_error(&rc_tradeoff_spec, "--variants: no variant '%s'%s%s%s", word, near ? " (did you mean " : "",
                     near ? near : "", near ? "?)" : "");
      return RC_ERR_USAGE;
    }
    p = comma ? comma + 1 : p + len;
  }
  bool builtins = names || s->a.custom.count == 0;
  for (size_t i = 0; builtins && i < BUILTIN_COUNT; i++)
    if (!names || listed(names, builtin_variants[i].name)) s->variants[s->variant_count++] = builtin_variants[i];
  for (unsigned k = 0; k < s->a.custom.count; k++) {
    const char *text = s->a.custom.item[k], *colon = strchr(text, ':');
    size_t len = colon ? (size_t)(colon - text) : 0;
    if (!colon || len == 0 || len >= sizeof s->custom_names[k] || strcspn(text, ", ") < len) {
      rc_usage_error(&rc_tradeoff_spec, "--variant: expected 'NAME: OPTIONS' (a name without spaces or commas), "
                     "got '%s'", text);
      return RC_ERR_USAGE;
    }
    snprintf(s->custom_names[k], sizeof s->custom_names[k], "%.*s", (int)len, text);
    const char *options = colon + 1 + strspn(colon + 1, " ");
    s->variants[s->variant_count++] = (rc_tradeoff_variant){s->custom_names[k], options, options};
  }
  return RC_OK;
}

/* Short names for the CSV: the file's name without its extension, numbered where two
 * scenes share one. */
static void name_scenes(sweep *s) {
  for (size_t i = 0; i < s->scene_count; i++) {
    const char *base = strrchr(s->a.scenes[i], '/');
    base = base ? base + 1 : s->a.scenes[i];
    const char *dot = strrchr(base, '.');
    int len = dot && dot != base ? (int)(dot - base) : (int)strlen(base);
    snprintf(s->scene_names[i], sizeof s->scene_names[i], "%.*s", len > 100 ? 100 : len, base);
    for (size_t j = 0; j < i; j++)
      if (strcmp(s->scene_names[i], s->scene_names[j]) == 0) {
        char numbered[128];
        snprintf(numbered, sizeof numbered, "%zu-%.100s", i + 1, s->scene_names[i]);
        snprintf(s->scene_names[i], sizeof s->scene_names[i], "%s", numbered);
        break;
      }
  }
}

static rc_status make_dir(const char *path) {
  if (mkdir(path, 0777) == 0 || errno == EEXIST) {
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) return RC_OK;
    rc_error("%s: not a folder", path);
    return RC_ERR_IO;
  }
  rc_error("%s: cannot create the folder: %s", path, strerror(errno));
  return RC_ERR_IO;
}

/* A path from a format; --out's length is checked once (setup), so none is cut short. */
static void path_of(char *out, size_t len, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(out, len, fmt, ap);
  va_end(ap);
}

static rc_status setup(int argc, char **argv, sweep *s) {
  memset(s, 0, sizeof *s);
  s->a.repeat = 3;
  s->a.reference_spp = 256;
  s->a.point = -1;
  rc_status st = rc_parse_command(&rc_tradeoff_spec, argc, argv, &s->a);
  if (st != RC_OK) return st;
  while (s->scene_count < MAX_SCENES && s->a.scenes[s->scene_count]) s->scene_count++;
  if (s->scene_count == 0) {
    rc_usage_error(&rc_tradeoff_spec, "no scene given");
    return RC_ERR_USAGE;
  }
  if (s->a.backend && strcmp(s->a.backend, "gpu") != 0 && strcmp(s->a.backend, "cpu") != 0) {
    rc_usage_error(&rc_tradeoff_spec, "--backend: expected gpu or cpu, got '%s'", s->a.backend);
    return RC_ERR_USAGE;
  }
  if ((st = parse_spps(s)) != RC_OK || (st = parse_variants(s)) != RC_OK) return st;
  name_scenes(s);
  for (size_t i = 0; !s->a.count && !s->a.gather && i < s->scene_count; i++)
    if (rc_check_input(s->a.scenes[i], "scene", NULL) != RC_OK) return RC_ERR_IO;
  ssize_t n = readlink("/proc/self/exe", s->self, sizeof s->self - 1);
  if (n <= 0) {
    rc_error("cannot find the vkraycast binary (/proc/self/exe): %s", strerror(errno));
    return RC_ERR_IO;
  }
  s->self[n] = '\0';
  if (strlen(s->a.out) > PATH_MAX / 2) {
    rc_usage_error(&rc_tradeoff_spec, "--out: a folder name of at most %d bytes", PATH_MAX / 2);
    return RC_ERR_USAGE;
  }
  path_of(s->work, sizeof s->work, "%s/work", s->a.out);
  path_of(s->points_dir, sizeof s->points_dir, "%s/points", s->a.out);
  path_of(s->log, sizeof s->log, "%s/render.log", s->work);
  if (s->a.count) return RC_OK;
  if ((st = make_dir(s->a.out)) != RC_OK || (st = make_dir(s->work)) != RC_OK ||
      (st = make_dir(s->points_dir)) != RC_OK)
    return st;
  return RC_OK;
}

/* Splits a copy of text at spaces into argv (at most max words). */
static int split_words(char *text, char **argv, int max) {
  int n = 0;
  for (char *p = strtok(text, " \t"); p && n < max; p = strtok(NULL, " \t")) argv[n++] = p;
  return n;
}

/* `vkraycast render SCENE -o OUT ...`, its stdout discarded, its stderr appended to the
 * log; returns its exit status (128 + signal when killed). */
static int run_render(const sweep *s, const char *scene, const char *out, const char *aov, const char *stats,
                      unsigned spp, const char *backend_opts, const char *variant_opts) {
  char *argv[96];
  char buf_spp[16], buf_w[16], buf_h[16], buf_repeat[16];
  char backend_copy[256], variant_copy[1024], extra_copy[1024];
  snprintf(backend_copy, sizeof backend_copy, "%s", backend_opts ? backend_opts : "");
  snprintf(variant_copy, sizeof variant_copy, "%s", variant_opts ? variant_opts : "");
  snprintf(extra_copy, sizeof extra_copy, "%s", s->a.render_args ? s->a.render_args : "");
  int n = 0;
  argv[n++] = (char *)s->self;
  argv[n++] = "render";
  argv[n++] = (char *)scene;
  argv[n++] = "-o";
  argv[n++] = (char *)out;
  argv[n++] = "--quiet";
  snprintf(buf_spp, sizeof buf_spp, "%u", spp);
  if (spp) argv[n++] = "--spp", argv[n++] = buf_spp; /* 0: the scene's own */
  if (s->a.width) snprintf(buf_w, sizeof buf_w, "%u", s->a.width), argv[n++] = "--width", argv[n++] = buf_w;
  if (s->a.height) snprintf(buf_h, sizeof buf_h, "%u", s->a.height), argv[n++] = "--height", argv[n++] = buf_h;
  if (aov) argv[n++] = "--aov", argv[n++] = (char *)aov;
  if (stats) {
    snprintf(buf_repeat, sizeof buf_repeat, "%u", s->a.repeat);
    argv[n++] = "--stats-json", argv[n++] = (char *)stats;
    argv[n++] = "--repeat", argv[n++] = buf_repeat;
  }
  n += split_words(backend_copy, argv + n, 8);
  n += split_words(variant_copy, argv + n, 32);
  n += split_words(extra_copy, argv + n, 32);
  argv[n] = NULL;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, s->log, O_WRONLY | O_CREAT | O_APPEND, 0666);
  /* The child starts with no signal blocked: this process blocks them in every thread
   * but its signal thread (cli/output.h), and a mask is inherited across exec. */
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  pid_t pid;
  int err = posix_spawn(&pid, s->self, &fa, &attr, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  if (err) {
    rc_error("cannot start %s: %s", s->self, strerror(err));
    return 127;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

static bool exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The last lines of the log, where a failed render said why. */
static void show_log_tail(const sweep *s) {
  FILE *f = fopen(s->log, "r");
  if (!f) return;
  char line[1024], last[4][1024] = {{0}};
  int n = 0;
  while (fgets(line, sizeof line, f)) snprintf(last[n++ % 4], sizeof last[0], "%s", line);
  fclose(f);
  for (int i = n > 4 ? n - 4 : 0; i < n; i++) fprintf(stderr, "    %s", last[i % 4]);
}

/* The CPU f64 renders a point is measured against, rendered once (a job array's tasks
 * may race: each renders to its own name... then the last rename wins, every copy equal). */
static rc_status reference(const sweep *s, size_t scene, unsigned spp, bool aov, char *image, char *aov_path,
                           size_t len) {
  path_of(image, len, "%s/%s.ref%u.exr", s->work, s->scene_names[scene], spp);
  if (aov) path_of(aov_path, len, "%s/%s.ref%u.aov.exr", s->work, s->scene_names[scene], spp);
  if (exists(image) && (!aov || exists(aov_path))) return RC_OK;
  int code = run_render(s, s->a.scenes[scene], image, aov ? aov_path : NULL, NULL, spp,
                        "--backend cpu --precision f64", NULL);
  if (code == 0) return RC_OK;
  rc_error("%s: the CPU f64 reference at %u spp failed (exit %d); its messages (%s):", s->a.scenes[scene], spp, code,
           s->log);
  show_log_tail(s);
  return RC_ERR_INPUT;
}

static bool read_stats(const char *path, rc_tradeoff_row *row) {
  char *text = NULL;
  size_t len = 0;
  if (rc_read_input(path, "statistics", 1 << 20, &text, &len) != RC_OK) return false;
  cJSON *j = cJSON_Parse(text);
  free(text);
  if (!j) return false;
  const cJSON *ms = cJSON_GetObjectItemCaseSensitive(j, "render_ms");
  const cJSON *wall = cJSON_GetObjectItemCaseSensitive(j, "render_wall_ms");
  const cJSON *cpu = cJSON_GetObjectItemCaseSensitive(j, "cpu_ms");
  const cJSON *prec = cJSON_GetObjectItemCaseSensitive(j, "precision");
  const cJSON *rays = cJSON_GetObjectItemCaseSensitive(j, "mrays_per_s");
  /* Certified mode re-renders its uncertified pixels on the CPU, outside the GPU's
   * timestamps (on the CPU backend render_ms holds it already): a point's time includes
   * it, as its frame does. */
  const cJSON *rerender = cJSON_GetObjectItemCaseSensitive(j, "rerender_ms");
  const cJSON *backend = cJSON_GetObjectItemCaseSensitive(j, "backend");
  bool ok = cJSON_IsNumber(ms) && cJSON_IsNumber(wall) && cJSON_IsNumber(cpu) && cJSON_IsNumber(rays);
  if (ok) {
    row->render_ms = ms->valuedouble, row->wall_ms = wall->valuedouble, row->cpu_ms = cpu->valuedouble;
    row->mrays_per_s = rays->valuedouble;
    if (cJSON_IsNumber(rerender) && cJSON_IsString(backend) && strcmp(backend->valuestring, "gpu") == 0)
      row->render_ms += rerender->valuedouble;
  }
  snprintf(row->precision, sizeof row->precision, "%s", cJSON_IsString(prec) ? prec->valuestring : "?");
  cJSON_Delete(j);
  return ok;
}

typedef struct {
  int w, h, c;
  float *px;
  char names[RC_AOV_MAX_CHANNELS][32];
  rc_aov_layout layout;
} loaded;

static bool load_image(const char *path, loaded *im) {
  char err[512];
  int n = 0;
  if (rc_image_read_named(path, &im->w, &im->h, &im->c, &im->px, im->names, RC_AOV_MAX_CHANNELS, &n, err,
                          sizeof err) != 0) {
    rc_error("%s: cannot read image: %s", path, err);
    return false;
  }
  rc_aov_find_channels(im->names, n, &im->layout);
  return true;
}

/* Decisions of the point's AOV against the reference's; its colour (the AOV's R, G, B,
 * the image's) against the many-sample reference. */
static bool measure(const char *aov, const char *ref_aov, const char *ref_colour, rc_tradeoff_row *row) {
  loaded a = {0}, b = {0}, c = {0};
  bool ok = load_image(aov, &a) && load_image(ref_aov, &b) && load_image(ref_colour, &c) && a.w == b.w &&
            a.h == b.h && a.c == b.c && a.w == c.w && a.h == c.h && c.c >= 3;
  float *rgb = ok ? rc_alloc((size_t)a.w * a.h * 3, sizeof(float), "the point's colour") : NULL;
  float *ref = ok ? rc_alloc((size_t)a.w * a.h * 3, sizeof(float), "the reference's colour") : NULL;
  ok = ok && rgb && ref;
  if (ok) {
    rc_compare_result r;
    bool colour[RC_AOV_MAX_CHANNELS] = {0};
    colour[a.layout.r] = colour[a.layout.g] = colour[a.layout.b] = true;
    rc_compare_images(a.px, b.px, a.w, a.h, a.c, colour, 0, 0, &r);
    rc_aov_compare_decisions(a.px, &a.layout, b.px, &b.layout, a.w, a.h, a.c, NULL, &r);
    double px = (double)r.pixels / 100.0;
    row->hit_pct = (double)r.hit_mismatch / px;
    row->object_pct = (double)r.object_mismatch / px;
    row->shadow_pct = (double)r.shadow_mismatch / px;
    row->mismatch_pct = row->hit_pct + row->object_pct + row->shadow_pct;
    for (size_t p = 0; p < (size_t)a.w * a.h; p++) {
      const float *x = a.px + p * a.c;
      rgb[3 * p] = x[a.layout.r], rgb[3 * p + 1] = x[a.layout.g], rgb[3 * p + 2] = x[a.layout.b];
      memcpy(ref + 3 * p, c.px + p * c.c, 3 * sizeof(float));
    }
    rc_compare_images(rgb, ref, a.w, a.h, 3, NULL, 0, 0, &r);
    row->psnr = r.psnr, row->rms = r.rms, row->max_error = r.max;
  }
  free(a.px), free(b.px), free(c.px), free(rgb), free(ref);
  return ok;
}

static size_t point_count(const sweep *s) { return s->scene_count * s->variant_count * s->spp_count; }

/* Point i (scene-major, then variant, then spp) measured into DIR/points/i.csv. */
static rc_status run_point(const sweep *s, size_t i, rc_tradeoff_row *row) {
  size_t per_scene = s->variant_count * s->spp_count;
  size_t scene = i / per_scene, v = i / s->spp_count % s->variant_count, k = i % s->spp_count;
  const rc_tradeoff_variant *var = &s->variants[v];
  memset(row, 0, sizeof *row);
  snprintf(row->scene, sizeof row->scene, "%s", s->scene_names[scene]);
  snprintf(row->variant, sizeof row->variant, "%s", var->name);
  row->spp = s->spps[k];
  row->psnr = row->rms = row->max_error = row->mrays_per_s = NAN;
  char ref_colour[PATH_MAX], ref_image[PATH_MAX], ref_aov[PATH_MAX], unused[PATH_MAX];
  rc_status st = reference(s, scene, s->a.reference_spp, false, ref_colour, unused, sizeof ref_colour);
  if (st == RC_OK) st = reference(s, scene, row->spp, true, ref_image, ref_aov, sizeof ref_image);
  if (st != RC_OK) return st;
  char image[PATH_MAX], aov[PATH_MAX], stats[PATH_MAX], backend[32];
  path_of(image, sizeof image, "%s/%s.%s.%u.exr", s->work, row->scene, var->name, row->spp);
  path_of(aov, sizeof aov, "%s/%s.%s.%u.aov.exr", s->work, row->scene, var->name, row->spp);
  path_of(stats, sizeof stats, "%s/%s.%s.%u.json", s->work, row->scene, var->name, row->spp);
  snprintf(backend, sizeof backend, "--backend %s", s->a.backend ? s->a.backend : "gpu");
  int code = run_render(s, s->a.scenes[scene], image, aov, stats, row->spp, backend, var->options);
  if (code != 0) {
    snprintf(row->status, sizeof row->status, "render failed (exit %d; see work/render.log)", code);
    fprintf(stderr, "vkraycast: warning: %s, variant %s, %u spp: the render failed (exit %d):\n", s->a.scenes[scene],
            var->name, row->spp, code);
    show_log_tail(s);
  } else if (!read_stats(stats, row) || !measure(aov, ref_aov, ref_colour, row)) {
    snprintf(row->status, sizeof row->status, "could not be measured");
  } else {
    snprintf(row->status, sizeof row->status, "ok");
  }
  if (!s->a.keep) unlink(image), unlink(aov), unlink(stats);
  char path[PATH_MAX + 32];
  path_of(path, sizeof path, "%s/%zu.csv", s->points_dir, i);
  FILE *f = fopen(path, "w");
  if (!f) {
    rc_error("%s: cannot write: %s", path, strerror(errno));
    return RC_ERR_IO;
  }
  rc_tradeoff_write_row(f, row);
  if (fclose(f) != 0) {
    rc_error("%s: cannot write: %s", path, strerror(errno));
    return RC_ERR_IO;
  }
  return RC_OK;
}

static rc_status read_point(const sweep *s, size_t i, rc_tradeoff_row *row) {
  char path[PATH_MAX + 32], line[1024];
  path_of(path, sizeof path, "%s/%zu.csv", s->points_dir, i);
  FILE *f = fopen(path, "r");
  bool ok = f && fgets(line, sizeof line, f) && rc_tradeoff_parse_row(line, row);
  if (f) fclose(f);
  if (!ok) {
    rc_error("%s: point %zu is missing or unreadable: measure it with --point %zu, then --gather again", path, i, i);
    return RC_ERR_INPUT;
  }
  return RC_OK;
}

/* DIR/tradeoff.csv, all-or-nothing like every output (written, synced, renamed). */
static rc_status write_csv(const sweep *s, const rc_tradeoff_row *rows, size_t n) {
  char *text = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  if (!f) return RC_ERR_OUT_OF_MEMORY;
  fprintf(f, "%s\n", rc_tradeoff_csv_header);
  for (size_t i = 0; i < n; i++) rc_tradeoff_write_row(f, &rows[i]);
  fclose(f);
  char path[PATH_MAX + 32], err[512];
  path_of(path, sizeof path, "%s/tradeoff.csv", s->a.out);
  rc_image_writer *w = rc_file_writer_open(path, text, len, err, sizeof err);
  free(text);
  if (!w || rc_image_writer_close(w, 1, err, sizeof err) != 0) {
    rc_error("%s: cannot write: %s", path, err);
    return RC_ERR_IO;
  }
  return RC_OK;
}

rc_status rc_cmd_tradeoff(int argc, char **argv) {
  static sweep s; /* large: the paths */
  rc_status st = setup(argc, argv, &s);
  if (st != RC_OK) return st == RC_DONE ? RC_OK : st;
  size_t n = point_count(&s);
  if (s.a.count) {
    printf("%zu\n", n);
    return RC_OK;
  }
  if (s.a.point >= 0 && (size_t)s.a.point >= n) {
    rc_usage_error(&rc_tradeoff_spec, "--point %d: there are %zu points (0..%zu)", s.a.point, n, n - 1);
    return RC_ERR_USAGE;
  }
  rc_tradeoff_row *rows = rc_alloc(n, sizeof *rows, "the trade-off's rows");
  if (!rows) return RC_ERR_OUT_OF_MEMORY;
  size_t failed = 0;
  for (size_t i = 0; st == RC_OK && i < n; i++) {
    if (s.a.gather || (s.a.point >= 0 && (size_t)s.a.point != i)) continue;
    st = run_point(&s, i, &rows[i]);
    if (st == RC_OK && !s.a.quiet)
      fprintf(stderr, "[%zu/%zu] %s, %s, %u spp: %s%.1f ms, decisions differ on %.4g %% of pixels\n", i + 1, n,
              rows[i].scene, rows[i].variant, rows[i].spp, strcmp(rows[i].status, "ok") ? "FAILED, " : "",
              rows[i].render_ms, rows[i].mismatch_pct);
  }
  if (s.a.point >= 0) {
    if (st == RC_OK && strcmp(rows[s.a.point].status, "ok") != 0) st = RC_MISMATCH;
    free(rows);
    return st;
  }
  for (size_t i = 0; st == RC_OK && i < n; i++) {
    st = read_point(&s, i, &rows[i]);
    failed += st == RC_OK && strcmp(rows[i].status, "ok") != 0;
  }
  if (st == RC_OK) st = write_csv(&s, rows, n);
  if (st == RC_OK) {
    rc_tradeoff_summary_info info = {s.variants, s.variant_count, s.scene_count,
                                     s.a.backend && strcmp(s.a.backend, "cpu") == 0 ? "the CPU reference" : "the GPU",
                                     s.a.width, s.a.height, s.a.reference_spp};
    if (rc_tradeoff_report(s.a.out, rows, n, &info, stdout) != 0) st = RC_ERR_IO;
  }
  if (st == RC_OK && !s.a.quiet)
    fprintf(stderr, "wrote %s/tradeoff.csv, %s/tradeoff-summary.csv, %s/tradeoff.svg\n", s.a.out, s.a.out, s.a.out);
  if (st == RC_OK && failed) {
    rc_error("%zu of %zu points failed: their rows in %s/tradeoff.csv say why", failed, n, s.a.out);
    st = RC_MISMATCH;
  }
  free(rows);
  return st;
}
