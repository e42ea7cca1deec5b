/* check_levels_table.c: the levels table (host/image/levels8.h) against the formula it is
 * made from, on every float from 0 to just past 1, for four encodings, each rounded and
 * truncated (docs/numerics.md §11). Prints how many differ for each.
 *   gcc -O2 -ffp-contract=off -Ihost tools/check_levels_table.c host/image/levels8.c -lm \
 *     -o /tmp/check_levels_table && /tmp/check_levels_table */
#include "image/levels8.h"

#include <stdio.h>
#include <string.h>

int main(void) {
  const rc_encoding encodings[] = {
      {RC_CURVE_LINEAR, 1.0f, 0.0f}, {RC_CURVE_SRGB, 1.0f, 0.0f}, {RC_CURVE_GAMMA, 2.2f, 0.0f}, {RC_CURVE_GAMMA, 1.8f, 1.5f}};
  const char *names[] = {"linear", "srgb", "gamma 2.2", "gamma 1.8, exposure 1.5"};
  int failed = 0;
  for (int e = 0; e < 4; e++) {
    for (int truncate = 0; truncate < 2; truncate++) {
      rc_levels t;
      rc_levels_make(encodings[e], truncate, &t);
      unsigned long differ = 0;
      for (uint32_t u = 0; u <= 0x3f810000u; u++) { /* to 1.0078 */
        float v;
        memcpy(&v, &u, sizeof v);
        differ += rc_level_of(&t, v) != rc_level_formula(encodings[e], truncate, v);
      }
      printf("%s%s: %lu floats differ\n", names[e], truncate ? ", truncated" : "", differ);
      failed |= differ != 0;
    }
  }
  return failed;
}
