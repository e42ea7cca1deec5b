// rc_camera.glsl: primary rays (docs/scene-format.md, `camera`). `raster` is the position in the image in
// pixels, x to the right and y up from the bottom edge (the pixel centre of column i, row
// j from the bottom is (i + 0.5, j + 0.5)). The basis u, v, w and the window l, r, b, t
// come from the host, computed in f64 (GPU trig carries 2^-11 absolute error). `precise`,
// as the intersection math is (numerics.md §1): unmarked, a driver may fuse these
// multiplies and adds (NVIDIA's compilers do), and the direction then leaves the CPU
// twin's, which a grazing ray's hit point amplifies (docs/porting.md, the H200's
// textured horizons).
void camera_ray(vec2 raster, out rvec3 origin, out rvec3 dir) {
  packed_camera c = frame.camera;
  precise real us = real(c.left) + (real(c.right) - real(c.left)) * real(raster.x) / real(c.width);
  precise real vs = real(c.bottom) + (real(c.top) - real(c.bottom)) * real(raster.y) / real(c.height);
  // Selects, not a branch: a branch whose condition depends on uniform values alone made
  // Mesa 22.3's lavapipe inline them and recompile the whole shader on every dispatch
  // (lvp_inline_uniforms.c; 5-9 ms a dispatch, docs/performance.md). The expressions keep
  // the CPU twin's order of operations.
  bool perspective = c.projection == RC_PROJECTION_PERSPECTIVE;
  precise rvec3 perspective_dir = normalize(-real(c.focal) * rvec3(c.w) + us * rvec3(c.u) + vs * rvec3(c.v));
  precise rvec3 parallel_origin = rvec3(c.eye) + us * rvec3(c.u) + vs * rvec3(c.v);
  origin = perspective ? rvec3(c.eye) : parallel_origin;
  dir = perspective ? perspective_dir : -rvec3(c.w);
}
