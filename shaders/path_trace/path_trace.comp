#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// The path tracer without the denoiser's images, or with them and one sample a pixel
// (first_hit_images.glsl), reading the scene's BVH from its buffers.
#include "path_trace/first_hit_images.glsl"
