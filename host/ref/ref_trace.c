/* ref_trace.c: mirrors shaders/rc_trace.glsl. */
#include "ref/ref_real.h"
#include "ref/ref_shader.h"


void REF(aov_begin)(const ref_scene *sc, const ref_hit *h) {
  uint32_t object = REF(surface_object)(sc, h->object);
  ref_aov_record.hit = (h->kind == RC_HIT_NONE) ? 0.0f : 1.0f;
  ref_aov_record.object = (h->kind == RC_HIT_NONE) ? -1.0f : (float)object;
  ref_aov_record.t = (h->kind == RC_HIT_NONE) ? 0.0f : (float)h->t;
  ref_aov_record.shadow_bits = 0.0f;
  ref_aov_record.normal = rcm_make_f(0, 0, 0);
  ref_aov_record.uncertified = sc->frame->certify ? 0.0f : (float)sc->frame->samples_per_pixel;
  ref_aov_record.certified_sum = rcm_make_f(0, 0, 0);
  ref_aov_record.uncertified_mask = 0;
  ref_aov_record.decisions = 0;
}

rvec3 REF(trace_sample)(const ref_scene *sc, uint32_t px, uint32_t py, uint32_t s) {
  ref_vec2 offset = ref_sample_offset(sc, px, py, s);
  ref_vec2 raster = {(float)px + offset.x, (float)(sc->frame->camera.height - 1u - py) + offset.y};
  rvec3 o, d;
  REF(camera_ray)(sc, raster, &o, &d);
  if (sc->frame->certify) REF(cert_camera)(sc, raster);
  rvec3 color = RV(make)(0, 0, 0);
  rvec3 weight = RV(make)(1, 1, 1);
  uint32_t first, end;
  REF(eye_nodes)(sc, px, py, &first, &end);
  real cone_width = (real)sc->frame->cone_width;
  real cone_spread = (real)sc->frame->cone_spread;
  for (uint32_t depth = 0; depth <= sc->frame->reflection_depth; depth++) {
    ref_hit h;
    ref_spawned_ray = depth > 0;
    bool hit = REF(closest_hit)(sc, o, d, first, end, &h);
    if (sc->frame->certify) REF(cert_note)(depth == 0 ? RC_UNCERTIFIED_HIT : RC_UNCERTIFIED_BOUNCE);
    ref_aov_recording = ref_aov_enabled && s == 0 && depth == 0;
    if (ref_aov_recording) REF(aov_begin)(sc, &h);
    ref_decision_key = (s << 8u) + depth;
    ref_note_decision(hit ? 2u * (REF(surface_object)(sc, h.object) + 1u) : 0u);
    if (!hit) {
      color = RV(add)(color, RV(mul)(weight, rvec3_from(sc->frame->background)));
      break;
    }
    ref_surface sf = REF(surface_at)(sc, o, d, &h);
    real width = cone_width + cone_spread * h.t;
    sf.footprint = width / rmax(R_ABS(RV(dot)(sf.ng, d)), RL(0.000001));
    if (sc->frame->certify) REF(cert_surface)(sc, d, &h, &sf);
    if (sc->frame->certify) REF(cert_note)(depth == 0 ? RC_UNCERTIFIED_HIT : RC_UNCERTIFIED_BOUNCE);
    real ed_in = ref_cert_ed;
    real across = sc->frame->certify ? REF(cert_mirror_across)(sc, &h, &sf, o, d, ref_cert_eo, ref_cert_ed) : -1;
    if (sc->frame->certify) ref_cert_spawn_object = REF(surface_object)(sc, h.object);
    if (ref_aov_recording) ref_aov_record.normal = vec3_from(sf.n);
    color = RV(add)(color, RV(mul)(weight, REF(shade_phong)(sc, &sf, d)));
    if (sc->frame->certify) REF(cert_note)(depth == 0 ? RC_UNCERTIFIED_SHADOW : RC_UNCERTIFIED_BOUNCE);
    ref_aov_recording = false;
    rvec3 mirror = rvec3_from(sc->materials[sf.material].mirror);
    if (depth == sc->frame->reflection_depth || RV(eq)(mirror, RV(make)(0, 0, 0))) break;
    weight = RV(mul)(weight, mirror);
    cone_width = width;
    cone_spread = cone_spread + 2 * width * sf.curvature;
    o = REF(spawn_origin)(sc, &sf);
    rvec3 bounced = RV(normalize)(RV(reflect)(d, sf.n)); /* `precise` in the shader: never fused */
    d = bounced;
    o = REF(t_min_start)(sc, o, d);
    first = 0, end = sc->frame->bvh_node_count; /* the eye buffer is for primary rays */
    if (sc->frame->certify) REF(cert_reflect)(sc, &sf, o, ed_in, across);
    ref_reflection_rays++;
  }
  if (sc->frame->certify) REF(cert_note)(RC_UNCERTIFIED_BOUNCE);
  return color;
}
