/* libFuzzer targets for the input parsers (tools/fuzz.sh builds and runs them):
 *   FUZZ_TARGET=1 the JSON scene parser, =2 the CSE167 .test parser, =4 the prepared-scene
 * reader (scene/prepared.h: when the input's last byte is odd, its size and checksum
 * fields are rewritten to match, so that mutations reach the summary and the array
 * checks past the checksum; what it accepts is then turned into a packed scene and read
 * whole), =3 mesh loading
 * (the input written to a file, its format chosen by the first byte: OBJ, PLY, STL, OFF,
 * an OBJ with a material library (the bytes up to the first NUL are the library and the
 * rest the OBJ, which names it), glTF, GLB; or, for the eighth kind, the bytes are an
 * answer of the mesh importer, given to its reader). Mesh loading runs assimp in
 * vkraycast-mesh-import, a process of its own (host/scene/mesh_wire.h): what assimp does
 * there (crash, loop, leak) is an error message here, not a finding; what this process
 * does with the file and the answer (mesh_check.c, mesh_wire.c, mesh.c) is fuzzed; =5 a
 * Bezier patch file (scene/scene_patch.h: the input written to a file, read, its patches
 * cut into pieces, and the scene packed, control points and all). Any
 * crash, hang, sanitizer report or leak is a finding (tools/fuzz.sh runs them with
 * -close_fd_mask=2: the parsers' error messages are dropped, libFuzzer's own are not). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <xxhash.h>

#include "scene/mesh.h"
#include "scene/mesh_wire.h"
#include "scene/prepared.h"
#include "scene/scene.h"
#include "scene/scene_pack.h"
#include "scene/scene_patch.h"

#if FUZZ_TARGET == 4
/* Reads every element of every array the renderers read, and every BVH node and reference,
 * so that an index the checks let through past its array is an ASan report. */
static uint32_t read_packed(const rc_packed_scene *p) {
  uint32_t sink = 0;
  const packed_frame *f = &p->frame;
  for (uint32_t i = 0; i < f->sphere_count; i++) {
    const packed_sphere *s = &p->spheres[i];
    sink += p->materials[s->material].texture != 0;
    if (s->transform != RC_NO_TRANSFORM) sink += p->transforms[s->transform].row0.w != 0;
  }
  for (uint32_t i = 0; i < p->triangle_total; i++) {
    const packed_triangle *t = &p->triangles[i];
    sink += p->materials[t->material].texture != 0;
    if (t->normals != RC_NO_NORMALS) sink += p->normals[t->normals].pad0 != 0;
    if (t->flags >> RC_TRIANGLE_UV_SHIFT) sink += p->texels[4 * ((size_t)(t->flags >> RC_TRIANGLE_UV_SHIFT) - 1 + 1) + 3];
  }
  for (uint32_t i = 0; i < p->quadric_total; i++) sink += p->materials[p->quadrics[i].material].pad1 != 0;
  for (uint32_t i = 0; i < f->light_count; i++) sink += p->lights[i].type;
  for (uint32_t i = 0; i < f->material_count; i++) {
    uint32_t first = p->materials[i].texture;
    if (first == RC_NO_TEXTURE) continue;
    packed_texture h;
    memcpy(&h, &p->texels[4 * (size_t)first], sizeof h);
    /* The texture's last texel: the one past it is past the array if the checks fail. */
    sink += p->texels[4 * ((size_t)h.texels + (size_t)h.width * h.height - 1)];
  }
  for (uint32_t i = 0; i < f->csg_count; i++)
    for (uint32_t k = 0; k < p->csg[i].count; k++) {
      uint32_t ins = p->csg_program[p->csg[i].first + k];
      if (ins >> RC_CSG_OP_SHIFT == RC_CSG_LEAF) sink += p->quadrics[ins & RC_CSG_OPERAND_MASK].flags;
    }
  for (uint32_t i = 0; i < f->bvh_node_count; i++) {
    const packed_bvh_node *n = &p->bvh_nodes[i];
    if (n->skip < f->bvh_node_count) sink += p->bvh_nodes[n->skip].leaf;
    uint32_t first = n->leaf >> RC_BVH_LEAF_SHIFT, count = n->leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1);
    for (uint32_t k = 0; n->leaf && k < count; k++) sink += p->bvh_prims[first + k] < f->object_count;
  }
  for (uint32_t k = 0; k < p->mesh_operand_count; k++) {
    const packed_quadric *q = &p->quadrics[p->mesh_operands[k].leaf];
    for (uint32_t i = q->mesh_root; i < q->mesh_end; i++) {
      const packed_bvh_node *n = &p->bvh_nodes[i];
      uint32_t first = n->leaf >> RC_BVH_LEAF_SHIFT, count = n->leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1);
      for (uint32_t j = 0; n->leaf && j < count; j++) sink += p->triangles[p->bvh_prims[first + j]].flags;
    }
  }
  return sink;
}
#endif

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size) {
  rc_scene s;
#if FUZZ_TARGET == 5
  char path[64];
  snprintf(path, sizeof path, "/tmp/vkraycast-fuzz-%d.bpt", (int)getpid());
  FILE *f = fopen(path, "wb");
  if (!f) return 0;
  fwrite(data, 1, size, f);
  fclose(f);
  memset(&s, 0, sizeof s);
  static rc_material_def material;
  s.materials = &material, s.material_count = 1;
  s.width = s.height = s.samples_per_pixel = 1;
  s.quality = rc_quality_default();
  s.camera = (rc_camera_def){.projection = RC_PROJECTION_PERSPECTIVE, .eye = {0, 0, 10}, .up = {0, 1, 0}, .fov_y_deg = 45};
  rc_affine id = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
  if (rc_patch_file_load(path, &id, 0, &s, "fuzz") == RC_OK) {
    rc_packed_scene p;
    if (rc_scene_pack(&s, &p) == RC_OK) rc_packed_scene_free(&p);
  }
  unlink(path);
  s.materials = NULL, s.material_count = 0;
#elif FUZZ_TARGET == 4
  /* A private, 64-byte aligned copy, as a mapping would be. */
  unsigned char *file = aligned_alloc(64, (size + 63) / 64 * 64 + 64);
  if (!file) return 0;
  memcpy(file, data, size);
  if (size >= 48 && (data[size - 1] & 1)) {
    const uint64_t len = size, sum = XXH3_64bits(file + 40, size - 40);
    memcpy(file + 24, &len, sizeof len);
    memcpy(file + 32, &sum, sizeof sum);
  }
  rc_prepared *pf = NULL;
  if (rc_prepared_decode("fuzz.vkrs", file, size, &pf, &s) == RC_OK) {
    rc_packed_scene p;
    volatile uint32_t sink = 0;
    if (rc_prepared_packed(pf, &s, &p) == RC_OK) sink += read_packed(&p);
    rc_packed_scene_free(&p);
    (void)sink;
    rc_scene_free(&s);
  }
  rc_prepared_close(pf);
  free(file);
  return 0;
#elif FUZZ_TARGET == 3
  enum { OBJ_WITH_MTL = 4, ANSWER = 7 }; /* an OBJ and its material library; an importer's answer */
  static const char *const ext[] = {".obj", ".ply", ".stl", ".off", ".obj", ".gltf", ".glb", ""};
  const unsigned kinds = sizeof ext / sizeof *ext;
  if (size < 1) return 0;
  const unsigned kind = data[0] % kinds;
  if (kind == ANSWER) {
    void *answer = malloc(size - 1 ? size - 1 : 1);
    if (!answer) return 0;
    memcpy(answer, data + 1, size - 1);
    rc_mesh_data m;
    /* A whole answer: everything it points at is read, so that a pointer past the
     * buffer is an ASan report. */
    volatile uint32_t sink = 0;
    if (!rc_mesh_wire_parse(answer, size - 1, &m)) {
      for (uint32_t i = 0; i < m.input_count; i++) sink += (uint32_t)strlen(m.inputs[i]);
      for (uint32_t i = 0; i < m.material_count; i++) sink += (uint32_t)m.materials[i].shininess;
      for (uint32_t i = 0; i < m.part_count; i++) {
        const rc_mesh_part *p = &m.parts[i];
        for (size_t k = 0; k < 3 * (size_t)p->vertex_count; k++)
          sink += (uint32_t)(p->positions[k] != 0) + (uint32_t)(p->normals && p->normals[k] != 0) +
                  (uint32_t)(p->uvs && k < 2 * (size_t)p->vertex_count && p->uvs[k] != 0);
        for (size_t k = 0; k < 3 * (size_t)p->triangle_count; k++) sink += p->indices[k];
      }
    }
    (void)sink;
    rc_mesh_data_free(&m);
    return 0;
  }
  char path[64], mtl[64] = "";
  snprintf(path, sizeof path, "/tmp/vkraycast-fuzz-%d%s", (int)getpid(), ext[kind]);
  const unsigned char *body = data + 1;
  size_t body_len = size - 1;
  if (kind == OBJ_WITH_MTL) {
    const unsigned char *nul = memchr(body, 0, body_len);
    size_t lib_len = nul ? (size_t)(nul - body) : body_len;
    snprintf(mtl, sizeof mtl, "/tmp/vkraycast-fuzz-%d.mtl", (int)getpid());
    FILE *m = fopen(mtl, "wb");
    if (!m) return 0;
    fwrite(body, 1, lib_len, m);
    fclose(m);
    body += lib_len + (nul != NULL);
    body_len -= lib_len + (nul != NULL);
  }
  FILE *f = fopen(path, "wb");
  if (!f) return 0;
  if (mtl[0]) fprintf(f, "mtllib %s\n", strrchr(mtl, '/') + 1);
  fwrite(body, 1, body_len, f);
  fclose(f);
  memset(&s, 0, sizeof s);
  rc_affine id = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
  rc_mesh_load(path, NULL, &id, 0, &s, "fuzz");
  /* As rc_scene_load does once a scene is loaded: each input is imported afresh (the
   * cache would keep up to 8 imports alive, and match a new input of the same size,
   * inode and modification time to an old one's import). */
  rc_mesh_cache_clear();
  unlink(path);
  if (mtl[0]) unlink(mtl);
#else
  /* The parsers take NUL-terminated text of a given length, as rc_scene_load reads it. */
  char *text = malloc(size + 1);
  if (!text) return 0;
  memcpy(text, data, size);
  text[size] = '\0';
#if FUZZ_TARGET == 1
  rc_scene_parse_json("fuzz.json", text, size, NULL, &s);
#else
  rc_scene_parse_cse167("fuzz.test", text, size, &s);
#endif
  free(text);
#endif
  rc_scene_free(&s);
  return 0;
}
