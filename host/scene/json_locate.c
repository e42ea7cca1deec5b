#include "scene/json_locate.h"

#include <stdio.h>
#include <string.h>

typedef struct {
  const char *s;
  size_t len, pos;
} cursor;

static void skip_ws(cursor *c) {
  while (c->pos < c->len && strchr(" \t\r\n", c->s[c->pos]) && c->s[c->pos] != '\0') c->pos++;
}

/* Skips a string starting at '"'; sets [*start, *end) to its raw contents. */
static bool skip_string(cursor *c, size_t *start, size_t *end) {
  if (c->pos >= c->len || c->s[c->pos] != '"') return false;
  c->pos++;
  *start = c->pos;
  while (c->pos < c->len && c->s[c->pos] != '"') c->pos += (c->s[c->pos] == '\\') ? 2 : 1;
  if (c->pos >= c->len) return false;
  *end = c->pos++;
  return true;
}

static bool skip_value(cursor *c, int depth);

static bool skip_container(cursor *c, char open, char close, int depth) {
  if (depth > 2000) return false;
  c->pos++; /* open */
  skip_ws(c);
  if (c->pos < c->len && c->s[c->pos] == close) {
    c->pos++;
    return true;
  }
  for (;;) {
    if (open == '{') {
      size_t a, b;
      skip_ws(c);
      if (!skip_string(c, &a, &b)) return false;
      skip_ws(c);
      if (c->pos >= c->len || c->s[c->pos] != ':') return false;
      c->pos++;
    }
    if (!skip_value(c, depth + 1)) return false;
    skip_ws(c);
    if (c->pos >= c->len) return false;
    if (c->s[c->pos] == ',') {
      c->pos++;
      continue;
    }
    if (c->s[c->pos] == close) {
      c->pos++;
      return true;
    }
    return false;
  }
}

static bool skip_value(cursor *c, int depth) {
  skip_ws(c);
  if (c->pos >= c->len) return false;
  char ch = c->s[c->pos];
  if (ch == '{') return skip_container(c, '{', '}', depth);
  if (ch == '[') return skip_container(c, '[', ']', depth);
  if (ch == '"') {
    size_t a, b;
    return skip_string(c, &a, &b);
  }
  while (c->pos < c->len && !strchr(",]} \t\r\n", c->s[c->pos])) c->pos++;
  return true;
}

/* Compares a raw JSON string (escapes undecoded) with a plain key; keys with escapes
 * compare unequal, which only costs a less precise location. */
static bool key_equals(const cursor *c, size_t a, size_t b, const char *key) {
  size_t n = strlen(key);
  return b - a == n && memcmp(c->s + a, key, n) == 0;
}

size_t rc_json_locate(const char *text, size_t len, const rc_json_step *path, size_t depth) {
  cursor c = {text, len, 0};
  skip_ws(&c);
  return rc_json_locate_from(text, len, c.pos, path, depth);
}

size_t rc_json_locate_from(const char *text, size_t len, size_t start, const rc_json_step *path, size_t depth) {
  cursor c = {text, len, start};
  for (size_t d = 0; d < depth; d++) {
    size_t here = c.pos;
    if (c.pos >= len) return here;
    if (path[d].key) {
      if (text[c.pos] != '{') return here;
      c.pos++;
      bool found = false;
      size_t seen = 0;
      for (;;) {
        size_t a, b;
        skip_ws(&c);
        if (!skip_string(&c, &a, &b)) return here;
        skip_ws(&c);
        if (c.pos >= len || text[c.pos] != ':') return here;
        c.pos++;
        skip_ws(&c);
        if (key_equals(&c, a, b, path[d].key) && seen++ == path[d].index) {
          found = true;
          break;
        }
        if (!skip_value(&c, 0)) return here;
        skip_ws(&c);
        if (c.pos >= len || text[c.pos] != ',') return here;
        c.pos++;
      }
      if (!found) return here;
    } else {
      if (text[c.pos] != '[') return here;
      c.pos++;
      for (size_t i = 0; i < path[d].index; i++) {
        if (!skip_value(&c, 0)) return here;
        skip_ws(&c);
        if (c.pos >= len || text[c.pos] != ',') return here;
        c.pos++;
      }
      skip_ws(&c);
    }
  }
  return c.pos;
}

void rc_json_line_col(const char *text, size_t len, size_t offset, int *line, int *col) {
  int l = 1, k = 1;
  for (size_t i = 0; i < offset && i < len; i++) {
    if (text[i] == '\n') {
      l++;
      k = 1;
    } else {
      k++;
    }
  }
  *line = l;
  *col = k;
}

size_t rc_json_token_length(const char *text, size_t len, size_t offset) {
  if (offset >= len || text[offset] == '{' || text[offset] == '[') return 0;
  cursor c = {text, len, offset};
  if (!skip_value(&c, 0)) return 0;
  return c.pos - offset;
}

size_t rc_json_find_nul_escape(const char *text, size_t len) {
  bool in_string = false;
  for (size_t i = 0; i < len; i++) {
    if (!in_string) {
      in_string = text[i] == '"';
    } else if (text[i] == '"') {
      in_string = false;
    } else if (text[i] == '\\') {
      if (i + 5 < len && memcmp(text + i + 1, "u0000", 5) == 0) return i;
      i++; /* the escaped character, which may be a quote */
    }
  }
  return len;
}

size_t rc_json_next_value(const char *text, size_t len, size_t offset, bool member) {
  cursor c = {text, len, offset};
  if (!skip_value(&c, 0)) return len;
  skip_ws(&c);
  if (c.pos >= len || text[c.pos] != ',') return len;
  c.pos++;
  skip_ws(&c);
  if (member) {
    size_t a, b;
    if (!skip_string(&c, &a, &b)) return len;
    skip_ws(&c);
    if (c.pos >= len || text[c.pos] != ':') return len;
    c.pos++;
    skip_ws(&c);
  }
  return c.pos;
}

bool rc_json_truncated(const char *text, size_t len, size_t offset, size_t *opened) {
  /* A stack of the offsets of open brackets, bounded: deeper nesting than this is
   * reported as whatever cJSON said. */
  size_t stack[256], depth = 0, string_at = len;
  bool in_string = false, overflow = false;
  for (size_t i = 0; i < len; i++) {
    char ch = text[i];
    if (in_string) {
      if (ch == '\\') i++;
      else if (ch == '"') in_string = false;
    } else if (ch == '"') {
      in_string = true, string_at = i;
    } else if (ch == '{' || ch == '[') {
      if (depth < sizeof stack / sizeof *stack) stack[depth] = i;
      else overflow = true;
      depth++;
    } else if ((ch == '}' || ch == ']') && depth > 0) {
      depth--;
    }
  }
  *opened = in_string ? string_at : depth > 0 && !overflow ? stack[depth - 1] : len;
  if (*opened == len) return false;
  for (size_t i = offset; i < len; i++)
    if (strchr("{}[],:", text[i]) && !(in_string && i >= string_at)) return false;
  return true;
}

void rc_json_quote(const char *text, size_t len, size_t max, char *out, size_t cap) {
  size_t o = 0;
  if (cap < 8) {
    if (cap) out[0] = '\0';
    return;
  }
  out[o++] = '\'';
  for (size_t i = 0; i < len && i < max && o + 6 < cap; i++) {
    unsigned char ch = (unsigned char)text[i];
    if (ch == '\n') o += (size_t)snprintf(out + o, cap - o, "\\n");
    else if (ch == '\t') o += (size_t)snprintf(out + o, cap - o, "\\t");
    else if (ch == '\r') o += (size_t)snprintf(out + o, cap - o, "\\r");
    else if (ch < 32 || ch > 126) o += (size_t)snprintf(out + o, cap - o, "\\x%02x", ch);
    else out[o++] = (char)ch;
  }
  out[o++] = '\'';
  out[o] = '\0';
}

rc_status rc_scene_check_text(const char *path, const char *text, size_t len) {
  const char *nul = memchr(text, '\0', len);
  if (!nul) return RC_OK;
  int line, col;
  rc_json_line_col(text, len, (size_t)(nul - text), &line, &col);
  fprintf(stderr, "%s:%d:%d: error: a NUL byte (byte %zu of the file)\n", path, line, col, (size_t)(nul - text));
  return RC_ERR_INPUT;
}
