/* compare_report.h: how `vkraycast compare` prints its findings, as text or as one JSON
 * object (the fields are listed in docs/cli.md, "compare"): the metrics, the headers'
 * differences, the worst pixels, each check with what it measured and allowed, notes
 * that explain a result, and the verdict with the checks that made it. */
#ifndef RC_COMPARE_REPORT_H
#define RC_COMPARE_REPORT_H

#include <stdio.h>

#include "compare/aov.h"
#include "compare/compare.h"
#include "compare/compare_checks.h"
#include "compare/compare_header.h"
#include "compare/heat_map.h"

typedef struct {
  int w, h, c;
  float *px;
  char names[RC_AOV_MAX_CHANNELS][32]; /* every channel's name (R, G, B, A by position where the file has none) */
  bool aov;
  rc_aov_layout layout;
  rc_image_header header;
} rc_compare_image;

typedef struct {
  const char *path_a, *path_b;
  const rc_compare_image *a, *b;
  const rc_compare_result *r;
  const rc_compare_limits *limits;
  const char *preset;                 /* NULL: none */
  const rc_compare_judgement *judgement;
  bool banded;                        /* --band given: decision counts leave the band out */
  uint64_t over_same_decisions;       /* AOV files: pixels over --fail whose decisions agree (first sample, or every
                                         sample where both files have digests) */
  int top;                            /* worst pixels to list */
  const char *heat_path;              /* --diff, or NULL */
  rc_heat_scale heat;
  uint64_t ringed;
} rc_compare_report;

void rc_compare_print_text(const rc_compare_report *rep, FILE *f);
void rc_compare_print_json(const rc_compare_report *rep, FILE *f);

#endif
