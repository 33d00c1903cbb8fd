#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// The path tracer (path_trace.glsl) with the denoiser's images and more than one sample a pixel:
// the first hit's albedo and emission, which trace_path hands over at the first vertex, are kept
// in workgroup memory until the path ends, not carried through it in registers (80 registers
// instead of 96 on an H100, and `classroom`'s path tracing at 1080p 6.15 ms instead of 6.74:
// bench/README.md). path_trace.comp serves every other case.
shared vec3 s_first_albedo[64];
shared vec3 s_first_emission[64];
#define PATH_KEEP_FIRST_ALBEDO(v) s_first_albedo[gl_LocalInvocationIndex] = (v);
#define PATH_KEEP_FIRST_EMISSION(v) s_first_emission[gl_LocalInvocationIndex] = (v);
#define PATH_FIRST_ALBEDO s_first_albedo[gl_LocalInvocationIndex]
#define PATH_FIRST_EMISSION s_first_emission[gl_LocalInvocationIndex]
#include "path_trace/path_trace.glsl"
