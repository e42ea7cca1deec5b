/* rcm_mat3.h: the few f64 3x3 matrix helpers the host needs (row-major double[3][3]).
 * Functions: rcm_mat3_det_d, rcm_mat3_inverse_d, rcm_mat3_rotation_d. */
#ifndef RCM_MAT3_H
#define RCM_MAT3_H

#include <math.h>
#include <stdbool.h>

#include "math/rcm_vec3.h"

static inline double rcm_mat3_det_d(const double a[3][3]) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

/* The inverse by cofactors; false (out untouched) for a singular or non-finite matrix. */
static inline bool rcm_mat3_inverse_d(const double a[3][3], double out[3][3]) {
  double det = rcm_mat3_det_d(a);
  if (!(fabs(det) > 0) || !isfinite(det)) return false;
  double r[3][3] = {{(a[1][1] * a[2][2] - a[1][2] * a[2][1]) / det, (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det,
                     (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det},
                    {(a[1][2] * a[2][0] - a[1][0] * a[2][2]) / det, (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det,
                     (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det},
                    {(a[1][0] * a[2][1] - a[1][1] * a[2][0]) / det, (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det,
                     (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) out[i][j] = r[i][j];
  return true;
}

/* Rodrigues' rotation by deg degrees about a unit axis (right-handed). */
static inline void rcm_mat3_rotation_d(dvec3 axis, double deg, double m[3][3]) {
  double t = deg * M_PI / 180.0, c = cos(t), s = sin(t), x = axis.x, y = axis.y, z = axis.z;
  double r[3][3] = {{c + (1 - c) * x * x, (1 - c) * x * y - s * z, (1 - c) * x * z + s * y},
                    {(1 - c) * y * x + s * z, c + (1 - c) * y * y, (1 - c) * y * z - s * x},
                    {(1 - c) * z * x - s * y, (1 - c) * z * y + s * x, c + (1 - c) * z * z}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) m[i][j] = r[i][j];
}

#endif
