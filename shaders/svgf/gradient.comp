#version 460
// Temporal gradients for A-SVGF, one per stratum: the light transport replayed last frame's path of
// pixel q at this stratum's picked pixel p (common/replay.glsl), in the current scene with last
// frame's camera and random numbers. The difference between p's radiance now and q's last frame is
// noise-free: zero where only the camera moved, the change in shading where lights or objects
// changed. Writes (new - old luminance, max(new, old)) per stratum, zero where nothing was replayed.
#include "common/rng.glsl"
#include "common/math.glsl"
#include "common/replay.glsl"
#include "svgf/common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D u_motion;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_radiance;
layout(set = 0, binding = 2, rgba32ui) uniform readonly uimage2D u_prev_surface;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D u_gradient;

layout(push_constant) uniform Push {
    ReplayParams replay; // as the light transport was given (stratum 0: nothing was replayed)
    uint frame;
} push;

void main() {
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(cell, imageSize(u_gradient)))) {
        return;
    }
    ivec2 size = imageSize(u_radiance);
    if (push.replay.stratum == 0u) {
        imageStore(u_gradient, cell, vec4(0.0));
        return;
    }
    ivec2 p = replay_pick(cell, push.replay.stratum, push.frame, size);
    ivec2 q = replay_source(p, imageLoad(u_motion, p).xy, push.replay, push.frame, size);
    if (q == NO_REPLAY) {
        imageStore(u_gradient, cell, vec4(0.0));
        return;
    }
    float old_luminance = svgf_unpack_surface(imageLoad(u_prev_surface, q)).radiance_luminance;
    float new_luminance = luminance(imageLoad(u_radiance, p).rgb);
    imageStore(u_gradient, cell, vec4(new_luminance - old_luminance, max(new_luminance, old_luminance), 0.0, 0.0));
}
