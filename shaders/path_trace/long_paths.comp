#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// Continues the paths the path tracer parked after PARK_DEPTH segments (parking/parking.glsl), one
// invocation each over parking/list.comp's list, and adds what they bring to their pixels' images
// (one sample a pixel, so each pixel has at most one). Counts the rays traced in b_stats.
#define PATH_KEEP_FIRST_ALBEDO(v)
#define PATH_KEEP_FIRST_EMISSION(v)
#define PARKING_CONTINUE
#define SCENE_IN_WORKGROUP
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

#include "parking/parking.glsl"
#include "path_trace/long_paths.glsl"
#include "common/path.glsl"

void main() {
    scene_to_workgroup(gl_WorkGroupSize.x * gl_WorkGroupSize.y);
    uint index = gl_GlobalInvocationID.x;
    uint rays = 0u;
    if (index < b_parked_count.n) {
        uint pixel_index = b_parked_list.q[index];
        ParkedPath t = b_parked.p[pixel_index];
        uint rng = t.rng;
        vec3 rest = trace_path_from(PARK_DEPTH, t.o, t.d, t.beta, t.prev_pdf, t.prev_delta != 0u, t.prev_p, rng,
                                    b_frame.f.max_depth, b_frame.f.rr_depth, 0.0, rays);
        add_parked_radiance(pixel_index, rest);
    }
    uint total = subgroupAdd(rays);
    if (subgroupElect()) {
        atomicAdd(b_stats.rays, total);
    }
}
