/* layout_dump.c: prints the C side of every shared struct (rc_shared.h) in the form
 * `glsl.path offset`, `array stride N`, `Block size N`, `Block binding N`, for
 * tests/unit/test_layout.sh to compare with glslang's reflection of raycast.comp. */
#include <stdio.h>

#include "rc_shared.h"

#define OFF(path, type, member) printf("%s %zu\n", path, offsetof(type, member))

int main(void) {
  OFF("frame.camera.eye", packed_frame, camera.eye);
  OFF("frame.camera.left", packed_frame, camera.left);
  OFF("frame.camera.u", packed_frame, camera.u);
  OFF("frame.camera.right", packed_frame, camera.right);
  OFF("frame.camera.v", packed_frame, camera.v);
  OFF("frame.camera.bottom", packed_frame, camera.bottom);
  OFF("frame.camera.w", packed_frame, camera.w);
  OFF("frame.camera.top", packed_frame, camera.top);
  OFF("frame.camera.focal", packed_frame, camera.focal);
  OFF("frame.camera.projection", packed_frame, camera.projection);
  OFF("frame.camera.width", packed_frame, camera.width);
  OFF("frame.camera.height", packed_frame, camera.height);
  OFF("frame.background", packed_frame, background);
  OFF("frame.specular_model", packed_frame, specular_model);
  OFF("frame.ambient_light", packed_frame, ambient_light);
  OFF("frame.reflection_depth", packed_frame, reflection_depth);
  OFF("frame.sphere_count", packed_frame, sphere_count);
  OFF("frame.triangle_count", packed_frame, triangle_count);
  OFF("frame.material_count", packed_frame, material_count);
  OFF("frame.light_count", packed_frame, light_count);
  OFF("frame.samples_per_pixel", packed_frame, samples_per_pixel);
  OFF("frame.seed", packed_frame, seed);
  OFF("frame.strata_x", packed_frame, strata_x);
  OFF("frame.strata_y", packed_frame, strata_y);
  OFF("frame.object_count", packed_frame, object_count);
  OFF("frame.bvh_node_count", packed_frame, bvh_node_count);
  OFF("frame.inv_strata_x", packed_frame, inv_strata_x);
  OFF("frame.inv_strata_y", packed_frame, inv_strata_y);
  OFF("frame.sphere_formula", packed_frame, sphere_formula);
  OFF("frame.triangle_formula", packed_frame, triangle_formula);
  OFF("frame.offset_strategy", packed_frame, offset_strategy);
  OFF("frame.offset_epsilon", packed_frame, offset_epsilon);
  OFF("frame.quadric_count", packed_frame, quadric_count);
  OFF("frame.csg_count", packed_frame, csg_count);
  OFF("frame.shadows", packed_frame, shadows);
  OFF("frame.csg_max_steps", packed_frame, csg_max_steps);
  OFF("frame.plane_count", packed_frame, plane_count);
  OFF("frame.patch_count", packed_frame, patch_count);
  OFF("frame.light_buffers", packed_frame, light_buffers);
  OFF("frame.certify", packed_frame, certify);
  printf("Frame size %zu\n", sizeof(packed_frame));

  OFF("scene_bvh_nodes.lo", packed_bvh_node, lo);
  OFF("scene_bvh_nodes.skip", packed_bvh_node, skip);
  OFF("scene_bvh_nodes.hi", packed_bvh_node, hi);
  OFF("scene_bvh_nodes.leaf", packed_bvh_node, leaf);
  printf("scene_bvh_nodes stride %zu\n", sizeof(packed_bvh_node));
  printf("scene_bvh_prims stride %zu\n", sizeof(uint32_t));
  OFF("scene_transforms.row0", packed_transform, row0);
  OFF("scene_transforms.row1", packed_transform, row1);
  OFF("scene_transforms.row2", packed_transform, row2);
  printf("scene_transforms stride %zu\n", sizeof(packed_transform));
  OFF("scene_normals.n0", packed_vertex_normals, n0);
  OFF("scene_normals.pad0", packed_vertex_normals, pad0);
  OFF("scene_normals.n1", packed_vertex_normals, n1);
  OFF("scene_normals.pad1", packed_vertex_normals, pad1);
  OFF("scene_normals.n2", packed_vertex_normals, n2);
  OFF("scene_normals.pad2", packed_vertex_normals, pad2);
  printf("scene_normals stride %zu\n", sizeof(packed_vertex_normals));

  OFF("scene_spheres.center", packed_sphere, center);
  OFF("scene_spheres.radius", packed_sphere, radius);
  OFF("scene_spheres.material", packed_sphere, material);
  OFF("scene_spheres.transform", packed_sphere, transform);
  OFF("scene_spheres.pad1", packed_sphere, pad1);
  OFF("scene_spheres.pad2", packed_sphere, pad2);
  printf("scene_spheres stride %zu\n", sizeof(packed_sphere));
  OFF("scene_triangles.v0", packed_triangle, v0);
  OFF("scene_triangles.material", packed_triangle, material);
  OFF("scene_triangles.v1", packed_triangle, v1);
  OFF("scene_triangles.normals", packed_triangle, normals);
  OFF("scene_triangles.v2", packed_triangle, v2);
  OFF("scene_triangles.flags", packed_triangle, flags);
  printf("scene_triangles stride %zu\n", sizeof(packed_triangle));
  OFF("scene_materials.ambient", packed_material, ambient);
  OFF("scene_materials.shininess", packed_material, shininess);
  OFF("scene_materials.diffuse", packed_material, diffuse);
  OFF("scene_materials.texture", packed_material, texture);
  OFF("scene_materials.specular", packed_material, specular);
  OFF("scene_materials.pad1", packed_material, pad1);
  OFF("scene_materials.mirror", packed_material, mirror);
  OFF("scene_materials.pad2", packed_material, pad2);
  OFF("scene_materials.emission", packed_material, emission);
  OFF("scene_materials.pad3", packed_material, pad3);
  printf("scene_materials stride %zu\n", sizeof(packed_material));
  OFF("scene_lights.position", packed_light, position);
  OFF("scene_lights.type", packed_light, type);
  OFF("scene_lights.intensity", packed_light, intensity);
  OFF("scene_lights.pad0", packed_light, pad0);
  OFF("scene_lights.attenuation", packed_light, attenuation);
  OFF("scene_lights.pad1", packed_light, pad1);
  printf("scene_lights stride %zu\n", sizeof(packed_light));

  OFF("scene_quadrics.center", packed_quadric, center);
  OFF("scene_quadrics.material", packed_quadric, material);
  OFF("scene_quadrics.axis_x", packed_quadric, axis_x);
  OFF("scene_quadrics.constant", packed_quadric, constant);
  OFF("scene_quadrics.axis_y", packed_quadric, axis_y);
  OFF("scene_quadrics.flags", packed_quadric, flags);
  OFF("scene_quadrics.axis_z", packed_quadric, axis_z);
  OFF("scene_quadrics.mesh_root", packed_quadric, mesh_root);
  OFF("scene_quadrics.diag", packed_quadric, diag);
  OFF("scene_quadrics.mesh_end", packed_quadric, mesh_end);
  OFF("scene_quadrics.off", packed_quadric, off);
  OFF("scene_quadrics.mesh_crossings", packed_quadric, mesh_crossings);
  OFF("scene_quadrics.linear", packed_quadric, linear);
  OFF("scene_quadrics.pad3", packed_quadric, pad3);
  OFF("scene_quadrics.lo", packed_quadric, lo);
  OFF("scene_quadrics.pad4", packed_quadric, pad4);
  OFF("scene_quadrics.hi", packed_quadric, hi);
  OFF("scene_quadrics.pad5", packed_quadric, pad5);
  printf("scene_quadrics stride %zu\n", sizeof(packed_quadric));
  OFF("scene_csg.lo", packed_csg, lo);
  OFF("scene_csg.first", packed_csg, first);
  OFF("scene_csg.hi", packed_csg, hi);
  OFF("scene_csg.count", packed_csg, count);
  printf("scene_csg stride %zu\n", sizeof(packed_csg));
  printf("scene_csg_program stride %zu\n", sizeof(uint32_t));

  OFF("push.tile_x", packed_push, tile_x);
  OFF("push.tile_y", packed_push, tile_y);
  OFF("push.tile_width", packed_push, tile_width);
  OFF("push.tile_height", packed_push, tile_height);
  OFF("push.batch_samples", packed_push, batch_samples);
  OFF("push.row_stride", packed_push, row_stride);
  OFF("push.light_pass", packed_push, light_pass);
  OFF("push.masked", packed_push, masked);
  printf("Push size %zu\n", sizeof(packed_push));
  OFF("status.exhausted_pixels", packed_status, exhausted_pixels);
  OFF("status.incomplete_pixels", packed_status, incomplete_pixels);
  OFF("status.shadow_rays", packed_status, shadow_rays);
  OFF("status.reflection_rays", packed_status, reflection_rays);
  OFF("status.exhausted_object", packed_status, exhausted_object);
  OFF("status.exhausted_pixel", packed_status, exhausted_pixel);
  OFF("status.crossing_object", packed_status, crossing_object);
  OFF("status.crossing_pixel", packed_status, crossing_pixel);
  OFF("status.patch_unconverged", packed_status, patch_unconverged);
  OFF("status.patch_unconverged_object", packed_status, patch_unconverged_object);
  OFF("status.patch_unconverged_pixel", packed_status, patch_unconverged_pixel);
  OFF("status.max_steps", packed_status, max_steps);
  printf("Status size %zu\n", sizeof(packed_status));

  OFF("level_table.value_scale", packed_levels, value_scale);
  OFF("level_table.inv_gamma", packed_levels, inv_gamma);
  OFF("level_table.bias", packed_levels, bias);
  OFF("level_table.pad0", packed_levels, pad0);
  OFF("level_table.sum_threshold", packed_levels, sum_threshold);
  printf("levels offset %zu\n", sizeof(packed_levels));

  OFF("aov.hit", packed_aov, hit);
  OFF("aov.object", packed_aov, object);
  OFF("aov.t", packed_aov, t);
  OFF("aov.shadow_bits", packed_aov, shadow_bits);
  OFF("aov.normal", packed_aov, normal);
  OFF("aov.uncertified", packed_aov, uncertified);
  OFF("aov.certified_sum", packed_aov, certified_sum);
  OFF("aov.uncertified_mask", packed_aov, uncertified_mask);
  printf("aov stride %zu\n", sizeof(packed_aov));

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
  printf("scene_texels binding %d\n", RC_BINDING_TEXELS);
  printf("Accum binding %d\n", RC_BINDING_ACCUM);
  printf("Status binding %d\n", RC_BINDING_STATUS);
  printf("Levels binding %d\n", RC_BINDING_AOV);
  printf("Aov binding %d\n", RC_BINDING_AOV);
  return 0;
}
