/* ref_trace.c: mirrors shaders/rc_trace.glsl. */
#include "ref/ref_real.h"
#include "ref/ref_shader.h"

#if REF_F64
typedef ref_hit_d ref_hit;
typedef ref_surface_d ref_surface;
#else
typedef ref_hit_f ref_hit;
typedef ref_surface_f ref_surface;
#endif

rvec3 REF(trace_sample)(const ref_scene *sc, uint32_t px, uint32_t py, uint32_t s) {
  ref_vec2 offset = ref_sample_offset(sc, px, py, s);
  ref_vec2 raster = {(float)px + offset.x, (float)(sc->frame->camera.height - 1u - py) + offset.y};
  rvec3 o, d;
  REF(camera_ray)(sc, raster, &o, &d);
  rvec3 color = RV(make)(0, 0, 0);
  rvec3 weight = RV(make)(1, 1, 1);
  for (uint32_t depth = 0; depth <= sc->frame->reflection_depth; depth++) {
    ref_hit h;
    if (!REF(closest_hit)(sc, o, d, &h)) {
      color = RV(add)(color, RV(mul)(weight, rvec3_from(sc->frame->background)));
      break;
    }
    ref_surface sf = REF(surface_at)(sc, o, d, &h);
    color = RV(add)(color, RV(mul)(weight, REF(shade_phong)(sc, &sf, d)));
    rvec3 mirror = rvec3_from(sc->materials[sf.material].mirror);
    if (depth == sc->frame->reflection_depth || (mirror.x == 0 && mirror.y == 0 && mirror.z == 0)) break;
    weight = RV(mul)(weight, mirror);
    o = REF(offset_ray_origin)(sf.p, sf.n);
    d = RV(normalize)(RV(reflect)(d, sf.n));
    ref_reflection_rays++;
  }
  return color;
}
