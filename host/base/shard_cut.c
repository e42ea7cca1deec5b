/* shard_cut.c: the region of shard I of N (region.h), cut from the frame by the cost
 * estimate the way a k-d tree is built by median splits, the median taken in cost:
 * recursively, each rectangle split in two where the cost before the cut reaches n1/n of
 * its cost, for its n shards split n1 = n/2 and n2 = n - n1. A split runs between rows, so
 * that ordinary frames get full-width bands, unless that leaves a side more than
 * BAND_SLACK times its fair share and a split between columns does better: a row whose
 * cost outweighs a shard's share (a mesh's silhouette seen edge-on, a strip of mirrors)
 * is cut into tiles rather than holding one node while the others idle. */
#include "base/region.h"

#include <stdlib.h>

/* How far above its fair share a band may go before a cut between columns is tried. */
#define BAND_SLACK 1.25

/* The cost of one pixel of cell (i, j); 1 where there is no estimate. */
static double cell_cost(const rc_cost_grid *g, uint32_t x, uint32_t y) {
  if (!g) return 1;
  uint32_t i = y / g->cell_h, j = x / g->cell_w;
  if (i >= g->rows) i = g->rows - 1;
  if (j >= g->cols) j = g->cols - 1;
  return g->cost[(size_t)i * g->cols + j];
}

/* The cost of each row (rows: true) or column of r, into p[0 .. its length). Cells are
 * constant, so a line's cost is a sum over the cells it crosses, each times its overlap. */
static void profile(const rc_cost_grid *g, rc_region r, bool rows, double *p) {
  const uint32_t a0 = rows ? r.y0 : r.x0, a1 = rows ? r.y1 : r.x1; /* along the cut */
  const uint32_t b0 = rows ? r.x0 : r.y0, b1 = rows ? r.x1 : r.y1; /* across it */
  const uint32_t step = !g ? b1 - b0 : rows ? g->cell_w : g->cell_h;
  for (uint32_t a = a0; a < a1; a++) {
    double sum = 0;
    for (uint32_t b = b0; b < b1;) {
      uint32_t end = (b / step + 1) * step; /* the end of the cell that holds b */
      if (end > b1 || !g) end = b1;
      sum += (double)(end - b) * (rows ? cell_cost(g, b, a) : cell_cost(g, a, b));
      b = end;
    }
    p[a - a0] = sum;
  }
}

/* Where to cut lines [0, len) of costs p (total C) for shares n1 : n - n1: the first line
 * where the cost before it (a line counting half on either side of its middle) reaches
 * n1/n of C, kept within [lo, hi]. *worst: the larger side's cost per shard. */
static uint32_t cut_at(const double *p, uint32_t len, uint32_t n, uint32_t n1, uint32_t lo, uint32_t hi,
                       double *worst) {
  double total = 0;
  for (uint32_t i = 0; i < len; i++) total += p[i];
  bool equal = !(total > 0);
  double target = equal ? (double)len * n1 / n : total * n1 / n, sum = 0;
  uint32_t c = 0;
  for (; c < len; c++) {
    const double line = equal ? 1 : p[c];
    if (sum + line * 0.5 >= target) break;
    sum += line;
  }
  if (c < lo) c = lo;
  if (c > hi) c = hi;
  double before = 0;
  for (uint32_t i = 0; i < c; i++) before += p[i];
  double a = before / n1, b = (total - before) / (n - n1);
  *worst = a > b ? a : b;
  return c;
}

bool rc_shard_region(const rc_cost_grid *grid, uint32_t width, uint32_t height, uint32_t index, uint32_t count,
                     rc_region *out) {
  double *p = malloc(((size_t)width + height) * sizeof *p);
  if (!p) return false;
  rc_region r = {0, 0, width, height};
  /* Invariant: r has at least n rows (count <= height; a cut between rows leaves each
   * side as many rows as its shards, one between columns keeps the rows), so every shard
   * gets a pixel at least. */
  for (uint32_t n = count; n > 1;) {
    const uint32_t n1 = n / 2, h = rc_region_height(r), w = rc_region_width(r);
    double fair = 0, worst_rows, worst_cols = 0;
    profile(grid, r, true, p);
    for (uint32_t i = 0; i < h; i++) fair += p[i];
    fair /= n;
    uint32_t y = cut_at(p, h, n, n1, n1, h - (n - n1), &worst_rows);
    bool columns = false;
    uint32_t x = 0;
    if (w >= 2 && worst_rows > BAND_SLACK * fair) {
      profile(grid, r, false, p);
      x = cut_at(p, w, n, n1, 1, w - 1, &worst_cols);
      columns = worst_cols < worst_rows;
    }
    const bool first = index < n1;
    if (columns) {
      if (first) r.x1 = r.x0 + x;
      else r.x0 += x;
    } else {
      if (first) r.y1 = r.y0 + y;
      else r.y0 += y;
    }
    if (!first) index -= n1;
    n = first ? n1 : n - n1;
  }
  free(p);
  *out = r;
  return true;
}
