/* compare_checks.h: the tolerances `vkraycast compare` judges by, named (presets) and
 * itemised (checks): every verdict is the list of checks it came from, each with what was
 * measured and what was allowed, so that a FAIL always says why. */
#ifndef RC_COMPARE_CHECKS_H
#define RC_COMPARE_CHECKS_H

#include <stdio.h>

#include "compare/compare.h"

/* Every tolerance of one comparison. NAN in a field means "not given" while options and
 * a preset are being combined; rc_compare_limits_finish fills the defaults. */
typedef struct rc_compare_limits {
  double fail, fail_percent, hardfail;   /* colour: per-channel threshold, share of pixels, any value */
  double warn, warn_percent;
  double min_psnr;                       /* dB; -INFINITY: none */
  double decisions, decisions_percent;   /* AOV files: pixels whose decisions differ */
  double depth_tolerance, normal_tolerance;
} rc_compare_limits;

/* A named set of limits and the documented reason for each (docs/gpu-vs-cpu.md). */
typedef struct rc_compare_preset {
  const char *name, *what;
  rc_compare_limits limits;
} rc_compare_preset;

extern const rc_compare_preset rc_compare_presets[];
extern const char *const rc_compare_preset_names[]; /* NULL-terminated, for the option table */

/* Fields of *l still NAN take the preset's value (preset may be NULL), then the
 * command's defaults (idiff's: 1e-6 for fail and warn, nothing else allowed). */
void rc_compare_limits_finish(rc_compare_limits *l, const rc_compare_preset *preset);

typedef enum { RC_VERDICT_PASS, RC_VERDICT_WARN, RC_VERDICT_FAIL } rc_verdict;

#define RC_COMPARE_MAX_CHECKS 10
typedef struct rc_compare_check {
  const char *id;        /* "pixels_over_fail": stable, for --json */
  char what[96];         /* "pixels over --fail 0.001" */
  char measured[96];     /* "1 (0.0004 %)" */
  char allowed[96];      /* "0.5 % = 1,280" */
  double measured_value, allowed_value;
  rc_verdict level;      /* the verdict this check gives when it is not met */
  bool ok;
} rc_compare_check;

typedef struct rc_compare_judgement {
  rc_compare_check checks[RC_COMPARE_MAX_CHECKS];
  int count;
  rc_verdict verdict;
} rc_compare_judgement;

/* The checks that apply to r (decision checks only where r->decisions) and the verdict. */
void rc_compare_judge(const rc_compare_result *r, const rc_compare_limits *l, rc_compare_judgement *j);

/* "1,280": n with thousands separators. */
const char *rc_group_digits(uint64_t n, char *buf, size_t len);

#endif
