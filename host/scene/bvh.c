#include "scene/bvh.h"

#include "math/rcm_mat3.h"
#include "scene/name_table.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* SAH bins per axis. Bins split a node's centroid bounds evenly, and a split that bins
 * cannot place is never tried: a floor under a mesh (every benchmark scene,
 * tools/mesh_scene.sh) has its centroids at the mesh's lowest point, and with 16 bins the
 * mesh's lowest triangles shared the floor's bin near the root, so their boxes were as
 * wide as the floor at the levels every ray walks. The top BINS_FINE_LEVELS levels (at
 * most 15 nodes), where large and small objects are still together, get a quarter of
 * their objects' count in bins, clamped to [BINS_MIN, BINS_MAX]; deeper nodes are
 * compact and keep 16. Box steps per ray counted in the CPU reference (1024x768, 1 spp,
 * f32, primary and shadow rays), 16 bins -> this rule: mesh 1k 13.82 -> 12.23, 100k
 * 23.00 -> 21.21, 1M 29.61 -> 26.16, spider 11.02 -> 8.82, 2CylinderEngine 16.29 ->
 * 12.62, mesh.json 20.06 -> 18.40, Wuson 12.72 -> 11.01; the sphere grid and
 * the other example scenes unchanged. The same rule at every level gained at most 0.2
 * more steps and cost the 1M mesh's build 17 % (docs/performance.md, finding 12). */
#define BINS_FINE_LEVELS 4u
#define BINS_MIN 16
#define BINS_MAX 1024

typedef struct {
  float lo[3], hi[3];
} box;

typedef struct {
  box bounds;
  float centroid[3];
} prim_info;

/* The binary tree before flattening. */
typedef struct {
  box bounds;
  uint32_t first, count; /* leaf: a range of refs */
  uint32_t left, right;  /* interior (count 0) */
} build_node;

/* choose_split's working arrays, one set per build (96 KiB: off the stack). */
typedef struct {
  box bounds[3][BINS_MAX];
  uint32_t count[3][BINS_MAX];
  double left_area[BINS_MAX];
  uint32_t left_count[BINS_MAX];
} bin_scratch;

typedef struct {
  prim_info *info;
  uint32_t *refs;
  bin_scratch *bins;
  build_node *nodes;
  uint32_t node_count, node_cap;
  uint32_t depth, leaves, max_leaf;
} builder;

static box empty_box(void) { return (box){{FLT_MAX, FLT_MAX, FLT_MAX}, {-FLT_MAX, -FLT_MAX, -FLT_MAX}}; }

static void grow(box *b, const box *o) {
  for (int k = 0; k < 3; k++) {
    if (o->lo[k] < b->lo[k]) b->lo[k] = o->lo[k];
    if (o->hi[k] > b->hi[k]) b->hi[k] = o->hi[k];
  }
}

static void grow_point(box *b, const float p[3]) {
  for (int k = 0; k < 3; k++) {
    if (p[k] < b->lo[k]) b->lo[k] = p[k];
    if (p[k] > b->hi[k]) b->hi[k] = p[k];
  }
}

static double area(const box *b) {
  double dx = (double)b->hi[0] - b->lo[0], dy = (double)b->hi[1] - b->lo[1], dz = (double)b->hi[2] - b->lo[2];
  if (dx < 0 || dy < 0 || dz < 0) return 0;
  return 2 * (dx * dy + dy * dz + dz * dx);
}

static uint32_t new_node(builder *b) {
  if (b->node_count == b->node_cap) {
    uint32_t cap = b->node_cap ? 2 * b->node_cap : 1024;
    build_node *n = realloc(b->nodes, cap * sizeof *n);
    if (!n) return UINT32_MAX;
    b->nodes = n;
    b->node_cap = cap;
  }
  return b->node_count++;
}

/* Chooses a split of refs[first, first+count): the SAH-best bin boundary, or -1 for a leaf.
 * One pass bins the objects along all three axes: the references point all over the info
 * array, and reading each object once a level instead of three times took the 1M-triangle
 * mesh's build from 1,827 to 1,658 ms (medians of 3; no change at 100k). The tree is the
 * same, byte for byte. */
/* The bins per axis for a node of `count` objects at `depth` (the rule above BINS_FINE_LEVELS). */
static int bins_for(uint32_t count, uint32_t depth) {
  uint32_t quarter = count / 4;
  if (depth >= BINS_FINE_LEVELS || quarter < BINS_MIN) return BINS_MIN;
  return quarter > BINS_MAX ? BINS_MAX : (int)quarter;
}

static int choose_split(builder *b, uint32_t first, uint32_t count, uint32_t depth, const box *bounds, int *axis_out,
                        float *pos_out) {
  const int bins = bins_for(count, depth);
  box cb = empty_box();
  for (uint32_t i = first; i < first + count; i++) grow_point(&cb, b->info[b->refs[i]].centroid);
  double best = (double)count; /* cost of a leaf, relative to one object test */
  int best_axis = -1;
  float best_pos = 0;
  double parent_area = area(bounds);
  float lo[3], extent[3];
  bool usable[3];
  box(*bin_box)[BINS_MAX] = b->bins->bounds;
  uint32_t(*bin_count)[BINS_MAX] = b->bins->count;
  for (int axis = 0; axis < 3; axis++) {
    lo[axis] = cb.lo[axis];
    extent[axis] = cb.hi[axis] - cb.lo[axis];
    usable[axis] = extent[axis] > 0;
    for (int i = 0; i < bins; i++) {
      bin_box[axis][i] = empty_box();
      bin_count[axis][i] = 0;
    }
  }
  for (uint32_t i = first; i < first + count; i++) {
    const prim_info *p = &b->info[b->refs[i]];
    for (int axis = 0; axis < 3; axis++) {
      if (!usable[axis]) continue;
      int bin = (int)((p->centroid[axis] - lo[axis]) / extent[axis] * bins);
      if (bin >= bins) bin = bins - 1;
      if (bin < 0) bin = 0;
      bin_count[axis][bin]++;
      grow(&bin_box[axis][bin], &p->bounds);
    }
  }
  for (int axis = 0; axis < 3; axis++) {
    if (!usable[axis]) continue;
    /* Sweep: area and count of everything left / right of each boundary. */
    double *left_area = b->bins->left_area;
    uint32_t *left_count = b->bins->left_count;
    box acc = empty_box();
    uint32_t n = 0;
    for (int i = 0; i < bins - 1; i++) {
      grow(&acc, &bin_box[axis][i]);
      n += bin_count[axis][i];
      left_area[i] = area(&acc);
      left_count[i] = n;
    }
    acc = empty_box();
    n = 0;
    for (int i = bins - 1; i > 0; i--) {
      grow(&acc, &bin_box[axis][i]);
      n += bin_count[axis][i];
      if (left_count[i - 1] == 0 || n == 0) continue;
      double cost = 1.0 + (left_area[i - 1] * left_count[i - 1] + area(&acc) * n) / parent_area;
      if (cost < best) {
        best = cost;
        best_axis = axis;
        best_pos = lo[axis] + extent[axis] * (float)i / (float)bins;
      }
    }
  }
  *axis_out = best_axis;
  *pos_out = best_pos;
  return best_axis;
}

static int cmp_axis;
static const prim_info *cmp_info;
static int by_centroid(const void *a, const void *b) {
  float x = cmp_info[*(const uint32_t *)a].centroid[cmp_axis], y = cmp_info[*(const uint32_t *)b].centroid[cmp_axis];
  return (x > y) - (x < y);
}

/* Builds the subtree of refs[first, first+count); returns its node index. */
static uint32_t build(builder *b, uint32_t first, uint32_t count, uint32_t depth) {
  uint32_t id = new_node(b);
  if (id == UINT32_MAX) return UINT32_MAX;
  box bounds = empty_box();
  for (uint32_t i = first; i < first + count; i++) grow(&bounds, &b->info[b->refs[i]].bounds);
  b->nodes[id] = (build_node){bounds, first, count, 0, 0};
  if (depth > b->depth) b->depth = depth;
  /* Halving by count needs ceil(log2(count)) more levels; once the depth left is down
   * to that, only halving keeps the tree within RC_BVH_MAX_DEPTH. */
  uint32_t halvings = 0;
  while ((1ull << halvings) < count) halvings++;
  bool must_halve = count > 1 && depth + halvings + 1 >= RC_BVH_MAX_DEPTH;
  int axis;
  float pos;
  uint32_t mid = first;
  if (count <= 1) {
    mid = first;
  } else if (!must_halve && choose_split(b, first, count, depth, &bounds, &axis, &pos) >= 0) {
    uint32_t i = first, j = first + count;
    while (i < j) {
      if (b->info[b->refs[i]].centroid[axis] < pos) {
        i++;
      } else {
        uint32_t t = b->refs[i];
        b->refs[i] = b->refs[--j];
        b->refs[j] = t;
      }
    }
    mid = i;
    if (mid == first || mid == first + count) mid = first; /* binning rounding: give up */
  }
  if (mid == first && (count > RC_BVH_LEAF_MAX || must_halve) && count > 1) {
    /* No useful SAH split but too many objects (or depth is running out): halve by count
     * along the widest centroid axis. */
    box cb = empty_box();
    for (uint32_t i = first; i < first + count; i++) grow_point(&cb, b->info[b->refs[i]].centroid);
    int widest = 0;
    for (int k = 1; k < 3; k++)
      if (cb.hi[k] - cb.lo[k] > cb.hi[widest] - cb.lo[widest]) widest = k;
    cmp_axis = widest;
    cmp_info = b->info;
    qsort(b->refs + first, count, sizeof *b->refs, by_centroid);
    mid = first + count / 2;
  }
  if (mid == first) {
    b->leaves++;
    if (count > b->max_leaf) b->max_leaf = count;
    return id;
  }
  uint32_t left = build(b, first, mid - first, depth + 1);
  uint32_t right = left == UINT32_MAX ? UINT32_MAX : build(b, mid, first + count - mid, depth + 1);
  if (right == UINT32_MAX) return UINT32_MAX;
  b->nodes[id].count = 0;
  b->nodes[id].left = left;
  b->nodes[id].right = right;
  return id;
}

/* Squared distance from p to the box, 0 inside it. */
static double box_distance2(const box *b, const float p[3]) {
  double d2 = 0;
  for (int k = 0; k < 3; k++) {
    double out = p[k] < b->lo[k] ? (double)b->lo[k] - p[k] : p[k] > b->hi[k] ? (double)p[k] - b->hi[k] : 0;
    d2 += out * out;
  }
  return d2;
}

/* Writes the subtree of build node `id` in depth-first order from out[*next] on, the
 * child nearer the eye first: in packed space every primary ray starts at the eye, so
 * the stackless traversal (rc_bvh.glsl) then meets near geometry first and culls more
 * of the far side. Shadow rays start elsewhere; the order never changes a result. */
static void flatten(const builder *b, uint32_t id, const float eye[3], uint32_t prim_base, packed_bvh_node *out,
                    uint32_t *next) {
  const build_node *bn = &b->nodes[id];
  uint32_t at = (*next)++;
  out[at].lo = (vec3){bn->bounds.lo[0], bn->bounds.lo[1], bn->bounds.lo[2]};
  out[at].hi = (vec3){bn->bounds.hi[0], bn->bounds.hi[1], bn->bounds.hi[2]};
  if (bn->count) {
    RC_ASSERT(bn->count <= RC_BVH_LEAF_MAX);
    out[at].leaf = (prim_base + bn->first) << RC_BVH_LEAF_SHIFT | bn->count;
  } else {
    uint32_t near = bn->left, far = bn->right;
    if (box_distance2(&b->nodes[far].bounds, eye) < box_distance2(&b->nodes[near].bounds, eye)) {
      near = bn->right;
      far = bn->left;
    }
    out[at].leaf = 0;
    flatten(b, near, eye, prim_base, out, next);
    flatten(b, far, eye, prim_base, out, next);
  }
  out[at].skip = *next;
}

/* The box of a transformed sphere (an ellipsoid): with M = packed_from_object, the
 * inverse of the f32 object_from_packed the shaders use (inverted here in f64), the box is
 * M(c) +- r |row_i(M)|, widened by a relative 1e-6 for the f32 rounding of the result. */
static box ellipsoid_box(const packed_sphere *s, const packed_transform *t) {
  const vec4 r[3] = {t->row0, t->row1, t->row2};
  double a[3][3] = {{r[0].x, r[0].y, r[0].z}, {r[1].x, r[1].y, r[1].z}, {r[2].x, r[2].y, r[2].z}};
  double m[3][3];
  if (!rcm_mat3_inverse_d(a, m)) m[0][0] = m[1][1] = m[2][2] = 1, m[0][1] = m[0][2] = m[1][0] = m[1][2] = m[2][0] = m[2][1] = 0;
  /* p_obj = A p + b  =>  p = M (p_obj - b) */
  double c[3] = {s->center.x - r[0].w, s->center.y - r[1].w, s->center.z - r[2].w};
  box out;
  for (int i = 0; i < 3; i++) {
    double mid = m[i][0] * c[0] + m[i][1] * c[1] + m[i][2] * c[2];
    double half = s->radius * sqrt(m[i][0] * m[i][0] + m[i][1] * m[i][1] + m[i][2] * m[i][2]);
    double pad = 1e-6 * (fabs(mid) + half);
    out.lo[i] = nextafterf((float)(mid - half - pad), -FLT_MAX);
    out.hi[i] = nextafterf((float)(mid + half + pad), FLT_MAX);
  }
  return out;
}

/* A box from double bounds, widened by a relative 1e-6 (the f32 rounding of the frame and
 * of the corners) and one f32 ulp outwards. */
static box padded_box(const double lo[3], const double hi[3]) {
  box out;
  for (int i = 0; i < 3; i++) {
    double pad = 1e-6 * (fabs(lo[i]) + fabs(hi[i]) + (hi[i] - lo[i]));
    out.lo[i] = nextafterf((float)(lo[i] - pad), -FLT_MAX);
    out.hi[i] = nextafterf((float)(hi[i] + pad), FLT_MAX);
  }
  return out;
}

/* A quadric's proxy: its clip box (in its own frame) carried to the packed space. */
static box quadric_box(const packed_quadric *q) {
  const dvec3 axis[3] = {rcm_to_d(q->axis_x), rcm_to_d(q->axis_y), rcm_to_d(q->axis_z)};
  dvec3 lo, hi;
  rc_frame_box_bounds(rcm_to_d(q->center), axis, rcm_to_d(q->lo), rcm_to_d(q->hi), &lo, &hi);
  return padded_box((const double[3]){lo.x, lo.y, lo.z}, (const double[3]){hi.x, hi.y, hi.z});
}

/* The geometry of object i as words, without its material; 0 words for a composite (not
 * compared). Two objects with the same words are the same surface. */
static uint32_t geometry_words(const rc_packed_scene *p, uint32_t i, uint32_t *w) {
  const packed_frame *f = &p->frame;
  uint32_t n = 0;
  if (i < f->sphere_count) {
    packed_sphere s = p->spheres[i];
    uint32_t t = s.transform;
    s.material = 0;
    s.transform = t == RC_NO_TRANSFORM ? t : 0; /* a transform is compared by value */
    memcpy(w, &s, sizeof s), n = sizeof s / 4;
    if (t != RC_NO_TRANSFORM) {
      memcpy(w + n, &p->transforms[t], sizeof(packed_transform));
      n += sizeof(packed_transform) / 4;
    }
  } else if ((i -= f->sphere_count) < f->triangle_count) {
    memcpy(w, &p->triangles[i].v0, sizeof(vec3));
    memcpy(w + 3, &p->triangles[i].v1, sizeof(vec3));
    memcpy(w + 6, &p->triangles[i].v2, sizeof(vec3));
    w[9] = p->triangles[i].flags; /* a one-sided copy is not a two-sided one's repeat */
    n = 10;
  } else if ((i -= f->triangle_count) < f->quadric_count) {
    packed_quadric q = p->quadrics[i];
    q.material = 0;
    memcpy(w, &q, sizeof q), n = sizeof q / 4;
  }
  return n;
}

#define GEOMETRY_WORDS_MAX ((sizeof(packed_sphere) + sizeof(packed_transform) + sizeof(packed_quadric)) / 4)

/* Whether object i's geometry words `a` equal those of an object already in the table
 * (open addressing over object indices); if not, i goes in. */
static bool seen_before(const rc_packed_scene *p, uint32_t *slot, size_t cap, uint32_t i, const uint32_t *a,
                        uint32_t words) {
  uint32_t b[GEOMETRY_WORDS_MAX];
  for (size_t at = (size_t)rc_hash_bytes(a, words * 4) & (cap - 1);; at = (at + 1) & (cap - 1)) {
    if (slot[at] == UINT32_MAX) {
      slot[at] = i;
      return false;
    }
    if (geometry_words(p, slot[at], b) == words && memcmp(a, b, words * 4) == 0) return true;
  }
}

/* A SIMD shader runs, for each object of a leaf, the test of every kind the tree's leaves
 * hold: llvmpipe skips no branch its lanes do not take (docs/performance.md, "What the
 * floor is"). A box beside three composites (scenes/csg.json) made every composite's leaf
 * run the bounded quadric's test too, 1,400 instructions with its clipped pieces and scan.
 * So where composites are the main kind (none of the other kinds has more objects), a few
 * bounded quadrics beside them leave the tree: at most RC_LOOSE_MAX, fewer than half the
 * composites (a leaf holds about two: more leaves to visit than loose objects to test).
 * Every ray tests them, before the tree, in a loop of their own, as it tests the planes
 * after it, where a hit can shorten the composites' walk: the CPU twin, which pays no
 * masks, gained too (csg.json: 0.93x its frame, the GPU path 0.81x). Nothing else leaves:
 * a loose object costs every ray its test, which the boxes spared the rays that miss it.
 * Leaving a box beside a mesh (dollhouse.json) cost the CPU twin 1.45x its frame for 0.97x
 * on the GPU path, and spheres beside a mesh or a composite cost the GPU path 1.17-1.20x
 * (docs/performance.md, "Loose objects"). */
uint32_t rc_loose_kinds(const packed_frame *f) {
  uint32_t bounded = f->quadric_count - f->plane_count; /* the planes are never in the tree */
  bool composites_lead = f->csg_count >= f->sphere_count && f->csg_count >= f->triangle_count && f->csg_count >= bounded;
  return composites_lead && bounded > 0 && bounded <= RC_LOOSE_MAX && f->csg_count > 2 * bounded ? RC_KIND_QUADRICS : 0;
}

uint32_t rc_loose_objects(const packed_frame *f) {
  return (f->loose_kinds & RC_KIND_QUADRICS) ? f->quadric_count - f->plane_count : 0;
}

/* Whether object i is one frame.loose_kinds keeps out of the tree. */
static bool is_loose(const packed_frame *f, uint32_t i) {
  uint32_t first_quadric = f->sphere_count + f->triangle_count;
  return (f->loose_kinds & RC_KIND_QUADRICS) && i >= first_quadric && i - first_quadric < f->quadric_count - f->plane_count;
}

/* Fills refs[] with every object whose geometry does not repeat an earlier object's bit
 * for bit, in order, and returns their count (in expected linear time). A repeat can never
 * be hit first: on equal t the lower object number wins (rc_intersect.glsl), and a shadow
 * ray is blocked by the first copy as surely as by the repeat. So the BVH leaves repeats
 * out, and a pile of coincident copies costs one test instead of exhausting the GPU's loop
 * budget. Brute force (--accel none) still tests them all, with the same result. */
static uint32_t distinct_objects(const rc_packed_scene *p, uint32_t n, uint32_t *refs) {
  size_t cap = 64;
  while (cap < 2 * (size_t)n) cap *= 2;
  uint32_t *slot = malloc(cap * sizeof *slot); /* without it: every object, only slower */
  if (slot) memset(slot, 0xff, cap * sizeof *slot);
  uint32_t a[GEOMETRY_WORDS_MAX], m = 0;
  const packed_frame *f = &p->frame;
  uint32_t planes_end = f->sphere_count + f->triangle_count + f->quadric_count, planes = planes_end - f->plane_count;
  for (uint32_t i = 0; i < n; i++) {
    if (i >= planes && i < planes_end) continue; /* unbounded: every ray tests the planes after the tree */
    if (is_loose(f, i)) continue;                /* every ray tests them too (rc_loose_kinds) */
    uint32_t words = slot ? geometry_words(p, i, a) : 0; /* 0: a composite, never compared */
    if (words && seen_before(p, slot, cap, i, a, words)) continue;
    refs[m++] = i;
  }
  free(slot);
  return m;
}

/* The bounds of triangle t. */
static box triangle_box(const packed_triangle *t) {
  box b = empty_box();
  const vec3 v[3] = {t->v0, t->v1, t->v2};
  for (int j = 0; j < 3; j++) grow_point(&b, (const float[3]){v[j].x, v[j].y, v[j].z});
  return b;
}

/* Object i's box (bvh.h): what its tree and the light buffers (light_buffer.c) bound it by. */
static box object_box(const rc_packed_scene *p, uint32_t i) {
  const packed_frame *f = &p->frame;
  box b = empty_box();
  if (i < f->sphere_count && p->spheres[i].transform != RC_NO_TRANSFORM) {
    b = ellipsoid_box(&p->spheres[i], &p->transforms[p->spheres[i].transform]);
  } else if (i < f->sphere_count) {
    const packed_sphere *s = &p->spheres[i];
    const float c[3] = {s->center.x, s->center.y, s->center.z};
    for (int k = 0; k < 3; k++) {
      /* One ulp outwards each way: c +- r is rounded. */
      b.lo[k] = nextafterf(c[k] - s->radius, -FLT_MAX);
      b.hi[k] = nextafterf(c[k] + s->radius, FLT_MAX);
    }
  } else if (i < f->sphere_count + f->triangle_count) {
    b = triangle_box(&p->triangles[i - f->sphere_count]);
  } else if (i < f->sphere_count + f->triangle_count + f->quadric_count) {
    b = quadric_box(&p->quadrics[i - f->sphere_count - f->triangle_count]);
  } else {
    const packed_csg *c = &p->csg[i - f->sphere_count - f->triangle_count - f->quadric_count];
    b = padded_box((const double[3]){c->lo.x, c->lo.y, c->lo.z}, (const double[3]){c->hi.x, c->hi.y, c->hi.z});
  }
  return b;
}

void rc_bvh_object_box(const rc_packed_scene *p, uint32_t object, float lo[3], float hi[3]) {
  box b = object_box(p, object);
  memcpy(lo, b.lo, sizeof b.lo);
  memcpy(hi, b.hi, sizeof b.hi);
}

/* The object tree's boxes: every object's, planes and repeats included (the tree leaves
 * them out through refs). */
static void object_boxes(const rc_packed_scene *p, prim_info *info) {
  for (uint32_t i = 0; i < p->frame.object_count; i++) {
    prim_info *q = &info[i];
    q->bounds = object_box(p, i);
    for (int k = 0; k < 3; k++) q->centroid[k] = 0.5f * (q->bounds.lo[k] + q->bounds.hi[k]);
  }
}

/* One tree over refs[0, m) (indices into info), appended to p's node and reference arrays;
 * the references written are base + ref. */
static rc_status append_tree(rc_packed_scene *p, prim_info *info, uint32_t *refs, uint32_t m, uint32_t base,
                             builder *b) {
  *b = (builder){.info = info, .refs = refs, .bins = malloc(sizeof(bin_scratch))};
  uint32_t root = b->bins ? build(b, 0, m, 0) : UINT32_MAX;
  free(b->bins);
  b->bins = NULL;
  if (root == UINT32_MAX) {
    free(b->nodes);
    return RC_ERR_OUT_OF_MEMORY;
  }
  uint32_t nodes = p->bvh_node_total + b->node_count, prims = p->bvh_prim_total + m;
  packed_bvh_node *n = realloc(p->bvh_nodes, (size_t)nodes * sizeof *n);
  if (n) p->bvh_nodes = n;
  uint32_t *r = realloc(p->bvh_prims, (size_t)(prims + 3) / 4 * 4 * sizeof *r);
  if (r) p->bvh_prims = r;
  if (!n || !r) {
    free(b->nodes);
    return RC_ERR_OUT_OF_MEMORY;
  }
  for (uint32_t i = 0; i < m; i++) p->bvh_prims[p->bvh_prim_total + i] = base + refs[i];
  for (uint32_t i = prims; i < (prims + 3) / 4 * 4; i++) p->bvh_prims[i] = 0;
  const packed_camera *cam = &p->frame.camera;
  const float eye[3] = {cam->eye.x, cam->eye.y, cam->eye.z};
  uint32_t next = p->bvh_node_total;
  flatten(b, root, eye, p->bvh_prim_total, p->bvh_nodes, &next);
  RC_ASSERT(next == nodes);
  p->bvh_node_total = nodes;
  p->bvh_prim_total = prims;
  free(b->nodes);
  return RC_OK;
}

/* The object tree (the first frame.bvh_node_count nodes). */
static rc_status build_objects(rc_packed_scene *p, rc_bvh_stats *stats) {
  packed_frame *f = &p->frame;
  uint32_t n = f->object_count;
  if (n >= (UINT32_MAX >> RC_BVH_LEAF_SHIFT)) {
    rc_refuse_scene("scene too large for the BVH: %u objects, at most %u", n, (UINT32_MAX >> RC_BVH_LEAF_SHIFT) - 1);
    return RC_ERR_TOO_LARGE;
  }
  prim_info *info = rc_alloc(n, sizeof *info, "BVH build");
  uint32_t *refs = rc_alloc(n, sizeof *refs, "BVH build");
  rc_status st = info && refs ? RC_OK : RC_ERR_OUT_OF_MEMORY;
  uint32_t m = 0;
  if (st == RC_OK) {
    f->loose_kinds = rc_loose_kinds(f);
    stats->loose = rc_loose_objects(f);
    m = distinct_objects(p, n, refs); /* objects in the tree */
    stats->repeats = n - f->plane_count - stats->loose - m;
    object_boxes(p, info);
  }
  builder b;
  if (st == RC_OK && m) st = append_tree(p, info, refs, m, 0, &b);
  if (st == RC_OK && m) {
    f->bvh_node_count = b.node_count;
    stats->nodes = b.node_count;
    stats->leaves = b.leaves;
    stats->depth = b.depth;
    stats->max_leaf = b.max_leaf;
  }
  free(info);
  free(refs);
  return st;
}

/* Each mesh operand's own tree over its triangles, after the object tree. A ray through a
 * composite may visit every node and test every triangle of its mesh operands, and insert
 * each crossing into a sorted list: the composites' step bound grows by that. */
static rc_status build_operands(rc_packed_scene *p) {
  uint64_t steps = 0;
  for (uint32_t k = 0; k < p->mesh_operand_count; k++) {
    const rc_mesh_operand *op = &p->mesh_operands[k];
    prim_info *info = rc_alloc(op->count, sizeof *info, "mesh operand BVH");
    uint32_t *refs = rc_alloc(op->count, sizeof *refs, "mesh operand BVH");
    rc_status st = info && refs ? RC_OK : RC_ERR_OUT_OF_MEMORY;
    for (uint32_t i = 0; st == RC_OK && i < op->count; i++) {
      info[i].bounds = triangle_box(&p->triangles[op->first + i]);
      for (int a = 0; a < 3; a++) info[i].centroid[a] = 0.5f * (info[i].bounds.lo[a] + info[i].bounds.hi[a]);
      refs[i] = i;
    }
    packed_quadric *q = &p->quadrics[op->leaf];
    q->mesh_root = p->bvh_node_total;
    builder b;
    if (st == RC_OK) st = append_tree(p, info, refs, op->count, op->first, &b);
    q->mesh_end = p->bvh_node_total;
    free(info);
    free(refs);
    if (st != RC_OK) return st;
    steps += (uint64_t)(q->mesh_end - q->mesh_root) + op->count + (uint64_t)q->mesh_crossings * q->mesh_crossings;
  }
  steps += p->frame.csg_max_steps;
  p->frame.csg_max_steps = steps > UINT32_MAX ? UINT32_MAX : (uint32_t)steps;
  return RC_OK;
}

rc_status rc_bvh_build(rc_packed_scene *p, bool objects, rc_bvh_stats *stats) {
  memset(stats, 0, sizeof *stats);
  double t0 = rc_now_ms();
  p->frame.bvh_node_count = 0;
  p->frame.loose_kinds = 0;
  p->bvh = objects;
  rc_status st = objects && p->frame.object_count ? build_objects(p, stats) : RC_OK;
  if (st == RC_OK) st = build_operands(p);
  stats->build_ms = rc_now_ms() - t0;
  return st;
}
