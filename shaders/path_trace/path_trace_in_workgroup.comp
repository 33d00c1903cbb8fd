#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// path_trace.comp for a scene small enough to walk in workgroup memory
// (common/workgroup_scene.glsl): the Cornell box's path tracer 10% faster on an H200, where the
// same workgroup memory declared in path_trace.comp, unused, would cost `classroom` 2.7%
// (bench/README.md).
#define SCENE_IN_WORKGROUP
#include "path_trace/first_hit_images.glsl"
