#include "compare/heat_map.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare/compare.h"

/* 5x7 glyphs for the legend's labels: one byte per row, the low five bits left to right. */
static const struct {
  char c;
  unsigned char rows[7];
} glyphs[] = {
    {'0', {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}}, {'1', {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e}},
    {'2', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}}, {'3', {0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e}},
    {'4', {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}}, {'5', {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e}},
    {'6', {0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e}}, {'7', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}}, {'9', {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c}},
    {'e', {0x00, 0x00, 0x0e, 0x11, 0x1f, 0x10, 0x0e}}, {'-', {0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00}}, {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c}},
    {'N', {0x11, 0x19, 0x15, 0x13, 0x11, 0x11, 0x11}}, {'a', {0x00, 0x00, 0x0e, 0x01, 0x0f, 0x11, 0x0f}},
    {'f', {0x06, 0x09, 0x08, 0x1c, 0x08, 0x08, 0x08}}, {'i', {0x04, 0x00, 0x0c, 0x04, 0x04, 0x04, 0x0e}},
    {'l', {0x0c, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e}},
};
enum { GLYPH_ADVANCE = 6 };

typedef struct {
  float *rgb;
  int w, h;
} canvas;

static void put(const canvas *cv, int x, int y, const float c[3]) {
  if (x < 0 || y < 0 || x >= cv->w || y >= cv->h) return;
  memcpy(cv->rgb + 3 * ((size_t)y * cv->w + x), c, 3 * sizeof(float));
}

static void fill_rect(const canvas *cv, int x0, int y0, int x1, int y1, const float c[3]) {
  for (int y = y0; y < y1; y++)
    for (int x = x0; x < x1; x++) put(cv, x, y, c);
}

static void text(const canvas *cv, int x, int y, const char *s, const float c[3]) {
  for (; *s; s++, x += GLYPH_ADVANCE)
    for (size_t g = 0; g < sizeof glyphs / sizeof *glyphs; g++) {
      if (glyphs[g].c != *s) continue;
      for (int r = 0; r < 7; r++)
        for (int k = 0; k < 5; k++)
          if (glyphs[g].rows[r] >> (4 - k) & 1) put(cv, x + k, y + r, c);
    }
}

static int text_width(const char *s) { return (int)strlen(s) * GLYPH_ADVANCE - 1; }

void rc_heat_colour(double t, float out[3]) {
  static const float stops[5][3] = {
      {0.15f, 0.10f, 0.55f}, {0.10f, 0.45f, 0.95f}, {0.10f, 0.80f, 0.45f}, {0.98f, 0.80f, 0.10f}, {0.95f, 0.10f, 0.05f}};
  if (!(t >= 0)) t = 0;
  if (t > 1) t = 1;
  double s = t * 4;
  int i = s >= 4 ? 3 : (int)s;
  double f = s - i;
  for (int k = 0; k < 3; k++) out[k] = (float)(stops[i][k] + f * (stops[i + 1][k] - stops[i][k]));
}

static const float NAN_COLOUR[3] = {1, 0, 1}, WHITE[3] = {1, 1, 1}, PANEL[3] = {0.06f, 0.06f, 0.06f};

static double position(const rc_heat_scale *s, double e) {
  return (log10(e) - log10(s->lo)) / (log10(s->hi) - log10(s->lo));
}

void rc_heat_map_size(int w, int h, int *out_w, int *out_h) {
  *out_w = w > RC_HEAT_MIN_WIDTH ? w : RC_HEAT_MIN_WIDTH;
  *out_h = h + RC_HEAT_LEGEND;
}

/* The reference's brightness, faint: enough to recognise the scene, dark enough that
 * every colour of the bar stands out on it. */
static void underlay(const float *b, int c, const bool *colour, size_t p, float out[3]) {
  double sum = 0;
  int n = 0;
  for (int k = 0; k < c && n < 3; k++)
    if (!colour || colour[k]) sum += isfinite(b[p * c + k]) ? fmin(1.0, fmax(0.0, b[p * c + k])) : 0, n++;
  float g = (float)(0.08 + 0.30 * sqrt(n ? sum / n : 0));
  out[0] = out[1] = out[2] = g;
}

static void pixel_colour(const rc_heat_scale *s, double e, const float bg[3], float out[3]) {
  if (isinf(e)) {
    memcpy(out, NAN_COLOUR, sizeof NAN_COLOUR);
    return;
  }
  if (!(e > s->lo)) {
    memcpy(out, bg, 3 * sizeof(float));
    return;
  }
  float heat[3];
  double t = position(s, e);
  rc_heat_colour(t, heat);
  /* The smallest differences tint the underlay; from mid-scale up they cover it. */
  float alpha = (float)fmin(1.0, 0.45 + 0.55 * 2 * t);
  for (int k = 0; k < 3; k++) out[k] = bg[k] + alpha * (heat[k] - bg[k]);
}

/* Pixel (x, y) enlarged to 3 x 3 in its colour, and a white ring of radius 4-5 around
 * it; neither covers another pixel that is over the mark. */
static void ring(const canvas *cv, const unsigned char *over, int w, int h, int x, int y, const float c[3]) {
  for (int dy = -5; dy <= 5; dy++)
    for (int dx = -5; dx <= 5; dx++) {
      int d2 = dx * dx + dy * dy, px = x + dx, py = y + dy;
      bool block = dx >= -1 && dx <= 1 && dy >= -1 && dy <= 1;
      if ((!block && (d2 < 16 || d2 > 25)) || px < 0 || py < 0 || px >= w || py >= h || over[(size_t)py * w + px])
        continue;
      put(cv, px, py, block ? c : WHITE);
    }
}

static void legend(const canvas *cv, int top, const rc_heat_scale *s) {
  fill_rect(cv, 0, top, cv->w, cv->h, PANEL);
  int x0 = 10, x1 = cv->w - 50, y0 = top + 11, y1 = top + 21;
  for (int x = x0; x < x1; x++) {
    float c[3];
    rc_heat_colour((double)(x - x0) / (x1 - 1 - x0), c);
    fill_rect(cv, x, y0, x + 1, y1, c);
  }
  /* A tick and a label per decade; labels thinned so that they never overlap. */
  int first = (int)ceil(log10(s->lo) - 1e-9), last = (int)floor(log10(s->hi) + 1e-9);
  int decades = last - first + 1, step = 1;
  while (decades > 1 && (double)(x1 - x0) * step / (decades - 1) < 34) step++;
  for (int k = first; k <= last; k++) {
    int x = x0 + (int)lround(position(s, pow(10, k)) * (x1 - 1 - x0));
    fill_rect(cv, x, y1, x + 1, y1 + 3, WHITE);
    if ((k - first) % step) continue;
    char label[16];
    snprintf(label, sizeof label, "1e%d", k);
    int lx = x - text_width(label) / 2;
    if (lx < 1) lx = 1;
    if (lx + text_width(label) > x1 + 8) lx = x1 + 8 - text_width(label);
    text(cv, lx, y1 + 5, label, WHITE);
  }
  if (s->mark > s->lo && s->mark < s->hi) {
    int x = x0 + (int)lround(position(s, s->mark) * (x1 - 1 - x0));
    fill_rect(cv, x, y0 - 3, x + 1, y1, WHITE);
    text(cv, x - text_width("fail") / 2, top + 1, "fail", WHITE);
  }
  fill_rect(cv, cv->w - 40, y0, cv->w - 30, y1, NAN_COLOUR);
  text(cv, cv->w - 26, y0 + 2, "NaN", WHITE);
}

uint64_t rc_heat_map_draw(const float *a, const float *b, int w, int h, int c, const bool *colour,
                          const rc_heat_scale *s, float *rgb) {
  canvas cv;
  rc_heat_map_size(w, h, &cv.w, &cv.h);
  cv.rgb = rgb;
  fill_rect(&cv, 0, 0, cv.w, h, PANEL);
  uint64_t over = 0;
  for (size_t p = 0; p < (size_t)w * h; p++) {
    int channel;
    double e = rc_compare_pixel_error(a, b, c, colour, p, &channel);
    float bg[3], out[3];
    underlay(b, c, colour, p, bg);
    pixel_colour(s, e, bg, out);
    put(&cv, (int)(p % w), (int)(p / w), out);
    over += e > s->mark;
  }
  uint64_t ringed = 0;
  unsigned char *mask = over && over <= RC_HEAT_MAX_RINGS ? calloc((size_t)w * h, 1) : NULL;
  if (mask) {
    for (size_t p = 0; p < (size_t)w * h; p++) {
      int channel;
      mask[p] = rc_compare_pixel_error(a, b, c, colour, p, &channel) > s->mark;
    }
    for (size_t p = 0; p < (size_t)w * h; p++) {
      if (!mask[p]) continue;
      float out[3];
      memcpy(out, rgb + 3 * ((p / w) * cv.w + p % w), sizeof out);
      ring(&cv, mask, w, h, (int)(p % w), (int)(p / w), out);
      ringed++;
    }
    free(mask);
  }
  legend(&cv, h, s);
  return ringed;
}
