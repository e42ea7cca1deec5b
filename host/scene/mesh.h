/* mesh.h: triangle meshes from files (OBJ+MTL, PLY, STL, glTF, and the other formats
 * assimp reads), read by assimp in a process of its own (mesh_import.h). */
#ifndef RC_MESH_H
#define RC_MESH_H

#include "scene/scene.h"

/* Appends the triangles of `file` (already resolved against the scene's folder) to the
 * scene, through world_from_object. material < 0: each assimp material (MTL's Ka, Kd, Ks,
 * Ns) becomes one of ours; else every triangle gets that material. Vertex normals, where
 * the file has them, make the triangles smooth shaded. `where` prefixes error messages
 * (FILE:LINE:COL: error: objects[i].file:). Zero-area triangles are counted in
 * scene->degenerate_triangles. Every file the importer opens (the mesh and those it names)
 * must be a regular file inside the folder `root`; NULL allows any folder. */
rc_status rc_mesh_load(const char *file, const char *root, const rc_affine *world_from_object, int material,
                       rc_scene *scene, const char *where);

/* Releases the imports rc_mesh_load keeps while a scene loads (a file placed many times
 * is imported once); rc_scene_load calls it when the scene is loaded. */
void rc_mesh_cache_clear(void);

#endif
