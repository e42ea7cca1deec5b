/* mesh_import.h: a mesh file read by assimp in a process of its own, vkraycast-mesh-import
 * (mesh_import_main.c; mesh_wire.h says why). */
#ifndef RC_MESH_IMPORT_H
#define RC_MESH_IMPORT_H

#include <stdbool.h>
#include <stddef.h>

#include "base/rc_base.h"
#include "scene/mesh_wire.h"

/* Runs the importer on `file` (`bytes` long: the time limit grows with it) and parses its
 * answer into *data. root: the folder every file the import opens must lie in (NULL:
 * anywhere); libraries: the file names material libraries (rc_mesh_check). RC_OK with
 * data->outcome saying whether assimp read the file; else the importer crashed, was
 * killed after the time limit (20 s + 1 s a MiB; VKRAYCAST_MESH_TIMEOUT_S sets it), could
 * not start or gave no whole answer: RC_ERR_INPUT (RC_ERR_INSTALL when it cannot be
 * found or started, as a missing image module is; RC_ERR_IO when its answer is not
 * whole), and `why` says which. The importer is looked for in VKRAYCAST_MESH_IMPORTER, then beside
 * the running binary, then where the build put it. */
rc_status rc_mesh_import(const char *file, const char *root, bool libraries, size_t bytes, rc_mesh_data *data,
                         char *why, size_t len);

#endif
