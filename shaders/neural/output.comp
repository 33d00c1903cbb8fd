#version 460
// The learned denoiser's output pass (output.glsl): the re-modulated radiance.
#include "neural/output.glsl"
