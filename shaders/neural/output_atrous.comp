#version 460
// The learned denoiser's output pass (output.glsl) for weights with a gated a-trous filter: the
// output's illumination and its gate, which atrous_step.comp and atrous_last.comp finish.
#define ATROUS_GATE
#include "neural/output.glsl"
