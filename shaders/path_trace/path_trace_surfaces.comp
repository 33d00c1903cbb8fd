#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// The path tracer (path_trace.glsl) with the denoiser's images: the first hit's albedo and emission,
// which trace_path hands over at the first vertex, are not carried through the path in registers:
// with ONE_SAMPLE they are stored to their images at once, otherwise kept in workgroup memory (80
// registers instead of 96 on an H100, and `classroom`'s path tracing at 1080p 6.15 ms instead of
// 6.74: bench/README.md). path_trace.comp is the same without the denoiser's images.
shared vec3 s_first_albedo[64];
shared vec3 s_first_emission[64];
#define PATH_KEEP_FIRST_ALBEDO(v) if (ONE_SAMPLE) { imageStore(u_albedo, ivec2(gl_GlobalInvocationID.xy), vec4((v), 1.0)); } else { s_first_albedo[gl_LocalInvocationIndex] = (v); }
#define PATH_KEEP_FIRST_EMISSION(v) if (ONE_SAMPLE) { imageStore(u_emission, ivec2(gl_GlobalInvocationID.xy), vec4((v), 1.0)); } else { s_first_emission[gl_LocalInvocationIndex] = (v); }
#define PATH_FIRST_ALBEDO s_first_albedo[gl_LocalInvocationIndex]
#define PATH_FIRST_EMISSION s_first_emission[gl_LocalInvocationIndex]
#include "path_trace/path_trace.glsl"
