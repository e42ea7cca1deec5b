#include "scene/mesh_check.h"

#include <ctype.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "base/rc_base.h"

/* The smallest a PLY element can be in the file: every property at least one byte in
 * binary (a char) and two in ASCII (a digit and a separator); a list at least its count. */
typedef struct {
  char name[32];
  unsigned long long count;
  unsigned scalars, lists;
} ply_element;

/* An ASCII body read through: every element's line holds its scalars and each list its
 * declared count of values, and the file holds every line the header declares; a list
 * that names vertices (the first list of the "face" element) names ones that exist.
 * assimp 5.2.4 reads past a short line into the next and renders what it found. */
static const char *check_ply_ascii_body(FILE *f, const ply_element *el, int count, char *why, size_t len) {
  unsigned long long vertices = 0;
  char line[4096];
  for (int e = 0; e < count; e++) {
    if (strcmp(el[e].name, "vertex") == 0) vertices = el[e].count;
    bool faces = strcmp(el[e].name, "face") == 0;
    for (unsigned long long i = 0; i < el[e].count; i++) {
      if (!fgets(line, sizeof line, f)) {
        snprintf(why, len, "the file ends after %llu of its %llu %s elements", i, el[e].count, el[e].name);
        return why;
      }
      /* Scalars come first in the files we know; a list is its count, then the values. */
      char *p = line, *end;
      unsigned tokens = 0;
      for (;;) {
        (void)strtod(p, &end);
        if (end == p) break;
        p = end, tokens++;
      }
      if (el[e].lists == 0 || !faces || el[e].lists > 1) {
        /* Lists elsewhere (or several) may sit anywhere among the scalars: the line's
         * presence is what is checked. */
        if (el[e].lists) continue;
        if (tokens < el[e].scalars) {
          snprintf(why, len, "%s %llu has %u values, its header declares %u", el[e].name, i, tokens, el[e].scalars);
          return why;
        }
        continue;
      }
      /* One list (the face's vertex indices), after the scalars. */
      p = line;
      for (unsigned k = 0; k < el[e].scalars; k++) (void)strtod(p, &p);
      long long n = strtoll(p, &end, 10);
      if (end == p || n < 0 || (unsigned long long)n + 1 + el[e].scalars > tokens) {
        snprintf(why, len, "%s %llu declares a list of %lld values and holds %u", el[e].name, i, n,
                 tokens > el[e].scalars ? tokens - el[e].scalars - 1 : 0);
        return why;
      }
      p = end;
      for (long long k = 0; faces && k < n; k++) {
        long long idx = strtoll(p, &end, 10);
        p = end;
        if (idx < 0 || (unsigned long long)idx >= vertices) {
          snprintf(why, len, "face %llu uses vertex %lld of %llu", i, idx, vertices);
          return why;
        }
      }
    }
  }
  return NULL;
}

/* The header's lines, up to end_header (at most 64 KiB: a longer header is refused). */
static const char *check_ply(FILE *f, size_t bytes, char *why, size_t len) {
  char line[512];
  ply_element el[16];
  int n = -1;
  bool ascii = false, end = false;
  size_t header = 0;
  while (!end && fgets(line, sizeof line, f)) {
    header += strlen(line);
    if (header > 65536) return "a PLY header longer than 64 KiB";
    char word[32] = "", kind[32] = "";
    unsigned long long count = 0;
    if (sscanf(line, "format %31s", word) == 1) {
      ascii = strcmp(word, "ascii") == 0;
    } else if (sscanf(line, "element %31s %llu", word, &count) == 2) {
      if (strchr(line + 8, '-')) return "a PLY element with a negative count";
      if (++n == 16) return "a PLY header with more than 16 elements";
      el[n] = (ply_element){"", count, 0, 0};
      snprintf(el[n].name, sizeof el[n].name, "%s", word);
    } else if (sscanf(line, "property %31s", kind) == 1 && n >= 0) {
      if (strcmp(kind, "list") == 0) el[n].lists++;
      else el[n].scalars++;
    } else if (strncmp(line, "end_header", 10) == 0) {
      end = true;
    }
  }
  if (!end) return NULL; /* not a header we read: the importer says what is wrong */
  if (n >= 0 && n < 16 && ascii) return check_ply_ascii_body(f, el, n + 1, why, len);
  /* assimp 5.2.4 takes a line feed that begins the binary data for the header's line end:
   * it reads the data one byte late and dies in an assertion (SIGABRT) on a valid file
   * whose first vertex begins with the byte 0x0A. */
  if (!ascii && fgetc(f) == '\n')
    return "its binary data begins with the byte 0x0A, which assimp 5.2.4 reads as part of the header (it then "
           "misreads the file and aborts); write the file as ASCII PLY or in another format";
  size_t body = bytes > header ? bytes - header : 0;
  for (int i = 0; i <= n; i++) {
    unsigned long long per = (ascii ? 2 : 1) * (unsigned long long)(el[i].scalars + el[i].lists);
    if (per == 0) continue;
    if (el[i].count > body / per) {
      snprintf(why, len, "its header declares %llu %s element%s of at least %llu bytes each, in a file of %zu bytes",
               el[i].count, el[i].name, el[i].count == 1 ? "" : "s", per, bytes);
      return why;
    }
  }
  return NULL;
}

/* OFF, read as assimp 5.2.4's OFFLoader reads it (the header's letters, its counts as
 * 32-bit integers that wrap, comments between tokens, lines as its GetNextLine cuts
 * them), so that what is checked is what the importer will see: the counts against the
 * file's size (it allocates for them first: "OFF1 3000000000000000010000" declared one
 * vertex and, wrapped, 2.6 billion faces, 42 GB, found by fuzz_mesh), and every face's
 * vertex indices against the vertex count (it moves an index out of range to the last
 * vertex and carries on: a wrong triangle, rendered). */
typedef struct {
  const char *at, *end;
} off_text;

static bool off_line_end(char c) { return c == '\r' || c == '\n' || c == '\0' || c == '\f'; }

/* assimp's NextToken: blanks, line ends and comment lines. */
static void off_next_token(off_text *t) {
  while (t->at < t->end && (*t->at == ' ' || *t->at == '\t' || *t->at == '\r' || *t->at == '\n')) t->at++;
  while (t->at < t->end && (*t->at == '#' || *t->at == '\n' || *t->at == '\r')) {
    while (t->at < t->end && !off_line_end(*t->at)) t->at++;
    while (t->at < t->end && (*t->at == '\r' || *t->at == '\n')) t->at++;
    while (t->at < t->end && (*t->at == ' ' || *t->at == '\t' || *t->at == '\r' || *t->at == '\n')) t->at++;
  }
}

/* assimp's strtoul10 within [p, end): decimal digits into 32 bits, wrapping. */
static uint32_t off_uint(const char **p, const char *end) {
  uint32_t v = 0;
  while (*p < end && **p >= '0' && **p <= '9') v = v * 10u + (uint32_t)(*(*p)++ - '0');
  return v;
}

/* assimp's GetNextLine: up to 4,096 characters to the next line end, then past every line
 * end; false at the end of the text. */
static bool off_line(off_text *t, const char **line, const char **line_end) {
  if (t->at >= t->end || *t->at == '\0') return false;
  *line = t->at;
  while (t->at < t->end && !off_line_end(*t->at) && t->at - *line < 4096) t->at++;
  *line_end = t->at;
  while (t->at < t->end && off_line_end(*t->at) && *t->at != '\0') t->at++;
  return true;
}

static const char *check_off_text(const char *text, size_t bytes, char *why, size_t len) {
  off_text t = {text, text + bytes};
  off_next_token(&t);
  const char *c = t.at, *e = t.end;
  bool dimension = false;
  /* The importer's buffer ends in a NUL one past the file: its "car < end - k" is
   * "c < e - k + 1" here. Without "OFF" it reads the counts (or refuses the file). */
  if (c < e - 1 && c[0] == 'S' && c[1] == 'T') c += 2;
  if (c < e && c[0] == 'C') c++;
  if (c < e && c[0] == 'N') c++;
  if (c < e && c[0] == '4') c++;
  if (c < e && c[0] == 'n') dimension = true, c++;
  if (c < e - 2 && c[0] == 'O' && c[1] == 'F' && c[2] == 'F') c += 3;
  t.at = c;
  off_next_token(&t);
  uint32_t dims = 3;
  if (dimension) {
    dims = off_uint(&t.at, t.end);
    off_next_token(&t);
  }
  if (dims > 3) return NULL; /* the importer refuses it */
  off_next_token(&t);
  const uint32_t nv = off_uint(&t.at, t.end);
  off_next_token(&t);
  const uint32_t nf = off_uint(&t.at, t.end);
  off_next_token(&t);
  (void)off_uint(&t.at, t.end); /* the edge count */
  off_next_token(&t);
  if (nv == 0 || nf == 0) return NULL; /* the importer refuses it */
  /* A vertex line holds its coordinates (a digit and a separator each); a face line its
   * count and a line end. */
  const size_t per_vertex = 2 * (dims ? dims : 1);
  if (nv > bytes / per_vertex || nf > bytes / 2) {
    snprintf(why, len, "its header declares %u vertices and %u faces, more than a file of %zu bytes holds", nv, nf,
             bytes);
    return why;
  }
  const char *line, *line_end;
  for (uint32_t v = 0; v < nv; v++)
    if (!off_line(&t, &line, &line_end)) return NULL; /* short: the importer says so */
  for (uint32_t i = 0; i < nf; i++) {
    if (!off_line(&t, &line, &line_end)) return NULL;
    const char *p = line;
    while (p < line_end && (*p == ' ' || *p == '\t')) p++;
    uint32_t k = off_uint(&p, line_end);
    if (k == 0 || k > 9) continue; /* skipped by the importer */
    for (uint32_t j = 0; j < k; j++) {
      while (p < line_end && (*p == ' ' || *p == '\t')) p++;
      uint32_t idx = off_uint(&p, line_end);
      if (idx >= nv) {
        snprintf(why, len, "face %u uses vertex %u of %u", i, idx, nv);
        return why;
      }
    }
  }
  return NULL;
}

static const char *check_off(FILE *f, size_t bytes, char *why, size_t len) {
  /* In memory, as the importer reads it (bounded by the file's size, which it reads whole too). */
  char *text = malloc(bytes ? bytes : 1);
  if (!text) return "the file does not fit in memory";
  const char *problem = fread(text, 1, bytes, f) == bytes ? check_off_text(text, bytes, why, len) : NULL;
  free(text);
  return problem;
}

/* Whether `name` (name_len bytes), as a file at `path` names a file (relative to its
 * folder unless absolute), is that file itself. */
static bool names_itself(const char *path, const char *name, size_t name_len, const struct stat *self) {
  char other[4200];
  const char *slash = strrchr(path, '/');
  int dir = name[0] == '/' || !slash ? 0 : (int)(slash - path + 1);
  if (snprintf(other, sizeof other, "%.*s%.*s", dir, path, (int)name_len, name) >= (int)sizeof other) return false;
  struct stat st;
  return stat(other, &st) == 0 && st.st_dev == self->st_dev && st.st_ino == self->st_ino;
}

/* Lines as assimp 5.2.4's readers cut them: at \n, \r, \f or NUL, then past spaces and
 * tabs. Each line's first LINE_KEPT characters after the blanks go to `fn`, with their
 * count and the line's number as an editor counts lines (\r\n, \n or a lone \r), until
 * fn returns true. Read in blocks from the start, whatever the file's size; f is rewound
 * after. */
enum { LINE_KEPT = 4096 };
typedef bool (*line_fn)(void *ctx, const char *line, size_t kept, unsigned long number);

static void scan_lines(FILE *f, line_fn fn, void *ctx) {
  char block[65536], line[LINE_KEPT + 1];
  size_t kept = 0, got;
  unsigned long number = 1;
  bool start = true, after_cr = false, done = false;
  rewind(f);
  while (!done && (got = fread(block, 1, sizeof block, f)) > 0) {
    for (size_t i = 0; i < got && !done; i++) {
      const char c = block[i];
      if (c == '\n' || c == '\r' || c == '\f' || c == '\0') {
        line[kept] = '\0';
        done = fn(ctx, line, kept, number);
        number += c == '\r' || (c == '\n' && !after_cr);
        after_cr = c == '\r';
        kept = 0, start = true;
        continue;
      }
      after_cr = false;
      if (start && (c == ' ' || c == '\t')) continue;
      start = false;
      if (kept < LINE_KEPT) line[kept++] = c;
    }
  }
  if (!done && !start) { /* the last line, unended */
    line[kept] = '\0';
    fn(ctx, line, kept, number);
  }
  rewind(f);
}

/* The `mtllib` statements of a file read as an OBJ, its lines cut as assimp cuts them
 * (scan_lines): whether it has one, and whether one names the file itself (the name as
 * the rest of the line, trimmed, as assimp 5.2.4 takes it, or its first word). */
typedef struct {
  const char *path;
  struct stat self;
  bool *any, *itself;
} library_scan;

static bool library_line(void *ctx, const char *line, size_t kept, unsigned long number) {
  library_scan *scan = ctx;
  (void)number;
  if (kept <= 7 || strncmp(line, "mtllib", 6) != 0 || (line[6] != ' ' && line[6] != '\t')) return false;
  *scan->any = true;
  const char *name = line + 7 + strspn(line + 7, " \t");
  size_t all = (size_t)(line + kept - name), word = strcspn(name, " \t");
  while (all > 0 && (name[all - 1] == ' ' || name[all - 1] == '\t')) all--;
  *scan->itself = (all && names_itself(scan->path, name, all, &scan->self)) ||
                  (word && names_itself(scan->path, name, word, &scan->self));
  return *scan->itself;
}

static void find_libraries(FILE *f, const char *path, bool *any, bool *itself) {
  library_scan scan = {.path = path, .any = any, .itself = itself};
  *any = *itself = false;
  if (fstat(fileno(f), &scan.self) == 0) scan_lines(f, library_line, &scan);
}

/* What assimp 5.2.4 may read a file as, whatever its name, when the importer of its
 * extension declines it: its SearchFileHeaderForToken looks for "ply" in the first 200
 * bytes and for "off" in the first 3, lower-cased, NUL bytes removed (a .gltf file holding
 * an OFF header was read as OFF: fuzz_mesh, a 16 GB allocation). */
static void sniff(FILE *f, bool *ply, bool *off) {
  char head[201];
  size_t got = fread(head, 1, 200, f), n = 0;
  for (size_t i = 0; i < got; i++)
    if (head[i]) head[n++] = (char)tolower((unsigned char)head[i]);
  head[n] = '\0';
  *ply = *ply || strstr(head, "ply") != NULL;
  *off = *off || (n >= 3 && strncmp(head, "off", 3) == 0);
  rewind(f);
}

const char *rc_mesh_check(const char *path, size_t bytes, bool *names_library, char *why, size_t len) {
  bool ply = rc_has_extension(path, ".ply"), off = rc_has_extension(path, ".off");
  *names_library = false;
  FILE *f = fopen(path, "rb");
  if (!f) return NULL; /* the importer's open reports it */
  sniff(f, &ply, &off);
  const char *problem = ply ? check_ply(f, bytes, why, len) : NULL;
  if (!problem && off) {
    rewind(f);
    problem = check_off(f, bytes, why, len);
  }
  rewind(f);
  /* Whatever its name says, assimp may read a file as an OBJ (it picks an importer by the
   * content when the extension's declines); one that names a material library has that
   * library checked when it is opened, and one that names itself is checked here. */
  bool itself = false;
  if (!problem) find_libraries(f, path, names_library, &itself);
  if (!problem && itself) problem = rc_mtl_check(f, why, len);
  fclose(f);
  return problem;
}

/* The statements of assimp 5.2.4's material library reader that write to the current
 * material without asking whether there is one: those that set a texture (map_*, bump,
 * disp, norm, refl: it matches their first four letters, the rest in any case) and the
 * anisotropy (any line starting with `a`; "a" alone crashed). Its other statements are
 * skipped or guarded there. */
static bool unguarded_statement(const char *p) {
  static const char *const keys[] = {"map_", "bump", "disp", "norm", "refl"};
  if (p[0] == 'a') return true;
  for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
    if (p[0] == keys[i][0] && strncasecmp(p, keys[i], 4) == 0) return true;
  return false;
}

/* A material library's lines (scan_lines) up to its first `newmtl`, each judged by its
 * head: refused at the first unguarded statement, with its line. */
typedef struct {
  char *why;
  size_t len;
  const char *problem;
} library_check;

static bool library_check_line(void *ctx, const char *line, size_t kept, unsigned long number) {
  library_check *check = ctx;
  if (kept == 0) return false;
  if (strncmp(line, "newmtl", 6) == 0 && (kept == 6 || line[6] == ' ' || line[6] == '\t')) return true;
  if (!unguarded_statement(line)) return false;
  size_t word = strcspn(line, " \t");
  snprintf(check->why, check->len,
           "line %lu: the statement `%.*s` comes before the first `newmtl` and belongs to no material "
           "(assimp 5.2.4 dies on it)",
           number, (int)(word < 8 ? word : 8), line);
  check->problem = check->why;
  return true;
}

const char *rc_mtl_check(FILE *f, char *why, size_t len) {
  library_check check = {why, len, NULL};
  scan_lines(f, library_check_line, &check);
  return check.problem;
}
