#version 460
// BDPT light pass for devices without float atomics: splats with a compare-and-swap loop.
#include "bdpt/light_pass.glsl"
