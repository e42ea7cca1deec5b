/* tradeoff_report.c: the trade-off's rows summarised per variant and spp, the Pareto
 * front, the table, and the plot as SVG (no plotting program needed: the user's machine
 * has what vkraycast needs and no more). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/rc_base.h"
#include "cli/tradeoff.h"
#include "image/image_io.h"

const char rc_tradeoff_csv_header[] =
    "scene,variant,spp,precision,render_ms,wall_ms,cpu_ms,mrays_per_s,decision_mismatch_pct,hit_mismatch_pct,"
    "object_mismatch_pct,shadow_mismatch_pct,psnr_db,rms_error,max_error,status";

/* CSV has no infinity: identical images (PSNR infinite) are written "inf", as strtod
 * reads it back; a value that was not measured is empty. */
static void number(FILE *f, double v) {
  if (isnan(v))
    fputs(",", f);
  else if (isinf(v))
    fputs(v > 0 ? ",inf" : ",-inf", f);
  else
    fprintf(f, ",%.9g", v);
}

void rc_tradeoff_write_row(FILE *f, const rc_tradeoff_row *r) {
  char spp[16] = "scene"; /* 0: each scene's own */
  if (r->spp) snprintf(spp, sizeof spp, "%u", r->spp);
  fprintf(f, "%s,%s,%s,%s", r->scene, r->variant, spp, r->precision[0] ? r->precision : "");
  const double v[] = {r->render_ms,  r->wall_ms, r->cpu_ms, r->mrays_per_s, r->mismatch_pct, r->hit_pct,
                      r->object_pct, r->shadow_pct, r->psnr, r->rms,         r->max_error};
  for (size_t i = 0; i < sizeof v / sizeof *v; i++) number(f, v[i]);
  /* The status is free text: commas would split it. */
  fputc(',', f);
  for (const char *p = r->status; *p; p++) fputc(*p == ',' || *p == '\n' ? ';' : *p, f);
  fputc('\n', f);
}

/* The next comma-separated field of *p into out. */
static void field(const char **p, char *out, size_t len) {
  size_t n = strcspn(*p, ",\n");
  snprintf(out, len, "%.*s", (int)n, *p);
  *p += n + ((*p)[n] == ',');
}

bool rc_tradeoff_parse_row(const char *line, rc_tradeoff_row *r) {
  memset(r, 0, sizeof *r);
  char text[128];
  const char *p = line;
  field(&p, r->scene, sizeof r->scene);
  field(&p, r->variant, sizeof r->variant);
  field(&p, text, sizeof text);
  bool own = strcmp(text, "scene") == 0;
  r->spp = (unsigned)strtoul(text, NULL, 10);
  field(&p, r->precision, sizeof r->precision);
  double *v[] = {&r->render_ms,  &r->wall_ms, &r->cpu_ms, &r->mrays_per_s, &r->mismatch_pct, &r->hit_pct,
                 &r->object_pct, &r->shadow_pct, &r->psnr, &r->rms,         &r->max_error};
  for (size_t i = 0; i < sizeof v / sizeof *v; i++) {
    field(&p, text, sizeof text);
    *v[i] = text[0] ? strtod(text, NULL) : NAN;
  }
  field(&p, r->status, sizeof r->status);
  return r->scene[0] && r->variant[0] && (r->spp > 0 || own) && r->status[0];
}

/* "16", or "scene" for 0: each scene's own. */
static const char *spp_text(unsigned spp, char buf[16]) {
  if (!spp) return "scene";
  snprintf(buf, 16, "%u", spp);
  return buf;
}

/* One (variant, spp) over every scene. */
typedef struct {
  const char *variant;
  size_t variant_index;
  unsigned spp;
  double ms, wall_ms, cpu_ms, mismatch, hit, object, shadow, psnr;
  size_t failed;
  bool pareto;
} summary;

/* Sums times, averages mismatch shares, and takes the PSNR of the scenes' mean MSE (a
 * scene rendered exactly, MSE 0, counts as no error, not as an infinite PSNR). */
static size_t summarise(const rc_tradeoff_row *rows, size_t n, const rc_tradeoff_summary_info *info, summary *out) {
  size_t m = 0;
  for (size_t i = 0; i < n; i++) {
    size_t k = 0;
    while (k < m && !(strcmp(out[k].variant, rows[i].variant) == 0 && out[k].spp == rows[i].spp)) k++;
    if (k == m) {
      memset(&out[m], 0, sizeof out[m]);
      out[m].variant = rows[i].variant;
      out[m].spp = rows[i].spp;
      for (size_t v = 0; v < info->variant_count; v++)
        if (strcmp(info->variants[v].name, rows[i].variant) == 0) out[m].variant_index = v;
      m++;
    }
    summary *s = &out[k];
    if (strcmp(rows[i].status, "ok") != 0) {
      s->failed++;
      continue;
    }
    s->ms += rows[i].render_ms, s->wall_ms += rows[i].wall_ms, s->cpu_ms += rows[i].cpu_ms;
    s->mismatch += rows[i].mismatch_pct, s->hit += rows[i].hit_pct;
    s->object += rows[i].object_pct, s->shadow += rows[i].shadow_pct;
    s->psnr += rows[i].rms * rows[i].rms; /* the MSE, for now */
  }
  for (size_t k = 0; k < m; k++) {
    double scenes = (double)info->scene_count;
    summary *s = &out[k];
    s->mismatch /= scenes, s->hit /= scenes, s->object /= scenes, s->shadow /= scenes;
    double mse = s->psnr / scenes;
    s->psnr = s->failed ? NAN : mse > 0 ? 10 * log10(1 / mse) : INFINITY;
  }
  /* The Pareto front: no other complete point both as fast and as accurate, and better
   * in one of the two. */
  for (size_t i = 0; i < m; i++) {
    out[i].pareto = !out[i].failed;
    for (size_t j = 0; j < m && out[i].pareto; j++)
      if (j != i && !out[j].failed && out[j].ms <= out[i].ms && out[j].mismatch <= out[i].mismatch &&
          (out[j].ms < out[i].ms || out[j].mismatch < out[i].mismatch))
        out[i].pareto = false;
  }
  return m;
}

/* A file in memory, written all-or-nothing as every vkraycast output is. */
static int commit(const char *dir, const char *name, char *text, size_t len) {
  char path[PATH_MAX + 64], err[512];
  if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, name) >= sizeof path) {
    rc_error("%s: the folder's name is too long", dir);
    free(text);
    return -1;
  }
  rc_image_writer *w = rc_file_writer_open(path, text, len, err, sizeof err);
  free(text);
  if (!w || rc_image_writer_close(w, 1, err, sizeof err) != 0) {
    rc_error("%s: cannot write: %s", path, err);
    return -1;
  }
  return 0;
}

static int write_summary(const char *dir, const summary *s, size_t m) {
  char *text = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  if (!f) return -1;
  fputs("variant,spp,render_ms_sum,wall_ms_sum,cpu_ms_sum,decision_mismatch_pct_mean,hit_mismatch_pct_mean,"
        "object_mismatch_pct_mean,shadow_mismatch_pct_mean,psnr_db_of_mean_mse,pareto,failed_points\n", f);
  for (size_t k = 0; k < m; k++) {
    if (s[k].spp)
      fprintf(f, "%s,%u", s[k].variant, s[k].spp);
    else
      fprintf(f, "%s,scene", s[k].variant);
    const double v[] = {s[k].ms, s[k].wall_ms, s[k].cpu_ms, s[k].mismatch, s[k].hit, s[k].object, s[k].shadow,
                        s[k].psnr};
    for (size_t i = 0; i < sizeof v / sizeof *v; i++) number(f, v[i]);
    fprintf(f, ",%s,%zu\n", s[k].pareto ? "yes" : "", s[k].failed);
  }
  fclose(f);
  return commit(dir, "tradeoff-summary.csv", text, len);
}

static void print_table(const summary *s, size_t m, const rc_tradeoff_summary_info *info, FILE *out) {
  char buf[16];
  fprintf(out, "| variant | spp | time ms (sum of %zu scene%s) | decisions differ %% (mean: hit / object / shadow) | "
               "PSNR dB vs %u spp | Pareto |\n|---|---|---|---|---|---|\n",
          info->scene_count, info->scene_count == 1 ? "" : "s", info->reference_spp);
  for (size_t k = 0; k < m; k++) {
    if (s[k].failed) {
      fprintf(out, "| %s | %s | %zu point(s) failed | | | |\n", s[k].variant, spp_text(s[k].spp, buf), s[k].failed);
      continue;
    }
    fprintf(out, "| %s | %s | %.1f | %.4g (%.3g / %.3g / %.3g) | ", s[k].variant, spp_text(s[k].spp, buf), s[k].ms,
            s[k].mismatch,
            s[k].hit, s[k].object, s[k].shadow);
    if (isinf(s[k].psnr))
      fputs("exact", out);
    else
      fprintf(out, "%.2f", s[k].psnr);
    fprintf(out, " | %s |\n", s[k].pareto ? "yes" : "");
  }
}

/* ---- the plot ---------------------------------------------------------------------- */

enum { SVG_W = 1000, SVG_H = 600, PX0 = 100, PX1 = 610, PY0 = 50, PY1 = 520, LEGEND_X = 640 };

static const char *const palette[] = {"#d62728", "#ff7f0e", "#bcbd22", "#8c564b", "#9467bd",
                                      "#1f77b4", "#2ca02c", "#e377c2", "#17becf", "#7f7f7f"};
/* Dashes and markers differ too, so that lines lying on one another stay apart. */
static const char *const dashes[] = {"", "8 4", "2 3", "10 3 2 3", "5 5", "", "1 2", "6 2", "3 6", "12 4"};

static void marker(FILE *f, int shape, double x, double y, const char *colour) {
  switch (shape % 4) {
  case 0:
    fprintf(f, "<circle cx='%.1f' cy='%.1f' r='4.5' fill='%s'/>", x, y, colour);
    break;
  case 1:
    fprintf(f, "<rect x='%.1f' y='%.1f' width='8' height='8' fill='%s'/>", x - 4, y - 4, colour);
    break;
  case 2:
    fprintf(f, "<path d='M%.1f %.1f l5 9 h-10 z' fill='%s'/>", x, y - 5.5, colour);
    break;
  default:
    fprintf(f, "<path d='M%.1f %.1f l5 5 l-5 5 l-5 -5 z' fill='%s'/>", x, y - 5, colour);
    break;
  }
}

typedef struct {
  double x_lo, x_hi, y_lo, y_hi, floor; /* log10 ranges; mismatch shares below floor sit on it */
} axes;

static double px(const axes *a, double ms) { return PX0 + (log10(ms) - a->x_lo) / (a->x_hi - a->x_lo) * (PX1 - PX0); }
static double py(const axes *a, double pct) {
  double v = log10(pct > a->floor ? pct : a->floor);
  return PY1 - (v - a->y_lo) / (a->y_hi - a->y_lo) * (PY1 - PY0);
}

static axes choose_axes(const summary *s, size_t m) {
  double t0 = INFINITY, t1 = 0, e0 = INFINITY, e1 = 0;
  for (size_t k = 0; k < m; k++) {
    if (s[k].failed || !(s[k].ms > 0)) continue;
    t0 = fmin(t0, s[k].ms), t1 = fmax(t1, s[k].ms);
    if (s[k].mismatch > 0) e0 = fmin(e0, s[k].mismatch), e1 = fmax(e1, s[k].mismatch);
  }
  if (!isfinite(t0)) t0 = 1, t1 = 10;
  if (!isfinite(e0)) e0 = 1e-3, e1 = 1e-2;
  axes a;
  a.x_lo = floor(log10(t0)), a.x_hi = ceil(log10(t1));
  if (a.x_hi <= a.x_lo) a.x_hi = a.x_lo + 1;
  /* 0 % has no logarithm: it is drawn on a line one decade below the smallest share. */
  a.y_lo = floor(log10(e0)) - 1, a.y_hi = ceil(log10(e1));
  if (a.y_hi <= a.y_lo + 1) a.y_hi = a.y_lo + 2;
  a.floor = pow(10, a.y_lo);
  return a;
}

static void svg_grid(FILE *f, const axes *a, const rc_tradeoff_summary_info *info) {
  fprintf(f, "<rect x='%d' y='%d' width='%d' height='%d' fill='white' stroke='#444'/>\n", PX0, PY0, PX1 - PX0,
          PY1 - PY0);
  for (int d = (int)a->x_lo; d <= (int)a->x_hi; d++) {
    double x = px(a, pow(10, d));
    fprintf(f, "<line x1='%.1f' y1='%d' x2='%.1f' y2='%d' stroke='#ddd'/>", x, PY0, x, PY1);
    fprintf(f, "<text x='%.1f' y='%d' text-anchor='middle'>%g</text>\n", x, PY1 + 18, pow(10, d));
    /* 2 and 5 of each decade too where the axis spans few decades. */
    for (int m = 2; d < (int)a->x_hi && a->x_hi - a->x_lo <= 2 && m <= 5; m += 3) {
      double xm = px(a, m * pow(10, d));
      fprintf(f, "<line x1='%.1f' y1='%d' x2='%.1f' y2='%d' stroke='#eee'/>", xm, PY0, xm, PY1);
      fprintf(f, "<text x='%.1f' y='%d' text-anchor='middle' fill='#666'>%g</text>\n", xm, PY1 + 18, m * pow(10, d));
    }
  }
  for (int d = (int)a->y_lo; d <= (int)a->y_hi; d++) {
    double y = py(a, pow(10, d));
    fprintf(f, "<line x1='%d' y1='%.1f' x2='%d' y2='%.1f' stroke='#ddd'/>", PX0, y, PX1, y);
    if (d == (int)a->y_lo)
      fprintf(f, "<text x='%d' y='%.1f' text-anchor='end'>0 (&lt;%g)</text>\n", PX0 - 6, y + 4, pow(10, d));
    else
      fprintf(f, "<text x='%d' y='%.1f' text-anchor='end'>%g</text>\n", PX0 - 6, y + 4, pow(10, d));
  }
  char size[64] = "each scene's own size";
  if (info->width && info->height) snprintf(size, sizeof size, "%ux%u", info->width, info->height);
  fprintf(f, "<text x='%d' y='%d' text-anchor='middle'>time, ms (sum over %zu scene%s, %s, %s)</text>\n",
          (PX0 + PX1) / 2, PY1 + 40, info->scene_count, info->scene_count == 1 ? "" : "s", info->device, size);
  fprintf(f, "<text transform='translate(24 %d) rotate(-90)' text-anchor='middle'>first-sample decisions that differ "
             "from CPU f64, %% of pixels (mean)</text>\n", (PY0 + PY1) / 2);
  fprintf(f, "<text x='%d' y='28' font-size='15' font-weight='bold'>What accuracy costs: each line one variant, "
             "its points labelled with their spp</text>\n", PX0);
}

/* The legend: a line and marker per variant, its name and what it sets (wrapped). */
static void svg_legend(FILE *f, const rc_tradeoff_summary_info *info) {
  double y = PY0 + 6;
  for (size_t v = 0; v < info->variant_count; v++) {
    const char *c = palette[v % 10];
    fprintf(f, "<line x1='%d' y1='%.1f' x2='%d' y2='%.1f' stroke='%s' stroke-width='2.5' stroke-dasharray='%s'/>",
            LEGEND_X, y, LEGEND_X + 34, y, c, dashes[v % 10]);
    marker(f, (int)v, LEGEND_X + 17, y, c);
    fprintf(f, "<text x='%d' y='%.1f' font-weight='bold'>%s</text>\n", LEGEND_X + 42, y + 4, info->variants[v].name);
    /* The explanation in lines of at most 46 characters, broken at spaces. */
    const char *w = info->variants[v].what;
    while (*w) {
      y += 15;
      size_t n = strlen(w);
      if (n > 46) {
        n = 46;
        while (n > 0 && w[n] != ' ') n--;
        if (n == 0) n = 46;
      }
      fprintf(f, "<text x='%d' y='%.1f' fill='#444'>", LEGEND_X + 42, y + 4);
      for (size_t i = 0; i < n; i++) {
        if (w[i] == '<') fputs("&lt;", f);
        else if (w[i] == '&') fputs("&amp;", f);
        else if (w[i] == '>') fputs("&gt;", f);
        else fputc(w[i], f);
      }
      fputs("</text>\n", f);
      w += n;
      while (*w == ' ') w++;
    }
    y += 24;
  }
  fprintf(f, "<circle cx='%d' cy='%.1f' r='9' fill='none' stroke='black' stroke-width='1.5'/>", LEGEND_X + 17, y);
  fprintf(f, "<text x='%d' y='%.1f'>on the Pareto front</text>\n", LEGEND_X + 42, y + 4);
}

static int write_svg(const char *dir, const summary *s, size_t m, const rc_tradeoff_summary_info *info) {
  char *text = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  if (!f) return -1;
  axes a = choose_axes(s, m);
  fprintf(f, "<svg xmlns='http://www.w3.org/2000/svg' width='%d' height='%d' font-family='sans-serif' "
             "font-size='12'>\n<rect width='100%%' height='100%%' fill='white'/>\n", SVG_W, SVG_H);
  svg_grid(f, &a, info);
  for (size_t v = 0; v < info->variant_count; v++) {
    const char *c = palette[v % 10];
    /* The variant's points in spp order, which is also the summary's order. */
    fprintf(f, "<polyline fill='none' stroke='%s' stroke-width='2.5' stroke-opacity='0.8' stroke-dasharray='%s' "
               "points='", c, dashes[v % 10]);
    for (size_t k = 0; k < m; k++)
      if (s[k].variant_index == v && !s[k].failed) fprintf(f, "%.1f,%.1f ", px(&a, s[k].ms), py(&a, s[k].mismatch));
    fputs("'/>\n", f);
    for (size_t k = 0; k < m; k++) {
      if (s[k].variant_index != v || s[k].failed) continue;
      double x = px(&a, s[k].ms), y = py(&a, s[k].mismatch);
      marker(f, (int)v, x, y, c);
      /* spp beside the point, shifted per variant so that labels of coinciding points
       * do not cover one another. */
      char buf[16];
      fprintf(f, "<text x='%.1f' y='%.1f' font-size='10' fill='%s'>%s</text>\n", x + 6, y - 6 - 9.0 * (double)(v % 4),
              c, spp_text(s[k].spp, buf));
      if (s[k].pareto)
        fprintf(f, "<circle cx='%.1f' cy='%.1f' r='9' fill='none' stroke='black' stroke-width='1.5'/>\n", x, y);
    }
  }
  svg_legend(f, info);
  fputs("</svg>\n", f);
  fclose(f);
  return commit(dir, "tradeoff.svg", text, len);
}

int rc_tradeoff_report(const char *dir, const rc_tradeoff_row *rows, size_t count,
                       const rc_tradeoff_summary_info *info, FILE *out) {
  summary *s = rc_alloc(count ? count : 1, sizeof *s, "the trade-off's summary");
  if (!s) return -1;
  size_t m = summarise(rows, count, info, s);
  int rc = write_summary(dir, s, m);
  if (rc == 0) rc = write_svg(dir, s, m, info);
  if (rc == 0) print_table(s, m, info, out);
  free(s);
  return rc;
}
