/* Shapes given two ways must render alike (issue 18): a quadric under a "transform"
 * against the same surface reached another way (a transformed sphere, the cylinder's
 * own axis, a general matrix), on the GPU in f32 and on the CPU reference in f64 and f32.
 * One case per ctest: test_shapes VKRAYCAST CASE. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image/image_io.h"
#include "rc_cli_test.h"
#include "rc_test.h"

typedef struct {
  int w, h, c;
  float *px;
} image;

static image load(const char *name) {
  image im = {0};
  char path[300], err[256];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  if (rc_image_read(path, &im.w, &im.h, &im.c, &im.px, err, sizeof err) != 0) printf("  cannot read %s: %s\n", path, err);
  return im;
}

/* Writes TMP/name.json: a 96x96 perspective view of `objects` (JSON array members) lit by
 * a point light and a directional one, with shadows on a floor below. */
static void write_scene(const char *name, const char *objects) {
  char path[300];
  snprintf(path, sizeof path, "%s/%s.json", tmp, name);
  FILE *f = fopen(path, "w");
  if (!f) return;
  fprintf(f,
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
  fclose(f);
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
      /* The object is in view: the images are not both background. */
      int lit = 0;
      for (size_t i = 0; i < (size_t)ia.w * ia.h; i++) lit += ia.px[i * ia.c] > 0.35f;
      CHECK(lit > 500);
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

int main(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: test_shapes VKRAYCAST CASE\n");
    return 2;
  }
  bin = argv[1];
  snprintf(tmp, sizeof tmp, "/tmp/vkraycast-shapes-XXXXXX");
  if (!mkdtemp(tmp)) return 2;
  TEST_MAIN_BEGIN
  static const struct {
    const char *name;
    void (*fn)(void);
  } cases[] = {
      {"transformed_ellipsoid", test_transformed_ellipsoid_is_the_transformed_sphere},
      {"rotated_cylinder_axis", test_rotated_cylinder_is_the_cylinder_along_the_rotated_axis},
      {"rotated_cylinder_matrix", test_rotated_cylinder_is_the_quadric_matrix},
      {"composite_transform", test_composite_transform_moves_its_operands_as_one},
  };
  bool found = false;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    if (strcmp(argv[2], cases[i].name) != 0) continue;
    found = true;
    int before = rc_test_failed_checks;
    cases[i].fn();
    if (rc_test_failed_checks == before) rc_test_passed++;
    else rc_test_failed++, printf("FAIL %s\n", cases[i].name);
  }
  if (!found) {
    fprintf(stderr, "test_shapes: no case %s\n", argv[2]);
    return 2;
  }
  char cleanup[300];
  snprintf(cleanup, sizeof cleanup, "rm -rf '%s'", tmp);
  if (rc_test_failed == 0 && !getenv("KEEP") && system(cleanup) != 0) printf("could not remove %s\n", tmp);
  TEST_MAIN_END
}
