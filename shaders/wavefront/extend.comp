#version 460
// Wavefront path tracing's extend kernel (wavefront/extend.glsl).
#include "wavefront/extend.glsl"
