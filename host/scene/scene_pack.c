#include "scene/scene_pack.h"

#include "scene/patch_bounds.h"

#include "math/rcm_mat3.h"
#include "scene/name_table.h"
#include "scene/texture_levels.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static vec3 to_packed(const rc_packed_scene *p, dvec3 world) {
  return rcm_to_f(rcm_scale_d(rcm_sub_d(world, p->origin), p->scale));
}

/* A plane is packed centred on its point nearest the eye, found in f64: relative to the
 * eye the centre is then the plane's signed distance times its unit normal, and a primary
 * ray's t = -f.z / v.z takes one rounding of each input and one division (however far the
 * point the scene named lies from the eye). */
static dvec3 plane_point_nearest_eye(const rc_scene *s, const rc_quadric_def *q) {
  dvec3 n = q->axis[2];
  return rcm_sub_d(s->camera.eye, rcm_scale_d(n, rcm_dot_d(rcm_sub_d(s->camera.eye, q->center), n)));
}

/* The largest distance from the packed origin that the scene's positions and sizes reach
 * (an infinity norm), in scene units: what the packing unit is chosen by. */
static double scene_size(const rc_scene *s, dvec3 origin) {
  double size = s->camera.projection == RC_PROJECTION_PARALLEL ? s->camera.view_height : 0;
#define REACH(point, extra) (size = fmax(size, rcm_max_abs_comp_d(rcm_sub_d((point), origin)) + (extra)))
  for (size_t i = 0; i < s->sphere_count; i++) {
    const rc_sphere_def *d = &s->spheres[i];
    if (d->transformed) REACH(rc_affine_point(&d->world_from_object, d->center), 0);
    else REACH(d->center, d->radius);
  }
  for (size_t i = 0; i < s->triangle_count; i++)
    for (int k = 0; k < 3; k++) REACH(s->triangles[i].v[k], 0);
  for (size_t i = 0; i < s->csg_triangle_count; i++)
    for (int k = 0; k < 3; k++) REACH(s->csg_triangles[i].v[k], 0);
  for (size_t i = 0; i < s->light_count; i++)
    if (s->lights[i].type == RC_LIGHT_POINT) REACH(s->lights[i].position, 0);
  for (size_t i = 0; i < s->quadric_count; i++)
    REACH(s->quadrics[i].center, fmax(rcm_max_abs_comp_d(s->quadrics[i].lo), rcm_max_abs_comp_d(s->quadrics[i].hi)));
  for (size_t i = 0; i < s->csg_count; i++) {
    REACH(s->csgs[i].lo, 0);
    REACH(s->csgs[i].hi, 0);
  }
  for (size_t i = 0; i < s->plane_count; i++) REACH(plane_point_nearest_eye(s, &s->planes[i]), 0);
#undef REACH
  return isfinite(size) ? size : 0;
}

/* docs/numerics.md §1: packing units. The renderers square lengths (r^2, |f|^2, c2 r^2), and
 * a GPU may flush f32 results below 2^-126 to zero (an NVIDIA H100 does: a sphere of radius
 * 1e-19 then rendered NaN in every pixel, docs/porting.md); squares overflow above 2^128.
 * A scene whose size leaves [2^-20, 2^20] is packed in units of a power of two near its
 * size instead, so its squares land near 1. A power of two scales every value exactly, and
 * every product, quotient and square root of the renderers with it: the image is the
 * image of the unscaled arithmetic wherever that stayed in range (tests/rescale/). The
 * exponent stays within 60, where the light's attenuation constant c0 s^2 is still normal. */
static double packing_scale(const rc_scene *s, dvec3 origin) {
  double size = scene_size(s, origin);
  if (!s->quality.rescale || size == 0 || (size >= 0x1p-20 && size < 0x1p20)) return 1;
  int e = ilogb(size);
  e = e < -60 ? -60 : e > 60 ? 60 : e;
  return ldexp(1, -e);
}

/* docs/design.md §1: w points from the scene back to the eye, u to the right, v up; the image
 * plane sits at distance 1 (perspective) and the window keeps the image's aspect ratio. */
static void pack_camera(const rc_scene *s, rc_packed_scene *p) {
  const rc_camera_def *c = &s->camera;
  dvec3 w = rcm_normalize_d(rcm_sub_d(c->eye, c->look_at));
  dvec3 u = rcm_normalize_d(rcm_cross_d(c->up, w));
  dvec3 v = rcm_cross_d(w, u);
  double aspect = (double)s->width / (double)s->height;
  /* A parallel window is a length (packed units); a perspective one a slope at focal 1. */
  double half_h = c->projection == RC_PROJECTION_PERSPECTIVE ? tan(c->fov_y_deg * M_PI / 360.0)
                                                             : 0.5 * c->view_height * p->scale;
  packed_camera *g = &p->frame.camera;
  g->eye = to_packed(p, c->eye);
  g->u = rcm_to_f(u);
  g->v = rcm_to_f(v);
  g->w = rcm_to_f(w);
  g->top = (float)half_h;
  g->bottom = (float)-half_h;
  g->right = (float)(half_h * aspect);
  g->left = (float)(-half_h * aspect);
  g->focal = 1.0f;
  g->projection = c->projection;
  g->width = s->width;
  g->height = s->height;
  /* A sample's ray cone (texture level of detail): one pixel's window over sqrt(spp), the
   * side of a sample's share of it; an angle from a pinhole, a width from a parallel window. */
  double per_sample = 2.0 * half_h / (double)s->height / sqrt((double)(s->samples_per_pixel ? s->samples_per_pixel : 1));
  p->frame.cone_spread = c->projection == RC_PROJECTION_PERSPECTIVE ? (float)per_sample : 0.0f;
  p->frame.cone_width = c->projection == RC_PROJECTION_PERSPECTIVE ? 0.0f : (float)per_sample;
}

static bool finite3(vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

/* Finite in f32 in packed units and, times `unit` (scene units per packed unit, of the
 * value's dimension), in scene units too: packing units fix a scene's numerics, never
 * which scenes are accepted (docs/scene-format.md). */
static bool fits(vec3 a, double unit) { return finite3(a) && rcm_max_abs_comp_f(a) * unit <= FLT_MAX; }
static bool fits1(float a, double unit) { return isfinite(a) && fabs(a) * unit <= FLT_MAX; }

/* The composite whose program uses leaf `leaf` (rc_scene.csg_leaves). */
static size_t csg_of_leaf(const rc_scene *s, size_t leaf) {
  for (size_t i = 0; i < s->csg_count; i++)
    for (uint32_t k = 0; k < s->csgs[i].length; k++) {
      uint32_t ins = s->csgs[i].program[k];
      if (ins >> RC_CSG_OP_SHIFT == RC_CSG_LEAF && (ins & RC_CSG_OPERAND_MASK) == leaf) return i;
    }
  return 0;
}

/* The composite with mesh operand triangle `t` (rc_scene.csg_triangles). */
static size_t csg_of_mesh_triangle(const rc_scene *s, size_t t) {
  for (size_t i = 0; i < s->csg_leaf_count; i++) {
    const rc_quadric_def *q = &s->csg_leaves[i];
    if (q->mesh && t >= q->mesh_first && t < (size_t)q->mesh_first + q->mesh_count) return csg_of_leaf(s, i);
  }
  return 0;
}

/* Values that are finite in f64 but leave the f32 range once packed would reach the
 * shader as Inf, which Vulkan lets shaders assume away (docs/numerics.md §1). The error names
 * the object in the scene file and the value. */
static rc_status check_f32_range(const rc_scene *s, const rc_packed_scene *p) {
  const char *field = NULL;
  uint32_t kind = 0;
  size_t index = 0;
  const double u = 1.0 / p->scale;
#define BAD(k, i, f) (kind = (k), index = (i), field = (f))
  for (size_t i = 0; i < s->sphere_count && !field; i++) {
    const rc_sphere_def *d = &s->spheres[i];
    dvec3 world = d->transformed ? rc_affine_point(&d->world_from_object, d->center) : d->center;
    float r = p->spheres[i].radius;
    if (!fits(p->spheres[i].center, u) || !fits(to_packed(p, world), u))
      BAD(RC_ORIGIN_SPHERE, i, "its centre (relative to the eye, transformed)");
    else if (!fits1(r * r, u * u))
      BAD(RC_ORIGIN_SPHERE, i, "its radius squared");
  }
  for (size_t i = 0; i < p->triangle_total && !field; i++)
    if (!fits(p->triangles[i].v0, u) || !fits(p->triangles[i].v1, u) || !fits(p->triangles[i].v2, u)) {
      if (i < s->triangle_count) BAD(RC_ORIGIN_TRIANGLE, i, "a vertex (relative to the eye, transformed)");
      else BAD(RC_ORIGIN_CSG, csg_of_mesh_triangle(s, i - s->triangle_count), "a vertex of a mesh operand (relative to the eye, transformed)");
    }
  size_t standalone = s->quadric_count + s->plane_count;
  for (size_t i = 0; i < standalone + s->csg_leaf_count && !field; i++) {
    const packed_quadric *q = &p->quadrics[i];
    bool bad = !fits(q->center, u) || !finite3(q->diag) || !finite3(q->off) || !fits(q->linear, u) ||
               !fits1(q->constant, u * u) || !fits(q->lo, u) || !fits(q->hi, u);
    /* A patch's control points within an eighth of the range: the lengths of its net's
     * second and mixed differences (4 coordinates' worth, in 3 axes) are packed too
     * (patch_bounds.h). */
    for (uint32_t k = 0; (q->flags & RC_QUADRIC_PATCH) && k < RC_TEXELS_PER_PATCH && !bad; k++) {
      vec3 v;
      memcpy(&v, &p->texels[4 * (size_t)(q->mesh_root + k)], sizeof v);
      bad = !fits(v, 8 * u);
    }
    if (bad && i < s->quadric_count) BAD(RC_ORIGIN_QUADRIC, i, "its centre (relative to the eye), size, coefficients or control points");
    else if (bad && i < standalone) BAD(RC_ORIGIN_PLANE, i - s->quadric_count, "its point nearest the eye (relative to the eye)");
    else if (bad) BAD(RC_ORIGIN_CSG, csg_of_leaf(s, i - standalone), "an operand's centre (relative to the eye), size or coefficients");
  }
  for (size_t i = 0; i < s->light_count && !field; i++) {
    if (!fits(p->lights[i].position, u)) BAD(RC_ORIGIN_LIGHT, i, "its position (relative to the eye)");
    else if (!finite3(p->lights[i].intensity)) BAD(RC_ORIGIN_LIGHT, i, "its intensity");
  }
  for (size_t i = 0; i < s->material_count && !field; i++)
    if (!finite3(p->materials[i].ambient) || !finite3(p->materials[i].diffuse) ||
        !finite3(p->materials[i].specular) || !finite3(p->materials[i].mirror) || !finite3(p->materials[i].emission) ||
        !isfinite(p->materials[i].shininess))
      BAD(RC_ORIGIN_MATERIAL, i, "a colour or the shininess");
#undef BAD
  if (!field) return RC_OK;
  rc_scene_error(s, kind, index, "%s is beyond the f32 range (3.4e38) the GPU renders in", field);
  return RC_ERR_INPUT;
}

/* object_from_packed = inverse(world_from_object) composed with packed -> world (+origin,
 * / scale), in f64, rounded to f32; object space is measured in packed units too (its
 * points times scale), so only the translation scales. Returns false for a transform that
 * is singular, or becomes so or infinite in f32 (a scale beyond 1e38 or below 1e-38). */
static bool object_from_packed(const rc_affine *w, dvec3 origin, double scale, packed_transform *out) {
  const double(*a)[4] = w->m;
  double lin[3][3] = {{a[0][0], a[0][1], a[0][2]}, {a[1][0], a[1][1], a[1][2]}, {a[2][0], a[2][1], a[2][2]}};
  double inv[3][3];
  if (!rcm_mat3_inverse_d(lin, inv)) return false;
  /* p_obj = inv (p_world - t) with p_world = p_packed + origin. */
  double shift[3] = {origin.x - a[0][3], origin.y - a[1][3], origin.z - a[2][3]};
  vec4 *rows[3] = {&out->row0, &out->row1, &out->row2};
  for (int i = 0; i < 3; i++) {
    double tr = (inv[i][0] * shift[0] + inv[i][1] * shift[1] + inv[i][2] * shift[2]) * scale;
    *rows[i] = (vec4){(float)inv[i][0], (float)inv[i][1], (float)inv[i][2], (float)tr};
  }
  const vec4 *r = &out->row0, *q = &out->row1, *t = &out->row2;
  double det = (double)r->x * ((double)q->y * t->z - (double)q->z * t->y) -
               (double)r->y * ((double)q->x * t->z - (double)q->z * t->x) +
               (double)r->z * ((double)q->x * t->y - (double)q->y * t->x);
  for (int i = 0; i < 3; i++)
    if (!isfinite(rows[i]->x) || !isfinite(rows[i]->y) || !isfinite(rows[i]->z) || !isfinite(rows[i]->w)) return false;
  return det != 0 && isfinite(det);
}

/* A quadric's frame stays in f64 up to here: the centre is made camera-relative before
 * rounding, the coefficients and the clip box are already centre-relative. In packed units
 * (x' = s x) the equation is multiplied through by s^2: the second-order coefficients stay,
 * the linear ones scale by s and the constant by s^2. */
static void pack_quadric(const rc_packed_scene *p, const rc_quadric_def *q, packed_quadric *g) {
  double s = p->scale;
  if (q->patch) {
    /* A patch piece: its box, its (u, v) part, where its patch's control points are. */
    *g = (packed_quadric){.center = to_packed(p, q->center),
                          .material = q->material,
                          .axis_x = {1, 0, 0},
                          .axis_y = {0, 1, 0},
                          .axis_z = {0, 0, 1},
                          .flags = RC_QUADRIC_PATCH,
                          .mesh_root = p->patch_first + RC_TEXELS_PER_PATCH * (q->patch - 1),
                          .mesh_end = q->patch_piece0,
                          .diag = {(float)q->domain[0], (float)q->domain[1], 0},
                          .off = {(float)q->domain[2], (float)q->domain[3], 0},
                          .lo = rcm_to_f(rcm_scale_d(q->lo, s)),
                          .hi = rcm_to_f(rcm_scale_d(q->hi, s))};
    return;
  }
  *g = (packed_quadric){.center = to_packed(p, q->center),
                     .material = q->material,
                     .axis_x = rcm_to_f(q->axis[0]),
                     .axis_y = rcm_to_f(q->axis[1]),
                     .axis_z = rcm_to_f(q->axis[2]),
                     .constant = (float)(q->constant * s * s),
                     .flags = (q->solid ? RC_QUADRIC_SOLID : 0u) | (q->one_sided ? RC_QUADRIC_ONE_SIDED : 0u) |
                              (q->uv << RC_QUADRIC_UV_SHIFT),
                     .diag = rcm_to_f(q->diag),
                     .off = rcm_to_f(q->off),
                     .linear = rcm_to_f(rcm_scale_d(q->linear, s)),
                     .lo = rcm_to_f(rcm_scale_d(q->lo, s)),
                     .hi = rcm_to_f(rcm_scale_d(q->hi, s))};
}

/* A plane has no clip box: `lo` holds its texture coordinates instead, (u, v) = (f.x, f.y)
 * lo.z + (lo.x, lo.y) in scene units from the point the scene gave, along its frame's x
 * and y axes (f: frame coordinates from the packed centre, rc_shade.glsl). The centre's
 * offset is found in f64, so a texture stays put wherever the eye is. */
static void pack_plane(const rc_packed_scene *p, const rc_scene *s, const rc_quadric_def *q, packed_quadric *g) {
  rc_quadric_def moved = *q;
  moved.center = plane_point_nearest_eye(s, q);
  pack_quadric(p, &moved, g);
  g->flags |= RC_QUADRIC_UNBOUNDED;
  dvec3 shift = rcm_sub_d(moved.center, q->center);
  g->lo = (vec3){(float)rcm_dot_d(shift, q->axis[0]), (float)rcm_dot_d(shift, q->axis[1]), (float)(1.0 / p->scale)};
}

/* The frame: the quality settings, the image's sampling, the counts. */
static void pack_frame(const rc_scene *s, rc_packed_scene *p) {
  packed_frame *f = &p->frame;
  f->sphere_formula = s->quality.sphere;
  f->triangle_formula = s->quality.triangle;
  f->offset_strategy = s->quality.offset;
  f->offset_epsilon = (float)(s->quality.offset_epsilon * p->scale);
  f->background = rcm_to_f(s->background);
  f->ambient_light = rcm_to_f(s->ambient_light);
  f->specular_model = s->specular_model;
  f->samples_per_pixel = s->samples_per_pixel;
  f->seed = s->seed;
  f->strata_x = (uint32_t)ceil(sqrt((double)s->samples_per_pixel));
  f->strata_y = (s->samples_per_pixel + f->strata_x - 1) / f->strata_x;
  f->inv_strata_x = 1.0f / (float)f->strata_x;
  f->inv_strata_y = 1.0f / (float)f->strata_y;
  f->sphere_count = (uint32_t)s->sphere_count;
  f->triangle_count = (uint32_t)s->triangle_count;
  f->material_count = (uint32_t)s->material_count;
  f->light_count = (uint32_t)s->light_count;
  f->quadric_count = (uint32_t)(s->quadric_count + s->plane_count);
  f->plane_count = (uint32_t)s->plane_count;
  f->csg_count = (uint32_t)s->csg_count;
  f->object_count = f->sphere_count + f->triangle_count + f->quadric_count + f->csg_count;
  f->shadows = s->quality.shadows ? 1u : 0u;
  /* Reflection costs a bounce loop only where some material mirrors. */
  bool any_mirror = false;
  for (size_t i = 0; i < s->material_count; i++) any_mirror |= rcm_max_abs_comp_d(s->materials[i].mirror) > 0.0;
  f->reflection_depth = any_mirror ? s->reflection_depth : 0;
  for (size_t i = 0; i < s->csg_count; i++)
    if (s->csgs[i].steps > f->csg_max_steps) f->csg_max_steps = s->csgs[i].steps;
}

/* The mip levels stored for image i (rc_texture_def.image): all of them where a texture
 * reading it is mip-mapped, else the image alone. */
static uint32_t image_levels(const rc_scene *s, size_t i) {
  bool mipmap = false;
  for (size_t k = 0; k < s->texture_count; k++) mipmap |= s->textures[k].image == i && s->textures[k].mipmap;
  return rc_texture_level_count(s->textures[i].width, s->textures[i].height, mipmap);
}

/* Every array at its size, at least one element each: Vulkan has no zero-sized buffers. */
static bool alloc_arrays(const rc_scene *s, rc_packed_scene *p) {
  p->spheres = rc_alloc(s->sphere_count + 1, sizeof *p->spheres, "packed spheres");
  p->triangle_total = (uint32_t)(s->triangle_count + s->csg_triangle_count);
  p->triangles = rc_alloc(p->triangle_total + 1, sizeof *p->triangles, "packed triangles");
  p->materials = rc_alloc(s->material_count + 1, sizeof *p->materials, "packed materials");
  p->lights = rc_alloc(s->light_count + 1, sizeof *p->lights, "packed lights");
  p->transforms = rc_alloc(s->sphere_count + 1, sizeof *p->transforms, "packed transforms");
  size_t smooth = 0;
  for (size_t i = 0; i < s->triangle_count; i++) smooth += s->triangles[i].smooth;
  p->normals = rc_alloc(smooth + 1, sizeof *p->normals, "packed normals");

  /* Standalone quadrics, then planes, then the composites' leaves. */
  size_t standalone = s->quadric_count + s->plane_count;
  p->quadrics = rc_alloc(standalone + s->csg_leaf_count + 1, sizeof *p->quadrics, "packed quadrics");
  p->csg = rc_alloc(s->csg_count + 1, sizeof *p->csg, "packed composites");
  size_t program = 0;
  for (size_t i = 0; i < s->csg_count; i++) program += s->csgs[i].length;
  p->csg_program = rc_alloc((program + 4) / 4 * 4, sizeof *p->csg_program, "packed CSG programs");
  p->csg_program_length = (uint32_t)program;
  p->quadric_total = (uint32_t)(standalone + s->csg_leaf_count);
  for (size_t i = 0; i < s->csg_leaf_count; i++) p->mesh_operand_count += s->csg_leaves[i].mesh;
  p->mesh_operands = rc_alloc(p->mesh_operand_count + 1, sizeof *p->mesh_operands, "packed mesh operands");
  size_t texels = 0;
  for (size_t i = 0; i < s->texture_count; i++)
    texels += RC_TEXELS_PER_TEXTURE_HEADER +
              (s->textures[i].image == i ? rc_texture_pyramid_texels(s->textures[i].width, s->textures[i].height,
                                                                     image_levels(s, i))
                                         : 0);
  /* Then the triangles' texture coordinates (RC_TRIANGLE_UV_SHIFT). */
  p->uv_first = (uint32_t)texels;
  for (size_t i = 0; i < s->triangle_count; i++) texels += s->triangles[i].has_uv ? RC_TEXELS_PER_VERTEX_UVS : 0;
  /* Then the patches' control points (RC_QUADRIC_PATCH). */
  p->patch_first = (uint32_t)texels;
  texels += RC_TEXELS_PER_PATCH * s->patch_count;
  p->texel_count = (uint32_t)texels;
  p->texture_count = (uint32_t)s->texture_count;
  p->texels = rc_alloc(4 * (texels + 1), sizeof *p->texels, "packed textures");
  return p->texels && p->mesh_operands && p->spheres && p->triangles && p->materials && p->lights && p->transforms &&
         p->normals && p->quadrics && p->csg && p->csg_program;
}

/* Spheres: packed-space centres, or object-space ones with the transform from packed space. */
static rc_status pack_spheres(const rc_scene *s, rc_packed_scene *p) {
  for (size_t i = 0; i < s->sphere_count; i++) {
    const rc_sphere_def *d = &s->spheres[i];
    p->spheres[i].radius = (float)(d->radius * p->scale);
    p->spheres[i].material = d->material;
    p->spheres[i].transform = RC_NO_TRANSFORM;
    if (!d->transformed) {
      p->spheres[i].center = to_packed(p, d->center);
    } else {
      p->spheres[i].center = rcm_to_f(rcm_scale_d(d->center, p->scale)); /* object space */
      if (!object_from_packed(&d->world_from_object, p->origin, p->scale, &p->transforms[p->transform_count])) {
        rc_scene_error(s, RC_ORIGIN_SPHERE, i, "its transform is singular, or is once inverted in f32 (a scale of "
                       "0, or beyond 1e38 or below 1e-38)");
        return RC_ERR_INPUT;
      }
      p->spheres[i].transform = p->transform_count++;
    }
  }
  return RC_OK;
}

/* The scene's triangles (with their vertex normals where smooth), then the composites'
 * mesh operands' triangles. */
static void pack_triangles(const rc_scene *s, rc_packed_scene *p) {
  for (size_t i = 0; i < s->triangle_count; i++) {
    p->triangles[i].v0 = to_packed(p, s->triangles[i].v[0]);
    p->triangles[i].v1 = to_packed(p, s->triangles[i].v[1]);
    p->triangles[i].v2 = to_packed(p, s->triangles[i].v[2]);
    p->triangles[i].material = s->triangles[i].material;
    p->triangles[i].flags = s->triangles[i].one_sided ? RC_TRIANGLE_ONE_SIDED : 0u;
    if (s->triangles[i].has_uv) {
      const double(*uv)[2] = s->triangles[i].uv;
      const packed_vertex_uvs t = {(float)uv[0][0], (float)uv[0][1], (float)uv[1][0], (float)uv[1][1],
                                   (float)uv[2][0], (float)uv[2][1], 0.0f, 0.0f};
      uint32_t at = p->uv_first + RC_TEXELS_PER_VERTEX_UVS * p->uv_count++;
      memcpy(&p->texels[4 * (size_t)at], &t, sizeof t);
      p->triangles[i].flags |= (at + 1) << RC_TRIANGLE_UV_SHIFT;
    }
    p->one_sided_triangle_count += s->triangles[i].one_sided;
    p->triangles[i].normals = RC_NO_NORMALS;
    if (s->triangles[i].smooth) {
      packed_vertex_normals *vn = &p->normals[p->normal_count];
      vn->n0 = rcm_to_f(s->triangles[i].n[0]);
      vn->n1 = rcm_to_f(s->triangles[i].n[1]);
      vn->n2 = rcm_to_f(s->triangles[i].n[2]);
      p->triangles[i].normals = p->normal_count++;
    }
  }
  for (size_t i = 0; i < s->csg_triangle_count; i++) {
    packed_triangle *g = &p->triangles[s->triangle_count + i];
    g->v0 = to_packed(p, s->csg_triangles[i].v[0]);
    g->v1 = to_packed(p, s->csg_triangles[i].v[1]);
    g->v2 = to_packed(p, s->csg_triangles[i].v[2]);
    g->material = s->csg_triangles[i].material;
    g->flags = 0u;
    g->normals = RC_NO_NORMALS;
  }
}

/* Each texture's header (packed_texture and its levels' table), then its image and mip
 * levels unless an earlier texture named the same file (rc_texture_def.image: the image is
 * shared), in the scene's order; *first gets where each header is. The images were read by
 * the command (cli/textures.c). */
static void pack_textures(const rc_scene *s, rc_packed_scene *p, uint32_t *first) {
  uint32_t at = 0;
  for (size_t i = 0; i < s->texture_count; i++) {
    const rc_texture_def *t = &s->textures[i];
    first[i] = at;
    at += RC_TEXELS_PER_TEXTURE_HEADER;
    uint32_t stored = image_levels(s, t->image), levels = t->mipmap ? stored : 1;
    uint32_t level_first[RC_TEXTURE_MAX_LEVELS] = {0};
    packed_texture h = {.width = t->width, .height = t->height,
                        .flags = (t->bilinear ? RC_TEXTURE_BILINEAR : 0u) | (t->clamp ? RC_TEXTURE_CLAMP : 0u) |
                                 levels << RC_TEXTURE_LEVELS_SHIFT,
                        .texels = at,
                        .scale_u = (float)t->scale[0], .scale_v = (float)t->scale[1],
                        .offset_u = (float)t->offset[0], .offset_v = (float)t->offset[1]};
    if (t->image != i) { /* a shared image: the earlier texture's header says where it lies */
      packed_texture shared;
      memcpy(&shared, &p->texels[4 * (size_t)first[t->image]], sizeof shared);
      h.texels = shared.texels;
      memcpy(level_first, &p->texels[4 * ((size_t)first[t->image] + 2)], sizeof level_first);
    } else {
      RC_ASSERT(t->rgb != NULL);
      rc_texture_write_levels(t->rgb, t->width, t->height, stored, at, &p->texels[4 * (size_t)at], level_first);
      at += (uint32_t)rc_texture_pyramid_texels(t->width, t->height, stored);
    }
    memcpy(&p->texels[4 * (size_t)first[i]], &h, sizeof h);
    memcpy(&p->texels[4 * ((size_t)first[i] + 2)], level_first, sizeof level_first);
  }
}

static void pack_materials(const rc_scene *s, rc_packed_scene *p, const uint32_t *texture_first) {
  for (size_t i = 0; i < s->material_count; i++) {
    const rc_material_def *m = &s->materials[i];
    p->materials[i].texture = m->texture ? texture_first[m->texture - 1] : RC_NO_TEXTURE;
    p->materials[i].ambient = rcm_to_f(m->ambient);
    p->materials[i].diffuse = rcm_to_f(m->diffuse);
    p->materials[i].specular = rcm_to_f(m->specular);
    p->materials[i].mirror = rcm_to_f(m->mirror);
    p->materials[i].shininess = (float)m->shininess;
    p->materials[i].emission = rcm_to_f(m->emission);
  }
}

static void pack_lights(const rc_scene *s, rc_packed_scene *p) {
  for (size_t i = 0; i < s->light_count; i++) {
    const rc_light_def *l = &s->lights[i];
    p->lights[i].type = l->type;
    /* A point light's I / (c0 + c1 r + c2 r^2) with r' = s r: I and c0 times s^2, c1 times s. */
    bool point = l->type == RC_LIGHT_POINT;
    double s2 = point ? p->scale * p->scale : 1;
    p->lights[i].intensity = rcm_to_f(rcm_scale_d(l->intensity, s2));
    p->lights[i].attenuation = rcm_to_f(point ? rcm_make_d(l->attenuation.x * s2, l->attenuation.y * p->scale,
                                                           l->attenuation.z)
                                              : rcm_make_d(1, 0, 0));
    p->lights[i].position = l->type == RC_LIGHT_POINT ? to_packed(p, l->position)
                                                      : rcm_to_f(rcm_normalize_d(l->direction));
  }
}

/* The patches' control points, in the packed space, 16 texels each (x, y, z, 0). */
static void pack_patches(const rc_scene *s, rc_packed_scene *p) {
  for (size_t i = 0; i < s->patch_count; i++)
    for (uint32_t k = 0; k < RC_TEXELS_PER_PATCH; k++) {
      vec3 v = to_packed(p, s->patches[i].p[k]);
      float w[4] = {v.x, v.y, v.z, 0};
      memcpy(&p->texels[4 * (p->patch_first + RC_TEXELS_PER_PATCH * i + k)], w, sizeof w);
    }
}

void rc_packed_scene_count_patches(rc_packed_scene *p) {
  p->frame.patch_count = 0;
  for (uint32_t i = 0; i < p->frame.quadric_count; i++) p->frame.patch_count += (p->quadrics[i].flags & RC_QUADRIC_PATCH) != 0;
}

/* Standalone quadrics, then planes, then the composites' leaves (a mesh operand's leaf
 * names its triangles), and the composites, whose leaf operands index that array. */
static void pack_quadrics_and_composites(const rc_scene *s, rc_packed_scene *p) {
  pack_patches(s, p);
  size_t standalone = s->quadric_count + s->plane_count;
  for (size_t i = 0; i < s->quadric_count; i++) pack_quadric(p, &s->quadrics[i], &p->quadrics[i]);
  for (size_t i = 0; i < s->plane_count; i++) pack_plane(p, s, &s->planes[i], &p->quadrics[s->quadric_count + i]);
  for (size_t i = 0, m = 0; i < s->csg_leaf_count; i++) {
    const rc_quadric_def *q = &s->csg_leaves[i];
    pack_quadric(p, q, &p->quadrics[standalone + i]);
    if (!q->mesh) continue;
    p->quadrics[standalone + i].flags |= RC_QUADRIC_MESH;
    p->quadrics[standalone + i].mesh_crossings = q->max_crossings;
    p->mesh_operands[m++] = (rc_mesh_operand){.leaf = (uint32_t)(standalone + i),
                                              .first = (uint32_t)(s->triangle_count + q->mesh_first),
                                              .count = q->mesh_count};
  }
  uint32_t at = 0;
  for (size_t i = 0; i < s->csg_count; i++) {
    const rc_csg_def *c = &s->csgs[i];
    p->csg[i] = (packed_csg){.lo = to_packed(p, c->lo), .hi = to_packed(p, c->hi), .first = at, .count = c->length};
    for (uint32_t k = 0; k < c->length; k++) {
      uint32_t ins = c->program[k];
      bool leaf = (ins >> RC_CSG_OP_SHIFT) == RC_CSG_LEAF;
      p->csg_program[at++] = leaf ? ins + (uint32_t)standalone : ins;
    }
  }
}

void rc_scene_pack_frame(const rc_scene *s, rc_packed_scene *p) {
  memset(&p->frame, 0, sizeof p->frame);
  pack_camera(s, p);
  pack_frame(s, p);
}

rc_status rc_scene_pack(const rc_scene *s, rc_packed_scene *p) {
  memset(p, 0, sizeof *p);
  /* Camera-relative packing is the default; without it the packed space is world space,
   * kept only to measure what the floating origin buys (docs/accuracy.md). */
  p->origin = s->quality.camera_relative ? s->camera.eye : rcm_make_d(0, 0, 0);
  p->scale = packing_scale(s, p->origin);
  rc_scene_pack_frame(s, p);
  if (!alloc_arrays(s, p)) {
    rc_packed_scene_free(p);
    return RC_ERR_OUT_OF_MEMORY;
  }
  rc_status st = pack_spheres(s, p);
  if (st == RC_OK) {
    pack_triangles(s, p);
    uint32_t *first = rc_alloc(s->texture_count + 1, sizeof *first, "texture offsets");
    if (!first) {
      rc_packed_scene_free(p);
      return RC_ERR_OUT_OF_MEMORY;
    }
    pack_textures(s, p, first);
    pack_materials(s, p, first);
    free(first);
    pack_lights(s, p);
    pack_quadrics_and_composites(s, p);
    rc_packed_scene_count_patches(p);
    st = check_f32_range(s, p);
    if (st == RC_OK) rc_packed_patch_bounds(p);
  }
  if (st != RC_OK) rc_packed_scene_free(p);
  return st;
}

/* docs/numerics.md §7: a relative change of up to 2^-22 (a few f32 ulps) in every input
 * coordinate. The amount hashes the value's bits with the seed, so a vertex shared by
 * several triangles moves the same way in all of them. The sign: seeds 1 and 2 move every
 * value up, then down (times `lean`), so that a decision on a knife edge (a ray exactly
 * tangent to a quadric) flips in one of them whichever way the edge leans; with random
 * signs all four references once shrank a tangent cylinder and the band missed it. Seeds
 * from 3 on take the sign from the hash: the values move independently. */
static float perturb_lean(float x, uint32_t seed, double lean) {
  uint32_t bits;
  memcpy(&bits, &x, sizeof bits);
  uint32_t h = bits ^ (seed * 0x9e3779b9u);
  h ^= h >> 16, h *= 0x7feb352du, h ^= h >> 15, h *= 0x846ca68bu, h ^= h >> 16;
  double d = seed <= 2 ? (seed == 1 ? lean : -lean) * ((double)h / 4294967295.0)
                       : (double)h / 4294967295.0 * 2.0 - 1.0;
  return (float)((double)x * (1.0 + d * 0x1p-22));
}

static float perturb_value(float x, uint32_t seed) { return perturb_lean(x, seed, 1.0); }

static vec3 perturb_vec3_lean(vec3 v, uint32_t seed, double lean) {
  return (vec3){perturb_lean(v.x, seed, lean), perturb_lean(v.y, seed, lean), perturb_lean(v.z, seed, lean)};
}

static vec3 perturb_vec3(vec3 v, uint32_t seed) { return perturb_vec3_lean(v, seed, 1.0); }

void rc_packed_scene_perturb(rc_packed_scene *p, uint32_t seed) {
  for (uint32_t i = 0; i < p->frame.sphere_count; i++) {
    p->spheres[i].center = perturb_vec3(p->spheres[i].center, seed);
    p->spheres[i].radius = perturb_value(p->spheres[i].radius, seed);
  }
  for (uint32_t i = 0; i < p->triangle_total; i++) {
    p->triangles[i].v0 = perturb_vec3(p->triangles[i].v0, seed);
    p->triangles[i].v1 = perturb_vec3(p->triangles[i].v1, seed);
    p->triangles[i].v2 = perturb_vec3(p->triangles[i].v2, seed);
  }
  for (uint32_t i = 0; i < p->frame.light_count; i++)
    if (p->lights[i].type == RC_LIGHT_POINT) p->lights[i].position = perturb_vec3(p->lights[i].position, seed);
  /* A quadric's inputs are its centre, coefficients and clip box (its radii, angles and
   * heights live there). Its frame rows are left as they are: a rotation, or under a
   * transform also its scale, whose own rounding the band therefore does not cover. */
  for (uint32_t i = 0; i < p->quadric_total; i++) {
    packed_quadric *q = &p->quadrics[i];
    if (q->flags & RC_QUADRIC_PATCH) {
      /* A patch's inputs are its control points, moved once, with its first piece; the
       * pieces' (u, v) parts are not measurements. */
      q->center = perturb_vec3(q->center, seed);
      q->lo = perturb_vec3(q->lo, seed);
      q->hi = perturb_vec3(q->hi, seed);
      for (uint32_t k = 0; q->diag.x == 0 && q->off.x == 0 && k < RC_TEXELS_PER_PATCH; k++) {
        vec3 v;
        memcpy(&v, &p->texels[4 * (size_t)(q->mesh_root + k)], sizeof v);
        v = perturb_vec3(v, seed);
        memcpy(&p->texels[4 * (size_t)(q->mesh_root + k)], &v, sizeof v);
      }
      continue;
    }
    q->center = perturb_vec3(q->center, seed);
    /* The second-order coefficients lean the other way from the constant, so that
     * -constant / diag (a radius squared, after normalization) moves rather than cancels. */
    q->diag = perturb_vec3_lean(q->diag, seed, -1.0);
    q->off = perturb_vec3_lean(q->off, seed, -1.0);
    q->linear = perturb_vec3(q->linear, seed);
    q->constant = perturb_value(q->constant, seed);
    q->lo = perturb_vec3(q->lo, seed);
    q->hi = perturb_vec3(q->hi, seed);
  }
  /* The patches' nets moved: their differences follow (they are derived, not inputs). */
  rc_packed_patch_bounds(p);
}

void rc_packed_scene_free(rc_packed_scene *p) {
  if (p->borrowed) {
    if (p->bvh_copied) free(p->bvh_nodes), free(p->bvh_prims);
    memset(p, 0, sizeof *p);
    return;
  }
  free(p->spheres);
  free(p->triangles);
  free(p->materials);
  free(p->lights);
  free(p->bvh_nodes);
  free(p->bvh_prims);
  free(p->transforms);
  free(p->normals);
  free(p->quadrics);
  free(p->csg);
  free(p->csg_program);
  free(p->mesh_operands);
  free(p->texels);
  memset(p, 0, sizeof *p);
}

/* The parts rc_packed_scene_hash chains: the frame, the packed space, then the arrays. */
typedef struct {
  const void *data;
  size_t bytes;
} hash_part;
#define HASH_PARTS (3 + RC_PACKED_ARRAYS)
static void hash_parts(const rc_packed_scene *p, hash_part parts[HASH_PARTS]) {
  const packed_frame *f = &p->frame;
  const hash_part all[HASH_PARTS] = {{f, sizeof *f},
                                     {&p->origin, sizeof p->origin},
                                     {&p->scale, sizeof p->scale},
                                     {p->spheres, f->sphere_count * sizeof *p->spheres},
                                     {p->triangles, p->triangle_total * sizeof *p->triangles},
                                     {p->materials, f->material_count * sizeof *p->materials},
                                     {p->lights, f->light_count * sizeof *p->lights},
                                     {p->transforms, p->transform_count * sizeof *p->transforms},
                                     {p->normals, p->normal_count * sizeof *p->normals},
                                     {p->quadrics, p->quadric_total * sizeof *p->quadrics},
                                     {p->csg, f->csg_count * sizeof *p->csg},
                                     {p->csg_program, p->csg_program_length * sizeof *p->csg_program},
                                     {p->texels, 4 * (size_t)p->texel_count * sizeof *p->texels}};
  memcpy(parts, all, sizeof all);
}

static uint64_t part_hash(const hash_part *part, size_t i) {
  return part->bytes ? rc_hash_bytes(part->data, part->bytes) : i;
}

void rc_packed_scene_array_hashes(const rc_packed_scene *p, uint64_t hashes[RC_PACKED_ARRAYS]) {
  hash_part parts[HASH_PARTS];
  hash_parts(p, parts);
  for (size_t i = 0; i < RC_PACKED_ARRAYS; i++) hashes[i] = part_hash(&parts[3 + i], 3 + i);
}

uint64_t rc_packed_scene_hash(const rc_packed_scene *p) {
  hash_part parts[HASH_PARTS];
  hash_parts(p, parts);
  /* Each part's hash chained into the next, so that moving bytes between parts counts. */
  uint64_t h[2] = {0, 0};
  for (size_t i = 0; i < HASH_PARTS; i++) {
    h[1] = i >= 3 && p->array_hashes ? p->array_hashes[i - 3] : part_hash(&parts[i], i);
    h[0] = rc_hash_bytes(h, sizeof h);
  }
  return h[0];
}
