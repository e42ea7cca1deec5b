/* scene.h: the validated scene model, in f64 and world units. Both renderers get their
 * arrays from it through rc_scene_pack (scene_pack.h); nothing renders from this model
 * directly. */
#ifndef RC_SCENE_H
#define RC_SCENE_H

#include "math/rcm_vec3.h"
#include "base/rc_base.h"

typedef struct rc_material_def {
  char *name;
  dvec3 ambient, diffuse, specular, mirror, emission;
  double shininess;
  uint32_t texture; /* 1 + its index in rc_scene.textures; 0: none */
} rc_material_def;

/* A material's texture (JSON "texture", docs/scene-format.md "Textures"): the image file,
 * read by the command once the scene is loaded (cli/textures.c: the scene stage reads no
 * images), and how it is sampled (packed_texture). */
#define RC_MAX_TEXTURE_SIDE 16384u
typedef struct rc_texture_def {
  char *path;            /* as opened: relative to the scene file's folder, joined */
  bool bilinear, clamp;  /* texture_filter, texture_wrap */
  bool mipmap;           /* texture_mipmap: minified lookups read the mip levels (packed_texture) */
  double scale[2], offset[2];
  char where[512];       /* "FILE:LINE:COL: error: materials.NAME.texture", for messages */
  uint32_t width, height;
  /* width x height RGB, row 0 the image's top; NULL until read, and for a texture whose
   * file an earlier one named: `image` is that one's index (else its own). */
  float *rgb;
  uint32_t image;
} rc_texture_def;

typedef struct rc_light_def {
  uint32_t type;    /* RC_LIGHT_* */
  dvec3 position;   /* point lights */
  dvec3 direction;  /* directional lights: the direction the light travels in */
  dvec3 intensity;
  dvec3 attenuation; /* point lights: c0, c1, c2 of 1 / (c0 + c1 r + c2 r^2) */
} rc_light_def;

/* An affine world_from_object transform: rows of a 3x4 matrix. */
typedef struct rc_affine {
  double m[3][4];
} rc_affine;

typedef struct rc_sphere_def {
  dvec3 center; /* in object space when transformed */
  double radius;
  uint32_t material;
  bool transformed;
  rc_affine world_from_object;
} rc_sphere_def;

typedef struct rc_triangle_def {
  dvec3 v[3];
  uint32_t material;
  bool smooth;    /* vertex normals below give the shading normal */
  bool one_sided; /* there only for rays meeting its front (RC_TRIANGLE_ONE_SIDED) */
  bool has_uv;    /* texture coordinates at the vertices below (JSON "uvs", a mesh's first uv channel) */
  dvec3 n[3];
  double uv[3][2];
} rc_triangle_def;

/* A quadric in its own frame (packed_quadric has the formula): world centre, the rows of the
 * world-to-frame matrix (the frame's axes; scaled or sheared by a "transform"), M (diag,
 * off), linear, constant, and the clip box [lo, hi] in the frame. */
typedef struct rc_quadric_def {
  dvec3 center, axis[3];
  dvec3 diag, off, linear;
  double constant;
  dvec3 lo, hi;
  uint32_t material;
  bool solid;
  bool one_sided; /* planes: hit from the normal's side only (RC_QUADRIC_ONE_SIDED) */
  /* A composite's closed mesh operand (RC_QUADRIC_MESH): triangles [mesh_first, mesh_first +
   * mesh_count) of rc_scene.csg_triangles; [lo, hi] about `center` is their box. */
  bool mesh;
  uint32_t mesh_first, mesh_count, max_crossings;
  /* A piece of a Bezier patch (RC_QUADRIC_PATCH, scene_patch.h): 1 + its rc_scene.patches
   * index (0: not a piece), and its part [u0, u1] x [v0, v1] of the (u, v) square; [lo, hi]
   * about `center` (axes identity) is its control net's box. */
  uint32_t uv;                  /* RC_QUADRIC_UV_*: how a named shape takes texture coordinates */
  uint32_t patch, patch_piece0; /* patch_piece0: the quadric index of the patch's first piece */
  double domain[4];
} rc_quadric_def;

/* A bicubic Bezier patch, world space: control point p[4 r + c] is row r (along v),
 * column c (along u); lower degrees are raised to 3 at load. Its pieces are quadrics. */
typedef struct rc_patch_def {
  dvec3 p[16];
  uint32_t material;
} rc_patch_def;

/* Where primitives came from in the scene file, for errors found after parsing (values
 * beyond f32 once packed, the GPU's loop budget): primitives [first, first + count) of
 * `kind` come from the value at line:col, field `what`[item] (JSON: "objects", "lights",
 * or "materials" with the material's name; .test: the command, item UINT32_MAX). */
enum { RC_ORIGIN_SPHERE, RC_ORIGIN_TRIANGLE, RC_ORIGIN_QUADRIC, RC_ORIGIN_CSG, RC_ORIGIN_LIGHT, RC_ORIGIN_MATERIAL,
       RC_ORIGIN_PLANE, RC_ORIGIN_KINDS };
typedef struct rc_origin {
  uint32_t kind, line, col, item;
  const char *what; /* a static string */
  size_t first, count;
} rc_origin;

/* A composite solid: a postfix program (RC_CSG_* << RC_CSG_OP_SHIFT | operand) whose leaf
 * operands index rc_scene.csg_leaves; its world-space bounding box. */
typedef struct rc_csg_def {
  uint32_t *program;
  uint32_t length;
  uint32_t steps; /* the most shader loop steps one ray can take in it (rc_quadric.glsl) */
  dvec3 lo, hi;
} rc_csg_def;

typedef struct rc_camera_def {
  uint32_t projection; /* RC_PROJECTION_* */
  dvec3 eye, look_at, up;
  double fov_y_deg;    /* perspective: full vertical field of view */
  double view_height;  /* parallel: height of the view window in world units */
} rc_camera_def;

/* The speed/accuracy knobs (docs/accuracy.md): `quality` in JSON, --precision etc. on the
 * command line (which wins). */
#define RC_PRECISION_AUTO 0u /* f32 unless the precision-budget pass finds the scene needs f64 */
#define RC_PRECISION_F32 1u
#define RC_PRECISION_F64 2u
#define RC_PRECISION_CERTIFIED 3u /* f32 with each decision certified, the rest again in f64 (rc_certify.glsl) */
typedef struct rc_quality {
  uint32_t precision;     /* RC_PRECISION_* */
  uint32_t sphere;        /* RC_SPHERE_* (rc_shared.h) */
  uint32_t triangle;      /* RC_TRIANGLE_* */
  uint32_t offset;        /* RC_OFFSET_*: where shadow and reflection rays start */
  double offset_epsilon;  /* RC_OFFSET_EPSILON's distance, scene units */
  bool camera_relative;   /* pack positions relative to the eye (in f64) before rounding to f32 */
  bool rescale;           /* pack in power-of-two units when the scene's size leaves [2^-20, 2^20] */
  bool shadows;           /* trace shadow rays (off: every light reaches every surface facing it) */
} rc_quality;
/* Names as written in scenes and on the command line, indexed by the constants. */
extern const char *const rc_precision_names[];      /* auto, f32, f64, certified */
extern const char *const rc_sphere_formula_names[];  /* geometric, algebraic */
extern const char *const rc_triangle_formula_names[]; /* watertight, moller-trumbore, cramer */
extern const char *const rc_offset_names[];         /* error-bound, ulp, epsilon, t-min */
/* The robust defaults. */
rc_quality rc_quality_default(void);
/* The index of `name` in a NULL-terminated name list, or -1. */
int rc_name_index(const char *const *names, const char *name);

/* Limits of the scene format (docs/scene-format.md). */
#define RC_MAX_IMAGE_SIDE 65536u
#define RC_MAX_SAMPLES_PER_PIXEL 1024u
#define RC_MAX_REFLECTION_DEPTH 16u

enum { RC_SCENE_ENCODING_LINEAR, RC_SCENE_ENCODING_SRGB, RC_SCENE_ENCODING_GAMMA };
#define RC_DEFAULT_GAMMA 2.2
#define RC_MIN_GAMMA 0.01    /* the gamma encoding's exponent, in [RC_MIN_GAMMA, RC_MAX_GAMMA] */
#define RC_MAX_GAMMA 100.0
#define RC_MAX_EXPOSURE 64.0 /* stops either way: 2^64 takes any f32 radiance past white */

typedef struct rc_scene {
  char *path;
  uint32_t width, height, samples_per_pixel;
  rc_camera_def camera;
  dvec3 background, ambient_light;
  uint32_t specular_model;   /* RC_SPECULAR_* */
  uint32_t reflection_depth; /* mirror bounces; 0 = no reflection */
  uint32_t seed;             /* sample jitter */
  rc_quality quality;
  rc_material_def *materials;
  size_t material_count;
  rc_texture_def *textures;
  size_t texture_count;
  rc_light_def *lights;
  size_t light_count;
  rc_sphere_def *spheres;
  size_t sphere_count;
  rc_triangle_def *triangles;
  size_t triangle_count, triangle_capacity;
  size_t degenerate_triangles; /* zero-area triangles skipped at load */
  size_t degenerate_in_meshes; /* of which in mesh files (mesh.c warns about those by file) */
  rc_quadric_def *quadrics;    /* standalone quadrics */
  size_t quadric_count, quadric_capacity;
  rc_patch_def *patches;       /* their pieces are among the quadrics (rc_quadric_def.patch) */
  size_t patch_count, patch_capacity;
  rc_quadric_def *planes;      /* infinite planes (RC_QUADRIC_UNBOUNDED), packed after the quadrics */
  size_t plane_count, plane_capacity;
  rc_quadric_def *csg_leaves;  /* the solids composites are made of */
  size_t csg_leaf_count, csg_leaf_capacity;
  rc_csg_def *csgs;
  size_t csg_count, csg_capacity;
  rc_triangle_def *csg_triangles; /* of the composites' mesh operands, packed after the triangles */
  size_t csg_triangle_count, csg_triangle_capacity;
  bool truncate_8bit;          /* the format's 8-bit rule: truncate (CSE167) or round (JSON) */
  /* How 8-bit outputs store a linear value (JSON image.encoding, gamma, exposure): the
   * curve (RC_SCENE_ENCODING_*, the order of image_io.h's rc_curve), the exponent of
   * the gamma curve, and an exposure in stops. */
  uint32_t encoding_8bit;
  double gamma_8bit, exposure_8bit;
  char output_name[256];       /* a .test scene's `output` file name ("" when none): a bare name, no folder */
  /* Every file the scene read besides itself (its meshes and the files they name), as
   * opened: the outputs of a run may name none of them (cli/cmd_render.c). */
  char **inputs;
  size_t input_count, input_capacity;
  rc_origin *origins;          /* in file order */
  size_t origin_count, origin_capacity;
} rc_scene;

/* The number of primitives of each RC_ORIGIN_* kind so far. */
void rc_scene_counts(const rc_scene *scene, size_t counts[RC_ORIGIN_KINDS]);
/* Records that the primitives added since `before` (rc_scene_counts) come from line:col. */
rc_status rc_scene_note_origin(rc_scene *scene, const size_t before[RC_ORIGIN_KINDS], int line, int col,
                               const char *what, uint32_t item);
/* Prints "FILE:LINE:COL: error: FIELD: message" for primitive `index` of `kind` (FIELD
 * says "triangle K of N" for one of many from the same object, a mesh), or "FILE: error:
 * KIND INDEX: message" when no origin was recorded. */
void rc_scene_error(const rc_scene *scene, uint32_t kind, size_t index, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* The same, as a warning. */
void rc_scene_warning(const rc_scene *scene, uint32_t kind, size_t index, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* How a scene may be read; NULL means all false. */
typedef struct rc_load_options {
  /* Meshes, and the files a mesh names, may lie outside the scene file's folder. Off by
   * default, so that rendering an untrusted scene cannot read arbitrary files into the
   * image (docs/scene-format.md, "Files a scene may read"). */
  bool allow_outside_paths;
} rc_load_options;

/* Reads and validates a scene file, JSON or (by the extension .test) the CSE167 format;
 * errors are printed as FILE:LINE:COL: error: ... */
rc_status rc_scene_load(const char *path, const rc_load_options *options, rc_scene *scene);
/* The CSE167x ray-tracer format (`.test` files: scene_cse167.c); it names no other files. */
rc_status rc_scene_parse_cse167(const char *path, const char *text, size_t len, rc_scene *scene);
/* The JSON format from text in memory; `path` names it in messages and locates meshes. */
rc_status rc_scene_parse_json(const char *path, const char *text, size_t len, const rc_load_options *options,
                              rc_scene *scene);
void rc_scene_free(rc_scene *scene);
/* Records a file the scene read (once each); false when memory runs out. */
bool rc_scene_note_input(rc_scene *scene, const char *path);
/* Room for `extra` more triangles (meshes and JSON triangles both append). */
rc_status rc_scene_reserve_triangles(rc_scene *scene, size_t extra);
/* Appends a triangle, or counts it in degenerate_triangles when its area is exactly zero
 * in f64: degenerate but meaningful input is skipped and counted (docs/numerics.md §7).
 * The one rule for JSON triangles, .test triangles and mesh faces. */
rc_status rc_scene_add_triangle(rc_scene *scene, const rc_triangle_def *t);
/* The axis-aligned bounds of the box [lo, hi] of a frame (centre, and the rows of the
 * world-to-frame matrix: orthonormal axes, or any invertible matrix under a transform):
 * its 8 corners carried out of the frame. */
void rc_frame_box_bounds(dvec3 center, const dvec3 axis[3], dvec3 lo, dvec3 hi, dvec3 *out_lo, dvec3 *out_hi);
/* The world-space bounding box of a quadric's clip box. */
void rc_quadric_world_box(const rc_quadric_def *q, dvec3 *lo, dvec3 *hi);
/* world_from_object applied to a point. */
dvec3 rc_affine_point(const rc_affine *a, dvec3 p);

/* Camera checks shared by the parser and by command-line overrides: eye != look_at, up
 * neither zero nor parallel to the view direction, fov in (0, 180), view_height > 0.
 * Returns NULL when valid, else the reason, and sets *field to the offending field. */
const char *rc_scene_camera_problem(const rc_camera_def *c, const char **field);

#endif
