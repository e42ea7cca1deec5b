/* scene_patch.c: Bezier patches (scene_patch.h). The shader intersects a piece by Newton's
 * method from the piece's centre (rc_patch.glsl); the cutting here is what makes that start
 * good: a piece whose net is nearly its bilinear corner surface has a Jacobian that
 * changes little across it, so Newton converges from the centre for the rays that hit it
 * (Martin et al., JGT 5(1), 2000, who flatten the subdivision hierarchy the same way). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_patch.h"

bool js_is_patch_type(const char *type) { return !strcmp(type, "bezier_patch") || !strcmp(type, "bezier_patches"); }

static dvec3 mid(dvec3 a, dvec3 b) { return rcm_scale_d(rcm_add_d(a, b), 0.5); }

/* de Casteljau at t = 1/2 on the four points p[k * stride], k = 0..3: the halves' nets. */
static void halve(const dvec3 *p, size_t stride, dvec3 *a, dvec3 *b) {
  dvec3 p0 = p[0], p1 = p[stride], p2 = p[2 * stride], p3 = p[3 * stride];
  dvec3 q0 = mid(p0, p1), q1 = mid(p1, p2), q2 = mid(p2, p3), r0 = mid(q0, q1), r1 = mid(q1, q2), s = mid(r0, r1);
  a[0] = p0, a[stride] = q0, a[2 * stride] = r0, a[3 * stride] = s;
  b[0] = s, b[stride] = r1, b[2 * stride] = q2, b[3 * stride] = p3;
}

static void net_box(const dvec3 n[16], dvec3 *lo, dvec3 *hi) {
  *lo = *hi = n[0];
  for (int i = 1; i < 16; i++) {
    lo->x = fmin(lo->x, n[i].x), lo->y = fmin(lo->y, n[i].y), lo->z = fmin(lo->z, n[i].z);
    hi->x = fmax(hi->x, n[i].x), hi->y = fmax(hi->y, n[i].y), hi->z = fmax(hi->z, n[i].z);
  }
}

/* How far the net strays from the bilinear surface through its corners, over its box's
 * diagonal: 0 for a bilinear patch (degree-elevated, its net is exactly that surface). */
static double flatness(const dvec3 n[16]) {
  dvec3 lo, hi;
  net_box(n, &lo, &hi);
  double diagonal = rcm_length_d(rcm_sub_d(hi, lo)), worst = 0;
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) {
      double u = c / 3.0, v = r / 3.0;
      dvec3 bottom = rcm_add_d(rcm_scale_d(n[0], 1 - u), rcm_scale_d(n[3], u));
      dvec3 top = rcm_add_d(rcm_scale_d(n[12], 1 - u), rcm_scale_d(n[15], u));
      dvec3 b = rcm_add_d(rcm_scale_d(bottom, 1 - v), rcm_scale_d(top, v));
      worst = fmax(worst, rcm_length_d(rcm_sub_d(n[4 * r + c], b)));
    }
  return diagonal > 0 ? worst / diagonal : 0;
}

typedef struct {
  rc_scene *s;
  uint32_t patch, material, piece0;
  const char *where;
} cutter;

/* The piece [u0, u1] x [v0, v1] with net n: cut in four, or added as a quadric. */
static rc_status cut(cutter *k, const dvec3 n[16], double u0, double u1, double v0, double v1, int depth) {
  if (depth < RC_PATCH_MAX_DEPTH && flatness(n) > RC_PATCH_FLATNESS) {
    dvec3 left[16], right[16], quarter[4][16];
    for (int r = 0; r < 4; r++) halve(n + 4 * r, 1, left + 4 * r, right + 4 * r);
    for (int c = 0; c < 4; c++) {
      halve(left + c, 4, quarter[0] + c, quarter[2] + c);
      halve(right + c, 4, quarter[1] + c, quarter[3] + c);
    }
    double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
    RC_TRY(cut(k, quarter[0], u0, um, v0, vm, depth + 1));
    RC_TRY(cut(k, quarter[1], um, u1, v0, vm, depth + 1));
    RC_TRY(cut(k, quarter[2], u0, um, vm, v1, depth + 1));
    return cut(k, quarter[3], um, u1, vm, v1, depth + 1);
  }
  rc_scene *s = k->s;
  if (s->quadric_count >= RC_MAX_PATCH_PIECES) {
    fprintf(stderr, "%s: the scene's patches need more than %u pieces\n", k->where, RC_MAX_PATCH_PIECES);
    return RC_ERR_INPUT;
  }
  RC_GROW(s->quadrics, s->quadric_count, s->quadric_capacity, 64);
  dvec3 lo, hi;
  net_box(n, &lo, &hi);
  /* The box grows by the Newton margin of its extent (rc_shared.h), so that a hit the
   * margin admits on an edge is inside it, plus a little for the f32 rounding of the box. */
  dvec3 grow = rcm_scale_d(rcm_sub_d(hi, lo), RC_PATCH_DOMAIN_MARGIN);
  double tiny = 0x1p-20 * rcm_max_abs_comp_d(rcm_make_d(fmax(fabs(lo.x), fabs(hi.x)), fmax(fabs(lo.y), fabs(hi.y)),
                                                        fmax(fabs(lo.z), fabs(hi.z))));
  grow = rcm_add_d(grow, rcm_make_d(tiny, tiny, tiny));
  dvec3 center = mid(lo, hi);
  rc_quadric_def *q = &s->quadrics[s->quadric_count++];
  *q = (rc_quadric_def){.center = center,
                        .axis = {rcm_make_d(1, 0, 0), rcm_make_d(0, 1, 0), rcm_make_d(0, 0, 1)},
                        .lo = rcm_sub_d(rcm_sub_d(lo, center), grow),
                        .hi = rcm_add_d(rcm_sub_d(hi, center), grow),
                        .material = k->material,
                        .patch = k->patch,
                        .patch_piece0 = k->piece0,
                        .domain = {u0, u1, v0, v1}};
  return RC_OK;
}

rc_status rc_scene_add_patch(rc_scene *s, const dvec3 p[16], uint32_t material, const char *where) {
  dvec3 lo, hi;
  net_box(p, &lo, &hi);
  if (rcm_eq_d(lo, hi)) {
    fprintf(stderr, "%s: all 16 control points are one point: the patch has no surface\n", where);
    return RC_ERR_INPUT;
  }
  RC_GROW(s->patches, s->patch_count, s->patch_capacity, 8);
  rc_patch_def *d = &s->patches[s->patch_count++];
  memcpy(d->p, p, sizeof d->p);
  d->material = material;
  cutter k = {s, (uint32_t)s->patch_count, material, (uint32_t)s->quadric_count, where};
  return cut(&k, p, 0, 1, 0, 1, 0);
}

/* A row of n + 1 points (stride apart) raised to degree 3, in place (room for 4): each
 * raise keeps the curve (Farin, "Curves and Surfaces for CAGD", §6.1). */
static void elevate(dvec3 *row, size_t stride, int n) {
  for (; n < 3; n++) {
    dvec3 next[4];
    next[0] = row[0], next[n + 1] = row[n * stride];
    for (int i = 1; i <= n; i++) {
      double a = (double)i / (n + 1);
      next[i] = rcm_add_d(rcm_scale_d(row[(i - 1) * stride], a), rcm_scale_d(row[i * stride], 1 - a));
    }
    for (int i = 0; i <= n + 1; i++) row[i * stride] = next[i];
  }
}

/* The patch file's words, with their lines. */
typedef struct {
  const char *path, *text, *at;
  int line, word_line; /* where the reader is, and the line of the last word read */
} reader;

static bool next_word(reader *r, const char **word, size_t *len) {
  for (;;) {
    while (*r->at == ' ' || *r->at == '\t' || *r->at == '\r' || *r->at == '\n') r->line += *r->at++ == '\n';
    if (*r->at != '#') break;
    while (*r->at && *r->at != '\n') r->at++; /* a comment to the line's end */
  }
  if (!*r->at) return false;
  *word = r->at;
  r->word_line = r->line;
  while (*r->at && *r->at != ' ' && *r->at != '\t' && *r->at != '\r' && *r->at != '\n') r->at++;
  *len = (size_t)(r->at - *word);
  return true;
}

static rc_status file_fail(const reader *r, const char *where, const char *what, size_t patch) {
  if (patch) fprintf(stderr, "%s:%d: error: patch %zu: %s\n", r->path, r->line, patch, what);
  else fprintf(stderr, "%s:%d: error: %s\n", r->path, r->line, what);
  fprintf(stderr, "%s: in this patch file\n", where);
  return RC_ERR_INPUT;
}

static rc_status read_number(reader *r, const char *where, size_t patch, const char *what, double *out) {
  const char *w;
  size_t len;
  char msg[160], buf[64];
  if (!next_word(r, &w, &len)) {
    snprintf(msg, sizeof msg, "the file ends where %s should be", what);
    r->line = r->word_line; /* the file's last line with something on it */
    return file_fail(r, where, msg, patch);
  }
  snprintf(buf, sizeof buf, "%.*s", (int)(len < 63 ? len : 63), w);
  char *end;
  errno = 0;
  *out = strtod(buf, &end);
  if (len > 63 || *end || end == buf || !isfinite(*out) || errno == ERANGE) {
    snprintf(msg, sizeof msg, "%s: expected a finite number, got \"%s\"%s", what, buf, len > 63 ? "..." : "");
    return file_fail(r, where, msg, patch);
  }
  return RC_OK;
}

static rc_status read_patches(reader *r, const rc_affine *m, uint32_t material, rc_scene *s, const char *where) {
  double count;
  RC_TRY(read_number(r, where, 0, "the patch count", &count));
  if (count != floor(count) || count < 1 || count > RC_MAX_PATCHES) {
    char msg[160];
    snprintf(msg, sizeof msg, "the patch count: expected a whole number from 1 to %u, got %g", RC_MAX_PATCHES, count);
    return file_fail(r, where, msg, 0);
  }
  for (size_t k = 1; k <= (size_t)count; k++) {
    double du, dv;
    RC_TRY(read_number(r, where, k, "its degree in u", &du));
    RC_TRY(read_number(r, where, k, "its degree in v", &dv));
    if (du != floor(du) || dv != floor(dv) || du < 1 || du > 3 || dv < 1 || dv > 3) {
      char msg[160];
      snprintf(msg, sizeof msg, "degrees %g %g: each must be 1, 2 or 3 (lower ones are raised to bicubic)", du, dv);
      return file_fail(r, where, msg, k);
    }
    /* (dv + 1) rows of (du + 1) points: u runs along a row. */
    dvec3 net[16];
    int nu = (int)du, nv = (int)dv;
    for (int row = 0; row <= nv; row++)
      for (int col = 0; col <= nu; col++) {
        double x[3];
        char what[64];
        for (int a = 0; a < 3; a++) {
          snprintf(what, sizeof what, "control point %d's %c", row * (nu + 1) + col + 1, "xyz"[a]);
          RC_TRY(read_number(r, where, k, what, &x[a]));
        }
        net[4 * row + col] = rc_affine_point(m, rcm_make_d(x[0], x[1], x[2]));
      }
    for (int row = 0; row <= nv; row++) elevate(net + 4 * row, 1, nu);
    for (int col = 0; col < 4; col++) elevate(net + col, 4, nv);
    char at[4400];
    snprintf(at, sizeof at, "%s:%d: error: patch %zu", r->path, r->line, k);
    rc_status st = rc_scene_add_patch(s, net, material, at);
    if (st != RC_OK) {
      fprintf(stderr, "%s: in this patch file\n", where);
      return st;
    }
  }
  const char *w;
  size_t len;
  if (next_word(r, &w, &len)) {
    char msg[160];
    snprintf(msg, sizeof msg, "text after the %zu patches the file's count promises: \"%.*s\"", (size_t)count,
             (int)(len < 40 ? len : 40), w);
    return file_fail(r, where, msg, 0);
  }
  return RC_OK;
}

rc_status rc_patch_file_load(const char *path, const rc_affine *m, uint32_t material, rc_scene *s, const char *where) {
  size_t bytes = 0;
  const char *why = rc_input_problem(path, &bytes);
  if (why) {
    fprintf(stderr, "%s: cannot read patch file %s: %s\n", where, path, why);
    return RC_ERR_IO;
  }
  if (!rc_scene_note_input(s, path)) return RC_ERR_OUT_OF_MEMORY;
  FILE *f = fopen(path, "rb");
  char *text = f ? malloc(bytes + 1) : NULL;
  size_t got = text ? fread(text, 1, bytes, f) : 0;
  if (f) fclose(f);
  if (!text || got != bytes) {
    fprintf(stderr, "%s: cannot read patch file %s: %s\n", where, path, text ? "short read" : "out of memory");
    free(text);
    return text ? RC_ERR_IO : RC_ERR_OUT_OF_MEMORY;
  }
  text[bytes] = 0;
  if (memchr(text, 0, bytes)) {
    fprintf(stderr, "%s: patch file %s is not text (it holds a zero byte)\n", where, path);
    free(text);
    return RC_ERR_INPUT;
  }
  reader r = {path, text, text, 1, 1};
  rc_status st = read_patches(&r, m, material, s, where);
  free(text);
  return st;
}

rc_status js_parse_patch_object(jctx *c, const cJSON *o, rc_scene *s) {
  const cJSON *tv = cJSON_GetObjectItemCaseSensitive(o, "type");
  bool file = !strcmp(tv->valuestring, "bezier_patches");
  static const char *const one[] = {"type", "control_points", "material", "transform", NULL};
  static const char *const many[] = {"type", "file", "material", "transform", NULL};
  RC_TRY(js_check_members(c, o, file ? many : one));
  uint32_t material;
  RC_TRY(js_get_material_ref(c, o, &material));
  rc_affine m;
  bool transformed;
  RC_TRY(js_get_transform(c, o, &m, &transformed));
  const char *key = file ? "file" : "control_points";
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
  if (!v) return js_fail(c, "missing field \"%s\"", key);
  js_push_key(c, key);
  char where[4400], field[256];
  int line, col;
  js_line_col(c, js_offset_near(c), &line, &col);
  js_format_path(c, field, sizeof field);
  snprintf(where, sizeof where, "%s:%d:%d: error: %s", c->file, line, col, field);
  if (file) {
    char path[4096], folder[4096];
    RC_TRY(js_scene_file(c, v, "a patch file name", path, folder));
    js_pop(c);
    return rc_patch_file_load(path, &m, material, s, where);
  }
  if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 16)
    return js_fail(c, "expected 16 points [x, y, z]: a bicubic patch's net, 4 rows of 4 (u along a row)");
  dvec3 net[16];
  for (int k = 0; k < 16; k++) {
    js_push_index(c, (size_t)k);
    RC_TRY(js_vec3_value(c, cJSON_GetArrayItem(v, k), -HUGE_VAL, &net[k]));
    net[k] = rc_affine_point(&m, net[k]);
    js_pop(c);
  }
  js_pop(c);
  return rc_scene_add_patch(s, net, material, where);
}
