/* json_locate.h: where a JSON value sits in its source text. cJSON keeps no positions,
 * so error messages find the line and column of a field by walking the original text
 * along the field's path (object keys and array indices). */
#ifndef RC_JSON_LOCATE_H
#define RC_JSON_LOCATE_H

#include <stdbool.h>
#include <stddef.h>

#include "base/rc_base.h"

typedef struct rc_json_step {
  const char *key; /* object member, or NULL for an array element */
  size_t index;    /* array element; for a member, which occurrence of a repeated key */
} rc_json_step;

/* Offset of the value at `path` (or of the deepest prefix that exists). */
size_t rc_json_locate(const char *text, size_t len, const rc_json_step *path, size_t depth);
/* The same from the value at `start`, `path` relative to it: a place inside one object
 * of a long array costs that object, not the array before it. */
size_t rc_json_locate_from(const char *text, size_t len, size_t start, const rc_json_step *path, size_t depth);
/* Offset of the element or member value after the one at `offset` in the same array or
 * object (member: skip its key), or len when it was the last: walking a long array costs
 * its length once, where rc_json_locate per element would cost its square. */
size_t rc_json_next_value(const char *text, size_t len, size_t offset, bool member);
/* 1-based line and column (in bytes) of an offset. */
void rc_json_line_col(const char *text, size_t len, size_t offset, int *line, int *col);

/* Neither scene format allows a NUL byte, which would silently end the C string of a name
 * or a token that holds it: an error with its line and column. Both parsers call it
 * first, so it lives below them. */
rc_status rc_scene_check_text(const char *path, const char *text, size_t len);
/* Offset of the first "\u0000" escape inside a string (a NUL that would end the decoded
 * name early), or len when there is none. */
size_t rc_json_find_nul_escape(const char *text, size_t len);
/* Length of the scalar token at offset (number, string, literal); 0 for objects/arrays. */
size_t rc_json_token_length(const char *text, size_t len, size_t offset);

/* Whether a parse error at `offset` is the text ending inside a value: at the end some
 * object, array or string is still open and nothing structural follows the error. Sets
 * *opened to where the innermost open value began (len when nothing is open). */
bool rc_json_truncated(const char *text, size_t len, size_t offset, size_t *opened);
/* Up to `max` bytes of text, quoted, with control characters and bytes over 126 escaped
 * (\n, \t, \xNN): an error message quotes a file without breaking its own line. */
void rc_json_quote(const char *text, size_t len, size_t max, char *out, size_t cap);

#endif
