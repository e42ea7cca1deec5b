// rc_trace.glsl: one camera sample: the primary ray, then mirror bounces up to
// frame.reflection_depth, each weighted by the product of the mirror coefficients so far.

rvec3 trace_sample(uvec2 pixel, uint s) {
  // Raster y grows upwards from the bottom row; image rows grow downwards.
  vec2 offset = sample_offset(pixel, s);
  vec2 raster = vec2(float(pixel.x) + offset.x, float(frame.camera.height - 1u - pixel.y) + offset.y);
  rvec3 o;
  rvec3 d;
  camera_ray(raster, o, d);
  rvec3 color = rvec3(0.0);
  rvec3 weight = rvec3(1.0);
  for (uint depth = 0u; depth <= frame.reflection_depth; depth++) {
    if (!budget_step()) break;
    hit_record h;
    if (!closest_hit(o, d, h)) {
      color += weight * rvec3(frame.background);
      break;
    }
    surface sf = surface_at(o, d, h);
    color += weight * shade_phong(sf, d);
    rvec3 mirror = rvec3(load_material(sf.material).mirror);
    if (depth == frame.reflection_depth || mirror == rvec3(0.0)) break;
    weight *= mirror;
    o = offset_ray_origin(sf.p, sf.n);
    d = normalize(reflect(d, sf.n));
    reflection_rays++;
  }
  return color;
}
