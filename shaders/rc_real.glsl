// rc_real.glsl: the working precision of the geometry and shading math. The f32 module
// is the default; RC_F64 builds the double-precision module (needs shaderFloat64). The
// scene arrays stay f32 either way; loads widen them.
// RC_UNIT_ROUNDOFF is u of the working precision (pbrt's gamma(n) = n u / (1 - n u));
// RC_SMALLEST_NORMAL stands in for "the next float above 0", as GPUs may flush subnormals.
// RL(x): the literal x rounded to f32, in the working precision: the same value in the
// shader (where a literal without LF is a float) and in the reference (ref_real.h).
#define RL(x) real(x)
#if RC_F64
#define real double
#define rvec2 dvec2
#define rvec3 dvec3
#define rvec4 dvec4
#define RC_UNIT_ROUNDOFF 1.1102230246251565e-16LF
#define RC_SMALLEST_NORMAL 2.2250738585072014e-308LF
#else
#define real float
#define rvec2 vec2
#define rvec3 vec3
#define rvec4 vec4
#define RC_UNIT_ROUNDOFF 5.9604644775390625e-8
#define RC_SMALLEST_NORMAL 1.17549435e-38
#endif

// min and max as the selects `a < b ? a : b` and `a > b ? a : b`, host/ref/ref_real.h's rmin
// and rmax, for operands that are never NaN (slab distances, root pairs, error bounds).
// GLSL's min() and max() must return the other operand when one is NaN, and llvmpipe pays
// a NaN compare and a masked move for each (finding 11, docs/performance.md).
real select_min(real a, real b) { return a < b ? a : b; }
real select_max(real a, real b) { return a > b ? a : b; }
