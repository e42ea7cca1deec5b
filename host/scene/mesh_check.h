/* mesh_check.h: what assimp is not given. A PLY header declaring two billion vertices in
 * a file of a hundred bytes made assimp 5.2.4 spin (until the watchdog) or allocate for
 * them; an OFF face naming a vertex past the last one is silently moved to the last
 * vertex by its reader, a wrong triangle rendered. Such files are refused here, before
 * the import, naming what the file declares against what it holds. (Face indices of
 * every format are checked after the import by assimp's own validation step, which
 * rc_mesh_load asks for.) */
#ifndef RC_MESH_CHECK_H
#define RC_MESH_CHECK_H

#include <stdbool.h>
#include <stddef.h>

#include <stdio.h>

/* NULL when the file may go to the importer; else why not (in why, or a constant).
 * *names_library: the file has an `mtllib` statement, so the files its import opens are
 * material libraries to check with rc_mtl_check (a glTF's binary buffers are not). */
const char *rc_mesh_check(const char *path, size_t bytes, bool *names_library, char *why, size_t len);

/* A file assimp may read as an OBJ's material library (every file the import of a mesh
 * with an `mtllib` statement opens, and the mesh itself when it names itself: assimp reads
 * a file as an OBJ when its content says so, whatever its name): NULL when it may go to
 * the importer;
 * else why not. A map statement (map_Kd, bump, disp, norm, refl, ...) or an anisotropy
 * (a line starting with `a`) before the first `newmtl` makes assimp 5.2.4 write through a
 * null material and die of SIGSEGV (found by fuzz_mesh, through an OBJ naming itself, a
 * .gltf file read as an OBJ, CR line ends and a bare "a").
 * Reads f from its start and rewinds it. */
const char *rc_mtl_check(FILE *f, char *why, size_t len);

#endif
