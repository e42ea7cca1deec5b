#include "scene/prepared_summary.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void rc_blob_put(rc_blob *b, const void *bytes, size_t len) {
  if (b->failed) return;
  if (len > b->cap - b->len) {
    size_t cap = b->cap ? b->cap : 4096;
    while (cap - b->len < len) {
      if (cap > SIZE_MAX / 2) {
        b->failed = true;
        return;
      }
      cap *= 2;
    }
    unsigned char *d = realloc(b->data, cap);
    if (!d) {
      b->failed = true;
      return;
    }
    b->data = d, b->cap = cap;
  }
  if (len) memcpy(b->data + b->len, bytes, len);
  b->len += len;
}

void rc_blob_align(rc_blob *b, size_t align) {
  static const unsigned char zeros[64];
  size_t pad = (align - b->len % align) % align;
  rc_blob_put(b, zeros, pad);
}

static void put_u32(rc_blob *b, uint32_t v) { rc_blob_put(b, &v, sizeof v); }
static void put_u64(rc_blob *b, uint64_t v) { rc_blob_put(b, &v, sizeof v); }
static void put_f64(rc_blob *b, double v) { rc_blob_put(b, &v, sizeof v); }
static void put_d3(rc_blob *b, dvec3 v) {
  put_f64(b, v.x), put_f64(b, v.y), put_f64(b, v.z);
}
static void put_str(rc_blob *b, const char *s) {
  size_t n = s ? strlen(s) : 0;
  put_u64(b, n);
  rc_blob_put(b, s ? s : "", n + 1);
}

/* Each section begins with its own tag, so that a summary is never read as another. */
#define SUMMARY_TAG 0x4d4d5553u /* "SUMM" */

void rc_summary_encode(rc_blob *b, const rc_scene *s, const rc_packed_scene *p, const rc_prepared_tree *tree) {
  put_u32(b, SUMMARY_TAG);
  put_str(b, s->path);
  put_u32(b, s->width), put_u32(b, s->height), put_u32(b, s->samples_per_pixel);
  const rc_camera_def *c = &s->camera;
  put_u32(b, c->projection);
  put_d3(b, c->eye), put_d3(b, c->look_at), put_d3(b, c->up);
  put_f64(b, c->fov_y_deg), put_f64(b, c->view_height);
  put_d3(b, s->background), put_d3(b, s->ambient_light);
  put_u32(b, s->specular_model), put_u32(b, s->reflection_depth), put_u32(b, s->seed);
  const rc_quality *q = &s->quality;
  put_u32(b, q->precision), put_u32(b, q->sphere), put_u32(b, q->triangle), put_u32(b, q->offset);
  put_f64(b, q->offset_epsilon);
  put_u32(b, q->camera_relative), put_u32(b, q->rescale), put_u32(b, q->shadows);
  const size_t counts[] = {s->material_count, s->light_count,   s->sphere_count,         s->triangle_count,
                           s->degenerate_triangles, s->degenerate_in_meshes, s->quadric_count, s->plane_count,
                           s->csg_leaf_count, s->csg_count, s->csg_triangle_count};
  for (size_t i = 0; i < sizeof counts / sizeof *counts; i++) put_u64(b, counts[i]);
  for (size_t i = 0; i < s->material_count; i++) {
    const rc_material_def *m = &s->materials[i];
    put_str(b, m->name);
    put_d3(b, m->ambient), put_d3(b, m->diffuse), put_d3(b, m->specular), put_d3(b, m->mirror),
        put_d3(b, m->emission);
    put_f64(b, m->shininess);
  }
  for (size_t i = 0; i < s->csg_count; i++) {
    put_u32(b, s->csgs[i].steps);
    put_d3(b, s->csgs[i].lo), put_d3(b, s->csgs[i].hi);
  }
  put_u32(b, s->truncate_8bit), put_u32(b, s->encoding_8bit);
  put_f64(b, s->gamma_8bit), put_f64(b, s->exposure_8bit);
  put_str(b, s->output_name);
  put_u64(b, s->input_count);
  for (size_t i = 0; i < s->input_count; i++) put_str(b, s->inputs[i]);
  put_u64(b, s->origin_count);
  for (size_t i = 0; i < s->origin_count; i++) {
    const rc_origin *o = &s->origins[i];
    put_u32(b, o->kind), put_u32(b, o->line), put_u32(b, o->col), put_u32(b, o->item);
    put_str(b, o->what);
    put_u64(b, o->first), put_u64(b, o->count);
  }
  put_d3(b, p->origin);
  put_f64(b, p->scale);
  const uint32_t sizes[] = {p->triangle_total,    p->transform_count,  p->normal_count,
                            p->one_sided_triangle_count, p->quadric_total, p->csg_program_length,
                            p->mesh_operand_count, p->bvh_node_total,  p->bvh_prim_total,
                            p->texel_count,       p->texture_count, p->uv_count, p->uv_first};
  for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) put_u32(b, sizes[i]);
  put_u32(b, p->bvh);
  put_u32(b, tree->object_nodes);
  put_u32(b, tree->loose_kinds);
  put_u64(b, tree->operand_steps);
  const rc_bvh_stats *t = &tree->stats;
  put_f64(b, t->build_ms);
  put_u32(b, t->nodes), put_u32(b, t->leaves), put_u32(b, t->depth), put_u32(b, t->max_leaf), put_u32(b, t->repeats);
  put_u32(b, SUMMARY_TAG);
}

/* A reader over the section; `bad` once it ran past the end (every later get gives 0). */
typedef struct {
  const unsigned char *p;
  size_t len, at;
  bool bad;
} reader;

static void get(reader *r, void *out, size_t n) {
  if (r->bad || n > r->len - r->at) {
    r->bad = true;
    memset(out, 0, n);
    return;
  }
  memcpy(out, r->p + r->at, n);
  r->at += n;
}
static uint32_t get_u32(reader *r) {
  uint32_t v;
  get(r, &v, sizeof v);
  return v;
}
static uint64_t get_u64(reader *r) {
  uint64_t v;
  get(r, &v, sizeof v);
  return v;
}
static double get_f64(reader *r) {
  double v;
  get(r, &v, sizeof v);
  return v;
}
static dvec3 get_d3(reader *r) {
  dvec3 v;
  v.x = get_f64(r), v.y = get_f64(r), v.z = get_f64(r);
  return v;
}
/* A string where it lies in the section (NUL-terminated there), or NULL. */
static const char *get_str(reader *r) {
  uint64_t n = get_u64(r);
  if (r->bad || n >= r->len - r->at || r->p[r->at + n] != 0 || memchr(r->p + r->at, 0, n)) {
    r->bad = true;
    return NULL;
  }
  const char *s = (const char *)r->p + r->at;
  r->at += n + 1;
  return s;
}
static bool finite_d3(dvec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

static const char *decode_settings(reader *r, rc_scene *s) {
  s->width = get_u32(r), s->height = get_u32(r), s->samples_per_pixel = get_u32(r);
  rc_camera_def *c = &s->camera;
  c->projection = get_u32(r);
  c->eye = get_d3(r), c->look_at = get_d3(r), c->up = get_d3(r);
  c->fov_y_deg = get_f64(r), c->view_height = get_f64(r);
  s->background = get_d3(r), s->ambient_light = get_d3(r);
  s->specular_model = get_u32(r), s->reflection_depth = get_u32(r), s->seed = get_u32(r);
  rc_quality *q = &s->quality;
  q->precision = get_u32(r), q->sphere = get_u32(r), q->triangle = get_u32(r), q->offset = get_u32(r);
  q->offset_epsilon = get_f64(r);
  uint32_t relative = get_u32(r), rescale = get_u32(r), shadows = get_u32(r);
  q->camera_relative = relative, q->rescale = rescale, q->shadows = shadows;
  const char *field = NULL;
  if (r->bad) return "the settings are cut short";
  if (s->width < 1 || s->width > RC_MAX_IMAGE_SIDE || s->height < 1 || s->height > RC_MAX_IMAGE_SIDE)
    return "the image size is out of range";
  if (s->samples_per_pixel < 1 || s->samples_per_pixel > RC_MAX_SAMPLES_PER_PIXEL ||
      s->reflection_depth > RC_MAX_REFLECTION_DEPTH)
    return "samples per pixel or the reflection depth is out of range";
  if (c->projection > RC_PROJECTION_PARALLEL || s->specular_model > RC_SPECULAR_PHONG || q->precision > 2 ||
      q->sphere > 1 || q->triangle > 2 || q->offset > 3 || relative > 1 || rescale > 1 || shadows > 1)
    return "a setting names no known choice";
  if (!finite_d3(c->eye) || !finite_d3(c->look_at) || !finite_d3(c->up) || !finite_d3(s->background) ||
      !finite_d3(s->ambient_light) || !(q->offset_epsilon > 0) || !isfinite(q->offset_epsilon) ||
      rc_scene_camera_problem(c, &field))
    return "the camera or a setting is not a valid value";
  return NULL;
}

/* Counts up to this: far above any scene that fits a device, far below overflow. */
#define MAX_COUNT ((uint64_t)1 << 31)

static const char *decode_lists(reader *r, rc_scene *s) {
  uint64_t counts[11];
  for (int i = 0; i < 11; i++) counts[i] = get_u64(r);
  for (int i = 0; i < 11; i++)
    if (counts[i] > MAX_COUNT) return "a count is out of range";
  size_t *const fields[] = {&s->material_count,      &s->light_count,   &s->sphere_count, &s->triangle_count,
                            &s->degenerate_triangles, &s->degenerate_in_meshes, &s->quadric_count,
                            &s->plane_count,          &s->csg_leaf_count, &s->csg_count, &s->csg_triangle_count};
  /* Each material takes at least 129 bytes of the section, each composite 52: a count
   * the section cannot hold is refused before anything is allocated for it. */
  if (r->bad || counts[0] > (r->len - r->at) / 129 || counts[9] > (r->len - r->at) / 52)
    return "the counts are cut short";
  s->materials = calloc(counts[0] + 1, sizeof *s->materials);
  s->csgs = calloc(counts[9] + 1, sizeof *s->csgs);
  if (!s->materials || !s->csgs) return "out of memory";
  for (uint64_t i = 0; i < counts[0] && !r->bad; i++) {
    rc_material_def *m = &s->materials[i];
    const char *name = get_str(r);
    m->ambient = get_d3(r), m->diffuse = get_d3(r), m->specular = get_d3(r), m->mirror = get_d3(r);
    m->emission = get_d3(r);
    m->shininess = get_f64(r);
    if (r->bad) break;
    m->name = strdup(name);
    s->material_count++;
    if (!m->name) return "out of memory";
  }
  for (uint64_t i = 0; i < counts[9] && !r->bad; i++) {
    s->csgs[i].steps = get_u32(r);
    s->csgs[i].lo = get_d3(r), s->csgs[i].hi = get_d3(r);
    s->csg_count++;
  }
  if (r->bad) return "the materials or composites are cut short";
  for (int i = 0; i < 11; i++) *fields[i] = (size_t)counts[i];
  return NULL;
}

static const char *decode_output(reader *r, rc_scene *s) {
  uint32_t truncate = get_u32(r);
  s->encoding_8bit = get_u32(r);
  s->gamma_8bit = get_f64(r), s->exposure_8bit = get_f64(r);
  const char *name = get_str(r);
  if (r->bad) return "the output rules are cut short";
  if (truncate > 1 || s->encoding_8bit > RC_SCENE_ENCODING_GAMMA) return "an output rule names no known choice";
  s->truncate_8bit = truncate;
  /* 0: the scene named none (the default applies). */
  if (!(s->gamma_8bit == 0 || (s->gamma_8bit >= RC_MIN_GAMMA && s->gamma_8bit <= RC_MAX_GAMMA)) ||
      !(fabs(s->exposure_8bit) <= RC_MAX_EXPOSURE))
    return "the gamma or the exposure is out of range";
  if (strlen(name) >= sizeof s->output_name || strchr(name, '/')) return "the output name is not a bare file name";
  memcpy(s->output_name, name, strlen(name) + 1);
  uint64_t n = get_u64(r);
  if (r->bad || n > (r->len - r->at) / 9) return "the inputs are cut short";
  for (uint64_t i = 0; i < n; i++) {
    const char *path = get_str(r);
    if (!path) return "the inputs are cut short";
    if (!rc_scene_note_input(s, path)) return "out of memory";
  }
  return NULL;
}

static const char *decode_origins(reader *r, rc_scene *s) {
  uint64_t n = get_u64(r);
  if (r->bad || n > (r->len - r->at) / 41) return "the origins are cut short";
  s->origins = calloc(n + 1, sizeof *s->origins);
  if (!s->origins) return "out of memory";
  size_t counts[RC_ORIGIN_KINDS];
  rc_scene_counts(s, counts);
  for (uint64_t i = 0; i < n; i++) {
    rc_origin *o = &s->origins[i];
    o->kind = get_u32(r), o->line = get_u32(r), o->col = get_u32(r), o->item = get_u32(r);
    o->what = get_str(r);
    uint64_t first = get_u64(r), count = get_u64(r);
    if (r->bad) return "the origins are cut short";
    if (o->kind >= RC_ORIGIN_KINDS || first > counts[o->kind] || count > counts[o->kind] - first)
      return "an origin names primitives the scene does not have";
    o->first = (size_t)first, o->count = (size_t)count;
    s->origin_count = s->origin_capacity = i + 1;
  }
  return NULL;
}

static const char *decode_packed(reader *r, rc_packed_scene *p, rc_prepared_tree *tree) {
  p->origin = get_d3(r);
  p->scale = get_f64(r);
  uint32_t *const sizes[] = {&p->triangle_total, &p->transform_count, &p->normal_count,
                             &p->one_sided_triangle_count, &p->quadric_total, &p->csg_program_length,
                             &p->mesh_operand_count, &p->bvh_node_total, &p->bvh_prim_total,
                             &p->texel_count, &p->texture_count, &p->uv_count, &p->uv_first};
  for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) *sizes[i] = get_u32(r);
  uint32_t bvh = get_u32(r);
  tree->object_nodes = get_u32(r);
  tree->loose_kinds = get_u32(r);
  tree->operand_steps = get_u64(r);
  rc_bvh_stats *t = &tree->stats;
  t->build_ms = get_f64(r);
  t->nodes = get_u32(r), t->leaves = get_u32(r), t->depth = get_u32(r), t->max_leaf = get_u32(r);
  t->repeats = get_u32(r);
  if (get_u32(r) != SUMMARY_TAG || r->bad) return "the packed scene's sizes are cut short";
  if (r->at != r->len) return "the summary has bytes after its end";
  if (bvh > 1 || !finite_d3(p->origin) || !(p->scale > 0) || !isfinite(p->scale))
    return "the packed scene's origin or unit is not a valid value";
  for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++)
    if (*sizes[i] > MAX_COUNT) return "a packed size is out of range";
  p->bvh = bvh;
  return NULL;
}

const char *rc_summary_decode(const unsigned char *bytes, size_t len, rc_scene *s, rc_packed_scene *p,
                              rc_prepared_tree *tree) {
  memset(s, 0, sizeof *s);
  memset(p, 0, sizeof *p);
  memset(tree, 0, sizeof *tree);
  reader r = {bytes, len, 0, false};
  const char *why = get_u32(&r) != SUMMARY_TAG ? "the summary's tag is missing" : NULL;
  const char *path = why ? NULL : get_str(&r);
  if (!why && !path) why = "the scene's name is cut short";
  if (!why && !(s->path = strdup(path))) why = "out of memory";
  if (!why) why = decode_settings(&r, s);
  if (!why) why = decode_lists(&r, s);
  if (!why) why = decode_output(&r, s);
  if (!why) why = decode_origins(&r, s);
  if (!why) why = decode_packed(&r, p, tree);
  if (why) rc_scene_free(s);
  return why;
}
