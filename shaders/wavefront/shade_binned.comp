#version 460
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// Wavefront path tracing's shade kernel over the material bins extend_binned fills
// (wavefront/shade.glsl).
#define BIN_BY_MATERIAL
#include "wavefront/shade.glsl"
