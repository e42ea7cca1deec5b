/* bench_embree: the yardstick of tools/bench_vs_embree.sh. Renders a vkraycast scene with
 * Intel Embree 3 from the very arrays vkraycast packs (same camera rays, f32 camera-relative
 * geometry, Blinn-Phong with one shadow ray per light, 1 spp, no reflections), with single
 * rays (rtcIntersect1/rtcOccluded1) and 8-wide primary packets (rtcIntersect8), on
 * all cores (row blocks on pthreads), and prints the timings as JSON.
 *   bench_embree SCENE [--width W] [--height H] [--repeat N] [--threads T] [--out IMAGE]
 *                [--shading reference|lambert] [--shadow-packets 0|1] [--coherent 0|1]
 *                [--quality low|medium|high]
 *   bench_embree --bbox MESHFILE        prints the mesh's bounding box
 * The options are the yardstick's own speed knobs (docs/performance.md, "Two Embree
 * harnesses"): --shading lambert replaces the reference's Phong terms by n.l times the
 * irradiance and the diffuse colour (the cheapest shading both sides share: every light,
 * every shadow ray, no pow); --shadow-packets 1 traces a packet's shadow rays toward each
 * light as one rtcOccluded8; --coherent 1 marks the primary packets' context coherent;
 * --quality is the BVH build quality (default medium).
 * Not part of vkraycast: a benchmark tool, built only when libembree-dev is installed. */
#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/image_io.h"
#include "ref/ref_shader.h"
#include "scene/mesh.h"
#include "scene/scene_pack.h"

typedef struct {
  const rc_packed_scene *p;
  ref_scene sc;
  RTCScene scene;
  unsigned tri_geom, sphere_geom;
  float *rgb;
  bool packets, lambert, shadow_packets, coherent;
  atomic_uint next_row;
  atomic_uint_fast64_t shadow_rays;
} bench;

static uint32_t material_of(const bench *b, unsigned geom, unsigned prim) {
  return geom == b->tri_geom ? b->p->triangles[prim].material : b->p->spheres[prim].material;
}

/* Shading by the reference's own functions (ref/ref_shade.c, the shader's twin): the light
 * directions, irradiance, shadow-ray extents and the Phong terms are vkraycast's; only the
 * shadow rays' occlusion test is Embree's. The surface is the flat one Embree reports
 * (its geometric normal facing the ray), leaving from the reference's offset origin. */
/* The colour one light adds: the reference's Phong terms, or (--shading lambert) n.l times
 * the irradiance and the diffuse colour. */
static vec3 light_term(const bench *b, packed_material m, vec3 n, vec3 l, vec3 v, float ndl, vec3 irradiance) {
  if (b->lambert) return rcm_scale_f(rcm_mul_f(m.diffuse, irradiance), ndl);
  return ref_light_contribution_f(&b->sc, m, m.diffuse, n, l, v, ndl, irradiance);
}

static vec3 shade(bench *b, vec3 o, vec3 d, float t, vec3 ng, uint32_t mat, uint64_t *shadow_rays) {
  const packed_material m = b->p->materials[mat];
  const packed_frame *f = &b->p->frame;
  vec3 n = rcm_normalize_f(ng);
  if (rcm_dot_f(n, d) > 0) n = rcm_neg_f(n);
  vec3 p = rcm_add_f(o, rcm_scale_f(d, t));
  vec3 origin = ref_offset_ray_origin_f(p, n);
  vec3 color = rcm_add_f(rcm_mul_f(m.ambient, f->ambient_light), m.emission);
  vec3 v = rcm_neg_f(d);
  for (uint32_t i = 0; i < f->light_count; i++) {
    vec3 l, irradiance, to_light;
    float t_max;
    if (!ref_light_at_f(b->p->lights[i], p, origin, &l, &irradiance, &to_light, &t_max)) continue;
    float ndl = rcm_dot_f(n, l);
    if (ndl <= 0) continue;
    (*shadow_rays)++;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay ray = {origin.x, origin.y, origin.z, 0, to_light.x, to_light.y, to_light.z, 0, t_max, 0xffffffffu, 0, 0};
    rtcOccluded1(b->scene, &ctx, &ray);
    if (ray.tfar < 0) continue; /* blocked */
    color = rcm_add_f(color, light_term(b, m, n, l, v, ndl, irradiance));
  }
  return color;
}

static void primary(const bench *b, uint32_t x, uint32_t y, vec3 *o, vec3 *d) {
  ref_vec2 raster = {(float)x + 0.5f, (float)(b->p->frame.camera.height - 1 - y) + 0.5f};
  ref_camera_ray_f(&b->sc, raster, o, d);
}

static void render_row_single(bench *b, uint32_t y, uint64_t *shadow_rays) {
  uint32_t w = b->p->frame.camera.width;
  for (uint32_t x = 0; x < w; x++) {
    vec3 o, d;
    primary(b, x, y, &o, &d);
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh = {0};
    rh.ray = (struct RTCRay){o.x, o.y, o.z, 0, d.x, d.y, d.z, 0, INFINITY, 0xffffffffu, 0, 0};
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(b->scene, &ctx, &rh);
    vec3 c = b->p->frame.background;
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID)
      c = shade(b, o, d, rh.ray.tfar, rcm_make_f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z),
                material_of(b, rh.hit.geomID, rh.hit.primID), shadow_rays);
    memcpy(b->rgb + 3 * ((size_t)y * w + x), &c, sizeof c);
  }
}

/* A packet's shading with its shadow rays toward each light traced as one rtcOccluded8
 * of the lanes that need one (--shadow-packets 1); the same terms as shade(). */
static void shade_packet(bench *b, const struct RTCRayHit8 *rh, const vec3 *o, const vec3 *d, uint32_t x0, uint32_t y,
                         uint64_t *shadow_rays) {
  const packed_frame *f = &b->p->frame;
  const uint32_t w = f->camera.width;
  vec3 n[8], p[8], origin[8], color[8];
  packed_material m[8];
  bool hit[8];
  for (int k = 0; k < 8; k++) {
    hit[k] = x0 + (uint32_t)k < w && rh->hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    color[k] = f->background;
    if (!hit[k]) continue;
    m[k] = b->p->materials[material_of(b, rh->hit.geomID[k], rh->hit.primID[k])];
    n[k] = rcm_normalize_f(rcm_make_f(rh->hit.Ng_x[k], rh->hit.Ng_y[k], rh->hit.Ng_z[k]));
    if (rcm_dot_f(n[k], d[k]) > 0) n[k] = rcm_neg_f(n[k]);
    p[k] = rcm_add_f(o[k], rcm_scale_f(d[k], rh->ray.tfar[k]));
    origin[k] = ref_offset_ray_origin_f(p[k], n[k]);
    color[k] = rcm_add_f(rcm_mul_f(m[k].ambient, f->ambient_light), m[k].emission);
  }
  for (uint32_t i = 0; i < f->light_count; i++) {
    _Alignas(32) int valid[8]; /* Embree reads the mask as one 32-byte vector */
    vec3 l[8], irradiance[8];
    float ndl[8];
    struct RTCRay8 ray;
    int any = 0;
    for (int k = 0; k < 8; k++) {
      valid[k] = 0;
      vec3 to_light;
      float t_max;
      if (!hit[k] || !ref_light_at_f(b->p->lights[i], p[k], origin[k], &l[k], &irradiance[k], &to_light, &t_max))
        continue;
      ndl[k] = rcm_dot_f(n[k], l[k]);
      if (ndl[k] <= 0) continue;
      valid[k] = -1, any = 1;
      ray.org_x[k] = origin[k].x, ray.org_y[k] = origin[k].y, ray.org_z[k] = origin[k].z;
      ray.dir_x[k] = to_light.x, ray.dir_y[k] = to_light.y, ray.dir_z[k] = to_light.z;
      ray.tnear[k] = 0, ray.tfar[k] = t_max, ray.time[k] = 0, ray.mask[k] = 0xffffffffu, ray.id[k] = (unsigned)k;
      ray.flags[k] = 0;
      (*shadow_rays)++;
    }
    if (!any) continue;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcOccluded8(valid, b->scene, &ctx, &ray);
    for (int k = 0; k < 8; k++)
      if (valid[k] && ray.tfar[k] >= 0)
        color[k] = rcm_add_f(color[k], light_term(b, m[k], n[k], l[k], rcm_neg_f(d[k]), ndl[k], irradiance[k]));
  }
  for (int k = 0; k < 8 && x0 + (uint32_t)k < w; k++)
    memcpy(b->rgb + 3 * ((size_t)y * w + x0 + (uint32_t)k), &color[k], sizeof color[k]);
}

/* Eight pixels of a row at a time through rtcIntersect8; shading and shadow rays per
 * lane as above (the shadow rays of a packet's lanes point to different places). */
static void render_row_packets(bench *b, uint32_t y, uint64_t *shadow_rays) {
  uint32_t w = b->p->frame.camera.width;
  for (uint32_t x0 = 0; x0 < w; x0 += 8) {
    struct RTCRayHit8 rh;
    _Alignas(32) int valid[8]; /* Embree reads the mask as one 32-byte vector */
    vec3 o[8], d[8];
    for (int k = 0; k < 8; k++) {
      uint32_t x = x0 + (uint32_t)k;
      valid[k] = x < w ? -1 : 0;
      primary(b, x < w ? x : w - 1, y, &o[k], &d[k]);
      rh.ray.org_x[k] = o[k].x, rh.ray.org_y[k] = o[k].y, rh.ray.org_z[k] = o[k].z;
      rh.ray.dir_x[k] = d[k].x, rh.ray.dir_y[k] = d[k].y, rh.ray.dir_z[k] = d[k].z;
      rh.ray.tnear[k] = 0, rh.ray.tfar[k] = INFINITY, rh.ray.time[k] = 0;
      rh.ray.mask[k] = 0xffffffffu, rh.ray.id[k] = (unsigned)k, rh.ray.flags[k] = 0;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    }
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    if (b->coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect8(valid, b->scene, &ctx, &rh);
    if (b->shadow_packets) {
      shade_packet(b, &rh, o, d, x0, y, shadow_rays);
      continue;
    }
    for (int k = 0; k < 8 && x0 + (uint32_t)k < w; k++) {
      vec3 c = b->p->frame.background;
      if (rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID)
        c = shade(b, o[k], d[k], rh.ray.tfar[k], rcm_make_f(rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]),
                  material_of(b, rh.hit.geomID[k], rh.hit.primID[k]), shadow_rays);
      memcpy(b->rgb + 3 * ((size_t)y * w + x0 + (uint32_t)k), &c, sizeof c);
    }
  }
}

static void *worker(void *arg) {
  bench *b = arg;
  uint64_t shadow = 0;
  for (;;) {
    uint32_t y = atomic_fetch_add(&b->next_row, 1);
    if (y >= b->p->frame.camera.height) break;
    if (b->packets)
      render_row_packets(b, y, &shadow);
    else
      render_row_single(b, y, &shadow);
  }
  atomic_fetch_add(&b->shadow_rays, shadow);
  return NULL;
}

static double render(bench *b, bool packets, uint32_t threads, uint64_t *shadow_rays) {
  b->packets = packets;
  atomic_store(&b->next_row, 0);
  atomic_store(&b->shadow_rays, 0);
  pthread_t t[64];
  double t0 = rc_now_ms();
  for (uint32_t i = 0; i < threads; i++) pthread_create(&t[i], NULL, worker, b);
  for (uint32_t i = 0; i < threads; i++) pthread_join(t[i], NULL);
  *shadow_rays = atomic_load(&b->shadow_rays);
  return rc_now_ms() - t0;
}

static int cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median_of_rest(double *v, int n) {
  if (n == 1) return v[0];
  qsort(v + 1, (size_t)n - 1, sizeof *v, cmp);
  return v[1 + (n - 1) / 2];
}

static int print_bbox(const char *file) {
  rc_scene s = {0};
  rc_affine id = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
  if (rc_mesh_load(file, NULL, &id, -1, &s, file) != RC_OK) return 2;
  double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
  for (size_t i = 0; i < s.triangle_count; i++)
    for (int k = 0; k < 3; k++) {
      const double v[3] = {s.triangles[i].v[k].x, s.triangles[i].v[k].y, s.triangles[i].v[k].z};
      for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], v[a]), hi[a] = fmax(hi[a], v[a]);
    }
  printf("%.9g %.9g %.9g %.9g %.9g %.9g %zu\n", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], s.triangle_count);
  rc_scene_free(&s);
  return 0;
}

int main(int argc, char **argv) {
  if (argc == 3 && strcmp(argv[1], "--bbox") == 0) return print_bbox(argv[2]);
  if (argc < 2) {
    fprintf(stderr, "usage: bench_embree SCENE [--width W] [--height H] [--repeat N] [--threads T] [--out IMAGE]\n");
    return 2;
  }
  uint32_t width = 0, height = 0, repeat = 5, threads = 2;
  const char *out = NULL, *shading = "reference", *quality = "medium";
  int shadow_packets = 0, coherent = 0;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "--width")) width = (uint32_t)atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--height")) height = (uint32_t)atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--repeat")) repeat = (uint32_t)atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--threads")) threads = (uint32_t)atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--out")) out = argv[i + 1];
    else if (!strcmp(argv[i], "--shading")) shading = argv[i + 1];
    else if (!strcmp(argv[i], "--shadow-packets")) shadow_packets = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--coherent")) coherent = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--quality")) quality = argv[i + 1];
    else {
      fprintf(stderr, "bench_embree: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  if (strcmp(shading, "reference") && strcmp(shading, "lambert")) return 2;
  if (threads < 1 || threads > 64 || repeat < 1) return 2;
  rc_scene s;
  /* The benchmark's scenes (tools/mesh_scene.sh) frame Debian's model files where they are
   * installed: a scene named on this tool's own command line is trusted. */
  const rc_load_options load = {.allow_outside_paths = true};
  if (rc_scene_load(argv[1], &load, &s) != RC_OK) return 2;
  if (width) s.width = width;
  if (height) s.height = height;
  s.samples_per_pixel = 1;
  rc_packed_scene p;
  if (rc_scene_pack(&s, &p) != RC_OK) return 2;
  for (uint32_t i = 0; i < p.frame.sphere_count; i++)
    if (p.spheres[i].transform != RC_NO_TRANSFORM) {
      fprintf(stderr, "bench_embree: transformed spheres are not supported\n");
      return 2;
    }

  RTCDevice dev = rtcNewDevice("threads=1"); /* our threads drive it; no TBB pool */
  double t0 = rc_now_ms();
  RTCScene scene = rtcNewScene(dev);
  rtcSetSceneBuildQuality(scene, !strcmp(quality, "high")  ? RTC_BUILD_QUALITY_HIGH
                                  : !strcmp(quality, "low") ? RTC_BUILD_QUALITY_LOW
                                                            : RTC_BUILD_QUALITY_MEDIUM);
  bench b = {.p = &p, .sc = {.frame = &p.frame}, .scene = scene, .tri_geom = RTC_INVALID_GEOMETRY_ID,
             .sphere_geom = RTC_INVALID_GEOMETRY_ID, .lambert = !strcmp(shading, "lambert"),
             .shadow_packets = shadow_packets != 0, .coherent = coherent != 0};
  if (p.frame.triangle_count) {
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                       3 * p.frame.triangle_count);
    unsigned *idx = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                            p.frame.triangle_count);
    for (uint32_t i = 0; i < p.frame.triangle_count; i++) {
      const vec3 tv[3] = {p.triangles[i].v0, p.triangles[i].v1, p.triangles[i].v2};
      for (int k = 0; k < 3; k++) {
        v[9 * i + 3 * k] = tv[k].x, v[9 * i + 3 * k + 1] = tv[k].y, v[9 * i + 3 * k + 2] = tv[k].z;
        idx[3 * i + k] = 3 * i + (unsigned)k;
      }
    }
    rtcCommitGeometry(g);
    b.tri_geom = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
  }
  if (p.frame.sphere_count) {
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float),
                                       p.frame.sphere_count);
    for (uint32_t i = 0; i < p.frame.sphere_count; i++) {
      v[4 * i] = p.spheres[i].center.x, v[4 * i + 1] = p.spheres[i].center.y, v[4 * i + 2] = p.spheres[i].center.z;
      v[4 * i + 3] = p.spheres[i].radius;
    }
    rtcCommitGeometry(g);
    b.sphere_geom = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene);
  double build_ms = rc_now_ms() - t0;
  b.rgb = calloc((size_t)s.width * s.height * 3, sizeof(float));
  double *ms = calloc(repeat, sizeof *ms);
  uint64_t primary_rays = (uint64_t)s.width * s.height, shadow = 0;
  double mrays[2];
  for (int mode = 0; mode < 2; mode++) {
    for (uint32_t r = 0; r < repeat; r++) ms[r] = render(&b, mode == 1, threads, &shadow);
    double med = median_of_rest(ms, (int)repeat);
    mrays[mode] = (double)(primary_rays + shadow) / (med * 1e3);
  }
  if (out) {
    char err[256];
    if (rc_image_write(out, (int)s.width, (int)s.height, 3, b.rgb, rc_encoding_linear(), false, err, sizeof err))
      fprintf(stderr, "bench_embree: %s\n", err);
  }
  printf("{ \"embree_build_ms\": %.2f, \"embree_single_mrays_per_s\": %.3f, \"embree_packet8_mrays_per_s\": %.3f, "
         "\"rays_primary\": %llu, \"rays_shadow\": %llu, \"threads\": %u }\n",
         build_ms, mrays[0], mrays[1], (unsigned long long)primary_rays, (unsigned long long)shadow, threads);
  rtcReleaseScene(scene);
  rtcReleaseDevice(dev);
  free(b.rgb);
  free(ms);
  rc_packed_scene_free(&p);
  rc_scene_free(&s);
  return 0;
}
