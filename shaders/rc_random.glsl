// rc_random.glsl: sample positions inside a pixel. Seeded per (pixel, sample, scene seed),
// never per thread or workgroup, so tiles, batches and backends all see the same samples.

// PCG hash (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020).
uint hash_pcg(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// The top 24 bits as a float in [0, 1): exact in f32, so both backends get the same value.
float hash_to_unit(uint h) { return float(h >> 8u) * (1.0 / 16777216.0); }

// Stratified jitter on a strata_x x strata_y grid (host picks it); one sample takes the
// pixel centre, as in docs/design.md §1.
vec2 sample_offset(uvec2 pixel, uint s) {
  if (scene_samples_per_pixel() == 1u) return vec2(0.5);
  uint h = hash_pcg(pixel.x ^ hash_pcg(pixel.y ^ hash_pcg(s ^ hash_pcg(frame.seed))));
  vec2 jitter = vec2(hash_to_unit(h), hash_to_unit(hash_pcg(h)));
  uvec2 cell = uvec2(s % frame.strata_x, s / frame.strata_x);
  return (vec2(cell) + jitter) * vec2(frame.inv_strata_x, frame.inv_strata_y);
}
