/* Prepared scenes (scene/prepared.h): a file decodes into the packed scene the parser and
 * the BVH build give, bit for bit; and a file whose checksum is right but whose contents
 * are not (an index past its array, a tree link backwards, a program that underflows its
 * stack, a section of the wrong size, a summary value out of range) is refused, naming
 * what is wrong, before any renderer reads it. The mutations rewrite the checksum, as a
 * forger (or the fuzzer, tests/fuzz/) would.
 * Usage: test_prepared SCENES_DIR */
#include <stdlib.h>
#include <string.h>
#include <xxhash.h>

#include "rc_test.h"
#include "scene/bvh.h"
#include "scene/patch_bounds.h"
#include "scene/prepared.h"

#include <float.h>
#include <math.h>

static const char *scenes_dir = ".";

/* The header's layout (prepared.c): magic, byte order, version, layout, size, checksum,
 * digest (48 bytes), then each section's offset, then each section's size. */
enum { SUMMARY, SPHERES, TRIANGLES, MATERIALS, LIGHTS, TRANSFORMS, NORMALS, QUADRICS, CSG, PROGRAM, OPERANDS,
       TEXELS, NODES, PRIMS, HASHES, SECTIONS };
static uint64_t *offset_of(unsigned char *f, int s) { return (uint64_t *)(f + 48 + 8 * s); }
static uint64_t *size_of(unsigned char *f, int s) { return (uint64_t *)(f + 48 + 8 * SECTIONS + 8 * s); }
static void reseal(unsigned char *f, size_t len) {
  uint64_t sum = XXH3_64bits(f + 40, len - 40);
  memcpy(f + 32, &sum, sizeof sum);
}

typedef struct {
  rc_scene scene;
  rc_packed_scene packed;
  unsigned char *file;
  size_t len;
} prepared_case;

static bool prepare(const char *name, prepared_case *c) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", scenes_dir, name);
  memset(c, 0, sizeof *c);
  if (rc_scene_load(path, NULL, &c->scene) != RC_OK) return false;
  /* The command reads the textures' images (cli/textures.c); here each is 2 x 2 texels. */
  for (size_t i = 0; i < c->scene.texture_count; i++) {
    rc_texture_def *t = &c->scene.textures[i];
    t->width = t->height = 2;
    t->image = (uint32_t)i;
    t->rgb = calloc(12, sizeof *t->rgb);
    for (int k = 0; t->rgb && k < 12; k++) t->rgb[k] = 0.25f * (float)(k % 4);
    if (!t->rgb) return false;
  }
  if (rc_scene_pack(&c->scene, &c->packed) != RC_OK) return false;
  rc_bvh_stats bvh;
  uint64_t digest = 0;
  if (rc_bvh_build(&c->packed, true, &bvh) != RC_OK ||
      rc_source_digest(path, c->scene.inputs, c->scene.input_count, &digest) != RC_OK)
    return false;
  void *bytes = NULL;
  if (rc_prepared_encode(&c->scene, &c->packed, &bvh, digest, &bytes, &c->len) != RC_OK) return false;
  c->file = bytes;
  return true;
}

static void release(prepared_case *c) {
  rc_scene_free(&c->scene);
  rc_packed_scene_free(&c->packed);
  free(c->file);
}

/* Decodes a copy of the file after `mutate` (resealed); the status. */
static rc_status decode_mutated(const prepared_case *c, void (*mutate)(unsigned char *f)) {
  unsigned char *f = malloc(c->len);
  memcpy(f, c->file, c->len);
  if (mutate) {
    mutate(f);
    reseal(f, c->len);
  }
  rc_prepared *pf = NULL;
  rc_scene s;
  rc_status st = rc_prepared_decode("mutated.vkrs", f, c->len, &pf, &s);
  if (st == RC_OK) rc_scene_free(&s);
  rc_prepared_close(pf);
  free(f);
  return st;
}

static void check_round_trip(const char *name) {
  prepared_case c;
  CHECK(prepare(name, &c));
  if (!c.file) return;
  rc_prepared *pf = NULL;
  rc_scene s;
  CHECK_EQ_INT(rc_prepared_decode("round-trip.vkrs", c.file, c.len, &pf, &s), RC_OK);
  if (pf) {
    rc_packed_scene p;
    CHECK_EQ_INT(rc_prepared_packed(pf, &s, &p), RC_OK);
    /* Frame, packed space and arrays (the hash), and the tree, as parsed and built. */
    CHECK(rc_packed_scene_hash(&p) == rc_packed_scene_hash(&c.packed));
    CHECK(memcmp(&p.frame, &c.packed.frame, sizeof p.frame) == 0);
    CHECK_EQ_INT(p.bvh_node_total, c.packed.bvh_node_total);
    CHECK(memcmp(p.bvh_nodes, c.packed.bvh_nodes, p.bvh_node_total * sizeof *p.bvh_nodes) == 0);
    CHECK(memcmp(p.bvh_prims, c.packed.bvh_prims, p.bvh_prim_total * sizeof *p.bvh_prims) == 0);
    CHECK(memcmp(p.quadrics, c.packed.quadrics, p.quadric_total * sizeof *p.quadrics) == 0);
    CHECK_EQ_INT(s.sphere_count, c.scene.sphere_count);
    CHECK_EQ_INT(s.origin_count, c.scene.origin_count);
    rc_packed_scene_free(&p);
    /* The copy, its tree built again, is the same scene too. */
    CHECK_EQ_INT(rc_prepared_packed_copy(pf, &s, &p), RC_OK);
    rc_bvh_stats bvh;
    CHECK_EQ_INT(rc_bvh_build(&p, true, &bvh), RC_OK);
    CHECK(memcmp(&p.frame, &c.packed.frame, sizeof p.frame) == 0);
    CHECK(memcmp(p.bvh_nodes, c.packed.bvh_nodes, p.bvh_node_total * sizeof *p.bvh_nodes) == 0);
    rc_packed_scene_free(&p);
    rc_scene_free(&s);
    rc_prepared_close(pf);
  }
  release(&c);
}

TEST(showcase_round_trips) { check_round_trip("showcase.json"); }
TEST(composites_with_mesh_operands_round_trip) { check_round_trip("csg_meshes.json"); }
TEST(smooth_mesh_round_trips) { check_round_trip("mesh.json"); }
TEST(textures_round_trip) { check_round_trip("earth.json"); }

static unsigned char *section(unsigned char *f, int s) { return f + *offset_of(f, s); }

static void sphere_material_past_end(unsigned char *f) { ((packed_sphere *)section(f, SPHERES))[0].material = 1000; }
static void sphere_transform_past_end(unsigned char *f) { ((packed_sphere *)section(f, SPHERES))[0].transform = 7; }
static void triangle_normals_past_end(unsigned char *f) { ((packed_triangle *)section(f, TRIANGLES))[0].normals = 1u << 20; }
static void triangle_flags_unknown(unsigned char *f) { ((packed_triangle *)section(f, TRIANGLES))[0].flags = 6; }
static void light_type_unknown(unsigned char *f) { ((packed_light *)section(f, LIGHTS))[0].type = 9; }
static void node_skips_backwards(unsigned char *f) { ((packed_bvh_node *)section(f, NODES))[1].skip = 1; }
static void root_skips_past_tree(unsigned char *f) { ((packed_bvh_node *)section(f, NODES))[0].skip = 1u << 30; }
static void leaf_past_references(unsigned char *f) {
  packed_bvh_node *n = (packed_bvh_node *)section(f, NODES);
  for (int i = 0;; i++)
    if (n[i].leaf) {
      n[i].leaf = (1000000u << RC_BVH_LEAF_SHIFT) | 1u;
      return;
    }
}
static void reference_past_objects(unsigned char *f) { ((uint32_t *)section(f, PRIMS))[0] = 999999; }
static void section_size_off(unsigned char *f) { *size_of(f, SPHERES) -= 32; }
static void section_overlaps(unsigned char *f) { *offset_of(f, TRIANGLES) = *offset_of(f, SPHERES); }
static void width_zero(unsigned char *f) {
  /* The summary: its tag, the scene's name (a length, the bytes, a NUL), then the width. */
  unsigned char *s = section(f, SUMMARY);
  uint64_t n;
  memcpy(&n, s + 4, sizeof n);
  memset(s + 12 + n + 1, 0, 4);
}

TEST(showcase_inconsistencies_are_refused) {
  prepared_case c;
  CHECK(prepare("showcase.json", &c));
  if (!c.file) return;
  CHECK_EQ_INT(decode_mutated(&c, NULL), RC_OK);
  void (*const mutations[])(unsigned char *) = {
      sphere_material_past_end, sphere_transform_past_end, triangle_flags_unknown, light_type_unknown,
      node_skips_backwards,     root_skips_past_tree,      leaf_past_references,   reference_past_objects,
      section_size_off,         section_overlaps,          width_zero};
  for (size_t i = 0; i < sizeof mutations / sizeof *mutations; i++) {
    rc_status st = decode_mutated(&c, mutations[i]);
    if (st != RC_ERR_INPUT) printf("  mutation %zu: status %d\n", i, (int)st);
    CHECK_EQ_INT(st, RC_ERR_INPUT);
  }
  release(&c);
}

static void csg_operand_past_end(unsigned char *f) {
  uint32_t *program = (uint32_t *)section(f, PROGRAM);
  for (int i = 0;; i++)
    if (program[i] >> RC_CSG_OP_SHIFT == RC_CSG_LEAF) {
      program[i] = 0xfffffffu;
      return;
    }
}
static void csg_program_underflows(unsigned char *f) {
  uint32_t *program = (uint32_t *)section(f, PROGRAM);
  program[0] = RC_CSG_UNION << RC_CSG_OP_SHIFT;
}
static void csg_program_past_end(unsigned char *f) { ((packed_csg *)section(f, CSG))[0].count = 1000; }
static void mesh_tree_empty(unsigned char *f) {
  packed_quadric *q = (packed_quadric *)section(f, QUADRICS);
  for (int i = 0;; i++)
    if (q[i].flags & RC_QUADRIC_MESH) {
      q[i].mesh_end = q[i].mesh_root;
      return;
    }
}
static void mesh_operand_triangles_past_end(unsigned char *f) {
  ((rc_mesh_operand *)section(f, OPERANDS))[0].count = 1u << 24;
}

TEST(composite_inconsistencies_are_refused) {
  prepared_case c;
  CHECK(prepare("csg_meshes.json", &c));
  if (!c.file) return;
  void (*const mutations[])(unsigned char *) = {csg_operand_past_end, csg_program_underflows, csg_program_past_end,
                                                mesh_tree_empty, mesh_operand_triangles_past_end};
  for (size_t i = 0; i < sizeof mutations / sizeof *mutations; i++) {
    rc_status st = decode_mutated(&c, mutations[i]);
    if (st != RC_ERR_INPUT) printf("  mutation %zu: status %d\n", i, (int)st);
    CHECK_EQ_INT(st, RC_ERR_INPUT);
  }
  release(&c);
}

/* csg.json's box is loose (frame.loose_kinds = RC_KIND_QUADRICS): the summary keeps the
 * kinds after the tree's flag (1) and its node count, which the file must give back, and a
 * forged value that names the spheres, never loose, is refused. */
static uint32_t csg_tree_nodes;
static void loose_kinds_forged(unsigned char *f) {
  unsigned char *s = section(f, SUMMARY);
  const uint32_t want[3] = {1, csg_tree_nodes, RC_KIND_QUADRICS};
  for (size_t at = 0; at + sizeof want <= *size_of(f, SUMMARY); at++) /* the summary packs its fields */
    if (memcmp(s + at, want, sizeof want) == 0) {
      const uint32_t spheres = RC_KIND_SPHERES;
      memcpy(s + at + 8, &spheres, 4);
      return;
    }
}

TEST(loose_kinds_round_trip_and_are_checked) {
  check_round_trip("csg.json");
  prepared_case c;
  CHECK(prepare("csg.json", &c));
  if (!c.file) return;
  CHECK_EQ_INT(c.packed.frame.loose_kinds, RC_KIND_QUADRICS);
  csg_tree_nodes = c.packed.frame.bvh_node_count;
  CHECK_EQ_INT(decode_mutated(&c, loose_kinds_forged), RC_ERR_INPUT);
  release(&c);
}

static void texture_past_texels(unsigned char *f) { ((packed_material *)section(f, MATERIALS))[0].texture = 1u << 20; }
static void texture_wider_than_texels(unsigned char *f) {
  packed_material *m = (packed_material *)section(f, MATERIALS);
  ((packed_texture *)(section(f, TEXELS) + 16 * (size_t)m[0].texture))->width = 1u << 16;
}
static void texture_flags_unknown(unsigned char *f) {
  packed_material *m = (packed_material *)section(f, MATERIALS);
  ((uint32_t *)section(f, TEXELS))[4 * m[0].texture + 2] = 8;
}

TEST(texture_inconsistencies_are_refused) {
  prepared_case c;
  CHECK(prepare("earth.json", &c));
  if (!c.file) return;
  CHECK(c.packed.texture_count > 0 && c.packed.materials[0].texture != RC_NO_TEXTURE);
  void (*const mutations[])(unsigned char *) = {texture_past_texels, texture_wider_than_texels, texture_flags_unknown};
  for (size_t i = 0; i < sizeof mutations / sizeof *mutations; i++) {
    rc_status st = decode_mutated(&c, mutations[i]);
    if (st != RC_ERR_INPUT) printf("  mutation %zu: status %d\n", i, (int)st);
    CHECK_EQ_INT(st, RC_ERR_INPUT);
  }
  release(&c);
}

TEST(mesh_normals_past_end_are_refused) {
  prepared_case c;
  CHECK(prepare("mesh.json", &c));
  if (!c.file) return;
  CHECK(c.packed.normal_count > 0); /* the scene is smooth shaded: the mutation means something */
  CHECK_EQ_INT(decode_mutated(&c, triangle_normals_past_end), RC_ERR_INPUT);
  release(&c);
}

/* The teapot's patch pieces carry their nets' differences (rc_shared.h, RC_QUADRIC_PATCH),
 * which the certificates take as bounds: a file whose are smaller than its control points'
 * is refused, and --perturb, which moves the points, moves them too. */
static void patch_difference_halved(unsigned char *f) {
  packed_quadric *q = (packed_quadric *)section(f, QUADRICS);
  q[0].linear.x *= 0.5f;
}

TEST(patch_bounds_round_trip_and_are_checked) {
  check_round_trip("teapot.json");
  prepared_case c;
  CHECK(prepare("teapot.json", &c));
  if (!c.file) return;
  const packed_quadric *q = &c.packed.quadrics[0];
  CHECK((q->flags & RC_QUADRIC_PATCH) != 0);
  CHECK(q->linear.x > 0 && q->linear.y > 0 && q->diag.z > 0 && q->off.z > 0);
  CHECK_EQ_INT(decode_mutated(&c, patch_difference_halved), RC_ERR_INPUT);
  uint32_t piece = 0;
  CHECK(rc_packed_patch_bounds_match(&c.packed, &piece));
  float before = q->linear.x;
  rc_packed_scene_perturb(&c.packed, 1);
  CHECK(rc_packed_patch_bounds_match(&c.packed, &piece));
  CHECK(q->linear.x != before);
  release(&c);
}

/* What cert_patch_bounds claims of a ray's frame (rc_certify_patch.glsl): a difference of
 * the net turned into it, each point's coordinates rounded as net_row rounds them (P - o,
 * then a dot product with a unit row), is at most the stored length times 1 + gamma(16) plus
 * 12 gamma(4) of the coordinates' scale. Checked over many rays at the teapot, in f32. */
static float gamma_f(float n) { return n * 0x1p-24f / (1 - n * 0x1p-24f); }

static uint32_t next_random(uint32_t *state) {
  *state = *state * 1664525u + 1013904223u;
  return *state >> 8;
}

static float unit_random(uint32_t *state) { return (float)next_random(state) / 16777216.0f * 2 - 1; }

/* The shader's patch_planes: a = w / |w| perpendicular to d, b = a x d (f32). */
static void planes(const float d[3], float a[3], float b[3]) {
  float w[3];
  if (fabsf(d[0]) > fabsf(d[1]) && fabsf(d[0]) > fabsf(d[2])) w[0] = d[1], w[1] = -d[0], w[2] = 0;
  else w[0] = 0, w[1] = d[2], w[2] = -d[1];
  float len = sqrtf(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  for (int k = 0; k < 3; k++) a[k] = w[k] / len;
  b[0] = a[1] * d[2] - a[2] * d[1];
  b[1] = a[2] * d[0] - a[0] * d[2];
  b[2] = a[0] * d[1] - a[1] * d[0];
}

static float dot3f(const float a[3], const float p[3]) { return a[0] * p[0] + a[1] * p[1] + a[2] * p[2]; }

TEST(patch_bounds_hold_in_every_ray_frame) {
  prepared_case c;
  CHECK(prepare("teapot.json", &c));
  if (!c.file) return;
  uint32_t state = 12345u, checked = 0, failed = 0;
  for (uint32_t i = 0; i < c.packed.frame.quadric_count; i += 7) {
    const packed_quadric *q = &c.packed.quadrics[i];
    if (!(q->flags & RC_QUADRIC_PATCH)) continue;
    float net[4 * RC_TEXELS_PER_PATCH];
    memcpy(net, &c.packed.texels[4 * (size_t)q->mesh_root], sizeof net);
    for (int ray = 0; ray < 16; ray++) {
      float d[3] = {unit_random(&state), unit_random(&state), unit_random(&state)};
      float len = sqrtf(dot3f(d, d));
      if (!(len > 0.1f)) continue;
      for (int k = 0; k < 3; k++) d[k] /= len;
      float a[3], b[3], o[3];
      planes(d, a, b);
      const float centre[3] = {q->center.x, q->center.y, q->center.z};
      for (int k = 0; k < 3; k++) o[k] = centre[k] + 4 * unit_random(&state);
      /* The net in the ray's frame, as net_row computes it. */
      float f[16][3];
      float scale = 0;
      for (int n = 0; n < 16; n++) {
        float p[3];
        for (int k = 0; k < 3; k++) p[k] = net[4 * n + k] - o[k], scale = fmaxf(scale, fabsf(p[k]));
        f[n][0] = dot3f(a, p), f[n][1] = dot3f(b, p), f[n][2] = dot3f(d, p);
      }
      /* The first differences along u and v, the second along u, the mixed ones. */
      double du = 0, dv = 0, duu = 0, duv = 0;
      for (int r = 0; r < 4; r++)
        for (int col = 0; col < 4; col++) {
          double s_u = 0, s_v = 0, s_uu = 0, s_uv = 0;
          for (int k = 0; k < 3; k++) {
            if (col < 3) s_u += pow((double)f[4 * r + col + 1][k] - f[4 * r + col][k], 2);
            if (r < 3) s_v += pow((double)f[4 * (r + 1) + col][k] - f[4 * r + col][k], 2);
            if (col < 2) s_uu += pow((double)f[4 * r + col + 2][k] - 2.0 * f[4 * r + col + 1][k] + f[4 * r + col][k], 2);
            if (r < 3 && col < 3)
              s_uv += pow((double)f[4 * (r + 1) + col + 1][k] - f[4 * (r + 1) + col][k] - f[4 * r + col + 1][k] + f[4 * r + col][k], 2);
          }
          du = fmax(du, sqrt(s_u)), dv = fmax(dv, sqrt(s_v)), duu = fmax(duu, sqrt(s_uu)), duv = fmax(duv, sqrt(s_uv));
        }
      double turn = 1 + gamma_f(16), e = 12 * gamma_f(4) * scale;
      bool ok = du <= q->linear.x * turn + e && dv <= q->linear.y * turn + e && duv <= q->linear.z * turn + e &&
                duu <= q->diag.z * turn + e;
      failed += !ok;
      checked++;
    }
  }
  CHECK(checked > 500);
  CHECK_EQ_INT(failed, 0);
  release(&c);
}

/* Every byte the checksum covers matters, and so does every header byte before it. */
TEST(any_changed_byte_is_refused_without_reseal) {
  prepared_case c;
  CHECK(prepare("showcase.json", &c));
  if (!c.file) return;
  size_t refused = 0, tried = 0;
  for (size_t at = 0; at < c.len; at += 1 + at / 8) {
    c.file[at] ^= 0x40;
    rc_prepared *pf = NULL;
    rc_scene s;
    rc_status st = rc_prepared_decode("flipped.vkrs", c.file, c.len, &pf, &s);
    if (st == RC_OK) {
      rc_scene_free(&s);
      rc_prepared_close(pf);
    }
    refused += st == RC_ERR_INPUT;
    tried++;
    c.file[at] ^= 0x40;
  }
  CHECK_EQ_INT(refused, tried);
  release(&c);
}

int main(int argc, char **argv) {
  if (argc > 1) scenes_dir = argv[1];
  TEST_MAIN_BEGIN
  RUN(showcase_round_trips);
  RUN(composites_with_mesh_operands_round_trip);
  RUN(smooth_mesh_round_trips);
  RUN(textures_round_trip);
  RUN(loose_kinds_round_trip_and_are_checked);
  RUN(showcase_inconsistencies_are_refused);
  RUN(composite_inconsistencies_are_refused);
  RUN(texture_inconsistencies_are_refused);
  RUN(mesh_normals_past_end_are_refused);
  RUN(patch_bounds_round_trip_and_are_checked);
  RUN(patch_bounds_hold_in_every_ray_frame);
  RUN(any_changed_byte_is_refused_without_reseal);
  TEST_MAIN_END
}
