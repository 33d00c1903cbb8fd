#version 460
// The last a-trous step of the learned denoiser's gated filter (atrous_step.glsl): the blend by the
// gate and the re-modulation too.
#define ATROUS_LAST
#include "neural/atrous_step.glsl"
