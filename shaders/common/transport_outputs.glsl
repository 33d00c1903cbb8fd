// Whether the light transport writes the images a denoiser reads besides the radiance (radiance
// demodulated by the first hit, that hit's albedo and emission; passes/src/transport.rs): off when
// no denoiser runs, so that a frame without one pays neither for the stores nor for the registers
// that carry the first hit's albedo and emission through the path.
#ifndef LUCID_TRANSPORT_OUTPUTS_GLSL
#define LUCID_TRANSPORT_OUTPUTS_GLSL

layout(constant_id = 109) const bool SURFACE_OUTPUTS = true;

#endif
