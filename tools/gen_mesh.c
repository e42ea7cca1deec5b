/* gen_mesh: writes a procedural benchmark mesh as binary PLY: a sphere of radius 1 with a
 * bumpy surface (so triangles face every way and the BVH has real work), subdivided into
 * about N triangles (a latitude-longitude grid of 2 * rows * cols triangles).
 * Usage: gen_mesh N OUT.ply */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: gen_mesh TRIANGLES OUT.ply\n");
    return 2;
  }
  long n = atol(argv[1]);
  if (n < 8) n = 8;
  long rows = (long)sqrt((double)n / 4.0);
  if (rows < 2) rows = 2;
  long cols = n / (2 * rows);
  if (cols < 3) cols = 3;
  FILE *f = fopen(argv[2], "wb");
  if (!f) {
    perror(argv[2]);
    return 2;
  }
  long verts = (rows + 1) * cols, faces = 2 * rows * cols;
  fprintf(f, "ply\nformat binary_little_endian 1.0\nelement vertex %ld\nproperty float x\nproperty float y\n"
             "property float z\nelement face %ld\nproperty list uchar int vertex_indices\nend_header\n",
          verts, faces);
  for (long i = 0; i <= rows; i++) {
    double theta = M_PI * (double)i / rows;
    for (long j = 0; j < cols; j++) {
      double phi = 2 * M_PI * (double)j / cols;
      double r = 1.0 + 0.04 * sin(7 * theta) * cos(9 * phi) + 0.015 * sin(37 * theta + 3 * phi);
      float p[3] = {(float)(r * sin(theta) * cos(phi)), (float)(r * cos(theta)), (float)(r * sin(theta) * sin(phi))};
      fwrite(p, sizeof p, 1, f);
    }
  }
  for (long i = 0; i < rows; i++) {
    for (long j = 0; j < cols; j++) {
      int32_t a = (int32_t)(i * cols + j), b = (int32_t)(i * cols + (j + 1) % cols);
      int32_t c = (int32_t)((i + 1) * cols + j), d = (int32_t)((i + 1) * cols + (j + 1) % cols);
      uint8_t three = 3;
      int32_t t1[3] = {a, c, b}, t2[3] = {b, c, d};
      fwrite(&three, 1, 1, f), fwrite(t1, sizeof t1, 1, f);
      fwrite(&three, 1, 1, f), fwrite(t2, sizeof t2, 1, f);
    }
  }
  if (fclose(f) != 0) return 2;
  printf("%ld triangles (%ld at the poles are degenerate)\n", faces, 2 * cols);
  return 0;
}
