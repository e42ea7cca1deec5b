/* cmd_render.c: `vkraycast render`: parse the scene, apply command-line overrides,
 * pack, render on the GPU (N times with --repeat), write the image and the statistics. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "gpu_render.h"
#include "bvh.h"
#include "output.h"
#include "precision_budget.h"
#include "image/image_io.h"
#include "ref/ref_render.h"
#include "scene/scene_pack.h"
#include "stats.h"

static const char render_usage[] =
    "usage: vkraycast render SCENE -o OUT [options]\n"
    "\n"
    "  -o, --output OUT        image to write; the extension picks the format (png, exr, tif, jpg, ...)\n"
    "  --width W, --height H   override the scene's image size\n"
    "  --spp N                 override samples per pixel (1..1024)\n"
    "  --backend B             gpu (default: the Vulkan compute shader) or cpu (the reference renderer)\n"
    "  --precision P           auto (default), f32 or f64 geometry and shading math. auto: f64 on cpu;\n"
    "                          on gpu f32 unless the precision-budget pass finds the scene needs f64\n"
    "                          and the device has shaderFloat64 (docs/accuracy.md)\n"
    "  --accel A               bvh (default) or none: brute force over every object, for comparison\n"
    "  --threads N             cpu backend: threads (default: all cores); the image does not depend on it\n"
    "  --device N              Vulkan device index (see `vkraycast devices`); default: discrete >\n"
    "                          integrated > virtual > CPU\n"
    "  --srgb                  8-bit outputs get the sRGB transfer curve (default: linear, clamped)\n"
    "  --quantize Q            8-bit outputs: round (JSON scenes' default) or truncate (.test scenes')\n"
    "  --repeat N              render N frames; statistics report the first and the median of the rest\n"
    "  --stats-json FILE       write the statistics as one JSON object\n"
    "  --aov FILE.exr          also write the decision outputs of each pixel's first sample: colour,\n"
    "                          hit, object, t, normal, shadow bits per light (see docs/gpu-vs-cpu.md)\n"
    "  --quiet                 no progress or summary on stderr\n"
    "  --allow-outside-paths   let meshes (and the files a mesh names) lie outside the scene\n"
    "                          file's folder; off by default, so an untrusted scene cannot read\n"
    "                          other files into the image\n"
    "\n"
    "speed against accuracy (docs/accuracy.md; each overrides the scene's `quality`):\n"
    "  --sphere F              geometric (default) or algebraic ray/sphere formula\n"
    "  --triangle F            watertight (default), moller-trumbore or cramer ray/triangle test\n"
    "  --shadow-offset S       error-bound (default), ulp or epsilon: where shadow/reflection rays start\n"
    "  --shadow-epsilon E      the epsilon strategy's offset in scene units (default 1e-4)\n"
    "  --camera-relative B     on (default) or off: positions relative to the eye before f32 rounding\n"
    "  --reflection-depth N    mirror bounces (0..16)\n"
    "  --shadows B             on (default) or off: trace shadow rays\n"
    "\n"
    "tuning and testing:\n"
    "  --scene-buffers K       texel (default) or storage: how the shader reads the scene arrays\n"
    "  --pipeline P            specialized (default: compiled for this scene's primitive kinds, light\n"
    "                          count, shadows, specular model and bounces) or generic (one pipeline\n"
    "                          for every scene; to measure what specializing buys)\n"
    "  --staging               upload and read back through staging buffers even on unified memory\n"
    "                          (also VKRAYCAST_FORCE_STAGING=1)\n"
    "  --tile-budget-ms T      the longest one dispatch (one submit) should run: tiles adapt to it;\n"
    "                          0: no limit (default: none on a CPU device such as lavapipe, which\n"
    "                          no watchdog resets; 100 elsewhere, as real GPUs reset after ~2 s)\n"
    "  --tile N                fixed N x N tiles instead of adaptive ones\n"
    "  --perturb SEED          scale every packed position and radius by 1 + d, |d| <= 2^-22, d a hash\n"
    "                          of SEED and the value (equal values move alike: meshes stay closed); its\n"
    "                          renders give `compare --band` the conditioning band\n"
    "  --plan-budget N         loop budget the host plans batches with (default: the shader's, 49152\n"
    "                          divided by the subgroup size on llvmpipe); larger values test the\n"
    "                          shader's exhaustion flag\n";

typedef struct {
  const char *scene, *output, *stats_json, *aov;
  uint32_t width, height, spp, repeat;
  int device;
  bool quiet, srgb;
  bool cpu;
  bool no_bvh;
  int truncate; /* -1: the scene format's rule */
  int precision; /* -1: the scene's (RC_PRECISION_*) */
  int sphere, triangle, offset, camera_relative, reflection_depth, shadows; /* -1: the scene's */
  double offset_epsilon; /* 0: the scene's */
  uint32_t perturb;      /* 0: none, else the seed */
  uint32_t threads;
  rc_gpu_options gpu;
  rc_load_options load;
} render_args;

rc_status rc_cli_uint(const char *name, const char *text, uint32_t lo, uint32_t hi, uint32_t *out) {
  char *end = NULL;
  errno = 0;
  unsigned long long v = strtoull(text, &end, 10);
  if (!text[0] || *end || errno || text[0] == '-' || v < lo || v > hi) {
    rc_error("%s: expected a whole number in [%u, %u], got '%s'", name, lo, hi, text);
    return RC_ERR_USAGE;
  }
  *out = (uint32_t)v;
  return RC_OK;
}

static rc_status cli_enum(const char *name, const char *v, const char *const *names, int *out) {
  int i = rc_name_index(names, v);
  if (i < 0) {
    char list[160] = "";
    for (int k = 0; names[k]; k++) snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "", names[k]);
    rc_error("%s: expected one of %s, got '%s'", name, list, v);
    return RC_ERR_USAGE;
  }
  *out = i;
  return RC_OK;
}

static bool option_takes_value(const char *o) {
  static const char *const with_value[] = {"-o", "--output", "--stats-json", "--width", "--height", "--spp",
                                           "--repeat", "--device", "--tile", "--plan-budget", "--scene-buffers",
                                           "--backend", "--precision", "--threads", "--aov", "--accel", "--quantize",
                                           "--tile-budget-ms", "--sphere", "--triangle", "--shadow-offset",
                                           "--shadow-epsilon", "--camera-relative", "--reflection-depth", "--perturb",
                                           "--shadows", "--pipeline"};
  for (size_t i = 0; i < sizeof with_value / sizeof *with_value; i++)
    if (strcmp(o, with_value[i]) == 0) return true;
  return false;
}

static rc_status parse_args(int argc, char **argv, render_args *a) {
  memset(a, 0, sizeof *a);
  a->device = -1;
  a->repeat = 1;
  a->precision = a->sphere = a->triangle = a->offset = a->camera_relative = a->reflection_depth = a->shadows = -1;
  a->truncate = -1;
  a->gpu.scene_buffers = RC_SCENE_BUFFERS_TEXEL;
  a->gpu.tile_size = 0;
  a->gpu.tile_budget_ms = -1; /* the device's default (gpu_render.c) */
  a->gpu.plan_budget = 0;
  const char *force = getenv("VKRAYCAST_FORCE_STAGING");
  a->gpu.force_staging = force && force[0] && strcmp(force, "0") != 0;
  for (int i = 0; i < argc; i++) {
    const char *o = argv[i];
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    bool takes_value = true;
    rc_status st = RC_OK;
    uint32_t n;
    if (strcmp(o, "--help") == 0 || strcmp(o, "-h") == 0) {
      fputs(render_usage, stdout);
      exit(0);
    } else if (strcmp(o, "--quiet") == 0) {
      a->quiet = true, takes_value = false;
    } else if (strcmp(o, "--srgb") == 0) {
      a->srgb = true, takes_value = false;
    } else if (strcmp(o, "--staging") == 0) {
      a->gpu.force_staging = true, takes_value = false;
    } else if (strcmp(o, "--allow-outside-paths") == 0) {
      a->load.allow_outside_paths = true, takes_value = false;
    } else if (o[0] == '-' && o[1] && !option_takes_value(o)) {
      rc_error("render: unknown option %s (see vkraycast render --help)", o);
      return RC_ERR_USAGE;
    } else if (o[0] == '-' && o[1] && !v) {
      rc_error("render: option %s needs a value", o);
      return RC_ERR_USAGE;
    } else if (strcmp(o, "-o") == 0 || strcmp(o, "--output") == 0) {
      a->output = v;
    } else if (strcmp(o, "--stats-json") == 0) {
      a->stats_json = v;
    } else if (strcmp(o, "--aov") == 0) {
      a->aov = v;
    } else if (strcmp(o, "--width") == 0) {
      st = rc_cli_uint(o, v, 1, RC_MAX_IMAGE_SIDE, &a->width);
    } else if (strcmp(o, "--height") == 0) {
      st = rc_cli_uint(o, v, 1, RC_MAX_IMAGE_SIDE, &a->height);
    } else if (strcmp(o, "--spp") == 0) {
      st = rc_cli_uint(o, v, 1, RC_MAX_SAMPLES_PER_PIXEL, &a->spp);
    } else if (strcmp(o, "--repeat") == 0) {
      st = rc_cli_uint(o, v, 1, 1000, &a->repeat);
    } else if (strcmp(o, "--device") == 0) {
      st = rc_cli_uint(o, v, 0, 1000, &n);
      a->device = (int)n;
    } else if (strcmp(o, "--tile-budget-ms") == 0) {
      uint32_t ms;
      st = rc_cli_uint(o, v, 0, 60000, &ms);
      a->gpu.tile_budget_ms = ms;
    } else if (strcmp(o, "--tile") == 0) {
      st = rc_cli_uint(o, v, 8, 4096, &a->gpu.tile_size);
    } else if (strcmp(o, "--plan-budget") == 0) {
      st = rc_cli_uint(o, v, 1, UINT32_MAX, &a->gpu.plan_budget);
    } else if (strcmp(o, "--threads") == 0) {
      st = rc_cli_uint(o, v, 1, 1024, &a->threads);
    } else if (strcmp(o, "--backend") == 0) {
      if (strcmp(v, "gpu") == 0 || strcmp(v, "cpu") == 0) {
        a->cpu = strcmp(v, "cpu") == 0;
      } else {
        rc_error("--backend: expected gpu or cpu, got '%s'", v);
        st = RC_ERR_USAGE;
      }
    } else if (strcmp(o, "--quantize") == 0) {
      if (strcmp(v, "round") == 0 || strcmp(v, "truncate") == 0) {
        a->truncate = strcmp(v, "truncate") == 0;
      } else {
        rc_error("--quantize: expected round or truncate, got '%s'", v);
        st = RC_ERR_USAGE;
      }
    } else if (strcmp(o, "--accel") == 0) {
      if (strcmp(v, "bvh") == 0 || strcmp(v, "none") == 0) {
        a->no_bvh = strcmp(v, "none") == 0;
      } else {
        rc_error("--accel: expected bvh or none, got '%s'", v);
        st = RC_ERR_USAGE;
      }
    } else if (strcmp(o, "--precision") == 0) {
      st = cli_enum(o, v, rc_precision_names, &a->precision);
    } else if (strcmp(o, "--sphere") == 0) {
      st = cli_enum(o, v, rc_sphere_formula_names, &a->sphere);
    } else if (strcmp(o, "--triangle") == 0) {
      st = cli_enum(o, v, rc_triangle_formula_names, &a->triangle);
    } else if (strcmp(o, "--shadow-offset") == 0) {
      st = cli_enum(o, v, rc_offset_names, &a->offset);
    } else if (strcmp(o, "--camera-relative") == 0) {
      static const char *const off_on[] = {"off", "on", NULL};
      st = cli_enum(o, v, off_on, &a->camera_relative);
    } else if (strcmp(o, "--shadows") == 0) {
      static const char *const off_on[] = {"off", "on", NULL};
      st = cli_enum(o, v, off_on, &a->shadows);
    } else if (strcmp(o, "--pipeline") == 0) {
      static const char *const kinds[] = {"specialized", "generic", NULL};
      int k = 0;
      st = cli_enum(o, v, kinds, &k);
      a->gpu.generic_pipeline = k == 1;
    } else if (strcmp(o, "--reflection-depth") == 0) {
      st = rc_cli_uint(o, v, 0, RC_MAX_REFLECTION_DEPTH, &n);
      a->reflection_depth = (int)n;
    } else if (strcmp(o, "--perturb") == 0) {
      st = rc_cli_uint(o, v, 1, UINT32_MAX, &a->perturb);
    } else if (strcmp(o, "--shadow-epsilon") == 0) {
      char *end = NULL;
      a->offset_epsilon = strtod(v, &end);
      if (!v[0] || *end || !(a->offset_epsilon > 0) || !((float)a->offset_epsilon > 0) ||
          !isfinite((float)a->offset_epsilon)) {
        rc_error("--shadow-epsilon: expected a positive number within f32 range, got '%s'", v);
        st = RC_ERR_USAGE;
      }
    } else if (strcmp(o, "--scene-buffers") == 0) {
      if (strcmp(v, "texel") == 0) {
        a->gpu.scene_buffers = RC_SCENE_BUFFERS_TEXEL;
      } else if (strcmp(v, "storage") == 0) {
        a->gpu.scene_buffers = RC_SCENE_BUFFERS_STORAGE;
      } else {
        rc_error("--scene-buffers: expected texel or storage, got '%s'", v);
        st = RC_ERR_USAGE;
      }
    } else if (!a->scene) {
      a->scene = o, takes_value = false;
    } else {
      rc_error("render: unexpected argument '%s' (one scene per command)", o);
      return RC_ERR_USAGE;
    }
    if (st != RC_OK) return st;
    if (takes_value) i++;
  }
  if (!a->scene || !a->output) {
    rc_error("render: %s", !a->scene ? "no scene file given" : "no output file given (-o OUT)");
    fputs(render_usage, stderr);
    return RC_ERR_USAGE;
  }
  /* Every output is checked before anything renders: an existing special file or folder,
   * or a missing folder, is refused now rather than after the render. */
  if (rc_check_output(a->output, "the image") != RC_OK) return RC_ERR_IO;
  if (a->aov && rc_check_output(a->aov, "the AOV file") != RC_OK) return RC_ERR_IO;
  if (a->stats_json && rc_check_output(a->stats_json, "statistics") != RC_OK) return RC_ERR_IO;
  const rc_file_role files[] = {{a->scene, "the scene file", false},
                                {a->output, "the image", true},
                                {a->aov, "the AOV file", true},
                                {a->stats_json, "the statistics", true}};
  if (rc_check_distinct(files, sizeof files / sizeof *files) != RC_OK) return RC_ERR_USAGE;
  a->gpu.aov = a->aov != NULL;
  if (a->aov) {
    size_t n = strlen(a->aov);
    if (n < 4 || strcmp(a->aov + n - 4, ".exr") != 0) {
      rc_error("--aov %s: the decision outputs need a multi-channel float file: name it .exr", a->aov);
      return RC_ERR_USAGE;
    }
  }
  if (!rc_image_can_write(a->output)) {
    rc_error("%s: no image format for this file name (use .png, .exr, .tif, .jpg, ...)", a->output);
    return RC_ERR_USAGE;
  }
  return RC_OK;
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
static rc_status open_output(const render_args *a, const rc_scene *scene, rc_output **out) {
  return rc_output_open(a->output, a->aov, scene->width, scene->height, a->srgb ? RC_ENCODING_SRGB : RC_ENCODING_LINEAR,
                        a->truncate < 0 ? scene->truncate_8bit : a->truncate == 1, out);
}

static rc_status render_frames(const render_args *a, rc_vk_ctx *ctx, const rc_scene *scene,
                               const rc_packed_scene *packed, rc_render_stats *rs, rc_output **out) {
  rc_gpu_renderer *r = NULL;
  rc_gpu_options opts = a->gpu;
  opts.progress = !a->quiet && isatty(STDERR_FILENO);
  rc_status st = rc_gpu_renderer_create(ctx, packed, &opts, &r, &rs->gpu);
  double *gpu_ms = calloc(a->repeat, sizeof *gpu_ms), *wall_ms = calloc(a->repeat, sizeof *wall_ms);
  if (!gpu_ms || !wall_ms) st = RC_ERR_OUT_OF_MEMORY;
  for (uint32_t i = 0; st == RC_OK && i < a->repeat; i++) {
    bool last = i + 1 == a->repeat;
    if (last) st = open_output(a, scene, out);
    if (st == RC_OK) st = rc_gpu_renderer_render(r, last ? rc_output_band : rc_output_discard, last ? *out : NULL, &rs->gpu);
    gpu_ms[i] = rs->gpu.gpu_ms;
    wall_ms[i] = rs->gpu.render_ms;
  }
  if (st == RC_OK) {
    rs->first_frame_ms = wall_ms[0];
    rs->render_ms = steady(gpu_ms, a->repeat);
    rs->render_wall_ms = steady(wall_ms, a->repeat);
    rs->rays_shadow = rs->gpu.shadow_rays;
    rs->rays_reflection = rs->gpu.reflection_rays;
  }
  free(gpu_ms);
  free(wall_ms);
  rc_gpu_renderer_destroy(r);
  return st;
}

/* The CPU reference in bands of CPU_BAND_ROWS rows. */
#define CPU_BAND_ROWS 32u

static rc_status render_frames_cpu(const render_args *a, const rc_scene *scene, const rc_packed_scene *packed,
                                   rc_render_stats *rs, rc_output **out) {
  rc_ref_options opts = {.f64 = a->gpu.f64, .threads = a->threads};
  uint32_t w = scene->width, h = scene->height;
  uint32_t band = h < CPU_BAND_ROWS ? h : CPU_BAND_ROWS;
  double *ms = calloc(a->repeat, sizeof *ms);
  float *rgb = rc_alloc((size_t)w * band * 3, sizeof(float), "one band of the image");
  gpu_aov *aov = a->aov ? rc_alloc((size_t)w * band, sizeof *aov, "one band of AOVs") : NULL;
  rc_status st = ms && rgb && (!a->aov || aov) ? RC_OK : RC_ERR_OUT_OF_MEMORY;
  rc_ref_stats last_stats = {0};
  for (uint32_t i = 0; st == RC_OK && i < a->repeat; i++) {
    bool last = i + 1 == a->repeat;
    rc_ref_stats fs = {0};
    if (last) st = open_output(a, scene, out);
    for (uint32_t y0 = 0; st == RC_OK && y0 < h; y0 += band) {
      uint32_t rows = h - y0 < band ? h - y0 : band;
      st = rc_ref_render(packed, &opts, y0, rows, rgb, aov, &fs);
      if (st == RC_OK && last) st = rc_output_band(y0, rows, rgb, aov, *out);
    }
    ms[i] = fs.render_ms;
    last_stats = fs;
  }
  if (st == RC_OK) {
    rs->first_frame_ms = ms[0];
    rs->render_ms = rs->render_wall_ms = steady(ms, a->repeat);
    rs->rays_shadow = last_stats.shadow_rays;
    rs->rays_reflection = last_stats.reflection_rays;
    rs->threads = last_stats.threads;
  }
  free(ms);
  free(rgb);
  free(aov);
  return st;
}

static void apply_quality_overrides(const render_args *a, rc_scene *s) {
  rc_quality *q = &s->quality;
  if (a->precision >= 0) q->precision = (uint32_t)a->precision;
  if (a->sphere >= 0) q->sphere = (uint32_t)a->sphere;
  if (a->triangle >= 0) q->triangle = (uint32_t)a->triangle;
  if (a->offset >= 0) q->offset = (uint32_t)a->offset;
  if (a->camera_relative >= 0) q->camera_relative = a->camera_relative == 1;
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

/* --precision auto on the GPU: f32 unless the scene needs f64 and the device has it. */
static bool gpu_precision(const rc_scene *s, const rc_precision_report *b, const rc_vk_ctx *ctx) {
  if (s->quality.precision == RC_PRECISION_F64) return true;
  if (s->quality.precision == RC_PRECISION_F32) {
    if (b->needs_f64) fprintf(stderr, "%s: warning: precision: rendering in f32 as asked; the output is degraded\n", s->path);
    return false;
  }
  if (!b->needs_f64) return false;
  if (ctx->float64) {
    fprintf(stderr, "%s: note: precision auto: rendering in f64\n", s->path);
    return true;
  }
  fprintf(stderr, "%s: warning: precision auto: device %s has no shaderFloat64; rendering in f32, the output is "
          "degraded (--backend cpu renders in f64)\n", s->path, ctx->props.deviceName);
  return false;
}

/* A sample that ran out of the GPU's loop budget on its own (a ray through a pile of
 * overlapping objects): the object the shader was testing, with its place in the scene
 * file, and the way out. Nothing has been written. */
static void report_loop_budget(const rc_scene *s, const rc_gpu_stats *g, const char *device) {
  char what[600];
  snprintf(what, sizeof what,
           "a ray through pixel (%u, %u) was testing this object when its sample ran out of the shader loop budget "
           "on %s (%u pixels did: objects piled up along a ray, or --accel none); refusing to write a wrong "
           "image: --backend cpu renders it",
           g->budget_x, g->budget_y, device, g->budget_pixels);
  size_t o = g->budget_object;
  size_t counts[] = {s->sphere_count, s->triangle_count, s->quadric_count, s->csg_count};
  uint32_t kinds[] = {RC_ORIGIN_SPHERE, RC_ORIGIN_TRIANGLE, RC_ORIGIN_QUADRIC, RC_ORIGIN_CSG};
  for (int k = 0; k < 4 && g->budget_object != UINT32_MAX; k++) {
    if (o < counts[k]) {
      rc_scene_error(s, kinds[k], o, "%s", what);
      return;
    }
    o -= counts[k];
  }
  fprintf(stderr, "%s: error: %s\n", s->path, what);
}

rc_status rc_cmd_render(int argc, char **argv) {
  render_args a;
  rc_status st = parse_args(argc, argv, &a);
  if (st != RC_OK) return st;

  rc_render_stats rs = {.backend = "gpu", .repeat = a.repeat};
  rc_scene scene;
  double t0 = rc_now_ms();
  rc_set_scene_path(a.scene);
  st = rc_scene_load(a.scene, &a.load, &scene);
  rs.parse_ms = rc_now_ms() - t0;
  if (st != RC_OK) {
    rc_scene_free(&scene);
    return st;
  }
  if (a.width) scene.width = a.width;
  if (a.height) scene.height = a.height;
  if (a.spp) scene.samples_per_pixel = a.spp;
  apply_quality_overrides(&a, &scene);

  rc_packed_scene packed = {0};
  rc_vk_ctx ctx = {0};
  rc_output *out = NULL;
  st = rc_scene_pack(&scene, &packed);
  if (st == RC_OK && a.perturb) rc_packed_scene_perturb(&packed, a.perturb);
  if (st == RC_OK && !a.no_bvh) {
    st = rc_bvh_build(&packed, &rs.bvh);
    /* The plan's traversal estimate uses the depth; 0 means brute force. */
    a.gpu.bvh_depth = packed.bvh_nodes ? rs.bvh.depth + 1 : 0;
  }
  rs.width = scene.width;
  rs.height = scene.height;
  rs.samples_per_pixel = scene.samples_per_pixel;
  rs.spheres = scene.sphere_count;
  rs.triangles = scene.triangle_count;
  rs.lights = scene.light_count;
  rs.quadrics = scene.quadric_count;
  rs.composites = scene.csg_count;
  rs.materials = scene.material_count;
  rs.shadows = scene.quality.shadows;
  rs.generic_pipeline = a.gpu.generic_pipeline;
  rs.rays_primary = (uint64_t)scene.width * scene.height * scene.samples_per_pixel;
  rc_precision_report budget = {0};
  if (st == RC_OK) {
    rc_precision_budget(&packed, scene.quality.sphere == RC_SPHERE_ALGEBRAIC, &budget);
    report_budget(&scene, &budget);
  }
  rs.budget_needs_f64 = budget.needs_f64;
  rs.budget_quantized = budget.quantized;
  rs.budget_ms = budget.ms;
  rs.precision_requested = rc_precision_names[scene.quality.precision];
  rs.sphere_formula = rc_sphere_formula_names[scene.quality.sphere];
  rs.triangle_formula = rc_triangle_formula_names[scene.quality.triangle];
  rs.shadow_offset = rc_offset_names[scene.quality.offset];
  rs.camera_relative = scene.quality.camera_relative;
  char driver[600] = "";
  rc_output_install_signal_handlers();
  if (st == RC_OK && a.cpu) {
    rs.backend = "cpu";
    rs.device = "CPU reference";
    rs.device_type = "cpu";
    rs.driver = "vkraycast ref";
    /* The reference renders in f64 unless f32 is asked for: it is the accuracy yardstick. */
    a.gpu.f64 = scene.quality.precision != RC_PRECISION_F32;
    rs.precision = a.gpu.f64 ? "f64" : "f32";
    st = render_frames_cpu(&a, &scene, &packed, &rs, &out);
  } else if (st == RC_OK) {
    rc_vk_options vo = {.device_index = a.device};
    st = rc_vk_create(&vo, &ctx);
    if (st == RC_OK) {
      snprintf(driver, sizeof driver, "%s %s", ctx.driver.driverName[0] ? ctx.driver.driverName : "unknown driver",
               ctx.driver.driverInfo);
      rs.device = ctx.props.deviceName;
      rs.device_type = rc_vk_device_type_str(ctx.props.deviceType);
      rs.driver = driver;
      a.gpu.f64 = gpu_precision(&scene, &budget, &ctx);
      rs.precision = a.gpu.f64 ? "f64" : "f32";
      st = render_frames(&a, &ctx, &scene, &packed, &rs, &out);
      if (rs.gpu.budget_refused) report_loop_budget(&scene, &rs.gpu, ctx.props.deviceName);
    }
  }
  rs.write_ms = rc_output_write_ms(out);
  rs.cpu_ms = rc_cpu_ms();
  if (st == RC_OK && a.stats_json) {
    /* The statistics join the image's transaction: all of them land, or none. */
    char *text = rc_stats_json(&rs);
    st = text ? rc_output_attach(out, a.stats_json, text) : RC_ERR_OUT_OF_MEMORY;
    free(text);
  }
  rc_status cst = rc_output_close(out, st == RC_OK);
  if (st == RC_OK) st = cst;
  if (st == RC_OK && !a.quiet) rc_stats_print(&rs);
  rc_status vst = ctx.instance ? rc_vk_destroy(&ctx) : RC_OK;
  rc_packed_scene_free(&packed);
  rc_scene_free(&scene);
  return st != RC_OK ? st : vst;
}
