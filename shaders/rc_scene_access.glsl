// rc_scene_access.glsl: how the shader reads the scene arrays. Three kinds, one interface:
// RGBA32UI storage texel buffers read with imageLoad (RC_SCENE_TEXEL_IMAGES=1), RGBA32UI
// uniform texel buffers read with texelFetch (RC_SCENE_TEXEL_BUFFERS=1), or std430 storage
// buffers. On Mesa 22 llvmpipe a storage-buffer load inside a loop becomes a per-lane scalar
// loop while both texel kinds stay vectorised, and a texelFetch from an RGBA32UI buffer is
// an out-of-line call where an imageLoad is inline code, 5-8 % faster a frame
// (docs/performance.md, finding 9); on discrete GPUs all three are fast. Texels hold raw
// bits, so integers and floats travel unchanged (a float view could flush the denormal bit
// patterns of small integers).
#ifndef RC_SCENE_TEXEL_IMAGES
#define RC_SCENE_TEXEL_IMAGES 0
#endif
#if RC_SCENE_TEXEL_BUFFERS
#if RC_SCENE_TEXEL_IMAGES
layout(binding = RC_BINDING_SPHERES, rgba32ui) readonly uniform uimageBuffer scene_spheres;
layout(binding = RC_BINDING_TRIANGLES, rgba32ui) readonly uniform uimageBuffer scene_triangles;
layout(binding = RC_BINDING_MATERIALS, rgba32ui) readonly uniform uimageBuffer scene_materials;
layout(binding = RC_BINDING_LIGHTS, rgba32ui) readonly uniform uimageBuffer scene_lights;
layout(binding = RC_BINDING_BVH_NODES, rgba32ui) readonly uniform uimageBuffer scene_bvh_nodes;
layout(binding = RC_BINDING_BVH_PRIMS, rgba32ui) readonly uniform uimageBuffer scene_bvh_prims;
layout(binding = RC_BINDING_TRANSFORMS, rgba32ui) readonly uniform uimageBuffer scene_transforms;
layout(binding = RC_BINDING_NORMALS, rgba32ui) readonly uniform uimageBuffer scene_normals;
layout(binding = RC_BINDING_QUADRICS, rgba32ui) readonly uniform uimageBuffer scene_quadrics;
layout(binding = RC_BINDING_CSG, rgba32ui) readonly uniform uimageBuffer scene_csg;
layout(binding = RC_BINDING_CSG_PROGRAM, rgba32ui) readonly uniform uimageBuffer scene_csg_program;
layout(binding = RC_BINDING_TEXELS, rgba32ui) readonly uniform uimageBuffer scene_texels;

#define texel(b, i) imageLoad(b, int(i))
#else
layout(binding = RC_BINDING_SPHERES) uniform usamplerBuffer scene_spheres;
layout(binding = RC_BINDING_TRIANGLES) uniform usamplerBuffer scene_triangles;
layout(binding = RC_BINDING_MATERIALS) uniform usamplerBuffer scene_materials;
layout(binding = RC_BINDING_LIGHTS) uniform usamplerBuffer scene_lights;
layout(binding = RC_BINDING_BVH_NODES) uniform usamplerBuffer scene_bvh_nodes;
layout(binding = RC_BINDING_BVH_PRIMS) uniform usamplerBuffer scene_bvh_prims;
layout(binding = RC_BINDING_TRANSFORMS) uniform usamplerBuffer scene_transforms;
layout(binding = RC_BINDING_NORMALS) uniform usamplerBuffer scene_normals;
layout(binding = RC_BINDING_QUADRICS) uniform usamplerBuffer scene_quadrics;
layout(binding = RC_BINDING_CSG) uniform usamplerBuffer scene_csg;
layout(binding = RC_BINDING_CSG_PROGRAM) uniform usamplerBuffer scene_csg_program;
layout(binding = RC_BINDING_TEXELS) uniform usamplerBuffer scene_texels;

uvec4 texel(usamplerBuffer b, uint i) { return texelFetch(b, int(i)); }
#endif

packed_sphere load_sphere(uint i) {
  uvec4 a = texel(scene_spheres, i * RC_TEXELS_PER_SPHERE);
  uvec4 b = texel(scene_spheres, i * RC_TEXELS_PER_SPHERE + 1u);
  packed_sphere s;
  s.center = uintBitsToFloat(a.xyz);
  s.radius = uintBitsToFloat(a.w);
  s.material = b.x;
  s.transform = b.y;
  return s;
}

packed_transform load_transform(uint i) {
  packed_transform m;
  m.row0 = uintBitsToFloat(texel(scene_transforms, i * RC_TEXELS_PER_TRANSFORM));
  m.row1 = uintBitsToFloat(texel(scene_transforms, i * RC_TEXELS_PER_TRANSFORM + 1u));
  m.row2 = uintBitsToFloat(texel(scene_transforms, i * RC_TEXELS_PER_TRANSFORM + 2u));
  return m;
}

packed_triangle load_triangle(uint i) {
  uvec4 a = texel(scene_triangles, i * RC_TEXELS_PER_TRIANGLE);
  uvec4 b = texel(scene_triangles, i * RC_TEXELS_PER_TRIANGLE + 1u);
  uvec4 c = texel(scene_triangles, i * RC_TEXELS_PER_TRIANGLE + 2u);
  packed_triangle t;
  t.v0 = uintBitsToFloat(a.xyz);
  t.material = a.w;
  t.v1 = uintBitsToFloat(b.xyz);
  t.normals = b.w;
  t.v2 = uintBitsToFloat(c.xyz);
  t.flags = c.w;
  return t;
}

// Vertex k of triangle i alone: one texel, where a certificate compares two vertices.
vec3 load_triangle_vertex(uint i, uint k) { return uintBitsToFloat(texel(scene_triangles, i * RC_TEXELS_PER_TRIANGLE + k).xyz); }

packed_vertex_normals load_vertex_normals(uint i) {
  packed_vertex_normals n;
  n.n0 = uintBitsToFloat(texel(scene_normals, i * RC_TEXELS_PER_VERTEX_NORMALS).xyz);
  n.n1 = uintBitsToFloat(texel(scene_normals, i * RC_TEXELS_PER_VERTEX_NORMALS + 1u).xyz);
  n.n2 = uintBitsToFloat(texel(scene_normals, i * RC_TEXELS_PER_VERTEX_NORMALS + 2u).xyz);
  return n;
}

packed_material load_material(uint i) {
  uvec4 a = texel(scene_materials, i * RC_TEXELS_PER_MATERIAL);
  uvec4 b = texel(scene_materials, i * RC_TEXELS_PER_MATERIAL + 1u);
  uvec4 c = texel(scene_materials, i * RC_TEXELS_PER_MATERIAL + 2u);
  uvec4 d = texel(scene_materials, i * RC_TEXELS_PER_MATERIAL + 3u);
  uvec4 e = texel(scene_materials, i * RC_TEXELS_PER_MATERIAL + 4u);
  packed_material m;
  m.ambient = uintBitsToFloat(a.xyz);
  m.shininess = uintBitsToFloat(a.w);
  m.diffuse = uintBitsToFloat(b.xyz);
  m.texture = b.w;
  m.specular = uintBitsToFloat(c.xyz);
  m.mirror = uintBitsToFloat(d.xyz);
  m.emission = uintBitsToFloat(e.xyz);
  return m;
}

packed_bvh_node load_bvh_node(uint i) {
  uvec4 a = texel(scene_bvh_nodes, i * RC_TEXELS_PER_BVH_NODE);
  uvec4 b = texel(scene_bvh_nodes, i * RC_TEXELS_PER_BVH_NODE + 1u);
  packed_bvh_node n;
  n.lo = uintBitsToFloat(a.xyz);
  n.skip = a.w;
  n.hi = uintBitsToFloat(b.xyz);
  n.leaf = b.w;
  return n;
}

uint load_bvh_prim(uint i) { return texel(scene_bvh_prims, i >> 2u)[i & 3u]; }
// Entries i and i + 1 of the reference array, i even (one texel: the light buffers' pairs).
uvec2 load_bvh_prim_pair(uint i) {
  uvec4 t = texel(scene_bvh_prims, i >> 2u);
  return (i & 2u) != 0u ? t.zw : t.xy;
}

packed_quadric load_quadric(uint i) {
  uint k = i * RC_TEXELS_PER_QUADRIC;
  uvec4 a = texel(scene_quadrics, k);
  uvec4 b = texel(scene_quadrics, k + 1u);
  uvec4 c = texel(scene_quadrics, k + 2u);
  packed_quadric q;
  q.center = uintBitsToFloat(a.xyz);
  q.material = a.w;
  q.axis_x = uintBitsToFloat(b.xyz);
  q.constant = uintBitsToFloat(b.w);
  q.axis_y = uintBitsToFloat(c.xyz);
  q.flags = c.w;
  uvec4 z = texel(scene_quadrics, k + 3u);
  uvec4 m = texel(scene_quadrics, k + 4u);
  uvec4 f = texel(scene_quadrics, k + 5u);
  q.axis_z = uintBitsToFloat(z.xyz);
  q.mesh_root = z.w;
  q.diag = uintBitsToFloat(m.xyz);
  q.mesh_end = m.w;
  q.off = uintBitsToFloat(f.xyz);
  q.mesh_crossings = f.w;
  q.linear = uintBitsToFloat(texel(scene_quadrics, k + 6u).xyz);
  q.lo = uintBitsToFloat(texel(scene_quadrics, k + 7u).xyz);
  q.hi = uintBitsToFloat(texel(scene_quadrics, k + 8u).xyz);
  return q;
}

packed_csg load_csg(uint i) {
  uvec4 a = texel(scene_csg, i * RC_TEXELS_PER_CSG);
  uvec4 b = texel(scene_csg, i * RC_TEXELS_PER_CSG + 1u);
  packed_csg c;
  c.lo = uintBitsToFloat(a.xyz);
  c.first = a.w;
  c.hi = uintBitsToFloat(b.xyz);
  c.count = b.w;
  return c;
}

uint load_csg_instruction(uint i) { return texel(scene_csg_program, i >> 2u)[i & 3u]; }

packed_texture load_texture(uint first) {
  uvec4 a = texel(scene_texels, first);
  uvec4 b = texel(scene_texels, first + 1u);
  packed_texture t;
  t.width = a.x;
  t.height = a.y;
  t.flags = a.z;
  t.texels = a.w;
  t.scale_u = uintBitsToFloat(b.x);
  t.scale_v = uintBitsToFloat(b.y);
  t.offset_u = uintBitsToFloat(b.z);
  t.offset_v = uintBitsToFloat(b.w);
  return t;
}

vec3 load_texel_rgb(uint i) { return uintBitsToFloat(texel(scene_texels, i).xyz); }
// The first texel of mip level `level` of the texture at `first` (its header's table).
uint load_texture_level(uint first, uint level) { return texel(scene_texels, first + 2u + (level >> 2u))[level & 3u]; }
// A patch's control point (RC_QUADRIC_PATCH): texel i of the texel array.
vec3 load_patch_point(uint i) { return uintBitsToFloat(texel(scene_texels, i).xyz); }

// The packed_vertex_uvs at texel `first` of the texel array.
packed_vertex_uvs load_vertex_uvs(uint first) {
  vec4 a = uintBitsToFloat(texel(scene_texels, first));
  vec4 b = uintBitsToFloat(texel(scene_texels, first + 1u));
  return packed_vertex_uvs(a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w);
}

packed_light load_light(uint i) {
  uvec4 a = texel(scene_lights, i * RC_TEXELS_PER_LIGHT);
  uvec4 b = texel(scene_lights, i * RC_TEXELS_PER_LIGHT + 1u);
  uvec4 c = texel(scene_lights, i * RC_TEXELS_PER_LIGHT + 2u);
  packed_light l;
  l.position = uintBitsToFloat(a.xyz);
  l.type = a.w;
  l.intensity = uintBitsToFloat(b.xyz);
  l.attenuation = uintBitsToFloat(c.xyz);
  return l;
}
#else
layout(std430, binding = RC_BINDING_SPHERES) readonly buffer Spheres { packed_sphere scene_spheres[]; };
layout(std430, binding = RC_BINDING_TRIANGLES) readonly buffer Triangles { packed_triangle scene_triangles[]; };
layout(std430, binding = RC_BINDING_MATERIALS) readonly buffer Materials { packed_material scene_materials[]; };
layout(std430, binding = RC_BINDING_LIGHTS) readonly buffer Lights { packed_light scene_lights[]; };
layout(std430, binding = RC_BINDING_BVH_NODES) readonly buffer BvhNodes { packed_bvh_node scene_bvh_nodes[]; };
layout(std430, binding = RC_BINDING_BVH_PRIMS) readonly buffer BvhPrims { uint scene_bvh_prims[]; };
layout(std430, binding = RC_BINDING_TRANSFORMS) readonly buffer Transforms { packed_transform scene_transforms[]; };
layout(std430, binding = RC_BINDING_NORMALS) readonly buffer Normals { packed_vertex_normals scene_normals[]; };
layout(std430, binding = RC_BINDING_QUADRICS) readonly buffer Quadrics { packed_quadric scene_quadrics[]; };
layout(std430, binding = RC_BINDING_CSG) readonly buffer Csg { packed_csg scene_csg[]; };
layout(std430, binding = RC_BINDING_CSG_PROGRAM) readonly buffer CsgProgram { uint scene_csg_program[]; };
layout(std430, binding = RC_BINDING_TEXELS) readonly buffer Texels { uvec4 scene_texels[]; };

packed_sphere load_sphere(uint i) { return scene_spheres[i]; }
packed_triangle load_triangle(uint i) { return scene_triangles[i]; }
vec3 load_triangle_vertex(uint i, uint k) {
  return (k == 0u) ? scene_triangles[i].v0 : ((k == 1u) ? scene_triangles[i].v1 : scene_triangles[i].v2);
}
packed_material load_material(uint i) { return scene_materials[i]; }
packed_light load_light(uint i) { return scene_lights[i]; }
packed_bvh_node load_bvh_node(uint i) { return scene_bvh_nodes[i]; }
uint load_bvh_prim(uint i) { return scene_bvh_prims[i]; }
uvec2 load_bvh_prim_pair(uint i) { return uvec2(scene_bvh_prims[i], scene_bvh_prims[i + 1u]); }
packed_transform load_transform(uint i) { return scene_transforms[i]; }
packed_vertex_normals load_vertex_normals(uint i) { return scene_normals[i]; }
packed_quadric load_quadric(uint i) { return scene_quadrics[i]; }
packed_csg load_csg(uint i) { return scene_csg[i]; }
uint load_csg_instruction(uint i) { return scene_csg_program[i]; }
packed_texture load_texture(uint first) {
  uvec4 a = scene_texels[first];
  uvec4 b = scene_texels[first + 1u];
  return packed_texture(a.x, a.y, a.z, a.w, uintBitsToFloat(b.x), uintBitsToFloat(b.y), uintBitsToFloat(b.z),
                        uintBitsToFloat(b.w));
}
vec3 load_texel_rgb(uint i) { return uintBitsToFloat(scene_texels[i].xyz); }
uint load_texture_level(uint first, uint level) { return scene_texels[first + 2u + (level >> 2u)][level & 3u]; }
vec3 load_patch_point(uint i) { return uintBitsToFloat(scene_texels[i].xyz); }
packed_vertex_uvs load_vertex_uvs(uint first) {
  vec4 a = uintBitsToFloat(scene_texels[first]);
  vec4 b = uintBitsToFloat(scene_texels[first + 1u]);
  return packed_vertex_uvs(a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w);
}
#endif
