// rc_budget.glsl: the per-lane loop budget (host/gpu/gpu_plan.h). llvmpipe ends every loop
// after 65,535 iterations summed over one SIMD vector of lanes, silently (the budget is
// that cap's share of one lane: rc_gpu_loop_budget); so every loop here
// calls budget_step() once per iteration and breaks when it returns false (the BVH's box
// walk takes the same step inline and tests it in its loop condition, rc_bvh.glsl). Every loop
// means every loop: llvmpipe does not unroll even a two-iteration loop, and an uncounted
// one once let it cut samples silently (rc_bvh.glsl). The host sizes
// each dispatch so that the worst case stays under loop_budget (host/gpu/gpu_plan.c); if an
// invocation still runs out, its whole workgroup discards the batch (raycast.comp) and the
// pixels are counted in packed_status.exhausted_pixels.
uint budget_steps = 0u;
bool budget_exhausted = false;
// 1 + the object whose test the budget could not pay for (0: it ran out elsewhere): the
// host names it, with its line in the scene file, when it refuses the scene.
uint budget_blame = 0u;

// The steps of a whole loop of n iterations, taken before it starts (a BVH leaf's
// objects): one check instead of n, the same guarantee, since the loop runs only when all
// n fit.
bool budget_take(uint n) {
  budget_steps += n;
  if (budget_steps > loop_budget) budget_exhausted = true;
  return !budget_exhausted;
}

bool budget_step() { return budget_take(1u); }
