/* patch_bounds.h: the largest differences of a Bezier patch's control net, which the
 * certified mode's bounds on the patch's derivatives are made of (rc_shared.h,
 * RC_QUADRIC_PATCH; rc_certify_patch.glsl, cert_patch_bounds). Computed once per patch on
 * the host instead of per ray in the shader: docs/performance.md, "Patch bounds packed". */
#ifndef RC_PATCH_BOUNDS_H
#define RC_PATCH_BOUNDS_H

#include "scene/scene_pack.h"

/* The five largest lengths, in packed units, of the net whose 16 points (x, y, z, w: 4
 * floats each, row r along v, column c along u) start at `net`: first differences along u,
 * along v, mixed, second along u, along v. Each computed in f64 and rounded up to f32 (a
 * length past f32's range is infinity). */
void rc_patch_net_differences(const float *net, float out[5]);

/* Stores them in every patch piece of `packed` (after packing, and again after --perturb
 * moves the control points). */
void rc_packed_patch_bounds(rc_packed_scene *packed);

/* Whether every patch piece of `packed` holds its net's differences exactly (a prepared
 * file's check); false names the first piece that does not in *piece. */
bool rc_packed_patch_bounds_match(const rc_packed_scene *packed, uint32_t *piece);

#endif
