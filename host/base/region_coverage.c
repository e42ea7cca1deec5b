/* region_coverage.c: whether n rectangles tile a frame, in O(n log n) whatever sizes the
 * rectangles and the frame declare (merge reads them from files: a part's header must not
 * be able to make the check spin).
 *
 * A sweep down the rows: the parts' top and bottom edges are the events, and between two
 * events the set of parts that meet a row does not change. The parts that meet the current
 * rows (the active ones) are kept ordered by their first column in a two-level bitset over
 * the distinct first columns (coordinate compression: n bits, whatever the width), so that
 * a new part is checked against its two neighbours only: the active parts never overlap,
 * since the sweep stops at the first overlap. A row set is covered when the active parts'
 * widths add up to the frame's. */
#include <stdlib.h>

#include "base/region.h"

typedef struct {
  uint32_t y;
  uint32_t insert; /* 0: the part's rows end here; 1: they begin (ends first at one y) */
  size_t part;
} edge;

/* The active parts by first column: bit c of `bits` when the part owner[c] starting at
 * column xs[c] is active; bit w of `summary` when bits[w] has any bit set. */
typedef struct {
  uint64_t *bits, *summary;
  size_t words, summary_words;
  size_t *owner;
} start_set;

static int edge_order(const void *a, const void *b) {
  const edge *x = a, *y = b;
  if (x->y != y->y) return x->y < y->y ? -1 : 1;
  if (x->insert != y->insert) return x->insert < y->insert ? -1 : 1;
  return x->part < y->part ? -1 : x->part > y->part;
}

static int column_order(const void *a, const void *b) {
  uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
  return x < y ? -1 : x > y;
}

/* The index of the first of xs[0..n) not below x (n if none). */
static size_t lower_bound(const uint32_t *xs, size_t n, uint32_t x) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (xs[mid] < x) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

static void set_put(start_set *s, size_t c, bool on) {
  uint64_t m = 1ull << (c & 63);
  if (on) s->bits[c >> 6] |= m;
  else s->bits[c >> 6] &= ~m;
  uint64_t w = 1ull << ((c >> 6) & 63);
  if (s->bits[c >> 6]) s->summary[c >> 12] |= w;
  else s->summary[c >> 12] &= ~w;
}

static bool set_has(const start_set *s, size_t c) { return (s->bits[c >> 6] >> (c & 63)) & 1; }

/* The first active index >= c, or SIZE_MAX. */
static size_t set_next(const start_set *s, size_t c) {
  size_t w = c >> 6;
  if (w >= s->words) return SIZE_MAX;
  uint64_t here = s->bits[w] & (~0ull << (c & 63));
  if (here) return (w << 6) + (size_t)__builtin_ctzll(here);
  for (size_t sw = (w + 1) >> 6; sw < s->summary_words; sw++) {
    uint64_t m = s->summary[sw];
    if (sw == (w + 1) >> 6) m &= (w + 1) & 63 ? ~0ull << ((w + 1) & 63) : ~0ull;
    if (m) {
      size_t word = (sw << 6) + (size_t)__builtin_ctzll(m);
      return (word << 6) + (size_t)__builtin_ctzll(s->bits[word]);
    }
  }
  return SIZE_MAX;
}

/* The last active index < c, or SIZE_MAX. */
static size_t set_prev(const start_set *s, size_t c) {
  if (c == 0) return SIZE_MAX;
  c--;
  size_t w = c >> 6;
  uint64_t here = s->bits[w] & ((c & 63) == 63 ? ~0ull : (2ull << (c & 63)) - 1);
  if (here) return (w << 6) + 63 - (size_t)__builtin_clzll(here);
  for (size_t sw = (w >> 6) + 1; sw-- > 0;) {
    uint64_t m = s->summary[sw];
    if (sw == w >> 6) m &= (w & 63) ? (1ull << (w & 63)) - 1 : 0;
    if (m) {
      size_t word = (sw << 6) + 63 - (size_t)__builtin_clzll(m);
      return (word << 6) + 63 - (size_t)__builtin_clzll(s->bits[word]);
    }
  }
  return SIZE_MAX;
}

typedef struct {
  const rc_region *parts;
  size_t n;
  edge *edges;       /* 2n, sorted */
  uint32_t *xs;      /* the distinct first columns, sorted */
  size_t columns;
  size_t *column_of; /* part -> its index in xs */
  start_set set;
} sweep;

/* Activates or retires the part of edge e; on activation, the active part it overlaps
 * (its left or right neighbour, or one with the same first column), else SIZE_MAX. */
static size_t apply(sweep *s, const edge *e, uint64_t *covered) {
  const rc_region *p = &s->parts[e->part];
  size_t c = s->column_of[e->part];
  if (!e->insert) {
    set_put(&s->set, c, false);
    *covered -= p->x1 - p->x0;
    return SIZE_MAX;
  }
  if (set_has(&s->set, c)) return s->set.owner[c];
  size_t next = set_next(&s->set, c + 1);
  if (next != SIZE_MAX && s->xs[next] < p->x1) return s->set.owner[next];
  size_t prev = set_prev(&s->set, c);
  if (prev != SIZE_MAX && s->parts[s->set.owner[prev]].x1 > p->x0) return s->set.owner[prev];
  set_put(&s->set, c, true);
  s->set.owner[c] = e->part;
  *covered += p->x1 - p->x0;
  return SIZE_MAX;
}

/* The first uncovered columns of the active rows: [*x0, *x1). */
static void first_gap(const sweep *s, uint32_t width, uint32_t *x0, uint32_t *x1) {
  uint32_t x = 0;
  for (;;) {
    size_t c = lower_bound(s->xs, s->columns, x);
    if (x >= width || c == s->columns || s->xs[c] != x || !set_has(&s->set, c)) break;
    x = s->parts[s->set.owner[c]].x1;
  }
  size_t next = set_next(&s->set, lower_bound(s->xs, s->columns, x));
  *x0 = x;
  *x1 = next == SIZE_MAX ? width : s->xs[next];
}

/* Whether an active part meets columns [x0, x1): the last one starting before x1. */
static bool span_met(const sweep *s, uint32_t x0, uint32_t x1) {
  size_t prev = set_prev(&s->set, lower_bound(s->xs, s->columns, x1));
  return prev != SIZE_MAX && s->parts[s->set.owner[prev]].x1 > x0;
}

/* Overlaps are reported before gaps, wherever they are: the sweep runs to its end unless
 * it meets one. */
static int sweep_run(sweep *s, uint32_t width, uint32_t height, size_t *overlap_a, size_t *overlap_b,
                     rc_region *gap) {
  uint64_t covered = 0;
  bool open = false, found = false;
  size_t i = 0, m = 2 * s->n;
  /* Row 0 first, whether or not a part starts there; then each y where one starts or ends. */
  for (uint32_t y = 0;;) {
    for (; i < m && s->edges[i].y == y; i++) {
      size_t other = apply(s, &s->edges[i], &covered);
      if (other != SIZE_MAX) {
        size_t a = s->edges[i].part;
        *overlap_a = other < a ? other : a;
        *overlap_b = other < a ? a : other;
        return 1;
      }
    }
    if (open && span_met(s, gap->x0, gap->x1)) {
      gap->y1 = y;
      open = false;
    }
    if (!found && y < height && covered != width) {
      first_gap(s, width, &gap->x0, &gap->x1);
      gap->y0 = y;
      open = found = true;
    }
    if (i == m) break;
    y = s->edges[i].y;
  }
  if (open) gap->y1 = height;
  return found ? 2 : 0;
}

int rc_region_coverage(const rc_region *parts, size_t n, uint32_t width, uint32_t height, size_t *overlap_a,
                       size_t *overlap_b, rc_region *gap) {
  for (size_t i = 0; i < n; i++) {
    const rc_region *p = &parts[i];
    if (p->x0 >= p->x1 || p->y0 >= p->y1 || p->x1 > width || p->y1 > height) {
      *overlap_a = i;
      return 3;
    }
  }
  sweep s = {.parts = parts, .n = n};
  s.columns = n;
  s.set.words = (n + 63) / 64 + 1;
  s.set.summary_words = (s.set.words + 63) / 64;
  s.edges = malloc(2 * n * sizeof *s.edges + 1);
  s.xs = malloc(n * sizeof *s.xs + 1);
  s.column_of = malloc(n * sizeof *s.column_of + 1);
  s.set.owner = malloc(n * sizeof *s.set.owner + 1);
  s.set.bits = calloc(s.set.words, sizeof *s.set.bits);
  s.set.summary = calloc(s.set.summary_words, sizeof *s.set.summary);
  int verdict = 4;
  if (s.edges && s.xs && s.column_of && s.set.owner && s.set.bits && s.set.summary) {
    for (size_t i = 0; i < n; i++) {
      s.edges[2 * i] = (edge){parts[i].y0, 1, i};
      s.edges[2 * i + 1] = (edge){parts[i].y1, 0, i};
      s.xs[i] = parts[i].x0;
    }
    qsort(s.edges, 2 * n, sizeof *s.edges, edge_order);
    qsort(s.xs, n, sizeof *s.xs, column_order);
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
      if (k == 0 || s.xs[i] != s.xs[k - 1]) s.xs[k++] = s.xs[i];
    s.columns = k;
    for (size_t i = 0; i < n; i++) s.column_of[i] = lower_bound(s.xs, k, parts[i].x0);
    verdict = sweep_run(&s, width, height, overlap_a, overlap_b, gap);
  }
  free(s.edges);
  free(s.xs);
  free(s.column_of);
  free(s.set.owner);
  free(s.set.bits);
  free(s.set.summary);
  return verdict;
}
