#include "scene/mesh_check.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

/* OFF: the counts against the file's size, and every face's vertex indices against the
 * vertex count (assimp's reader replaces an index out of range by the last vertex and
 * carries on: a wrong triangle, rendered). */
static const char *check_off(FILE *f, size_t bytes, char *why, size_t len) {
  char word[16];
  unsigned long long nv, nf;
  if (fscanf(f, "%15s", word) != 1 || !strstr(word, "OFF")) return NULL;
  /* The first two numbers after the keyword are what the importer reserves for, whatever
   * follows them (the fuzzer found "OFF 3 1000000000" and then garbage, which ran it out
   * of memory); for COFF, NOFF and the like too, counts being counts. */
  if (fscanf(f, "%llu %llu", &nv, &nf) != 2) return NULL;
  /* A vertex is at least "0 0 0\n" (6 bytes), a face "3 0 0 0\n" (8). */
  if (nv > bytes / 6 || nf > bytes / 8) {
    snprintf(why, len, "its header declares %llu vertices and %llu faces, more than a file of %zu bytes holds", nv,
             nf, bytes);
    return why;
  }
  if (strcmp(word, "OFF") != 0) return NULL; /* the indices of the plain format only */
  int ch;
  while ((ch = fgetc(f)) != EOF && ch != '\n') {
  }
  for (unsigned long long v = 0; v < nv; v++) {
    double x, y, z;
    if (fscanf(f, "%lf %lf %lf", &x, &y, &z) != 3) return NULL;
    int c;
    while ((c = fgetc(f)) != EOF && c != '\n') {
    }
  }
  for (unsigned long long i = 0; i < nf; i++) {
    unsigned long long k;
    if (fscanf(f, "%llu", &k) != 1) return NULL;
    if (k > 64) {
      snprintf(why, len, "face %llu has %llu vertices (at most 64 are read)", i, k);
      return why;
    }
    for (unsigned long long j = 0; j < k; j++) {
      long long idx;
      if (fscanf(f, "%lld", &idx) != 1) return NULL;
      if (idx < 0 || (unsigned long long)idx >= nv) {
        snprintf(why, len, "face %llu uses vertex %lld of %llu", i, idx, nv);
        return why;
      }
    }
    int c;
    while ((c = fgetc(f)) != EOF && c != '\n') {
    }
  }
  return NULL;
}

/* Whether `name`, as an OBJ at `path` names a file (relative to the OBJ's folder unless
 * absolute), is the OBJ itself. */
static bool names_itself(const char *path, const char *name, size_t name_len, const struct stat *self) {
  char other[4200];
  const char *slash = strrchr(path, '/');
  int dir = name[0] == '/' || !slash ? 0 : (int)(slash - path + 1);
  if (snprintf(other, sizeof other, "%.*s%.*s", dir, path, (int)name_len, name) >= (int)sizeof other) return false;
  struct stat st;
  return stat(other, &st) == 0 && st.st_dev == self->st_dev && st.st_ino == self->st_ino;
}

/* An OBJ whose `mtllib` names the OBJ itself: assimp reads its geometry as a material
 * library, where a map statement before any `newmtl` kills it (rc_mtl_check). The name is
 * the rest of the line, as assimp 5.2.4 takes it; its first word too, as other readers do. */
static const char *check_obj(FILE *f, const char *path, char *why, size_t len) {
  struct stat self;
  if (fstat(fileno(f), &self) != 0) return NULL;
  char line[4096];
  for (unsigned long n = 1; fgets(line, sizeof line, f); n++) {
    const char *p = line + strspn(line, " \t");
    if (strncmp(p, "mtllib", 6) != 0 || (p[6] != ' ' && p[6] != '\t')) continue;
    p += 6 + strspn(p + 6, " \t");
    size_t all = strcspn(p, "\r\n"), word = strcspn(p, " \t\r\n");
    while (all > 0 && (p[all - 1] == ' ' || p[all - 1] == '\t')) all--;
    if ((all && names_itself(path, p, all, &self)) || (word && names_itself(path, p, word, &self))) {
      snprintf(why, len, "line %lu: `mtllib %.*s` names the OBJ itself as its material library", n,
               (int)(all < 200 ? all : 200), p);
      return why;
    }
  }
  return NULL;
}

const char *rc_mesh_check(const char *path, size_t bytes, char *why, size_t len) {
  bool ply = rc_has_extension(path, ".ply"), off = rc_has_extension(path, ".off"),
       obj = rc_has_extension(path, ".obj");
  if (!ply && !off && !obj) return NULL;
  FILE *f = fopen(path, "rb");
  if (!f) return NULL; /* the importer's open reports it */
  const char *problem = ply   ? check_ply(f, bytes, why, len)
                        : off ? check_off(f, bytes, why, len)
                              : check_obj(f, path, why, len);
  fclose(f);
  return problem;
}

const char *rc_mtl_check(FILE *f, char *why, size_t len) {
  char line[1024];
  const char *problem = NULL;
  rewind(f);
  for (unsigned long n = 1; !problem && fgets(line, sizeof line, f); n++) {
    const char *p = line;
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\v' || *p == '\f') p++;
    if (*p == '\n' || *p == '\0' || *p == '#') continue;
    size_t word = strcspn(p, " \t\r\n\v\f");
    if (word == 6 && strncmp(p, "newmtl", 6) == 0) break;
    snprintf(why, len, "line %lu: `%.*s` before the first `newmtl` belongs to no material (is it a material library?)",
             n, (int)(word < 40 ? word : 40), p);
    problem = why;
  }
  rewind(f);
  return problem;
}
