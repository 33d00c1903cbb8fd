#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// The path tracer (path_trace.glsl) without the denoiser's images: the first hit's albedo and
// emission are not kept. path_trace_surfaces.comp is the same with them.
#define PATH_KEEP_FIRST_ALBEDO(v)
#define PATH_KEEP_FIRST_EMISSION(v)
#define PATH_FIRST_ALBEDO vec3(1.0)
#define PATH_FIRST_EMISSION vec3(0.0)
#include "path_trace/path_trace.glsl"
