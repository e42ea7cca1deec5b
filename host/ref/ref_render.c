/* ref_render.c: the per-pixel loop of raycast.comp's main() on CPU threads. Rows are
 * handed out in blocks through an atomic counter; each pixel's samples are summed in
 * order 0..spp-1, as the shader does across its batches. */
#include "ref/ref_render.h"

#include "base/certified_marks.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

#include "ref/ref_shader.h"

_Thread_local uint64_t ref_shadow_rays, ref_reflection_rays, ref_work;
_Thread_local bool ref_spawned_ray;
_Thread_local bool ref_aov_enabled, ref_aov_recording;
_Thread_local packed_aov ref_aov_record;
_Thread_local uint32_t ref_decision_key, ref_sample_decisions;

/* raycast.comp's decision_hash (Wellons's lowbias32) and note_decision, bit for bit. */
uint32_t ref_decision_hash(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

void ref_note_decision(uint32_t value) {
  if (ref_aov_enabled) ref_sample_decisions += ref_decision_hash(ref_decision_hash(ref_decision_key) + value);
}

#define ROWS_PER_JOB 4

typedef struct {
  ref_scene scene;
  bool only_uncertified; /* rc_ref_rerender: the pixels whose aov counts uncertified samples */
  /* The f32 pass's uncertified samples, by RC_UNCERTIFIED_HIT, _SHADOW, _BOUNCE. */
  atomic_uint_fast64_t uncertified_at[3];
  const packed_frame *frame;
  bool f64;
  float *rgb;
  packed_aov *aov;
  rc_region region;
  atomic_uint next_row;
  atomic_uint_fast64_t shadow_rays, reflection_rays;
  bool flush_subnormals;
  atomic_uint crossing_object; /* 1 + the composite of the first crossing failure, 0: none */
  uint32_t crossing_x, crossing_y;
  atomic_uint_fast64_t patch_stalls;
  atomic_uint patch_stall_object; /* 1 + the object of the first stall, 0: none */
  uint32_t patch_stall_x, patch_stall_y;
  atomic_uint_fast64_t lane_steps, vector_steps; /* rc_ref_stats: the SIMD model */
  uint32_t *model;          /* per thread, 2 x samples_per_pixel steps: worker() */
  atomic_uint next_thread;
} job;

/* sample_steps[s]: the loop steps sample s took (ref_work: boxes, object tests, Newton). */
static void render_pixel(job *j, uint32_t x, uint32_t y, uint32_t *sample_steps) {
  const uint32_t spp = j->frame->samples_per_pixel;
  size_t index = (size_t)(y - j->region.y0) * rc_region_width(j->region) + (x - j->region.x0);
  float *o = j->rgb + 3 * index;
  memset(sample_steps, 0, spp * sizeof *sample_steps);
  /* rc_ref_rerender: the f32 pass's record marks what to render again. */
  const packed_aov *mark = j->only_uncertified ? &j->aov[index] : NULL;
  if (mark && !(mark->uncertified > 0)) return;
  uint32_t uncertified_at[3] = {0, 0, 0}, uncertified_mask = 0; /* by cert_note's stage */
  vec3 certified_sum = {0, 0, 0};
  bool traced_first = true;
  /* As main()'s: from the certified samples' digest where only the others are traced. */
  uint32_t decisions = mark && rc_aov_per_sample(mark) ? mark->decisions : 0;
  if (j->f64) {
    dvec3 sum = {0, 0, 0};
    if (mark && rc_aov_per_sample(mark))
      sum = (dvec3){mark->certified_sum.x, mark->certified_sum.y, mark->certified_sum.z};
    for (uint32_t s = 0; s < spp; s++) {
      if (mark && !rc_aov_rerenders(mark, s)) {
        if (s == 0) traced_first = false;
        continue;
      }
      uint64_t w = ref_work;
      ref_sample_decisions = 0;
      sum = rcm_add_d(sum, ref_trace_sample_d(&j->scene, x, y, s));
      sample_steps[s] = (uint32_t)(ref_work - w);
      if (!j->frame->certify || ref_cert_ok_d) decisions += ref_sample_decisions;
    }
    sum = rcm_scale_d(sum, 1.0 / spp);
    o[0] = (float)sum.x, o[1] = (float)sum.y, o[2] = (float)sum.z;
  } else {
    /* The shader's arithmetic: an f32 running sum, divided by the f32 sample count. */
    vec3 sum = {0, 0, 0};
    for (uint32_t s = 0; s < spp; s++) {
      uint64_t w = ref_work;
      ref_sample_decisions = 0;
      vec3 c = ref_trace_sample_f(&j->scene, x, y, s);
      sum = rcm_add_f(sum, c);
      sample_steps[s] = (uint32_t)(ref_work - w);
      if (!j->frame->certify || ref_cert_ok_f) decisions += ref_sample_decisions;
      if (!j->frame->certify) continue;
      if (!ref_cert_ok_f) {
        uncertified_at[ref_cert_stage_f - 1]++;
        if (s < 32) uncertified_mask |= 1u << s;
      } else {
        certified_sum = rcm_add_f(certified_sum, c);
      }
    }
    o[0] = sum.x / (float)spp, o[1] = sum.y / (float)spp, o[2] = sum.z / (float)spp;
  }
  /* A re-render that skipped sample 0 keeps the f32 pass's record (certified, so the
   * reference's decisions); the marks stay either way. */
  packed_aov rec = traced_first ? ref_aov_record : *mark;
  if (j->frame->certify) {
    rec.uncertified = (float)(uncertified_at[0] + uncertified_at[1] + uncertified_at[2]);
    rec.uncertified_mask = uncertified_mask;
    rec.certified_sum = certified_sum;
    for (int k = 0; k < 3; k++)
      if (uncertified_at[k]) atomic_fetch_add(&j->uncertified_at[k], uncertified_at[k]);
  }
  rec.decisions = decisions;
  if (mark) rc_aov_keep_marks(&rec, mark);
  if (j->aov) j->aov[index] = rec;
  if (ref_crossing_blame) {
    unsigned none = 0;
    if (atomic_compare_exchange_strong(&j->crossing_object, &none, ref_crossing_blame)) j->crossing_x = x, j->crossing_y = y;
    ref_crossing_blame = 0;
  }
  if (ref_patch_stalls) {
    atomic_fetch_add(&j->patch_stalls, ref_patch_stalls);
    unsigned none = 0, object = j->frame->sphere_count + j->frame->triangle_count + ref_patch_stall_piece;
    if (atomic_compare_exchange_strong(&j->patch_stall_object, &none, object)) j->patch_stall_x = x, j->patch_stall_y = y;
    ref_patch_stalls = ref_patch_stall_piece = 0;
  }
}

/* The floating-point control word's flush bits: returns the old word, sets flush on or off. */
#if defined(__x86_64__) || defined(__i386__)
bool rc_ref_can_flush_subnormals(void) { return true; }
static uint64_t set_flush(bool on) {
  unsigned csr = _mm_getcsr();
  const unsigned bits = 0x8000u /* FTZ */ | 0x0040u /* DAZ */;
  _mm_setcsr(on ? csr | bits : csr & ~bits);
  return csr;
}
static void restore_flush(uint64_t word) { _mm_setcsr((unsigned)word); }
#elif defined(__aarch64__)
bool rc_ref_can_flush_subnormals(void) { return true; }
static uint64_t set_flush(bool on) {
  uint64_t fpcr;
  __asm__ volatile("mrs %0, fpcr" : "=r"(fpcr));
  uint64_t word = on ? fpcr | (1ull << 24) /* FZ */ : fpcr & ~(1ull << 24);
  __asm__ volatile("msr fpcr, %0" : : "r"(word));
  return fpcr;
}
static void restore_flush(uint64_t word) { __asm__ volatile("msr fpcr, %0" : : "r"(word)); }
#else
bool rc_ref_can_flush_subnormals(void) { return false; }
static uint64_t set_flush(bool on) { (void)on; return 0; }
static void restore_flush(uint64_t word) { (void)word; }
#endif

/* The SIMD model (rc_ref_stats: lane_steps, vector_steps): the shader runs 8 neighbouring
 * pixels of a row (x / 8 the same) as the lanes of one vector on lavapipe, and a vector
 * takes each sample's loops until its slowest lane is done. */
#define MODEL_LANES 8u

static void *worker(void *arg) {
  job *j = arg;
  /* Restored on the way out: with no thread started this is the caller's thread. */
  uint64_t control = set_flush(j->flush_subnormals);
  ref_shadow_rays = ref_reflection_rays = 0;
  ref_aov_enabled = j->aov != NULL || j->frame->certify;
  const rc_region r = j->region;
  const uint32_t spp = j->frame->samples_per_pixel;
  uint32_t *steps = j->model + 2 * (size_t)spp * atomic_fetch_add(&j->next_thread, 1), *slowest = steps + spp;
  uint64_t lane = 0, vector = 0;
  for (;;) {
    uint32_t y0 = r.y0 + atomic_fetch_add(&j->next_row, ROWS_PER_JOB);
    if (y0 >= r.y1) break;
    for (uint32_t y = y0; y < y0 + ROWS_PER_JOB && y < r.y1; y++) {
      for (uint32_t x = r.x0; x < r.x1; x++) {
        render_pixel(j, x, y, steps);
        for (uint32_t s = 0; s < spp; s++) {
          lane += steps[s];
          if (steps[s] > slowest[s]) slowest[s] = steps[s];
        }
        if (x % MODEL_LANES == MODEL_LANES - 1 || x + 1 == r.x1) {
          for (uint32_t s = 0; s < spp; s++) vector += (uint64_t)MODEL_LANES * slowest[s];
          memset(slowest, 0, spp * sizeof *slowest);
        }
      }
    }
  }
  atomic_fetch_add(&j->lane_steps, lane);
  atomic_fetch_add(&j->vector_steps, vector);
  atomic_fetch_add(&j->shadow_rays, ref_shadow_rays);
  atomic_fetch_add(&j->reflection_rays, ref_reflection_rays);
  restore_flush(control);
  return NULL;
}

static ref_scene scene_of(const rc_packed_scene *p) {
  return (ref_scene){.frame = &p->frame,
                     .spheres = p->spheres,
                     .triangles = p->triangles,
                     .materials = p->materials,
                     .lights = p->lights,
                     .bvh_nodes = p->bvh_nodes,
                     .bvh_prims = p->bvh_prims,
                     .transforms = p->transforms,
                     .normals = p->normals,
                     .quadrics = p->quadrics,
                     .csg = p->csg,
                     .csg_program = p->csg_program,
                     .texels = (const float(*)[4])p->texels,
                     .use_bvh = p->bvh && p->frame.bvh_node_count > 0};
}

/* The job's pixels on opts->threads threads; its counters start at 0 here. */
static rc_status run(job *j, const rc_ref_options *opts, rc_ref_stats *stats) {
  for (int k = 0; k < 3; k++) atomic_init(&j->uncertified_at[k], 0);
  atomic_init(&j->next_row, 0);
  atomic_init(&j->shadow_rays, 0);
  atomic_init(&j->reflection_rays, 0);
  atomic_init(&j->crossing_object, 0);
  atomic_init(&j->patch_stalls, 0);
  atomic_init(&j->patch_stall_object, 0);
  atomic_init(&j->lane_steps, 0);
  atomic_init(&j->vector_steps, 0);
  atomic_init(&j->next_thread, 0);
  long cores = sysconf(_SC_NPROCESSORS_ONLN);
  uint32_t n = opts->threads ? opts->threads : (uint32_t)(cores > 0 ? cores : 1);
  pthread_t *threads = calloc(n, sizeof *threads);
  j->model = calloc((size_t)n * 2 * j->frame->samples_per_pixel, sizeof *j->model);
  if (!threads || !j->model) {
    free(threads);
    free(j->model);
    return RC_ERR_OUT_OF_MEMORY;
  }
  double t0 = rc_now_ms(), c0 = rc_cpu_ms();
  uint32_t started = 0;
  for (; started < n; started++)
    if (pthread_create(&threads[started], NULL, worker, j) != 0) break;
  if (started == 0) worker(j); /* no threads could start: render on this one */
  for (uint32_t i = 0; i < started; i++) pthread_join(threads[i], NULL);
  free(threads);
  free(j->model);
  stats->lane_steps += atomic_load(&j->lane_steps);
  stats->vector_steps += atomic_load(&j->vector_steps);
  stats->render_ms += rc_now_ms() - t0;
  stats->cpu_ms += rc_cpu_ms() - c0;
  stats->threads = started ? started : 1;
  stats->shadow_rays += atomic_load(&j->shadow_rays);
  stats->reflection_rays += atomic_load(&j->reflection_rays);
  for (int k = 0; k < 3; k++) {
    uint64_t at = atomic_load(&j->uncertified_at[k]);
    stats->uncertified_at[k] += at;
    stats->samples_uncertified += at;
  }
  uint64_t stalls = atomic_load(&j->patch_stalls);
  if (stalls && stats->patch_stalls == 0) {
    stats->patch_stall_object = atomic_load(&j->patch_stall_object) - 1;
    stats->patch_stall_x = j->patch_stall_x, stats->patch_stall_y = j->patch_stall_y;
  }
  stats->patch_stalls += stalls;
  uint32_t crossing = atomic_load(&j->crossing_object);
  if (crossing) {
    stats->crossing_object = crossing - 1;
    stats->crossing_x = j->crossing_x, stats->crossing_y = j->crossing_y;
    return RC_ERR_TOO_LARGE;
  }
  return RC_OK;
}

rc_status rc_ref_render(const rc_packed_scene *p, const rc_ref_options *opts, rc_region region, float *rgb,
                        packed_aov *aov, rc_ref_stats *stats) {
  job j = {.scene = scene_of(p), .frame = &p->frame, .f64 = opts->f64, .rgb = rgb, .aov = aov, .region = region,
           .flush_subnormals = opts->flush_subnormals};
  return run(&j, opts, stats);
}

rc_status rc_ref_rerender(const rc_packed_scene *p, const rc_ref_options *opts, rc_region region, float *rgb,
                          packed_aov *aov, rc_ref_stats *stats) {
  /* The reference proper: f64, and its frame without certify (which changes no decision). */
  packed_frame plain = p->frame;
  plain.certify = RC_CERTIFY_OFF;
  job j = {.scene = scene_of(p), .frame = &plain, .f64 = true, .rgb = rgb, .aov = aov, .region = region,
           .flush_subnormals = opts->flush_subnormals, .only_uncertified = true};
  j.scene.frame = &plain;
  uint64_t pixels = 0, samples = 0;
  for (size_t i = 0; i < rc_region_pixels(region); i++) {
    pixels += aov[i].uncertified > 0;
    samples += rc_aov_samples_rerendered(&aov[i], plain.samples_per_pixel);
  }
  double t0 = rc_now_ms();
  rc_status st = run(&j, opts, stats);
  stats->rerender_ms += rc_now_ms() - t0;
  stats->pixels_rerendered += pixels;
  stats->samples_rerendered += samples;
  return st;
}

/* The cost model of a pixel: a fixed part (ray generation, shading, the write) worth this
 * many loop steps, plus the steps its first sample's rays take. */
#define COST_PIXEL_STEPS 8.0
void rc_ref_cost_grid(const rc_packed_scene *p, double cost[RC_REF_COST_CELLS], rc_cost_grid *grid) {
  const ref_scene sc = scene_of(p);
  const uint32_t w = p->frame.camera.width, h = p->frame.camera.height;
  const uint32_t sy = (h + RC_REF_COST_ROWS - 1) / RC_REF_COST_ROWS, sx = (w + RC_REF_COST_COLS - 1) / RC_REF_COST_COLS;
  *grid = (rc_cost_grid){cost, (w + sx - 1) / sx, (h + sy - 1) / sy, sx, sy};
  bool aov = ref_aov_enabled;
  ref_aov_enabled = false;
  for (uint32_t i = 0; i < grid->rows; i++) {
    for (uint32_t j = 0; j < grid->cols; j++) {
      /* The middle pixel of each cell (of what the frame's edge leaves of it) stands for it. */
      uint32_t y = i * sy + sy / 2, x = j * sx + sx / 2;
      if (y >= h) y = (i * sy + h) / 2;
      if (x >= w) x = (j * sx + w) / 2;
      ref_work = 0;
      ref_trace_sample_f(&sc, x, y, 0);
      cost[(size_t)i * grid->cols + j] = COST_PIXEL_STEPS + (double)ref_work;
    }
  }
  ref_aov_enabled = aov;
  ref_crossing_blame = 0;
  ref_patch_stalls = ref_patch_stall_piece = 0;
}
