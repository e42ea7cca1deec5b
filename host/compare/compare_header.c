#include "compare/compare_header.h"

#include <stdio.h>
#include <string.h>

/* Settings are words "name=value" separated by single spaces (cli/part.c writes them). */
static size_t word_length(const char *s) {
  size_t n = 0;
  while (s[n] && s[n] != ' ') n++;
  return n;
}

/* Word of s at *at into name and value; advances *at. False at the end. */
static bool next_setting(const char *s, size_t *at, char name[32], char value[64]) {
  while (s[*at] == ' ') (*at)++;
  if (!s[*at]) return false;
  size_t n = word_length(s + *at);
  const char *eq = memchr(s + *at, '=', n);
  size_t key = eq ? (size_t)(eq - (s + *at)) : n;
  snprintf(name, 32, "%.*s", (int)key, s + *at);
  snprintf(value, 64, "%.*s", eq ? (int)(n - key - 1) : 0, eq ? eq + 1 : "");
  *at += n;
  return true;
}

bool rc_settings_value(const char *settings, const char *name, char *value, size_t len) {
  char k[32], v[64];
  for (size_t at = 0; next_setting(settings, &at, k, v);)
    if (strcmp(k, name) == 0) {
      snprintf(value, len, "%s", v);
      return true;
    }
  if (len) value[0] = '\0';
  return false;
}

static void record(rc_setting_difference *out, int max, int *n, const char *name, const char *a, const char *b) {
  if (*n < max) {
    snprintf(out[*n].name, sizeof out[*n].name, "%s", name);
    snprintf(out[*n].a, sizeof out[*n].a, "%s", a);
    snprintf(out[*n].b, sizeof out[*n].b, "%s", b);
  }
  (*n)++;
}

int rc_settings_differences(const char *x, const char *y, rc_setting_difference *out, int max) {
  int n = 0;
  char k[32], v[64], w[64];
  for (size_t at = 0; next_setting(x, &at, k, v);) {
    bool in_y = rc_settings_value(y, k, w, sizeof w);
    if (!in_y || strcmp(v, w) != 0) record(out, max, &n, k, v, in_y ? w : "");
  }
  for (size_t at = 0; next_setting(y, &at, k, v);)
    if (!rc_settings_value(x, k, w, sizeof w)) record(out, max, &n, k, "", v);
  return n;
}
