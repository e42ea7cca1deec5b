/* mesh_import_main.c: vkraycast-mesh-import, which runs assimp on one mesh file and writes what it read to stdout
 * as mesh_wire.h describes; rc_mesh_import (mesh_import.c) starts it, one process per file, so that
 * whatever assimp does on a malformed file (crash, abort, loop, exhaust memory) ends this
 * process and not the render (mesh_wire.h says why).
 *
 * Usage: vkraycast-mesh-import FILE ROOT LIBRARIES PARENT
 *   ROOT       the folder every file the import opens must lie in; "" for anywhere
 *   LIBRARIES  1 when FILE names material libraries (mesh_check.h): the files it opens
 *              are checked with rc_mtl_check before assimp reads them
 *   PARENT     the process id of the render that starts it
 * Exit status 0 with a whole answer; anything else (a signal included) is a failure the
 * caller reports. Nothing is written to stderr: assimp's own messages go nowhere, and its
 * error comes back in the answer. */
#include "scene/mesh_check.h"
#include "scene/mesh_wire.h"

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/rc_base.h"

/* Every file assimp opens (the mesh, and what it names: an OBJ's MTL, a glTF's buffers)
 * goes through these callbacks, so that each is checked as the scene file is: a regular
 * file opened without blocking (rc_fopen_regular), inside the scene's folder unless the
 * user allowed otherwise (docs/scene-format.md, "Files a scene may read"). The first
 * refusal is kept for the answer; assimp only sees a file that will not open. */
typedef struct {
  const char *root; /* the folder files must lie in; NULL: anywhere */
  struct stat mesh; /* the mesh file's identity (device, inode) */
  bool libraries;   /* the mesh names material libraries: the files opened are checked as such */
  char refused[4200];
  const char *opened[64]; /* the files opened, for the caller's list of the scene's inputs */
  unsigned opened_count;
} file_policy;

static size_t file_read(struct aiFile *f, char *buf, size_t size, size_t count) {
  return fread(buf, size, count, (FILE *)f->UserData);
}
static size_t file_write(struct aiFile *f, const char *buf, size_t size, size_t count) {
  (void)f, (void)buf, (void)size, (void)count;
  return 0;
}
static size_t file_tell(struct aiFile *f) {
  long at = ftell((FILE *)f->UserData);
  return at < 0 ? 0 : (size_t)at;
}
static size_t file_size(struct aiFile *f) {
  struct stat st;
  return fstat(fileno((FILE *)f->UserData), &st) == 0 ? (size_t)st.st_size : 0;
}
static enum aiReturn file_seek(struct aiFile *f, size_t offset, enum aiOrigin origin) {
  int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
  return fseek((FILE *)f->UserData, (long)offset, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}
static void file_flush(struct aiFile *f) { (void)f; }

static void note_opened(file_policy *policy, const char *path) {
  for (unsigned i = 0; i < policy->opened_count; i++)
    if (strcmp(policy->opened[i], path) == 0) return;
  /* More than 64 distinct files is a malformed glTF (one buffer per file): refused. */
  if (policy->opened_count == sizeof policy->opened / sizeof *policy->opened) return;
  policy->opened[policy->opened_count++] = strdup(path);
}

static struct aiFile *file_open(struct aiFileIO *io, const char *path, const char *mode) {
  file_policy *policy = (file_policy *)io->UserData;
  const char *why = NULL;
  if (strpbrk(mode, "wa+"))
    why = "assimp asked to write it";
  else if (policy->root && !rc_path_within(policy->root, path))
    why = "it lies outside the scene's folder (--allow-outside-paths allows it)";
  else if (policy->opened_count == sizeof policy->opened / sizeof *policy->opened)
    why = "the import opened more than 64 files";
  FILE *fp = why ? NULL : rc_fopen_regular(path, NULL, &why);
  struct stat id;
  char mtl_why[300];
  if (fp && policy->libraries && fstat(fileno(fp), &id) == 0 &&
      !(id.st_dev == policy->mesh.st_dev && id.st_ino == policy->mesh.st_ino) &&
      (why = rc_mtl_check(fp, mtl_why, sizeof mtl_why)) != NULL) {
    fclose(fp);
    fp = NULL;
  }
  struct aiFile *f = fp ? malloc(sizeof *f) : NULL;
  if (!f) {
    if (fp) fclose(fp);
    /* Importers probe for optional files that do not exist (an OBJ's MTL): not a refusal. */
    bool absent = why && strcmp(why, strerror(ENOENT)) == 0;
    if (!policy->refused[0] && !absent) snprintf(policy->refused, sizeof policy->refused, "%s: %s", path, why);
    return NULL;
  }
  *f = (struct aiFile){file_read, file_write, file_tell, file_size, file_seek, file_flush, (aiUserData)fp};
  note_opened(policy, path);
  return f;
}

static void file_close(struct aiFileIO *io, struct aiFile *f) {
  (void)io;
  if (!f) return;
  fclose((FILE *)f->UserData);
  free(f);
}

/* --- the answer ----------------------------------------------------------------------- */

static void put_words(const void *p, size_t words) {
  if (words && fwrite(p, 4, words, stdout) != words) _exit(1);
}
static void put_word(uint32_t w) { put_words(&w, 1); }
static void put_string(const char *s) {
  uint32_t len = (uint32_t)strlen(s);
  put_word(len);
  if (fwrite(s, 1, len, stdout) != len) _exit(1);
  static const char zeros[4];
  if (fwrite(zeros, 1, 4 - len % 4, stdout) != 4 - len % 4) _exit(1); /* at least one NUL */
}

static void put_color(const struct aiMaterial *m, const char *key, unsigned type, unsigned index, float r, float g,
                      float b) {
  struct aiColor4D c;
  if (aiGetMaterialColor(m, key, type, index, &c) == AI_SUCCESS) r = c.r, g = c.g, b = c.b;
  float rgb[3] = {r < 0 ? 0 : r, g < 0 ? 0 : g, b < 0 ? 0 : b};
  put_words(rgb, 3);
}

/* One of our materials per assimp material: Ka, Kd, Ks, Ke, Ns (absent or 0 Ns -> 1). */
static void put_materials(const struct aiScene *ai) {
  put_word(ai->mNumMaterials);
  for (unsigned i = 0; i < ai->mNumMaterials; i++) {
    const struct aiMaterial *m = ai->mMaterials[i];
    put_color(m, AI_MATKEY_COLOR_AMBIENT, 0, 0, 0);
    put_color(m, AI_MATKEY_COLOR_DIFFUSE, 0.8f, 0.8f, 0.8f);
    put_color(m, AI_MATKEY_COLOR_SPECULAR, 0, 0, 0);
    put_color(m, AI_MATKEY_COLOR_EMISSIVE, 0, 0, 0);
    ai_real shininess = 0;
    float ns = aiGetMaterialFloatArray(m, AI_MATKEY_SHININESS, &shininess, NULL) == AI_SUCCESS && shininess > 0
                   ? (float)shininess
                   : 1.0f;
    put_words(&ns, 1);
  }
}

/* The triangles of each mesh; points and lines (faces of other than 3 indices) are left
 * out. Indices go as assimp holds them: the reader checks them against the vertices. */
static void put_parts(const struct aiScene *ai) {
  _Static_assert(sizeof(struct aiVector3D) == 3 * sizeof(float), "assimp built with float ai_real");
  put_word(ai->mNumMeshes);
  for (unsigned i = 0; i < ai->mNumMeshes; i++) {
    const struct aiMesh *mesh = ai->mMeshes[i];
    uint32_t triangles = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; f++) triangles += mesh->mFaces[f].mNumIndices == 3;
    put_word(mesh->mMaterialIndex);
    put_word(mesh->mNormals != NULL);
    put_word(mesh->mTextureCoords[0] != NULL);
    put_word(mesh->mNumVertices);
    put_word(triangles);
    put_words(mesh->mVertices, 3 * (size_t)mesh->mNumVertices);
    if (mesh->mNormals) put_words(mesh->mNormals, 3 * (size_t)mesh->mNumVertices);
    for (unsigned v = 0; mesh->mTextureCoords[0] && v < mesh->mNumVertices; v++) {
      const float uv[2] = {mesh->mTextureCoords[0][v].x, mesh->mTextureCoords[0][v].y};
      put_words(uv, 2);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; f++)
      if (mesh->mFaces[f].mNumIndices == 3) put_words(mesh->mFaces[f].mIndices, 3);
  }
}

int main(int argc, char **argv) {
  if (argc != 5) {
    fprintf(stderr, "usage: vkraycast-mesh-import FILE ROOT LIBRARIES PARENT (run by vkraycast, see mesh_wire.h)\n");
    return 2;
  }
  /* Ends with the render that started it, even if that one is killed mid-import; one
   * already gone before the request (the parent is someone else now) ends it here. The
   * render's id is compared, not 1: in a container the render may be process 1. */
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if ((long)getppid() != atol(argv[4])) return 1;
  file_policy policy = {.root = argv[2][0] ? argv[2] : NULL, .libraries = strcmp(argv[3], "1") == 0};
  if (stat(argv[1], &policy.mesh) != 0) memset(&policy.mesh, 0, sizeof policy.mesh);
  struct aiFileIO io = {file_open, file_close, (aiUserData)&policy};
  /* Triangulate n-gons; flatten the node hierarchy into the vertices; drop points and
   * lines. No normal generation: files without normals are flat shaded. assimp's own
   * validation runs first (aiProcess_ValidateDataStructure): a face index past the vertex
   * array (a PLY face naming vertex 2,000,000,000) is refused there, where the later
   * steps would read out of bounds and crash. */
  const struct aiScene *ai =
      aiImportFileEx(argv[1],
                     aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_PreTransformVertices |
                         aiProcess_SortByPType | aiProcess_JoinIdenticalVertices,
                     &io);
  /* Fault injection (tests/reliability/test_faults.sh): the ways an importer can end
   * other than with a whole answer. */
  if (rc_fault("mesh-import-crash")) raise(SIGSEGV);
  if (rc_fault("mesh-import-abort")) abort();
  static char out_buffer[1 << 16];
  setvbuf(stdout, out_buffer, _IOFBF, sizeof out_buffer);
  put_words("VKRM", 1);
  put_word(RC_MESH_WIRE_VERSION);
  uint32_t outcome = policy.refused[0] ? RC_MESH_REFUSED : ai ? RC_MESH_IMPORTED : RC_MESH_FAILED;
  put_word(outcome);
  put_string(outcome == RC_MESH_REFUSED ? policy.refused : outcome == RC_MESH_FAILED ? aiGetErrorString() : "");
  if (rc_fault("mesh-import-short")) {
    fflush(stdout);
    _exit(0);
  }
  put_word(policy.opened_count);
  for (unsigned i = 0; i < policy.opened_count; i++) put_string(policy.opened[i]);
  if (outcome == RC_MESH_IMPORTED) {
    put_materials(ai);
    put_parts(ai);
  }
  put_words("MEND", 1);
  if (fflush(stdout) != 0) _exit(1);
  /* _exit: the process's memory goes back with it, and assimp 5.2.4 leaks on malformed
   * files (fuzz_mesh found 1,356 bytes from a broken ASCII PLY), which a sanitizer build
   * would report at exit, failing an answer that is whole. No process that loads assimp
   * is leak-checked, so tools/fuzz.sh needs no suppressions for it. */
  _exit(0);
}
