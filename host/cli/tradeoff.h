/* tradeoff.h: `vkraycast tradeoff`, the speed/accuracy trade measured on the user's own
 * scenes (docs/accuracy.md). A point is one (scene, variant, spp): the variant's render
 * timed, its first-sample decisions against the CPU f64 reference of the same samples,
 * its colour against a CPU f64 render of many samples. cmd_tradeoff.c renders the points;
 * tradeoff_report.c turns their rows into the CSV files, the table and the plot. */
#ifndef RC_CLI_TRADEOFF_H
#define RC_CLI_TRADEOFF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#define RC_TRADEOFF_MAX_VARIANTS 16
#define RC_TRADEOFF_MAX_SPPS 8

typedef struct rc_tradeoff_variant {
  const char *name;    /* "fast", "default": the legend's label and the CSV's */
  const char *what;    /* the legend's explanation: what the variant sets */
  const char *options; /* render options, separated by spaces */
} rc_tradeoff_variant;

/* One measured point; status "ok" or why it has no measurement ("render failed (exit 2)"). */
typedef struct rc_tradeoff_row {
  char scene[128], variant[64], precision[8], status[96];
  unsigned spp;
  double render_ms, wall_ms, cpu_ms;            /* steady state: medians of frames 2..N */
  double mrays_per_s;                           /* primary + shadow + reflection rays over render_ms */
  double mismatch_pct, hit_pct, object_pct, shadow_pct; /* first-sample decisions vs CPU f64, % of pixels */
  double psnr, rms, max_error;                  /* colour vs the many-sample CPU f64 render */
} rc_tradeoff_row;

/* "scene,variant,spp,..." and one row; read back by rc_tradeoff_parse_row. */
extern const char rc_tradeoff_csv_header[];
void rc_tradeoff_write_row(FILE *f, const rc_tradeoff_row *r);
bool rc_tradeoff_parse_row(const char *line, rc_tradeoff_row *r);

typedef struct rc_tradeoff_summary_info {
  const rc_tradeoff_variant *variants;
  size_t variant_count;
  size_t scene_count;
  const char *device;      /* what rendered the timed frames */
  unsigned width, height;  /* 0: the scenes' own sizes */
  unsigned reference_spp;
} rc_tradeoff_summary_info;

/* Writes DIR/tradeoff-summary.csv (per variant and spp: summed time, mean mismatch, PSNR
 * of the mean MSE, Pareto flag) and DIR/tradeoff.svg, and prints the table to out.
 * Returns 0, or -1 after printing why a file could not be written. */
int rc_tradeoff_report(const char *dir, const rc_tradeoff_row *rows, size_t count,
                       const rc_tradeoff_summary_info *info, FILE *out);

#endif
