#include "cli/stats.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>
#include <sys/resource.h>

double rc_stats_mrays_per_s(const rc_render_stats *s) {
  double rays = (double)(s->rays_primary + s->rays_shadow + s->rays_reflection);
  return s->render_ms > 0 ? rays / (s->render_ms * 1e3) : 0.0;
}

void rc_stats_describe_scene(rc_render_stats *s, const rc_scene *scene) {
  s->width = scene->width;
  s->height = scene->height;
  s->samples_per_pixel = scene->samples_per_pixel;
  s->spheres = scene->sphere_count;
  s->triangles = scene->triangle_count;
  s->lights = scene->light_count;
  s->quadrics = scene->quadric_count;
  s->planes = scene->plane_count;
  s->composites = scene->csg_count;
  s->materials = scene->material_count;
  s->shadows = scene->quality.shadows;
  s->sphere_formula = rc_sphere_formula_names[scene->quality.sphere];
  s->triangle_formula = rc_triangle_formula_names[scene->quality.triangle];
  s->shadow_offset = rc_offset_names[scene->quality.offset];
  s->camera_relative = scene->quality.camera_relative;
}

/* ", lights in passes of N" where a sample was too long for one dispatch (gpu_plan.h). */
static const char *light_passes_text(const rc_render_stats *s) {
  static char text[64];
  text[0] = 0;
  if (s->gpu.lights_per_pass) snprintf(text, sizeof text, ", lights in passes of %u", s->gpu.lights_per_pass);
  return text;
}

void rc_stats_print(const rc_render_stats *s) {
  fprintf(stderr, "vkraycast: device %s (%s, %s)\n", s->device, s->device_type, s->driver);
  fprintf(stderr, "vkraycast: %ux%u, %u spp, %zu spheres + %zu triangles + %zu quadrics + %zu planes + %zu composites, "
          "%zu lights; %s backend, %s\n", s->width, s->height, s->samples_per_pixel, s->spheres, s->triangles, s->quadrics,
          s->planes,
          s->composites, s->lights, s->backend, s->precision);
  if (strcmp(s->backend, "gpu") == 0)
    fprintf(stderr, "vkraycast: %s buffers%s; %u tiles, %u dispatches, %u samples per batch%s\n",
            rc_scene_buffer_names[s->gpu.scene_buffers], s->gpu.staging ? ", staging" : "",
            s->gpu.tiles, s->gpu.dispatches, s->gpu.plan.batch_samples, light_passes_text(s));
  else
    fprintf(stderr, "vkraycast: %u threads; vectors of 8 pixels would keep %.0f %% of their lanes busy\n", s->threads,
            100 * s->simd8_efficiency);
  if (s->bvh.nodes)
    fprintf(stderr, "vkraycast: BVH %u nodes, %u leaves (at most %u objects), depth %u, built in %.1f ms; %u exact "
            "repeats of an earlier object left out, %u objects tested beside it\n", s->bvh.nodes, s->bvh.leaves,
            s->bvh.max_leaf, s->bvh.depth, s->bvh.build_ms, s->bvh.repeats, s->bvh.loose);
  if (s->rerender && strcmp(s->rerender, "off") != 0)
    fprintf(stderr, "vkraycast: certified: %llu samples uncertified (first at the primary hit %llu, its shadow rays "
            "%llu, a mirror bounce %llu); %llu samples of %llu pixels rendered again in f64 (%s), %.1f ms\n",
            (unsigned long long)s->samples_uncertified, (unsigned long long)s->uncertified_at[0],
            (unsigned long long)s->uncertified_at[1], (unsigned long long)s->uncertified_at[2],
            (unsigned long long)s->samples_rerendered, (unsigned long long)s->pixels_rerendered, s->rerender,
            s->rerender_ms);
  if (s->light_buffers.lights)
    fprintf(stderr, "vkraycast: light buffers for %u lights: %llu cells, %llu empty, %llu with a list, %llu with a "
            "subtree; %.1f KiB, built in %.1f ms\n", s->light_buffers.lights, (unsigned long long)s->light_buffers.cells,
            (unsigned long long)s->light_buffers.empty, (unsigned long long)s->light_buffers.lists,
            (unsigned long long)s->light_buffers.subtrees, s->light_buffers.bytes / 1024.0, s->light_buffers.build_ms);
  if (s->light_buffers.eye_tile)
    fprintf(stderr, "vkraycast: eye buffer of %u-pixel tiles: %llu tiles, %llu empty, %llu with a list, %llu with a "
            "subtree\n", s->light_buffers.eye_tile, (unsigned long long)s->light_buffers.eye_cells,
            (unsigned long long)s->light_buffers.eye_empty, (unsigned long long)s->light_buffers.eye_lists,
            (unsigned long long)s->light_buffers.eye_subtrees);
  if (strcmp(s->backend, "gpu") == 0)
    fprintf(stderr, "vkraycast: parse %.1f ms, upload %.1f ms, pipeline %.1f ms, first frame %.1f ms, render %.1f ms "
            "(GPU), %.1f ms (wall), readback %.1f ms, write %.1f ms\n",
            s->parse_ms, s->gpu.upload_ms, s->gpu.pipeline_ms, s->first_frame_ms, s->render_ms, s->render_wall_ms,
            s->gpu.readback_ms, s->write_ms);
  else
    fprintf(stderr, "vkraycast: parse %.1f ms, first frame %.1f ms, render %.1f ms (wall), write %.1f ms\n",
            s->parse_ms, s->first_frame_ms, s->render_ms, s->write_ms);
  fprintf(stderr, "vkraycast: rays %llu primary + %llu shadow + %llu reflection, %.2f Mrays/s\n",
          (unsigned long long)s->rays_primary, (unsigned long long)s->rays_shadow,
          (unsigned long long)s->rays_reflection, rc_stats_mrays_per_s(s));
}

/* The --stats-json fields that are one field of rc_render_stats each: one table, in the
 * order they are written, for both backends or the GPU's alone (absent on the CPU backend
 * rather than zero). The fields computed from others are written by rc_stats_json. */
typedef enum { F_STRING, F_BOOL, F_U32, F_U64, F_SIZE, F_DOUBLE } field_kind;
typedef struct {
  const char *key;
  field_kind kind;
  size_t offset;
} stats_field;
#define FIELD(key, kind, member) {key, kind, offsetof(rc_render_stats, member)}

static const stats_field head_fields[] = {
    FIELD("vkraycast", F_STRING, version),
    FIELD("scene", F_STRING, scene),
    FIELD("device", F_STRING, device),
    FIELD("device_type", F_STRING, device_type),
    FIELD("driver", F_STRING, driver),
    FIELD("backend", F_STRING, backend),
    FIELD("precision", F_STRING, precision),
    FIELD("precision_requested", F_STRING, precision_requested),
    FIELD("sphere_intersection", F_STRING, sphere_formula),
    FIELD("triangle_intersection", F_STRING, triangle_formula),
    FIELD("shadow_offset", F_STRING, shadow_offset),
    FIELD("camera_relative", F_BOOL, camera_relative),
    FIELD("packing_scale", F_DOUBLE, packing_scale),
    FIELD("budget_needs_f64", F_U32, budget_needs_f64),
    FIELD("budget_quantized", F_U32, budget_quantized),
    FIELD("budget_ms", F_DOUBLE, budget_ms),
};
static const stats_field frame_fields[] = {
    FIELD("width", F_U32, width),
    FIELD("height", F_U32, height),
    FIELD("samples_per_pixel", F_U32, samples_per_pixel),
};
static const stats_field scene_fields[] = {
    FIELD("part_ms", F_DOUBLE, part_ms),
    FIELD("spheres", F_SIZE, spheres),
    FIELD("triangles", F_SIZE, triangles),
    FIELD("lights", F_SIZE, lights),
    FIELD("quadrics", F_SIZE, quadrics),
    FIELD("planes", F_SIZE, planes),
    FIELD("composites", F_SIZE, composites),
    FIELD("materials", F_SIZE, materials),
    FIELD("shadows", F_BOOL, shadows),
    FIELD("rays_primary", F_U64, rays_primary),
    FIELD("rays_shadow", F_U64, rays_shadow),
    FIELD("rays_reflection", F_U64, rays_reflection),
    FIELD("patch_unconverged", F_U64, patch_unconverged),
};
static const stats_field bvh_fields[] = {
    FIELD("bvh_build_ms", F_DOUBLE, bvh.build_ms),
    FIELD("bvh_nodes", F_U32, bvh.nodes),
    FIELD("bvh_depth", F_U32, bvh.depth),
    FIELD("bvh_repeats_left_out", F_U32, bvh.repeats),
    FIELD("bvh_loose_objects", F_U32, bvh.loose),
    FIELD("samples_uncertified", F_U64, samples_uncertified),
    FIELD("samples_uncertified_hit", F_U64, uncertified_at[0]),
    FIELD("samples_uncertified_shadow", F_U64, uncertified_at[1]),
    FIELD("samples_uncertified_bounce", F_U64, uncertified_at[2]),
    FIELD("pixels_rerendered", F_U64, pixels_rerendered),
    FIELD("samples_rerendered", F_U64, samples_rerendered),
    FIELD("rerender", F_STRING, rerender),
    FIELD("rerender_ms", F_DOUBLE, rerender_ms),
    FIELD("light_buffers", F_U32, light_buffers.lights),
    FIELD("light_buffer_cells", F_U64, light_buffers.cells),
    FIELD("light_buffer_empty_cells", F_U64, light_buffers.empty),
    FIELD("light_buffer_list_cells", F_U64, light_buffers.lists),
    FIELD("light_buffer_subtree_cells", F_U64, light_buffers.subtrees),
    FIELD("light_buffer_bytes", F_U64, light_buffers.bytes),
    FIELD("light_buffer_ms", F_DOUBLE, light_buffers.build_ms),
    FIELD("eye_buffer_tile", F_U32, light_buffers.eye_tile),
    FIELD("eye_buffer_cells", F_U64, light_buffers.eye_cells),
    FIELD("eye_buffer_empty_cells", F_U64, light_buffers.eye_empty),
    FIELD("eye_buffer_list_cells", F_U64, light_buffers.eye_lists),
    FIELD("eye_buffer_subtree_cells", F_U64, light_buffers.eye_subtrees),
    FIELD("parse_ms", F_DOUBLE, parse_ms),
    FIELD("first_frame_ms", F_DOUBLE, first_frame_ms),
    FIELD("render_ms", F_DOUBLE, render_ms),
    FIELD("render_wall_ms", F_DOUBLE, render_wall_ms),
    FIELD("write_ms", F_DOUBLE, write_ms),
    FIELD("cpu_ms", F_DOUBLE, cpu_ms),
};
static const stats_field gpu_fields[] = {
    FIELD("staging", F_BOOL, gpu.staging),
    FIELD("gpu_encoded", F_BOOL, gpu.encoded),
    FIELD("readback_cached", F_BOOL, gpu.readback_cached),
    FIELD("upload_ms", F_DOUBLE, gpu.upload_ms),
    FIELD("pipeline_ms", F_DOUBLE, gpu.pipeline_ms),
    FIELD("pipeline_cache_hit", F_BOOL, gpu.pipeline_cache_hit),
    FIELD("spec_cache_hit", F_BOOL, gpu.spec_cache_hit),
    FIELD("specialize_ms", F_DOUBLE, gpu.specialize_ms),
    FIELD("readback_ms", F_DOUBLE, gpu.readback_ms),
    FIELD("upload_bytes", F_U64, gpu.upload_bytes),
    FIELD("readback_bytes", F_U64, gpu.readback_bytes),
    FIELD("tiles", F_U32, gpu.tiles),
    FIELD("dispatches", F_U32, gpu.dispatches),
    FIELD("readback_submits", F_U32, gpu.readback_submits),
    FIELD("readback_overlapped", F_U32, gpu.readback_overlapped),
    FIELD("bands_overlapped", F_U32, gpu.bands_overlapped),
    FIELD("band_overlapped_ms", F_DOUBLE, gpu.band_overlapped_ms),
    FIELD("band_hidden_ms", F_DOUBLE, gpu.band_hidden_ms),
    FIELD("tile_budget_ms", F_DOUBLE, gpu.tile_budget_ms),
    FIELD("max_dispatch_ms", F_DOUBLE, gpu.max_dispatch_ms),
    FIELD("dispatches_over_budget", F_U32, gpu.over_budget),
    FIELD("batch_samples", F_U32, gpu.plan.batch_samples),
    FIELD("batch_samples_end", F_U32, gpu.batch_samples_end),
    FIELD("lights_per_pass", F_U32, gpu.lights_per_pass),
    FIELD("loop_steps_per_sample", F_U64, gpu.plan.steps_per_sample),
    FIELD("budget_retries", F_U32, gpu.budget_retries),
    FIELD("loop_budget", F_U32, gpu.loop_budget),
    FIELD("subgroup_size", F_U32, gpu.subgroup_size),
    FIELD("workgroup_x", F_U32, gpu.workgroup_x),
    FIELD("workgroup_y", F_U32, gpu.workgroup_y),
    FIELD("memory_blocks", F_U32, gpu.memory_blocks),
};
#define ADD_FIELDS(o, s, table) add_fields(o, s, table, sizeof table / sizeof *table)

static void add_fields(cJSON *o, const rc_render_stats *s, const stats_field *f, size_t n) {
  for (size_t i = 0; i < n; i++) {
    const void *p = (const char *)s + f[i].offset;
    switch (f[i].kind) {
    case F_STRING: cJSON_AddStringToObject(o, f[i].key, *(const char *const *)p); break;
    case F_BOOL: cJSON_AddBoolToObject(o, f[i].key, *(const bool *)p); break;
    case F_U32: cJSON_AddNumberToObject(o, f[i].key, *(const uint32_t *)p); break;
    case F_U64: cJSON_AddNumberToObject(o, f[i].key, (double)*(const uint64_t *)p); break;
    case F_SIZE: cJSON_AddNumberToObject(o, f[i].key, (double)*(const size_t *)p); break;
    case F_DOUBLE: cJSON_AddNumberToObject(o, f[i].key, *(const double *)p); break;
    }
  }
}

char *rc_stats_json(const rc_render_stats *s) {
  cJSON *o = cJSON_CreateObject();
  ADD_FIELDS(o, s, head_fields);
  if (s->prepared) cJSON_AddStringToObject(o, "prepared", s->prepared);
  if (s->threads) cJSON_AddNumberToObject(o, "threads", s->threads);
  if (s->threads) cJSON_AddNumberToObject(o, "simd8_efficiency", s->simd8_efficiency);
  ADD_FIELDS(o, s, frame_fields);
  const double region[4] = {s->region.x0, s->region.y0, s->region.x1, s->region.y1};
  cJSON_AddItemToObject(o, "region", cJSON_CreateDoubleArray(region, 4));
  if (s->shard_count) {
    char shard[24];
    snprintf(shard, sizeof shard, "%u/%u", s->shard_index, s->shard_count);
    cJSON_AddStringToObject(o, "shard", shard);
  }
  ADD_FIELDS(o, s, scene_fields);
  cJSON_AddStringToObject(o, "accel", s->bvh.nodes ? "bvh" : "none");
  ADD_FIELDS(o, s, bvh_fields);
  struct rusage ru;
  if (getrusage(RUSAGE_SELF, &ru) == 0) cJSON_AddNumberToObject(o, "peak_rss_mib", (double)ru.ru_maxrss / 1024.0);
  cJSON_AddNumberToObject(o, "mrays_per_s", rc_stats_mrays_per_s(s));
  cJSON_AddNumberToObject(o, "repeat", s->repeat);
  /* What only the GPU backend has: absent on the CPU backend rather than zero. */
  if (strcmp(s->backend, "gpu") == 0) {
    cJSON_AddStringToObject(o, "pipeline", s->generic_pipeline ? "generic" : "specialized");
    cJSON_AddStringToObject(o, "spec_constants", s->gpu.host_specialized ? "host" : "driver");
    cJSON_AddStringToObject(o, "scene_buffers", rc_scene_buffer_names[s->gpu.scene_buffers]);
    ADD_FIELDS(o, s, gpu_fields);
    cJSON_AddNumberToObject(o, "memory_mib", (double)s->gpu.memory_bytes / (1 << 20));
  }
  char *text = cJSON_Print(o);
  cJSON_Delete(o);
  char *line = text ? malloc(strlen(text) + 2) : NULL;
  if (line) sprintf(line, "%s\n", text);
  free(text);
  return line;
}
