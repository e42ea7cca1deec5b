/* layout_dump.c: prints the C side of every shared struct (rc_shared.h) in the form
 * `glsl.path offset`, `array stride N`, `Block size N`, `Block binding N`, for
 * tests/unit/test_layout.sh to compare with glslang's reflection of raycast.comp. */
#include <stdio.h>

#include "rc_shared.h"

#define OFF(path, type, member) printf("%s %zu\n", path, offsetof(type, member))

int main(void) {
  OFF("frame.camera.eye", gpu_frame, camera.eye);
  OFF("frame.camera.left", gpu_frame, camera.left);
  OFF("frame.camera.u", gpu_frame, camera.u);
  OFF("frame.camera.right", gpu_frame, camera.right);
  OFF("frame.camera.v", gpu_frame, camera.v);
  OFF("frame.camera.bottom", gpu_frame, camera.bottom);
  OFF("frame.camera.w", gpu_frame, camera.w);
  OFF("frame.camera.top", gpu_frame, camera.top);
  OFF("frame.camera.focal", gpu_frame, camera.focal);
  OFF("frame.camera.projection", gpu_frame, camera.projection);
  OFF("frame.camera.width", gpu_frame, camera.width);
  OFF("frame.camera.height", gpu_frame, camera.height);
  OFF("frame.background", gpu_frame, background);
  OFF("frame.specular_model", gpu_frame, specular_model);
  OFF("frame.ambient_light", gpu_frame, ambient_light);
  OFF("frame.reflection_depth", gpu_frame, reflection_depth);
  OFF("frame.sphere_count", gpu_frame, sphere_count);
  OFF("frame.triangle_count", gpu_frame, triangle_count);
  OFF("frame.material_count", gpu_frame, material_count);
  OFF("frame.light_count", gpu_frame, light_count);
  OFF("frame.samples_per_pixel", gpu_frame, samples_per_pixel);
  OFF("frame.seed", gpu_frame, seed);
  OFF("frame.strata_x", gpu_frame, strata_x);
  OFF("frame.strata_y", gpu_frame, strata_y);
  OFF("frame.object_count", gpu_frame, object_count);
  OFF("frame.bvh_node_count", gpu_frame, bvh_node_count);
  OFF("frame.inv_strata_x", gpu_frame, inv_strata_x);
  OFF("frame.inv_strata_y", gpu_frame, inv_strata_y);
  OFF("frame.sphere_formula", gpu_frame, sphere_formula);
  OFF("frame.triangle_formula", gpu_frame, triangle_formula);
  OFF("frame.offset_strategy", gpu_frame, offset_strategy);
  OFF("frame.offset_epsilon", gpu_frame, offset_epsilon);
  OFF("frame.quadric_count", gpu_frame, quadric_count);
  OFF("frame.csg_count", gpu_frame, csg_count);
  OFF("frame.shadows", gpu_frame, shadows);
  OFF("frame.csg_max_steps", gpu_frame, csg_max_steps);
  OFF("frame.plane_count", gpu_frame, plane_count);
  OFF("frame.pad0", gpu_frame, pad0);
  OFF("frame.pad1", gpu_frame, pad1);
  OFF("frame.pad2", gpu_frame, pad2);
  printf("Frame size %zu\n", sizeof(gpu_frame));

  OFF("scene_bvh_nodes.lo", gpu_bvh_node, lo);
  OFF("scene_bvh_nodes.skip", gpu_bvh_node, skip);
  OFF("scene_bvh_nodes.hi", gpu_bvh_node, hi);
  OFF("scene_bvh_nodes.leaf", gpu_bvh_node, leaf);
  printf("scene_bvh_nodes stride %zu\n", sizeof(gpu_bvh_node));
  printf("scene_bvh_prims stride %zu\n", sizeof(uint32_t));
  OFF("scene_transforms.row0", gpu_transform, row0);
  OFF("scene_transforms.row1", gpu_transform, row1);
  OFF("scene_transforms.row2", gpu_transform, row2);
  printf("scene_transforms stride %zu\n", sizeof(gpu_transform));
  OFF("scene_normals.n0", gpu_vertex_normals, n0);
  OFF("scene_normals.pad0", gpu_vertex_normals, pad0);
  OFF("scene_normals.n1", gpu_vertex_normals, n1);
  OFF("scene_normals.pad1", gpu_vertex_normals, pad1);
  OFF("scene_normals.n2", gpu_vertex_normals, n2);
  OFF("scene_normals.pad2", gpu_vertex_normals, pad2);
  printf("scene_normals stride %zu\n", sizeof(gpu_vertex_normals));

  OFF("scene_spheres.center", gpu_sphere, center);
  OFF("scene_spheres.radius", gpu_sphere, radius);
  OFF("scene_spheres.material", gpu_sphere, material);
  OFF("scene_spheres.transform", gpu_sphere, transform);
  OFF("scene_spheres.pad1", gpu_sphere, pad1);
  OFF("scene_spheres.pad2", gpu_sphere, pad2);
  printf("scene_spheres stride %zu\n", sizeof(gpu_sphere));
  OFF("scene_triangles.v0", gpu_triangle, v0);
  OFF("scene_triangles.material", gpu_triangle, material);
  OFF("scene_triangles.v1", gpu_triangle, v1);
  OFF("scene_triangles.normals", gpu_triangle, normals);
  OFF("scene_triangles.v2", gpu_triangle, v2);
  OFF("scene_triangles.pad1", gpu_triangle, pad1);
  printf("scene_triangles stride %zu\n", sizeof(gpu_triangle));
  OFF("scene_materials.ambient", gpu_material, ambient);
  OFF("scene_materials.shininess", gpu_material, shininess);
  OFF("scene_materials.diffuse", gpu_material, diffuse);
  OFF("scene_materials.pad0", gpu_material, pad0);
  OFF("scene_materials.specular", gpu_material, specular);
  OFF("scene_materials.pad1", gpu_material, pad1);
  OFF("scene_materials.mirror", gpu_material, mirror);
  OFF("scene_materials.pad2", gpu_material, pad2);
  OFF("scene_materials.emission", gpu_material, emission);
  OFF("scene_materials.pad3", gpu_material, pad3);
  printf("scene_materials stride %zu\n", sizeof(gpu_material));
  OFF("scene_lights.position", gpu_light, position);
  OFF("scene_lights.type", gpu_light, type);
  OFF("scene_lights.intensity", gpu_light, intensity);
  OFF("scene_lights.pad0", gpu_light, pad0);
  OFF("scene_lights.attenuation", gpu_light, attenuation);
  OFF("scene_lights.pad1", gpu_light, pad1);
  printf("scene_lights stride %zu\n", sizeof(gpu_light));

  OFF("scene_quadrics.center", gpu_quadric, center);
  OFF("scene_quadrics.material", gpu_quadric, material);
  OFF("scene_quadrics.axis_x", gpu_quadric, axis_x);
  OFF("scene_quadrics.constant", gpu_quadric, constant);
  OFF("scene_quadrics.axis_y", gpu_quadric, axis_y);
  OFF("scene_quadrics.flags", gpu_quadric, flags);
  OFF("scene_quadrics.axis_z", gpu_quadric, axis_z);
  OFF("scene_quadrics.mesh_root", gpu_quadric, mesh_root);
  OFF("scene_quadrics.diag", gpu_quadric, diag);
  OFF("scene_quadrics.mesh_end", gpu_quadric, mesh_end);
  OFF("scene_quadrics.off", gpu_quadric, off);
  OFF("scene_quadrics.mesh_crossings", gpu_quadric, mesh_crossings);
  OFF("scene_quadrics.linear", gpu_quadric, linear);
  OFF("scene_quadrics.pad3", gpu_quadric, pad3);
  OFF("scene_quadrics.lo", gpu_quadric, lo);
  OFF("scene_quadrics.pad4", gpu_quadric, pad4);
  OFF("scene_quadrics.hi", gpu_quadric, hi);
  OFF("scene_quadrics.pad5", gpu_quadric, pad5);
  printf("scene_quadrics stride %zu\n", sizeof(gpu_quadric));
  OFF("scene_csg.lo", gpu_csg, lo);
  OFF("scene_csg.first", gpu_csg, first);
  OFF("scene_csg.hi", gpu_csg, hi);
  OFF("scene_csg.count", gpu_csg, count);
  printf("scene_csg stride %zu\n", sizeof(gpu_csg));
  printf("scene_csg_program stride %zu\n", sizeof(uint32_t));

  OFF("push.tile_x", gpu_push, tile_x);
  OFF("push.tile_y", gpu_push, tile_y);
  OFF("push.tile_width", gpu_push, tile_width);
  OFF("push.tile_height", gpu_push, tile_height);
  OFF("push.batch_samples", gpu_push, batch_samples);
  OFF("push.row_stride", gpu_push, row_stride);
  OFF("push.light_pass", gpu_push, light_pass);
  OFF("push.pad0", gpu_push, pad0);
  printf("Push size %zu\n", sizeof(gpu_push));
  OFF("status.exhausted_pixels", gpu_status, exhausted_pixels);
  OFF("status.incomplete_pixels", gpu_status, incomplete_pixels);
  OFF("status.shadow_rays", gpu_status, shadow_rays);
  OFF("status.reflection_rays", gpu_status, reflection_rays);
  OFF("status.exhausted_object", gpu_status, exhausted_object);
  OFF("status.exhausted_pixel", gpu_status, exhausted_pixel);
  OFF("status.crossing_object", gpu_status, crossing_object);
  OFF("status.crossing_pixel", gpu_status, crossing_pixel);
  printf("Status size %zu\n", sizeof(gpu_status));

  OFF("aov.hit", gpu_aov, hit);
  OFF("aov.object", gpu_aov, object);
  OFF("aov.t", gpu_aov, t);
  OFF("aov.shadow_bits", gpu_aov, shadow_bits);
  OFF("aov.normal", gpu_aov, normal);
  OFF("aov.pad0", gpu_aov, pad0);
  printf("aov stride %zu\n", sizeof(gpu_aov));

  printf("Frame binding %d\n", RC_BINDING_FRAME);
  printf("scene_spheres binding %d\n", RC_BINDING_SPHERES);
  printf("scene_triangles binding %d\n", RC_BINDING_TRIANGLES);
  printf("scene_materials binding %d\n", RC_BINDING_MATERIALS);
  printf("scene_lights binding %d\n", RC_BINDING_LIGHTS);
  printf("scene_bvh_nodes binding %d\n", RC_BINDING_BVH_NODES);
  printf("scene_bvh_prims binding %d\n", RC_BINDING_BVH_PRIMS);
  printf("scene_transforms binding %d\n", RC_BINDING_TRANSFORMS);
  printf("scene_normals binding %d\n", RC_BINDING_NORMALS);
  printf("scene_quadrics binding %d\n", RC_BINDING_QUADRICS);
  printf("scene_csg binding %d\n", RC_BINDING_CSG);
  printf("scene_csg_program binding %d\n", RC_BINDING_CSG_PROGRAM);
  printf("Accum binding %d\n", RC_BINDING_ACCUM);
  printf("Status binding %d\n", RC_BINDING_STATUS);
  printf("Aov binding %d\n", RC_BINDING_AOV);
  return 0;
}
