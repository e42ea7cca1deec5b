// rc_trace.glsl: one camera sample: the primary ray, then mirror bounces up to
// frame.reflection_depth, each weighted by the product of the mirror coefficients so far.

// Starts the AOV record at the primary hit of sample 0.
void aov_begin(hit_record h) {
  uint object = surface_object(h.object);
  aov_record.hit = (h.kind == RC_HIT_NONE) ? 0.0 : 1.0;
  aov_record.object = (h.kind == RC_HIT_NONE) ? -1.0 : float(object);
  aov_record.t = (h.kind == RC_HIT_NONE) ? 0.0 : float(h.t);
  aov_record.shadow_bits = 0.0;
  aov_record.normal = vec3(0.0);
  // Counted by raycast.comp under certify; otherwise no sample is certified.
  aov_record.uncertified = certify ? 0.0 : float(scene_samples_per_pixel());
  aov_record.certified_sum = vec3(0.0);
  aov_record.uncertified_mask = 0u;
  aov_record.decisions = 0u;
}

rvec3 trace_sample(uvec2 pixel, uint s) {
  // Raster y grows upwards from the bottom row; image rows grow downwards.
  vec2 offset = sample_offset(pixel, s);
  vec2 raster = vec2(float(pixel.x) + offset.x, float(frame.camera.height - 1u - pixel.y) + offset.y);
  rvec3 o;
  rvec3 d;
  camera_ray(raster, o, d);
#if RC_CERTIFY
  if (certify) cert_camera(raster);
#endif
  rvec3 color = rvec3(0.0);
  rvec3 weight = rvec3(1.0);
  uvec2 nodes = eye_nodes(pixel);
  // The sample's ray cone (Akenine-Moller et al., "Texture Level of Detail Strategies for
  // Real-Time Ray Tracing", Ray Tracing Gems, 2019, ch. 20), for texture lookups: its width
  // grows by the spread angle per unit of distance. A mirror passes it on, its spread grown
  // by twice the angle the normal turns through across the cone's width (a convex
  // sphere's w / r, doubled by the reflection; 0 on a flat or unknown surface).
  real cone_width = real(frame.cone_width);
  real cone_spread = real(frame.cone_spread);
  for (uint depth = 0u; depth <= scene_reflection_depth(); depth++) {
    if (!budget_step()) break;
    hit_record h;
    spawned_ray = depth > 0u;
    bool hit = closest_hit(o, d, nodes, h);
#if RC_CERTIFY
    if (certify) cert_note(depth == 0u ? RC_UNCERTIFIED_HIT : RC_UNCERTIFIED_BOUNCE);
#endif
    aov_recording = aov_enabled && s == 0u && depth == 0u;
    if (aov_recording) aov_begin(h);
    // Once a sample: a later light pass traces the same rays again.
    decision_key = (s << 8u) + depth;
    if (light_pass_begin() == 0u) note_decision(hit ? 2u * (surface_object(h.object) + 1u) : 0u);
    if (!hit) {
      if (light_pass_begin() == 0u) color += weight * rvec3(frame.background);
      break;
    }
    surface sf = surface_at(o, d, h);
    precise real width = cone_width + cone_spread * h.t;
    sf.footprint = width / select_max(abs(dot(sf.ng, d)), RL(0.000001));
#if RC_CERTIFY
    if (certify) cert_surface(d, h, sf);
    if (certify) cert_note(depth == 0u ? RC_UNCERTIFIED_HIT : RC_UNCERTIFIED_BOUNCE);
    real ed_in = cert_ed;
    real across = certify ? cert_mirror_across(h, sf, o, d, cert_eo, cert_ed) : -1.0;
    if (certify) cert_spawn_object = surface_object(h.object);
#endif
    if (aov_recording) aov_record.normal = vec3(sf.n);
    color += weight * shade_phong(sf, d);
#if RC_CERTIFY
    if (certify) cert_note(depth == 0u ? RC_UNCERTIFIED_SHADOW : RC_UNCERTIFIED_BOUNCE);
#endif
    aov_recording = false;
    rvec3 mirror = rvec3(load_material(sf.material).mirror);
    if (depth == scene_reflection_depth() || mirror == rvec3(0.0)) break;
    weight *= mirror;
    cone_width = width;
    cone_spread = cone_spread + 2.0 * width * sf.curvature;
    o = spawn_origin(sf);
    precise rvec3 bounced = normalize(reflect(d, sf.n)); // unfused, as the CPU twin's (rc_camera.glsl)
    d = bounced;
    o = t_min_start(o, d);
    nodes = uvec2(0u, frame.bvh_node_count);  // the eye buffer is for primary rays
#if RC_CERTIFY
    if (certify) cert_reflect(sf, o, ed_in, across);
#endif
    if (light_pass_begin() == 0u) reflection_rays++;
  }
#if RC_CERTIFY
  // What the last bounce's set-up (cert_reflect) left uncertified, if nothing before did.
  if (certify) cert_note(RC_UNCERTIFIED_BOUNCE);
#endif
  return color;
}
