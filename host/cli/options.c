/* options.c: the table-driven option parser and help printer (options.h). */
#include "cli/options.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Help layout: options in a column of this width, their text after it. */
#define HELP_COLUMN 26

static const char *display_name(const rc_option *o) { return o->name ? o->name : o->alias; }

static const rc_option *find_option(const rc_command_spec *s, const char *arg, size_t len) {
  for (size_t i = 0; i < s->option_count; i++) {
    const rc_option *o = &s->options[i];
    if ((o->name && strlen(o->name) == len && strncmp(o->name, arg, len) == 0) ||
        (o->alias && strlen(o->alias) == len && strncmp(o->alias, arg, len) == 0))
      return o;
  }
  return NULL;
}

static bool takes_value(const rc_option *o) { return o->kind != RC_OPT_FLAG; }

/* "-5" or "-0.5": a negative number given to a numeric option, which then fails its range
 * check with the value quoted, rather than being taken for an unknown option. */
static bool looks_numeric(const char *v) { return v[0] == '-' && ((v[1] >= '0' && v[1] <= '9') || v[1] == '.'); }

static bool looks_like_option(const rc_option *o, const char *v) {
  if (v[0] != '-' || v[1] == '\0') return false; /* a lone "-" is standard input/output */
  bool numeric = o->kind == RC_OPT_UINT || o->kind == RC_OPT_INT || o->kind == RC_OPT_REAL;
  return !(numeric && looks_numeric(v));
}

static void print_usage_line(const rc_command_spec *s, FILE *f) {
  fprintf(f, "usage: vkraycast %s%s%s\n", s->name, s->synopsis[0] ? " " : "", s->synopsis);
}

void rc_usage_error(const rc_command_spec *s, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "vkraycast: error: %s: ", s->name);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
  print_usage_line(s, stderr);
  fprintf(stderr, "(vkraycast %s --help lists the options)\n", s->name);
}

static void unknown_option(const rc_command_spec *s, const char *arg, size_t len) {
  char word[64];
  snprintf(word, sizeof word, "%.*s", (int)(len < sizeof word ? len : sizeof word - 1), arg);
  const char *names[2 * 64 + 1];
  size_t n = 0;
  for (size_t i = 0; i < s->option_count && n + 2 < sizeof names / sizeof *names; i++) {
    names[n++] = s->options[i].name;
    names[n++] = s->options[i].alias;
  }
  names[n++] = "--help";
  const char *near = rc_nearest(word, names, n);
  if (near)
    rc_usage_error(s, "unknown option %s (did you mean %s?)", word, near);
  else
    rc_usage_error(s, "unknown option %s", word);
}

/* A choice of exactly off and on (in that order, so that the index is the truth value). */
static bool is_off_on(const rc_option *o) {
  return o->choices && o->choices[0] && o->choices[1] && !o->choices[2] && strcmp(o->choices[0], "off") == 0 &&
         strcmp(o->choices[1], "on") == 0;
}

static rc_status store(const rc_command_spec *s, const rc_option *o, const char *v, void *args) {
  char *field = (char *)args + o->offset;
  const char *name = display_name(o);
  char *end = NULL;
  errno = 0;
  switch (o->kind) {
  case RC_OPT_FLAG:
    *(bool *)field = true;
    return RC_OK;
  case RC_OPT_STRING:
    if (!v[0]) {
      rc_usage_error(s, "%s: expected %s, got an empty string", name, o->metavar);
      return RC_ERR_USAGE;
    }
    *(const char **)field = v;
    return RC_OK;
  case RC_OPT_LIST: {
    rc_opt_list *list = (rc_opt_list *)field;
    if (list->count == RC_OPT_LIST_MAX) {
      rc_usage_error(s, "%s: at most %d are allowed", name, RC_OPT_LIST_MAX);
      return RC_ERR_USAGE;
    }
    list->item[list->count++] = v;
    return RC_OK;
  }
  case RC_OPT_CHOICE:
    for (int i = 0; o->choices[i]; i++)
      if (strcmp(o->choices[i], v) == 0) {
        *(int *)field = i;
        return RC_OK;
      }
    if (is_off_on(o)) {
      /* A switch takes the spellings scripts and other tools use, as on and off. */
      static const char *const yes[] = {"yes", "true", "1"}, *const no[] = {"no", "false", "0"};
      for (int i = 0; i < 3; i++)
        if (strcasecmp(v, yes[i]) == 0 || strcasecmp(v, no[i]) == 0) {
          *(int *)field = strcasecmp(v, yes[i]) == 0 ? 1 : 0;
          return RC_OK;
        }
    }
    {
      char list[200] = "";
      for (int i = 0; o->choices[i]; i++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", o->choices[i]);
      size_t n = 0;
      while (o->choices[n]) n++;
      const char *near = rc_nearest(v, o->choices, n);
      rc_usage_error(s, "%s: expected one of %s, got '%s'%s%s%s", name, list, v, near ? " (did you mean " : "",
                     near ? near : "", near ? "?)" : "");
    }
    return RC_ERR_USAGE;
  case RC_OPT_UINT:
  case RC_OPT_INT: {
    unsigned long long x = strtoull(v, &end, 10);
    if (!v[0] || *end || errno || v[0] == '-' || v[0] == '+' || (double)x < o->lo || (double)x > o->hi) {
      rc_usage_error(s, "%s: expected a whole number in [%.0f, %.0f], got '%s'", name, o->lo, o->hi, v);
      return RC_ERR_USAGE;
    }
    if (o->kind == RC_OPT_UINT)
      *(uint32_t *)field = (uint32_t)x;
    else
      *(int *)field = (int)x;
    return RC_OK;
  }
  case RC_OPT_REAL: {
    double x = strtod(v, &end);
    bool lo_ok = (o->flags & RC_OPT_LO_OPEN) ? x > o->lo : x >= o->lo;
    bool f32_ok = !(o->flags & RC_OPT_F32) || (isfinite((float)x) && (x == 0 || (float)x != 0));
    if (!v[0] || *end || !isfinite(x) || !lo_ok || x > o->hi || !f32_ok) {
      rc_usage_error(s, "%s: expected a number in %s%g, %g]%s, got '%s'", name, (o->flags & RC_OPT_LO_OPEN) ? "(" : "[",
                     o->lo, o->hi, (o->flags & RC_OPT_F32) ? " within f32 range" : "", v);
      return RC_ERR_USAGE;
    }
    *(double *)field = x;
    return RC_OK;
  }
  }
  return RC_ERR_USAGE;
}

rc_status rc_parse_command(const rc_command_spec *s, int argc, char **argv, void *args) {
  unsigned positional = 0;
  bool seen[64] = {0};
  RC_ASSERT(s->option_count <= 64);
  bool options_done = false;
  for (int i = 0; i < argc; i++) {
    const char *arg = argv[i];
    bool is_option = !options_done && arg[0] == '-' && arg[1] != '\0';
    if (is_option && strcmp(arg, "--") == 0) {
      options_done = true;
      continue;
    }
    if (!is_option) {
      if (positional == s->max_positional) {
        if (s->max_positional == 0)
          rc_usage_error(s, "unexpected argument '%s' (%s takes no files)", arg, s->name);
        else
          rc_usage_error(s, "unexpected argument '%s' (%s takes %u file%s)", arg, s->name, s->max_positional,
                         s->max_positional == 1 ? "" : "s");
        return RC_ERR_USAGE;
      }
      ((const char **)((char *)args + s->positional_offset))[positional++] = arg;
      continue;
    }
    if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
      rc_print_help(s, stdout);
      return RC_DONE;
    }
    const char *eq = strchr(arg, '=');
    size_t len = eq ? (size_t)(eq - arg) : strlen(arg);
    const rc_option *o = find_option(s, arg, len);
    if (!o) {
      unknown_option(s, arg, len);
      return RC_ERR_USAGE;
    }
    const char *v = NULL;
    if (!takes_value(o)) {
      if (eq) {
        rc_usage_error(s, "%s takes no value (got '%s')", display_name(o), eq + 1);
        return RC_ERR_USAGE;
      }
    } else if (eq) {
      v = eq + 1;
    } else if (i + 1 >= argc) {
      rc_usage_error(s, "%s needs a value (%s)", arg, o->metavar);
      return RC_ERR_USAGE;
    } else if (looks_like_option(o, argv[i + 1])) {
      rc_usage_error(s, "%s needs a value (%s) but is followed by the option %s (write %s=%s if that is the value)",
                     arg, o->metavar, argv[i + 1], arg, argv[i + 1]);
      return RC_ERR_USAGE;
    } else {
      v = argv[++i];
    }
    /* Given twice, the last one wins (getopt's rule, which scripts that append to a
     * default command line rely on); RC_OPT_LIST collects every one. */
    seen[o - s->options] = true;
    rc_status st = store(s, o, v, args);
    if (st != RC_OK) return st;
  }
  if (positional < s->min_positional) {
    rc_usage_error(s, "no %s given", s->positional_names[positional]);
    return RC_ERR_USAGE;
  }
  for (size_t k = 0; k < s->option_count; k++)
    if ((s->options[k].flags & RC_OPT_REQUIRED) && !seen[k]) {
      const rc_option *o = &s->options[k];
      rc_usage_error(s, "no %s given (%s %s)", o->what ? o->what : o->metavar, o->alias ? o->alias : o->name,
                     o->metavar);
      return RC_ERR_USAGE;
    }
  return RC_OK;
}

bool rc_option_takes_value(const rc_command_spec *const *specs, size_t count, const char *arg) {
  if (strchr(arg, '=')) return false;
  for (size_t i = 0; i < count; i++) {
    const rc_option *o = find_option(specs[i], arg, strlen(arg));
    if (o && takes_value(o)) return true;
  }
  return false;
}

/* "values: 1 to 1024; default 1" for numbers and choices, from the table the parser
 * reads (the default where the table holds it), so that the help cannot drift. */
static bool values_text(const rc_option *o, char *out, size_t cap) {
  int n = 0;
  if (o->kind == RC_OPT_UINT || o->kind == RC_OPT_INT)
    n = snprintf(out, cap, "values: %.0f to %.0f", o->lo, o->hi);
  else if (o->kind == RC_OPT_REAL && isfinite(o->hi))
    n = snprintf(out, cap, "values: %g %s to %g", o->lo, (o->flags & RC_OPT_LO_OPEN) ? "(excluded)" : "", o->hi);
  else if (o->kind == RC_OPT_REAL)
    n = snprintf(out, cap, "values: from %g%s", o->lo, (o->flags & RC_OPT_LO_OPEN) ? " (excluded)" : "");
  else if (o->kind == RC_OPT_CHOICE) {
    n = snprintf(out, cap, "values:");
    for (int i = 0; o->choices[i] && n < (int)cap; i++)
      n += snprintf(out + n, cap - (size_t)n, "%s%s", i ? " | " : " ", o->choices[i]);
    if (is_off_on(o) && n < (int)cap) n += snprintf(out + n, cap - (size_t)n, " (also yes | no, true | false, 1 | 0)");
  } else {
    return false;
  }
  if (o->def && n < (int)cap) snprintf(out + n, cap - (size_t)n, "; default %s", o->def);
  return true;
}

void rc_print_help(const rc_command_spec *s, FILE *f) {
  print_usage_line(s, f);
  if (s->summary) fprintf(f, "\n%s\n", s->summary);
  if (s->option_count) fputc('\n', f);
  for (size_t i = 0; i < s->option_count; i++) {
    const rc_option *o = &s->options[i];
    if (o->heading) fprintf(f, "\n%s\n", o->heading);
    char left[80];
    int n = snprintf(left, sizeof left, "  %s%s%s%s%s", o->alias ? o->alias : "", o->alias && o->name ? ", " : "",
                     o->name ? o->name : "", o->metavar ? " " : "", o->metavar ? o->metavar : "");
    fputs(left, f);
    /* The help text: its first line beside the option (or under it when the option is
     * wide), the rest indented to the column. */
    const char *line = o->help;
    if (n >= HELP_COLUMN) fputc('\n', f), n = 0;
    while (line) {
      const char *nl = strchr(line, '\n');
      int len = nl ? (int)(nl - line) : (int)strlen(line);
      fprintf(f, "%*s%.*s\n", HELP_COLUMN - n, "", len, line);
      n = 0;
      line = nl ? nl + 1 : NULL;
    }
    char values[256];
    if (values_text(o, values, sizeof values)) fprintf(f, "%*s%s\n", HELP_COLUMN, "", values);
  }
  if (s->epilogue) fprintf(f, "\n%s", s->epilogue);
}
