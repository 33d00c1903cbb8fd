// The per-pixel inputs of the learned denoiser ("record"): planar float channels, channel c of
// pixel p at c * width * height + p.y * width + p.x, in the order of RECORD_CHANNELS in
// training/model.py, then one more plane: the G-buffer's object id of the pixel (its low 24 bits,
// exact in a float, as the denoiser's surface history keeps it). `lucid dataset` reads these
// buffers back as they are.
#ifndef LUCID_NEURAL_RECORD_GLSL
#define LUCID_NEURAL_RECORD_GLSL

const uint RECORD_DEMODULATED = 0u;
const uint RECORD_ALBEDO = 3u;
const uint RECORD_EMISSION = 6u;
const uint RECORD_NORMAL = 9u;
const uint RECORD_ROUGHNESS = 12u;
const uint RECORD_DEPTH = 13u;
const uint RECORD_MOTION = 14u;
const uint RECORD_SIZE = 17u;
const uint RECORD_OBJECT = RECORD_SIZE;  // the plane after the channels
const uint OBJECT_BITS = 0xffffffu;

uint record_index(uint channel, ivec2 pixel, uvec2 size) {
    return channel * size.x * size.y + uint(pixel.y) * size.x + uint(pixel.x);
}

#endif
