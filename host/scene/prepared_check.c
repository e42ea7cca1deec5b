#include "scene/prepared_check.h"

#include "scene/bvh.h"
#include "scene/patch_bounds.h"
#include "scene/texture_levels.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const char *say(char *why, size_t cap, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static const char *say(char *why, size_t cap, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, cap, fmt, ap);
  va_end(ap);
  return why;
}

/* Nodes [root, end) as one depth-first tree with skip links (bvh.h): an interior node's
 * first child follows it, every skip moves forward and stays within the tree, and a leaf's
 * references lie in the reference array and name objects below `limit`. */
static const char *tree_problem(const rc_packed_scene *p, uint32_t root, uint32_t end, uint32_t limit, char *why,
                                size_t cap) {
  for (uint32_t i = root; i < end; i++) {
    const packed_bvh_node *n = &p->bvh_nodes[i];
    if (n->skip <= i || n->skip > end) return say(why, cap, "BVH node %u skips to node %u, outside (%u, %u]", i, n->skip, i, end);
    if (!n->leaf) {
      if (i + 1 >= n->skip) return say(why, cap, "BVH node %u is interior but has no child", i);
      continue;
    }
    uint32_t first = n->leaf >> RC_BVH_LEAF_SHIFT, count = n->leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1);
    if (count < 1 || count > RC_BVH_LEAF_MAX || first > p->bvh_prim_total || count > p->bvh_prim_total - first)
      return say(why, cap, "BVH leaf %u references objects [%u, %u + %u), outside the %u references", i, first,
                 first, count, p->bvh_prim_total);
    for (uint32_t k = first; k < first + count; k++)
      if (p->bvh_prims[k] >= limit)
        return say(why, cap, "BVH leaf %u references object %u of %u", i, p->bvh_prims[k], limit);
  }
  return NULL;
}

static const char *csg_problem(const rc_packed_scene *p, char *why, size_t cap) {
  for (uint32_t i = 0; i < p->frame.csg_count; i++) {
    const packed_csg *c = &p->csg[i];
    if (c->count < 1 || c->first > p->csg_program_length || c->count > p->csg_program_length - c->first)
      return say(why, cap, "composite %u's program lies outside the %u instructions", i, p->csg_program_length);
    /* The interpreters keep RC_CSG_STACK lists and pop two for each operation. */
    uint32_t depth = 0;
    for (uint32_t k = c->first; k < c->first + c->count; k++) {
      uint32_t op = p->csg_program[k] >> RC_CSG_OP_SHIFT, operand = p->csg_program[k] & RC_CSG_OPERAND_MASK;
      if (op > RC_CSG_DIFFERENCE) return say(why, cap, "composite %u has an unknown operation %u", i, op);
      if (op == RC_CSG_LEAF && (operand >= p->quadric_total || !(p->quadrics[operand].flags & RC_QUADRIC_SOLID)))
        return say(why, cap, "composite %u's operand %u is not a solid of the %u quadrics", i, operand,
                   p->quadric_total);
      depth = op == RC_CSG_LEAF ? depth + 1 : depth >= 2 ? depth - 1 : RC_CSG_STACK + 1;
      if (depth > RC_CSG_STACK) return say(why, cap, "composite %u's program over- or underflows its stack", i);
    }
    if (depth != 1) return say(why, cap, "composite %u's program leaves %u results", i, depth);
  }
  return NULL;
}

const char *rc_packed_arrays_problem(const rc_packed_scene *p, uint32_t object_nodes, char *why, size_t cap) {
  const packed_frame *f = &p->frame;
  for (uint32_t i = 0; i < f->sphere_count; i++) {
    const packed_sphere *s = &p->spheres[i];
    if (s->material >= f->material_count || (s->transform != RC_NO_TRANSFORM && s->transform >= p->transform_count))
      return say(why, cap, "sphere %u names material %u or transform %u, past the arrays", i, s->material,
                 s->transform);
  }
  uint32_t one_sided = 0;
  for (uint32_t i = 0; i < p->triangle_total; i++) {
    const packed_triangle *t = &p->triangles[i];
    /* 1 + the texel of its texture coordinates (2 texels), or 0. */
    uint32_t uv = t->flags >> RC_TRIANGLE_UV_SHIFT;
    if (t->material >= f->material_count || (t->normals != RC_NO_NORMALS && t->normals >= p->normal_count) ||
        (uv && (uint64_t)uv - 1 + RC_TEXELS_PER_VERTEX_UVS > p->texel_count))
      return say(why, cap, "triangle %u names material %u, normals %u or texture coordinates %u past the arrays", i,
                 t->material, t->normals, uv);
    one_sided += t->flags & RC_TRIANGLE_ONE_SIDED;
  }
  if (one_sided != p->one_sided_triangle_count) return say(why, cap, "the one-sided triangles are miscounted");
  for (uint32_t i = 0; i < f->material_count; i++) {
    uint32_t first = p->materials[i].texture;
    if (first == RC_NO_TEXTURE) continue;
    packed_texture h;
    if (first > p->texel_count || p->texel_count - first < RC_TEXELS_PER_TEXTURE_HEADER)
      return say(why, cap, "material %u's texture begins past the %u texels", i, p->texel_count);
    memcpy(&h, &p->texels[4 * (size_t)first], sizeof h);
    uint32_t levels = h.flags >> RC_TEXTURE_LEVELS_SHIFT, level_first[RC_TEXTURE_MAX_LEVELS];
    memcpy(level_first, &p->texels[4 * ((size_t)first + 2)], sizeof level_first);
    bool fits = h.width >= 1 && h.height >= 1 && levels >= 1 && levels < RC_TEXTURE_MAX_LEVELS &&
                (h.flags & ((1u << RC_TEXTURE_LEVELS_SHIFT) - 1u)) <= (RC_TEXTURE_BILINEAR | RC_TEXTURE_CLAMP) &&
                levels <= rc_texture_level_count(h.width, h.height, true) && level_first[0] == h.texels;
    for (uint32_t k = 0; fits && k < levels; k++)
      fits = (uint64_t)level_first[k] + (uint64_t)rc_texture_level_side(h.width, k) * rc_texture_level_side(h.height, k) <=
             p->texel_count;
    if (!fits)
      return say(why, cap, "material %u's texture (%u x %u, flags %u) does not fit the %u texels", i, h.width,
                 h.height, h.flags, p->texel_count);
  }
  for (uint32_t i = 0; i < f->light_count; i++)
    if (p->lights[i].type > RC_LIGHT_DIRECTIONAL) return say(why, cap, "light %u has an unknown type", i);
  uint32_t meshes = 0;
  for (uint32_t i = 0; i < p->quadric_total; i++) {
    const packed_quadric *q = &p->quadrics[i];
    if (q->material >= f->material_count) return say(why, cap, "quadric %u names material %u", i, q->material);
    meshes += (q->flags & RC_QUADRIC_MESH) != 0;
    /* A patch piece: a standalone quadric of nothing else, its control points in the texel
     * array, and its patch's first piece before it (rc_shared.h, RC_QUADRIC_PATCH). */
    if ((q->flags & RC_QUADRIC_PATCH) &&
        (q->flags != RC_QUADRIC_PATCH || i >= f->quadric_count - f->plane_count || q->mesh_end > i ||
         q->mesh_root > p->texel_count || p->texel_count - q->mesh_root < RC_TEXELS_PER_PATCH))
      return say(why, cap, "quadric %u is a patch piece whose control points or first piece lie past the arrays", i);
  }
  if (meshes != p->mesh_operand_count) return say(why, cap, "the mesh operands are miscounted");
  /* The certificates trust a patch's stored net differences as bounds (patch_bounds.h). */
  uint32_t piece;
  if (!rc_packed_patch_bounds_match(p, &piece))
    return say(why, cap, "quadric %u is a patch piece whose net differences are not its control points'", piece);
  const char *problem = csg_problem(p, why, cap);
  if (problem) return problem;
  if (object_nodes > p->bvh_node_total || (object_nodes && !p->bvh))
    return say(why, cap, "the object tree's %u nodes are not among the %u", object_nodes, p->bvh_node_total);
  if (object_nodes && (problem = tree_problem(p, 0, object_nodes, f->object_count, why, cap))) return problem;
  if ((f->loose_kinds & ~RC_KIND_QUADRICS) ||
      rc_loose_objects(f) > RC_LOOSE_MAX || (f->loose_kinds && !p->bvh))
    return say(why, cap, "the frame's loose kinds %u name more than %u objects or no tree", f->loose_kinds,
               RC_LOOSE_MAX);
  for (uint32_t k = 0; k < p->mesh_operand_count; k++) {
    const rc_mesh_operand *op = &p->mesh_operands[k];
    /* In leaf order, each once: with the count above, every mesh leaf's tree is checked. */
    if ((k && op->leaf <= op[-1].leaf) || op->leaf >= p->quadric_total || !(p->quadrics[op->leaf].flags & RC_QUADRIC_MESH) ||
        op->first > p->triangle_total || op->count > p->triangle_total - op->first)
      return say(why, cap, "mesh operand %u names quadric %u or triangles past the arrays", k, op->leaf);
    const packed_quadric *q = &p->quadrics[op->leaf];
    if (q->mesh_root < object_nodes || q->mesh_root >= q->mesh_end || q->mesh_end > p->bvh_node_total ||
        q->mesh_crossings < 2 || q->mesh_crossings > 2 * RC_CSG_MAX_INTERVALS)
      return say(why, cap, "mesh operand %u's tree [%u, %u) or crossing bound %u is out of range", k, q->mesh_root,
                 q->mesh_end, q->mesh_crossings);
    if ((problem = tree_problem(p, q->mesh_root, q->mesh_end, p->triangle_total, why, cap))) return problem;
  }
  return NULL;
}
