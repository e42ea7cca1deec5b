#include "cli/stats.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
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
    fprintf(stderr, "vkraycast: %u threads\n", s->threads);
  if (s->bvh.nodes)
    fprintf(stderr, "vkraycast: BVH %u nodes, %u leaves (at most %u objects), depth %u, built in %.1f ms; %u exact "
            "repeats of an earlier object left out\n", s->bvh.nodes, s->bvh.leaves, s->bvh.max_leaf, s->bvh.depth,
            s->bvh.build_ms, s->bvh.repeats);
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

static void add_gpu_fields(cJSON *o, const rc_render_stats *s);

char *rc_stats_json(const rc_render_stats *s) {
  cJSON *o = cJSON_CreateObject();
  bool gpu = strcmp(s->backend, "gpu") == 0;
  cJSON_AddStringToObject(o, "vkraycast", s->version);
  cJSON_AddStringToObject(o, "scene", s->scene);
  cJSON_AddStringToObject(o, "device", s->device);
  cJSON_AddStringToObject(o, "device_type", s->device_type);
  cJSON_AddStringToObject(o, "driver", s->driver);
  cJSON_AddStringToObject(o, "backend", s->backend);
  cJSON_AddStringToObject(o, "precision", s->precision);
  cJSON_AddStringToObject(o, "precision_requested", s->precision_requested);
  cJSON_AddStringToObject(o, "sphere_intersection", s->sphere_formula);
  cJSON_AddStringToObject(o, "triangle_intersection", s->triangle_formula);
  cJSON_AddStringToObject(o, "shadow_offset", s->shadow_offset);
  cJSON_AddBoolToObject(o, "camera_relative", s->camera_relative);
  cJSON_AddNumberToObject(o, "packing_scale", s->packing_scale);
  cJSON_AddNumberToObject(o, "budget_needs_f64", s->budget_needs_f64);
  cJSON_AddNumberToObject(o, "budget_quantized", s->budget_quantized);
  cJSON_AddNumberToObject(o, "budget_ms", s->budget_ms);
  if (s->threads) cJSON_AddNumberToObject(o, "threads", s->threads);
  cJSON_AddNumberToObject(o, "width", s->width);
  cJSON_AddNumberToObject(o, "height", s->height);
  cJSON_AddNumberToObject(o, "samples_per_pixel", s->samples_per_pixel);
  const double region[4] = {s->region.x0, s->region.y0, s->region.x1, s->region.y1};
  cJSON_AddItemToObject(o, "region", cJSON_CreateDoubleArray(region, 4));
  if (s->shard_count) {
    char shard[24];
    snprintf(shard, sizeof shard, "%u/%u", s->shard_index, s->shard_count);
    cJSON_AddStringToObject(o, "shard", shard);
  }
  cJSON_AddNumberToObject(o, "part_ms", s->part_ms);
  cJSON_AddNumberToObject(o, "spheres", (double)s->spheres);
  cJSON_AddNumberToObject(o, "triangles", (double)s->triangles);
  cJSON_AddNumberToObject(o, "lights", (double)s->lights);
  cJSON_AddNumberToObject(o, "quadrics", (double)s->quadrics);
  cJSON_AddNumberToObject(o, "planes", (double)s->planes);
  cJSON_AddNumberToObject(o, "composites", (double)s->composites);
  cJSON_AddNumberToObject(o, "materials", (double)s->materials);
  cJSON_AddBoolToObject(o, "shadows", s->shadows);
  cJSON_AddNumberToObject(o, "rays_primary", (double)s->rays_primary);
  cJSON_AddNumberToObject(o, "rays_shadow", (double)s->rays_shadow);
  cJSON_AddNumberToObject(o, "rays_reflection", (double)s->rays_reflection);
  cJSON_AddStringToObject(o, "accel", s->bvh.nodes ? "bvh" : "none");
  cJSON_AddNumberToObject(o, "bvh_build_ms", s->bvh.build_ms);
  cJSON_AddNumberToObject(o, "bvh_nodes", s->bvh.nodes);
  cJSON_AddNumberToObject(o, "bvh_depth", s->bvh.depth);
  cJSON_AddNumberToObject(o, "bvh_repeats_left_out", s->bvh.repeats);
  cJSON_AddNumberToObject(o, "parse_ms", s->parse_ms);
  cJSON_AddNumberToObject(o, "first_frame_ms", s->first_frame_ms);
  cJSON_AddNumberToObject(o, "render_ms", s->render_ms);
  cJSON_AddNumberToObject(o, "render_wall_ms", s->render_wall_ms);
  cJSON_AddNumberToObject(o, "write_ms", s->write_ms);
  cJSON_AddNumberToObject(o, "cpu_ms", s->cpu_ms);
  struct rusage ru;
  if (getrusage(RUSAGE_SELF, &ru) == 0) cJSON_AddNumberToObject(o, "peak_rss_mib", (double)ru.ru_maxrss / 1024.0);
  cJSON_AddNumberToObject(o, "mrays_per_s", rc_stats_mrays_per_s(s));
  cJSON_AddNumberToObject(o, "repeat", s->repeat);
  /* What only the GPU backend has: absent on the CPU backend rather than zero. */
  if (gpu) add_gpu_fields(o, s);
  char *text = cJSON_Print(o);
  cJSON_Delete(o);
  char *line = text ? malloc(strlen(text) + 2) : NULL;
  if (line) sprintf(line, "%s\n", text);
  free(text);
  return line;
}

static void add_gpu_fields(cJSON *o, const rc_render_stats *s) {
  cJSON_AddStringToObject(o, "pipeline", s->generic_pipeline ? "generic" : "specialized");
  cJSON_AddStringToObject(o, "scene_buffers", rc_scene_buffer_names[s->gpu.scene_buffers]);
  cJSON_AddBoolToObject(o, "staging", s->gpu.staging);
  cJSON_AddNumberToObject(o, "upload_ms", s->gpu.upload_ms);
  cJSON_AddNumberToObject(o, "pipeline_ms", s->gpu.pipeline_ms);
  cJSON_AddBoolToObject(o, "pipeline_cache_hit", s->gpu.pipeline_cache_hit);
  cJSON_AddNumberToObject(o, "readback_ms", s->gpu.readback_ms);
  cJSON_AddNumberToObject(o, "tiles", s->gpu.tiles);
  cJSON_AddNumberToObject(o, "dispatches", s->gpu.dispatches);
  cJSON_AddNumberToObject(o, "tile_budget_ms", s->gpu.tile_budget_ms);
  cJSON_AddNumberToObject(o, "max_dispatch_ms", s->gpu.max_dispatch_ms);
  cJSON_AddNumberToObject(o, "dispatches_over_budget", s->gpu.over_budget);
  cJSON_AddNumberToObject(o, "batch_samples", s->gpu.plan.batch_samples);
  cJSON_AddNumberToObject(o, "lights_per_pass", s->gpu.lights_per_pass);
  cJSON_AddNumberToObject(o, "loop_steps_per_sample", (double)s->gpu.plan.steps_per_sample);
  cJSON_AddNumberToObject(o, "budget_retries", s->gpu.budget_retries);
  cJSON_AddNumberToObject(o, "loop_budget", s->gpu.loop_budget);
  cJSON_AddNumberToObject(o, "subgroup_size", s->gpu.subgroup_size);
  cJSON_AddNumberToObject(o, "workgroup_x", s->gpu.workgroup_x);
  cJSON_AddNumberToObject(o, "workgroup_y", s->gpu.workgroup_y);
  cJSON_AddNumberToObject(o, "memory_blocks", s->gpu.memory_blocks);
  cJSON_AddNumberToObject(o, "memory_mib", (double)s->gpu.memory_bytes / (1 << 20));
}
