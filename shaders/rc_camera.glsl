// rc_camera.glsl: primary rays, DESIGN.md §1. `raster` is the position in the image in
// pixels, x to the right and y up from the bottom edge (the pixel centre of column i, row
// j from the bottom is (i + 0.5, j + 0.5)). The basis u, v, w and the window l, r, b, t
// come from the host, computed in f64 (GPU trig carries 2^-11 absolute error).
void camera_ray(vec2 raster, out rvec3 origin, out rvec3 dir) {
  gpu_camera c = frame.camera;
  real us = real(c.left) + (real(c.right) - real(c.left)) * real(raster.x) / real(c.width);
  real vs = real(c.bottom) + (real(c.top) - real(c.bottom)) * real(raster.y) / real(c.height);
  if (c.projection == RC_PROJECTION_PERSPECTIVE) {
    origin = rvec3(c.eye);
    dir = normalize(-real(c.focal) * rvec3(c.w) + us * rvec3(c.u) + vs * rvec3(c.v));
  } else {
    origin = rvec3(c.eye) + us * rvec3(c.u) + vs * rvec3(c.v);
    dir = -rvec3(c.w);
  }
}
