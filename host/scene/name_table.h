/* name_table.h: byte strings to indices in expected O(1), so that parsing a scene is
 * linear in its size. Named materials, and the .test reader's deduplicated material
 * states, were found by a scan of all earlier ones: 200,000 materials took minutes.
 * Open addressing with linear probing, FNV-1a hashes, at most half full. The table
 * keeps its own copy of each key. */
#ifndef RC_NAME_TABLE_H
#define RC_NAME_TABLE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct rc_name_slot rc_name_slot;

typedef struct rc_name_table {
  rc_name_slot *slots;
  size_t cap, count; /* cap: a power of two, or 0 before the first insert */
} rc_name_table;

/* The hash both this table and the BVH's repeat detection (bvh.c) use: FNV-1a over the
 * bytes (Fowler, Noll, Vo), then splitmix64's finalizer so that the low bits, which a
 * power-of-two table keeps, depend on every byte. */
uint64_t rc_hash_bytes(const void *key, size_t len);

/* Finds `key`; when absent, adds it with `value`. *out is the value stored for the key
 * (the earlier one when it was present). False only when memory runs out. */
bool rc_name_table_insert(rc_name_table *t, const void *key, size_t len, uint32_t value, uint32_t *out,
                          bool *was_present);
/* The value of `key`, or false when absent. */
bool rc_name_table_find(const rc_name_table *t, const void *key, size_t len, uint32_t *out);
void rc_name_table_free(rc_name_table *t);

#endif
