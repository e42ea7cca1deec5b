/* libFuzzer targets for the input parsers (tools/fuzz.sh builds and runs them):
 *   FUZZ_TARGET=1 the JSON scene parser, =2 the CSE167 .test parser, =3 mesh loading
 * (the input written to a file, its format chosen by the first byte: OBJ, PLY, STL, OFF,
 * an OBJ with a material library (the bytes up to the first NUL are the library and the
 * rest the OBJ, which names it), glTF, GLB; or, for the eighth kind, the bytes are an
 * answer of the mesh importer, given to its reader). Mesh loading runs assimp in
 * vkraycast-mesh-import, a process of its own (host/scene/mesh_wire.h): what assimp does
 * there (crash, loop, leak) is an error message here, not a finding; what this process
 * does with the file and the answer (mesh_check.c, mesh_wire.c, mesh.c) is fuzzed. Any
 * crash, hang, sanitizer report or leak is a finding (tools/fuzz.sh runs them with
 * -close_fd_mask=2: the parsers' error messages are dropped, libFuzzer's own are not). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/mesh.h"
#include "scene/mesh_wire.h"
#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size) {
  rc_scene s;
#if FUZZ_TARGET == 3
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
          sink += (uint32_t)(p->positions[k] != 0) + (uint32_t)(p->normals && p->normals[k] != 0);
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
