/* ref_random.c: mirrors shaders/rc_random.glsl (integer hash, f32 jitter). Compiled once:
 * both precisions use the same f32 sample positions, as the shader does. */
#include "ref/ref_shader.h"

uint32_t ref_hash_pcg(uint32_t v) {
  uint32_t state = v * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

float ref_hash_to_unit(uint32_t h) { return (float)(h >> 8u) * (1.0f / 16777216.0f); }

ref_vec2 ref_sample_offset(const ref_scene *sc, uint32_t px, uint32_t py, uint32_t s) {
  const packed_frame *f = sc->frame;
  if (f->samples_per_pixel == 1u) return (ref_vec2){0.5f, 0.5f};
  uint32_t h = ref_hash_pcg(px ^ ref_hash_pcg(py ^ ref_hash_pcg(s ^ ref_hash_pcg(f->seed))));
  float jx = ref_hash_to_unit(h), jy = ref_hash_to_unit(ref_hash_pcg(h));
  uint32_t cx = s % f->strata_x, cy = s / f->strata_x;
  return (ref_vec2){((float)cx + jx) * f->inv_strata_x, ((float)cy + jy) * f->inv_strata_y};
}
