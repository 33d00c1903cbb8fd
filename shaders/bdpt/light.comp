#version 460
#extension GL_EXT_shader_atomic_float : require
// BDPT light pass, splatting light tracing with float atomicAdd (VK_EXT_shader_atomic_float).
#define SPLAT_FLOAT_ATOMICS
#include "bdpt/light_pass.glsl"
