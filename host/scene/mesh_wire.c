#include "scene/mesh_wire.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/* A cursor over the answer, in words. Every count is checked against what is left before
 * anything is taken, so a short or corrupt answer is an error, never a read past it. */
typedef struct {
  const uint32_t *at, *end;
} cursor;

static bool take_word(cursor *c, uint32_t *w) {
  if (c->at >= c->end) return false;
  *w = *c->at++;
  return true;
}

static const void *take_words(cursor *c, uint64_t words) {
  if (words > (uint64_t)(c->end - c->at)) return NULL;
  const void *p = c->at;
  c->at += words;
  return p;
}

/* A string: its length in bytes, then the bytes and at least one NUL, padded to a word. */
static const char *take_string(cursor *c) {
  uint32_t len;
  if (!take_word(c, &len)) return NULL;
  const char *s = take_words(c, ((uint64_t)len + 4) / 4);
  return s && s[len] == '\0' && strlen(s) == len ? s : NULL;
}

static bool take_magic(cursor *c, const char magic[4]) {
  const void *p = take_words(c, 1);
  return p && memcmp(p, magic, 4) == 0;
}

const char *rc_mesh_wire_parse(void *buffer, size_t len, rc_mesh_data *d) {
  memset(d, 0, sizeof *d);
  d->buffer = buffer;
  d->length = len;
  if (len % 4) return "its length is not a whole number of words";
  cursor c = {buffer, (const uint32_t *)buffer + len / 4};
  uint32_t version;
  if (!take_magic(&c, "VKRM") || !take_word(&c, &version)) return "it does not begin as an answer";
  if (version != RC_MESH_WIRE_VERSION) return "it is from another version of the importer";
  if (!take_word(&c, &d->outcome) || d->outcome > RC_MESH_FAILED) return "its outcome is missing";
  if (!(d->message = take_string(&c))) return "its message is cut short";
  if (!take_word(&c, &d->input_count) || d->input_count > (size_t)(c.end - c.at)) return "its files are cut short";
  d->inputs = malloc((d->input_count ? d->input_count : 1) * sizeof *d->inputs);
  if (!d->inputs) return "out of memory";
  for (uint32_t i = 0; i < d->input_count; i++)
    if (!(d->inputs[i] = take_string(&c))) return "its files are cut short";
  if (d->outcome == RC_MESH_IMPORTED) {
    enum { MATERIAL_WORDS = sizeof(rc_mesh_material) / 4 };
    _Static_assert(sizeof(rc_mesh_material) == 13 * sizeof(float), "13 floats a material on the wire");
    if (!take_word(&c, &d->material_count) ||
        !(d->materials = take_words(&c, (uint64_t)d->material_count * MATERIAL_WORDS)))
      return "its materials are cut short";
    if (!take_word(&c, &d->part_count) || d->part_count > (size_t)(c.end - c.at) / 4) return "its parts are cut short";
    d->parts = calloc(d->part_count ? d->part_count : 1, sizeof *d->parts);
    if (!d->parts) return "out of memory";
    for (uint32_t i = 0; i < d->part_count; i++) {
      rc_mesh_part *p = &d->parts[i];
      if (!take_word(&c, &p->material) || !take_word(&c, &p->has_normals) || !take_word(&c, &p->has_uvs) ||
          !take_word(&c, &p->vertex_count) || !take_word(&c, &p->triangle_count))
        return "a part is cut short";
      if (p->material >= d->material_count || p->has_normals > 1 || p->has_uvs > 1)
        return "a part names what is not there";
      p->positions = take_words(&c, 3 * (uint64_t)p->vertex_count);
      if (p->has_normals) p->normals = take_words(&c, 3 * (uint64_t)p->vertex_count);
      if (p->has_uvs) p->uvs = take_words(&c, 2 * (uint64_t)p->vertex_count);
      p->indices = take_words(&c, 3 * (uint64_t)p->triangle_count);
      if (!p->positions || (p->has_normals && !p->normals) || (p->has_uvs && !p->uvs) || !p->indices)
        return "a part is cut short";
    }
  }
  if (!take_magic(&c, "MEND")) return "it does not end as an answer";
  if (c.at != c.end) return "it goes on past its end";
  return NULL;
}

void rc_mesh_data_free(rc_mesh_data *d) {
  free(d->inputs);
  free(d->parts);
  free(d->buffer);
  memset(d, 0, sizeof *d);
}
