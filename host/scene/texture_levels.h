#ifndef RC_TEXTURE_LEVELS_H
#define RC_TEXTURE_LEVELS_H
/* A texture's mip levels (packed_texture in rc_shared.h, docs/scene-format.md "Textures"):
 * level k is ceil(w / 2^k) x ceil(h / 2^k) texels, down to 1 x 1. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* How many levels a w x h image has: 1 without mip-mapping, else 1 + ceil(log2(max(w, h))). */
uint32_t rc_texture_level_count(uint32_t w, uint32_t h, bool mipmap);

/* Level k's side for a side of n texels at level 0: ceil(n / 2^k), as the shader computes it. */
static inline uint32_t rc_texture_level_side(uint32_t n, uint32_t k) { return ((n - 1u) >> k) + 1u; }

/* The texels of all `levels` levels together. */
size_t rc_texture_pyramid_texels(uint32_t w, uint32_t h, uint32_t levels);

/* Writes the levels of the w x h RGB image `rgb` (row 0 the top) as RGBA f32 texels, 4
 * words each, into `out` (rc_texture_pyramid_texels of them), level 0 the image itself, and
 * each level's first texel, counted from `first`, into level_first[0..levels). */
void rc_texture_write_levels(const float *rgb, uint32_t w, uint32_t h, uint32_t levels, uint32_t first,
                             uint32_t *out, uint32_t *level_first);
#endif
