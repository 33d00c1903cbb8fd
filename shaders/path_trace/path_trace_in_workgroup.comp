#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// path_trace.comp for a scene small enough to walk in workgroup memory
// (common/workgroup_scene.glsl): the Cornell box's path tracer 10% faster on an H200, where the
// same workgroup memory declared in path_trace.comp, unused, would cost `classroom` 2.7%. In 16x8
// workgroups, so that each copy of the scene serves twice the pixels: 1.7% less again on the
// Cornell box, where 8x8, 32x8 and 16x16 lose (bench/README.md).
#define SCENE_IN_WORKGROUP
#define PATH_TRACE_WORKGROUP_WIDTH 16
#include "path_trace/first_hit_images.glsl"
