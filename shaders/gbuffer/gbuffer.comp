#version 460
// Primary visibility at pixel centres: linear depth, world normal and roughness, demodulation
// albedo, directly seen emission, ids, and motion vectors from the previous frame's camera and
// instance transforms.
#include "common/math.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Last frame's object-to-world rows, indexed by scene instance.
struct PrevTransform { vec4 rows[3]; };
layout(set = 0, binding = 16, std430) readonly buffer PrevTransforms { PrevTransform t[]; } b_prev_transforms;

layout(set = 0, binding = 17, r32f) uniform writeonly image2D u_depth;               // view depth, 0 = sky
layout(set = 0, binding = 18, rgba16f) uniform writeonly image2D u_normal_roughness; // world normal, GGX alpha
layout(set = 0, binding = 19, rgba16f) uniform writeonly image2D u_albedo;           // demodulation albedo
layout(set = 0, binding = 20, rgba16f) uniform writeonly image2D u_emission;         // emitted radiance seen
layout(set = 0, binding = 21, rgba32ui) uniform writeonly uimage2D u_ids;            // object, material, primitive, hit flag
layout(set = 0, binding = 22, rgba16f) uniform writeonly image2D u_motion;           // previous pixel - pixel (xy), previous depth (z)

// Largest motion offset stored, in pixels: beyond every image's size, so a clamped offset still
// leads off the frame, and exact in half precision.
const float MOTION_LIMIT = 32768.0;

// The offset from `pixel` to where `prev` (camera_project's, with the previous camera) lies on the
// previous frame. Offsets are clamped to MOTION_LIMIT, and a point at or behind the previous
// camera's plane (whose projection is mirrored, infinite or NaN) gets MOTION_LIMIT: rgba16f holds
// no more than 65504, so a larger offset would be stored as infinity, and infinity minus infinity
// is NaN wherever the motion is used (reprojection weights, a denoiser's training).
vec2 motion_offset(vec3 prev, ivec2 pixel, uvec2 size) {
    vec2 offset = prev.xy * vec2(size) - 0.5 - vec2(pixel);
    if (!(prev.z > 0.0) || any(isnan(offset))) {
        return vec2(MOTION_LIMIT);
    }
    return clamp(offset, -MOTION_LIMIT, MOTION_LIMIT);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    if (any(greaterThanEqual(uvec2(pixel), size))) {
        return;
    }
    float aspect = float(size.x) / float(size.y);
    Camera cam = b_frame.f.camera;
    Camera prev_cam = b_frame.f.prev_camera;
    cam.position_aperture.w = 0.0; // pinhole at pixel centres
    vec3 origin;
    vec3 dir;
    camera_ray(cam, film_ndc(vec2(pixel), vec2(0.5), vec2(size)), aspect, vec2(0.0), origin, dir);
    Hit hit;
    if (!trace_closest(origin, dir, T_INFINITY, hit)) {
        imageStore(u_depth, pixel, vec4(0.0));
        imageStore(u_normal_roughness, pixel, vec4(0.0));
        imageStore(u_albedo, pixel, vec4(1.0));
        imageStore(u_emission, pixel, vec4(environment_radiance(dir) + sun_radiance(dir), 1.0));
        imageStore(u_ids, pixel, uvec4(0xffffffffu, 0xffffffffu, 0xffffffffu, 0u));
        // The sky moves with the camera's rotation only.
        vec3 prev = camera_project(prev_cam, prev_cam.position_aperture.xyz + dir, aspect);
        imageStore(u_motion, pixel, vec4(motion_offset(prev, pixel, size), 0.0, 1.0));
        return;
    }
    Surface s = surface_at(hit, origin, dir);
    BsdfParams m = material_params_lod(s.material, s.uv, s.color, cone_lod(s, dir, hit.t * pixel_spread(cam, float(size.y))));
    vec3 n = dot(s.ns, dir) > 0.0 ? -s.ns : s.ns;
    float depth = dot(s.p - cam.position_aperture.xyz, cam.forward.xyz);
    imageStore(u_depth, pixel, vec4(depth));
    imageStore(u_normal_roughness, pixel, vec4(n, gbuffer_roughness(m)));
    imageStore(u_albedo, pixel, vec4(demodulation_albedo(m), 1.0));
    imageStore(u_emission, pixel, vec4(surface_emission(s, dir), 1.0));
    imageStore(u_ids, pixel, uvec4(s.object_id, s.material, hit.primitive, 1u));

    // Where this surface point was last frame: back to object space with this frame's transform,
    // forward with last frame's.
    Instance inst = b_instances.i[hit.instance];
    vec3 prev_world = s.p;
    if (inst.kind == INSTANCE_TRIANGLES) {
        vec3 object = transform_point(inst.world_to_object, s.p);
        prev_world = transform_point(b_prev_transforms.t[inst.scene_instance].rows, object);
    }
    vec3 prev = camera_project(prev_cam, prev_world, aspect);
    imageStore(u_motion, pixel, vec4(motion_offset(prev, pixel, size), prev.z, 1.0));
}
