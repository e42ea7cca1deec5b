/* scene_cse167.c: the CSE167x / CS-184.1x ray-tracer scene format (`.test`), with the
 * semantics confirmed against the course's reference images (shared/peer/cse167/README.md):
 *  - materials (ambient, diffuse, specular, emission, shininess) are state captured when
 *    `sphere` or `tri` is issued; ambient is per object (so Ia = 1) and defaults to .2;
 *  - transforms right-multiply the current matrix (OpenGL order); `tri` applies it to its
 *    vertices at `tri` time; `sphere` keeps it (an ellipsoid through the inverse);
 *  - `directional x y z` gives the direction towards the light; `attenuation c0 c1 c2`
 *    (default 1 0 0) applies to point lights;
 *  - Blinn-Phong, mirror reflection weighted by the specular colour, `maxdepth` n = the
 *    primary ray plus n - 1 bounces, black background, 8-bit output by truncation.
 * Errors: FILE:LINE:COL: error: COMMAND: what is wrong (value), as for JSON scenes. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "math/rcm_mat3.h"
#include "scene/json_locate.h"
#include "scene/name_table.h"
#include "scene/scene.h"

#define MAX_ARGS 10
#define MAX_STACK 64

typedef struct {
  const char *file;
  int line;
  const char *line_start;
  const char *cmd;
  const char *tok[MAX_ARGS + 1];
  int ntok;
} ctx;

static rc_status fail(const ctx *c, int arg, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static rc_status fail(const ctx *c, int arg, const char *fmt, ...) {
  char what[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  const char *at = arg < c->ntok ? c->tok[arg] : c->tok[0];
  int col = (int)(at - c->line_start) + 1;
  if (arg > 0 && arg < c->ntok)
    fprintf(stderr, "%s:%d:%d: error: %s: %s (%.*s)\n", c->file, c->line, col, c->cmd, what,
            (int)strcspn(at, " \t\r\n"), at);
  else
    fprintf(stderr, "%s:%d:%d: error: %s: %s\n", c->file, c->line, col, c->cmd, what);
  return RC_ERR_INPUT;
}

static rc_status number(const ctx *c, int arg, double *out) {
  char *end = NULL;
  errno = 0;
  double v = strtod(c->tok[arg], &end);
  size_t len = strcspn(c->tok[arg], " \t\r\n");
  if (end != c->tok[arg] + len || len == 0) return fail(c, arg, "expected a number");
  if (!isfinite(v) || errno == ERANGE) return fail(c, arg, "number is not finite");
  *out = v;
  return RC_OK;
}

static rc_status numbers(const ctx *c, int first, int count, double *out) {
  for (int i = 0; i < count; i++) {
    rc_status st = number(c, first + i, &out[i]);
    if (st != RC_OK) return st;
  }
  return RC_OK;
}

static rc_status whole(const ctx *c, int arg, long lo, long hi, long *out) {
  double v = 0;
  rc_status st = number(c, arg, &v);
  if (st != RC_OK) return st;
  if (v != floor(v) || v < lo || v > hi) return fail(c, arg, "expected a whole number in [%ld, %ld]", lo, hi);
  *out = (long)v;
  return RC_OK;
}

typedef double mat4[4][4];

static void mat_identity(mat4 m) {
  memset(m, 0, sizeof(mat4));
  for (int i = 0; i < 4; i++) m[i][i] = 1;
}

/* m = m * r (right-multiplication, as OpenGL's glMultMatrix). */
static void mat_right_multiply(mat4 m, const mat4 r) {
  mat4 out;
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) out[i][j] = m[i][0] * r[0][j] + m[i][1] * r[1][j] + m[i][2] * r[2][j] + m[i][3] * r[3][j];
  memcpy(m, out, sizeof(mat4));
}

static dvec3 mat_point(const mat4 m, dvec3 p) {
  return rcm_make_d(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                    m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                    m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]);
}

static dvec3 mat_vector(const mat4 m, dvec3 v) {
  return rcm_make_d(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                    m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
}

static bool mat_is_identity(const mat4 m) {
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      if (m[i][j] != (i == j ? 1.0 : 0.0)) return false;
  return true;
}

static void mat_rotation(mat4 r, dvec3 axis, double deg) {
  double m[3][3];
  rcm_mat3_rotation_d(axis, deg, m);
  mat_identity(r);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) r[i][j] = m[i][j];
}

typedef struct {
  dvec3 ambient, diffuse, specular, emission;
  double shininess; /* +0.0 for -0.0: equal states must have equal bytes */
} material_state;
_Static_assert(sizeof(material_state) == 13 * sizeof(double), "material states are hashed as bytes: no padding");

/* Materials are deduplicated: objects with equal state share one. `seen` maps a state's
 * bytes to its material, so that a file of n objects parses in O(n). */
static rc_status material_index(rc_scene *s, size_t *cap, rc_name_table *seen, const material_state *m,
                                uint32_t *out) {
  bool present;
  if (!rc_name_table_insert(seen, m, sizeof *m, (uint32_t)s->material_count, out, &present))
    return RC_ERR_OUT_OF_MEMORY;
  if (present) return RC_OK;
  if (s->material_count == *cap) {
    size_t n = *cap ? 2 * *cap : 16;
    rc_material_def *p = realloc(s->materials, n * sizeof *p);
    if (!p) return RC_ERR_OUT_OF_MEMORY;
    s->materials = p;
    *cap = n;
  }
  rc_material_def *d = &s->materials[s->material_count];
  char name[32];
  snprintf(name, sizeof name, "m%zu", s->material_count);
  *d = (rc_material_def){strdup(name), m->ambient, m->diffuse, m->specular, m->specular, m->emission, m->shininess};
  *out = (uint32_t)s->material_count++;
  return RC_OK;
}

#define GROW(array, count, cap) RC_GROW(array, count, cap, 64)

typedef struct {
  rc_scene *s;
  mat4 stack[MAX_STACK];
  int top;
  material_state mat;
  dvec3 attenuation;
  dvec3 *verts;
  size_t nverts, verts_cap;
  size_t mat_cap, light_cap, sphere_cap;
  rc_name_table seen_materials;
  bool have_size, have_camera;
  int normal_warnings;
} state;

/* The commands, one handler each. A handler gets its arguments c->tok[1..] already
 * counted, and parsed as numbers into v where its entry says so. */
typedef rc_status (*command_fn)(state *g, ctx *c, const double *v);

static rc_status cmd_size(state *g, ctx *c, const double *v) {
  (void)v;
  long w = 0, h = 0;
  RC_TRY(whole(c, 1, 1, RC_MAX_IMAGE_SIDE, &w));
  RC_TRY(whole(c, 2, 1, RC_MAX_IMAGE_SIDE, &h));
  g->s->width = (uint32_t)w, g->s->height = (uint32_t)h, g->have_size = true;
  return RC_OK;
}

static rc_status cmd_maxdepth(state *g, ctx *c, const double *v) {
  (void)v;
  long d = 0;
  RC_TRY(whole(c, 1, 1, RC_MAX_REFLECTION_DEPTH + 1, &d));
  g->s->reflection_depth = (uint32_t)d - 1;
  return RC_OK;
}

/* Honoured when the command line names no -o. A bare file name written in the current
 * folder, as the course's programs did: an untrusted scene must not name /etc/... */
static rc_status cmd_output(state *g, ctx *c, const double *v) {
  (void)v;
  rc_scene *s = g->s;
  const char *name = c->tok[1];
  size_t len = strcspn(name, " \t\r\n");
  if (len >= sizeof s->output_name || strchr(name, '/') || name[0] == '.' || name[0] == '-')
    return fail(c, 1, "an output file name without a folder, not starting with '.' or '-', at most %zu bytes "
                      "(-o on the command line can name any path)", sizeof s->output_name - 1);
  for (size_t i = 0; i < len; i++)
    if ((unsigned char)name[i] < 0x20 || name[i] == 0x7f) return fail(c, 1, "a control character in the file name");
  memcpy(s->output_name, name, len);
  s->output_name[len] = '\0';
  return RC_OK;
}

static rc_status cmd_camera(state *g, ctx *c, const double *v) {
  rc_scene *s = g->s;
  s->camera = (rc_camera_def){RC_PROJECTION_PERSPECTIVE, rcm_make_d(v[0], v[1], v[2]), rcm_make_d(v[3], v[4], v[5]),
                              rcm_make_d(v[6], v[7], v[8]), v[9], 0};
  const char *field = NULL, *problem = rc_scene_camera_problem(&s->camera, &field);
  if (problem) {
    int arg = !strcmp(field, "look_at") ? 4 : !strcmp(field, "up") ? 7 : 10;
    return fail(c, arg, "%s %s", field, problem);
  }
  g->have_camera = true;
  return RC_OK;
}

static rc_status cmd_sphere(state *g, ctx *c, const double *v) {
  rc_scene *s = g->s;
  if (!(v[3] > 0)) return fail(c, 4, "radius must be greater than 0");
  GROW(s->spheres, s->sphere_count, g->sphere_cap);
  rc_sphere_def *d = &s->spheres[s->sphere_count];
  memset(d, 0, sizeof *d);
  d->center = rcm_make_d(v[0], v[1], v[2]);
  d->radius = v[3];
  const double(*m)[4] = g->stack[g->top];
  if (!mat_is_identity(m)) {
    d->transformed = true;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 4; j++) d->world_from_object.m[i][j] = m[i][j];
  }
  RC_TRY(material_index(s, &g->mat_cap, &g->seen_materials, &g->mat, &d->material));
  s->sphere_count++;
  return RC_OK;
}

/* maxverts, maxvertnorms: only a size hint. */
static rc_status cmd_hint(state *g, ctx *c, const double *v) {
  (void)g, (void)c, (void)v;
  return RC_OK;
}

static rc_status cmd_vertex(state *g, ctx *c, const double *v) {
  (void)c;
  GROW(g->verts, g->nverts, g->verts_cap);
  g->verts[g->nverts++] = rcm_make_d(v[0], v[1], v[2]);
  return RC_OK;
}

static rc_status cmd_vertexnormal(state *g, ctx *c, const double *v) {
  RC_TRY(cmd_vertex(g, c, v));
  if (!g->normal_warnings++)
    rc_warning("%s:%d: vertexnormal: per-vertex normals are not used (triangles are flat shaded)", c->file, c->line);
  return RC_OK;
}

/* tri, trinormal (whose indices name vertexnormal vertices: the same list here). */
static rc_status cmd_tri(state *g, ctx *c, const double *v) {
  (void)v;
  long idx[3];
  for (int k = 0; k < 3; k++) {
    RC_TRY(whole(c, 1 + k, 0, 0x7fffffff, &idx[k]));
    if ((size_t)idx[k] >= g->nverts)
      return fail(c, 1 + k, "vertex index out of range (%zu vertices defined so far)", g->nverts);
  }
  rc_triangle_def t = {0};
  for (int k = 0; k < 3; k++) t.v[k] = mat_point(g->stack[g->top], g->verts[idx[k]]);
  RC_TRY(material_index(g->s, &g->mat_cap, &g->seen_materials, &g->mat, &t.material));
  return rc_scene_add_triangle(g->s, &t);
}

static rc_status cmd_translate(state *g, ctx *c, const double *v) {
  (void)c;
  mat4 r;
  mat_identity(r);
  r[0][3] = v[0], r[1][3] = v[1], r[2][3] = v[2];
  mat_right_multiply(g->stack[g->top], r);
  return RC_OK;
}

static rc_status cmd_scale(state *g, ctx *c, const double *v) {
  if (v[0] == 0 || v[1] == 0 || v[2] == 0) return fail(c, 1, "a zero scale makes objects vanish");
  mat4 r;
  mat_identity(r);
  r[0][0] = v[0], r[1][1] = v[1], r[2][2] = v[2];
  mat_right_multiply(g->stack[g->top], r);
  return RC_OK;
}

static rc_status cmd_rotate(state *g, ctx *c, const double *v) {
  dvec3 axis = rcm_make_d(v[0], v[1], v[2]);
  if (rcm_max_abs_comp_d(axis) == 0) return fail(c, 1, "the rotation axis must not be zero");
  mat4 r;
  mat_rotation(r, rcm_normalize_d(axis), v[3]);
  mat_right_multiply(g->stack[g->top], r);
  return RC_OK;
}

static rc_status cmd_push(state *g, ctx *c, const double *v) {
  (void)v;
  if (g->top + 1 >= MAX_STACK) return fail(c, 0, "more than %d nested pushTransform", MAX_STACK - 1);
  memcpy(g->stack[g->top + 1], g->stack[g->top], sizeof(mat4));
  g->top++;
  return RC_OK;
}

static rc_status cmd_pop(state *g, ctx *c, const double *v) {
  (void)v;
  if (g->top == 0) return fail(c, 0, "popTransform without a matching pushTransform");
  g->top--;
  return RC_OK;
}

/* directional, point: x y z r g b. */
static rc_status cmd_light(state *g, ctx *c, const double *v) {
  rc_scene *s = g->s;
  for (int k = 3; k < 6; k++)
    if (v[k] < 0) return fail(c, 1 + k, "light colour must not be negative");
  GROW(s->lights, s->light_count, g->light_cap);
  rc_light_def *l = &s->lights[s->light_count];
  memset(l, 0, sizeof *l);
  l->intensity = rcm_make_d(v[3], v[4], v[5]);
  if (c->cmd[0] == 'd') {
    dvec3 toward = mat_vector(g->stack[g->top], rcm_make_d(v[0], v[1], v[2]));
    if (rcm_max_abs_comp_d(toward) == 0) return fail(c, 1, "direction must not be zero");
    l->type = RC_LIGHT_DIRECTIONAL;
    l->direction = rcm_neg_d(toward); /* ours: the direction the light travels in */
  } else {
    l->type = RC_LIGHT_POINT;
    l->position = mat_point(g->stack[g->top], rcm_make_d(v[0], v[1], v[2]));
    l->attenuation = g->attenuation;
  }
  s->light_count++;
  return RC_OK;
}

static rc_status cmd_attenuation(state *g, ctx *c, const double *v) {
  if (v[0] < 0 || v[1] < 0 || v[2] < 0 || (v[0] == 0 && v[1] == 0 && v[2] == 0))
    return fail(c, 1, "coefficients must be non-negative and not all zero");
  g->attenuation = rcm_make_d(v[0], v[1], v[2]);
  return RC_OK;
}

/* ambient, diffuse, specular, emission: the material state's colours. */
static rc_status cmd_colour(state *g, ctx *c, const double *v) {
  for (int k = 0; k < 3; k++)
    if (v[k] < 0) return fail(c, 1 + k, "must not be negative");
  dvec3 col = rcm_make_d(v[0], v[1], v[2]);
  char k = c->cmd[0];
  *(k == 'a' ? &g->mat.ambient : k == 'd' ? &g->mat.diffuse : k == 's' ? &g->mat.specular : &g->mat.emission) = col;
  return RC_OK;
}

static rc_status cmd_shininess(state *g, ctx *c, const double *v) {
  if (v[0] < 0) return fail(c, 1, "must not be negative");
  g->mat.shininess = v[0] + 0.0;
  return RC_OK;
}

/* Every command: its name, its argument count, whether those are all numbers (parsed
 * into v before the handler runs), and its handler. The names also feed did-you-mean. */
static const struct {
  const char *name;
  int args;
  bool numbers;
  command_fn run;
} commands[] = {
    {"size", 2, false, cmd_size},           {"maxdepth", 1, false, cmd_maxdepth},
    {"output", 1, false, cmd_output},       {"camera", 10, true, cmd_camera},
    {"sphere", 4, true, cmd_sphere},        {"maxverts", 1, false, cmd_hint},
    {"maxvertnorms", 1, false, cmd_hint},   {"vertex", 3, true, cmd_vertex},
    {"vertexnormal", 6, true, cmd_vertexnormal}, {"tri", 3, false, cmd_tri},
    {"trinormal", 3, false, cmd_tri},       {"translate", 3, true, cmd_translate},
    {"rotate", 4, true, cmd_rotate},        {"scale", 3, true, cmd_scale},
    {"pushTransform", 0, false, cmd_push},  {"popTransform", 0, false, cmd_pop},
    {"directional", 6, true, cmd_light},    {"point", 6, true, cmd_light},
    {"attenuation", 3, true, cmd_attenuation}, {"ambient", 3, true, cmd_colour},
    {"diffuse", 3, true, cmd_colour},       {"specular", 3, true, cmd_colour},
    {"emission", 3, true, cmd_colour},      {"shininess", 1, true, cmd_shininess},
};
#define COMMAND_COUNT (sizeof commands / sizeof *commands)

/* One command; the arguments are c->tok[1..ntok-1]. */
static rc_status command(state *g, ctx *c) {
  for (size_t i = 0; i < COMMAND_COUNT; i++) {
    if (strcmp(c->cmd, commands[i].name) != 0) continue;
    if (c->ntok - 1 != commands[i].args) return fail(c, 0, "expected %d arguments, got %d", commands[i].args, c->ntok - 1);
    double v[MAX_ARGS];
    if (commands[i].numbers) RC_TRY(numbers(c, 1, commands[i].args, v));
    return commands[i].run(g, c, v);
  }
  const char *known[COMMAND_COUNT];
  for (size_t i = 0; i < COMMAND_COUNT; i++) known[i] = commands[i].name;
  const char *near = rc_nearest(c->cmd, known, COMMAND_COUNT);
  if (near) return fail(c, 0, "unknown command (did you mean %s?)", near);
  return fail(c, 0, "unknown command");
}

/* The commands that add to the scene, as static strings for rc_origin. */
static const char *origin_name(const char *cmd) {
  static const char *const names[] = {"sphere", "tri", "trinormal", "point", "directional", NULL};
  int i = rc_name_index(names, cmd);
  return i >= 0 ? names[i] : "command";
}

rc_status rc_scene_parse_cse167(const char *path, const char *text, size_t len, rc_scene *s) {
  memset(s, 0, sizeof *s);
  s->path = strdup(path);
  s->samples_per_pixel = 1;
  s->reflection_depth = 4; /* maxdepth 5 */
  s->ambient_light = rcm_make_d(1, 1, 1);
  s->specular_model = RC_SPECULAR_BLINN_PHONG;
  s->truncate_8bit = true;
  s->quality = rc_quality_default();
  if (rc_scene_check_text(path, text, len) != RC_OK) return RC_ERR_INPUT;
  state g = {.s = s};
  mat_identity(g.stack[0]);
  g.mat.ambient = rcm_make_d(0.2, 0.2, 0.2);
  g.attenuation = rcm_make_d(1, 0, 0);
  rc_status st = RC_OK;
  const char *p = text, *end = text + len;
  ctx c = {.file = path};
  while (p < end && st == RC_OK) {
    const char *eol = memchr(p, '\n', (size_t)(end - p));
    if (!eol) eol = end;
    c.line++;
    c.line_start = p;
    c.ntok = 0;
    const char *q = p;
    bool too_many = false;
    while (q < eol) {
      while (q < eol && (*q == ' ' || *q == '\t' || *q == '\r')) q++;
      if (q >= eol || *q == '#') break;
      if (c.ntok > MAX_ARGS) {
        too_many = true;
        break;
      }
      c.tok[c.ntok++] = q;
      while (q < eol && *q != ' ' && *q != '\t' && *q != '\r') q++;
    }
    if (c.ntok > 0) {
      char name[32];
      snprintf(name, sizeof name, "%.*s", (int)strcspn(c.tok[0], " \t\r\n"), c.tok[0]);
      c.cmd = name;
      size_t before[RC_ORIGIN_KINDS];
      rc_scene_counts(s, before);
      st = too_many ? fail(&c, 0, "too many arguments") : command(&g, &c);
      if (st == RC_OK) st = rc_scene_note_origin(s, before, c.line, (int)(c.tok[0] - p) + 1, origin_name(name), UINT32_MAX);
    }
    p = eol + 1;
  }
  if (st == RC_OK && (!g.have_size || !g.have_camera)) {
    fprintf(stderr, "%s:%d:1: error: scene has no %s command\n", path, c.line, !g.have_size ? "size" : "camera");
    st = RC_ERR_INPUT;
  }
  free(g.verts);
  rc_name_table_free(&g.seen_materials);
  return st;
}
