/* rc_shared.h: every struct, binding number and constant that both the C host and the
 * GLSL shaders see. Compiled as C11 (host, CPU reference, tests) and as GLSL 450
 * (glslangValidator defines VULKAN, which selects the GLSL side).
 *
 * Layout rules (std430 storage buffers, std140 uniform buffer, RGBA32UI texel buffers):
 *  - only vec4, scalars, and a vec3 always followed by one 4-byte scalar;
 *  - every struct is a multiple of 16 bytes, so one struct is a whole number of texels;
 *  - no bool, no scalar arrays in the uniform buffer;
 *  - padding fields are named pad0, pad1, ...
 * The C tail of this file asserts every size and offset; tests/unit/test_layout.sh checks
 * the same numbers against glslang's reflection. */
#ifndef RC_SHARED_H
#define RC_SHARED_H

#ifndef VULKAN
#include <stddef.h>
#include <stdint.h>
typedef uint32_t uint;
typedef struct { float x, y, z; } vec3;
typedef struct { float x, y, z, w; } vec4;
/* GLSL has no typedef; C gets the struct names as type names up front. */
typedef struct packed_camera packed_camera;
typedef struct packed_frame packed_frame;
typedef struct packed_sphere packed_sphere;
typedef struct packed_triangle packed_triangle;
typedef struct packed_material packed_material;
typedef struct packed_light packed_light;
typedef struct packed_status packed_status;
typedef struct packed_levels packed_levels;
typedef struct packed_push packed_push;
typedef struct packed_aov packed_aov;
typedef struct packed_bvh_node packed_bvh_node;
typedef struct packed_transform packed_transform;
typedef struct packed_vertex_normals packed_vertex_normals;
typedef struct packed_quadric packed_quadric;
typedef struct packed_csg packed_csg;
typedef struct packed_texture packed_texture;
typedef struct packed_vertex_uvs packed_vertex_uvs;
#endif

/* Descriptor bindings (set 0). The scene arrays (spheres, triangles, materials, lights,
 * the BVH's nodes and references, transforms, normals, quadrics, composites and their
 * programs, textures: 12 in all) are read either as storage buffers or as RGBA32UI uniform texel
 * buffers (rc_scene_access.glsl); the binding numbers are the same for both kinds. */
#define RC_BINDING_FRAME 0     /* uniform packed_frame */
#define RC_BINDING_SPHERES 1   /* packed_sphere[] */
#define RC_BINDING_TRIANGLES 2 /* packed_triangle[] */
#define RC_BINDING_MATERIALS 3 /* packed_material[] */
#define RC_BINDING_LIGHTS 4    /* packed_light[] */
#define RC_BINDING_ACCUM 5     /* vec4 per tile pixel: rgb = sum of samples, a = progress (RC_SPEC_LIGHT_PASSES) */
#define RC_BINDING_STATUS 6    /* packed_status */
/* packed_aov per tile pixel (written only when aov_enabled). With RC_SPEC_LEVELS, which
 * never comes with AOVs, the same binding holds packed_levels, then a uint per tile pixel:
 * its levels (r, g, b in bytes 0-2) and 255 in byte 3 once the pixel has all its samples.
 * (A binding of its own made the storage-buffer path's layout one descriptor too many for
 * the minimum device and for NVIDIA's best practices.) */
#define RC_BINDING_AOV 7
#define RC_BINDING_BVH_NODES 8 /* packed_bvh_node[] (texel or storage, like the scene arrays) */
#define RC_BINDING_BVH_PRIMS 9 /* uint[] object references of the leaves, 4 per texel */
#define RC_BINDING_TRANSFORMS 10 /* packed_transform[] of transformed spheres */
#define RC_BINDING_NORMALS 11    /* packed_vertex_normals[] of smooth-shaded triangles */
#define RC_BINDING_QUADRICS 12   /* packed_quadric[]: the standalone ones, then the CSG leaves */
#define RC_BINDING_CSG 13        /* packed_csg[] */
#define RC_BINDING_CSG_PROGRAM 14 /* uint[] CSG instructions, 4 per texel */
#define RC_BINDING_TEXELS 15     /* textures: each a packed_texture, then its texels (RGBA f32) */
#define RC_BINDING_COUNT 16
#define RC_LEVEL_COUNT 256

/* Specialization constant ids. */
#define RC_SPEC_LOCAL_SIZE_X 0
#define RC_SPEC_LOCAL_SIZE_Y 1
#define RC_SPEC_LOOP_BUDGET 2
#define RC_SPEC_AOV 3 /* bool: record the decision outputs (packed_aov) */
#define RC_SPEC_BVH 4 /* bool: traverse the BVH (else test every object) */
#define RC_SPEC_SPHERE_FORMULA 5   /* RC_SPHERE_* */
#define RC_SPEC_TRIANGLE_FORMULA 6 /* RC_TRIANGLE_* */
#define RC_SPEC_OFFSET_STRATEGY 7  /* RC_OFFSET_* */
#define RC_SPEC_OFFSET_EPSILON 8   /* float: the epsilon strategy's distance */
/* The scene's features (create_pipeline, host/gpu/gpu_render.c): code for a kind the scene
 * lacks is compiled out, and the light loop and bounce count become constants. A generic
 * pipeline (render --pipeline generic) sets every kind and RC_LIGHTS_FROM_FRAME. */
#define RC_SPEC_KINDS 9            /* bit mask of RC_KIND_* present */
#define RC_SPEC_LIGHT_COUNT 10     /* the number of lights, or RC_LIGHTS_FROM_FRAME */
#define RC_SPEC_SHADOWS 11         /* 1: trace shadow rays, 0: not, or RC_SHADOWS_FROM_FRAME */
#define RC_SPEC_SPECULAR_MODEL 12  /* RC_SPECULAR_*, or RC_SPECULAR_FROM_FRAME */
#define RC_SPEC_REFLECTION_DEPTH 13 /* mirror bounces, or RC_DEPTH_FROM_FRAME */
#define RC_SPEC_SAMPLES 14         /* 1 for one sample a pixel, else RC_SAMPLES_FROM_FRAME */
/* bool: a sample's lights are shaded in passes of push.light_pass (host/gpu/gpu_plan.h),
 * and accum.a counts lights (sample x lights + lights done) instead of samples */
#define RC_SPEC_LIGHT_PASSES 15
/* 0, or 1 + the curve (RC_LEVEL_CURVE_*): the shader encodes each pixel's sum into the
 * output file's 8-bit levels (in RC_BINDING_AOV) in the dispatch that completes it, and
 * the host reads those back instead of the sums (render --gpu-encode) */
#define RC_SPEC_LEVELS 16
#define RC_SPEC_COUNT 17 /* the ids above: 0 to RC_SPEC_COUNT - 1, each 4 bytes at 4 x id */
#define RC_KIND_SPHERES 1u
#define RC_KIND_TRIANGLES 2u
#define RC_KIND_QUADRICS 4u /* the quadric test: a standalone quadric that is not a plane, or planes
                             * without the BVH (with it, test_planes tests them; the quadric test in
                             * the leaf loop cost a scene of planes and a mesh 4x the loop's
                             * instructions, docs/performance.md) */
#define RC_KIND_CSG 8u
#define RC_KIND_PLANES 16u /* frame.plane_count > 0: a plane loop after every traversal */
#define RC_KIND_CSG_MESHES 32u /* a composite has a closed mesh operand (RC_QUADRIC_MESH) */
#define RC_KIND_SPHERE_TRANSFORMS 64u /* a sphere has a transform (an ellipsoid) */
#define RC_KIND_VERTEX_NORMALS 128u   /* a triangle has vertex normals (smooth shading) */
#define RC_KIND_ONE_SIDED_TRIANGLES 256u /* a triangle has RC_TRIANGLE_ONE_SIDED */
#define RC_KIND_TEXTURES 512u /* a material has a texture (packed_material.texture) */
#define RC_KIND_PATCHES 1024u /* a quadric is a piece of a Bezier patch (RC_QUADRIC_PATCH) */
/* frame.loose_kinds holds RC_KIND_QUADRICS: the bounded quadrics are tested in a loop of
 * their own beside the tree, not in its leaves (host/scene/bvh.c, rc_loose_kinds) */
#define RC_KIND_LOOSE_QUADRICS 2048u
#define RC_KIND_ALL 4095u
#define RC_LIGHTS_FROM_FRAME 0xffffffffu
#define RC_SPECULAR_FROM_FRAME 0xffffffffu
#define RC_DEPTH_FROM_FRAME 0xffffffffu
#define RC_SHADOWS_FROM_FRAME 0xffffffffu
#define RC_SAMPLES_FROM_FRAME 0xffffffffu

/* The speed/accuracy knobs (docs/accuracy.md). The first of each is the robust default;
 * the GPU specializes on them (RC_SPEC_*), the CPU reference reads the copies in packed_frame. */
/* --precision certified (rc_certify.glsl, docs/numerics.md §10): off; on, a decision
 * certified when its margin exceeds its f32 error bound; halved and zero, the faults
 * injected to test the soundness tests (--certified-bound half, zero). */
#define RC_CERTIFY_OFF 0u
#define RC_CERTIFY_ON 1u
#define RC_CERTIFY_HALVED 2u
#define RC_CERTIFY_ZERO 3u
/* The side of a one-sided triangle a certified ray meets (cert_triangle_side). */
#define RC_SIDE_FRONT 0u
#define RC_SIDE_BACK 1u
#define RC_SIDE_UNSURE 2u

#define RC_SPHERE_GEOMETRIC 0u  /* Hearn-Baker discriminant, stable roots, centre-relative normal */
#define RC_SPHERE_ALGEBRAIC 1u  /* textbook b^2 - 4ac, (-b -/+ sqrt)/2a, normal from o + t d */
#define RC_TRIANGLE_WATERTIGHT 0u       /* Woop-Benthin-Wald, precise edge functions */
#define RC_TRIANGLE_MOLLER_TRUMBORE 1u  /* Moller-Trumbore 1997, with the paper's |det| < 1e-6 */
#define RC_TRIANGLE_CRAMER 2u           /* the textbook 3x3 Cramer solve (Shirley) */
#define RC_OFFSET_ERROR_BOUND 0u /* pbrt: along the normal by the hit point's rounding-error bound */
#define RC_OFFSET_ULP 1u         /* Wachter-Binder: a fixed count of ulps along the normal */
#define RC_OFFSET_EPSILON 2u     /* a fixed distance along the normal (quality.shadow_epsilon) */
#define RC_OFFSET_T_MIN 3u       /* the course's t_min: from the hit point, hits nearer than
                                  * quality.shadow_epsilon along the ray ignored */
#define RC_OFFSET_EPSILON_DEFAULT 1.0e-4

/* The builder caps the BVH's depth (host/scene/bvh.c): the loop plan's traversal estimate grows
 * with it (host/gpu/gpu_plan.c). Traversal itself is stackless (rc_bvh.glsl). */
#define RC_BVH_MAX_DEPTH 47
/* pbrt's conservative slab test: the far distance grows by 1 + 2 gamma(3) (f32) so that
 * rounding in the box test never culls a box the ray touches (Ize, JCGT 2(2), 2013). */
#define RC_BOX_FAR_SCALE 1.0000003576278687
/* The near cull: a box is skipped only when it is entered beyond the nearest hit so far
 * (or a shadow ray's t_max) times 1 + 2^-19, so that every object that can tie with or
 * undercut that hit after rounding is still tested and the tie rule sees it: the BVH
 * then picks what brute force picks (docs/numerics.md §4, tests/reliability/test_ties.sh).
 * Coplanar neighbours, where ties happen, get t from depths of one sign with at most
 * gamma(9) relative error, the slab entry has gamma(3), and (1 + gamma(3)) / (1 - gamma(9))
 * < 1 + 13 u in f32 (u = 2^-24); 2^-19 is 32 u. Exact in f32 and f64; RC_T_FAR times it
 * stays finite. */
#define RC_BOX_NEAR_SCALE 1.0000019073486328

/* llvmpipe silently ends every loop once one SIMD vector of lanes (a subgroup of
 * invocations) has run 65,535 loop iterations in total (tests/gpu/test_gpu_render.c
 * renders a scene past it). Every shader loop counts into one per-lane budget (a
 * specialization constant: this, a quarter below the cap, divided by the subgroup size on
 * llvmpipe: rc_gpu_loop_budget), and the host plans each dispatch's work so that its worst
 * case fits (host/gpu/gpu_plan.c). */
#define RC_LOOP_BUDGET 49152u

#define RC_PROJECTION_PERSPECTIVE 0u
#define RC_PROJECTION_PARALLEL 1u
#define RC_SPECULAR_BLINN_PHONG 0u
#define RC_SPECULAR_PHONG 1u
#define RC_LIGHT_POINT 0u
#define RC_LIGHT_DIRECTIONAL 1u
#define RC_HIT_NONE 0u
#define RC_HIT_SPHERE 1u
#define RC_HIT_TRIANGLE 2u
#define RC_HIT_QUADRIC 3u
#define RC_HIT_CSG 4u

/* "No hit" is a large finite t: Vulkan lets shaders assume no Inf (the SPIR-V environment). */
#define RC_T_FAR 3.0e38
/* A shadow ray towards a point light stops this fraction short of the light, so that a
 * light lying on a surface is not occluded by that surface (pbrt's ShadowEpsilon). */
#define RC_SHADOW_EPSILON 1.0e-4
/* Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing
 * Gems ch. 6 (2019): move a spawned origin int(256 n) ulps along the normal, or by n/65536
 * near the world origin where ulps are too fine to help. */
#define RC_OFFSET_ORIGIN (1.0 / 32.0)
#define RC_OFFSET_FLOAT_SCALE (1.0 / 65536.0)
#define RC_OFFSET_INT_SCALE 256.0

/* Camera, in the packed (camera-relative) space (docs/scene-format.md): the image plane spans
 * [left, right] x [bottom, top] at distance `focal` along -w from the eye. */
struct packed_camera {
  vec3 eye;   float left;
  vec3 u;     float right;
  vec3 v;     float bottom;
  vec3 w;     float top;
  float focal; uint projection; uint width; uint height;
};

/* The uniform buffer: the camera and everything else that is constant for a frame. */
struct packed_frame {
  packed_camera camera;
  vec3 background;    uint specular_model;
  vec3 ambient_light; uint reflection_depth;
  uint sphere_count;  uint triangle_count; uint material_count; uint light_count;
  uint samples_per_pixel; uint seed; uint strata_x; uint strata_y;
  uint object_count;      uint bvh_node_count;
  float inv_strata_x;     float inv_strata_y; /* 1/strata in f32: a multiply rounds the same on
                                                 both backends, a GPU division may not */
  /* The formula knobs, for the CPU reference; the GPU reads its specialization constants. */
  uint sphere_formula;    uint triangle_formula; uint offset_strategy; float offset_epsilon;
  uint quadric_count;     uint csg_count;
  uint shadows;           /* 0: no shadow rays */
  uint csg_max_steps;     /* the most loop steps one ray can take in a composite (the host's plan) */
  uint plane_count;       /* the last plane_count of the quadric_count standalone quadrics are
                             infinite planes: outside the BVH, every ray tests them */
  uint patch_count;       /* of the standalone quadrics, how many are patch pieces (RC_QUADRIC_PATCH) */
  uint light_buffers;     /* where the light buffers' table starts in the BVH's reference array
                             (RC_LIGHT_BUFFER_*); 0: the scene has none */
  uint certify;           /* RC_CERTIFY_*: certify each sample's decisions (--precision certified) */
  /* A sample's ray cone (texture level of detail, rc_trace.glsl): its width at the camera
   * (packed units; a parallel camera's pixel over sqrt(spp)) and its spread angle (radians;
   * a perspective camera's pixel over sqrt(spp)). */
  float cone_width;       float cone_spread;
  uint loose_kinds;       /* 0 or RC_KIND_QUADRICS: every bounded standalone quadric is out of
                             the object tree, tested by every ray in a loop of its own
                             (rc_bvh.glsl, test_loose): at most RC_LOOSE_MAX */
  uint pad_cone1;
};
/* Objects a frame may keep out of its tree (frame.loose_kinds), all kinds together. */
#define RC_LOOSE_MAX 8u

/* A sphere; with transform != RC_NO_TRANSFORM, the sphere (center, radius) lives in an
 * object space and the ray is taken there by packed_transform: an ellipsoid (CSE167 format,
 * JSON "transform"). */
#define RC_NO_TRANSFORM 0xffffffffu
struct packed_sphere {
  vec3 center; float radius;
  uint material; uint transform; uint pad1; uint pad2;
};

/* object_from_packed as the rows of a 3x4 affine matrix: p_obj = (row . (p, 1)). Its
 * linear part A also carries normals back: n_world ~ A^T n_obj (the inverse transpose of
 * world_from_object). */
struct packed_transform {
  vec4 row0;
  vec4 row1;
  vec4 row2;
};
#define RC_TEXELS_PER_TRANSFORM 3

/* Vertices in the packed space; the geometric normal is cross(v1 - v0, v2 - v0). With
 * normals != RC_NO_NORMALS the triangle is smooth shaded: its shading normal interpolates
 * packed_vertex_normals[normals] by the barycentrics (mesh files with vertex normals).
 * flags: RC_TRIANGLE_ONE_SIDED, a triangle there only for rays that meet its front (the
 * side its geometric normal points to, counter-clockwise winding) and transparent to every
 * other ray, shadow rays included, as a one-sided plane is. */
#define RC_NO_NORMALS 0xffffffffu
#define RC_TRIANGLE_ONE_SIDED 1u
/* flags >> RC_TRIANGLE_UV_SHIFT: 0, or 1 + the texel where the triangle's packed_vertex_uvs
 * lies in the texel array (RC_BINDING_TEXELS, after the textures: one binding fewer, which
 * NVIDIA's best practices ask of the storage-buffer path): the texture coordinates at its
 * vertices, JSON "uvs" or a mesh file's first uv channel. */
#define RC_TRIANGLE_UV_SHIFT 1u
struct packed_triangle {
  vec3 v0; uint material;
  vec3 v1; uint normals;
  vec3 v2; uint flags;
};

struct packed_vertex_normals {
  vec3 n0; float pad0;
  vec3 n1; float pad1;
  vec3 n2; float pad2;
};
#define RC_TEXELS_PER_VERTEX_NORMALS 3

/* A triangle's texture coordinates at v0, v1, v2 (RC_TRIANGLE_UV_SHIFT), 2 texels of the
 * texel array. */
struct packed_vertex_uvs {
  float u0; float v0; float u1; float v1;
  float u2; float v2; float pad0; float pad1;
};
#define RC_TEXELS_PER_VERTEX_UVS 2

/* A quadric surface Q = 0 clipped to a box, both in the quadric's own frame: f = R (p -
 * center), R's rows axis_x, axis_y, axis_z (orthonormal, unless the scene gave the object a
 * "transform": then R is the inverse of the transform's linear part times the shape's own
 * rotation, any invertible matrix; t is the same in both spaces, f = R(o - center) + t R d),
 * and
 *   Q = f^T M f + 2 linear.f + constant,
 *   M = [[diag.x, off.x, off.y], [off.x, diag.y, off.z], [off.y, off.z, diag.z]],
 * the box lo <= f <= hi. The named shapes (ellipsoid, cylinder, cone, ...) are built in
 * their principal frame (off = 0, centred), where the shader forms a, b, c from small,
 * axis-aligned products (little cancellation in f32) and a cylinder's caps are box faces; a
 * general matrix keeps R = I (its bounds are world-aligned) and its off-diagonal terms.
 * Q < 0 is the inside and grad Q the outward normal. With RC_QUADRIC_SOLID the object is
 * the solid {Q <= 0} inside the box, whose boundary includes the box faces where they cut
 * it (a capped cylinder; M = 0, linear = 0 and constant = -1 is the box itself); without
 * it, the open surface alone. CSG leaves are always solid. */
#define RC_QUADRIC_SOLID 1u
/* An infinite plane (scene type "plane"): Q = 2 f.z in a frame whose z is the unit normal
 * and whose centre is the plane's point nearest the eye, so that for a primary ray (o = 0
 * in packed space) t = -f.z / v.z is one division of two well-conditioned numbers. No clip
 * box (lo, hi are unused) and no place in the BVH. */
#define RC_QUADRIC_UNBOUNDED 2u
/* Hit only from the side the normal faces (a ray with d.normal < 0); seen from behind,
 * and for shadow rays leaving from behind, the plane is not there. */
#define RC_QUADRIC_ONE_SIDED 4u
/* A composite's operand that is a closed triangle mesh (scene type "mesh" inside a "csg"):
 * no quadric, only the box lo..hi (axes identity, centre 0) and the mesh's own BVH, nodes
 * [mesh_root, mesh_end) of the node array after the object tree, whose leaves reference
 * triangles after the standalone ones. A ray line crosses it at most mesh_crossings times
 * (the scene's "max_crossings"); its inside is where the number of crossings before a point
 * is odd (rc_quadric.glsl, mesh_intervals). */
#define RC_QUADRIC_MESH 8u
/* A piece of a bicubic Bezier patch (scene types "bezier_patch", "bezier_patches";
 * rc_patch.glsl): no quadric. The patch's 16 control points are 16 texels of the texel
 * array from mesh_root on (x, y, z in the packed space, row r = 0..3 of the net along v,
 * column c = 0..3 along u: texel mesh_root + 4 r + c); this piece is its part
 * [diag.x, diag.y] x [off.x, off.y] of the (u, v) square, whose control net lies in the box
 * lo..hi about `center` (axes identity): the piece's place in the BVH, and the box its rays
 * must enter. mesh_end: the quadric index of the patch's first piece (the patch's number
 * in the AOVs, packed_aov.object). A ray is solved by Newton's method on the piece, seeded at its centre
 * (Martin et al., "Practical Ray Tracing of Trimmed NURBS Surfaces", JGT 5(1), 2000).
 * The certificates' bounds on the patch's derivatives (rc_certify_patch.glsl,
 * cert_patch_bounds) take the net's largest differences, in packed units, from here:
 * linear = (first differences along u, along v, mixed differences), diag.z = second
 * differences along u, off.z = along v; each the largest length over the whole net,
 * computed in f64 from the f32 control points and rounded up (host/scene/patch_bounds.c;
 * a prepared file's are checked against them). They do not depend on the ray: lengths do
 * not change when the net is turned into a ray's frame. */
#define RC_QUADRIC_PATCH 16u
/* flags >> RC_QUADRIC_UV_SHIFT & 3: how a named shape's surface takes texture coordinates
 * (rc_shade.glsl, quadric_uv): none (a general matrix), as an ellipsoid (the sphere's
 * longitude and latitude of its normalized frame point), around its axis (frame z: the
 * cylinder, cone, paraboloid, hyperboloids), or a box's faces; any shape's box faces (caps)
 * take the face's two other frame coordinates across the box. */
#define RC_QUADRIC_UV_SHIFT 5u
#define RC_QUADRIC_UV_NONE 0u
#define RC_QUADRIC_UV_ELLIPSOID 1u
#define RC_QUADRIC_UV_AXIAL 2u
#define RC_QUADRIC_UV_BOX 3u
/* Newton iterations on a patch piece, at most: each evaluates the patch and its
 * derivatives once, and the last only checks convergence. 6 left rays that graze a patch
 * (shadow boundaries on the teapot's belly) unconverged, 653 pixels' shadow decisions
 * apart between f32 and f64; 12 leave 2 (docs/numerics.md §8). The planner counts them
 * (host/gpu/gpu_plan.c) where a scene has patches. */
#define RC_PATCH_NEWTON_STEPS 12u
/* Converged: the patch point lies within this many ulps (of the working precision) of the
 * control points' largest coordinate from the ray line (docs/numerics.md §8). */
#define RC_PATCH_TOLERANCE_ULPS 32.0
/* ... or, at the last step, within 32 f32 ulps (2^-19) in either precision: f64's own
 * criterion asks for more than 6 steps give a grazing ray, and that ray's hit is no less a
 * hit than f32's. */
#define RC_PATCH_LAST_TOLERANCE 1.9073486328125e-06
/* A converged (u, v) still counts for the piece within this fraction of its width beyond
 * its edges, so that rounding never drops a hit on an edge two pieces share. */
#define RC_PATCH_DOMAIN_MARGIN 0.0009765625
/* At the patch's own edges (u or v 0 or 1) only 2^-20 of the square: no piece of another
 * patch lies beyond them, and a hit there would stand out of the patch (its square's
 * triangles, tests/patches). */
#define RC_PATCH_EDGE_MARGIN 9.5367431640625e-07
#define RC_TEXELS_PER_PATCH 16u
struct packed_quadric {
  vec3 center; uint material;
  vec3 axis_x; float constant;
  vec3 axis_y; uint flags;
  vec3 axis_z; uint mesh_root;
  vec3 diag;   uint mesh_end;
  vec3 off;    uint mesh_crossings;
  vec3 linear; float pad3;
  vec3 lo;     float pad4;
  vec3 hi;     float pad5;
};
#define RC_TEXELS_PER_QUADRIC 9
/* A composite solid: `count` instructions from `first` in the CSG program, in postfix
 * order. An instruction is (op << 28) | operand: RC_CSG_LEAF pushes the intervals of the
 * solid quadric `operand` along the ray; the others pop two lists (right on top) and push
 * their combination. [lo, hi] bounds the composite (its proxy in the BVH). */
#define RC_CSG_LEAF 0u
#define RC_CSG_UNION 1u
#define RC_CSG_INTERSECTION 2u
#define RC_CSG_DIFFERENCE 3u
#define RC_CSG_OP_SHIFT 28u
#define RC_CSG_OPERAND_MASK 0x0fffffffu
/* An interval end's code (rc_quadric.glsl, csg_code): bit 0 from a subtracted solid, bit 1
 * the leaf's exit, bits 2-3 the face (0: the quadric, 1..3: a box face), bit 4 set when the
 * leaf is a triangle of a mesh operand, and the leaf's index (a quadric or, with bit 4, a
 * triangle) from bit 5 on. */
#define RC_CSG_CODE_MESH 16u
#define RC_CSG_CODE_LEAF_SHIFT 5u
/* Fixed sizes of the shader's interval lists: a list holds at most RC_CSG_MAX_INTERVALS
 * [in, out] intervals, and at most RC_CSG_STACK lists are live at once. The loader bounds
 * both for each tree (a leaf has up to 2 intervals, a union or difference up to the sum of
 * its operands', an intersection one fewer) and rejects a tree beyond them. */
#define RC_CSG_MAX_INTERVALS 8u
#define RC_CSG_STACK 4u
/* The interval stack (rc_quadric.glsl and its twin): RC_CSG_STACK slots of up to
 * 2 RC_CSG_MAX_INTERVALS ends, then one scratch slot that combine_intervals writes. */
#define RC_CSG_SLOT (2u * RC_CSG_MAX_INTERVALS)
/* The kinds of a quadric's inside {Q < 0} along a whole ray line (quadric_roots). */
#define RC_QR_NONE 0u    /* nowhere */
#define RC_QR_ALL 1u     /* everywhere */
#define RC_QR_BETWEEN 2u /* [t_lo, t_hi] */
#define RC_QR_OUTSIDE 3u /* (-inf, t_lo] and [t_hi, inf) */
struct packed_csg {
  vec3 lo; uint first;
  vec3 hi; uint count;
};
#define RC_TEXELS_PER_CSG 2
/* Phong material: L = ambient*Ia + emission + sum(diffuse*E*max(0,n.l) + specular*E*spec^shininess),
 * plus mirror * (radiance along the reflected ray). Coefficients are per RGB channel.
 * texture: RC_NO_TEXTURE, or the first texel of a packed_texture in the texel array,
 * whose colour at the surface's (u, v) multiplies ambient and diffuse (rc_shade.glsl). */
#define RC_NO_TEXTURE 0xffffffffu
struct packed_material {
  vec3 ambient;  float shininess;
  vec3 diffuse;  uint texture;
  vec3 specular; float pad1;
  vec3 mirror;   float pad2;
  vec3 emission; float pad3; /* added unshadowed, like the ambient term */
};

/* A texture in the texel array (RC_BINDING_TEXELS): this header (2 texels), the first
 * texel of each mip level (RC_TEXTURE_MAX_LEVELS words in 4 texels; level 0 is `texels`),
 * and its image: width x height texels from `texels` on, row 0 the image's top row, each
 * RGBA f32 (A unused), then its levels: level k is ceil(width / 2^k) x ceil(height / 2^k)
 * texels, each the mean of the 2 x 2 of level k - 1 under it (flags >> RC_TEXTURE_LEVELS_SHIFT
 * levels in all, 1 without mip-mapping); materials that name one file share its image. The colour
 * at surface coordinates (u, v) is the image's at (u', v') = (u, v) * scale + offset, with
 * u' across the image from its left edge and v' up from its bottom edge, each texel a unit
 * square (docs/scene-format.md, "Textures"); nearest or bilinear, repeated or clamped at
 * the edges (flags). */
/* Where a surface's (u, v) comes from (rc_shade.glsl, surface.uv_kind): none (the texture
 * is not applied), a sphere (from its unit normal in its own frame), or given. */
#define RC_UV_NONE 0u
#define RC_UV_SPHERE 1u
#define RC_UV_GIVEN 2u /* (u, v, 0) found with the hit: a plane's frame, a triangle's vertices */
#define RC_UV_AXIAL 3u /* around an axis: (x, y, v), u from the angle of (x, y), v given (a cylinder's side) */
#define RC_TEXTURE_BILINEAR 1u
#define RC_TEXTURE_CLAMP 2u
#define RC_TEXTURE_LEVELS_SHIFT 4u /* flags >> this: the number of mip levels, 1 to 15 */
#define RC_TEXTURE_MAX_LEVELS 16u
#define RC_TEXELS_PER_TEXTURE_HEADER 6 /* the packed_texture, then the levels' first texels */
struct packed_texture {
  uint width; uint height; uint flags; uint texels;
  float scale_u; float scale_v; float offset_u; float offset_v;
};

/* Point light: `position` in the packed space, irradiance intensity / (c0 + c1 r + c2 r^2)
 * with (c0, c1, c2) = attenuation ((0, 0, 1) is the physical 1/r^2).
 * Directional light: `position` holds the unit direction the light travels in; no falloff. */
struct packed_light {
  vec3 position;    uint type;
  vec3 intensity;   float pad0;
  vec3 attenuation; float pad1;
};

/* Written by the shader with atomics, read back after each dispatch. */
struct packed_status {
  uint exhausted_pixels;  /* pixels whose batch was discarded: their workgroup ran out of loop budget */
  uint incomplete_pixels; /* pixels that still have samples to take */
  uint shadow_rays;
  uint reflection_rays;
  uint exhausted_object;  /* 1 + an object some ray was testing when its invocation ran out of budget; 0: none */
  uint exhausted_pixel;   /* 1 + y * width + x of that ray's pixel in the frame */
  uint crossing_object;   /* 1 + a composite a ray line crossed more often than its mesh operand's
                             bound, or an odd number of times; 0: none (the render fails) */
  uint crossing_pixel;    /* 1 + y * width + x of that ray's pixel */
  /* Newton's method on a patch piece that stayed inside the piece without converging in
   * RC_PATCH_NEWTON_STEPS (a ray taken as missing it that may hit it): how often, and the
   * first such piece (1 + object) and pixel (1 + y * width + x). The render warns. */
  uint patch_unconverged;
  uint patch_unconverged_object;
  uint patch_unconverged_pixel;
  uint max_steps;         /* the most loop-budget steps one invocation took in the dispatch: what
                             the host sizes the next batch by (gpu_render.c, grow_batch) */
  /* Certified mode: the samples (or light passes) left uncertified, by where on the path the
   * first uncertified decision lies (RC_UNCERTIFIED_HIT, _SHADOW, _BOUNCE). */
  uint uncertified_hit;
  uint uncertified_shadow;
  uint uncertified_bounce;
  uint pad0;
};

/* Where a sample's first uncertified decision lies (rc_certify.glsl, cert_note): at the
 * primary ray's hit or miss (the object, which of two is nearer, the surface point), at one
 * of the primary hit's shadow rays, or anywhere along a mirror bounce (its hit and its
 * shadow rays). render --stats-json reports the three counts. */
#define RC_UNCERTIFIED_HIT 1u
#define RC_UNCERTIFIED_SHADOW 2u
#define RC_UNCERTIFIED_BOUNCE 3u

/* A triangle that a ray passes near one edge of (rc_certify.glsl, cert_near_edge), noted as
 * triangle << RC_CERT_EDGE_SHIFT | edge << 1 | (its det < 0): edge 0 runs v1 -> v2, 1 v2 -> v0,
 * 2 v0 -> v1. RC_CERT_NO_EDGE: near none of them, or near more than one. Triangle indices stay
 * below 1 << 28 (the BVH's leaves hold them shifted by RC_BVH_LEAF_SHIFT), so a note fits. */
#define RC_CERT_EDGE_SHIFT 3u
#define RC_CERT_NO_EDGE 7u

/* How the shader encodes a complete pixel's sum of samples into the output file's 8-bit
 * levels (RC_SPEC_LEVELS, render --gpu-encode; host/image/levels8.h). sum_threshold[k] is
 * the least sum whose level is k or more, and decides the level exactly; the other fields
 * only estimate where the search for it starts (raycast.comp, level_of). */
#define RC_LEVEL_CURVE_LINEAR 0u /* rc_curve's order (host/image/image_io.h) */
#define RC_LEVEL_CURVE_SRGB 1u
#define RC_LEVEL_CURVE_GAMMA 2u
struct packed_levels {
  float value_scale; /* 2^exposure / spp: a sum to the value the curve takes */
  float inv_gamma;   /* RC_LEVEL_CURVE_GAMMA: 1 / gamma (the curve is RC_SPEC_LEVELS') */
  float bias;        /* 0.5: levels round to the nearest; 0: they truncate */
  uint pad0;
  float sum_threshold[RC_LEVEL_COUNT]; /* [0] is unused */
};

/* Decision outputs (AOVs) of a pixel's first sample, at its primary hit: what GPU/CPU
 * comparisons check before colour (docs/gpu-vs-cpu.md). object: spheres 0..S-1, then
 * triangles S..S+T-1, quadrics, composites; shadow_bits: bit i set when light i faces the surface but its shadow
 * ray is blocked (lights 0..23: the bits stay exact in a float). */
#define RC_AOV_SHADOW_LIGHTS 24u
struct packed_aov {
  float hit; float object; float t; float shadow_bits;
  vec3 normal; float uncertified; /* with frame.certify: the pixel's samples (all of them,
                                     not only the first) whose decisions are not certified */
  /* With frame.certify, what the re-render needs to trace only the uncertified samples:
   * the f32 sum of the certified samples' colours, in sample order, and bit s set when
   * sample s < 32 is uncertified. Where the bits count fewer samples than `uncertified`
   * (samples from 32 on, light passes) the whole pixel is rendered again. */
  vec3 certified_sum; uint uncertified_mask;
  /* A digest of the decisions of every sample the pixel's colour holds (hit or miss and the
   * object at each bounce, the lights a shadow ray found blocked): the wrapping sum over
   * samples and decisions of a hash of (sample, bounce, decision), raycast.comp's
   * note_decision. A sum, so batches, light passes and a re-render's samples add to it in
   * any order; in certified mode's f32 pass, of the certified samples only, which the
   * re-render's then join. Equal digests: the same decisions in every sample (up to a
   * collision, 2^-24 in the AOV file's float channel). */
  uint decisions; uint pad0; uint pad1; uint pad2;
};

/* A BVH node: one box, in depth-first order (an interior node's first child is the next
 * node), with `skip`, the node that follows its subtree (bvh_node_count after the last),
 * so traversal needs no stack (rc_bvh.glsl). `leaf` is 0 for an interior node, else
 * (first << RC_BVH_LEAF_SHIFT) | count: `count` objects starting at `first` in the
 * object-reference array, whose entries are object numbers (spheres 0..S-1, then
 * triangles S..S+T-1, standalone quadrics, composites). */
struct packed_bvh_node {
  vec3 lo; uint skip;
  vec3 hi; uint leaf;
};
#define RC_TEXELS_PER_BVH_NODE 2
#define RC_BVH_LEAF_SHIFT 4u
#define RC_BVH_LEAF_MAX 8u /* objects per leaf: fits below 1 << RC_BVH_LEAF_SHIFT */

/* Light buffers (Haines & Greenberg, "The Light Buffer: A Shadow-Testing Accelerator",
 * IEEE CG&A 6(9), 1986; host/scene/light_buffer.h): a cube of RC_LIGHT_BUFFER_RES^2 cells
 * a face around a point light, indexed by a shadow ray's direction towards the light, each
 * cell naming the range of BVH nodes [first, end) that holds every object that a shadow ray
 * through it can meet: none, one leaf made for the cell (at most RC_LIGHT_BUFFER_LIST
 * objects), or the smallest subtree of the object tree that holds them all. In the BVH's
 * reference array, from frame.light_buffers: a pair (cells, reach) per light, where `cells`
 * is where the light's 6 x RES^2 pairs (first, end) start (0: the light has no buffer) and
 * `reach` (f32 bits) the longest shadow ray the buffer answers for.
 * The eye buffer is the same for primary rays, projected onto the image instead of a cube:
 * tiles of 2^shift pixels square, each naming what a primary ray through one of its
 * pixels can meet. Its pair follows the lights' (entry light_count): (cells, shift |
 * columns << RC_EYE_BUFFER_COLUMNS_SHIFT), cells 0 where there is none; tile (i, j), in
 * pixels counted from the image's top left corner, is pair j * columns + i from `cells` on. */
#define RC_LIGHT_BUFFER_RES 64u
#define RC_LIGHT_BUFFER_LIST 4u /* below 1 << RC_BVH_LEAF_SHIFT */
#define RC_EYE_BUFFER_COLUMNS_SHIFT 5u

/* Per-dispatch parameters: the tile and the sample batch. */
struct packed_push {
  uint tile_x; uint tile_y; uint tile_width; uint tile_height;
  uint batch_samples;
  uint row_stride; /* workgroup row i renders block row (i * row_stride) mod rows (gpu_tiles.h) */
  uint light_pass; /* with RC_SPEC_LIGHT_PASSES: the lights one dispatch shades per sample */
  uint masked;     /* 1: trace only the pixels whose AOV record the host set uncertified > 0
                      (certified mode's re-render in f64 on the GPU); the others complete
                      untraced, black */
};

#define RC_TEXELS_PER_SPHERE 2
#define RC_TEXELS_PER_TRIANGLE 3
#define RC_TEXELS_PER_MATERIAL 5
#define RC_TEXELS_PER_LIGHT 3

#ifndef VULKAN

#define RC_ASSERT_LAYOUT(type, member, offset) \
  _Static_assert(offsetof(type, member) == (offset), #type "." #member " offset")
#define RC_ASSERT_SIZE(type, size) _Static_assert(sizeof(type) == (size), #type " size")

RC_ASSERT_SIZE(vec3, 12);
_Static_assert(RC_KIND_ALL == 2u * RC_KIND_LOOSE_QUADRICS - 1u && RC_KIND_LOOSE_QUADRICS == 2u * RC_KIND_PATCHES,
               "RC_KIND_ALL is every kind bit, the loose quadrics' the highest");
RC_ASSERT_LAYOUT(packed_camera, eye, 0);    RC_ASSERT_LAYOUT(packed_camera, left, 12);
RC_ASSERT_LAYOUT(packed_camera, u, 16);     RC_ASSERT_LAYOUT(packed_camera, right, 28);
RC_ASSERT_LAYOUT(packed_camera, v, 32);     RC_ASSERT_LAYOUT(packed_camera, bottom, 44);
RC_ASSERT_LAYOUT(packed_camera, w, 48);     RC_ASSERT_LAYOUT(packed_camera, top, 60);
RC_ASSERT_LAYOUT(packed_camera, focal, 64); RC_ASSERT_LAYOUT(packed_camera, projection, 68);
RC_ASSERT_LAYOUT(packed_camera, width, 72); RC_ASSERT_LAYOUT(packed_camera, height, 76);
RC_ASSERT_SIZE(packed_camera, 80);

RC_ASSERT_LAYOUT(packed_frame, camera, 0);
RC_ASSERT_LAYOUT(packed_frame, background, 80);     RC_ASSERT_LAYOUT(packed_frame, specular_model, 92);
RC_ASSERT_LAYOUT(packed_frame, ambient_light, 96);  RC_ASSERT_LAYOUT(packed_frame, reflection_depth, 108);
RC_ASSERT_LAYOUT(packed_frame, sphere_count, 112);  RC_ASSERT_LAYOUT(packed_frame, triangle_count, 116);
RC_ASSERT_LAYOUT(packed_frame, material_count, 120); RC_ASSERT_LAYOUT(packed_frame, light_count, 124);
RC_ASSERT_LAYOUT(packed_frame, samples_per_pixel, 128); RC_ASSERT_LAYOUT(packed_frame, seed, 132);
RC_ASSERT_LAYOUT(packed_frame, strata_x, 136);      RC_ASSERT_LAYOUT(packed_frame, strata_y, 140);
RC_ASSERT_LAYOUT(packed_frame, object_count, 144);  RC_ASSERT_LAYOUT(packed_frame, bvh_node_count, 148);
RC_ASSERT_LAYOUT(packed_frame, inv_strata_x, 152);  RC_ASSERT_LAYOUT(packed_frame, inv_strata_y, 156);
RC_ASSERT_LAYOUT(packed_frame, sphere_formula, 160); RC_ASSERT_LAYOUT(packed_frame, triangle_formula, 164);
RC_ASSERT_LAYOUT(packed_frame, offset_strategy, 168); RC_ASSERT_LAYOUT(packed_frame, offset_epsilon, 172);
RC_ASSERT_LAYOUT(packed_frame, quadric_count, 176); RC_ASSERT_LAYOUT(packed_frame, csg_count, 180);
RC_ASSERT_LAYOUT(packed_frame, shadows, 184); RC_ASSERT_LAYOUT(packed_frame, csg_max_steps, 188);
RC_ASSERT_LAYOUT(packed_frame, plane_count, 192); RC_ASSERT_LAYOUT(packed_frame, patch_count, 196);
RC_ASSERT_LAYOUT(packed_frame, light_buffers, 200); RC_ASSERT_LAYOUT(packed_frame, certify, 204);
RC_ASSERT_LAYOUT(packed_frame, cone_width, 208); RC_ASSERT_LAYOUT(packed_frame, cone_spread, 212);
RC_ASSERT_LAYOUT(packed_frame, loose_kinds, 216);
RC_ASSERT_SIZE(packed_frame, 224);
RC_ASSERT_LAYOUT(packed_quadric, center, 0);   RC_ASSERT_LAYOUT(packed_quadric, material, 12);
RC_ASSERT_LAYOUT(packed_quadric, axis_x, 16);  RC_ASSERT_LAYOUT(packed_quadric, constant, 28);
RC_ASSERT_LAYOUT(packed_quadric, axis_y, 32);  RC_ASSERT_LAYOUT(packed_quadric, flags, 44);
RC_ASSERT_LAYOUT(packed_quadric, axis_z, 48);  RC_ASSERT_LAYOUT(packed_quadric, mesh_root, 60);
RC_ASSERT_LAYOUT(packed_quadric, diag, 64);    RC_ASSERT_LAYOUT(packed_quadric, mesh_end, 76);
RC_ASSERT_LAYOUT(packed_quadric, off, 80);     RC_ASSERT_LAYOUT(packed_quadric, mesh_crossings, 92);     RC_ASSERT_LAYOUT(packed_quadric, linear, 96);
RC_ASSERT_LAYOUT(packed_quadric, lo, 112);     RC_ASSERT_LAYOUT(packed_quadric, hi, 128);
RC_ASSERT_SIZE(packed_quadric, 16 * RC_TEXELS_PER_QUADRIC);
RC_ASSERT_LAYOUT(packed_csg, lo, 0);  RC_ASSERT_LAYOUT(packed_csg, first, 12);
RC_ASSERT_LAYOUT(packed_csg, hi, 16); RC_ASSERT_LAYOUT(packed_csg, count, 28);
RC_ASSERT_SIZE(packed_csg, 16 * RC_TEXELS_PER_CSG);

RC_ASSERT_LAYOUT(packed_bvh_node, lo, 0);   RC_ASSERT_LAYOUT(packed_bvh_node, skip, 12);
RC_ASSERT_LAYOUT(packed_bvh_node, hi, 16);  RC_ASSERT_LAYOUT(packed_bvh_node, leaf, 28);
RC_ASSERT_SIZE(packed_bvh_node, 16 * RC_TEXELS_PER_BVH_NODE);

RC_ASSERT_LAYOUT(packed_sphere, center, 0); RC_ASSERT_LAYOUT(packed_sphere, radius, 12);
RC_ASSERT_LAYOUT(packed_sphere, material, 16); RC_ASSERT_LAYOUT(packed_sphere, transform, 20);
RC_ASSERT_LAYOUT(packed_transform, row0, 0);   RC_ASSERT_LAYOUT(packed_transform, row1, 16);
RC_ASSERT_LAYOUT(packed_transform, row2, 32);
RC_ASSERT_SIZE(packed_transform, 16 * RC_TEXELS_PER_TRANSFORM);
RC_ASSERT_SIZE(packed_sphere, 16 * RC_TEXELS_PER_SPHERE);

RC_ASSERT_LAYOUT(packed_triangle, v0, 0);  RC_ASSERT_LAYOUT(packed_triangle, material, 12);
RC_ASSERT_LAYOUT(packed_triangle, v1, 16); RC_ASSERT_LAYOUT(packed_triangle, normals, 28);
RC_ASSERT_LAYOUT(packed_triangle, v2, 32); RC_ASSERT_LAYOUT(packed_triangle, flags, 44);
RC_ASSERT_LAYOUT(packed_vertex_normals, n0, 0); RC_ASSERT_LAYOUT(packed_vertex_normals, n1, 16);
RC_ASSERT_LAYOUT(packed_vertex_normals, n2, 32);
RC_ASSERT_SIZE(packed_vertex_normals, 16 * RC_TEXELS_PER_VERTEX_NORMALS);
RC_ASSERT_LAYOUT(packed_vertex_uvs, u0, 0); RC_ASSERT_LAYOUT(packed_vertex_uvs, u2, 16);
RC_ASSERT_SIZE(packed_vertex_uvs, 16 * RC_TEXELS_PER_VERTEX_UVS);
RC_ASSERT_SIZE(packed_triangle, 16 * RC_TEXELS_PER_TRIANGLE);

RC_ASSERT_LAYOUT(packed_material, ambient, 0);   RC_ASSERT_LAYOUT(packed_material, shininess, 12);
RC_ASSERT_LAYOUT(packed_material, diffuse, 16);  RC_ASSERT_LAYOUT(packed_material, texture, 28);
RC_ASSERT_LAYOUT(packed_material, specular, 32);
RC_ASSERT_LAYOUT(packed_texture, width, 0);    RC_ASSERT_LAYOUT(packed_texture, flags, 8);
RC_ASSERT_LAYOUT(packed_texture, texels, 12);
RC_ASSERT_LAYOUT(packed_texture, scale_u, 16); RC_ASSERT_LAYOUT(packed_texture, offset_v, 28);
RC_ASSERT_SIZE(packed_texture, 32); /* then the levels' table: RC_TEXELS_PER_TEXTURE_HEADER in all */
RC_ASSERT_LAYOUT(packed_material, mirror, 48);   RC_ASSERT_LAYOUT(packed_material, emission, 64);
RC_ASSERT_SIZE(packed_material, 16 * RC_TEXELS_PER_MATERIAL);

RC_ASSERT_LAYOUT(packed_light, position, 0);  RC_ASSERT_LAYOUT(packed_light, type, 12);
RC_ASSERT_LAYOUT(packed_light, intensity, 16); RC_ASSERT_LAYOUT(packed_light, attenuation, 32);
RC_ASSERT_SIZE(packed_light, 16 * RC_TEXELS_PER_LIGHT);

RC_ASSERT_LAYOUT(packed_status, exhausted_pixels, 0); RC_ASSERT_LAYOUT(packed_status, incomplete_pixels, 4);
RC_ASSERT_LAYOUT(packed_status, shadow_rays, 8);      RC_ASSERT_LAYOUT(packed_status, reflection_rays, 12);
RC_ASSERT_LAYOUT(packed_status, exhausted_object, 16); RC_ASSERT_LAYOUT(packed_status, exhausted_pixel, 20);
RC_ASSERT_LAYOUT(packed_status, crossing_object, 24); RC_ASSERT_LAYOUT(packed_status, crossing_pixel, 28);
RC_ASSERT_LAYOUT(packed_status, patch_unconverged, 32); RC_ASSERT_LAYOUT(packed_status, patch_unconverged_pixel, 40);
RC_ASSERT_LAYOUT(packed_status, max_steps, 44);     RC_ASSERT_LAYOUT(packed_status, uncertified_hit, 48);
RC_ASSERT_LAYOUT(packed_status, uncertified_shadow, 52); RC_ASSERT_LAYOUT(packed_status, uncertified_bounce, 56);
RC_ASSERT_SIZE(packed_status, 64);

RC_ASSERT_LAYOUT(packed_levels, value_scale, 0); RC_ASSERT_LAYOUT(packed_levels, inv_gamma, 4);
RC_ASSERT_LAYOUT(packed_levels, bias, 8);
RC_ASSERT_LAYOUT(packed_levels, sum_threshold, 16);
RC_ASSERT_SIZE(packed_levels, 16 + 4 * RC_LEVEL_COUNT);

RC_ASSERT_LAYOUT(packed_aov, hit, 0);    RC_ASSERT_LAYOUT(packed_aov, object, 4);
RC_ASSERT_LAYOUT(packed_aov, t, 8);      RC_ASSERT_LAYOUT(packed_aov, shadow_bits, 12);
RC_ASSERT_LAYOUT(packed_aov, normal, 16);   RC_ASSERT_LAYOUT(packed_aov, uncertified, 28);
RC_ASSERT_LAYOUT(packed_aov, certified_sum, 32); RC_ASSERT_LAYOUT(packed_aov, uncertified_mask, 44);
RC_ASSERT_LAYOUT(packed_aov, decisions, 48);
RC_ASSERT_SIZE(packed_aov, 64);

RC_ASSERT_LAYOUT(packed_push, tile_x, 0); RC_ASSERT_LAYOUT(packed_push, tile_width, 8);
RC_ASSERT_LAYOUT(packed_push, batch_samples, 16); RC_ASSERT_LAYOUT(packed_push, row_stride, 20);
RC_ASSERT_SIZE(packed_push, 32);
#endif

#endif
