// rc_real.glsl: the working precision of the geometry and shading math. The f32 module
// is the default; RC_F64 builds the double-precision module (needs shaderFloat64). The
// scene arrays stay f32 either way; loads widen them.
#if RC_F64
#define real double
#define rvec2 dvec2
#define rvec3 dvec3
#else
#define real float
#define rvec2 vec2
#define rvec3 vec3
#endif
