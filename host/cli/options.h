/* options.h: one table per subcommand drives its parsing, its one-line usage and its
 * --help text, so that an option is written once (issue 17 item 1, docs/cli.md).
 *
 * Conventions, as in getopt_long and the tools users already know:
 *   --name value and --name=value (and -o value, -o=value) are the same;
 *   options may come before or after the subcommand and between positional arguments;
 *   `--` ends the options; a lone `-` is a positional argument (standard input/output);
 *   an option given twice takes the last value (a repeatable one collects them all);
 *   a value that looks like an option (`-o --quiet`) is an error naming both;
 *   an unknown option is an error that suggests the nearest known one. */
#ifndef RC_CLI_OPTIONS_H
#define RC_CLI_OPTIONS_H

#include <stddef.h>
#include <stdio.h>

#include "base/rc_base.h"

typedef enum {
  RC_OPT_FLAG,   /* bool, set to true */
  RC_OPT_STRING, /* const char * */
  RC_OPT_UINT,   /* uint32_t in [lo, hi] */
  RC_OPT_INT,    /* int in [lo, hi] (the field's default may be -1: "not given") */
  RC_OPT_REAL,   /* double in [lo, hi], lo excluded when lo_open; f32: also nonzero in f32 */
  RC_OPT_CHOICE, /* int: the index of the value in choices */
  RC_OPT_LIST,   /* rc_opt_list: repeatable */
} rc_opt_kind;

#define RC_OPT_LIST_MAX 8
typedef struct {
  const char *item[RC_OPT_LIST_MAX];
  unsigned count;
} rc_opt_list;

typedef struct {
  const char *name;            /* "--spp" */
  const char *alias;           /* "-o", or NULL */
  rc_opt_kind kind;
  size_t offset;               /* offsetof the field in the command's argument struct */
  const char *metavar;         /* "N", "FILE"; NULL for flags */
  double lo, hi;               /* numeric kinds */
  const char *const *choices;  /* RC_OPT_CHOICE, NULL-terminated */
  const char *help;            /* lines separated by '\n' */
  const char *heading;         /* non-NULL: a section of the help starts at this option */
  unsigned flags;              /* RC_OPT_REQUIRED, RC_OPT_LO_OPEN, RC_OPT_F32 */
  const char *what;            /* RC_OPT_REQUIRED: "output file", for "no output file given" */
  const char *def;             /* the default, as --help shows it ("1", "the scene's"); NULL: none to show */
} rc_option;

enum { RC_OPT_REQUIRED = 1u, RC_OPT_LO_OPEN = 2u, RC_OPT_F32 = 4u };

typedef struct {
  const char *name;          /* "render" */
  const char *synopsis;      /* "SCENE -o OUT [options]" */
  const char *summary;       /* one paragraph under the usage line in --help */
  const char *epilogue;      /* after the options in --help (exit status, ...) */
  unsigned min_positional, max_positional;
  size_t positional_offset;  /* const char *[max_positional] in the argument struct */
  const char *const *positional_names; /* for "no X given" */
  const rc_option *options;
  size_t option_count;
} rc_command_spec;

/* Parses argv (the arguments after the subcommand's name) into args. Returns RC_OK,
 * RC_ERR_USAGE after printing the problem and the usage line, or RC_DONE after printing
 * --help to stdout. */
rc_status rc_parse_command(const rc_command_spec *spec, int argc, char **argv, void *args);

void rc_print_help(const rc_command_spec *spec, FILE *f);

/* error: "vkraycast: error: render: <message>" then "usage: vkraycast render ..." */
void rc_usage_error(const rc_command_spec *spec, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Whether `arg` (an option as written, without "=value") takes a value in any of the
 * specs: how main() finds the subcommand among options written before it. */
bool rc_option_takes_value(const rc_command_spec *const *specs, size_t count, const char *arg);

#endif
