/* patch_bounds.c: the net differences of rc_shared.h's patch pieces (patch_bounds.h).
 * The shader turns each ray's net into the ray's frame; a difference's length there is its
 * length here within the frame's rounding, which cert_patch_bounds adds. */
#include "scene/patch_bounds.h"

#include <math.h>
#include <string.h>

/* Point (r, c) of the net, in f64 (exactly the f32 values the renderers read). */
static void point(const float *net, int r, int c, double p[3]) {
  const float *f = net + 4 * (4 * r + c);
  for (int k = 0; k < 3; k++) p[k] = f[k];
}

/* The length of the combination of `count` points with these coefficients: a difference, a
 * second difference or a mixed one. */
static double combination(const double (*p)[3], const double *coefficients, int count) {
  double s = 0;
  for (int k = 0; k < 3; k++) {
    double x = 0;
    for (int i = 0; i < count; i++) x += coefficients[i] * p[i][k];
    s += x * x;
  }
  return sqrt(s);
}

/* Rounded up: the f32 at or above x (f64's own rounding of the differences and the root,
 * a few units of 2^-53 relative, is below the 2^-40 added first). */
static float up(double x) {
  double grown = x * (1 + 0x1p-40);
  float f = (float)grown;
  if ((double)f < grown) f = nextafterf(f, INFINITY);
  return f;
}

void rc_patch_net_differences(const float *net, float out[5]) {
  static const double first[2] = {-1, 1}, second[3] = {1, -2, 1}, mixed[4] = {1, -1, -1, 1};
  double best[5] = {0, 0, 0, 0, 0};
  double p[4][3];
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) {
      if (c < 3) {
        point(net, r, c, p[0]);
        point(net, r, c + 1, p[1]);
        best[0] = fmax(best[0], combination(p, first, 2));
      }
      if (r < 3) {
        point(net, r, c, p[0]);
        point(net, r + 1, c, p[1]);
        best[1] = fmax(best[1], combination(p, first, 2));
      }
      if (r < 3 && c < 3) {
        point(net, r, c, p[0]);
        point(net, r, c + 1, p[1]);
        point(net, r + 1, c, p[2]);
        point(net, r + 1, c + 1, p[3]);
        best[2] = fmax(best[2], combination(p, mixed, 4));
      }
      if (c < 2) {
        point(net, r, c, p[0]);
        point(net, r, c + 1, p[1]);
        point(net, r, c + 2, p[2]);
        best[3] = fmax(best[3], combination(p, second, 3));
      }
      if (r < 2) {
        point(net, r, c, p[0]);
        point(net, r + 1, c, p[1]);
        point(net, r + 2, c, p[2]);
        best[4] = fmax(best[4], combination(p, second, 3));
      }
    }
  for (int k = 0; k < 5; k++) out[k] = up(best[k]);  /* infinity stays infinity */
}

/* Piece i's net, from the texel array. */
static void piece_differences(const rc_packed_scene *p, uint32_t i, float out[5]) {
  float net[4 * RC_TEXELS_PER_PATCH];
  memcpy(net, &p->texels[4 * (size_t)p->quadrics[i].mesh_root], sizeof net);
  rc_patch_net_differences(net, out);
}

void rc_packed_patch_bounds(rc_packed_scene *p) {
  for (uint32_t i = 0; i < p->frame.quadric_count; i++) {
    packed_quadric *q = &p->quadrics[i];
    if (!(q->flags & RC_QUADRIC_PATCH)) continue;
    float d[5];
    piece_differences(p, i, d);
    q->linear = (vec3){d[0], d[1], d[2]};
    q->diag.z = d[3];
    q->off.z = d[4];
  }
}

bool rc_packed_patch_bounds_match(const rc_packed_scene *p, uint32_t *piece) {
  for (uint32_t i = 0; i < p->frame.quadric_count; i++) {
    const packed_quadric *q = &p->quadrics[i];
    if (!(q->flags & RC_QUADRIC_PATCH)) continue;
    float d[5];
    piece_differences(p, i, d);
    float have[5] = {q->linear.x, q->linear.y, q->linear.z, q->diag.z, q->off.z};
    if (memcmp(d, have, sizeof d) != 0) {
      *piece = i;
      return false;
    }
  }
  return true;
}
