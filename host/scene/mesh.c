#include "scene/mesh.h"
#include "scene/mesh_check.h"

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Normals go through the inverse transpose of the linear part: the cofactor matrix,
 * whose scale does not matter once normalised. */
static dvec3 apply_normal(const rc_affine *a, dvec3 n) {
  const double(*m)[4] = a->m;
  double c[3][3] = {{m[1][1] * m[2][2] - m[1][2] * m[2][1], m[1][2] * m[2][0] - m[1][0] * m[2][2],
                     m[1][0] * m[2][1] - m[1][1] * m[2][0]},
                    {m[0][2] * m[2][1] - m[0][1] * m[2][2], m[0][0] * m[2][2] - m[0][2] * m[2][0],
                     m[0][1] * m[2][0] - m[0][0] * m[2][1]},
                    {m[0][1] * m[1][2] - m[0][2] * m[1][1], m[0][2] * m[1][0] - m[0][0] * m[1][2],
                     m[0][0] * m[1][1] - m[0][1] * m[1][0]}};
  dvec3 r = rcm_make_d(c[0][0] * n.x + c[0][1] * n.y + c[0][2] * n.z, c[1][0] * n.x + c[1][1] * n.y + c[1][2] * n.z,
                       c[2][0] * n.x + c[2][1] * n.y + c[2][2] * n.z);
  double len = rcm_length_d(r);
  return len > 0 ? rcm_scale_d(r, 1 / len) : r;
}

static dvec3 color(const struct aiMaterial *m, const char *key, unsigned type, unsigned index, dvec3 fallback) {
  struct aiColor4D c;
  if (aiGetMaterialColor(m, key, type, index, &c) != AI_SUCCESS) return fallback;
  return rcm_make_d(c.r < 0 ? 0 : c.r, c.g < 0 ? 0 : c.g, c.b < 0 ? 0 : c.b);
}

/* One of our materials per assimp material: Ka, Kd, Ks, Ns (absent or 0 Ns -> 1). */
static rc_status add_materials(const struct aiScene *ai, rc_scene *s, const char *file, uint32_t *first) {
  size_t n = s->material_count + ai->mNumMaterials;
  rc_material_def *m = realloc(s->materials, (n ? n : 1) * sizeof *m);
  if (!m) return RC_ERR_OUT_OF_MEMORY;
  s->materials = m;
  *first = (uint32_t)s->material_count;
  for (unsigned i = 0; i < ai->mNumMaterials; i++) {
    const struct aiMaterial *am = ai->mMaterials[i];
    rc_material_def *d = &s->materials[s->material_count];
    memset(d, 0, sizeof *d);
    char name[300];
    snprintf(name, sizeof name, "%s#%u", file, i);
    d->name = strdup(name);
    d->ambient = color(am, AI_MATKEY_COLOR_AMBIENT, rcm_make_d(0, 0, 0));
    d->diffuse = color(am, AI_MATKEY_COLOR_DIFFUSE, rcm_make_d(0.8, 0.8, 0.8));
    d->specular = color(am, AI_MATKEY_COLOR_SPECULAR, rcm_make_d(0, 0, 0));
    d->emission = color(am, AI_MATKEY_COLOR_EMISSIVE, rcm_make_d(0, 0, 0));
    ai_real shininess = 0;
    d->shininess = aiGetMaterialFloatArray(am, AI_MATKEY_SHININESS, &shininess, NULL) == AI_SUCCESS && shininess > 0
                       ? (double)shininess
                       : 1.0;
    s->material_count++;
  }
  return RC_OK;
}

/* Every file assimp opens (the mesh, and what it names: an OBJ's MTL, a glTF's buffers)
 * goes through these callbacks, so that each is checked as the scene file is: a regular
 * file opened without blocking (rc_fopen_regular), inside the scene's folder unless the
 * user allowed otherwise (docs/scene-format.md, "Files a scene may read"). The first
 * refusal is kept for the error message; assimp only sees a file that will not open. */
typedef struct {
  const char *root; /* the folder files must lie in; NULL: anywhere */
  struct stat mesh; /* the mesh file's identity (device, inode): checked before the import */
  bool libraries;   /* the mesh names material libraries: the files opened are checked as such */
  char refused[4200];
  rc_scene *scene;  /* records every file opened (rc_scene_note_input) */
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

static struct aiFile *file_open(struct aiFileIO *io, const char *path, const char *mode) {
  file_policy *policy = (file_policy *)io->UserData;
  const char *why = NULL;
  if (strpbrk(mode, "wa+"))
    why = "assimp asked to write it";
  else if (policy->root && !rc_path_within(policy->root, path))
    why = "it lies outside the scene's folder (--allow-outside-paths allows it)";
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
  if (policy->scene) rc_scene_note_input(policy->scene, path);
  return f;
}

static void file_close(struct aiFileIO *io, struct aiFile *f) {
  (void)io;
  if (!f) return;
  fclose((FILE *)f->UserData);
  free(f);
}

/* assimp's own validation runs first (aiProcess_ValidateDataStructure): a face index past
 * the vertex array (a PLY face naming vertex 2,000,000,000) is refused there, where the
 * later steps would read out of bounds and crash. */
/* assimp 5.2.4 can loop forever on a malformed file (fuzz_mesh found a 171-byte ASCII PLY
 * that spins in fread at end of file). The import runs on a helper thread; if it has not
 * finished after 20 s + 1 s per MiB, the process reports the file and exits with status 2
 * (no output file exists yet at load time), rather than hang. */
typedef struct {
  const char *file;
  struct aiFileIO io;
  const struct aiScene *scene;
  bool done;
  pthread_mutex_t lock;
  pthread_cond_t cond;
} import_job;

static void *import_thread(void *arg) {
  import_job *j = arg;
  const struct aiScene *s = aiImportFileEx(j->file, aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                        aiProcess_SortByPType | aiProcess_JoinIdenticalVertices,
                                           &j->io);
  pthread_mutex_lock(&j->lock);
  j->scene = s;
  j->done = true;
  pthread_cond_signal(&j->cond);
  pthread_mutex_unlock(&j->lock);
  return NULL;
}

static const struct aiScene *import_with_watchdog(const char *file, off_t bytes, file_policy *policy,
                                                  const char *where) {
  static import_job job; /* static: a timed-out import thread may still touch it */
  job = (import_job){.file = file, .io = {file_open, file_close, (aiUserData)policy}};
  pthread_mutex_init(&job.lock, NULL);
  pthread_cond_init(&job.cond, NULL);
  pthread_t t;
  if (pthread_create(&t, NULL, import_thread, &job) != 0) {
    import_thread(&job);
    return job.scene;
  }
  long limit_s = 20 + (long)(bytes >> 20);
  const char *env = getenv("VKRAYCAST_MESH_TIMEOUT_S");
  if (env && atol(env) > 0) limit_s = atol(env);
  struct timespec until;
  clock_gettime(CLOCK_REALTIME, &until);
  until.tv_sec += limit_s;
  pthread_mutex_lock(&job.lock);
  while (!job.done) {
    if (pthread_cond_timedwait(&job.cond, &job.lock, &until) != 0 && !job.done) {
      fprintf(stderr, "%s: cannot load mesh %s: the importer did not finish within %ld s (a malformed file?)\n",
              where, file, limit_s);
      _exit(2);
    }
  }
  pthread_mutex_unlock(&job.lock);
  pthread_join(t, NULL);
  return job.scene;
}

/* Imports kept while a scene loads: a scene that places one mesh file many times (8,000
 * copies of a part) imports it once. Keyed by the path and the policy's folder, checked
 * against the file's identity (device, inode, size, modification time), the oldest
 * released first; rc_mesh_cache_clear releases them all when the scene is loaded. */
#define MESH_CACHE 8
static struct cached_import {
  char path[4200], root[4200];
  struct stat id;
  const struct aiScene *scene;
} cache[MESH_CACHE];
static unsigned cache_next;

static bool same_file(const struct stat *a, const struct stat *b) {
  return a->st_dev == b->st_dev && a->st_ino == b->st_ino && a->st_size == b->st_size &&
         a->st_mtim.tv_sec == b->st_mtim.tv_sec && a->st_mtim.tv_nsec == b->st_mtim.tv_nsec;
}

static const struct aiScene *cache_find(const char *file, const char *root, const struct stat *id) {
  for (unsigned i = 0; i < MESH_CACHE; i++)
    if (cache[i].scene && strcmp(cache[i].path, file) == 0 && strcmp(cache[i].root, root ? root : "") == 0 &&
        same_file(&cache[i].id, id))
      return cache[i].scene;
  return NULL;
}

static void cache_add(const char *file, const char *root, const struct stat *id, const struct aiScene *ai) {
  struct cached_import *c = &cache[cache_next++ % MESH_CACHE];
  if (c->scene) aiReleaseImport(c->scene);
  snprintf(c->path, sizeof c->path, "%s", file);
  snprintf(c->root, sizeof c->root, "%s", root ? root : "");
  c->id = *id;
  c->scene = ai;
}

void rc_mesh_cache_clear(void) {
  for (unsigned i = 0; i < MESH_CACHE; i++) {
    if (cache[i].scene) aiReleaseImport(cache[i].scene);
    cache[i].scene = NULL;
  }
  cache_next = 0;
}

rc_status rc_mesh_load(const char *file, const char *root, const rc_affine *world_from_object, int material,
                       rc_scene *s, const char *where) {
  /* Triangulate n-gons; flatten the node hierarchy into the vertices; drop points and
   * lines. No normal generation: files without normals are flat shaded. */
  size_t bytes = 0;
  const char *why = rc_input_problem(file, &bytes);
  if (why) {
    /* The path as tried, absolute, beside the name as resolved from the scene's folder. */
    char resolved[4200];
    if (!rc_resolve_path(file, resolved, sizeof resolved) || strcmp(resolved, file) == 0)
      fprintf(stderr, "%s: cannot load mesh %s: %s\n", where, file, why);
    else
      fprintf(stderr, "%s: cannot load mesh %s (looked for %s): %s\n", where, file, resolved, why);
    return RC_ERR_IO;
  }
  if (!rc_scene_note_input(s, file)) return RC_ERR_OUT_OF_MEMORY;
  struct stat id;
  bool known = stat(file, &id) == 0;
  const struct aiScene *ai = known ? cache_find(file, root, &id) : NULL;
  if (!ai) {
    /* Checked once per import: a cached one (the same file, unchanged) passed. */
    char why_not[300];
    bool libraries = false;
    const char *refused = rc_mesh_check(file, bytes, &libraries, why_not, sizeof why_not);
    if (refused) {
      fprintf(stderr, "%s: cannot load mesh %s: %s\n", where, file, refused);
      return RC_ERR_INPUT;
    }
    file_policy policy = {.root = root, .scene = s, .mesh = id, .libraries = libraries};
    ai = import_with_watchdog(file, (off_t)bytes, &policy, where);
    if (policy.refused[0]) {
      fprintf(stderr, "%s: cannot load mesh %s: refused to open %s\n", where, file, policy.refused);
      if (ai) aiReleaseImport(ai);
      return RC_ERR_IO;
    }
    if (!ai) {
      fprintf(stderr, "%s: cannot load mesh %s: %s\n", where, file, aiGetErrorString());
      return RC_ERR_IO;
    }
    /* Kept for the next object that names the file; released by the cache. */
    if (known) cache_add(file, root, &id, ai);
  }
  rc_status st = RC_OK;
  uint32_t first_material = 0;
  if (material < 0) st = add_materials(ai, s, file, &first_material);
  size_t faces = 0;
  for (unsigned i = 0; i < ai->mNumMeshes; i++) faces += ai->mMeshes[i]->mNumFaces;
  if (st == RC_OK && faces == 0) {
    fprintf(stderr, "%s: mesh %s has no triangles\n", where, file);
    st = RC_ERR_INPUT;
  }
  size_t degenerate_before = s->degenerate_triangles;
  if (st == RC_OK) st = rc_scene_reserve_triangles(s, faces); /* one allocation for the whole mesh */
  for (unsigned i = 0; st == RC_OK && i < ai->mNumMeshes; i++) {
    const struct aiMesh *mesh = ai->mMeshes[i];
    for (unsigned f = 0; st == RC_OK && f < mesh->mNumFaces; f++) {
      const struct aiFace *face = &mesh->mFaces[f];
      if (face->mNumIndices != 3) continue; /* points and lines */
      rc_triangle_def d = {0};
      d.material = material >= 0 ? (uint32_t)material : first_material + mesh->mMaterialIndex;
      d.smooth = mesh->mNormals != NULL;
      for (int k = 0; k < 3 && st == RC_OK; k++) {
        unsigned idx = face->mIndices[k];
        if (idx >= mesh->mNumVertices) {
          fprintf(stderr, "%s: mesh %s: face %u of mesh %u uses vertex %u of %u\n", where, file, f, i, idx,
                  mesh->mNumVertices);
          st = RC_ERR_INPUT;
          break;
        }
        struct aiVector3D v = mesh->mVertices[idx];
        if (!isfinite(v.x) || !isfinite(v.y) || !isfinite(v.z)) {
          fprintf(stderr, "%s: mesh %s: vertex %u of mesh %u is not finite\n", where, file, idx, i);
          st = RC_ERR_INPUT;
          break;
        }
        d.v[k] = rc_affine_point(world_from_object, rcm_make_d(v.x, v.y, v.z));
        if (d.smooth) {
          struct aiVector3D n = mesh->mNormals[idx];
          d.n[k] = apply_normal(world_from_object, rcm_make_d(n.x, n.y, n.z));
          /* A zero or broken normal falls back to flat shading. */
          if (!(rcm_length_d(d.n[k]) > 0.5)) d.smooth = false;
        }
      }
      if (st == RC_OK) st = rc_scene_add_triangle(s, &d);
    }
  }
  if (!known) aiReleaseImport(ai);
  /* Zero-area faces are a property of the mesh file: the warning names it. */
  size_t skipped = s->degenerate_triangles - degenerate_before;
  if (st == RC_OK && skipped)
    fprintf(stderr, "%s: warning: skipped %zu degenerate (zero-area) triangle%s of %zu\n", file, skipped,
            skipped == 1 ? "" : "s", faces);
  s->degenerate_in_meshes += skipped;
  return st;
}
