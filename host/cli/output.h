/* output.h: where a render's bands of rows go: the image file (and the AOV file) through
 * OpenImageIO's scanline writers, into temporary files renamed into place only when the
 * whole frame is written, every write checked and the file fsynced first (image_io.h).
 * The image, the AOV file and the statistics of a run are one commit: each old file is
 * kept as a hard link until every rename has succeeded, and put back if one fails.
 * The temporaries are unnamed where Linux allows it (O_TMPFILE); where they have names,
 * and for the backups, one signal thread takes every asynchronous terminating signal
 * (all other threads block them from the start), waits for a commit under way, unlinks
 * them and dies by the signal. SIGXFSZ (a file size limit) is ignored so that a full disk
 * or a size limit becomes a write error. Either way an existing image is never left half
 * overwritten, and the files of a run are all old or all new. */
#ifndef RC_OUTPUT_H
#define RC_OUTPUT_H

#include "image/image_io.h"
#include "base/rc_base.h"
#include "rc_shared.h"

typedef struct rc_output rc_output;

/* An image name whose extension OpenImageIO can write: RC_OK, RC_ERR_USAGE with the
 * message, or RC_ERR_INSTALL when the image module cannot be loaded. Loads the module, so
 * commands call it once their cheaper checks have passed, before anything is written. */
rc_status rc_output_check_format(const char *path);
/* rc_output_check_format before a scene is read: for the names every image format command
 * writes in practice (.png, .exr, .tif, .jpg, .hdr, ...), nothing, as the command checks
 * them with rc_output_check_format once the scene has been read; for any other name, that
 * check now, so that a name no format writes costs no scene read. Why: loading the image
 * module costs a process about 0.2 s of CPU, which a scene refused at parse need not pay
 * (docs/performance.md, "Process start-up", finding 12). */
rc_status rc_output_check_format_early(const char *path);

/* meta: header attributes of both files (image_io.h). image_path NULL: the AOV file alone
 * (merge of AOV parts, written by rc_output_aov_rows). */
rc_status rc_output_open(const char *image_path, const char *aov_path, uint32_t width, uint32_t height,
                         rc_encoding enc, bool truncate, const rc_image_meta *meta, int meta_count, rc_output **out);
/* Scene units per packed unit (1 / rc_packed_scene.scale): the AOV depth is written in
 * scene units. */
void rc_output_set_length_unit(rc_output *o, double unit);
/* An rc_band_fn (gpu_render.h): writes rows [y0, y0 + rows), given as floats or as the
 * image's 8-bit levels. */
rc_status rc_output_band(uint32_t y0, uint32_t rows, const float *rgb, const uint8_t *levels,
                         const packed_aov *aov, void *output);
/* Rows of the AOV file already in its channel layout (aov.h), RC_AOV_CHANNELS floats a
 * pixel: what `merge` copies from AOV parts. */
rc_status rc_output_aov_rows(rc_output *o, uint32_t rows, const float *channels);
/* A band function for frames that are not written (--repeat). */
rc_status rc_output_discard(uint32_t y0, uint32_t rows, const float *rgb, const uint8_t *levels,
                            const packed_aov *aov, void *unused);
/* Adds the statistics file (its whole text) to the transaction: written now, renamed
 * with the image. */
rc_status rc_output_attach(rc_output *o, const char *path, const char *text);
/* The same for any bytes (`what` names them in messages): a prepared scene, written alone. */
rc_status rc_output_attach_bytes(rc_output *o, const char *path, const void *bytes, size_t len, const char *what);
/* Renames the files into place (commit) or removes them; frees the output. */
rc_status rc_output_close(rc_output *o, bool commit);
double rc_output_write_ms(const rc_output *o);

/* Blocks the asynchronous terminating signals in the calling thread (and so in every
 * thread it starts) and starts the signal thread; once a process, first thing in main.
 * A child process must be started with an empty signal mask (posix_spawnattr). */
void rc_output_install_signal_handlers(void);

#endif
