// Per-frame constants (written by the frame_constants pass each frame). Mirrors
// lucid_passes::frame_constants::FrameConstants.
#ifndef LUCID_FRAME_GLSL
#define LUCID_FRAME_GLSL

struct FrameConstants {
    Camera camera;
    Camera prev_camera;
    uvec4 frame;   // frame index, seed, samples per pixel, max path depth (Mitsuba's convention)
    uvec4 size;    // width, height, frames accumulated before this one, flags
    vec4 params;   // russian-roulette start depth, 0, 0, 0
};

layout(set = 0, binding = 12, std430) readonly buffer FramePayload { FrameConstants f; } b_frame;

#endif
