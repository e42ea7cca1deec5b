/* cmd_prepare.c: `vkraycast prepare SCENE -o FILE.vkrs`: parse the scene, read its meshes,
 * pack it and build its BVH once, into one file that every shard of a farm renders from
 * (scene/prepared.h; docs/cluster.md, "Prepared scenes"). */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/output.h"
#include "cli/textures.h"
#include "scene/bvh.h"
#include "scene/prepared.h"
#include "scene/scene_pack.h"

typedef struct {
  const char *scene, *output;
  int camera_relative, rescale; /* -1: the scene's */
  bool quiet, allow_outside_paths;
} prepare_args;

static const char *const off_on[] = {"off", "on", NULL};

#define ARG(field) offsetof(prepare_args, field)
static const rc_option prepare_options[] = {
    {"--output", "-o", RC_OPT_STRING, ARG(output), "FILE.vkrs", .help = "the prepared scene to write (required)"},
    {"--camera-relative", NULL, RC_OPT_CHOICE, ARG(camera_relative), "B", .choices = off_on,
     .help = "on (default) or off: as render's; the packed positions depend on it,\n"
             "so a render of the file takes the value it was prepared with"},
    {"--rescale", NULL, RC_OPT_CHOICE, ARG(rescale), "B", .choices = off_on,
     .help = "on (default) or off: as render's, and fixed in the file likewise"},
    {"--allow-outside-paths", NULL, RC_OPT_FLAG, ARG(allow_outside_paths),
     .help = "let meshes (and the files a mesh names) and textures lie outside the\n"
             "scene file's folder"},
    {"--quiet", "-q", RC_OPT_FLAG, ARG(quiet), .help = "no summary on stderr"},
};
#undef ARG

static const char *const prepare_positional[] = {"scene file (SCENE)"};
const rc_command_spec rc_prepare_spec = {
    .name = "prepare",
    .synopsis = "SCENE -o FILE.vkrs [options]",
    .summary = "Packs SCENE and builds its BVH once, into FILE.vkrs: `render FILE.vkrs` (or render SCENE\n"
               "--prepared FILE.vkrs, which also checks that SCENE has not changed) maps it instead of\n"
               "parsing the scene and building the tree, and renders the same image bit for bit.",
    .epilogue = "Exit status: 0 written; 2 bad input or usage (nothing written); 3 memory failure.\n",
    .min_positional = 1,
    .max_positional = 1,
    .positional_offset = offsetof(prepare_args, scene),
    .positional_names = prepare_positional,
    .options = prepare_options,
    .option_count = sizeof prepare_options / sizeof *prepare_options,
};

static rc_status check_args(const prepare_args *a) {
  if (strcmp(a->scene, "-") == 0) {
    rc_usage_error(&rc_prepare_spec, "- (standard input): a prepared scene records its scene file's digest, so that "
                                     "renders can tell it is stale; name the file");
    return RC_ERR_USAGE;
  }
  if (!a->output) {
    rc_usage_error(&rc_prepare_spec, "no output file given (-o FILE.vkrs)");
    return RC_ERR_USAGE;
  }
  if (!rc_has_extension(a->output, RC_PREPARED_EXTENSION)) {
    rc_usage_error(&rc_prepare_spec, "-o %s: name the prepared scene FILE.vkrs (render tells it from a scene by that)",
                   a->output);
    return RC_ERR_USAGE;
  }
  RC_TRY(rc_check_output(a->output, "the prepared scene") == RC_OK ? RC_OK : RC_ERR_IO);
  const rc_file_role files[2] = {{a->scene, "the scene file", false}, {a->output, "the prepared scene", true}};
  return rc_check_distinct(files, 2) != RC_OK ? RC_ERR_USAGE : RC_OK;
}

/* Packs, builds the tree, encodes and writes (all or nothing) the loaded scene. */
static rc_status prepare(const prepare_args *a, const rc_scene *scene, double parse_ms) {
  for (size_t i = 0; i < scene->input_count; i++) {
    const rc_file_role pair[2] = {{scene->inputs[i], "a file the scene reads", false},
                                  {a->output, "the prepared scene", true}};
    if (rc_check_distinct(pair, 2) != RC_OK) return RC_ERR_USAGE;
  }
  uint64_t digest = 0;
  RC_TRY(rc_source_digest(a->scene, scene->inputs, scene->input_count, &digest));
  double t0 = rc_now_ms();
  rc_packed_scene packed;
  RC_TRY(rc_scene_pack(scene, &packed));
  rc_bvh_stats bvh;
  rc_status st = rc_bvh_build(&packed, true, &bvh);
  void *bytes = NULL;
  size_t len = 0;
  if (st == RC_OK) st = rc_prepared_encode(scene, &packed, &bvh, digest, &bytes, &len);
  double build_ms = rc_now_ms() - t0;
  rc_output *out = NULL;
  if (st == RC_OK) st = rc_output_open(NULL, NULL, 0, 0, rc_encoding_linear(), false, NULL, 0, &out);
  if (st == RC_OK) st = rc_output_attach_bytes(out, a->output, bytes, len, "the prepared scene");
  rc_status cst = rc_output_close(out, st == RC_OK);
  if (st == RC_OK) st = cst;
  if (st == RC_OK && !a->quiet)
    fprintf(stderr,
            "vkraycast: prepared %s: %u objects, %u triangles, BVH %u nodes (depth %u); %s, %.1f MiB; parse %.0f ms, "
            "pack and BVH %.0f ms\n",
            a->scene, packed.frame.object_count, packed.triangle_total, packed.bvh_node_total, bvh.depth, a->output,
            (double)len / (1 << 20), parse_ms, build_ms);
  free(bytes);
  rc_packed_scene_free(&packed);
  return st;
}

rc_status rc_cmd_prepare(int argc, char **argv) {
  prepare_args a = {.camera_relative = -1, .rescale = -1};
  rc_status st = rc_parse_command(&rc_prepare_spec, argc, argv, &a);
  if (st != RC_OK) return st == RC_DONE ? RC_OK : st;
  RC_TRY(check_args(&a));
  rc_output_install_signal_handlers();
  rc_load_options load = {.allow_outside_paths = a.allow_outside_paths};
  rc_scene scene;
  rc_set_scene_path(a.scene);
  double t0 = rc_now_ms();
  st = rc_scene_load(a.scene, &load, &scene);
  if (st == RC_OK) st = rc_scene_read_textures(&scene);
  double parse_ms = rc_now_ms() - t0;
  if (st != RC_OK) {
    rc_scene_free(&scene);
    return st;
  }
  if (a.camera_relative >= 0) scene.quality.camera_relative = a.camera_relative == 1;
  if (a.rescale >= 0) scene.quality.rescale = a.rescale == 1;
  st = prepare(&a, &scene, parse_ms);
  rc_scene_free(&scene);
  return st;
}
