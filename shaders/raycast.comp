#version 450
// raycast.comp: one invocation per pixel of a tile. Each dispatch adds up to
// push.batch_samples more samples to every pixel's running sum in `accum`; the host
// repeats dispatches until every pixel has frame.samples_per_pixel (docs/design.md §2).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#if RC_F64
#extension GL_ARB_gpu_shader_int64 : require
#endif

#include "rc_shared.h"

// RC_QUADRICS=0 builds the module without quadric and composite code (host/gpu/gpu_shaders.c
// picks it for scenes that have neither): lavapipe translates and optimizes the whole
// module before specialization removes dead code, and the quadric code tripled that time.
#ifndef RC_QUADRICS
#define RC_QUADRICS 1
#endif
// RC_PATCHES=0 builds it without the Bezier patch code (rc_patch.glsl): its Newton
// iteration, inlined wherever an object is tested, cost lavapipe 150-350 ms more CPU to
// create every quadric scene's pipeline before specialization removed it.
#ifndef RC_PATCHES
#define RC_PATCHES RC_QUADRICS
#endif

layout(local_size_x_id = RC_SPEC_LOCAL_SIZE_X, local_size_y_id = RC_SPEC_LOCAL_SIZE_Y) in;
layout(constant_id = RC_SPEC_LOOP_BUDGET) const uint loop_budget = RC_LOOP_BUDGET;
layout(constant_id = RC_SPEC_AOV) const bool aov_enabled = false;
layout(constant_id = RC_SPEC_BVH) const bool use_bvh = true;
layout(constant_id = RC_SPEC_SPHERE_FORMULA) const uint sphere_formula = RC_SPHERE_GEOMETRIC;
layout(constant_id = RC_SPEC_TRIANGLE_FORMULA) const uint triangle_formula = RC_TRIANGLE_WATERTIGHT;
layout(constant_id = RC_SPEC_OFFSET_STRATEGY) const uint offset_strategy = RC_OFFSET_ERROR_BOUND;
layout(constant_id = RC_SPEC_OFFSET_EPSILON) const float offset_epsilon = RC_OFFSET_EPSILON_DEFAULT;
layout(constant_id = RC_SPEC_KINDS) const uint scene_kinds = RC_KIND_ALL;
layout(constant_id = RC_SPEC_LIGHT_COUNT) const uint spec_light_count = RC_LIGHTS_FROM_FRAME;
layout(constant_id = RC_SPEC_SHADOWS) const uint spec_shadows = RC_SHADOWS_FROM_FRAME;
layout(constant_id = RC_SPEC_SPECULAR_MODEL) const uint spec_specular_model = RC_SPECULAR_FROM_FRAME;
layout(constant_id = RC_SPEC_REFLECTION_DEPTH) const uint spec_reflection_depth = RC_DEPTH_FROM_FRAME;
layout(constant_id = RC_SPEC_SAMPLES) const uint spec_samples = RC_SAMPLES_FROM_FRAME;
layout(constant_id = RC_SPEC_LIGHT_PASSES) const bool light_passes = false;
layout(constant_id = RC_SPEC_LEVELS) const uint spec_levels = 0u;
const bool encode_levels = spec_levels != 0u;
const uint level_curve = spec_levels - 1u; // a constant: the other curves' code is dropped
// RC_CERTIFY=1 builds the module of --precision certified (rc_certify.glsl); the others have
// none of its code, which is under `#if RC_CERTIFY` where it is called: lavapipe translates a
// whole module before specialization drops dead code, and the certificates cost every
// pipeline about 100 ms of creation there.
#ifndef RC_CERTIFY
#define RC_CERTIFY 0
#endif
const bool certify = RC_CERTIFY != 0;

layout(std140, binding = RC_BINDING_FRAME) uniform Frame { packed_frame frame; };
layout(std430, binding = RC_BINDING_ACCUM) buffer Accum { vec4 accum[]; };
layout(std430, binding = RC_BINDING_STATUS) buffer Status { packed_status status; };
layout(std430, binding = RC_BINDING_AOV) buffer Aov { packed_aov aov[]; };
// The AOV binding's other use (rc_shared.h, RC_BINDING_AOV): a pipeline has one or neither.
layout(std430, binding = RC_BINDING_AOV) buffer Levels {
  packed_levels level_table;
  uint levels[];
};
layout(push_constant) uniform Push { packed_push push; };

// Where each kind's object numbers begin (rc_intersect.glsl's object_kind), read from the
// frame once, at the top of main(). Read where they are used, inside the BVH's leaf loop,
// llvmpipe fetched them as per-lane gathers on every object tested (finding 11).
uint first_triangle_object;
uint first_quadric_object;
uint first_csg_object;
uint shadow_rays = 0u;
uint reflection_rays = 0u;
// Whether the ray being traced left a surface (shadow and reflection rays): only those can
// re-hit the surface they start on, so only they reject hits within t's error bound.
bool spawned_ray = false;
// The lights this dispatch shades, [pass_first_light, pass_end_light): all of them unless the
// scene's samples are too long for one dispatch (RC_SPEC_LIGHT_PASSES, host/gpu/gpu_plan.h).
uint pass_first_light = 0u;
uint pass_end_light = 0u;
// The AOV record of this invocation's first sample (rc_trace.glsl fills it).
bool aov_recording = false;
packed_aov aov_record;
// The sample and bounce being traced (rc_trace.glsl), and the digest of that sample's
// decisions so far (packed_aov.decisions).
uint decision_key = 0u;
uint sample_decisions = 0u;

// The scene's features: the specialized constant, or the frame's value in a generic
// pipeline. A constant lets the compiler drop unused code and fix the loop counts.
bool has_kind(uint kind) { return (scene_kinds & kind) != 0u; }
uint scene_light_count() { return spec_light_count == RC_LIGHTS_FROM_FRAME ? frame.light_count : spec_light_count; }
bool scene_shadows() { return (spec_shadows == RC_SHADOWS_FROM_FRAME ? frame.shadows : spec_shadows) != 0u; }
uint scene_specular_model() {
  return spec_specular_model == RC_SPECULAR_FROM_FRAME ? frame.specular_model : spec_specular_model;
}
uint scene_samples_per_pixel() {
  return spec_samples == RC_SAMPLES_FROM_FRAME ? frame.samples_per_pixel : spec_samples;
}
uint scene_reflection_depth() {
  return spec_reflection_depth == RC_DEPTH_FROM_FRAME ? frame.reflection_depth : spec_reflection_depth;
}
// The light pass: constants, and so free, where the scene needs none. Only the first pass of
// a sample adds what no light contributes (background, ambient, emission) and counts its
// reflection rays.
uint light_pass_begin() { return light_passes ? pass_first_light : 0u; }
uint light_pass_end() { return light_passes ? pass_end_light : scene_light_count(); }

// Chris Wellons's "lowbias32" integer hash (2018): full avalanche in 32 bits, so that the
// digest's sum of hashes shows any one decision that differs. Its twin: ref_render.c.
uint decision_hash(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// Adds one decision of the sample and bounce in decision_key to the sample's digest: 0 a
// miss, 2 (object + 1) a hit, 2 light + 1 a blocked shadow ray. Only where AOVs are recorded.
void note_decision(uint value) {
  if (aov_enabled) sample_decisions += decision_hash(decision_hash(decision_key) + value);
}

#include "rc_real.glsl"
#include "rc_scene_access.glsl"
#include "rc_budget.glsl"
#include "rc_random.glsl"
#include "rc_camera.glsl"
#include "rc_triangle.glsl"
#if RC_QUADRICS
#include "rc_quadric.glsl"
#endif
#if RC_CERTIFY
#include "rc_certify.glsl"  // after rc_quadric.glsl: it recomputes the quadric tests
#if RC_QUADRICS
#include "rc_certify_csg.glsl"
#endif
#endif
#if RC_PATCHES
#include "rc_patch.glsl"
#if RC_CERTIFY
#include "rc_certify_patch.glsl"
#endif
#endif
#include "rc_intersect.glsl"
#include "rc_bvh.glsl"
#include "rc_shade.glsl"
#include "rc_trace.glsl"

// The 8-bit level of one channel's sum of samples: how many of sum_threshold[1..255] are
// <= it, as the writer's rc_level_of counts them (host/image/levels8.h): comparisons only,
// so the byte is the writer's exactly. The count starts from an estimate, the level of the
// sum's value by the curve in f32 (which a GPU's pow need not round as the host's does),
// and walks to the exact level: one comparison each way where the estimate is right or one
// off. A binary search from the table alone took 8 dependent loads a channel, and cost the
// showcase's kernel 13 % on lavapipe.
uint level_of(float sum) {
  float x = clamp(sum * level_table.value_scale, 0.0, 1.0);
  float e = x;
  if (level_curve == RC_LEVEL_CURVE_SRGB)
    e = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
  else if (level_curve == RC_LEVEL_CURVE_GAMMA)
    e = pow(x, level_table.inv_gamma);
  uint k = min(uint(max(e, 0.0) * 255.0 + level_table.bias), 255u);
  while (k < 255u && sum >= level_table.sum_threshold[k + 1u]) k++;
  while (k > 0u && !(sum >= level_table.sum_threshold[k])) k--;
  return k;
}

uint encode_pixel(vec3 sum) {
  return level_of(sum.r) | level_of(sum.g) << 8 | level_of(sum.b) << 16 | 255u << 24;
}

// Set when any invocation of the workgroup ran out of budget. llvmpipe runs the
// invocations of a workgroup as SIMD lanes and its loop cap counts the vector's
// iterations, so once one lane is over budget the loops of its neighbours may have been
// cut short too, silently. The whole workgroup therefore discards its batch.
shared bool group_exhausted;

void main() {
  first_triangle_object = frame.sphere_count;
  first_quadric_object = first_triangle_object + frame.triangle_count;
  first_csg_object = first_quadric_object + frame.quadric_count;
  if (gl_LocalInvocationIndex == 0u) group_exhausted = false;
  barrier();

  // Rows of workgroups in the order host/gpu/gpu_tiles.h explains: spread over the tile
  // so that each of llvmpipe's threads gets an even share of the image.
  uint row = (gl_WorkGroupID.y * push.row_stride) % gl_NumWorkGroups.y;
  uvec2 local = uvec2(gl_WorkGroupID.x, row) * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy;
  bool inside = local.x < push.tile_width && local.y < push.tile_height;
  uvec2 pixel = uvec2(push.tile_x, push.tile_y) + local;
  uint slot = local.y * push.tile_width + local.x;

  vec4 sum = vec4(0.0);
  uint target = 0u;     // the pixel's progress after this dispatch
  uint total = 0u;      // ... when it is complete
  bool aov_write = false;
  // Samples (or light passes) of this dispatch not certified (rc_certify.glsl), by where their
  // first uncertified decision lies (cert_note: the hit, a shadow ray, a bounce).
  uvec3 uncertified_at = uvec3(0u);
  vec3 certified_sum = vec3(0.0);  // the certified samples' colours so far (packed_aov)
  uint uncertified_mask = 0u;
  bool trace_all = true;  // false: trace only the samples in trace_mask
  uint trace_mask = 0u;
  uint decisions = 0u;  // packed_aov.decisions, continued from the pixel's earlier dispatches
  packed_aov mark;
  if (inside) {
    sum = accum[slot];
    uint done = uint(sum.a);
    if (certify && done > 0u) certified_sum = aov[slot].certified_sum;
    // Certified mode's f64 re-render (push.masked): a pixel the f32 pass certified is
    // complete before it starts; the host keeps the f32 pass's colour for it. Where the
    // f32 pass's record names every uncertified sample, only those are traced, added to
    // the sum of the certified ones.
    if (push.masked != 0u) {
      mark = aov[slot];
      if (!(mark.uncertified > 0.0)) {
        sum = vec4(0.0, 0.0, 0.0, float(scene_samples_per_pixel() * (light_passes ? scene_light_count() : 1u)));
        done = uint(sum.a);
      } else if (!light_passes && float(bitCount(mark.uncertified_mask)) == mark.uncertified) {
        trace_all = false;
        trace_mask = mark.uncertified_mask;
        if (done == 0u) sum.rgb = mark.certified_sum;
      }
    }
    // The digest goes on from the pixel's earlier dispatches, or from the certified samples'
    // where a re-render traces only the others; a pixel traced from its first sample starts
    // from none.
    if (aov_enabled && (done > 0u || !trace_all)) decisions = aov[slot].decisions;
    if (light_passes) {
      // Progress counts lights: the next pass of sample s starts at light done - s x lights,
      // and traces the sample's rays again (the same rays: nothing in them is random).
      uint lights = scene_light_count();
      uint s = done / lights;
      total = scene_samples_per_pixel() * lights;
      target = done;
      if (s < scene_samples_per_pixel() && budget_step()) {
        pass_first_light = done - s * lights;
        pass_end_light = min(pass_first_light + push.light_pass, lights);
        sample_decisions = 0u;
        sum.rgb += vec3(trace_sample(pixel, s));
        bool decided = true;  // the pass's decisions join the digest (certified ones only)
#if RC_CERTIFY
        if (!cert_ok) uncertified_at[cert_stage - 1u]++;
        decided = !certify || cert_ok;
#endif
        if (decided) decisions += sample_decisions;
        target = s * lights + pass_end_light;
        // The first sample's record gathers its shadow bits over the passes.
        aov_write = aov_enabled && s == 0u;
        if (aov_write && pass_first_light > 0u) {
          aov_record.shadow_bits += aov[slot].shadow_bits;
          aov_record.uncertified = aov[slot].uncertified;
        }
      }
    } else {
      total = scene_samples_per_pixel();
      target = min(done + push.batch_samples, total);
      // Sample 0 makes the record; a re-render that skips it keeps the f32 pass's.
      aov_write = aov_enabled && done == 0u && target > 0u && (trace_all || (trace_mask & 1u) != 0u);
      for (uint s = done; s < target; s++) {
        if (!trace_all && (s >= 32u || ((trace_mask >> s) & 1u) == 0u)) continue;
        if (!budget_step()) break;
        sample_decisions = 0u;
        vec3 c = vec3(trace_sample(pixel, s));
        sum.rgb += c;
        bool decided = true;  // the sample's decisions join the digest (certified ones only)
#if RC_CERTIFY
        if (!cert_ok) {
          uncertified_at[cert_stage - 1u]++;
          if (s < 32u) uncertified_mask |= 1u << s;
        } else {
          certified_sum += c;
        }
        decided = !certify || cert_ok;
#endif
        if (decided) decisions += sample_decisions;
      }
      if (aov_write && push.masked != 0u) {
        // The marks stay for the pixel's later dispatches.
        aov_record.uncertified = mark.uncertified;
        aov_record.certified_sum = mark.certified_sum;
        aov_record.uncertified_mask = mark.uncertified_mask;
      }
    }
#if RC_QUADRICS
    if (crossing_blame != 0u && atomicCompSwap(status.crossing_object, 0u, crossing_blame) == 0u)
      status.crossing_pixel = 1u + pixel.y * frame.camera.width + pixel.x;
#endif
#if RC_PATCHES
    if (patch_stall_piece != 0u && atomicCompSwap(status.patch_unconverged_object, 0u, first_quadric_object + patch_stall_piece) == 0u)
      status.patch_unconverged_pixel = 1u + pixel.y * frame.camera.width + pixel.x;
#endif
    if (budget_exhausted) {
      group_exhausted = true;
      // The first lane to report names its object and pixel (both, or neither).
      if (budget_blame != 0u && atomicCompSwap(status.exhausted_object, 0u, budget_blame) == 0u)
        status.exhausted_pixel = 1u + pixel.y * frame.camera.width + pixel.x;
    }
  }
  barrier();
  if (!inside) return;
  if (group_exhausted) {
    atomicAdd(status.exhausted_pixels, 1u);
    atomicAdd(status.incomplete_pixels, 1u);
    return;
  }
  accum[slot] = vec4(sum.rgb, float(target));
  if (encode_levels && target == total) levels[slot] = encode_pixel(sum.rgb);
  if (aov_write) aov[slot] = aov_record;
  if (aov_enabled) aov[slot].decisions = decisions;
  // The count and the bits gather over the pixel's dispatches: its first wrote the
  // record, with none. The sum runs on, in sample order, as the colour's does.
  if (certify) {
    aov[slot].uncertified += float(uncertified_at.x + uncertified_at.y + uncertified_at.z);
    aov[slot].uncertified_mask |= uncertified_mask;
    aov[slot].certified_sum = certified_sum;
  }
  if (target < total) atomicAdd(status.incomplete_pixels, 1u);
  if (shadow_rays != 0u) atomicAdd(status.shadow_rays, shadow_rays);
#if RC_PATCHES
  if (patch_stalls != 0u) atomicAdd(status.patch_unconverged, patch_stalls);
#endif
  if (reflection_rays != 0u) atomicAdd(status.reflection_rays, reflection_rays);
  if (uncertified_at.x != 0u) atomicAdd(status.uncertified_hit, uncertified_at.x);
  if (uncertified_at.y != 0u) atomicAdd(status.uncertified_shadow, uncertified_at.y);
  if (uncertified_at.z != 0u) atomicAdd(status.uncertified_bounce, uncertified_at.z);
  if (budget_steps != 0u) atomicMax(status.max_steps, budget_steps);
}
