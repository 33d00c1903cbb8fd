#version 460
// An a-trous step of the learned denoiser's gated filter before its last (atrous_step.glsl).
#include "neural/atrous_step.glsl"
