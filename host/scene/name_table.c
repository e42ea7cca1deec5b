#include "scene/name_table.h"

#include <stdlib.h>
#include <string.h>

struct rc_name_slot {
  char *key; /* NULL: empty */
  size_t len;
  uint64_t hash;
  uint32_t value;
};

uint64_t rc_hash_bytes(const void *key, size_t len) {
  const unsigned char *p = key;
  uint64_t h = 0xcbf29ce484222325u;
  for (size_t i = 0; i < len; i++) h = (h ^ p[i]) * 0x100000001b3u;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9u;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebu;
  return h ^ (h >> 31);
}

static rc_name_slot *probe(rc_name_slot *slots, size_t cap, uint64_t h, const void *key, size_t len) {
  for (size_t i = (size_t)h & (cap - 1);; i = (i + 1) & (cap - 1)) {
    rc_name_slot *s = &slots[i];
    if (!s->key || (s->hash == h && s->len == len && memcmp(s->key, key, len) == 0)) return s;
  }
}

static bool grow(rc_name_table *t) {
  size_t cap = t->cap ? 2 * t->cap : 64;
  rc_name_slot *slots = calloc(cap, sizeof *slots);
  if (!slots) return false;
  for (size_t i = 0; i < t->cap; i++) {
    rc_name_slot *old = &t->slots[i];
    if (old->key) *probe(slots, cap, old->hash, old->key, old->len) = *old;
  }
  free(t->slots);
  t->slots = slots;
  t->cap = cap;
  return true;
}

bool rc_name_table_insert(rc_name_table *t, const void *key, size_t len, uint32_t value, uint32_t *out,
                          bool *was_present) {
  if (2 * (t->count + 1) > t->cap && !grow(t)) return false;
  uint64_t h = rc_hash_bytes(key, len);
  rc_name_slot *s = probe(t->slots, t->cap, h, key, len);
  *was_present = s->key != NULL;
  if (!s->key) {
    char *copy = malloc(len ? len : 1);
    if (!copy) return false;
    memcpy(copy, key, len);
    *s = (rc_name_slot){copy, len, h, value};
    t->count++;
  }
  *out = s->value;
  return true;
}

bool rc_name_table_find(const rc_name_table *t, const void *key, size_t len, uint32_t *out) {
  if (!t->cap) return false;
  const rc_name_slot *s = probe(t->slots, t->cap, rc_hash_bytes(key, len), key, len);
  if (!s->key) return false;
  *out = s->value;
  return true;
}

void rc_name_table_free(rc_name_table *t) {
  for (size_t i = 0; i < t->cap; i++) free(t->slots[i].key);
  free(t->slots);
  *t = (rc_name_table){0};
}
