/* prepared.h: a scene packed and its BVH built once, in one file (`vkraycast prepare`,
 * `.vkrs`), that every shard of a render farm maps instead of parsing the scene, reading
 * its meshes and building the tree again (docs/cluster.md, "Prepared scenes").
 *
 * The file holds every array the renderers read (rc_packed_scene's, in the byte layout of
 * rc_shared.h), the BVH, and the scene's summary: the settings the frame is re-derived
 * from (so that --spp, --width, the formulas and the other frame overrides apply exactly
 * as they do to a parsed scene, through rc_scene_pack_frame), the counts the statistics
 * report, the places in the scene file that messages name, the 8-bit output rules and the
 * files the scene read. The arrays are mapped and used where they lie; only --perturb
 * and --accel none (a different tree) copy them and build the BVH again.
 *
 * Layout, all in the writer's byte order: a header (magic, byte order, format version,
 * struct layout, size, checksum, the source digest, the sections' offsets and sizes), then
 * the sections, each 64-byte aligned: the summary (a sequence of fixed-width values and
 * length-prefixed strings) and one section per array. The checksum (XXH3-64) covers every
 * byte after it. A reader refuses, naming which: a file too short for its header
 * (truncated), one without the magic (foreign), another byte order, another format
 * version or struct layout, a size other than the header's (truncated or extended), a
 * checksum that does not match (damaged or changed), a summary or array that is
 * malformed or inconsistent (an index past its array: checked here, so that no renderer
 * reads outside an array even for a file whose checksum was forged), and, given the
 * scene, one whose source digest differs (stale). The checksum detects damage and
 * careless edits; it is not a signature.
 *
 * RC_PREPARED_VERSION changes whenever the packing or the tree changes what it writes,
 * so that a file is never rendered by a build that would pack the scene differently. */
#ifndef RC_PREPARED_H
#define RC_PREPARED_H

#include "scene/bvh.h"
#include "scene/scene.h"
#include "scene/scene_pack.h"

#define RC_PREPARED_VERSION 4u
#define RC_PREPARED_EXTENSION ".vkrs"

typedef struct rc_prepared rc_prepared;

/* The file's bytes for a scene packed by rc_scene_pack and given its object tree by
 * rc_bvh_build(packed, true, bvh): malloc'ed into *bytes. `source_digest`:
 * rc_source_digest of the scene and its inputs. */
rc_status rc_prepared_encode(const rc_scene *scene, const rc_packed_scene *packed, const rc_bvh_stats *bvh,
                             uint64_t source_digest, void **bytes, size_t *len);

/* Maps and checks the file at `path` (messages name it); fills *scene with the summary
 * (free it with rc_scene_free; it holds no primitives, only their counts, and its
 * origins' names point into the file, so close the file after the scene). */
rc_status rc_prepared_open(const char *path, rc_prepared **out, rc_scene *scene);
/* The same checks on bytes in memory (the fuzzer's entry); `bytes` must outlive *out. */
rc_status rc_prepared_decode(const char *name, const void *bytes, size_t len, rc_prepared **out, rc_scene *scene);
void rc_prepared_close(rc_prepared *pf);

/* The packed scene for `scene` (the summary with the command line's overrides applied):
 * the frame re-derived, the arrays and the tree where they lie in the file (borrowed:
 * rc_packed_scene_free leaves them). For --accel none and --perturb, whose trees differ,
 * use rc_prepared_packed_copy. Refuses (exit status 2) overrides that would change the
 * packed arrays (--camera-relative, --rescale). */
rc_status rc_prepared_packed(const rc_prepared *pf, const rc_scene *scene, rc_packed_scene *packed);
/* The same with arrays of its own and no tree (for --perturb, --accel none): the caller
 * builds it with rc_bvh_build. */
rc_status rc_prepared_packed_copy(const rc_prepared *pf, const rc_scene *scene, rc_packed_scene *packed);
/* What building the tree reported when the file was prepared. */
rc_bvh_stats rc_prepared_bvh_stats(const rc_prepared *pf);

/* A digest of the scene file's bytes and, in order, each input's path and bytes: what a
 * prepared file records and `render SCENE --prepared FILE` compares (a mismatch: the file
 * is stale). Messages name the file that cannot be read. */
rc_status rc_source_digest(const char *scene_path, char *const *inputs, size_t input_count, uint64_t *digest);
/* Checks that `scene_path` and the inputs the file records (scene: its summary) still
 * have the digest it was prepared from; RC_ERR_INPUT, naming both files, when not. */
rc_status rc_prepared_check_source(const rc_prepared *pf, const rc_scene *scene, const char *scene_path);

#endif
