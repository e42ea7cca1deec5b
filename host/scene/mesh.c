#include "scene/mesh.h"
#include "scene/mesh_check.h"

#include "scene/mesh_import.h"

#include <math.h>
#include <sys/stat.h>
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

/* Imports kept while a scene loads: a scene that places one mesh file many times (8,000
 * copies of a part) imports it once. Keyed by the path and the policy's folder, checked
 * against the file's identity (device, inode, size, modification time), the oldest
 * released first; rc_mesh_cache_clear releases them all when the scene is loaded. */
#define MESH_CACHE 8
static struct cached_import {
  char path[4200], root[4200];
  struct stat id;
  rc_mesh_data data;
  bool used;
} cache[MESH_CACHE];
static unsigned cache_next;

static bool same_file(const struct stat *a, const struct stat *b) {
  return a->st_dev == b->st_dev && a->st_ino == b->st_ino && a->st_size == b->st_size &&
         a->st_mtim.tv_sec == b->st_mtim.tv_sec && a->st_mtim.tv_nsec == b->st_mtim.tv_nsec;
}

static const rc_mesh_data *cache_find(const char *file, const char *root, const struct stat *id) {
  for (unsigned i = 0; i < MESH_CACHE; i++)
    if (cache[i].used && strcmp(cache[i].path, file) == 0 && strcmp(cache[i].root, root ? root : "") == 0 &&
        same_file(&cache[i].id, id))
      return &cache[i].data;
  return NULL;
}

/* Takes over *data; returns where it now lives. */
static const rc_mesh_data *cache_add(const char *file, const char *root, const struct stat *id, rc_mesh_data *data) {
  struct cached_import *c = &cache[cache_next++ % MESH_CACHE];
  if (c->used) rc_mesh_data_free(&c->data);
  snprintf(c->path, sizeof c->path, "%s", file);
  snprintf(c->root, sizeof c->root, "%s", root ? root : "");
  c->id = *id;
  c->data = *data;
  c->used = true;
  return &c->data;
}

void rc_mesh_cache_clear(void) {
  for (unsigned i = 0; i < MESH_CACHE; i++) {
    if (cache[i].used) rc_mesh_data_free(&cache[i].data);
    cache[i].used = false;
  }
  cache_next = 0;
}

/* One of our materials per imported one, named FILE#INDEX. */
static rc_status add_materials(const rc_mesh_data *m, rc_scene *s, const char *file, uint32_t *first) {
  size_t n = s->material_count + m->material_count;
  rc_material_def *defs = realloc(s->materials, (n ? n : 1) * sizeof *defs);
  if (!defs) return RC_ERR_OUT_OF_MEMORY;
  s->materials = defs;
  *first = (uint32_t)s->material_count;
  for (uint32_t i = 0; i < m->material_count; i++) {
    const rc_mesh_material *in = &m->materials[i];
    rc_material_def *d = &s->materials[s->material_count];
    memset(d, 0, sizeof *d);
    char name[300];
    snprintf(name, sizeof name, "%s#%u", file, i);
    if (!(d->name = strdup(name))) return RC_ERR_OUT_OF_MEMORY;
    d->ambient = rcm_make_d(in->ambient[0], in->ambient[1], in->ambient[2]);
    d->diffuse = rcm_make_d(in->diffuse[0], in->diffuse[1], in->diffuse[2]);
    d->specular = rcm_make_d(in->specular[0], in->specular[1], in->specular[2]);
    d->emission = rcm_make_d(in->emission[0], in->emission[1], in->emission[2]);
    d->shininess = in->shininess;
    s->material_count++;
  }
  return RC_OK;
}

/* The triangles of every part, through world_from_object. */
static rc_status add_triangles(const rc_mesh_data *m, const rc_affine *world_from_object, int material,
                               uint32_t first_material, rc_scene *s, const char *file, const char *where) {
  rc_status st = RC_OK;
  for (uint32_t i = 0; st == RC_OK && i < m->part_count; i++) {
    const rc_mesh_part *part = &m->parts[i];
    for (uint32_t f = 0; st == RC_OK && f < part->triangle_count; f++) {
      rc_triangle_def d = {0};
      d.material = material >= 0 ? (uint32_t)material : first_material + part->material;
      d.smooth = part->has_normals != 0;
      d.has_uv = part->has_uvs != 0;
      for (int k = 0; k < 3 && st == RC_OK; k++) {
        uint32_t idx = part->indices[3 * (size_t)f + k];
        if (idx >= part->vertex_count) {
          fprintf(stderr, "%s: mesh %s: face %u of mesh %u uses vertex %u of %u\n", where, file, f, i, idx,
                  part->vertex_count);
          st = RC_ERR_INPUT;
          break;
        }
        const float *v = &part->positions[3 * (size_t)idx];
        if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) {
          fprintf(stderr, "%s: mesh %s: vertex %u of mesh %u is not finite\n", where, file, idx, i);
          st = RC_ERR_INPUT;
          break;
        }
        d.v[k] = rc_affine_point(world_from_object, rcm_make_d(v[0], v[1], v[2]));
        if (d.has_uv) {
          const float *uv = &part->uvs[2 * (size_t)idx];
          d.uv[k][0] = uv[0], d.uv[k][1] = uv[1];
          /* Coordinates that are not finite leave the triangle untextured. */
          if (!isfinite(uv[0]) || !isfinite(uv[1]) || fabsf(uv[0]) > 1e30f || fabsf(uv[1]) > 1e30f) d.has_uv = false;
        }
        if (d.smooth) {
          const float *n = &part->normals[3 * (size_t)idx];
          d.n[k] = apply_normal(world_from_object, rcm_make_d(n[0], n[1], n[2]));
          /* A zero or broken normal falls back to flat shading. */
          if (!(rcm_length_d(d.n[k]) > 0.5)) d.smooth = false;
        }
      }
      if (st == RC_OK) st = rc_scene_add_triangle(s, &d);
    }
  }
  return st;
}

/* Reads the file in the importer process (mesh_import.h): NULL after printing why not. */
static const rc_mesh_data *import(const char *file, const char *root, size_t bytes, const struct stat *id,
                                  bool known, rc_mesh_data *uncached, rc_scene *s, const char *where,
                                  rc_status *st) {
  char why_not[4400];
  bool libraries = false;
  const char *refused = rc_mesh_check(file, bytes, &libraries, why_not, sizeof why_not);
  if (refused) {
    fprintf(stderr, "%s: cannot load mesh %s: %s\n", where, file, refused);
    *st = RC_ERR_INPUT;
    return NULL;
  }
  rc_mesh_data data;
  *st = rc_mesh_import(file, root, libraries, bytes, &data, why_not, sizeof why_not);
  if (*st != RC_OK) {
    fprintf(stderr, "%s: cannot load mesh %s: %s\n", where, file, why_not);
    return NULL;
  }
  for (uint32_t i = 0; i < data.input_count && *st == RC_OK; i++)
    if (!rc_scene_note_input(s, data.inputs[i])) *st = RC_ERR_OUT_OF_MEMORY;
  if (*st == RC_OK && data.outcome != RC_MESH_IMPORTED) {
    fprintf(stderr, "%s: cannot load mesh %s: %s%s\n", where, file,
            data.outcome == RC_MESH_REFUSED ? "refused to open " : "", data.message);
    *st = RC_ERR_IO;
  }
  if (*st != RC_OK) {
    rc_mesh_data_free(&data);
    return NULL;
  }
  /* Kept for the next object that names the file; released by the cache. */
  if (known) return cache_add(file, root, id, &data);
  *uncached = data;
  return uncached;
}

rc_status rc_mesh_load(const char *file, const char *root, const rc_affine *world_from_object, int material,
                       rc_scene *s, const char *where) {
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
  rc_status st = RC_OK;
  rc_mesh_data uncached = {0};
  /* Checked and imported once per file: a cached import (the same file, unchanged) passed. */
  const rc_mesh_data *m = known ? cache_find(file, root, &id) : NULL;
  if (!m && !(m = import(file, root, bytes, &id, known, &uncached, s, where, &st))) return st;
  uint32_t first_material = 0;
  if (material < 0) st = add_materials(m, s, file, &first_material);
  size_t triangles = 0;
  for (uint32_t i = 0; i < m->part_count; i++) triangles += m->parts[i].triangle_count;
  if (st == RC_OK && triangles == 0) {
    fprintf(stderr, "%s: mesh %s has no triangles\n", where, file);
    st = RC_ERR_INPUT;
  }
  size_t degenerate_before = s->degenerate_triangles;
  if (st == RC_OK) st = rc_scene_reserve_triangles(s, triangles); /* one allocation for the whole mesh */
  if (st == RC_OK) st = add_triangles(m, world_from_object, material, first_material, s, file, where);
  rc_mesh_data_free(&uncached);
  /* Zero-area faces are a property of the mesh file: the warning names it. */
  size_t skipped = s->degenerate_triangles - degenerate_before;
  if (st == RC_OK && skipped)
    fprintf(stderr, "%s: warning: skipped %zu degenerate (zero-area) triangle%s of %zu\n", file, skipped,
            skipped == 1 ? "" : "s", triangles);
  s->degenerate_in_meshes += skipped;
  return st;
}
