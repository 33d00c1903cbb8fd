#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Continues the camera subpaths camera.comp parked after PARK_DEPTH segments (parking/parking.glsl,
// bdpt/long_paths.glsl), one invocation each over parking/list.comp's list, and adds what they
// bring to their pixels' images (one sample a pixel, so each pixel has at most one). Counts the
// rays traced in b_stats.
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
#include "common/light_emit.glsl"
#include "bdpt/bdpt.glsl"
#include "common/transport_outputs.glsl"
#include "parking/parking.glsl"
#include "bdpt/long_paths.glsl"
#include "bdpt/camera_path.glsl"

layout(local_size_x = 64) in;

void main() {
    scene_to_workgroup(gl_WorkGroupSize.x * gl_WorkGroupSize.y);
    uint index = gl_GlobalInvocationID.x;
    if (index < b_parked_count.n) {
        uint pixel_index = b_parked_list.q[index];
        ParkedCameraPath p = b_parked.p[pixel_index];
        uint rng = p.rng;
        vec3 first_albedo;
        vec3 first_emission;
        vec3 rest = trace_camera_from(PARK_DEPTH, p.o, p.d, p.beta, p.dvcm, p.dvc, max(p.prev_pdf, 0.0),
                                      p.prev_pdf < 0.0, p.prev_p, rng, b_frame.f.max_depth, b_frame.f.rr_depth,
                                      first_albedo, first_emission);
        add_parked_radiance(pixel_index, rest);
    }
    uint rays = subgroupAdd(rays_traced);
    if (subgroupElect()) {
        atomicAdd(b_stats.rays, rays);
    }
}
