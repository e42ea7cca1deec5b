#include "scene/prepared.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <xxhash.h>

#include "scene/prepared_check.h"
#include "scene/prepared_summary.h"

/* "VKRS", then bytes that text-mode transfers and mail gateways change (as PNG's do). */
static const char magic[8] = {'V', 'K', 'R', 'S', '\r', '\n', 0x1a, '\n'};
#define BYTE_ORDER_MARK 0x01020304u

enum { SEC_SUMMARY, SEC_SPHERES, SEC_TRIANGLES, SEC_MATERIALS, SEC_LIGHTS, SEC_TRANSFORMS, SEC_NORMALS,
       SEC_QUADRICS, SEC_CSG, SEC_PROGRAM, SEC_OPERANDS, SEC_TEXELS, SEC_NODES, SEC_PRIMS, SEC_HASHES, SECTIONS };
static const char *const section_names[SECTIONS] = {
    "summary", "spheres", "triangles", "materials", "lights", "transforms", "vertex normals", "quadrics",
    "composites", "composite programs", "mesh operands", "textures", "BVH nodes", "BVH references", "array hashes"};
#define SECTION_ALIGN 64u

typedef struct vkrs_header {
  char magic[8];
  uint32_t byte_order, version;
  uint64_t layout;     /* layout_word(): the struct sizes this build reads the arrays with */
  uint64_t file_bytes;
  uint64_t checksum;   /* XXH3-64 of every byte after this field */
  uint64_t source_digest;
  uint64_t offset[SECTIONS], bytes[SECTIONS];
} vkrs_header;
#define CHECKED_FROM offsetof(vkrs_header, source_digest)

struct rc_prepared {
  char *name;
  void *map;
  size_t map_len;
  rc_packed_scene packed; /* the scalars and the arrays where they lie; the frame as prepared */
  rc_prepared_tree tree;
  uint64_t source_digest;
  const uint64_t *array_hashes;
  bool camera_relative, rescale;
};

static uint64_t layout_word(void) {
  const uint64_t sizes[] = {sizeof(vkrs_header),    SECTIONS,
                            sizeof(packed_sphere),  sizeof(packed_triangle),
                            sizeof(packed_material), sizeof(packed_light),
                            sizeof(packed_transform), sizeof(packed_vertex_normals),
                            sizeof(packed_quadric), sizeof(packed_csg),
                            sizeof(rc_mesh_operand), sizeof(packed_bvh_node),
                            sizeof(packed_texture), sizeof(packed_vertex_uvs), RC_PACKED_ARRAYS};
  return XXH3_64bits(sizes, sizeof sizes);
}

/* The bytes of each array section for these counts: every array has one element more than
 * it uses (Vulkan has no empty buffers), the reference arrays are padded to 4. */
static void section_sizes(const rc_packed_scene *p, uint64_t bytes[SECTIONS]) {
  const packed_frame *f = &p->frame;
  bytes[SEC_SPHERES] = ((uint64_t)f->sphere_count + 1) * sizeof(packed_sphere);
  bytes[SEC_TRIANGLES] = ((uint64_t)p->triangle_total + 1) * sizeof(packed_triangle);
  bytes[SEC_MATERIALS] = ((uint64_t)f->material_count + 1) * sizeof(packed_material);
  bytes[SEC_LIGHTS] = ((uint64_t)f->light_count + 1) * sizeof(packed_light);
  bytes[SEC_TRANSFORMS] = ((uint64_t)p->transform_count + 1) * sizeof(packed_transform);
  bytes[SEC_NORMALS] = ((uint64_t)p->normal_count + 1) * sizeof(packed_vertex_normals);
  bytes[SEC_QUADRICS] = ((uint64_t)p->quadric_total + 1) * sizeof(packed_quadric);
  bytes[SEC_CSG] = ((uint64_t)f->csg_count + 1) * sizeof(packed_csg);
  bytes[SEC_PROGRAM] = ((uint64_t)p->csg_program_length + 4) / 4 * 4 * sizeof(uint32_t);
  bytes[SEC_OPERANDS] = ((uint64_t)p->mesh_operand_count + 1) * sizeof(rc_mesh_operand);
  bytes[SEC_TEXELS] = ((uint64_t)p->texel_count + 1) * 4 * sizeof(uint32_t);
  bytes[SEC_NODES] = (uint64_t)p->bvh_node_total * sizeof(packed_bvh_node);
  bytes[SEC_PRIMS] = ((uint64_t)p->bvh_prim_total + 3) / 4 * 4 * sizeof(uint32_t);
  bytes[SEC_HASHES] = RC_PACKED_ARRAYS * sizeof(uint64_t);
}

/* The array pointers of a packed scene, in section order (SEC_SPHERES..SEC_PRIMS). */
static void array_slots(rc_packed_scene *p, void **slots[SECTIONS]) {
  void **s[SECTIONS] = {NULL,
                        (void **)&p->spheres,    (void **)&p->triangles, (void **)&p->materials,
                        (void **)&p->lights,     (void **)&p->transforms, (void **)&p->normals,
                        (void **)&p->quadrics,   (void **)&p->csg,       (void **)&p->csg_program,
                        (void **)&p->mesh_operands, (void **)&p->texels, (void **)&p->bvh_nodes,
                        (void **)&p->bvh_prims, NULL};
  memcpy(slots, s, sizeof s);
}

rc_status rc_prepared_encode(const rc_scene *scene, const rc_packed_scene *packed, const rc_bvh_stats *bvh,
                             uint64_t source_digest, void **bytes, size_t *len) {
  /* What the frame re-derivation will not give back: the tree's share of the frame. */
  rc_packed_scene plain = *packed;
  rc_scene_pack_frame(scene, &plain);
  rc_prepared_tree tree = {.stats = *bvh, .object_nodes = packed->frame.bvh_node_count,
                           .loose_kinds = packed->frame.loose_kinds,
                           .operand_steps = (uint64_t)packed->frame.csg_max_steps - plain.frame.csg_max_steps};
  /* Inputs by absolute path, so that a shard in another folder finds them. */
  rc_scene named = *scene;
  char **absolute = calloc(scene->input_count + 1, sizeof *absolute);
  if (!absolute) return RC_ERR_OUT_OF_MEMORY;
  for (size_t i = 0; i < scene->input_count; i++) {
    char path[PATH_MAX];
    absolute[i] = strdup(rc_resolve_path(scene->inputs[i], path, sizeof path) ? path : scene->inputs[i]);
  }
  named.inputs = absolute;
  rc_blob b = {0};
  vkrs_header h = {.byte_order = BYTE_ORDER_MARK, .version = RC_PREPARED_VERSION, .layout = layout_word(),
                   .source_digest = source_digest};
  memcpy(h.magic, magic, sizeof magic);
  rc_blob_put(&b, &h, sizeof h);
  rc_blob_align(&b, SECTION_ALIGN);
  h.offset[SEC_SUMMARY] = b.len;
  for (size_t i = 0; i < scene->input_count; i++) b.failed |= absolute[i] == NULL;
  rc_summary_encode(&b, &named, packed, &tree);
  h.bytes[SEC_SUMMARY] = b.len - h.offset[SEC_SUMMARY];
  for (size_t i = 0; i < scene->input_count; i++) free(absolute[i]);
  free(absolute);
  uint64_t hashes[RC_PACKED_ARRAYS];
  rc_packed_scene_array_hashes(packed, hashes);
  void **slots[SECTIONS];
  array_slots((rc_packed_scene *)packed, slots);
  uint64_t sizes[SECTIONS];
  section_sizes(packed, sizes);
  for (int s = SEC_SPHERES; s < SECTIONS; s++) {
    rc_blob_align(&b, SECTION_ALIGN);
    h.offset[s] = b.len, h.bytes[s] = sizes[s];
    rc_blob_put(&b, s == SEC_HASHES ? (void *)hashes : *slots[s], sizes[s]);
  }
  if (b.failed) {
    free(b.data);
    rc_error("out of memory writing the prepared scene");
    return RC_ERR_OUT_OF_MEMORY;
  }
  h.file_bytes = b.len;
  memcpy(b.data, &h, sizeof h);
  h.checksum = XXH3_64bits(b.data + CHECKED_FROM, b.len - CHECKED_FROM);
  memcpy(b.data, &h, sizeof h);
  *bytes = b.data, *len = b.len;
  return RC_OK;
}

static rc_status refuse(const char *name, const char *fmt, const char *detail) {
  fprintf(stderr, "%s: error: not a usable prepared scene: ", name);
  fprintf(stderr, fmt, detail);
  fputc('\n', stderr);
  return RC_ERR_INPUT;
}

/* The header's own checks, in the order that names the most useful reason first. */
static rc_status check_header(const char *name, const vkrs_header *h, size_t len) {
  char detail[160];
  if (memcmp(h->magic, magic, 4) != 0)
    return refuse(name, "%s", "foreign: it does not begin with VKRS (`vkraycast prepare SCENE -o FILE.vkrs` writes one)");
  if (memcmp(h->magic, magic, sizeof magic) != 0)
    return refuse(name, "%s", "damaged: the bytes after VKRS were changed (a text-mode transfer?)");
  if (h->byte_order != BYTE_ORDER_MARK)
    return refuse(name, "%s", "foreign: written on a machine of the other byte order; prepare it on this kind");
  if (h->version != RC_PREPARED_VERSION) {
    snprintf(detail, sizeof detail, "version: format version %u, and this vkraycast reads version %u; prepare it again",
             h->version, RC_PREPARED_VERSION);
    return refuse(name, "%s", detail);
  }
  if (h->layout != layout_word())
    return refuse(name, "%s", "foreign: written by a build whose packed structures differ; prepare it again");
  if (h->file_bytes != len) {
    snprintf(detail, sizeof detail, "truncated or extended: %zu bytes, and its header says %llu", len,
             (unsigned long long)h->file_bytes);
    return refuse(name, "%s", detail);
  }
  return RC_OK;
}

/* The sections lie in the file, aligned, in order, without overlapping. */
static rc_status check_sections(const char *name, const vkrs_header *h, size_t len) {
  uint64_t end = sizeof *h;
  for (int s = 0; s < SECTIONS; s++) {
    if (h->offset[s] % SECTION_ALIGN || h->offset[s] < end || h->offset[s] > len || h->bytes[s] > len - h->offset[s])
      return refuse(name, "malformed: its %s section lies outside the file", section_names[s]);
    end = h->offset[s] + h->bytes[s];
  }
  return RC_OK;
}

static rc_status check_arrays(rc_prepared *pf, const vkrs_header *h, const unsigned char *base) {
  uint64_t sizes[SECTIONS];
  section_sizes(&pf->packed, sizes);
  void **slots[SECTIONS];
  array_slots(&pf->packed, slots);
  for (int s = SEC_SPHERES; s < SECTIONS; s++) {
    if (h->bytes[s] != sizes[s])
      return refuse(pf->name, "inconsistent: its %s section's size does not match the scene's counts",
                    section_names[s]);
    if (slots[s]) *slots[s] = (void *)(base + h->offset[s]);
  }
  pf->array_hashes = (const uint64_t *)(base + h->offset[SEC_HASHES]);
  char why[200];
  const char *problem = rc_packed_arrays_problem(&pf->packed, pf->tree.object_nodes, why, sizeof why);
  return problem ? refuse(pf->name, "inconsistent: %s", problem) : RC_OK;
}

rc_status rc_prepared_decode(const char *name, const void *bytes, size_t len, rc_prepared **out, rc_scene *scene) {
  *out = NULL;
  memset(scene, 0, sizeof *scene);
  if (len < sizeof(vkrs_header)) {
    char detail[120];
    snprintf(detail, sizeof detail, "truncated: %zu bytes, shorter than the %zu of a header", len, sizeof(vkrs_header));
    return refuse(name, "%s", detail);
  }
  vkrs_header h;
  memcpy(&h, bytes, sizeof h);
  const unsigned char *base = bytes;
  RC_TRY(check_header(name, &h, len));
  if (XXH3_64bits(base + CHECKED_FROM, len - CHECKED_FROM) != h.checksum)
    return refuse(name, "%s", "checksum: its bytes changed after `vkraycast prepare` wrote it (damaged or edited)");
  RC_TRY(check_sections(name, &h, len));
  rc_prepared *pf = calloc(1, sizeof *pf);
  if (!pf || !(pf->name = strdup(name))) {
    free(pf);
    return RC_ERR_OUT_OF_MEMORY;
  }
  pf->source_digest = h.source_digest;
  const char *why = rc_summary_decode(base + h.offset[SEC_SUMMARY], h.bytes[SEC_SUMMARY], scene, &pf->packed,
                                      &pf->tree);
  rc_status st = why ? refuse(name, "malformed: %s", why) : RC_OK;
  if (st == RC_OK && scene->triangle_count + scene->csg_triangle_count != pf->packed.triangle_total)
    st = refuse(name, "%s", "inconsistent: the triangles are miscounted");
  if (st == RC_OK && scene->quadric_count + scene->plane_count + scene->csg_leaf_count != pf->packed.quadric_total)
    st = refuse(name, "%s", "inconsistent: the quadrics are miscounted");
  if (st == RC_OK) {
    rc_scene_pack_frame(scene, &pf->packed);
    pf->packed.frame.loose_kinds = pf->tree.loose_kinds; /* checked with the arrays */
    st = check_arrays(pf, &h, base);
  }
  if (st != RC_OK) {
    rc_scene_free(scene);
    rc_prepared_close(pf);
    return st;
  }
  pf->camera_relative = scene->quality.camera_relative;
  pf->rescale = scene->quality.rescale;
  *out = pf;
  return RC_OK;
}

rc_status rc_prepared_open(const char *path, rc_prepared **out, rc_scene *scene) {
  *out = NULL;
  memset(scene, 0, sizeof *scene);
  size_t len = 0;
  FILE *f = rc_open_input(path, "the prepared scene", &len);
  if (!f) return RC_ERR_IO;
  void *map = len ? mmap(NULL, len, PROT_READ, MAP_PRIVATE, fileno(f), 0) : NULL;
  fclose(f);
  if (map == MAP_FAILED) {
    rc_error("%s: cannot map the prepared scene (%zu bytes)", path, len);
    return RC_ERR_IO;
  }
  if (map) madvise(map, len, MADV_WILLNEED);
  static const char empty[1];
  rc_status st = rc_prepared_decode(path, map ? map : empty, map ? len : 0, out, scene);
  if (st != RC_OK) {
    if (map) munmap(map, len);
    return st;
  }
  (*out)->map = map, (*out)->map_len = len;
  return RC_OK;
}

void rc_prepared_close(rc_prepared *pf) {
  if (!pf) return;
  if (pf->map) munmap(pf->map, pf->map_len);
  free(pf->name);
  free(pf);
}

static rc_status check_overrides(const rc_prepared *pf, const rc_scene *scene) {
  const char *option = scene->quality.camera_relative != pf->camera_relative ? "--camera-relative"
                       : scene->quality.rescale != pf->rescale               ? "--rescale"
                                                                              : NULL;
  if (!option) return RC_OK;
  bool prepared = option[2] == 'c' ? pf->camera_relative : pf->rescale;
  fprintf(stderr,
          "%s: error: %s %s: the file was prepared with %s %s, and the packed positions depend on it; prepare it "
          "again with %s %s\n",
          pf->name, option, prepared ? "off" : "on", option, prepared ? "on" : "off", option, prepared ? "off" : "on");
  return RC_ERR_USAGE;
}

rc_status rc_prepared_packed(const rc_prepared *pf, const rc_scene *scene, rc_packed_scene *p) {
  RC_TRY(check_overrides(pf, scene));
  *p = pf->packed;
  p->borrowed = true;
  p->array_hashes = pf->array_hashes;
  rc_scene_pack_frame(scene, p);
  rc_packed_scene_count_patches(p);
  /* As rc_bvh_build leaves the frame (bvh.c, build_operands). */
  p->frame.bvh_node_count = pf->tree.object_nodes;
  p->frame.loose_kinds = pf->tree.loose_kinds;
  uint64_t steps = pf->tree.operand_steps + p->frame.csg_max_steps;
  p->frame.csg_max_steps = steps > UINT32_MAX ? UINT32_MAX : (uint32_t)steps;
  return RC_OK;
}

rc_status rc_prepared_packed_copy(const rc_prepared *pf, const rc_scene *scene, rc_packed_scene *p) {
  RC_TRY(check_overrides(pf, scene));
  *p = pf->packed;
  p->borrowed = false;
  p->array_hashes = NULL;
  p->bvh = false;
  p->bvh_node_total = p->bvh_prim_total = 0;
  uint64_t sizes[SECTIONS];
  section_sizes(p, sizes);
  void **slots[SECTIONS];
  array_slots(p, slots);
  bool ok = true;
  for (int s = SEC_SPHERES; s < SEC_NODES; s++) {
    void *copy = rc_alloc(1, sizes[s], section_names[s]);
    if (copy) memcpy(copy, *slots[s], sizes[s]);
    ok &= copy != NULL;
    *slots[s] = copy;
  }
  p->bvh_nodes = NULL, p->bvh_prims = NULL;
  if (!ok) {
    rc_packed_scene_free(p);
    return RC_ERR_OUT_OF_MEMORY;
  }
  rc_scene_pack_frame(scene, p);
  rc_packed_scene_count_patches(p);
  return RC_OK;
}

rc_bvh_stats rc_prepared_bvh_stats(const rc_prepared *pf) { return pf->tree.stats; }

static rc_status digest_file(XXH3_state_t *state, const char *path, const char *what) {
  size_t bytes = 0;
  FILE *f = rc_open_input(path, what, &bytes);
  if (!f) return RC_ERR_IO;
  /* Each file's length first, so that bytes cannot move between files unseen. */
  uint64_t n = bytes;
  XXH3_64bits_update(state, &n, sizeof n);
  char buf[1 << 16];
  size_t got;
  while ((got = fread(buf, 1, sizeof buf, f)) > 0) XXH3_64bits_update(state, buf, got);
  bool failed = ferror(f);
  fclose(f);
  if (failed) {
    rc_error("%s: cannot read %s", path, what);
    return RC_ERR_IO;
  }
  return RC_OK;
}

rc_status rc_source_digest(const char *scene_path, char *const *inputs, size_t input_count, uint64_t *digest) {
  XXH3_state_t *state = XXH3_createState();
  if (!state) return RC_ERR_OUT_OF_MEMORY;
  XXH3_64bits_reset(state);
  rc_status st = digest_file(state, scene_path, "the scene file");
  for (size_t i = 0; st == RC_OK && i < input_count; i++) st = digest_file(state, inputs[i], "a file the scene reads");
  *digest = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  return st;
}

rc_status rc_prepared_check_source(const rc_prepared *pf, const rc_scene *scene, const char *scene_path) {
  uint64_t digest = 0;
  rc_status st = rc_source_digest(scene_path, scene->inputs, scene->input_count, &digest);
  if (st != RC_OK) {
    fprintf(stderr, "%s: error: cannot check that it is the prepared form of %s (see above)\n", pf->name, scene_path);
    return RC_ERR_INPUT;
  }
  if (digest != pf->source_digest) {
    fprintf(stderr,
            "%s: error: stale: %s, or a file it reads, changed since this file was prepared from it (or it was "
            "prepared from another scene); prepare it again\n",
            pf->name, scene_path);
    return RC_ERR_INPUT;
  }
  return RC_OK;
}
