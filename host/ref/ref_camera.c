/* ref_camera.c: mirrors shaders/rc_camera.glsl. */
#include "ref/ref_real.h"
#include "ref/ref_shader.h"

void REF(camera_ray)(const ref_scene *sc, ref_vec2 raster, rvec3 *origin, rvec3 *dir) {
  const packed_camera *c = &sc->frame->camera;
  real us = (real)c->left + ((real)c->right - (real)c->left) * (real)raster.x / (real)c->width;
  real vs = (real)c->bottom + ((real)c->top - (real)c->bottom) * (real)raster.y / (real)c->height;
  if (c->projection == RC_PROJECTION_PERSPECTIVE) {
    *origin = rvec3_from(c->eye);
    *dir = RV(normalize)(RV(add)(RV(add)(RV(scale)(rvec3_from(c->w), -(real)c->focal), RV(scale)(rvec3_from(c->u), us)),
                                 RV(scale)(rvec3_from(c->v), vs)));
  } else {
    *origin = RV(add)(RV(add)(rvec3_from(c->eye), RV(scale)(rvec3_from(c->u), us)), RV(scale)(rvec3_from(c->v), vs));
    *dir = RV(neg)(rvec3_from(c->w));
  }
}
