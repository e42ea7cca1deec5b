#include "compare/aov.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The digest's low 24 bits: every such integer is exact in a float channel. */
#define RC_AOV_DIGEST_MASK 0xffffffu

const char *const rc_aov_channel_names[RC_AOV_CHANNELS] = {"R", "G", "B", "hit", "object", "t",
                                                           "N.X", "N.Y", "N.Z", "shadow", "uncertified", "decisions"};

void rc_aov_pack(const float *rgb, const packed_aov *aov, size_t count, double length_unit, float *out) {
  for (size_t i = 0; i < count; i++) {
    const packed_aov *a = &aov[i];
    const float v[RC_AOV_CHANNELS] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], a->hit,      a->object,
                                      (float)(a->t * length_unit), a->normal.x,    a->normal.y,    a->normal.z, a->shadow_bits,
                                      a->uncertified, (float)(a->decisions & RC_AOV_DIGEST_MASK)};
    memcpy(out + i * RC_AOV_CHANNELS, v, sizeof v);
  }
}

static int find(char names[][32], int count, const char *name) {
  for (int i = 0; i < count; i++)
    if (strcmp(names[i], name) == 0) return i;
  return -1;
}

bool rc_aov_find_channels(char names[][32], int count, rc_aov_layout *layout) {
  for (int i = 0; i < RC_AOV_REQUIRED_CHANNELS; i++)
    if (find(names, count, rc_aov_channel_names[i]) < 0) return false;
  int *slots[RC_AOV_CHANNELS] = {&layout->r,  &layout->g,  &layout->b,      &layout->hit,         &layout->object,
                                 &layout->t,  &layout->nx, &layout->ny,     &layout->nz,          &layout->shadow,
                                 &layout->uncertified,     &layout->decisions};
  for (int i = 0; i < RC_AOV_CHANNELS; i++) *slots[i] = find(names, count, rc_aov_channel_names[i]);
  return true;
}

bool rc_aov_same_decisions(const float *a, const rc_aov_layout *la, const float *b, const rc_aov_layout *lb, int c,
                           size_t i) {
  const float *x = a + i * c, *y = b + i * c;
  bool samples = la->decisions < 0 || lb->decisions < 0 || x[la->decisions] == y[lb->decisions];
  return x[la->hit] == y[lb->hit] && x[la->object] == y[lb->object] && x[la->shadow] == y[lb->shadow] && samples;
}

void rc_aov_compare_decisions(const float *a, const rc_aov_layout *la, const float *b, const rc_aov_layout *lb, int w,
                              int h, int c, const unsigned char *band, rc_compare_result *r) {
  r->decisions = true;
  r->digests = la->decisions >= 0 && lb->decisions >= 0;
  double sum2 = 0;
  bool nonfinite = false;
  for (size_t i = 0; i < (size_t)w * h; i++) {
    const float *x = a + i * c, *y = b + i * c;
    bool same_hit = x[la->hit] == y[lb->hit];
    bool same_object = same_hit && x[la->object] == y[lb->object];
    bool same_decisions = same_object && x[la->shadow] == y[lb->shadow];
    /* Every sample's, bounces included: the digests. */
    bool same_samples = !r->digests || x[la->decisions] == y[lb->decisions];
    if (same_decisions && same_samples) {
      r->pixels_alike++;
      const int ka[3] = {la->r, la->g, la->b}, kb[3] = {lb->r, lb->g, lb->b};
      for (int k = 0; k < 3; k++) {
        double e = rc_compare_channel_error(x[ka[k]], y[kb[k]], &nonfinite);
        if (isfinite(e)) sum2 += e * e;
      }
    }
    r->a_hits += x[la->hit] != 0;
    r->b_hits += y[lb->hit] != 0;
    r->a_shadowed += x[la->shadow] != 0;
    r->b_shadowed += y[lb->shadow] != 0;
    if (band && band[i]) {
      r->band_pixels++;
      r->certified_in_band += la->uncertified >= 0 && x[la->uncertified] == 0;
      continue;
    }
    r->hit_mismatch += !same_hit;
    r->object_mismatch += same_hit && !same_object;
    r->shadow_mismatch += same_object && !same_decisions;
    r->sample_mismatch += !same_samples;
    /* A's certified pixels (--precision certified): their decisions, in every sample where
     * the digests say, are claimed to be the f64 reference's, so against it any difference
     * is a broken certificate. */
    bool certified = la->uncertified >= 0 && x[la->uncertified] == 0;
    r->uncertified_pixels += la->uncertified >= 0 && x[la->uncertified] != 0;
    r->certified_mismatch += certified && !(same_decisions && same_samples);
    if (!same_object || y[lb->hit] == 0) continue;
    /* Depth relative to the reference's; the normal as the angle between the two. */
    double tb = y[lb->t], dt = fabs((double)x[la->t] - tb) / (tb != 0 ? fabs(tb) : 1);
    if (!(dt <= r->max_depth_rel)) r->max_depth_rel = isnan(dt) ? INFINITY : dt;
    /* The angle as atan2(|a x b|, a . b): exact 0 for equal vectors (acos of a rounded
     * cosine is not) and well conditioned near 0 and pi. */
    double ax = x[la->nx], ay = x[la->ny], az = x[la->nz], bx = y[lb->nx], by = y[lb->ny], bz = y[lb->nz];
    double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    double angle = atan2(sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz);
    if (!(angle <= r->max_normal_angle)) r->max_normal_angle = isnan(angle) ? INFINITY : angle;
  }
  double mse = r->pixels_alike ? sum2 / (3.0 * (double)r->pixels_alike) : 0;
  r->psnr_alike = nonfinite ? NAN : mse > 0 ? 10.0 * log10(1.0 / mse) : INFINITY;
}
