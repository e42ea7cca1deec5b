/* Scene parsing defaults and packing: what the format promises in docs/scene-format.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rc_test.h"
#include "scene/bvh.h"
#include "scene/mesh_import.h"
#include "scene/scene_pack.h"
#include "scene/precision_budget.h"

static rc_status parse(const char *text, rc_scene *s) { return rc_scene_parse_json("test.json", text, strlen(text), NULL, s); }

TEST(defaults_are_the_documented_ones) {
  rc_scene s;
  CHECK_EQ_INT(parse("{\"image\":{\"width\":4,\"height\":2},\"camera\":{\"eye\":[0,0,5],\"look_at\":[0,0,0]}}", &s), RC_OK);
  CHECK_EQ_INT(s.samples_per_pixel, 1);
  CHECK_EQ_INT(s.camera.projection, RC_PROJECTION_PERSPECTIVE);
  CHECK(s.camera.up.x == 0 && s.camera.up.y == 1 && s.camera.up.z == 0);
  CHECK(s.camera.fov_y_deg == 45.0);
  CHECK(s.background.x == 0 && s.ambient_light.x == 1);
  CHECK_EQ_INT(s.specular_model, RC_SPECULAR_BLINN_PHONG);
  CHECK_EQ_INT(s.reflection_depth, 5);
  CHECK_EQ_INT(s.sphere_count + s.triangle_count + s.light_count + s.material_count, 0);
  rc_scene_free(&s);
}

TEST(materials_lights_objects_are_read) {
  const char *text =
      "{\"image\":{\"width\":8,\"height\":8,\"samples_per_pixel\":16},"
      "\"camera\":{\"projection\":\"parallel\",\"eye\":[0,0,5],\"look_at\":[0,0,0],\"view_height\":3},"
      "\"specular_model\":\"phong\","
      "\"materials\":{\"m\":{\"diffuse\":[0.5,0.25,1],\"shininess\":7,\"mirror\":0.5}},"
      "\"lights\":[{\"type\":\"directional\",\"direction\":[0,0,-2],\"intensity\":[1,1,1]}],"
      "\"objects\":[{\"type\":\"sphere\",\"center\":[1,2,3],\"radius\":0.5,\"material\":\"m\"},"
      "{\"type\":\"triangle\",\"vertices\":[[0,0,0],[1,0,0],[0,1,0]],\"material\":\"m\"},"
      "{\"type\":\"triangle\",\"vertices\":[[0,0,0],[1,1,1],[2,2,2]],\"material\":\"m\"}]}";
  rc_scene s;
  CHECK_EQ_INT(parse(text, &s), RC_OK);
  CHECK_EQ_INT(s.camera.projection, RC_PROJECTION_PARALLEL);
  CHECK(s.camera.view_height == 3);
  CHECK_EQ_INT(s.specular_model, RC_SPECULAR_PHONG);
  CHECK(s.materials[0].mirror.y == 0.5 && s.materials[0].diffuse.y == 0.25 && s.materials[0].shininess == 7);
  CHECK_EQ_INT(s.sphere_count, 1);
  CHECK_EQ_INT(s.triangle_count, 1);       /* the collinear one is skipped ... */
  CHECK_EQ_INT(s.degenerate_triangles, 1); /* ... and counted */
  rc_packed_scene p;
  CHECK_EQ_INT(rc_scene_pack(&s, &p), RC_OK);
  /* Camera-relative packing: the eye is the origin of the packed space. */
  CHECK(p.frame.camera.eye.x == 0 && p.frame.camera.eye.z == 0);
  CHECK(p.spheres[0].center.x == 1 && p.spheres[0].center.y == 2 && p.spheres[0].center.z == -2);
  CHECK_NEAR(p.lights[0].position.z, -1.0, 0); /* directional: normalised */
  CHECK_EQ_INT(p.frame.strata_x, 4);
  CHECK_EQ_INT(p.frame.strata_y, 4);
  CHECK_EQ_INT(p.frame.reflection_depth, 5); /* a material mirrors */
  CHECK_NEAR(p.frame.camera.top, 1.5, 0);    /* half the view height */
  rc_packed_scene_free(&p);
  rc_scene_free(&s);
}

TEST(camera_basis_is_right_handed_and_window_follows_fov_and_aspect) {
  rc_scene s;
  CHECK_EQ_INT(parse("{\"image\":{\"width\":200,\"height\":100},\"camera\":{\"eye\":[0,0,0],\"look_at\":[0,0,-1],"
                     "\"fov_y_deg\":90}}",
                     &s),
               RC_OK);
  rc_packed_scene p;
  CHECK_EQ_INT(rc_scene_pack(&s, &p), RC_OK);
  const packed_camera *c = &p.frame.camera;
  CHECK(c->u.x == 1 && c->v.y == 1 && c->w.z == 1);
  CHECK_NEAR(c->top, 1.0, 1e-7); /* tan(45 deg) */
  CHECK_NEAR(c->right, 2.0, 1e-7);
  CHECK_EQ_INT(p.frame.reflection_depth, 0); /* no mirror: no bounce loop */
  rc_packed_scene_free(&p);
  rc_scene_free(&s);
}

TEST(camera_problems_are_named) {
  rc_camera_def c = {RC_PROJECTION_PERSPECTIVE, {0, 0, 0}, {0, 0, -1}, {0, 0, 1}, 45, 0};
  const char *field = NULL;
  CHECK(rc_scene_camera_problem(&c, &field) != NULL && strcmp(field, "up") == 0);
  c.up = rcm_make_d(0, 1, 0);
  CHECK(rc_scene_camera_problem(&c, &field) == NULL);
  c.fov_y_deg = 180;
  CHECK(rc_scene_camera_problem(&c, &field) != NULL && strcmp(field, "fov_y_deg") == 0);
}

/* JSON transforms compose as matrix * T * R * S (points scaled first). */
TEST(transforms_compose_scale_rotate_translate) {
  rc_scene s;
  CHECK_EQ_INT(parse("{\"image\":{\"width\":4,\"height\":4},\"camera\":{\"eye\":[0,0,5],\"look_at\":[0,0,0]},"
                     "\"materials\":{\"m\":{}},\"objects\":[{\"type\":\"triangle\",\"vertices\":[[1,0,0],[0,1,0],[0,0,1]],"
                     "\"material\":\"m\",\"transform\":{\"translate\":[10,0,0],\"rotate_deg\":{\"axis\":[0,0,1],"
                     "\"angle\":90},\"scale\":2}},{\"type\":\"sphere\",\"center\":[0,0,0],\"radius\":1,\"material\":\"m\","
                     "\"transform\":{\"scale\":[2,1,1]}}]}",
                     &s),
               RC_OK);
  /* (1,0,0) -> scale (2,0,0) -> rotate 90 about z (0,2,0) -> translate (10,2,0) */
  CHECK_NEAR(s.triangles[0].v[0].x, 10, 1e-12);
  CHECK_NEAR(s.triangles[0].v[0].y, 2, 1e-12);
  CHECK_NEAR(s.triangles[0].v[1].x, 8, 1e-12); /* (0,1,0) -> (0,2,0) -> (-2,0,0) -> (8,0,0) */
  CHECK(s.spheres[0].transformed && s.spheres[0].world_from_object.m[0][0] == 2);
  rc_scene_free(&s);
}

/* A mesh through assimp: assimp-testmodels' OBJ cube (6 quads -> 12 triangles), its MTL
 * material, and the transform applied to every vertex. */
static const char box_scene[] =
    "{\"image\":{\"width\":4,\"height\":4},\"camera\":{\"eye\":[0,0,5],\"look_at\":[0,0,0]},"
    "\"objects\":[{\"type\":\"mesh\",\"file\":\"/usr/share/assimp/models/OBJ/box.obj\","
    "\"transform\":{\"translate\":[100,0,0]}}]}";

TEST(obj_mesh_is_triangulated_and_transformed) {
  rc_scene s;
  rc_load_options outside = {.allow_outside_paths = true};
  CHECK_EQ_INT(rc_scene_parse_json("test.json", box_scene, strlen(box_scene), &outside, &s), RC_OK);
  CHECK_EQ_INT(s.triangle_count, 12);
  CHECK(s.material_count >= 1);
  double min_x = 1e30, max_x = -1e30;
  for (size_t i = 0; i < s.triangle_count; i++)
    for (int k = 0; k < 3; k++) {
      if (s.triangles[i].v[k].x < min_x) min_x = s.triangles[i].v[k].x;
      if (s.triangles[i].v[k].x > max_x) max_x = s.triangles[i].v[k].x;
    }
  CHECK(min_x > 98 && max_x < 102 && max_x > min_x);
  rc_scene_free(&s);
}

/* The importer's answer for that cube (host/scene/mesh_wire.h), and every way it can come
 * short: each prefix of it, a foreign version, a count past what follows, trailing bytes.
 * None may be read past its end (the ASan build of this test would report it). */
static const char *parse_copy(const rc_mesh_data *whole, size_t len, void (*damage)(uint32_t *words, size_t n)) {
  void *copy = malloc(len ? len : 1);
  memcpy(copy, whole->buffer, len < whole->length ? len : whole->length);
  if (len > whole->length) memset((char *)copy + whole->length, 0, len - whole->length);
  if (damage) damage(copy, len / 4);
  rc_mesh_data d;
  const char *wrong = rc_mesh_wire_parse(copy, len, &d);
  rc_mesh_data_free(&d);
  return wrong;
}
static void foreign_version(uint32_t *w, size_t n) { (void)n, w[1] = RC_MESH_WIRE_VERSION + 1; }
static size_t damaged_word;
static void all_ones(uint32_t *w, size_t n) {
  if (damaged_word < n) w[damaged_word] = 0xffffffffu;
}

TEST(importer_answer_is_checked_whole) {
  rc_mesh_data m;
  char why[4400] = "";
  const char *box = "/usr/share/assimp/models/OBJ/box.obj";
  CHECK_EQ_INT(rc_mesh_import(box, NULL, true, 1000, &m, why, sizeof why), RC_OK);
  CHECK_EQ_INT(m.outcome, RC_MESH_IMPORTED);
  CHECK(m.input_count >= 1 && strcmp(m.inputs[0], box) == 0);
  uint32_t triangles = 0;
  for (uint32_t i = 0; i < m.part_count; i++) triangles += m.parts[i].triangle_count;
  CHECK_EQ_INT(triangles, 12);
  CHECK(m.length > 0 && m.length % 4 == 0);
  CHECK(parse_copy(&m, m.length, NULL) == NULL);
  size_t refused = 0;
  for (size_t len = 0; len < m.length; len++) refused += parse_copy(&m, len, NULL) != NULL;
  CHECK_EQ_INT(refused, m.length);
  CHECK(parse_copy(&m, m.length + 4, NULL) != NULL);
  CHECK(parse_copy(&m, m.length, foreign_version) != NULL);
  /* Each word in turn made 0xffffffff: every count, index of a material, flag, magic
   * word and the version refused (8 words, and 5 in each part's header); floats, vertex
   * indices (checked when the triangles are built) and string bytes may pass. */
  size_t structural = 0;
  for (damaged_word = 0; damaged_word < m.length / 4; damaged_word++)
    structural += parse_copy(&m, m.length, all_ones) != NULL;
  CHECK(structural >= 8 + 5 * (size_t)m.part_count);
  rc_mesh_data_free(&m);
  /* A file assimp cannot read: an answer, with assimp's reason. */
  CHECK_EQ_INT(rc_mesh_import("/usr/share/assimp/models/OBJ/box.mtl", NULL, false, 100, &m, why, sizeof why), RC_OK);
  CHECK(m.outcome == RC_MESH_FAILED && m.message[0] != '\0');
  rc_mesh_data_free(&m);
}

/* By default a mesh outside the scene's folder (here ".") is refused before it is read. */
TEST(mesh_outside_the_scene_folder_needs_the_option) {
  rc_scene s;
  CHECK_EQ_INT(parse(box_scene, &s), RC_ERR_INPUT);
  CHECK_EQ_INT(s.triangle_count, 0);
  rc_scene_free(&s);
}

/* tools/gen_mesh.c's bumpy sphere (radius 1 +- 0.055; rows x 2*rows quads, two triangles
 * each, the caps' degenerate ones skipped by the parser), optionally on a floor of two
 * triangles 8 wide at its lowest point, as tools/mesh_scene.sh frames every benchmark mesh. */
static void bumpy(double theta, double phi, double p[3]) {
  double r = 1.0 + 0.04 * sin(7 * theta) * cos(9 * phi) + 0.015 * sin(37 * theta + 3 * phi);
  p[0] = (float)(r * sin(theta) * cos(phi));
  p[1] = (float)(r * cos(theta));
  p[2] = (float)(r * sin(theta) * sin(phi));
}

static char *sphere_scene(int rows, bool floor) {
  size_t cap = 512 + (size_t)rows * 2 * rows * 2 * 256, len = 0;
  char *t = malloc(cap);
  if (!t) return NULL;
  len += (size_t)snprintf(t + len, cap - len,
                          "{\"image\":{\"width\":8,\"height\":8},\"camera\":{\"eye\":[3,2,4],\"look_at\":[0,0,0]},"
                          "\"materials\":{\"m\":{\"diffuse\":[1,1,1]}},\"objects\":[");
  const double pi = 3.14159265358979323846;
  double y0 = 1;
  for (int i = 0; i < rows; i++)
    for (int j = 0; j < 2 * rows; j++) {
      double p[4][3];
      bumpy(pi * i / rows, pi * j / rows, p[0]);
      bumpy(pi * i / rows, pi * (j + 1) / rows, p[1]);
      bumpy(pi * (i + 1) / rows, pi * j / rows, p[2]);
      bumpy(pi * (i + 1) / rows, pi * (j + 1) / rows, p[3]);
      static const int tri[2][3] = {{0, 2, 1}, {1, 2, 3}};
      for (int k = 0; k < 2; k++) {
        const double *a = p[tri[k][0]], *b = p[tri[k][1]], *c = p[tri[k][2]];
        len += (size_t)snprintf(t + len, cap - len,
                                "%s{\"type\":\"triangle\",\"vertices\":[[%.9g,%.9g,%.9g],[%.9g,%.9g,%.9g],[%.9g,%.9g,%.9g]],"
                                "\"material\":\"m\"}",
                                i + j + k ? "," : "", a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]);
      }
      for (int v = 0; v < 4; v++) y0 = p[v][1] < y0 ? p[v][1] : y0;
    }
  if (floor)
    len += (size_t)snprintf(t + len, cap - len,
                            ",{\"type\":\"triangle\",\"vertices\":[[-4,%.9g,-4],[-4,%.9g,4],[4,%.9g,4]],\"material\":\"m\"}"
                            ",{\"type\":\"triangle\",\"vertices\":[[-4,%.9g,-4],[4,%.9g,4],[4,%.9g,-4]],\"material\":\"m\"}",
                            y0, y0, y0, y0, y0, y0);
  snprintf(t + len, cap - len, "]}");
  return t;
}

/* The tree's surface-area cost (MacDonald and Booth 1990) in absolute area units: each
 * node's box area for its visit, times its object count at a leaf. Divided by a box's
 * area, it is the expected box and object tests of a ray that enters that box. */
static double node_area(const packed_bvh_node *n) {
  double dx = (double)n->hi.x - n->lo.x, dy = (double)n->hi.y - n->lo.y, dz = (double)n->hi.z - n->lo.z;
  return 2 * (dx * dy + dy * dz + dz * dx);
}

static double tree_cost(const rc_packed_scene *p) {
  double cost = 0;
  for (uint32_t i = 0; i < p->frame.bvh_node_count; i++) {
    const packed_bvh_node *n = &p->bvh_nodes[i];
    cost += n->leaf ? node_area(n) * (double)(n->leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u)) : node_area(n);
  }
  return cost;
}

static double build_cost(int rows, bool floor, double *root_area) {
  char *text = sphere_scene(rows, floor);
  rc_scene s;
  rc_packed_scene p;
  rc_bvh_stats stats;
  double cost = -1;
  if (text && parse(text, &s) == RC_OK) {
    if (rc_scene_pack(&s, &p) == RC_OK) {
      if (rc_bvh_build(&p, true, &stats) == RC_OK) {
        cost = tree_cost(&p);
        *root_area = node_area(&p.bvh_nodes[0]);
      }
      rc_packed_scene_free(&p);
    }
    rc_scene_free(&s);
  }
  free(text);
  return cost;
}

/* A floor under a detailed object must cost the tree what its own two triangles cost: a
 * root that holds both and a leaf of the two, 1 + 2 x (floor box area / root area) in
 * root areas. SAH bins divide a node's centroid bounds, and the mesh's lowest triangles
 * have their centroids within a bin's width of the floor's: with a fixed 16 bins per
 * axis (before host/scene/bvh.c scaled them with the node) the floor added 3.62 root
 * areas to this tree, with 256 at most 2.98, with 1024 at most 2.32, its own share. */
TEST(a_floor_does_not_spoil_the_tree_of_the_object_on_it) {
  double sphere_root = 0, root = 0;
  double sphere = build_cost(48, false, &sphere_root), both = build_cost(48, true, &root);
  CHECK(sphere > 0 && both > 0);
  double added = (both - sphere) / root, own = 1 + 2 * (2 * 8.0 * 8.0) / root;
  printf("  the floor adds %.3f root areas to the tree, its own share is %.3f\n", added, own);
  CHECK(added < own * 1.01);
}

/* The kinds the object tree leaves out (bvh.c, rc_loose_kinds): the bounded quadrics, where
 * composites are the main kind, the quadrics at most RC_LOOSE_MAX and fewer than half of
 * them; the planes apart. */
static uint32_t loose_of(uint32_t spheres, uint32_t triangles, uint32_t quadrics, uint32_t planes, uint32_t csg) {
  packed_frame f = {.sphere_count = spheres, .triangle_count = triangles, .quadric_count = quadrics + planes,
                    .plane_count = planes, .csg_count = csg};
  return rc_loose_kinds(&f);
}

TEST(a_few_quadrics_beside_composites_leave_the_tree) {
  CHECK_EQ_INT(loose_of(0, 0, 1, 0, 3), RC_KIND_QUADRICS);  /* csg.json: a floor box beside three */
  CHECK_EQ_INT(loose_of(1, 0, 1, 6, 5), RC_KIND_QUADRICS);  /* the planes are apart */
  CHECK_EQ_INT(loose_of(2, 1000, 1, 0, 0), 0);              /* dollhouse: a mesh leads */
  CHECK_EQ_INT(loose_of(1, 0, 1, 6, 1), 0);                 /* room: one composite */
  CHECK_EQ_INT(loose_of(0, 5, 1, 0, 4), 0);                 /* triangles lead */
  CHECK_EQ_INT(loose_of(4, 0, 1, 0, 4), RC_KIND_QUADRICS);  /* a tie for the lead: composites */
  CHECK_EQ_INT(loose_of(0, 0, 8, 0, 17), RC_KIND_QUADRICS); /* RC_LOOSE_MAX */
  CHECK_EQ_INT(loose_of(0, 0, 9, 0, 19), 0);                /* over it */
  CHECK_EQ_INT(loose_of(0, 0, 3, 0, 7), RC_KIND_QUADRICS);  /* 7 > 2 x 3 */
  CHECK_EQ_INT(loose_of(0, 0, 3, 0, 6), 0);                 /* 6 is not */
  CHECK_EQ_INT(loose_of(0, 0, 0, 3, 4), 0);                 /* planes only */
  CHECK_EQ_INT(loose_of(4096, 0, 0, 0, 0), 0);              /* one kind */
}

/* The tree of a scene of three composites and a box holds the composites, and the frame
 * names the box's kind, which both renderers then test beside it. */
TEST(the_tree_leaves_the_box_out) {
  const char *text =
      "{\"image\":{\"width\":8,\"height\":8},\"camera\":{\"eye\":[0,2,9],\"look_at\":[0,0,0]},"
      "\"materials\":{\"m\":{\"diffuse\":[1,1,1]}},\"objects\":["
      "{\"type\":\"box\",\"min\":[-8,-0.2,-6],\"max\":[8,0,4],\"material\":\"m\"},"
      "{\"type\":\"csg\",\"op\":\"union\",\"material\":\"m\",\"left\":{\"type\":\"sphere\",\"center\":[-3,1,0],"
      "\"radius\":1},\"right\":{\"type\":\"sphere\",\"center\":[-2,1,0],\"radius\":1}},"
      "{\"type\":\"csg\",\"op\":\"union\",\"material\":\"m\",\"left\":{\"type\":\"sphere\",\"center\":[0,1,0],"
      "\"radius\":1},\"right\":{\"type\":\"sphere\",\"center\":[1,1,0],\"radius\":1}},"
      "{\"type\":\"csg\",\"op\":\"union\",\"material\":\"m\",\"left\":{\"type\":\"sphere\",\"center\":[3,1,0],"
      "\"radius\":1},\"right\":{\"type\":\"sphere\",\"center\":[4,1,0],\"radius\":1}}]}";
  rc_scene s;
  rc_packed_scene p;
  rc_bvh_stats stats;
  CHECK_EQ_INT(parse(text, &s), RC_OK);
  CHECK_EQ_INT(rc_scene_pack(&s, &p), RC_OK);
  CHECK_EQ_INT(rc_bvh_build(&p, true, &stats), RC_OK);
  CHECK_EQ_INT(p.frame.loose_kinds, RC_KIND_QUADRICS);
  CHECK_EQ_INT(stats.loose, 1);
  CHECK_EQ_INT(rc_loose_objects(&p.frame), 1);
  uint32_t in_tree = 0, first_csg = p.frame.sphere_count + p.frame.triangle_count + p.frame.quadric_count;
  for (uint32_t i = 0; i < p.frame.bvh_node_count; i++) {
    uint32_t leaf = p.bvh_nodes[i].leaf;
    for (uint32_t k = 0; k < (leaf & ((1u << RC_BVH_LEAF_SHIFT) - 1u)); k++) {
      CHECK(p.bvh_prims[(leaf >> RC_BVH_LEAF_SHIFT) + k] >= first_csg); /* a composite */
      in_tree++;
    }
  }
  CHECK_EQ_INT(in_tree, 3);
  /* Brute force has no tree and nothing loose. */
  CHECK_EQ_INT(rc_bvh_build(&p, false, &stats), RC_OK);
  CHECK_EQ_INT(p.frame.loose_kinds, 0);
  rc_packed_scene_free(&p);
  rc_scene_free(&s);
}

/* One extension test for every reader and command (rc_base.h): any case, and a name
 * that is only the extension has none. */
TEST(extensions_are_read_alike_everywhere) {
  CHECK(rc_has_extension("scene.test", ".test"));
  CHECK(rc_has_extension("dir/SCENE.TEST", ".test"));
  CHECK(rc_has_extension("mesh.Ply", ".ply"));
  CHECK(!rc_has_extension(".test", ".test"));
  CHECK(!rc_has_extension("scene.test.json", ".test"));
  CHECK(!rc_has_extension("test", ".test"));
}

/* The one precision decision (precision_budget.h), for every request, finding and device. */
TEST(precision_is_decided_once_for_both_backends) {
  rc_precision_report fine = {0}, needs = {.needs_f64 = 3};
  struct {
    uint32_t requested;
    const rc_precision_report *budget;
    bool reference, device_f64, f64, certified;
    rc_precision_why why;
  } cases[] = {
      {RC_PRECISION_AUTO, &fine, true, true, true, false, RC_PRECISION_QUIET},
      {RC_PRECISION_AUTO, &needs, true, true, true, false, RC_PRECISION_QUIET},
      {RC_PRECISION_F32, &needs, true, true, false, false, RC_PRECISION_QUIET},
      {RC_PRECISION_F64, &fine, true, true, true, false, RC_PRECISION_QUIET},
      {RC_PRECISION_CERTIFIED, &needs, true, true, false, true, RC_PRECISION_QUIET},
      {RC_PRECISION_AUTO, &fine, false, true, false, false, RC_PRECISION_QUIET},
      {RC_PRECISION_AUTO, &needs, false, true, true, false, RC_PRECISION_AUTO_F64},
      {RC_PRECISION_AUTO, &fine, false, false, false, false, RC_PRECISION_QUIET},
      {RC_PRECISION_AUTO, &needs, false, false, false, true, RC_PRECISION_AUTO_CERTIFIED},
      {RC_PRECISION_F32, &fine, false, true, false, false, RC_PRECISION_QUIET},
      {RC_PRECISION_F32, &needs, false, true, false, false, RC_PRECISION_F32_DEGRADED},
      {RC_PRECISION_CERTIFIED, &fine, false, true, false, true, RC_PRECISION_QUIET},
      {RC_PRECISION_F64, &fine, false, false, true, false, RC_PRECISION_QUIET}, /* the renderer refuses it by name */
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    rc_precision_choice c = rc_precision_choose(cases[i].requested, cases[i].budget, cases[i].reference,
                                                cases[i].device_f64);
    CHECK_EQ_INT(c.f64, cases[i].f64);
    CHECK_EQ_INT(c.certified, cases[i].certified);
    CHECK_EQ_INT(c.why, cases[i].why);
  }
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(defaults_are_the_documented_ones);
  RUN(materials_lights_objects_are_read);
  RUN(camera_basis_is_right_handed_and_window_follows_fov_and_aspect);
  RUN(camera_problems_are_named);
  RUN(transforms_compose_scale_rotate_translate);
  RUN(obj_mesh_is_triangulated_and_transformed);
  RUN(mesh_outside_the_scene_folder_needs_the_option);
  RUN(importer_answer_is_checked_whole);
  RUN(a_floor_does_not_spoil_the_tree_of_the_object_on_it);
  RUN(a_few_quadrics_beside_composites_leave_the_tree);
  RUN(the_tree_leaves_the_box_out);
  RUN(precision_is_decided_once_for_both_backends);
  RUN(extensions_are_read_alike_everywhere);
  TEST_MAIN_END
}
