/* mesh_check.h: what assimp is not given. A PLY header declaring two billion vertices in
 * a file of a hundred bytes made assimp 5.2.4 spin (until the watchdog) or allocate for
 * them; an OFF face naming a vertex past the last one is silently moved to the last
 * vertex by its reader, a wrong triangle rendered. Such files are refused here, before
 * the import, naming what the file declares against what it holds. (Face indices of
 * every format are checked after the import by assimp's own validation step, which
 * rc_mesh_load asks for.) */
#ifndef RC_MESH_CHECK_H
#define RC_MESH_CHECK_H

#include <stddef.h>

#include <stdio.h>

/* NULL when the file may go to the importer; else why not (in why, or a constant). */
const char *rc_mesh_check(const char *path, size_t bytes, char *why, size_t len);

/* A file an OBJ names (its `mtllib`, read as a material library): NULL when it may go to
 * the importer; else why not. A statement before the first `newmtl` belongs to no
 * material, and assimp 5.2.4 writes a texture map statement there (map_Kd, bump, ...)
 * through a null material and dies of SIGSEGV (found by fuzz_mesh; an OBJ that names
 * itself as its library is the same case). Reads f from its start and rewinds it. */
const char *rc_mtl_check(FILE *f, char *why, size_t len);

#endif
