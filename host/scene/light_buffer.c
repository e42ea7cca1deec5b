#include "scene/light_buffer.h"

#include "scene/bvh.h"
#include "scene/name_table.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RES RC_LIGHT_BUFFER_RES
#define CELLS (6u * RES * RES)
#define NONE UINT32_MAX
/* The eye buffer's tiles: 8 x 8 pixels (one workgroup), larger where the image would have
 * more than EYE_CELLS_MAX of them. */
#define EYE_TILE_SHIFT 3u
#define EYE_CELLS_MAX (1u << 18)
/* A box's projection onto the image widens by this many pixels: the f32 ray through a
 * raster point leaves the exact one by ~1e-6 radians, 1e-3 pixels on a 1,000-pixel image. */
#define EYE_MARGIN_PX 0.5

/* The reach (rc_shared.h): this many times the farthest corner of the object tree's box
 * from the light. A shadow ray from farther away (from a plane beyond the objects) walks
 * the whole tree: the pad below grows with the reach. */
#define REACH_FACTOR 4.0
/* Every object's box grows by (reach + |light|) 2^-18 before it is projected: the shadow
 * ray's line passes the light within a few f32 ulps of those lengths (docs/numerics.md §9). */
#define PAD_SCALE 0x1p-18
/* Face coordinates s = x / z widen by this, for the shader's f32 division and the choice
 * of face where two components tie. */
#define MARGIN 1e-5

/* A cell while the objects are projected: how many fall in it, the first
 * RC_LIGHT_BUFFER_LIST of them, and the smallest subtree of the object tree holding them all. */
typedef struct {
  uint32_t count, subtree;
  uint32_t ids[RC_LIGHT_BUFFER_LIST];
} cell_acc;

/* The object tree, read once for every light. */
typedef struct {
  const packed_bvh_node *nodes;
  uint32_t node_count;
  uint32_t *parent;          /* per node; NONE for the root */
  uint32_t count;            /* objects in the tree (repeats and planes are not) */
  uint32_t *object, *leaf;   /* per tree object: its number and its leaf */
  float (*lo)[3], (*hi)[3];  /* per tree object: its box (rc_bvh_object_box) */
} tree;

/* What is appended after the tree's nodes and references. */
typedef struct {
  packed_bvh_node *nodes;
  uint32_t node_count, node_cap;
  uint32_t *words;           /* the table, the cells, then the leaves' object lists */
  uint32_t word_count, word_cap;
  uint32_t node_base, word_base; /* absolute positions of nodes[0] and words[0] */
  uint32_t *slots;           /* open addressing over the made leaves, keyed by their lists */
  uint32_t slot_mask;
} appendix;

static void tree_free(tree *t) {
  free(t->parent);
  free(t->object);
  free(t->leaf);
  free(t->lo);
  free(t->hi);
}

static rc_status tree_read(const rc_packed_scene *p, tree *t) {
  const uint32_t n = p->frame.bvh_node_count;
  *t = (tree){.nodes = p->bvh_nodes, .node_count = n};
  t->parent = rc_alloc(n, sizeof *t->parent, "light buffers");
  if (!t->parent) return RC_ERR_OUT_OF_MEMORY;
  uint32_t objects = 0;
  for (uint32_t i = 0; i < n; i++) {
    t->parent[i] = NONE;
    objects += p->bvh_nodes[i].leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u);
  }
  /* Depth-first: an inner node's children are the next node and the node after its subtree. */
  for (uint32_t i = 0; i < n; i++)
    if (p->bvh_nodes[i].leaf == 0 && i + 1 < n) {
      t->parent[i + 1] = i;
      if (p->bvh_nodes[i + 1].skip < n) t->parent[p->bvh_nodes[i + 1].skip] = i;
    }
  t->object = rc_alloc(objects, sizeof *t->object, "light buffers");
  t->leaf = rc_alloc(objects, sizeof *t->leaf, "light buffers");
  t->lo = rc_alloc(objects, sizeof *t->lo, "light buffers");
  t->hi = rc_alloc(objects, sizeof *t->hi, "light buffers");
  if (!t->object || !t->leaf || !t->lo || !t->hi) return RC_ERR_OUT_OF_MEMORY;
  for (uint32_t i = 0; i < n; i++) {
    uint32_t leaf = p->bvh_nodes[i].leaf, first = leaf >> RC_BVH_LEAF_SHIFT;
    for (uint32_t k = 0; k < (leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u)); k++) {
      t->object[t->count] = p->bvh_prims[first + k];
      t->leaf[t->count] = i;
      rc_bvh_object_box(p, t->object[t->count], t->lo[t->count], t->hi[t->count]);
      t->count++;
    }
  }
  return RC_OK;
}

static void add(const tree *t, cell_acc *c, uint32_t object, uint32_t leaf) {
  if (c->count < RC_LIGHT_BUFFER_LIST) c->ids[c->count] = object;
  c->count++;
  if (c->subtree == NONE) {
    c->subtree = leaf;
    return;
  }
  /* Node a holds node b exactly when a <= b < a.skip (depth-first order). */
  while (!(c->subtree <= leaf && leaf < t->nodes[c->subtree].skip)) c->subtree = t->parent[c->subtree];
}

/* The cell column or row of face coordinate s in [-1, 1], clamped as the shader clamps. */
static int cell_of(double s) {
  double x = floor((s + 1) * 0.5 * RES);
  return x < 0 ? 0 : (x > RES - 1 ? (int)RES - 1 : (int)x);
}

/* Adds tree object k to every cell through which a shadow ray towards the light at L can
 * meet its box. A shadow ray's direction d points from the surface towards the light, so
 * the directions that meet the box are those of B = L - box (grown by pad). Face (axis a,
 * sign) holds the directions whose largest component is the signed a-th; its coordinates
 * are (s, t) = (d_b, d_c) / |d_a|, and over B, where |d_a| >= the box's Chebyshev
 * distance from the light, they lie between the extremes at B's corners. */
static void project(const tree *t, cell_acc *cells, const double L[3], double pad, uint32_t k) {
  double lo[3], hi[3], dist = 0;
  for (int i = 0; i < 3; i++) {
    lo[i] = L[i] - t->hi[k][i] - pad;
    hi[i] = L[i] - t->lo[k][i] + pad;
    double di = lo[i] > 0 ? lo[i] : (hi[i] < 0 ? -hi[i] : 0);
    if (di > dist) dist = di;
  }
  for (uint32_t face = 0; face < 6; face++) {
    int a = (int)face / 2, b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
    int i0 = 0, i1 = (int)RES - 1, j0 = 0, j1 = (int)RES - 1;
    if (dist > 0) { /* else the light is inside the box: every cell */
      double z_lo = face & 1 ? -hi[a] : lo[a], z_hi = face & 1 ? -lo[a] : hi[a];
      if (z_hi <= 0) continue;
      z_lo = fmax(z_lo, dist * (1 - MARGIN));
      double s_lo = fmin(lo[b] / z_lo, lo[b] / z_hi) - MARGIN, s_hi = fmax(hi[b] / z_lo, hi[b] / z_hi) + MARGIN;
      double t_lo = fmin(lo[c] / z_lo, lo[c] / z_hi) - MARGIN, t_hi = fmax(hi[c] / z_lo, hi[c] / z_hi) + MARGIN;
      if (s_hi < -1 || s_lo > 1 || t_hi < -1 || t_lo > 1) continue;
      i0 = cell_of(s_lo), i1 = cell_of(s_hi), j0 = cell_of(t_lo), j1 = cell_of(t_hi);
    }
    for (int j = j0; j <= j1; j++)
      for (int i = i0; i <= i1; i++) add(t, &cells[(face * RES + (uint32_t)j) * RES + (uint32_t)i], t->object[k], t->leaf[k]);
  }
}

static bool grow_words(appendix *x, uint32_t more) {
  if (x->word_count + more <= x->word_cap) return true;
  uint32_t cap = x->word_cap ? x->word_cap : 1024;
  while (cap < x->word_count + more) cap *= 2;
  uint32_t *w = realloc(x->words, (size_t)cap * sizeof *w);
  if (!w) return false;
  x->words = w, x->word_cap = cap;
  return true;
}

/* The node of a leaf made for cell c's objects, shared by every cell with the same list. */
static uint32_t leaf_for(const tree *t, appendix *x, const cell_acc *c, const uint32_t *index_of) {
  size_t bytes = c->count * sizeof *c->ids;
  /* The probe ends at the list's leaf, or at the free slot where its new leaf goes. */
  uint32_t at = (uint32_t)rc_hash_bytes(c->ids, bytes) & x->slot_mask;
  for (;; at = (at + 1) & x->slot_mask) {
    uint32_t node = x->slots[at];
    if (node == NONE) break;
    const packed_bvh_node *n = &x->nodes[node];
    uint32_t first = (n->leaf >> RC_BVH_LEAF_SHIFT) - x->word_base;
    if ((n->leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u)) == c->count && !memcmp(&x->words[first], c->ids, bytes))
      return x->node_base + node;
  }
  if (x->node_count == x->node_cap) {
    uint32_t cap = x->node_cap ? 2 * x->node_cap : 256;
    packed_bvh_node *n = realloc(x->nodes, cap * sizeof *n);
    if (!n) return NONE;
    x->nodes = n, x->node_cap = cap;
  }
  if (!grow_words(x, c->count)) return NONE;
  packed_bvh_node *n = &x->nodes[x->node_count];
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (uint32_t i = 0; i < c->count; i++) {
    uint32_t k = index_of[c->ids[i]];
    for (int a = 0; a < 3; a++) lo[a] = fminf(lo[a], t->lo[k][a]), hi[a] = fmaxf(hi[a], t->hi[k][a]);
  }
  n->lo = (vec3){lo[0], lo[1], lo[2]};
  n->hi = (vec3){hi[0], hi[1], hi[2]};
  n->skip = x->node_base + x->node_count + 1;
  n->leaf = ((x->word_base + x->word_count) << RC_BVH_LEAF_SHIFT) | c->count;
  memcpy(&x->words[x->word_count], c->ids, bytes);
  x->word_count += c->count;
  x->slots[at] = x->node_count;
  return x->node_base + x->node_count++;
}

/* Writes the node range of each of the n cells in acc at x->words[cells...] and counts
 * what they name. */
static rc_status emit_cells(const tree *t, appendix *x, const cell_acc *acc, uint32_t n, uint32_t cells,
                            const uint32_t *index_of, uint64_t *empty, uint64_t *lists, uint64_t *subtrees) {
  for (uint32_t c = 0; c < n; c++) {
    uint32_t first = 0, end = 0; /* an empty range: nothing to meet */
    if (acc[c].count > RC_LIGHT_BUFFER_LIST) {
      first = acc[c].subtree, end = t->nodes[first].skip;
      ++*subtrees;
    } else if (acc[c].count > 0) {
      first = leaf_for(t, x, &acc[c], index_of);
      if (first == NONE) return RC_ERR_OUT_OF_MEMORY;
      end = first + 1;
      ++*lists;
    } else {
      ++*empty;
    }
    x->words[cells + 2 * c] = first;
    x->words[cells + 2 * c + 1] = end;
  }
  return RC_OK;
}

/* The reach of a buffer around L, and the pad of every box projected from L (above). */
static float reach_from(const tree *t, const double L[3], double *pad) {
  const packed_bvh_node *root = &t->nodes[0];
  double far2 = 0;
  for (int corner = 0; corner < 8; corner++) {
    double q[3] = {corner & 1 ? root->hi.x : root->lo.x, corner & 2 ? root->hi.y : root->lo.y,
                   corner & 4 ? root->hi.z : root->lo.z};
    double d2 = (q[0] - L[0]) * (q[0] - L[0]) + (q[1] - L[1]) * (q[1] - L[1]) + (q[2] - L[2]) * (q[2] - L[2]);
    if (d2 > far2) far2 = d2;
  }
  const float reach = (float)(REACH_FACTOR * sqrt(far2));
  *pad = ((double)reach + sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2])) * PAD_SCALE;
  return reach;
}

/* Light `light`'s buffer: its cells' node ranges from `cells` on in x->words. */
static rc_status build_light(const tree *t, appendix *x, const packed_light *light, const uint32_t *index_of,
                             cell_acc *acc, uint32_t cells, float *reach_out, rc_light_buffer_stats *st) {
  const double L[3] = {light->position.x, light->position.y, light->position.z};
  double pad;
  *reach_out = reach_from(t, L, &pad);
  for (uint32_t c = 0; c < CELLS; c++) acc[c] = (cell_acc){.count = 0, .subtree = NONE};
  for (uint32_t k = 0; k < t->count; k++) project(t, acc, L, pad, k);
  st->cells += CELLS;
  return emit_cells(t, x, acc, CELLS, cells, index_of, &st->empty, &st->lists, &st->subtrees);
}

/* The eye buffer's layout: tiles of 2^shift pixels, columns x rows of them. */
typedef struct {
  uint32_t shift, columns, rows;
} eye_layout;

static eye_layout eye_layout_for(const packed_camera *c) {
  eye_layout g = {.shift = EYE_TILE_SHIFT};
  for (;; g.shift++) {
    g.columns = (uint32_t)(((uint64_t)c->width + (1u << g.shift) - 1) >> g.shift);
    g.rows = (uint32_t)(((uint64_t)c->height + (1u << g.shift) - 1) >> g.shift);
    if ((uint64_t)g.columns * g.rows <= EYE_CELLS_MAX) return g;
  }
}

/* Adds tree object k to every tile of the image whose pixels' primary rays can meet its
 * box. A point q (relative to the eye, in the camera's basis u, v, w) lies on the ray
 * through window point (us, vs) when (us, vs) = focal (q.u, q.v) / (-q.w) for a perspective
 * camera, (q.u, q.v) for a parallel one (rc_camera.glsl); the window maps onto raster
 * coordinates linearly, and a box in front of the eye projects inside its corners' hull. A
 * box that reaches the eye's plane covers the whole image. */
static void project_eye(const tree *t, cell_acc *cells, const packed_camera *c, uint32_t shift, uint32_t columns,
                        double pad, uint32_t k) {
  const double E[3] = {c->eye.x, c->eye.y, c->eye.z};
  const double U[3] = {c->u.x, c->u.y, c->u.z}, V[3] = {c->v.x, c->v.y, c->v.z}, W[3] = {c->w.x, c->w.y, c->w.z};
  const bool perspective = c->projection == RC_PROJECTION_PERSPECTIVE;
  const double width = c->width, height = c->height;
  const double sx = width / ((double)c->right - c->left), sy = height / ((double)c->top - c->bottom);
  /* (q.u, q.v, -q.w) at the box's low corner, and what each axis's extent adds: the
   * corners' values are sums (a million-triangle mesh projects in tens of ms). */
  double a0 = 0, b0 = 0, z0 = 0, da[3], db[3], dz[3];
  for (int i = 0; i < 3; i++) {
    double lo = t->lo[k][i] - pad - E[i], extent = (double)t->hi[k][i] - t->lo[k][i] + 2 * pad;
    a0 += lo * U[i], b0 += lo * V[i], z0 -= lo * W[i];
    da[i] = extent * U[i], db[i] = extent * V[i], dz[i] = -extent * W[i];
  }
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  bool whole = false;
  int behind = 0; /* corners at or behind the eye's plane */
  for (int corner = 0; corner < 8; corner++) {
    double a = a0, b = b0, depth = z0;
    for (int i = 0; i < 3; i++)
      if ((corner >> i) & 1) a += da[i], b += db[i], depth += dz[i];
    if (perspective) {
      if (!(depth > 0)) {
        whole = true;
        behind += depth <= 0;
        continue;
      }
      const double scale = c->focal / depth;
      a *= scale, b *= scale;
    }
    const double x = (a - c->left) * sx, y = (b - c->bottom) * sy;
    if (isnan(x) || isnan(y)) {
      whole = true;
      break;
    }
    x0 = x < x0 ? x : x0, x1 = x > x1 ? x : x1, y0 = y < y0 ? y : y0, y1 = y > y1 ? y : y1;
  }
  /* A box wholly behind the eye's plane meets no primary ray: every point of a primary ray
   * at t > 0 is in front of it (its direction's depth is focal over its length). */
  if (behind == 8) return;
  /* Raster x of pixel column i is in [i, i + 1); raster y of pixel row j (from the top) is
   * in [height - 1 - j, height - j) (rc_trace.glsl: trace_sample). */
  double i0 = 0, i1 = width - 1, j0 = 0, j1 = height - 1;
  if (!whole) {
    i0 = fmax(floor(x0 - EYE_MARGIN_PX), 0), i1 = fmin(floor(x1 + EYE_MARGIN_PX), width - 1);
    j0 = fmax(height - 1 - floor(y1 + EYE_MARGIN_PX), 0), j1 = fmin(height - 1 - floor(y0 - EYE_MARGIN_PX), height - 1);
    if (!(i0 <= i1 && j0 <= j1)) return; /* off the image (or NaN) */
  }
  for (uint32_t j = (uint32_t)j0 >> shift; j <= (uint32_t)j1 >> shift; j++)
    for (uint32_t i = (uint32_t)i0 >> shift; i <= (uint32_t)i1 >> shift; i++)
      add(t, &cells[j * columns + i], t->object[k], t->leaf[k]);
}

/* The eye buffer: its tiles' node ranges from `cells` on in x->words. */
static rc_status build_eye(const tree *t, appendix *x, const packed_camera *c, eye_layout g, const uint32_t *index_of,
                           cell_acc *acc, uint32_t cells, rc_light_buffer_stats *st) {
  const double E[3] = {c->eye.x, c->eye.y, c->eye.z};
  double pad;
  reach_from(t, E, &pad);
  const uint32_t n = g.columns * g.rows;
  for (uint32_t i = 0; i < n; i++) acc[i] = (cell_acc){.count = 0, .subtree = NONE};
  for (uint32_t k = 0; k < t->count; k++) project_eye(t, acc, c, g.shift, g.columns, pad, k);
  st->eye_tile = 1u << g.shift;
  st->eye_cells = n;
  return emit_cells(t, x, acc, n, cells, index_of, &st->eye_empty, &st->eye_lists, &st->eye_subtrees);
}

/* Where borrowed (a prepared scene's file), the tree's arrays become the scene's own copies. */
static rc_status own_tree(rc_packed_scene *p) {
  if (!p->borrowed || p->bvh_copied) return RC_OK;
  packed_bvh_node *n = rc_alloc(p->bvh_node_total, sizeof *n, "light buffers");
  uint32_t words = (p->bvh_prim_total + 3) / 4 * 4;
  uint32_t *r = rc_alloc(words, sizeof *r, "light buffers");
  if (!n || !r) {
    free(n);
    free(r);
    return RC_ERR_OUT_OF_MEMORY;
  }
  memcpy(n, p->bvh_nodes, p->bvh_node_total * sizeof *n);
  memcpy(r, p->bvh_prims, words * sizeof *r);
  p->bvh_nodes = n, p->bvh_prims = r, p->bvh_copied = true;
  return RC_OK;
}

/* Appends x after the tree's arrays. */
static rc_status append(rc_packed_scene *p, const appendix *x) {
  RC_TRY(own_tree(p));
  uint32_t nodes = p->bvh_node_total + x->node_count, words = x->word_base + x->word_count;
  packed_bvh_node *n = realloc(p->bvh_nodes, (size_t)nodes * sizeof *n);
  if (n) p->bvh_nodes = n;
  uint32_t *r = realloc(p->bvh_prims, (size_t)(words + 3) / 4 * 4 * sizeof *r);
  if (r) p->bvh_prims = r;
  if (!n || !r) return RC_ERR_OUT_OF_MEMORY;
  if (x->node_count) memcpy(p->bvh_nodes + p->bvh_node_total, x->nodes, x->node_count * sizeof *n); /* NULL if none */
  for (uint32_t i = p->bvh_prim_total; i < x->word_base; i++) p->bvh_prims[i] = 0;
  memcpy(p->bvh_prims + x->word_base, x->words, x->word_count * sizeof *r);
  for (uint32_t i = words; i < (words + 3) / 4 * 4; i++) p->bvh_prims[i] = 0;
  p->bvh_node_total = nodes;
  p->bvh_prim_total = words;
  return RC_OK;
}

rc_status rc_light_buffers_build(rc_packed_scene *p, bool lights_on, bool eye_on, rc_light_buffer_stats *st) {
  memset(st, 0, sizeof *st);
  packed_frame *f = &p->frame;
  f->light_buffers = 0;
  uint32_t lights = 0;
  for (uint32_t i = 0; lights_on && f->shadows && i < f->light_count && lights < RC_LIGHT_BUFFERS_MAX; i++)
    lights += p->lights[i].type == RC_LIGHT_POINT;
  const eye_layout eye = eye_on ? eye_layout_for(&f->camera) : (eye_layout){0};
  const uint32_t eye_cells = eye.columns * eye.rows;
  if (!p->bvh || f->bvh_node_count == 0 || lights + eye_cells == 0) return RC_OK;
  double t0 = rc_now_ms();
  /* The table (a pair per light, then the eye's), then each buffered light's cells, the
   * eye's tiles, then the made leaves' lists; the leaves' references (first <<
   * RC_BVH_LEAF_SHIFT) must stay below 2^32. */
  appendix x = {.node_base = p->bvh_node_total, .word_base = (p->bvh_prim_total + 3) / 4 * 4};
  const uint32_t table_words = (2 * (f->light_count + 1) + 3) / 4 * 4;
  const uint64_t all_cells = (uint64_t)lights * CELLS + eye_cells;
  const uint64_t reserved = table_words + 2 * all_cells;
  if (x.word_base + reserved + all_cells * RC_LIGHT_BUFFER_LIST >= (1ull << (32 - RC_BVH_LEAF_SHIFT)))
    return RC_OK; /* too many references already: the tree alone, as before */
  tree t;
  rc_status s = tree_read(p, &t);
  uint32_t *index_of = s == RC_OK ? rc_alloc(f->object_count, sizeof *index_of, "light buffers") : NULL;
  const uint32_t most = CELLS > eye_cells ? CELLS : eye_cells;
  cell_acc *acc = s == RC_OK ? rc_alloc(most, sizeof *acc, "light buffers") : NULL;
  /* At most one leaf a cell: the table is never more than half full. */
  uint32_t slots = 1;
  while (slots < 2 * all_cells) slots *= 2;
  x.slot_mask = slots - 1;
  x.slots = s == RC_OK ? rc_alloc(slots, sizeof *x.slots, "light buffers") : NULL;
  if (s == RC_OK && (!index_of || !acc || !x.slots || !grow_words(&x, (uint32_t)reserved))) s = RC_ERR_OUT_OF_MEMORY;
  if (s == RC_OK) {
    memset(x.slots, 0xff, (size_t)slots * sizeof *x.slots);
    for (uint32_t k = 0; k < t.count; k++) index_of[t.object[k]] = k;
    memset(x.words, 0, reserved * sizeof *x.words);
    x.word_count = (uint32_t)reserved;
    uint32_t cells = table_words;
    for (uint32_t i = 0; s == RC_OK && i < f->light_count; i++) {
      if (p->lights[i].type != RC_LIGHT_POINT || st->lights == lights) continue;
      float reach = 0;
      s = build_light(&t, &x, &p->lights[i], index_of, acc, cells, &reach, st);
      x.words[2 * i] = x.word_base + cells;
      memcpy(&x.words[2 * i + 1], &reach, sizeof reach);
      cells += 2 * CELLS;
      st->lights++;
    }
    if (s == RC_OK && eye_cells) {
      s = build_eye(&t, &x, &f->camera, eye, index_of, acc, cells, st);
      x.words[2 * f->light_count] = x.word_base + cells;
      x.words[2 * f->light_count + 1] = eye.shift | eye.columns << RC_EYE_BUFFER_COLUMNS_SHIFT;
    }
  }
  if (s == RC_OK) s = append(p, &x);
  if (s == RC_OK) f->light_buffers = x.word_base;
  st->bytes = (uint64_t)x.node_count * sizeof(packed_bvh_node) + (uint64_t)x.word_count * sizeof(uint32_t);
  free(x.nodes);
  free(x.words);
  free(x.slots);
  free(acc);
  free(index_of);
  tree_free(&t);
  st->build_ms = rc_now_ms() - t0;
  return s;
}
