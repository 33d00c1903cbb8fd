#version 460
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// Wavefront path tracing's shade kernel (wavefront/shade.glsl).
#include "wavefront/shade.glsl"
