#version 460
// Temporal gradients for A-SVGF, one sample per stratum of `stratum` x `stratum` pixels. A pixel of
// the stratum, picked afresh each frame, is followed back along its motion vector to last frame's
// pixel q; q's path is re-traced in the current scene with last frame's camera and exactly the
// random numbers the path tracer drew for q last frame (its RNG is a pure function of pixel, frame
// index and seed). Comparing with the luminance the path tracer produced for q last frame gives a
// noise-free difference: zero where only the camera moved, the change in shading where lights or
// objects changed. Writes (new - old luminance, max(new, old)) per stratum.
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"
#include "svgf/common.glsl"
#include "common/path.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 16, rgba16f) uniform readonly image2D u_motion;
layout(set = 0, binding = 17, rgba32ui) uniform readonly uimage2D u_prev_surface;
layout(set = 0, binding = 18, rgba32f) uniform writeonly image2D u_gradient;

layout(push_constant) uniform Params {
    uint enabled;  // 0: write no gradient (history is only rejected by geometry)
    uint stratum;  // side of a stratum in pixels
} params;

void main() {
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(cell, imageSize(u_gradient)))) {
        return;
    }
    uvec2 size = b_frame.f.size.xy;
    uint frame = b_frame.f.frame.x;
    uint stratum = params.stratum;
    uint pick = pcg_hash(uint(cell.x) ^ pcg_hash(uint(cell.y) ^ pcg_hash(frame)));
    ivec2 pixel = min(cell * int(stratum) + ivec2(pick % stratum, (pick / stratum) % stratum), ivec2(size) - 1);
    ivec2 q = ivec2(floor(vec2(pixel) + imageLoad(u_motion, pixel).xy + 0.5));
    if (params.enabled == 0u || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(size)))) {
        imageStore(u_gradient, cell, vec4(0.0));
        return;
    }
    float old_luminance = svgf_unpack_surface(imageLoad(u_prev_surface, q)).radiance_luminance;
    uint rng = rng_init(uvec2(q), frame - 1u, b_frame.f.frame.y);
    uint spp = max(b_frame.f.frame.z, 1u);
    uint max_depth = b_frame.f.frame.w;
    uint rr_depth = uint(b_frame.f.params.x);
    float aspect = float(size.x) / float(size.y);
    vec3 sum = vec3(0.0);
    uint rays = 0u;
    for (uint i = 0u; i < spp; ++i) {
        vec2 ndc = film_ndc(vec2(q), rng_next2(rng), vec2(size));
        vec3 origin;
        vec3 dir;
        camera_ray(b_frame.f.prev_camera, ndc, aspect, rng_next2(rng), origin, dir);
        vec3 l = trace_path(origin, dir, rng, max_depth, rr_depth, rays).radiance;
        if (any(isnan(l)) || any(isinf(l))) {
            l = vec3(0.0);
        }
        sum += l;
    }
    float new_luminance = luminance(sum / float(spp));
    imageStore(u_gradient, cell, vec4(new_luminance - old_luminance, max(new_luminance, old_luminance), 0.0, 0.0));
}
