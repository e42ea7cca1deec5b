/* staged_file.h: the transaction every image and file the renderer writes goes through,
 * shared by its three writers (image_io.cpp for OpenImageIO's formats, exr_write.cpp for
 * OpenEXR's, png_write.c for PNGs; each linked copy counts its own temporary names): the
 * bytes go to a temporary in the target's folder, and only a complete, fsynced file is
 * renamed over the target, so an existing file is never left half overwritten and no
 * signal leaves a temporary behind where O_TMPFILE is available. */
#ifndef RC_STAGED_FILE_H
#define RC_STAGED_FILE_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rc_staged {
  FILE *file;        /* the temporary, open for writing */
  char *path, *dir;  /* the target and its folder ("." for a bare name) */
  char *tmp;         /* the temporary's name; NULL while it has none (O_TMPFILE) */
} rc_staged;

/* Opens the temporary for `path`: unnamed (O_TMPFILE) where the filesystem allows it, else
 * a short hidden name beside the target. 0, or -1 with the reason in err (and *s empty). */
int rc_staged_open(rc_staged *s, const char *path, char *err, size_t err_len);
/* Every byte written so far on disk: stdio's buffer flushed, then fsync. 0 or -1. */
int rc_staged_sync(rc_staged *s, char *err, size_t err_len);
/* The whole file at once, `len` bytes, then rc_staged_sync. 0 or -1. */
int rc_staged_write_all(rc_staged *s, const void *bytes, size_t len, char *err, size_t err_len);
/* Names the temporary (linkat for an unnamed one), renames it over the target and fsyncs
 * the folder; closes the file either way. Call after rc_staged_sync. 0 or -1. */
int rc_staged_commit(rc_staged *s, char *err, size_t err_len);
/* Closes and removes the temporary; safe on an empty or committed *s. */
void rc_staged_discard(rc_staged *s);
/* The temporary's name, "" while it has none. */
const char *rc_staged_temp_path(const rc_staged *s);

#ifdef __cplusplus
}
#endif

#endif
