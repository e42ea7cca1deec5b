/* mesh_wire.h: the answer of vkraycast-mesh-import, the process that runs assimp on one
 * mesh file (mesh_import.c), to the process that renders (mesh.c).
 *
 * Why a process of its own: assimp 5.2.4 crashes, aborts, loops forever or exhausts
 * memory on malformed files (fuzz_mesh found a new way into each of these in almost every
 * CI run: writes through a null material, a PLY that spins at end of file, an OFF count
 * that wraps). mesh_check.c refuses the classes found so far with a precise message; the
 * separate process makes every other one a clear error, exit status 2, instead of a crash
 * of vkraycast.
 *
 * The answer, on the importer's stdout, is a sequence of 32-bit words in the machine's
 * byte order (both ends are the same build on the same machine):
 *   "VKRM" (4 bytes), RC_MESH_WIRE_VERSION
 *   outcome: RC_MESH_IMPORTED, RC_MESH_REFUSED (a file the import opened was refused:
 *            message names it and why) or RC_MESH_FAILED (assimp's error in message)
 *   message: a string (a word with its length, then its bytes, padded to a word)
 *   the files the import opened (the mesh, an OBJ's MTL, a glTF's buffers): a count, then
 *            a string each
 *   when imported:
 *     materials: a count, then 13 floats each: ambient, diffuse, specular and emission
 *            (RGB, assimp's defaults for an absent colour already applied) and shininess
 *     parts (assimp's meshes): a count, then for each: material (an index into the
 *            materials above), has_normals (0 or 1), has_uvs (0 or 1), vertex count V,
 *            triangle count T, 3V floats of positions, 3V floats of normals when
 *            has_normals, 2V floats of texture coordinates (the first uv channel) when
 *            has_uvs, 3T indices
 *   "MEND"
 * Every array starts on a word, so that the reader's buffer (malloc'd) can be read in
 * place. */
#ifndef RC_MESH_WIRE_H
#define RC_MESH_WIRE_H

#include <stddef.h>
#include <stdint.h>

enum { RC_MESH_WIRE_VERSION = 2 };
enum { RC_MESH_IMPORTED = 0, RC_MESH_REFUSED = 1, RC_MESH_FAILED = 2 };

typedef struct {
  float ambient[3], diffuse[3], specular[3], emission[3], shininess;
} rc_mesh_material;

typedef struct {
  uint32_t material, has_normals, has_uvs, vertex_count, triangle_count;
  const float *positions, *normals; /* 3 per vertex; normals NULL when has_normals is 0 */
  const float *uvs;                 /* 2 per vertex; NULL when has_uvs is 0 */
  const uint32_t *indices;          /* 3 per triangle, not yet checked against vertex_count */
} rc_mesh_part;

/* One answer, parsed; every pointer points into `buffer`, which it owns. */
typedef struct {
  uint32_t outcome;
  const char *message;
  uint32_t input_count, material_count, part_count;
  const char **inputs;
  const rc_mesh_material *materials;
  rc_mesh_part *parts;
  void *buffer;
  size_t length; /* of the answer in buffer, in bytes */
} rc_mesh_data;

/* Parses the answer in buffer[0, len) (malloc'd, taken over: rc_mesh_data_free frees it,
 * on failure too) into *d. NULL when it is whole; else what is wrong with it. */
const char *rc_mesh_wire_parse(void *buffer, size_t len, rc_mesh_data *d);

void rc_mesh_data_free(rc_mesh_data *d);

#endif
