/* 8-bit levels (host/image/levels8.h): the table both the image writer and the shader
 * look levels up in gives the formula's level for every value, and its version for sums
 * of samples gives the level of sum / spp. No device, no file. */
#include "image/levels8.h"
#include "rc_test.h"

#include <stdint.h>
#include <string.h>

static float float_of(uint32_t u) {
  float f;
  memcpy(&f, &u, sizeof f);
  return f;
}

static uint32_t bits_of(float f) {
  uint32_t u;
  memcpy(&u, &f, sizeof u);
  return u;
}

/* Linear, sRGB, two powers (one under exposure), and each truncated (the CSE167 format). */
static const rc_encoding encodings[] = {
    {RC_CURVE_LINEAR, 1.0f, 0.0f}, {RC_CURVE_SRGB, 1.0f, 0.0f},    {RC_CURVE_GAMMA, 2.2f, 0.0f},
    {RC_CURVE_GAMMA, 1.8f, 1.5f},  {RC_CURVE_SRGB, 1.0f, -3.25f}, {RC_CURVE_LINEAR, 1.0f, 64.0f},
};
#define ENCODINGS (sizeof encodings / sizeof *encodings)

/* Every float within 64 steps of each threshold, and one in 4,099 of the floats up to
 * twice white: table and formula agree. (Every float in [0, 1.0078] was checked once for
 * the first four: docs/numerics.md §11.) */
TEST(table_is_the_formula) {
  for (size_t e = 0; e < ENCODINGS; e++) {
    for (int truncate = 0; truncate < 2; truncate++) {
      rc_levels t;
      rc_levels_make(encodings[e], truncate, &t);
      int wrong = 0;
      for (int k = 1; k < RC_LEVELS; k++) {
        CHECK(t.threshold[k] >= t.threshold[k - 1]);
        if (!(t.threshold[k] < INFINITY)) continue;
        uint32_t at = bits_of(t.threshold[k]);
        for (uint32_t u = at > 64 ? at - 64 : 0; u <= at + 64; u++)
          wrong += rc_level_of(&t, float_of(u)) != rc_level_formula(encodings[e], truncate, float_of(u));
      }
      for (uint32_t u = 0; u <= bits_of(2.0f); u += 4099)
        wrong += rc_level_of(&t, float_of(u)) != rc_level_formula(encodings[e], truncate, float_of(u));
      CHECK_EQ_INT(wrong, 0);
    }
  }
}

/* Values whose levels are known: the rounding is OpenImageIO's, half away from zero. */
TEST(known_levels) {
  rc_levels lin, srgb, trunc;
  rc_levels_make(encodings[0], false, &lin);
  rc_levels_make(encodings[1], false, &srgb);
  rc_levels_make(encodings[0], true, &trunc);
  CHECK_EQ_INT(rc_level_of(&lin, 0.0f), 0);
  CHECK_EQ_INT(rc_level_of(&lin, -1.0f), 0);
  CHECK_EQ_INT(rc_level_of(&lin, NAN), 0);
  CHECK_EQ_INT(rc_level_of(&lin, 1.0f), 255);
  CHECK_EQ_INT(rc_level_of(&lin, INFINITY), 255);
  CHECK_EQ_INT(rc_level_of(&lin, 0.5f), 128);   /* 127.5 rounds up */
  CHECK_EQ_INT(rc_level_of(&trunc, 0.5f), 127); /* and truncates down */
  CHECK_EQ_INT(rc_level_of(&lin, 0.5f / 255.0f), 1);
  /* Just below half a level: 0.49999997 of a level rounds to 0 (x + 0.5f would give 1). */
  CHECK_EQ_INT(rc_level_of(&lin, float_of(bits_of(0.5f / 255.0f) - 1)), 0);
  CHECK_EQ_INT(rc_level_of(&srgb, 0.5f), 188); /* 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 */
  CHECK_EQ_INT(rc_level_of(&srgb, 0.0031308f), 10);
}

/* The thresholds on sums: s >= threshold[k] exactly when s / spp reaches level k, around
 * every threshold and across the range, for several sample counts. */
TEST(sums_stand_for_values) {
  const uint32_t spps[] = {1, 3, 7, 16, 1000, 65536};
  for (size_t e = 0; e < 3; e++) {
    rc_levels values;
    rc_levels_make(encodings[e], false, &values);
    for (size_t i = 0; i < sizeof spps / sizeof *spps; i++) {
      rc_levels sums;
      rc_levels_of_sums(&values, spps[i], &sums);
      const float spp = (float)spps[i];
      int wrong = 0;
      for (int k = 1; k < RC_LEVELS; k++) {
        uint32_t at = bits_of(sums.threshold[k]);
        for (uint32_t u = at - 16; u <= at + 16; u++)
          wrong += rc_level_of(&sums, float_of(u)) != rc_level_of(&values, float_of(u) / spp);
      }
      for (uint32_t u = 0; u <= bits_of(2.0f * spp); u += 65537)
        wrong += rc_level_of(&sums, float_of(u)) != rc_level_of(&values, float_of(u) / spp);
      CHECK_EQ_INT(wrong, 0);
      if (spps[i] == 1) CHECK(memcmp(&sums, &values, sizeof sums) == 0);
    }
  }
}

int main(void) {
  TEST_MAIN_BEGIN
  RUN(table_is_the_formula);
  RUN(known_levels);
  RUN(sums_stand_for_values);
  TEST_MAIN_END
}
