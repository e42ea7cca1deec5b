/* scene_json_mesh.c: mesh files named by a JSON scene: a mesh object's triangles, and a
 * closed triangle mesh as a composite's operand (docs/scene-format.md, "Composites"). The shader finds a ray's intervals inside the mesh by parity: every crossing
 * of the ray's line with its triangles toggles inside and outside (rc_quadric.glsl,
 * mesh_intervals). That is right only for a closed surface, so the loader refuses a mesh
 * with an open edge and names it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/mesh.h"
#include "scene/scene_json_mesh.h"

/* An edge as its two end points, the smaller (lexicographically) first, and the triangle it
 * came from. Positions are compared exactly: a file's shared vertex is one value, carried
 * through the same transform, so its copies in different triangles are equal. */
typedef struct {
  dvec3 a, b;
  size_t triangle;
} edge;

static int compare_point(dvec3 p, dvec3 q) {
  if (p.x != q.x) return p.x < q.x ? -1 : 1;
  if (p.y != q.y) return p.y < q.y ? -1 : 1;
  if (p.z != q.z) return p.z < q.z ? -1 : 1;
  return 0;
}

static int compare_edge(const void *x, const void *y) {
  const edge *e = x, *f = y;
  int c = compare_point(e->a, f->a);
  if (!c) c = compare_point(e->b, f->b);
  if (!c) c = (e->triangle > f->triangle) - (e->triangle < f->triangle);
  return c;
}

/* Parity needs every edge on an even number of triangles (2 for a manifold; 4 where two
 * parts touch along an edge). Returns the triangle and edge of the first (in file order)
 * that is on an odd number, or false when there is none. */
static rc_status find_open_edge(const rc_triangle_def *t, size_t n, bool *open, edge *first) {
  *open = false;
  edge *e = rc_alloc(3 * n, sizeof *e, "mesh edges");
  if (!e) return RC_ERR_OUT_OF_MEMORY;
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      dvec3 p = t[i].v[k], q = t[i].v[(k + 1) % 3];
      bool swap = compare_point(q, p) < 0;
      e[3 * i + k] = (edge){swap ? q : p, swap ? p : q, i};
    }
  qsort(e, 3 * n, sizeof *e, compare_edge);
  for (size_t i = 0; i < 3 * n;) {
    size_t j = i + 1;
    while (j < 3 * n && compare_point(e[j].a, e[i].a) == 0 && compare_point(e[j].b, e[i].b) == 0) j++;
    if ((j - i) % 2 && (!*open || e[i].triangle < first->triangle)) {
      *first = e[i];
      *open = true;
    }
    i = j;
  }
  free(e);
  return RC_OK;
}

rc_status js_parse_mesh_operand(jctx *c, const cJSON *o, rc_scene *s, int material, const rc_affine *t,
                                rc_quadric_def *q, uint32_t *intervals) {
  static const char *const allowed[] = {"type", "file", "material", "transform", "max_crossings", NULL};
  RC_TRY(js_check_members(c, o, allowed));
  uint32_t crossings;
  RC_TRY(js_get_uint(c, o, "max_crossings", false, 8, 2, 2 * RC_CSG_MAX_INTERVALS, &crossings));
  if (crossings % 2) {
    js_push_key(c, "max_crossings");
    return js_fail(c, "must be even: a closed surface is crossed in pairs, in and out");
  }
  size_t before = s->triangle_count;
  rc_status st = js_load_mesh(c, o, s, t, material);
  size_t n = s->triangle_count - before;
  s->triangle_count = before; /* the triangles belong to the composite, not the scene's objects */
  if (st != RC_OK) return st;
  if (n == 0) {
    js_push_key(c, "file");
    return js_fail(c, "the mesh has no triangle of non-zero area, so it has no inside for a composite");
  }
  const rc_triangle_def *tris = s->triangles + before; /* after a failure, s->triangles may be NULL */
  bool open;
  edge e;
  RC_TRY(find_open_edge(tris, n, &open, &e));
  if (open) {
    js_push_key(c, "file");
    return js_fail(c, "the mesh is not closed, so it has no inside for a composite: the edge (%g, %g, %g)-(%g, %g, %g) "
                      "of its triangle %zu (after any transform) belongs to an odd number of triangles",
                   e.a.x, e.a.y, e.a.z, e.b.x, e.b.y, e.b.z, e.triangle + 1);
  }
  if (s->csg_triangle_count + n > RC_CSG_OPERAND_MASK >> RC_CSG_CODE_LEAF_SHIFT)
    return js_fail(c, "too many triangles in the composites' meshes: at most %u",
                   RC_CSG_OPERAND_MASK >> RC_CSG_CODE_LEAF_SHIFT);
  dvec3 lo = tris[0].v[0], hi = lo;
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      dvec3 v = tris[i].v[k];
      lo = rcm_make_d(fmin(lo.x, v.x), fmin(lo.y, v.y), fmin(lo.z, v.z));
      hi = rcm_make_d(fmax(hi.x, v.x), fmax(hi.y, v.y), fmax(hi.z, v.z));
    }
  *q = (rc_quadric_def){0};
  q->mesh = q->solid = true;
  q->mesh_first = (uint32_t)s->csg_triangle_count;
  q->mesh_count = (uint32_t)n;
  q->max_crossings = crossings;
  q->material = tris[0].material;
  q->center = rcm_scale_d(rcm_add_d(lo, hi), 0.5);
  q->hi = rcm_sub_d(hi, q->center);
  q->lo = rcm_sub_d(lo, q->center);
  q->axis[0] = rcm_make_d(1, 0, 0), q->axis[1] = rcm_make_d(0, 1, 0), q->axis[2] = rcm_make_d(0, 0, 1);
  for (size_t i = 0; i < n; i++) {
    RC_GROW(s->csg_triangles, s->csg_triangle_count, s->csg_triangle_capacity, 64);
    rc_triangle_def d = tris[i];
    d.smooth = false; /* flat: the normal comes from the triangle, turned outwards by parity */
    s->csg_triangles[s->csg_triangle_count++] = d;
  }
  *intervals = crossings / 2;
  return RC_OK;
}

/* A mesh object: the file relative to the scene file's folder. */
rc_status js_load_mesh(jctx *c, const cJSON *o, rc_scene *s, const rc_affine *m, int material) {
  const cJSON *f = cJSON_GetObjectItemCaseSensitive(o, "file");
  if (!f) return js_fail(c, "missing field \"file\"");
  js_push_key(c, "file");
  char path[4096], folder[4096];
  RC_TRY(js_scene_file(c, f, "a file name", path, folder));
  /* Found from the object, counted on from the last place: linear in the file however
   * many meshes it names. */
  size_t off = js_offset_near(c);
  int line, col;
  js_line_col(c, off, &line, &col);
  char where[4400];
  char fpath[256];
  js_format_path(c, fpath, sizeof fpath);
  snprintf(where, sizeof where, "%s:%d:%d: error: %s", c->file, line, col, fpath);
  js_pop(c);
  if (cJSON_GetObjectItemCaseSensitive(o, "material")) {
    uint32_t id;
    RC_TRY(js_get_material_ref(c, o, &id));
    material = (int)id;
  }
  return rc_mesh_load(path, c->allow_outside_paths ? NULL : folder, m, material, s, where);
}
