/* texture_levels.c: a texture's mip pyramid, built once on the host; both renderers read
 * the same texels (the shader and its CPU twin, rc_shade.glsl texture_color). */
#include "scene/texture_levels.h"

#include <string.h>

uint32_t rc_texture_level_count(uint32_t w, uint32_t h, bool mipmap) {
  uint32_t levels = 1;
  while (mipmap && (rc_texture_level_side(w, levels - 1) > 1 || rc_texture_level_side(h, levels - 1) > 1)) levels++;
  return levels;
}

size_t rc_texture_pyramid_texels(uint32_t w, uint32_t h, uint32_t levels) {
  size_t n = 0;
  for (uint32_t k = 0; k < levels; k++) n += (size_t)rc_texture_level_side(w, k) * rc_texture_level_side(h, k);
  return n;
}

static void put(uint32_t *out, size_t texel, const double rgb[3]) {
  const float rgba[4] = {(float)rgb[0], (float)rgb[1], (float)rgb[2], 1.0f};
  memcpy(&out[4 * texel], rgba, sizeof rgba);
}

static double channel(const uint32_t *out, size_t texel, int c) {
  float v;
  memcpy(&v, &out[4 * texel + (size_t)c], sizeof v);
  return v;
}

/* A box filter: texel (i, j) of level k is the mean of texels 2i, 2i + 1 by 2j, 2j + 1 of
 * level k - 1, an odd side's last column or row taken twice (a texel of weight 1 over a
 * half-texel border). Summed in f64 and rounded once: the mean of equal texels is that
 * texel exactly, so a constant texture stays constant at every level. */
void rc_texture_write_levels(const float *rgb, uint32_t w, uint32_t h, uint32_t levels, uint32_t first,
                             uint32_t *out, uint32_t *level_first) {
  size_t at = 0;
  for (size_t k = 0; k < (size_t)w * h; k++, at++) {
    const double c[3] = {rgb[3 * k], rgb[3 * k + 1], rgb[3 * k + 2]};
    put(out, at, c);
  }
  level_first[0] = first;
  size_t prev = 0;
  for (uint32_t k = 1; k < levels; k++) {
    uint32_t pw = rc_texture_level_side(w, k - 1), ph = rc_texture_level_side(h, k - 1);
    uint32_t lw = rc_texture_level_side(w, k), lh = rc_texture_level_side(h, k);
    level_first[k] = first + (uint32_t)at;
    for (uint32_t j = 0; j < lh; j++)
      for (uint32_t i = 0; i < lw; i++, at++) {
        uint32_t x0 = 2 * i, y0 = 2 * j;
        uint32_t x1 = x0 + 1 < pw ? x0 + 1 : pw - 1, y1 = y0 + 1 < ph ? y0 + 1 : ph - 1;
        double c[3];
        for (int ch = 0; ch < 3; ch++)
          c[ch] = 0.25 * (channel(out, prev + (size_t)y0 * pw + x0, ch) + channel(out, prev + (size_t)y0 * pw + x1, ch) +
                          channel(out, prev + (size_t)y1 * pw + x0, ch) + channel(out, prev + (size_t)y1 * pw + x1, ch));
        put(out, at, c);
      }
    prev = (size_t)level_first[k] - first;
  }
}
