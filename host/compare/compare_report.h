/* compare_report.h: how `vkraycast compare` prints its findings, as text or as one JSON
 * object (the fields are listed in docs/cli.md, "compare"). */
#ifndef RC_COMPARE_REPORT_H
#define RC_COMPARE_REPORT_H

#include <stdio.h>

#include "compare/aov.h"
#include "compare/compare.h"

typedef struct {
  int w, h, c;
  float *px;
  char names[RC_AOV_MAX_CHANNELS][32]; /* every channel's name (R, G, B, A by position where the file has none) */
  bool aov;
  rc_aov_layout layout;
} rc_compare_image;

typedef enum { RC_VERDICT_PASS, RC_VERDICT_WARN, RC_VERDICT_FAIL } rc_verdict;

typedef struct {
  const char *path_a, *path_b;
  const rc_compare_image *a, *b;
  const rc_compare_result *r;
  double fail, warn;
  rc_verdict verdict;
  bool banded; /* --band given: decision counts leave the band out */
} rc_compare_report;

void rc_compare_print_text(const rc_compare_report *rep, FILE *f);
void rc_compare_print_json(const rc_compare_report *rep, FILE *f);

#endif
