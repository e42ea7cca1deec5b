/* aov.h: the decision-output (AOV) file: a float EXR with the colour and the packed_aov
 * record of each pixel's first sample, in the channels named below. */
#ifndef RC_AOV_H
#define RC_AOV_H

#include "compare/compare.h"
#include "rc_shared.h"

#define RC_AOV_CHANNELS 12
/* The channels a file must have; `uncertified` and `decisions` came later. */
#define RC_AOV_REQUIRED_CHANNELS 10
#define RC_AOV_MAX_CHANNELS 64
extern const char *const rc_aov_channel_names[RC_AOV_CHANNELS]; /* R G B hit object t N.X N.Y N.Z shadow
                                                                                   uncertified decisions */

/* Interleaves count pixels of colour and records into the AOV channel layout; the depth t
 * times length_unit (scene units per packed unit, scene_pack.h). */
void rc_aov_pack(const float *rgb, const packed_aov *aov, size_t count, double length_unit, float *out);
/* Where the decision channels of a file are (files may reorder channels: OpenEXR stores
 * them sorted by name). */
/* uncertified, decisions: -1 in a file written before the channel existed. */
typedef struct rc_aov_layout { int r, g, b, hit, object, t, nx, ny, nz, shadow, uncertified, decisions; } rc_aov_layout;
/* True when the file has every AOV channel (`uncertified` and `decisions` may be missing);
 * fills the layout. */
bool rc_aov_find_channels(char names[][32], int count, rc_aov_layout *layout);
/* Counts pixels whose hit flag, object index or shadow bits differ (sets r->decisions), and
 * where both files have the digest of every sample's decisions, the pixels whose digests
 * differ (r->sample_mismatch), leaving out the pixels where band[i] is set (the
 * conditioning band, docs/accuracy.md; band may be NULL), and measures depth and normal
 * error where both hit the same object, and the PSNR of the pixels that decide alike
 * (r->psnr_alike). */
void rc_aov_compare_decisions(const float *a, const rc_aov_layout *la, const float *b, const rc_aov_layout *lb,
                              int width, int height, int channels, const unsigned char *band, rc_compare_result *r);
/* True when pixel i of the two AOV files has the same hit flag, object and shadow bits,
 * and, where both record it, the same digest of every sample's decisions. */
bool rc_aov_same_decisions(const float *a, const rc_aov_layout *la, const float *b, const rc_aov_layout *lb, int c,
                           size_t i);

#endif
