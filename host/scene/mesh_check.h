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

/* NULL when the file may go to the importer; else why not (in why, or a constant). */
const char *rc_mesh_check(const char *path, size_t bytes, char *why, size_t len);

#endif
