#version 460
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// Wavefront path tracing's extend kernel, binning the hits by material (wavefront/extend.glsl).
#define BIN_BY_MATERIAL
#include "wavefront/extend.glsl"
