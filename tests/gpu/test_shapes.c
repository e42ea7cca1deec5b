/* Shapes of issue 18 on the GPU in f32 and on the CPU reference in f64 and f32: a quadric
 * under a "transform" against the same surface reached another way (a transformed sphere,
 * the cylinder's own axis, a general matrix), infinite planes against their closed form,
 * and closed meshes in composites against the boxes they equal.
 * One case per ctest: test_shapes VKRAYCAST CASE. */
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rc_cli_test.h"
#include "rc_image_test.h"
#include "rc_test.h"

/* TMP/name.ext opened for writing, or NULL with the test failed. */
static FILE *create_tmp(const char *name, const char *ext) {
  char path[300];
  snprintf(path, sizeof path, "%s/%s.%s", tmp, name, ext);
  FILE *f = fopen(path, "w");
  if (!f) {
    printf("  cannot write %s\n", path);
    rc_test_failed_checks++;
  }
  return f;
}

/* Writes TMP/name.json from a printf format. */
static void write_json(const char *name, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void write_json(const char *name, const char *fmt, ...) {
  FILE *f = create_tmp(name, "json");
  if (!f) return;
  va_list ap;
  va_start(ap, fmt);
  vfprintf(f, fmt, ap);
  va_end(ap);
  fclose(f);
}

/* Writes TMP/name.json: a 96x96 perspective view of `objects` (JSON array members) lit by
 * a point light and a directional one, with shadows on a floor below. */
static void write_scene(const char *name, const char *objects) {
  write_json(name,
             "{\"image\": {\"width\": 96, \"height\": 96},\n"
             " \"camera\": {\"eye\": [0.5, 1.5, 6], \"look_at\": [0, 0, 0], \"fov_y_deg\": 45},\n"
             " \"background\": [0.1, 0.2, 0.3],\n"
             " \"materials\": {\"m\": {\"diffuse\": [0.7, 0.6, 0.5], \"specular\": [0.3, 0.3, 0.3], \"shininess\": 40},\n"
             "               \"floor\": {\"diffuse\": [0.5, 0.5, 0.5]}},\n"
             " \"lights\": [{\"type\": \"point\", \"position\": [3, 4, 5], \"intensity\": [30, 30, 30]},\n"
             "            {\"type\": \"directional\", \"direction\": [-1, -2, -0.5], \"intensity\": [0.4, 0.4, 0.4]}],\n"
             " \"objects\": [{\"type\": \"box\", \"min\": [-4, -2.5, -4], \"max\": [4, -2, 4], \"material\": \"floor\"},\n"
             "   %s]}\n",
             objects);
}

/* Pixels of two images of one size whose colours differ by more than tol in a channel. */
static int pixels_over(const image *a, const image *b, double tol, double *max) {
  int n = 0;
  *max = 0;
  for (size_t i = 0; i < (size_t)a->w * a->h; i++) {
    double m = 0;
    for (int k = 0; k < 3; k++) m = fmax(m, fabs((double)a->px[i * a->c + k] - b->px[i * b->c + k]));
    *max = fmax(*max, m);
    n += m > tol;
  }
  return n;
}

/* Renders scenes a and b on each backend and precision; pixels whose colour differs by
 * more than 1/255 may be at most `edge` (rays that graze a silhouette decide differently
 * when the two ways of stating the surface round differently), and none that much on the
 * f64 reference, whose rounding is 2^-29 of f32's. */
static void check_alike(const char *a, const char *b, int edge) {
  static const char *const variants[3][2] = {{"gpu", "f32"}, {"cpu", "f64"}, {"cpu", "f32"}};
  for (int v = 0; v < 3; v++) {
    const char *backend = variants[v][0], *precision = variants[v][1];
    for (int k = 0; k < 2; k++) {
      const char *name = k ? b : a;
      CHECK_EQ_INT(run("render %s/%s.json -o %s/%s.%s.%s.exr --backend %s --precision %s --quiet", tmp, name, tmp, name,
                       backend, precision, backend, precision),
                   0);
    }
    char na[200], nb[200];
    snprintf(na, sizeof na, "%s.%s.%s.exr", a, backend, precision);
    snprintf(nb, sizeof nb, "%s.%s.%s.exr", b, backend, precision);
    image ia = load(na), ib = load(nb);
    if (!ia.px || !ib.px || ia.w != ib.w || ia.h != ib.h) {
      CHECK(false);
    } else {
      double max;
      int over = pixels_over(&ia, &ib, 1.0 / 255, &max);
      printf("  %s vs %s, %s %s: %d pixels over 1/255, largest difference %.3g\n", a, b, backend, precision, over, max);
      CHECK(over <= (strcmp(precision, "f64") == 0 ? 0 : edge));
      /* The object is in view: material m is warm (R > B), the floor and background not. */
      int seen = 0;
      for (size_t i = 0; i < (size_t)ia.w * ia.h; i++) seen += ia.px[i * ia.c] > ia.px[i * ia.c + 2] + 0.03f;
      printf("    %d pixels show the object\n", seen);
      CHECK(seen > 400);
    }
    free(ia.px);
    free(ib.px);
  }
}

/* A unit ellipsoid (radii 1, 1, 1) and a unit sphere under one transform that scales
 * unevenly, rotates about a skew axis and moves: the quadric's frame becomes a general
 * matrix, the sphere goes through its own object-space intersection. */
TEST(transformed_ellipsoid_is_the_transformed_sphere) {
  const char *t = "\"transform\": {\"translate\": [0.2, -0.3, 0.1], \"rotate_deg\": {\"axis\": [1, 1, 0.3], \"angle\": 35},"
                  " \"scale\": [1.6, 0.7, 1.1]}";
  char o[1024];
  snprintf(o, sizeof o, "{\"type\": \"ellipsoid\", \"center\": [0, 0, 0], \"radii\": [1, 1, 1], \"material\": \"m\", %s}", t);
  write_scene("ellipsoid", o);
  snprintf(o, sizeof o, "{\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m\", %s}", t);
  write_scene("sphere", o);
  check_alike("ellipsoid", "sphere", 12);
}

/* A capped cylinder along y turned by Euler angles (20, 0, 30) degrees and moved, against
 * the same cylinder stated by its axis R (0, 1, 0) and centre: the caps are the same
 * discs; the frame's x and y axes differ, which a surface of revolution cannot show. */
TEST(rotated_cylinder_is_the_cylinder_along_the_rotated_axis) {
  double ax = 20 * M_PI / 180, az = 30 * M_PI / 180;
  /* R = Rz Ry Rx (Ry = I) applied to (0, 1, 0): Rx gives (0, cos ax, sin ax), then Rz. */
  double y = cos(ax), z = sin(ax);
  double axis[3] = {-sin(az) * y, cos(az) * y, z};
  char o[1024];
  snprintf(o, sizeof o,
           "{\"type\": \"cylinder\", \"center\": [0, 0, 0], \"radius\": 0.8, \"height\": 2.5, \"material\": \"m\","
           " \"transform\": {\"rotate_deg\": [20, 0, 30], \"translate\": [0.1, 0.2, -0.3]}}");
  write_scene("turned", o);
  snprintf(o, sizeof o,
           "{\"type\": \"cylinder\", \"center\": [0.1, 0.2, -0.3], \"axis\": [%.17g, %.17g, %.17g], \"radius\": 0.8,"
           " \"height\": 2.5, \"material\": \"m\"}",
           axis[0], axis[1], axis[2]);
  write_scene("axis", o);
  check_alike("turned", "axis", 12);
}

/* The same cylinder laid along x by a 90 degree turn about z, against the general quadric
 * (y^2 + z^2) / r^2 - 1 clipped to the same box: here the named shape's clip box is
 * world-aligned after the turn, so both solids are the same set exactly. */
TEST(rotated_cylinder_is_the_quadric_matrix) {
  char o[1024];
  snprintf(o, sizeof o,
           "{\"type\": \"cylinder\", \"center\": [0, 0, 0], \"radius\": 0.8, \"height\": 3, \"material\": \"m\","
           " \"transform\": {\"rotate_deg\": {\"axis\": [0, 0, 1], \"angle\": 90}, \"translate\": [0, 0.3, 0]}}");
  write_scene("turned", o);
  double r = 0.8, m = 0.8 * (1 + 1.0 / 1024);
  snprintf(o, sizeof o,
           "{\"type\": \"quadric\", \"matrix\": [[0, 0, 0, 0], [0, %.17g, 0, %.17g], [0, 0, %.17g, 0], [0, %.17g, 0, %.17g]],"
           " \"bounds\": {\"min\": [-1.5, %.17g, %.17g], \"max\": [1.5, %.17g, %.17g]}, \"solid\": true, \"material\": \"m\"}",
           1 / (r * r), -0.3 / (r * r), 1 / (r * r), -0.3 / (r * r), 0.09 / (r * r) - 1, 0.3 - m, -m, 0.3 + m, m);
  write_scene("matrix", o);
  check_alike("turned", "matrix", 12);
}

/* A hyperboloid of two sheets (gap 0.8 between the vertices, end radius 1 at height 2.4)
 * against the general quadric (x^2 + z^2) / a^2 - y^2 / s^2 + 1 <= 0 clipped to the same
 * box: s = 0.4, a^2 = 1 / ((1.2 / 0.4)^2 - 1). */
TEST(two_sheet_hyperboloid_is_the_quadric_matrix) {
  char o[1024];
  snprintf(o, sizeof o,
           "{\"type\": \"hyperboloid\", \"sheets\": 2, \"center\": [0, 0, 0], \"gap\": 0.8, \"end_radius\": 1,"
           " \"height\": 2.4, \"material\": \"m\"}");
  write_scene("named", o);
  double s2 = 0.16, a2 = 1 / (1.44 / s2 - 1), m = 1 + 1.0 / 1024;
  snprintf(o, sizeof o,
           "{\"type\": \"quadric\", \"matrix\": [[%.17g, 0, 0, 0], [0, %.17g, 0, 0], [0, 0, %.17g, 0], [0, 0, 0, 1]],"
           " \"bounds\": {\"min\": [%.17g, -1.2, %.17g], \"max\": [%.17g, 1.2, %.17g]}, \"solid\": true, \"material\": \"m\"}",
           1 / a2, -1 / s2, 1 / a2, -m, -m, m, m);
  write_scene("matrix", o);
  check_alike("named", "matrix", 12);
}

/* A composite's transform moves its operands as one: a box minus a sphere, turned and
 * scaled as a whole, against the same composite with the transform on each operand. */
TEST(composite_transform_moves_its_operands_as_one) {
  const char *t = "\"transform\": {\"rotate_deg\": [15, 40, 0], \"scale\": [1.2, 0.9, 1]}";
  const char *box = "{\"type\": \"box\", \"min\": [-1, -1, -1], \"max\": [1, 1, 1]%s%s}";
  const char *ball = "{\"type\": \"sphere\", \"center\": [0.6, 0.6, 0.6], \"radius\": 0.9%s%s}";
  char l[512], r[512], o[2048];
  snprintf(l, sizeof l, box, "", "");
  snprintf(r, sizeof r, ball, "", "");
  snprintf(o, sizeof o, "{\"type\": \"csg\", \"op\": \"difference\", \"material\": \"m\", \"left\": %s, \"right\": %s, %s}", l,
           r, t);
  write_scene("whole", o);
  snprintf(l, sizeof l, box, ", ", t);
  snprintf(r, sizeof r, ball, ", ", t);
  snprintf(o, sizeof o, "{\"type\": \"csg\", \"op\": \"difference\", \"material\": \"m\", \"left\": %s, \"right\": %s}", l, r);
  write_scene("each", o);
  check_alike("whole", "each", 0);
}

/* The AOV channels as read back (OpenEXR stores them sorted, layers last): R, G, B, decisions,
 * hit, object, shadow, t, uncertified, N.X, N.Y, N.Z. */
enum { CH_HIT = 4, CH_OBJECT = 5, CH_SHADOW = 6, CH_T = 7, CH_NX = 9, CH_NY = 10, CH_NZ = 11, CH_COUNT = 12 };

/* Renders TMP/name.json on each backend and precision to name.BACKEND.PRECISION.aov.exr and
 * hands each image to check(). */
static void for_each_variant(const char *name, void (*check)(const image *im, const char *variant)) {
  static const char *const variants[3][2] = {{"gpu", "f32"}, {"cpu", "f64"}, {"cpu", "f32"}};
  for (int v = 0; v < 3; v++) {
    char out[200], variant[32];
    snprintf(variant, sizeof variant, "%s %s", variants[v][0], variants[v][1]);
    snprintf(out, sizeof out, "%s.%s.%s.aov.exr", name, variants[v][0], variants[v][1]);
    CHECK_EQ_INT(run("render %s/%s.json -o %s/%s.png --aov %s/%s --backend %s --precision %s --quiet", tmp, name, tmp, name,
                     tmp, out, variants[v][0], variants[v][1]),
                 0);
    image im = load(out);
    if (!im.px || im.c != CH_COUNT) {
      CHECK(false);
    } else {
      check(&im, variant);
    }
    free(im.px);
  }
}

/* The floor y = 0 (stated by the point (3, 0, -2) and the normal (0, 2, 0)) seen straight
 * down by a parallel camera at height 10, lit by a point light at (1, 4, -1) with the
 * physical 1/r^2 falloff and nothing else: pixel (i, j) looks at (x, 0, z) with
 * x = -4 + 8 (i + 0.5) / 64 and z = -4 + 8 (j + 0.5) / 64 (image rows downwards; v = -z), where t is
 * the height 10, the normal (0, 1, 0), and the radiance kd I cos / r^2 = kd I h / r^3. */
static void check_floor(const image *im, const char *variant) {
  int bad_t = 0, bad_n = 0, bad_c = 0;
  double worst = 0;
  for (int j = 0; j < im->h; j++) {
    for (int i = 0; i < im->w; i++) {
      const float *px = im->px + ((size_t)j * im->w + i) * im->c;
      double x = -4 + 8 * (i + 0.5) / 64, z = -4 + 8 * (j + 0.5) / 64;
      double dx = x - 1, dy = 4, dz = z + 1, r = sqrt(dx * dx + dy * dy + dz * dz);
      double want = 0.5 * 10 * dy / (r * r * r);
      bad_t += !(px[CH_HIT] == 1 && fabs(px[CH_T] - 10) <= 4e-6 * 10);
      bad_n += !(fabs(px[CH_NX]) <= 1e-6 && fabs(px[CH_NY] - 1) <= 1e-6 && fabs(px[CH_NZ]) <= 1e-6);
      double e = fabs(px[0] - want) / want;
      worst = fmax(worst, e);
      bad_c += e > 1e-5;
    }
  }
  printf("  floor, %s: %d pixels with a wrong t, %d with a wrong normal, %d with radiance off by more than 1e-5 "
         "(worst %.3g relative)\n", variant, bad_t, bad_n, bad_c, worst);
  CHECK_EQ_INT(bad_t, 0);
  CHECK_EQ_INT(bad_n, 0);
  CHECK_EQ_INT(bad_c, 0);
}

TEST(plane_matches_the_closed_form) {
  write_json("floor", "{\"image\": {\"width\": 64, \"height\": 64},\n"
             " \"camera\": {\"projection\": \"parallel\", \"eye\": [0, 10, 0], \"look_at\": [0, 0, 0], \"up\": [0, 0, -1],"
             " \"view_height\": 8},\n"
             " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5]}},\n"
             " \"lights\": [{\"type\": \"point\", \"position\": [1, 4, -1], \"intensity\": [10, 10, 10]}],\n"
             " \"objects\": [{\"type\": \"plane\", \"point\": [3, 0, -2], \"normal\": [0, 2, 0], \"material\": \"m\"}]}\n");
  for_each_variant("floor", check_floor);
}

/* A one-sided plane is there from its front only: a camera behind the wall sees through it
 * to the floor beyond (and the light behind it still reaches the floor), a camera in front
 * sees the wall. */
static int wall_hits;
static void count_wall(const image *im, const char *variant) {
  (void)variant;
  wall_hits = 0;
  for (size_t i = 0; i < (size_t)im->w * im->h; i++) wall_hits += im->px[i * im->c + CH_HIT] == 1 && im->px[i * im->c + CH_OBJECT] == 1;
}

TEST(one_sided_plane_is_seen_from_its_front_only) {
  const char *sides[2] = {"front", "back"};
  for (int k = 0; k < 2; k++) {
    write_json(sides[k], "{\"image\": {\"width\": 32, \"height\": 32},\n"
               " \"camera\": {\"eye\": [0, 1, %d], \"look_at\": [0, 0.5, 0]},\n"
               " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5]}},\n"
               " \"lights\": [{\"type\": \"point\", \"position\": [0, 3, -3], \"intensity\": [10, 10, 10]}],\n"
               " \"objects\": [{\"type\": \"plane\", \"point\": [0, 0, 0], \"normal\": [0, 1, 0], \"material\": \"m\"},\n"
               "   {\"type\": \"plane\", \"point\": [0, 0, 0], \"normal\": [0, 0, 1], \"one_sided\": true, \"material\": \"m\"}]}\n",
            k ? -5 : 5);
    for_each_variant(sides[k], count_wall);
    printf("  camera at the wall's %s: %d pixels on the wall\n", sides[k], wall_hits);
    CHECK(k ? wall_hits == 0 : wall_hits > 200);
  }
}

/* One-sided triangles, in a mesh file and as JSON triangles: the wall is there from its
 * front only (the side its counter-clockwise winding faces, +z here), also under a
 * transform that mirrors it, and lets shadow rays through from behind. Pixels are told
 * apart by their normal (the wall's is +-z, the floor's +y), not by object numbers. */
static int wall_pixels, shadowed_floor;
static void count_wall_and_shadow(const image *im, const char *variant) {
  (void)variant;
  wall_pixels = shadowed_floor = 0;
  for (size_t i = 0; i < (size_t)im->w * im->h; i++) {
    const float *px = im->px + i * im->c;
    if (px[CH_HIT] != 1) continue;
    wall_pixels += fabsf(px[CH_NZ]) > 0.9f;
    shadowed_floor += fabsf(px[CH_NY]) > 0.9f && px[CH_SHADOW] != 0;
  }
}

TEST(one_sided_triangles_are_seen_from_their_front_only) {
  FILE *f = create_tmp("quad", "obj");
  if (!f) return;
  fprintf(f, "v -2 0 0\nv 2 0 0\nv 2 2 0\nv -2 2 0\nf 1 2 3 4\n"); /* counter-clockwise seen from +z */
  fclose(f);
  static const char *const walls[][2] = {
      {"mesh", "{\"type\": \"mesh\", \"file\": \"quad.obj\", \"one_sided\": %s, \"material\": \"m\"}"},
      {"mirrored mesh", "{\"type\": \"mesh\", \"file\": \"quad.obj\", \"one_sided\": %s, \"material\": \"m\", "
                        "\"transform\": {\"scale\": [-1, 1, 1]}}"},
      {"triangles", "{\"type\": \"triangle\", \"vertices\": [[-2, 0, 0], [2, 0, 0], [2, 2, 0]], \"one_sided\": %s, "
                    "\"material\": \"m\"}, {\"type\": \"triangle\", \"vertices\": [[-2, 0, 0], [2, 2, 0], [-2, 2, 0]], "
                    "\"one_sided\": %s, \"material\": \"m\"}"}};
  for (size_t w = 0; w < sizeof walls / sizeof *walls; w++)
    for (int sided = 1; sided <= 2; sided++)
      for (int k = 0; k < 2; k++) {
        /* The light is on the wall's front, at z = 3; the camera at z = 5 (front) or -5. */
        char wall[600], name[32];
        const char *v = sided == 1 ? "true" : "false";
        snprintf(wall, sizeof wall, walls[w][1], v, v);
        snprintf(name, sizeof name, "quad%zu%d%d", w, sided, k);
        write_json(name, "{\"image\": {\"width\": 32, \"height\": 32},\n"
                   " \"camera\": {\"eye\": [0, 1, %d], \"look_at\": [0, 0.5, 0]},\n"
                   " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5]}},\n"
                   " \"lights\": [{\"type\": \"point\", \"position\": [0, 3, 3], \"intensity\": [10, 10, 10]}],\n"
                   " \"objects\": [{\"type\": \"plane\", \"point\": [0, 0, 0], \"normal\": [0, 1, 0], \"material\": \"m\"},\n"
                   "   %s]}\n", k ? -5 : 5, wall);
        for_each_variant(name, count_wall_and_shadow);
        printf("  %s, %s-sided, camera at its %s: %d pixels on the wall, %d of the floor in shadow\n", walls[w][0],
               sided == 1 ? "one" : "two", k ? "back" : "front", wall_pixels, shadowed_floor);
        if (sided == 2 || k == 0) CHECK(wall_pixels > 150);
        if (sided == 1 && k == 1) CHECK(wall_pixels == 0 && shadowed_floor == 0);
        if (sided == 2 && k == 1) CHECK(shadowed_floor > 50); /* the control: the wall's shadow */
      }
}

/* Writes TMP/name.obj: `cubes` cubes [-1, 1]^3 moved by (4 k, 0, 0), 12 triangles each,
 * the first of each face pair wound outwards and the second inwards (parity must not care). */
static void write_cubes(const char *name, int cubes) {
  FILE *f = create_tmp(name, "obj");
  if (!f) return;
  static const int face[12][3] = {{1, 3, 2}, {1, 3, 4}, {5, 6, 7}, {5, 8, 7}, {1, 2, 6}, {1, 5, 6},
                                  {4, 8, 7}, {4, 3, 7}, {1, 5, 8}, {1, 4, 8}, {2, 3, 7}, {2, 6, 7}};
  for (int k = 0; k < cubes; k++)
    for (int v = 0; v < 8; v++)
      fprintf(f, "v %d %d %d\n", 4 * k + ((v == 1 || v == 2 || v == 5 || v == 6) ? 1 : -1), (v % 4 >= 2) ? 1 : -1,
              v >= 4 ? 1 : -1);
  for (int k = 0; k < cubes; k++)
    for (int i = 0; i < 12; i++) fprintf(f, "f %d %d %d\n", 8 * k + face[i][0], 8 * k + face[i][1], 8 * k + face[i][2]);
  fclose(f);
}

/* A cube as a closed mesh minus a sphere, against the box minus the same sphere, both
 * turned and moved by one transform: the mesh's intervals come from parity over its own
 * BVH, the box's from its slabs, and they bound the same solid. */
TEST(mesh_cube_minus_sphere_is_the_box_minus_sphere) {
  write_cubes("cube", 1);
  const char *t = "\"transform\": {\"rotate_deg\": [25, 35, 0], \"translate\": [0, -0.4, 0]}";
  const char *sphere = "{\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1.3}";
  char o[1024];
  snprintf(o, sizeof o, "{\"type\": \"csg\", \"op\": \"difference\", \"material\": \"m\", %s,"
           " \"left\": {\"type\": \"mesh\", \"file\": \"cube.obj\"}, \"right\": %s}", t, sphere);
  write_scene("mesh_cube", o);
  snprintf(o, sizeof o, "{\"type\": \"csg\", \"op\": \"difference\", \"material\": \"m\", %s,"
           " \"left\": {\"type\": \"box\", \"min\": [-1, -1, -1], \"max\": [1, 1, 1]}, \"right\": %s}", t, sphere);
  write_scene("box_cube", o);
  check_alike("mesh_cube", "box_cube", 12);
}

/* Two cubes in one mesh along the view: a ray line crosses it 4 times. With max_crossings
 * 2 every backend refuses the scene, naming the composite, and writes nothing; with 4 it
 * renders the two cubes as the boxes would. */
TEST(mesh_crossings_beyond_the_bound_fail_loudly) {
  write_cubes("cubes", 2);
  const char *layout = "\"transform\": {\"rotate_deg\": [0, 80, 0], \"translate\": [1.2, 0, -1]}";
  char o[1024];
  for (int bound = 2; bound <= 4; bound += 2) {
    snprintf(o, sizeof o, "{\"type\": \"csg\", \"op\": \"union\", \"material\": \"m\", %s,"
             " \"left\": {\"type\": \"mesh\", \"file\": \"cubes.obj\", \"max_crossings\": %d},"
             " \"right\": {\"type\": \"sphere\", \"center\": [-9, 0, 0], \"radius\": 0.5}}", layout, bound);
    char name[32];
    snprintf(name, sizeof name, "cubes%d", bound);
    write_scene(name, o);
  }
  static const char *const backends[] = {"gpu", "cpu"};
  for (int b = 0; b < 2; b++) {
    CHECK_EQ_INT(run("render %s/cubes2.json -o %s/cubes2.%s.png --backend %s --quiet", tmp, tmp, backends[b], backends[b]), 2);
    CHECK(stderr_contains("cubes2.json:9:4: error: objects[1]: the line of a ray through pixel"));
    CHECK(stderr_contains("\"max_crossings\""));
    char out[300];
    snprintf(out, sizeof out, "%s/cubes2.%s.png", tmp, backends[b]);
    CHECK(access(out, F_OK) != 0);
  }
  snprintf(o, sizeof o, "{\"type\": \"csg\", \"op\": \"union\", \"material\": \"m\", %s,"
           " \"left\": {\"type\": \"csg\", \"op\": \"union\", \"left\": {\"type\": \"box\", \"min\": [-1, -1, -1], \"max\": [1, 1, 1]},"
           " \"right\": {\"type\": \"box\", \"min\": [3, -1, -1], \"max\": [5, 1, 1]}},"
           " \"right\": {\"type\": \"sphere\", \"center\": [-9, 0, 0], \"radius\": 0.5}}", layout);
  write_scene("boxes", o);
  check_alike("cubes4", "boxes", 12);
}

int main(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: test_shapes VKRAYCAST CASE\n");
    return 2;
  }
  bin = argv[1];
  snprintf(tmp, sizeof tmp, "/tmp/vkraycast-shapes-XXXXXX");
  if (!mkdtemp(tmp)) return 2;
  TEST_MAIN_BEGIN
  static const rc_test_case cases[] = {
      {"transformed_ellipsoid", test_transformed_ellipsoid_is_the_transformed_sphere},
      {"rotated_cylinder_axis", test_rotated_cylinder_is_the_cylinder_along_the_rotated_axis},
      {"rotated_cylinder_matrix", test_rotated_cylinder_is_the_quadric_matrix},
      {"composite_transform", test_composite_transform_moves_its_operands_as_one},
      {"hyperboloid_two_sheets", test_two_sheet_hyperboloid_is_the_quadric_matrix},
      {"plane_closed_form", test_plane_matches_the_closed_form},
      {"plane_one_sided", test_one_sided_plane_is_seen_from_its_front_only},
      {"triangles_one_sided", test_one_sided_triangles_are_seen_from_their_front_only},
      {"mesh_cube_minus_sphere", test_mesh_cube_minus_sphere_is_the_box_minus_sphere},
      {"mesh_crossings_bound", test_mesh_crossings_beyond_the_bound_fail_loudly},
  };
  if (!rc_run_cases(cases, sizeof cases / sizeof cases[0], argv[2], &rc_test_passed, &rc_test_failed)) return 2;
  char cleanup[300];
  snprintf(cleanup, sizeof cleanup, "rm -rf '%s'", tmp);
  /* KEEP=1 keeps the scenes and images for a look. */
  if (rc_test_failed == 0 && !getenv("KEEP") && system(cleanup) != 0) printf("could not remove %s\n", tmp);
  TEST_MAIN_END
}
