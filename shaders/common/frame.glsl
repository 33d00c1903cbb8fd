// Per-frame constants (written by the frame_constants pass each frame). Mirrors
// lucid_passes::frame_constants::FrameConstants field by field (std430, 176 bytes).
#ifndef LUCID_FRAME_GLSL
#define LUCID_FRAME_GLSL

struct FrameConstants {
    Camera camera;
    Camera prev_camera;
    uint frame_index;        // advances every frame
    uint seed;               // of the per-pixel random numbers
    uint samples_per_pixel;  // at least 1 (validated where settings enter)
    uint max_depth;          // longest path, Mitsuba's convention
    uint width;
    uint height;
    uint accumulated;        // frames accumulated before this one
    uint rr_depth;           // depth from which Russian roulette may end paths
    uvec4 padding;           // zero
};

layout(set = 0, binding = 12, std430) readonly buffer FramePayload { FrameConstants f; } b_frame;

#endif
