#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// Continues the paths the path tracer parked after PARK_DEPTH segments (path_trace/long_paths.glsl),
// one invocation each over long_paths_list.comp's list, and adds what they bring to their pixels'
// radiance (one sample a pixel, so each pixel has at most one); with SURFACE_OUTPUTS the pixel's
// demodulated radiance is computed again from the new radiance and the first hit's albedo and
// emission the path tracer wrote. A non-finite continuation is dropped and counted in b_stats, as
// are the rays traced.
#define PATH_KEEP_FIRST_ALBEDO(v)
#define PATH_KEEP_FIRST_EMISSION(v)
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"
#include "common/transport_outputs.glsl"

layout(local_size_x = 64) in;

#define LONG_PATHS_CONTINUE
#include "path_trace/long_paths.glsl"
#include "common/path.glsl"

layout(set = 0, binding = 16, rgba32f) uniform image2D u_radiance;
layout(set = 0, binding = 17, rgba32f) uniform writeonly image2D u_demodulated;
layout(set = 0, binding = 18, rgba32f) uniform readonly image2D u_albedo;
layout(set = 0, binding = 19, rgba32f) uniform readonly image2D u_emission;
layout(set = 0, binding = 20, std430) buffer Stats { uint non_finite; uint rays; uint cut_short; uint pad1; } b_stats;
layout(set = 0, binding = 24, std430) readonly buffer ParkedList { uint q[]; } b_parked_list;
layout(set = 0, binding = 25, std430) readonly buffer ParkedCount { uint n; } b_parked_count;

void main() {
    uint index = gl_GlobalInvocationID.x;
    uint rays = 0u;
    if (index < b_parked_count.n) {
        uint pixel_index = b_parked_list.q[index];
        ParkedPath t = b_parked.p[pixel_index];
        uint rng = t.rng;
        vec3 rest = trace_path_from(PARK_DEPTH, t.o, t.d, t.beta, t.prev_pdf, t.prev_delta != 0u, t.prev_p, rng,
                                    b_frame.f.max_depth, b_frame.f.rr_depth, 0.0, rays);
        if (!(any(isnan(rest)) || any(isinf(rest)))) {
            uint width = b_frame.f.width;
            ivec2 pixel = ivec2(pixel_index % width, pixel_index / width);
            vec3 radiance = imageLoad(u_radiance, pixel).rgb + rest;
            imageStore(u_radiance, pixel, vec4(radiance, 1.0));
            if (SURFACE_OUTPUTS) {
                vec3 demodulated = demodulate(radiance, imageLoad(u_emission, pixel).rgb, imageLoad(u_albedo, pixel).rgb);
                imageStore(u_demodulated, pixel, vec4(demodulated, 1.0));
            }
        } else {
            atomicAdd(b_stats.non_finite, 1u);
        }
    }
    uint total = subgroupAdd(rays);
    if (subgroupElect()) {
        atomicAdd(b_stats.rays, total);
    }
}
