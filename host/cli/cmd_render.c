/* cmd_render.c: `vkraycast render`: parse the scene, apply command-line overrides,
 * pack, render on the GPU (N times with --repeat), write the image and the statistics. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/certified_marks.h"
#include "cli/cli.h"
#include "cli/options.h"
#include "gpu/gpu_render.h"
#include "scene/bvh.h"
#include "scene/light_buffer.h"
#include "cli/output.h"
#include "cli/part.h"
#include "scene/precision_budget.h"
#include "scene/prepared.h"
#include "image/image_io.h"
#include "image/levels8.h"
#include "ref/ref_render.h"
#include "scene/scene_pack.h"
#include "cli/stats.h"
#include "cli/textures.h"

/* --band-renders: at most this many perturbed re-renders in one run. */
#define RC_MAX_BAND_RENDERS 8

typedef struct {
  const char *scene; /* the positional argument; "-": standard input */
  const char *output, *stats_json, *aov;
  const char *region_text, *shard_text; /* --region, --shard */
  const char *prepared_path; /* --prepared, or the scene itself when it is a .vkrs file */
  bool prepared_given;       /* --prepared: the scene is checked against the file's digest */
  uint32_t width, height, spp, repeat, threads, perturb, band_renders, tile, plan_budget;
  int device, tile_budget_ms; /* -1: the default */
  bool quiet, srgb, staging, allow_outside_paths, flush_subnormals;
  /* RC_OPT_CHOICE indices; -1: the scene's (or the default) */
  int backend, accel, encoding, quantize, precision, sphere, triangle, offset, camera_relative, rescale, reflection_depth, shadows,
      scene_buffers, pipeline, spec_constants, light_buffers, eye_buffer, certified_rerender, certified_bound,
      gpu_encode;
  double offset_epsilon; /* 0: the scene's */
  double gamma;          /* 0: the scene's (or 2.2) */
  double exposure;       /* NAN: the scene's */
  /* derived once parsed */
  bool cpu, no_bvh, stats_stdout;
  rc_region region_asked;
  uint32_t shard_index, shard_count; /* count 0: no --shard */
  rc_part_info part;                 /* what the image's header says (part.h) */
  rc_gpu_options gpu;
  rc_load_options load;
  rc_prepared *prepared; /* open while the scene renders */
} render_args;

static const char *const off_on[] = {"off", "on", NULL};
static const char *const backends[] = {"gpu", "cpu", NULL};
static const char *const accels[] = {"bvh", "none", NULL};
static const char *const quantizers[] = {"round", "truncate", NULL};
static const char *const encodings[] = {"linear", "srgb", "gamma", NULL};
static const char *const rerenders[] = {"cpu", "none", "gpu", NULL};
/* --certified-rerender, in rerenders' order. */
enum { RERENDER_CPU, RERENDER_NONE, RERENDER_GPU };
static const char *const cert_bounds[] = {"full", "half", "zero", NULL};
static const char *const pipelines[] = {"specialized", "generic", NULL};
static const char *const spec_constants[] = {"host", "driver", NULL};
static const char *const auto_off[] = {"auto", "off", NULL};

#define ARG(field) offsetof(render_args, field)
static const rc_option render_options[] = {
    {"--output", "-o", RC_OPT_STRING, ARG(output), "OUT",
     .help = "image to write; the extension picks the format (png, exr, tif, jpg, ...);\n"
             "required, except for a .test scene with an `output` command"},
    {"--width", NULL, RC_OPT_UINT, ARG(width), "W", 1, RC_MAX_IMAGE_SIDE, .help = "override the scene's image width",
     .def = "the scene's"},
    {"--height", NULL, RC_OPT_UINT, ARG(height), "H", 1, RC_MAX_IMAGE_SIDE, .help = "override the scene's image height",
     .def = "the scene's"},
    {"--spp", NULL, RC_OPT_UINT, ARG(spp), "N", 1, RC_MAX_SAMPLES_PER_PIXEL, .help = "override samples per pixel",
     .def = "the scene's (1 when it names none)"},
    {"--backend", NULL, RC_OPT_CHOICE, ARG(backend), "B", .choices = backends,
     .help = "gpu (default: the Vulkan compute shader) or cpu (the reference renderer)"},
    {"--precision", NULL, RC_OPT_CHOICE, ARG(precision), "P", .choices = rc_precision_names,
     .help = "auto (default), f32 or f64 geometry and shading math. auto: f64 on cpu;\n"
             "on gpu f32 unless the precision-budget pass finds the scene needs f64:\n"
             "then f64 where the device has shaderFloat64, else certified\n"
             "(docs/accuracy.md). certified: f32 with\n"
             "every hit, object and shadow decision checked against its error bound,\n"
             "and the samples it cannot vouch for rendered again in f64\n"
             "(docs/numerics.md §10)"},
    {"--certified-rerender", NULL, RC_OPT_CHOICE, ARG(certified_rerender), "R", .choices = rerenders,
     .help = "--precision certified: the uncertified samples rendered again in f64\n"
             "(a pixel's all where one from sample 32 on is uncertified):\n"
             "gpu (the default on a GPU with shaderFloat64) traces just those samples\n"
             "with the f64 shader; cpu (the default elsewhere: lavapipe, the cpu\n"
             "backend) on the CPU reference; none leaves them as traced (to measure\n"
             "the certificates: the AOV's `uncertified` channel marks them)"},
    {"--certified-bound", NULL, RC_OPT_CHOICE, ARG(certified_bound), "B", .choices = cert_bounds,
     .help = "full (default); half or zero certify against half the error bound or\n"
             "none, faults to test the soundness tests with (docs/testing.md)"},
    {"--accel", NULL, RC_OPT_CHOICE, ARG(accel), "A", .choices = accels,
     .help = "bvh (default) or none: brute force over every object, for comparison"},
    {"--light-buffers", NULL, RC_OPT_CHOICE, ARG(light_buffers), "B", .choices = off_on,
     .help = "on (default) or off: a cube of cells around each of the first 8 point lights\n"
             "naming what its shadow rays can meet (Haines & Greenberg 1986); the image\n"
             "does not depend on it"},
    {"--eye-buffer", NULL, RC_OPT_CHOICE, ARG(eye_buffer), "B", .choices = off_on,
     .help = "on (default) or off: the objects projected onto the image's tiles, naming\n"
             "what each pixel's primary rays can meet; the image does not depend on it"},
    {"--gpu-encode", NULL, RC_OPT_CHOICE, ARG(gpu_encode), "E", .choices = auto_off,
     .help = "auto (default) or off: where the image is an 8-bit file and nothing else\n"
             "needs the colours as floats (no --aov, no certified re-render), the\n"
             "shader encodes each pixel into the file's levels and the host reads 4\n"
             "bytes a pixel instead of 16; the same file, byte for byte"},
    {"--threads", NULL, RC_OPT_UINT, ARG(threads), "N", 1, 1024,
     .help = "cpu backend: threads (default: all cores); the image does not depend on it"},
    {"--flush-subnormals", NULL, RC_OPT_FLAG, ARG(flush_subnormals),
     .help = "cpu backend: flush subnormal floats to zero, as GPUs may in f32\n"
             "(docs/numerics.md §1)"},
    {"--device", NULL, RC_OPT_INT, ARG(device), "N", 0, 1000,
     .help = "Vulkan device index (see `vkraycast devices`); default: discrete >\n"
             "integrated > virtual > CPU"},
    {"--encoding", NULL, RC_OPT_CHOICE, ARG(encoding), "E", .choices = encodings,
     .help = "8-bit outputs: linear (clamped; the default), srgb (the transfer\n"
             "curve) or gamma (a pure power, --gamma); overrides image.encoding"},
    {"--srgb", NULL, RC_OPT_FLAG, ARG(srgb), .help = "--encoding srgb (where both are given, --encoding rules)"},
    {"--gamma", NULL, RC_OPT_REAL, ARG(gamma), "G", RC_MIN_GAMMA, RC_MAX_GAMMA,
     .help = "--encoding gamma with this exponent: 8-bit outputs store c^(1/G)\n"
             "(default: the scene's image.gamma, else 2.2)"},
    {"--exposure", NULL, RC_OPT_REAL, ARG(exposure), "E", -RC_MAX_EXPOSURE, RC_MAX_EXPOSURE,
     .help = "8-bit outputs scale the linear value by 2^E before the curve (stops;\n"
             "default: the scene's image.exposure, else 0); float outputs keep it"},
    {"--quantize", NULL, RC_OPT_CHOICE, ARG(quantize), "Q", .choices = quantizers,
     .help = "8-bit outputs: round (JSON scenes' default) or truncate (.test scenes');\n"
             "overrides the scene's image.quantize"},
    {"--repeat", NULL, RC_OPT_UINT, ARG(repeat), "N", 1, 1000,
     .help = "render N frames; statistics report the first and the median of the rest", .def = "1"},
    {"--stats-json", NULL, RC_OPT_STRING, ARG(stats_json), "FILE",
     .help = "write the statistics as one JSON object (- : standard output)"},
    {"--aov", NULL, RC_OPT_STRING, ARG(aov), "FILE.exr",
     .help = "also write the decision outputs of each pixel's first sample: colour,\n"
             "hit, object, t, normal, shadow bits per light (see docs/gpu-vs-cpu.md)"},
    {"--quiet", "-q", RC_OPT_FLAG, ARG(quiet), .help = "no progress or summary on stderr"},
    {"--prepared", NULL, RC_OPT_STRING, ARG(prepared_path), "FILE.vkrs",
     .help = "render from FILE.vkrs (`vkraycast prepare SCENE`): its packed arrays and\n"
             "BVH, mapped, instead of parsing SCENE and building the tree; refused\n"
             "when SCENE or a file it reads changed since (SCENE FILE.vkrs alone\n"
             "renders the file without that check); the same image, bit for bit"},
    {"--allow-outside-paths", NULL, RC_OPT_FLAG, ARG(allow_outside_paths),
     .help = "let meshes (and the files a mesh names) and textures lie outside the\n"
             "scene file's folder; off by default, so an untrusted scene cannot\n"
             "read other files into the image"},
    {"--region", NULL, RC_OPT_STRING, ARG(region_text), "X0,Y0,X1,Y1",
     .heading = "render farms (docs/cluster.md):",
     .help = "render only columns [X0, X1) and rows [Y0, Y1) of the frame (pbrt's crop\n"
             "window, in pixels); its pixels are bit-identical to the whole frame's"},
    {"--shard", NULL, RC_OPT_STRING, ARG(shard_text), "I/N",
     .help = "render shard I of N (0 <= I < N): bands of rows, and tiles where a row\n"
             "outweighs a shard, cut by an estimate of their cost; write it as .exr and\n"
             "join the N parts with `vkraycast merge`"},
    {"--sphere", NULL, RC_OPT_CHOICE, ARG(sphere), "F", .choices = rc_sphere_formula_names,
     .heading = "speed against accuracy (docs/accuracy.md; each overrides the scene's `quality`):",
     .help = "geometric (default) or algebraic ray/sphere formula"},
    {"--triangle", NULL, RC_OPT_CHOICE, ARG(triangle), "F", .choices = rc_triangle_formula_names,
     .help = "watertight (default), moller-trumbore or cramer ray/triangle test"},
    {"--shadow-offset", NULL, RC_OPT_CHOICE, ARG(offset), "S", .choices = rc_offset_names,
     .help = "error-bound (default), ulp, epsilon or t-min: where shadow/reflection\n"
             "rays start (t-min: at the hit, ignoring hits nearer than the epsilon)"},
    {"--shadow-epsilon", NULL, RC_OPT_REAL, ARG(offset_epsilon), "E", 0, 3.4e38, .flags = RC_OPT_LO_OPEN | RC_OPT_F32,
     .help = "the epsilon strategy's offset in scene units (default 1e-4)"},
    {"--camera-relative", NULL, RC_OPT_CHOICE, ARG(camera_relative), "B", .choices = off_on,
     .help = "on (default) or off: positions relative to the eye before f32 rounding"},
    {"--rescale", NULL, RC_OPT_CHOICE, ARG(rescale), "B", .choices = off_on,
     .help = "on (default) or off: pack a scene far from unit size in power-of-two units"},
    {"--reflection-depth", NULL, RC_OPT_INT, ARG(reflection_depth), "N", 0, RC_MAX_REFLECTION_DEPTH,
     .help = "mirror bounces", .def = "the scene's (JSON: 5; .test: maxdepth - 1, 4 when absent)"},
    {"--shadows", NULL, RC_OPT_CHOICE, ARG(shadows), "B", .choices = off_on,
     .help = "on (default) or off: trace shadow rays"},
    {"--scene-buffers", NULL, RC_OPT_CHOICE, ARG(scene_buffers), "K", .choices = rc_scene_buffer_names,
     .heading = "tuning and testing:", .help = "image (default: storage texel buffers), texel (uniform texel\n"
             "buffers) or storage: how the shader reads the scene arrays"},
    {"--pipeline", NULL, RC_OPT_CHOICE, ARG(pipeline), "P", .choices = pipelines,
     .help = "specialized (default: compiled for this scene's primitive kinds, light\n"
             "count, shadows, specular model and bounces) or generic (one pipeline\n"
             "for every scene; to measure what specializing buys)"},
    {"--spec-constants", NULL, RC_OPT_CHOICE, ARG(spec_constants), "W", .choices = spec_constants,
     .help = "host (default: SPIRV-Tools applies the pipeline's specialization\n"
             "constants and drops the code they rule out before the driver compiles)\n"
             "or driver (the driver specializes the whole module; to compare the two)"},
    {"--staging", NULL, RC_OPT_FLAG, ARG(staging),
     .help = "upload and read back through staging buffers even on unified memory\n"
             "(also VKRAYCAST_FORCE_STAGING=1)"},
    {"--tile-budget-ms", NULL, RC_OPT_INT, ARG(tile_budget_ms), "T", 0, 60000,
     .help = "the longest one dispatch (one submit) should run: tiles adapt to it;\n"
             "0: no limit (default: none on a CPU device such as lavapipe, which\n"
             "no watchdog resets; 100 elsewhere, as real GPUs reset after ~2 s)"},
    {"--tile", NULL, RC_OPT_UINT, ARG(tile), "N", 8, 4096, .help = "fixed N x N tiles instead of adaptive ones"},
    {"--perturb", NULL, RC_OPT_UINT, ARG(perturb), "SEED", 1, UINT32_MAX,
     .help = "scale every packed position and radius by 1 + d, |d| <= 2^-22, d a hash\n"
             "of SEED and the value (equal values move alike: meshes stay closed); its\n"
             "renders give `compare --band` the conditioning band"},
    {"--band-renders", NULL, RC_OPT_UINT, ARG(band_renders), "N", 1, RC_MAX_BAND_RENDERS,
     .help = "after OUT, render the conditioning band too: N re-renders with seeds\n"
             "1..N of --perturb, written beside OUT (and --aov FILE) as NAME.bandK.EXT,\n"
             "in this one process (for `compare --band`)"},
    {"--plan-budget", NULL, RC_OPT_UINT, ARG(plan_budget), "N", 1, UINT32_MAX,
     .help = "loop budget the host plans batches with (default: the shader's, 49152\n"
             "divided by the subgroup size on llvmpipe); larger values test the\n"
             "shader's exhaustion flag, smaller ones smaller light passes"},
};
#undef ARG

static const char *const render_positional[] = {"scene file (SCENE, or - for standard input)"};
const rc_command_spec rc_render_spec = {
    .name = "render",
    .synopsis = "SCENE -o OUT [options]",
    .summary = "Renders SCENE (.json, or .test; - reads it from standard input) to the image OUT.",
    .epilogue = "Exit status: 0 written; 2 bad input or usage (nothing written); 3 device or memory failure.\n",
    .min_positional = 1,
    .max_positional = 1,
    .positional_offset = offsetof(render_args, scene),
    .positional_names = render_positional,
    .options = render_options,
    .option_count = sizeof render_options / sizeof *render_options,
};

static bool is_exr(const char *path) { return rc_has_extension(path, ".exr"); }

/* OUT with ".bandK" before the extension of its last component (x.exr: x.band2.exr). */
static bool band_path(const char *path, uint32_t k, char *out, size_t cap) {
  const char *slash = strrchr(path, '/');
  const char *dot = strrchr(slash ? slash + 1 : path, '.');
  size_t stem = dot ? (size_t)(dot - path) : strlen(path);
  int len = snprintf(out, cap, "%.*s.band%u%s", (int)stem, path, k, dot ? dot : "");
  return len > 0 && (size_t)len < cap;
}

/* The run's files as rc_check_distinct's roles: the scene and the prepared scene (the
 * inputs), then the outputs: the image, the AOV file, the statistics, and each band
 * render's image and AOV file (their names written into names). Returns the count; 0
 * after saying that a band render's name is too long. */
#define RUN_FIXED_FILES 5
#define RUN_FILES_MAX (RUN_FIXED_FILES + 2 * RC_MAX_BAND_RENDERS)
static size_t run_files(const render_args *a, rc_file_role files[RUN_FILES_MAX],
                        char names[2 * RC_MAX_BAND_RENDERS][PATH_MAX]) {
  files[0] = (rc_file_role){strcmp(a->scene, "-") ? a->scene : NULL, "the scene file", false};
  files[1] = (rc_file_role){a->prepared_given ? a->prepared_path : NULL, "the prepared scene", false};
  files[2] = (rc_file_role){a->output, "the image", true};
  files[3] = (rc_file_role){a->aov, "the AOV file", true};
  files[4] = (rc_file_role){a->stats_stdout ? NULL : a->stats_json, "the statistics", true};
  size_t n = RUN_FIXED_FILES;
  static const char *const band_roles[2] = {"a band image", "a band AOV file"};
  const char *base[2] = {a->output, a->aov};
  for (uint32_t k = 1; k <= a->band_renders; k++)
    for (int f = 0; f < 2 && base[f]; f++) {
      char *name = names[n - RUN_FIXED_FILES];
      if (!band_path(base[f], k, name, PATH_MAX)) {
        rc_error("%s: too long a name for its band renders (--band-renders)", base[f]);
        return 0;
      }
      files[n++] = (rc_file_role){name, band_roles[f], true};
    }
  return n;
}

/* Every output is checked before the scene is read: an existing special file or folder,
 * a missing folder, two roles naming one file (band renders' files included, each
 * checked like OUT itself: a folder named NAME.bandK.EXT would otherwise fail the band
 * render after OUT had landed), and a name no image format writes. */
static rc_status check_outputs(const render_args *a) {
  if (strcmp(a->output, "-") == 0) {
    rc_usage_error(&rc_render_spec, "-o -: images are not written to standard output (a renamed temporary file is what "
                                    "keeps a failed run from leaving half an image); name a file");
    return RC_ERR_USAGE;
  }
  if (a->aov && strcmp(a->aov, "-") == 0) {
    rc_usage_error(&rc_render_spec, "--aov -: the AOV file is not written to standard output; name a .exr file");
    return RC_ERR_USAGE;
  }
  rc_file_role files[RUN_FILES_MAX];
  char band_names[2 * RC_MAX_BAND_RENDERS][PATH_MAX];
  size_t n = run_files(a, files, band_names);
  if (n == 0) return RC_ERR_USAGE;
  for (size_t i = 0; i < n; i++)
    if (files[i].output && files[i].path && rc_check_output(files[i].path, files[i].role) != RC_OK) return RC_ERR_IO;
  if (rc_check_distinct(files, n) != RC_OK) return RC_ERR_USAGE;
  if (a->aov && !is_exr(a->aov)) {
    rc_error("--aov %s: the decision outputs need a multi-channel float file: name it .exr", a->aov);
    return RC_ERR_USAGE;
  }
  /* Before the scene and its meshes are read, a name no format writes costs nothing; a
   * common one is checked after (rc_cmd_render), so that a refused scene costs no module. */
  return rc_output_check_format_early(a->output);
}

static rc_status check_output_args(const render_args *a);

static rc_status parse_args(int argc, char **argv, render_args *a) {
  memset(a, 0, sizeof *a);
  a->device = a->tile_budget_ms = -1;
  a->repeat = 1;
  a->exposure = NAN;
  a->backend = a->accel = a->encoding = a->quantize = a->precision = a->sphere = a->triangle = a->offset =
      a->camera_relative = a->rescale = a->reflection_depth = a->shadows = a->scene_buffers = a->pipeline =
          a->spec_constants = a->light_buffers = a->eye_buffer = a->certified_rerender = a->certified_bound = a->gpu_encode = -1;
  rc_status st = rc_parse_command(&rc_render_spec, argc, argv, a);
  if (st != RC_OK) return st;
  a->cpu = a->backend == 1;
  a->no_bvh = a->accel == 1;
  a->stats_stdout = a->stats_json && strcmp(a->stats_json, "-") == 0;
  /* The choices are listed in rc_scene_buffers' order; the default is the first. */
  a->gpu.scene_buffers = a->scene_buffers < 0 ? RC_SCENE_BUFFERS_IMAGE : (rc_scene_buffers)a->scene_buffers;
  a->gpu.tile_size = a->tile;
  a->gpu.tile_budget_ms = a->tile_budget_ms; /* -1: the device's default (gpu_render.c) */
  a->gpu.plan_budget = a->plan_budget;
  a->gpu.generic_pipeline = a->pipeline == 1;
  a->gpu.driver_spec_constants = a->spec_constants == 1;
  const char *force = getenv("VKRAYCAST_FORCE_STAGING");
  a->gpu.force_staging = a->staging || (force && force[0] && strcmp(force, "0") != 0);
  a->load.allow_outside_paths = a->allow_outside_paths;
  const char *why = NULL;
  char msg[300];
  if (a->gamma > 0 && (a->encoding >= 0 ? a->encoding != RC_CURVE_GAMMA : a->srgb)) {
    rc_usage_error(&rc_render_spec, "--gamma is the exponent of --encoding gamma; it does not go with another encoding");
    return RC_ERR_USAGE;
  }
  if (a->region_text && a->shard_text) {
    rc_usage_error(&rc_render_spec, "--region and --shard: a shard is already a region of the frame; give one");
    return RC_ERR_USAGE;
  }
  if (a->region_text && !rc_region_parse(a->region_text, &a->region_asked, &why)) {
    snprintf(msg, sizeof msg, "--region %s: %s", a->region_text, why);
    rc_usage_error(&rc_render_spec, "%s", msg);
    return RC_ERR_USAGE;
  }
  if (a->shard_text && !rc_shard_parse(a->shard_text, &a->shard_index, &a->shard_count, &why)) {
    snprintf(msg, sizeof msg, "--shard %s: %s", a->shard_text, why);
    rc_usage_error(&rc_render_spec, "%s", msg);
    return RC_ERR_USAGE;
  }
  if (a->flush_subnormals && (!a->cpu || !rc_ref_can_flush_subnormals())) {
    rc_usage_error(&rc_render_spec, a->cpu ? "--flush-subnormals: this CPU has no flush-to-zero mode the reference knows"
                                           : "--flush-subnormals is for --backend cpu: a GPU's mode is its own");
    return RC_ERR_USAGE;
  }
  a->prepared_given = a->prepared_path != NULL;
  if (rc_has_extension(a->scene, RC_PREPARED_EXTENSION)) {
    if (a->prepared_given) {
      rc_usage_error(&rc_render_spec, "%s is a prepared scene already; --prepared goes with the scene file it was "
                     "prepared from", a->scene);
      return RC_ERR_USAGE;
    }
    a->prepared_path = a->scene;
  } else if (a->prepared_given && strcmp(a->scene, "-") == 0) {
    rc_usage_error(&rc_render_spec, "--prepared with - (standard input): the prepared scene is checked against its "
                                    "scene file; name the file, or render %s alone", a->prepared_path);
    return RC_ERR_USAGE;
  } else if (a->prepared_given && !rc_has_extension(a->prepared_path, RC_PREPARED_EXTENSION)) {
    rc_usage_error(&rc_render_spec, "--prepared %s: a prepared scene is a .vkrs file (`vkraycast prepare`)",
                   a->prepared_path);
    return RC_ERR_USAGE;
  }
  if (a->band_renders && a->perturb) {
    rc_usage_error(&rc_render_spec, "--band-renders and --perturb: the band renders take seeds 1..N themselves; give one");
    return RC_ERR_USAGE;
  }
  if (!a->output) {
    /* A .test scene may name its image (its `output` command): read once it is loaded. */
    if (strcmp(a->scene, "-") == 0 || rc_has_extension(a->scene, ".test") || a->prepared_path) return RC_OK;
    rc_usage_error(&rc_render_spec, "no output file given (-o OUT)");
    return RC_ERR_USAGE;
  }
  return check_output_args(a);
}

/* The outputs, every one checked before the scene is read (or, for a .test scene's own
 * `output`, before anything else is). */
static rc_status check_output_args(const render_args *a) {
  if (a->shard_text && !is_exr(a->output)) {
    char msg[PATH_MAX + 200];
    snprintf(msg, sizeof msg,
             "--shard %s -o %s: a shard is a part for `vkraycast merge`, which needs its float pixels and its "
             "header: name it .exr",
             a->shard_text, a->output);
    rc_usage_error(&rc_render_spec, "%s", msg);
    return RC_ERR_USAGE;
  }
  return check_outputs(a);
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Median of frames 2..N (the steady state), or the only frame. */
static double steady(double *v, uint32_t n) {
  if (n == 1) return v[0];
  qsort(v + 1, n - 1, sizeof *v, cmp_double);
  return v[1 + (n - 1) / 2];
}

/* Frames 1..N-1 are rendered and dropped; the last one streams into the output files. */
/* 8-bit output: the command line's choices, else the scene's. */
_Static_assert(RC_SCENE_ENCODING_LINEAR == (int)RC_CURVE_LINEAR && RC_SCENE_ENCODING_SRGB == (int)RC_CURVE_SRGB &&
                   RC_SCENE_ENCODING_GAMMA == (int)RC_CURVE_GAMMA,
               "image.encoding's names in the order of rc_curve");
static rc_encoding output_encoding(const render_args *a, const rc_scene *s) {
  rc_encoding e = rc_encoding_linear();
  e.curve = a->encoding >= 0 ? (rc_curve)a->encoding
            : a->gamma > 0   ? RC_CURVE_GAMMA
            : a->srgb        ? RC_CURVE_SRGB
                             : (rc_curve)s->encoding_8bit;
  e.gamma = (float)(a->gamma > 0 ? a->gamma : s->gamma_8bit > 0 ? s->gamma_8bit : RC_DEFAULT_GAMMA);
  e.exposure = (float)(isnan(a->exposure) ? s->exposure_8bit : a->exposure);
  return e;
}
static bool truncate_output(const render_args *a, const rc_scene *s) {
  return a->quantize < 0 ? s->truncate_8bit : a->quantize == 1;
}

static rc_status open_output(const render_args *a, const rc_scene *scene, const rc_packed_scene *packed,
                             rc_output **out) {
  rc_image_meta meta[RC_PART_FIELDS];
  char text[RC_PART_FIELDS][64];
  int n = rc_part_meta(&a->part, meta, text);
  const rc_region r = a->part.region;
  rc_status st = rc_output_open(a->output, a->aov, rc_region_width(r), rc_region_height(r),
                        output_encoding(a, scene), truncate_output(a, scene),
                        meta, n, out);
  if (st == RC_OK) rc_output_set_length_unit(*out, 1.0 / packed->scale);
  return st;
}

/* --precision certified on the GPU: before a band is written (or dropped), its pixels with an
 * uncertified sample are rendered again on the f64 CPU reference (--certified-rerender cpu). */
typedef struct {
  const render_args *a;
  const rc_packed_scene *packed;
  rc_band_fn next;
  void *next_user;
  float *rgb;
  packed_aov *aov;
  size_t capacity; /* pixels */
  rc_ref_stats stats;
  rc_gpu_renderer *f64;   /* --certified-rerender gpu: the f64 renderer */
  rc_gpu_stats f64_stats;
} certified_sink;

/* A band of the GPU's f64 re-render (rc_gpu_renderer_rerender): its traced pixels, those
 * the f32 pass left uncertified, replace the f32 pass's; y0 counts from the re-rendered
 * band's first row, which is the sink's. */
static rc_status rerendered_band(uint32_t y0, uint32_t rows, const float *rgb, const uint8_t *levels,
                                 const packed_aov *aov, void *user) {
  (void)levels; /* a re-render reads sums */
  certified_sink *c = user;
  const size_t width = rc_region_width(c->a->part.region), first = (size_t)y0 * width;
  const uint32_t spp = c->packed->frame.samples_per_pixel;
  for (size_t i = 0; i < (size_t)rows * width; i++) {
    packed_aov *mark = &c->aov[first + i];
    if (!(mark->uncertified > 0)) continue;
    memcpy(&c->rgb[3 * (first + i)], &rgb[3 * i], 3 * sizeof *rgb);
    /* The record is sample 0's: the re-render's where it traced sample 0, else the f32
     * pass's, certified. The marks stay. */
    if (rc_aov_rerenders(mark, 0)) {
      packed_aov marks = *mark;
      *mark = aov[i];
      rc_aov_keep_marks(mark, &marks);
    }
    /* The digest of every sample's decisions: the certified samples' (the marks carried it
     * into the re-render) and the re-rendered ones'. */
    mark->decisions = aov[i].decisions;
    c->stats.pixels_rerendered++;
    c->stats.samples_rerendered += rc_aov_samples_rerendered(mark, spp);
  }
  return RC_OK;
}

static rc_status certified_band(uint32_t y0, uint32_t rows, const float *rgb, const uint8_t *levels,
                                const packed_aov *aov, void *user) {
  (void)levels; /* certified renders read sums (encode_on_gpu) */
  certified_sink *c = user;
  const rc_region r = c->a->part.region;
  size_t n = (size_t)rc_region_width(r) * rows;
  if (n > c->capacity) {
    free(c->rgb);
    free(c->aov);
    c->rgb = rc_alloc(n * 3, sizeof(float), "one band of the image");
    c->aov = rc_alloc(n, sizeof(packed_aov), "one band of AOVs");
    c->capacity = c->rgb && c->aov ? n : 0;
    if (!c->capacity) return RC_ERR_OUT_OF_MEMORY;
  }
  memcpy(c->rgb, rgb, n * 3 * sizeof(float));
  memcpy(c->aov, aov, n * sizeof(packed_aov));
  for (size_t i = 0; i < n; i++) c->stats.samples_uncertified += (uint64_t)aov[i].uncertified;
  rc_region band = {r.x0, r.y0 + y0, r.x1, r.y0 + y0 + rows};
  if (c->a->certified_rerender == RERENDER_CPU) {
    rc_ref_options opts = {.f64 = true, .threads = c->a->threads};
    rc_status st = rc_ref_rerender(c->packed, &opts, band, c->rgb, c->aov, &c->stats);
    if (st != RC_OK) return st;
  } else if (c->a->certified_rerender == RERENDER_GPU) {
    double t0 = rc_now_ms();
    rc_status st = rc_gpu_renderer_rerender(c->f64, band, aov, rerendered_band, c, &c->f64_stats);
    c->stats.rerender_ms += rc_now_ms() - t0;
    if (st != RC_OK) return st;
  }
  return c->next(y0, rows, c->rgb, NULL, c->a->aov ? c->aov : NULL, c->next_user);
}

_Static_assert(RC_LEVELS == RC_LEVEL_COUNT, "levels8.h's table is packed_levels.sum_threshold");
_Static_assert(RC_LEVEL_CURVE_LINEAR == (int)RC_CURVE_LINEAR && RC_LEVEL_CURVE_SRGB == (int)RC_CURVE_SRGB &&
                   RC_LEVEL_CURVE_GAMMA == (int)RC_CURVE_GAMMA,
               "RC_SPEC_LEVELS names an rc_curve");

/* --gpu-encode auto: whether the shader can encode the image into its file's 8-bit levels:
 * the file stores them, and nothing but the file needs the frame's colours (the AOV file
 * packs them as floats, a certified render replaces re-rendered pixels in them). */
static bool encode_on_gpu(const render_args *a, const rc_packed_scene *packed) {
  return a->gpu_encode != 1 && a->output && !a->aov && packed->frame.certify == RC_CERTIFY_OFF &&
         rc_image_stores_levels(a->output) == 1;
}

/* What the shader encodes a pixel's sum of spp samples with: the writer's table for the
 * output's encoding (levels8.h) moved to sums, which decides, and the curve (*curve, a
 * specialization constant), which only tells the shader where to look in it. False where
 * the table cannot go to the GPU, and the host encodes: a GPU may flush subnormal operands
 * to zero (docs/numerics.md §1), which would move a threshold to 0. Level 1's is the least,
 * (1/510)^gamma of white over 2^exposure: a normal float up to a gamma of about 14 (at
 * exposure 0), and --gamma goes to 100. */
static bool shader_levels(const render_args *a, const rc_scene *scene, uint32_t spp, packed_levels *out,
                          uint32_t *curve) {
  const rc_encoding enc = output_encoding(a, scene);
  const bool truncate = truncate_output(a, scene);
  rc_levels values, sums;
  rc_levels_make(enc, truncate, &values);
  rc_levels_of_sums(&values, spp, &sums);
  for (int k = 1; k < RC_LEVELS; k++)
    if (!(sums.threshold[k] >= FLT_MIN)) return false;
  memcpy(out->sum_threshold, sums.threshold, sizeof out->sum_threshold);
  out->value_scale = exp2f(enc.exposure) / (float)spp;
  out->inv_gamma = 1.0f / enc.gamma;
  out->bias = truncate ? 0.0f : 0.5f;
  *curve = (uint32_t)enc.curve;
  return true;
}

static rc_status render_frames(const render_args *a, rc_vk_ctx *ctx, const rc_scene *scene,
                               const rc_packed_scene *packed, rc_render_stats *rs, rc_output **out) {
  rc_gpu_renderer *r = NULL;
  const bool certified = packed->frame.certify != RC_CERTIFY_OFF;
  certified_sink sink = {.a = a, .packed = packed};
  rc_gpu_options opts = a->gpu;
  opts.progress = !a->quiet && isatty(STDERR_FILENO);
  packed_levels levels = {0};
  if (encode_on_gpu(a, packed) && shader_levels(a, scene, packed->frame.samples_per_pixel, &levels, &opts.level_curve))
    opts.levels = &levels;
  rc_status st = rc_gpu_renderer_create(ctx, packed, &opts, &r, &rs->gpu);
  if (st == RC_OK && certified && a->certified_rerender == RERENDER_GPU) {
    /* The re-render's renderer: the f64 module, no certificates, records on (they carry the
     * marks), over the same region. */
    rc_packed_scene plain = *packed;
    plain.frame.certify = RC_CERTIFY_OFF;
    rc_gpu_options o64 = opts;
    o64.f64 = true, o64.aov = true, o64.progress = false, o64.levels = NULL;
    st = rc_gpu_renderer_create(ctx, &plain, &o64, &sink.f64, &sink.f64_stats);
  }
  double *gpu_ms = calloc(a->repeat, sizeof *gpu_ms), *wall_ms = calloc(a->repeat, sizeof *wall_ms);
  if (!gpu_ms || !wall_ms) st = RC_ERR_OUT_OF_MEMORY;
  for (uint32_t i = 0; st == RC_OK && i < a->repeat; i++) {
    bool last = i + 1 == a->repeat;
    if (last) st = open_output(a, scene, packed, out);
    rc_band_fn band = last ? rc_output_band : rc_output_discard;
    void *user = last ? *out : NULL;
    if (certified) {
      sink.next = band, sink.next_user = user;
      memset(&sink.stats, 0, sizeof sink.stats);
      band = certified_band, user = &sink;
    }
    /* The last frame streams its bands into the output files from inside the render; that
     * time is the write's (write_ms), not the frame's, as on the CPU backend, whose frame
     * time stops before its bands are written. Counted in both, it made the steady frame
     * of a 2- or 3-frame --repeat (steady() takes the later of frames 2 and 3) the
     * frame plus the write. The certified re-render in the sink stays in the frame, and so
     * does the part of a band's write that the next band's dispatch ran beside
     * (band_hidden_ms): the frame would have taken that time without the write. Counting
     * the whole of such writes in, the frame of a one-frame 4K PNG on an H200 read 240 ms,
     * 225 of them zlib's, beside 1.3 ms of shader. (No output yet, or a discarded frame: no
     * write time, and rc_output_write_ms of NULL is 0.) */
    double written = rc_output_write_ms(*out);
    if (st == RC_OK) st = rc_gpu_renderer_render(r, band, user, &rs->gpu);
    gpu_ms[i] = rs->gpu.gpu_ms;
    double write_ms = rc_output_write_ms(*out) - written;
    double hidden = rs->gpu.band_hidden_ms < write_ms ? rs->gpu.band_hidden_ms : write_ms;
    wall_ms[i] = rs->gpu.render_ms - (write_ms - hidden);
  }
  if (st == RC_OK) {
    rs->first_frame_ms = wall_ms[0];
    rs->render_ms = steady(gpu_ms, a->repeat);
    rs->render_wall_ms = steady(wall_ms, a->repeat);
    rs->rays_shadow = rs->gpu.shadow_rays;
    rs->rays_reflection = rs->gpu.reflection_rays;
    rs->patch_unconverged = rs->gpu.patch_stalls;
    rs->patch_stall_object = rs->gpu.patch_stall_object;
    rs->patch_stall_x = rs->gpu.patch_stall_x, rs->patch_stall_y = rs->gpu.patch_stall_y;
    rs->samples_uncertified = sink.stats.samples_uncertified;
    memcpy(rs->uncertified_at, rs->gpu.uncertified_at, sizeof rs->uncertified_at);
    rs->pixels_rerendered = sink.stats.pixels_rerendered;
    rs->samples_rerendered = sink.stats.samples_rerendered;
    rs->rerender_ms = sink.stats.rerender_ms;
  }
  free(sink.rgb);
  free(sink.aov);
  rc_gpu_renderer_destroy(sink.f64);
  free(gpu_ms);
  free(wall_ms);
  rc_gpu_renderer_destroy(r);
  return st;
}

static void report_crossings(const rc_scene *s, uint32_t object, uint32_t x, uint32_t y);

/* The CPU reference in bands of CPU_BAND_ROWS rows, in f64 or f32 (rc_precision_choose). */
#define CPU_BAND_ROWS 32u

static rc_status render_frames_cpu(const render_args *a, const rc_scene *scene, const rc_packed_scene *packed,
                                   bool f64, rc_render_stats *rs, rc_output **out) {
  const bool certified = packed->frame.certify != RC_CERTIFY_OFF;
  rc_ref_options opts = {.f64 = f64, .threads = a->threads, .flush_subnormals = a->flush_subnormals};
  const rc_region region = a->part.region;
  uint32_t w = rc_region_width(region), h = rc_region_height(region);
  uint32_t band = h < CPU_BAND_ROWS ? h : CPU_BAND_ROWS;
  double *ms = calloc(a->repeat, sizeof *ms);
  float *rgb = rc_alloc((size_t)w * band * 3, sizeof(float), "one band of the image");
  /* Certified renders count each pixel's uncertified samples in its record. */
  const bool records = a->aov || certified;
  packed_aov *aov = records ? rc_alloc((size_t)w * band, sizeof *aov, "one band of AOVs") : NULL;
  rc_status st = ms && rgb && (!records || aov) ? RC_OK : RC_ERR_OUT_OF_MEMORY;
  rc_ref_stats last_stats = {0};
  for (uint32_t i = 0; st == RC_OK && i < a->repeat; i++) {
    bool last = i + 1 == a->repeat;
    rc_ref_stats fs = {0};
    if (last) st = open_output(a, scene, packed, out);
    for (uint32_t y0 = 0; st == RC_OK && y0 < h; y0 += band) {
      uint32_t rows = h - y0 < band ? h - y0 : band;
      rc_region part = {region.x0, region.y0 + y0, region.x1, region.y0 + y0 + rows};
      st = rc_ref_render(packed, &opts, part, rgb, aov, &fs);
      if (st == RC_OK && certified && a->certified_rerender == RERENDER_CPU)
        st = rc_ref_rerender(packed, &opts, part, rgb, aov, &fs);
      if (st == RC_ERR_TOO_LARGE) report_crossings(scene, fs.crossing_object, fs.crossing_x, fs.crossing_y);
      if (st == RC_OK && last) st = rc_output_band(y0, rows, rgb, NULL, a->aov ? aov : NULL, *out);
    }
    ms[i] = fs.render_ms;
    last_stats = fs;
  }
  if (st == RC_OK) {
    rs->first_frame_ms = ms[0];
    rs->render_ms = rs->render_wall_ms = steady(ms, a->repeat);
    rs->rays_shadow = last_stats.shadow_rays;
    rs->rays_reflection = last_stats.reflection_rays;
    rs->patch_unconverged = last_stats.patch_stalls;
    rs->patch_stall_object = last_stats.patch_stall_object;
    rs->patch_stall_x = last_stats.patch_stall_x, rs->patch_stall_y = last_stats.patch_stall_y;
    rs->threads = last_stats.threads;
    rs->simd8_efficiency = last_stats.vector_steps ? (double)last_stats.lane_steps / last_stats.vector_steps : 1;
    rs->samples_uncertified = last_stats.samples_uncertified;
    memcpy(rs->uncertified_at, last_stats.uncertified_at, sizeof rs->uncertified_at);
    rs->pixels_rerendered = last_stats.pixels_rerendered;
    rs->samples_rerendered = last_stats.samples_rerendered;
    rs->rerender_ms = last_stats.rerender_ms;
  }
  free(ms);
  free(rgb);
  free(aov);
  return st;
}

static void apply_quality_overrides(const render_args *a, rc_scene *s) {
  rc_quality *q = &s->quality;
  if (a->sphere >= 0) q->sphere = (uint32_t)a->sphere;
  if (a->triangle >= 0) q->triangle = (uint32_t)a->triangle;
  if (a->offset >= 0) q->offset = (uint32_t)a->offset;
  if (a->camera_relative >= 0) q->camera_relative = a->camera_relative == 1;
  if (a->rescale >= 0) q->rescale = a->rescale == 1;
  if (a->offset_epsilon > 0) q->offset_epsilon = a->offset_epsilon;
  if (a->reflection_depth >= 0) s->reflection_depth = (uint32_t)a->reflection_depth;
  if (a->shadows >= 0) q->shadows = a->shadows == 1;
}

/* The precision-budget findings, once, before rendering (precision_budget.h). */
static void report_budget(const rc_scene *s, const rc_precision_report *b) {
  if (b->needs_f64)
    fprintf(stderr, "%s: warning: precision: %u object(s) need more than f32 arithmetic, first %s\n", s->path,
            b->needs_f64, b->first_f64);
  if (b->quantized)
    fprintf(stderr,
            "%s: warning: precision: rounding positions to f32 moves %u object(s) by more than %g of their size, "
            "first %s; no shader precision restores this: bring the scene nearer the origin%s\n",
            s->path, b->quantized, RC_BUDGET_QUANTIZATION, b->first_quantized,
            s->quality.camera_relative ? "" : " or leave --camera-relative on");
}

/* Certified mode (--precision certified, or auto on a device without f64): the frame's
 * certify word (--certified-bound injects faults), the re-render of the uncertified
 * samples' pixels, and the AOV records that count them. The re-render's default is the GPU
 * where its f64 module can run, but not on a CPU device: there the f64 shader's SIMD lanes
 * trace a scattered few pixels in vectors of 8 and took 1.4-13x the CPU reference's time
 * (docs/performance.md, "What certified decisions cost"). */
static rc_status use_certified(render_args *a, rc_packed_scene *packed, rc_render_stats *rs, bool gpu_f64,
                               bool cpu_device) {
  packed->frame.certify = a->certified_bound == 1 ? RC_CERTIFY_HALVED
                          : a->certified_bound == 2 ? RC_CERTIFY_ZERO
                                                    : RC_CERTIFY_ON;
  if (a->certified_rerender < 0) a->certified_rerender = gpu_f64 && !cpu_device ? RERENDER_GPU : RERENDER_CPU;
  if (a->certified_rerender == RERENDER_GPU && !gpu_f64) {
    rc_error("--certified-rerender gpu: %s; use cpu", a->cpu ? "the cpu backend has no GPU"
                                                              : "the device does not support shaderFloat64");
    return a->cpu ? RC_ERR_USAGE : RC_ERR_DEVICE; /* as --precision f64 is refused */
  }
  rs->rerender = rerenders[a->certified_rerender];
  a->gpu.aov = true;
  return RC_OK;
}

/* What the precision decision says to the user (rc_precision_choose). */
static void report_precision(const rc_scene *s, rc_precision_why why, const char *device) {
  if (why == RC_PRECISION_F32_DEGRADED)
    fprintf(stderr, "%s: warning: precision: rendering in f32 as asked; the output is degraded\n", s->path);
  else if (why == RC_PRECISION_AUTO_F64)
    fprintf(stderr, "%s: note: precision auto: rendering in f64\n", s->path);
  else if (why == RC_PRECISION_AUTO_CERTIFIED)
    fprintf(stderr, "%s: note: precision auto: device %s has no shaderFloat64; rendering in f32 with certified "
            "decisions, and the samples it cannot certify again in f64 on the CPU (docs/numerics.md section 10)\n",
            s->path, device);
}

/* An error about the shader's object number `o` (spheres, triangles, quadrics, planes,
 * composites), with its place in the scene file; UINT32_MAX: the scene as a whole. */
static void report_object(const rc_scene *s, size_t o, const char *what) {
  size_t counts[] = {s->sphere_count, s->triangle_count, s->quadric_count, s->plane_count, s->csg_count};
  uint32_t kinds[] = {RC_ORIGIN_SPHERE, RC_ORIGIN_TRIANGLE, RC_ORIGIN_QUADRIC, RC_ORIGIN_PLANE, RC_ORIGIN_CSG};
  for (int k = 0; k < 5 && o != UINT32_MAX; k++) {
    if (o < counts[k]) {
      rc_scene_error(s, kinds[k], o, "%s", what);
      return;
    }
    o -= counts[k];
  }
  fprintf(stderr, "%s: error: %s\n", s->path, what);
}

/* A sample that ran out of the GPU's loop budget on its own (a ray through a pile of
 * overlapping objects): the object the shader was testing, with its place in the scene
 * file, what exceeded the budget, and the way out. Nothing has been written. */
static void report_loop_budget(const rc_scene *s, const rc_gpu_stats *g, uint32_t spp, const char *device) {
  char work[300], plan[120] = "", what[1100];
  if (g->plan.budget != g->loop_budget)
    snprintf(plan, sizeof plan, " for a budget of %u (--plan-budget)", g->plan.budget);
  /* The plan put a sample over the budget in one dispatch because its passes could not be
   * counted (gpu_plan.h): fewer samples or lights are the way out, not fewer objects. */
  const bool uncountable = g->plan.uncountable;
  if (g->lights_per_pass)
    snprintf(work, sizeof work, "the rays of one sample shading a single light of its %zu", s->light_count);
  else if (uncountable)
    snprintf(work, sizeof work,
             "one sample (%zu lights, all shaded in one dispatch: %u samples x %zu lights is more than the "
             "16,777,216 a pixel can count in light passes)",
             s->light_count, spp, s->light_count);
  else
    snprintf(work, sizeof work, "one sample (%zu lights%s)", s->light_count,
             s->light_count ? ", all shaded in one dispatch as planned" : "");
  snprintf(what, sizeof what,
           "%s through pixel (%u, %u) %s %s needed more than the shader loop budget of %u iterations on %s (planned "
           "at about %llu per sample%s; %u pixels ran out: %s); refusing to write a wrong image: --backend cpu renders "
           "it",
           g->budget_object == UINT32_MAX ? "in the sample" : "a ray", g->budget_x, g->budget_y,
           g->budget_object == UINT32_MAX ? "" : "was testing this object when", work, g->loop_budget, device,
           (unsigned long long)g->plan.steps_per_sample, plan, g->budget_pixels,
           uncountable ? "use fewer samples per pixel or lights, so that the lights go in passes"
                       : "objects piled up along a ray, or --accel none");
  report_object(s, g->budget_object, what);
}

/* A ray line that crossed a composite's mesh operand more often than its max_crossings, or
 * an odd number of times: the composite, the pixel and the way out. Nothing has been written. */
/* A patch piece where Newton's method stayed near the ray without converging
 * (rc_patch.glsl): the image may miss a sliver of the patch there. Said, never silent. */
static void report_patch_stalls(const rc_scene *s, const rc_render_stats *rs) {
  size_t piece = rs->patch_stall_object - s->sphere_count - s->triangle_count;
  char what[400];
  snprintf(what, sizeof what,
           "on %llu rays (more than 1 in 1000) Newton's method stayed near a Bezier patch piece without converging "
           "in %u steps, and took the ray as a miss (the first: this patch, pixel (%u, %u)): the image may lack "
           "slivers of the patches; the count is the statistics' \"patch_unconverged\"",
           (unsigned long long)rs->patch_unconverged, RC_PATCH_NEWTON_STEPS,
           rs->patch_stall_x, rs->patch_stall_y);
  if (piece < s->quadric_count) rc_scene_warning(s, RC_ORIGIN_QUADRIC, piece, "%s", what);
  else fprintf(stderr, "%s: warning: %s\n", s->path, what);
}

static void report_crossings(const rc_scene *s, uint32_t object, uint32_t x, uint32_t y) {
  char what[400];
  snprintf(what, sizeof what,
           "the line of a ray through pixel (%u, %u) crosses a mesh operand of this composite more often than its "
           "\"max_crossings\" (default 8, at most %u), or an odd number of times (a hole the loader's edge check "
           "cannot see); refusing to write a wrong image",
           x, y, 2 * RC_CSG_MAX_INTERVALS);
  report_object(s, object, what);
}

/* The pixels to render: --region, --shard's band of rows, or the frame; and what the
 * image's header will say about them (part.h). */
static rc_status resolve_part(render_args *a, const rc_scene *s, const rc_packed_scene *packed) {
  const uint32_t w = s->width, h = s->height;
  rc_part_info *p = &a->part;
  p->width = w, p->height = h;
  p->region = (rc_region){0, 0, w, h};
  if (a->region_text) {
    rc_region r = a->region_asked;
    if (r.x1 > w || r.y1 > h) {
      rc_error("--region %s: the frame is %u x %u pixels; a region lies within it (X1 <= %u, Y1 <= %u)",
               a->region_text, w, h, w, h);
      return RC_ERR_USAGE;
    }
    p->region = r;
  }
  if (a->shard_count) {
    if (a->shard_count > h) {
      rc_error("--shard %s: the frame has %u rows, and a shard is at least one row: at most %u shards", a->shard_text,
               h, h);
      return RC_ERR_USAGE;
    }
    double *cost = a->shard_count > 1 ? rc_alloc(RC_REF_COST_CELLS, sizeof *cost, "the shard cost estimate") : NULL;
    if (a->shard_count > 1 && !cost) return RC_ERR_OUT_OF_MEMORY;
    rc_cost_grid grid;
    if (cost) rc_ref_cost_grid(packed, cost, &grid);
    bool ok = rc_shard_region(cost ? &grid : NULL, w, h, a->shard_index, a->shard_count, &p->region);
    free(cost);
    if (!ok) {
      rc_error("out of memory cutting the frame into shards");
      return RC_ERR_OUT_OF_MEMORY;
    }
    p->shard_index = a->shard_index, p->shard_count = a->shard_count;
  }
  snprintf(p->scene_hash, sizeof p->scene_hash, "%016llx", (unsigned long long)rc_packed_scene_hash(packed));
  return RC_OK;
}

/* Every setting that changes a pixel and is not in the packed scene, for the header:
 * parts that disagree on one are never merged. */
static void part_settings(render_args *a, const rc_scene *s, const char *backend, const char *precision) {
  const rc_quality *q = &s->quality;
  char encoding[96];
  rc_part_encoding_text(output_encoding(a, s), encoding, sizeof encoding);
  snprintf(a->part.settings, sizeof a->part.settings,
           "backend=%s precision=%s spp=%u accel=%s sphere=%s triangle=%s shadow_offset=%s shadow_epsilon=%.9g "
           "camera_relative=%s reflection_depth=%u shadows=%s perturb=%u %s quantize=%s",
           backend, precision, s->samples_per_pixel, a->no_bvh ? "none" : "bvh", rc_sphere_formula_names[q->sphere],
           rc_triangle_formula_names[q->triangle], rc_offset_names[q->offset], q->offset_epsilon,
           q->camera_relative ? "on" : "off", s->reflection_depth, q->shadows ? "on" : "off", a->perturb,
           encoding, truncate_output(a, s) ? "truncate" : "round");
}

static rc_status render_scene(render_args *a, const rc_scene *scene, rc_vk_ctx *ctx, double parse_ms, bool warn);

/* No output may name a file the scene read (a mesh, the MTL or glTF buffer it names):
 * writing one would replace an input of the very render, or of the next. Known only once
 * the scene has loaded, and checked then, before anything renders or is written. */
static rc_status check_outputs_against_inputs(const render_args *a, const rc_scene *scene) {
  rc_file_role files[RUN_FILES_MAX];
  char band_names[2 * RC_MAX_BAND_RENDERS][PATH_MAX];
  size_t n = run_files(a, files, band_names);
  if (n == 0) return RC_ERR_USAGE;
  for (size_t i = 0; i < scene->input_count; i++)
    for (size_t k = 0; k < n; k++) {
      if (!files[k].output || !files[k].path) continue;
      const rc_file_role pair[2] = {{scene->inputs[i], "a file the scene reads", false}, files[k]};
      if (rc_check_distinct(pair, 2) != RC_OK) return RC_ERR_USAGE;
    }
  return RC_OK;
}

rc_status rc_cmd_render(int argc, char **argv) {
  render_args a;
  rc_status st = parse_args(argc, argv, &a);
  if (st != RC_OK) return st == RC_DONE ? RC_OK : st;

  rc_scene scene;
  double t0 = rc_now_ms();
  rc_set_scene_path(a.scene);
  if (a.prepared_path) {
    st = rc_prepared_open(a.prepared_path, &a.prepared, &scene);
    if (st == RC_OK && a.prepared_given) st = rc_prepared_check_source(a.prepared, &scene, a.scene);
  } else {
    st = rc_scene_load(a.scene, &a.load, &scene);
    if (st == RC_OK) st = rc_scene_read_textures(&scene);
  }
  double parse_ms = rc_now_ms() - t0;
  if (st == RC_OK) st = check_outputs_against_inputs(&a, &scene);
  if (st == RC_OK && !a.output) {
    if (scene.output_name[0]) {
      a.output = scene.output_name;
      st = check_output_args(&a);
    } else {
      rc_usage_error(&rc_render_spec, "no output file given (-o OUT), and %s has no `output` command", a.scene);
      st = RC_ERR_USAGE;
    }
  }
  if (st == RC_OK) st = rc_output_check_format(a.output);
  if (st != RC_OK) {
    rc_scene_free(&scene);
    rc_prepared_close(a.prepared);
    return st;
  }
  if (a.width) scene.width = a.width;
  if (a.height) scene.height = a.height;
  if (a.spp) scene.samples_per_pixel = a.spp;
  apply_quality_overrides(&a, &scene);
  /* The frame asked for, then its conditioning band: seeds 1..N into files of their own,
   * each run its own transaction, the statistics and the summary the first's alone. They
   * share one Vulkan context: instance and device are created once a process. */
  rc_output_install_signal_handlers(); /* once a process: they guard every render's files */
  rc_vk_ctx ctx = {0};
  st = render_scene(&a, &scene, &ctx, parse_ms, true);
  render_args band = a;
  band.stats_json = NULL, band.stats_stdout = false, band.quiet = true;
  char image[PATH_MAX], aov[PATH_MAX]; /* their lengths were checked with the outputs */
  for (uint32_t k = 1; st == RC_OK && k <= a.band_renders; k++) {
    band.perturb = k;
    band_path(a.output, k, image, sizeof image);
    band.output = image;
    if (a.aov) band_path(a.aov, k, aov, sizeof aov);
    band.aov = a.aov ? aov : NULL;
    st = render_scene(&band, &scene, &ctx, parse_ms, false);
  }
  rc_status vst = ctx.instance ? rc_vk_destroy(&ctx) : RC_OK;
  rc_scene_free(&scene); /* before the file: its origins' names lie there */
  rc_prepared_close(a.prepared);
  return st != RC_OK ? st : vst;
}

/* One render of the loaded scene into a's outputs, statistics and summary included; `ctx`:
 * the process's Vulkan context, created here on the first GPU render; `warn`: print the
 * precision-budget warnings (once a run: band renders re-render the same scene). */
static rc_status render_scene(render_args *a, const rc_scene *scene, rc_vk_ctx *ctx, double parse_ms, bool warn) {
  rc_render_stats rs = {.version = rc_version_string(), .scene = strcmp(a->scene, "-") ? a->scene : RC_STDIN_NAME,
                        .backend = "gpu", .repeat = a->repeat, .parse_ms = parse_ms};
  rc_packed_scene packed = {0};
  rc_output *out = NULL;
  rc_status st;
  /* A prepared scene's arrays and tree serve as they lie unless this render changes them. */
  const bool as_prepared = a->prepared && !a->perturb && !a->no_bvh;
  rs.prepared = a->prepared_path;
  if (as_prepared) {
    st = rc_prepared_packed(a->prepared, scene, &packed);
    rs.bvh = rc_prepared_bvh_stats(a->prepared);
    rs.bvh.build_ms = 0; /* built when it was prepared */
    if (st == RC_OK) rs.bvh.loose = rc_loose_objects(&packed.frame);
  } else {
    st = a->prepared ? rc_prepared_packed_copy(a->prepared, scene, &packed) : rc_scene_pack(scene, &packed);
    if (st == RC_OK && a->perturb) rc_packed_scene_perturb(&packed, a->perturb);
    if (st == RC_OK) st = rc_bvh_build(&packed, !a->no_bvh, &rs.bvh);
  }
  if (st == RC_OK) {
    /* The plan's traversal estimate uses the depth; 0 means brute force. */
    a->gpu.bvh_depth = packed.bvh && packed.frame.bvh_node_count ? rs.bvh.depth + 1 : 0;
  }
  if (st == RC_OK) {
    double t1 = rc_now_ms();
    st = resolve_part(a, scene, &packed);
    a->gpu.region = a->part.region;
    rs.part_ms = rc_now_ms() - t1;
  }
  /* After the part's scene hash (resolve_part): the buffers, like the tree, only speed the
   * renderers up, and parts rendered with and without them merge. */
  if (st == RC_OK) st = rc_light_buffers_build(&packed, a->light_buffers != 0, a->eye_buffer != 0, &rs.light_buffers);
  rs.region = a->part.region;
  rs.shard_index = a->part.shard_index, rs.shard_count = a->part.shard_count;
  rc_stats_describe_scene(&rs, scene);
  rs.generic_pipeline = a->gpu.generic_pipeline;
  rs.rays_primary = rc_region_pixels(a->part.region) * scene->samples_per_pixel;
  rc_precision_report budget = {0};
  if (st == RC_OK) {
    rc_precision_budget(&packed, scene->quality.sphere == RC_SPHERE_ALGEBRAIC, &budget);
    if (warn) report_budget(scene, &budget);
  }
  rs.budget_needs_f64 = budget.needs_f64;
  rs.budget_quantized = budget.quantized;
  rs.budget_ms = budget.ms;
  rs.packing_scale = packed.scale;
  /* --precision wins over the scene's `quality`; the decision is rc_precision_choose's. */
  const uint32_t requested = a->precision >= 0 ? (uint32_t)a->precision : scene->quality.precision;
  rs.precision_requested = rc_precision_names[requested];
  rs.rerender = "off";
  a->gpu.aov = a->aov != NULL;
  char driver[600] = "";
  if (st == RC_OK && a->cpu) {
    rs.backend = "cpu";
    rs.device = "CPU reference";
    rs.device_type = "cpu";
    rs.driver = "vkraycast ref";
    const rc_precision_choice precision = rc_precision_choose(requested, &budget, true, true);
    if (precision.certified) st = use_certified(a, &packed, &rs, false, true);
    rs.precision = precision.certified ? "certified" : precision.f64 ? "f64" : "f32";
    part_settings(a, scene, rs.backend, rs.precision);
    snprintf(a->part.device, sizeof a->part.device, "%s", rs.device);
    if (st == RC_OK) st = render_frames_cpu(a, scene, &packed, precision.f64, &rs, &out);
  } else if (st == RC_OK) {
    rc_vk_options vo = {.device_index = a->device};
    if (!ctx->instance) st = rc_vk_create(&vo, ctx);
    if (st == RC_OK) {
      snprintf(driver, sizeof driver, "%s %s", ctx->driver.driverName[0] ? ctx->driver.driverName : "unknown driver",
               ctx->driver.driverInfo);
      rs.device = ctx->props.deviceName;
      rs.device_type = rc_vk_device_type_str(ctx->props.deviceType);
      rs.driver = driver;
      const rc_precision_choice precision = rc_precision_choose(requested, &budget, false, ctx->float64);
      report_precision(scene, precision.why, ctx->props.deviceName);
      a->gpu.f64 = precision.f64;
      if (precision.certified)
        st = use_certified(a, &packed, &rs, ctx->float64, ctx->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU);
      rs.precision = precision.certified ? "certified" : precision.f64 ? "f64" : "f32";
      part_settings(a, scene, rs.backend, rs.precision);
      snprintf(a->part.device, sizeof a->part.device, "%s (%s)", rs.device, driver);
      if (st == RC_OK) st = render_frames(a, ctx, scene, &packed, &rs, &out);
      if (rs.gpu.budget_refused)
        report_loop_budget(scene, &rs.gpu, packed.frame.samples_per_pixel, ctx->props.deviceName);
      if (rs.gpu.crossing_object != UINT32_MAX)
        report_crossings(scene, rs.gpu.crossing_object, rs.gpu.crossing_x, rs.gpu.crossing_y);
    }
  }
  /* Stalls happen where a ray grazes a patch (silhouettes, shadow terminators), a few in
   * ten thousand rays on the teapot: above 1 in 1000, say so (docs/numerics.md §8). */
  uint64_t rays = rs.rays_primary + rs.rays_shadow + rs.rays_reflection;
  if (st == RC_OK && rs.patch_unconverged * 1000 > rays) report_patch_stalls(scene, &rs);
  rs.write_ms = rc_output_write_ms(out);
  rs.cpu_ms = rc_cpu_ms();
  if (st == RC_OK && a->stats_json && !a->stats_stdout) {
    /* The statistics join the image's transaction: all of them land, or none. */
    char *text = rc_stats_json(&rs);
    st = text ? rc_output_attach(out, a->stats_json, text) : RC_ERR_OUT_OF_MEMORY;
    free(text);
  }
  rc_status cst = rc_output_close(out, st == RC_OK);
  if (st == RC_OK) st = cst;
  if (st == RC_OK && a->stats_stdout) {
    /* Standard output is not part of the files' transaction: it gets the statistics of a
     * run whose files have landed. */
    char *text = rc_stats_json(&rs);
    st = text && fputs(text, stdout) >= 0 && fflush(stdout) == 0 ? RC_OK : RC_ERR_IO;
    if (st != RC_OK) rc_error("cannot write the statistics to standard output");
    free(text);
  }
  if (st == RC_OK && !a->quiet) rc_stats_print(&rs);
  rc_packed_scene_free(&packed);
  return st;
}
