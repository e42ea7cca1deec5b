#include "image/levels8.h"

#include <math.h>
#include <string.h>

/* IEC 61966-2-1's transfer curve on [0, 1]. */
static float srgb_encode(float x) {
  if (!(x > 0.0f)) return 0.0f;
  if (x >= 1.0f) return 1.0f;
  return x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
}

uint8_t rc_level_formula(rc_encoding enc, bool truncate, float v) {
  /* Exposure 0 multiplies by exactly 1: the linear and sRGB curves store what they stored
   * before exposure existed. */
  float x = v * exp2f(enc.exposure), e;
  if (enc.curve == RC_CURVE_SRGB) {
    e = srgb_encode(x);
  } else {
    x = x > 1.0f ? 1.0f : (x > 0.0f ? x : 0.0f);
    e = enc.curve == RC_CURVE_GAMMA ? powf(x, 1.0f / enc.gamma) : x;
  }
  /* A truncated value lies on a level, where rounding keeps it. */
  if (truncate) e = floorf(e * 255.0f) / 255.0f;
  return (uint8_t)roundf(e * 255.0f);
}

static uint32_t bits_of(float f) {
  uint32_t u;
  memcpy(&u, &f, sizeof u);
  return u;
}

static float float_of(uint32_t u) {
  float f;
  memcpy(&f, &u, sizeof f);
  return f;
}

/* The least non-negative float f with reaches(f): the non-negative floats are ordered as
 * their bit patterns, +inf (0x7f800000) last. +inf when none below it reaches. */
typedef bool (*reach_fn)(float f, const void *ctx);
static float least_reaching(reach_fn reaches, const void *ctx) {
  uint32_t lo = 0, hi = bits_of(INFINITY); /* the answer lies in [lo, hi] */
  while (lo < hi) {
    uint32_t mid = lo + (hi - lo) / 2;
    if (reaches(float_of(mid), ctx)) hi = mid;
    else lo = mid + 1;
  }
  return float_of(lo);
}

typedef struct {
  rc_encoding enc;
  bool truncate;
  unsigned level;
} level_goal;

static bool reaches_level(float f, const void *ctx) {
  const level_goal *g = ctx;
  return rc_level_formula(g->enc, g->truncate, f) >= g->level;
}

void rc_levels_make(rc_encoding enc, bool truncate, rc_levels *out) {
  out->threshold[0] = 0.0f;
  for (unsigned k = 1; k < RC_LEVELS; k++) {
    level_goal g = {enc, truncate, k};
    out->threshold[k] = least_reaching(reaches_level, &g);
  }
}

typedef struct {
  float value, spp;
} sum_goal;

static bool reaches_value(float s, const void *ctx) {
  const sum_goal *g = ctx;
  return s / g->spp >= g->value;
}

void rc_levels_of_sums(const rc_levels *values, uint32_t spp, rc_levels *out) {
  out->threshold[0] = 0.0f;
  for (unsigned k = 1; k < RC_LEVELS; k++) {
    sum_goal g = {values->threshold[k], (float)spp};
    out->threshold[k] = least_reaching(reaches_value, &g);
  }
}
