#version 460
// The primary hits SVGF demodulates by and re-modulates with, antialiased so that emitter and
// albedo edges do not alias (a G-buffer sampled at pixel centres flips whole pixels as an edge
// crosses them, which flickers under sub-pixel motion):
// - the re-modulation albedo and emission: the mean over a fixed `grid` x `grid` lattice of pinhole
//   rays per pixel (deterministic, so they change smoothly as the camera moves);
// - the demodulated illumination of the input: with `exact_sample` set (one path-traced sample per
//   pixel this frame), the path tracer's own primary ray is re-cast with its random numbers, and
//   its exact emission and albedo are removed: (radiance - emission) / albedo. Otherwise (several
//   or accumulated samples) the grid's means stand in for them.
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

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 16, rgba32f) uniform readonly image2D u_radiance;
layout(set = 0, binding = 17, rgba32f) uniform writeonly image2D u_illumination;
layout(set = 0, binding = 18, rgba32f) uniform writeonly image2D u_albedo;
layout(set = 0, binding = 19, rgba32f) uniform writeonly image2D u_emission;

layout(push_constant) uniform Params {
    uint exact_sample;
    uint grid;
} params;

// Emission seen along (origin, dir) and the albedo the path tracer demodulates that hit by.
void primary_hit(vec3 origin, vec3 dir, uint max_depth, out vec3 emission, out vec3 albedo) {
    Hit hit;
    if (!trace_closest(origin, dir, T_INFINITY, hit)) {
        emission = environment_radiance(dir) + sun_radiance(dir);
        albedo = vec3(1.0);
        return;
    }
    Surface s = surface_at(hit, origin, dir);
    emission = surface_emission(s, dir);
    albedo = max_depth > 1u ? demodulation_albedo(material_params(s.material, s.uv)) : vec3(1.0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = b_frame.f.size.xy;
    if (any(greaterThanEqual(uvec2(pixel), size))) {
        return;
    }
    float aspect = float(size.x) / float(size.y);
    uint max_depth = b_frame.f.frame.w;
    Camera pinhole = b_frame.f.camera;
    pinhole.position_aperture.w = 0.0;
    vec3 emission_sum = vec3(0.0);
    vec3 albedo_sum = vec3(0.0);
    int grid = int(max(params.grid, 1u));
    for (int i = 0; i < grid * grid; ++i) {
        vec2 offset = (vec2(i % grid, i / grid) + 0.5) / float(grid);
        vec3 origin;
        vec3 dir;
        camera_ray(pinhole, film_ndc(vec2(pixel), offset, vec2(size)), aspect, vec2(0.5), origin, dir);
        vec3 emission;
        vec3 albedo;
        primary_hit(origin, dir, max_depth, emission, albedo);
        emission_sum += emission;
        albedo_sum += albedo;
    }
    vec3 emission = emission_sum / float(grid * grid);
    vec3 albedo = albedo_sum / float(grid * grid);
    imageStore(u_albedo, pixel, vec4(albedo, 1.0));
    imageStore(u_emission, pixel, vec4(emission, 1.0));

    vec3 radiance = imageLoad(u_radiance, pixel).rgb;
    vec3 illumination;
    if (params.exact_sample != 0u) {
        uint rng = rng_init(uvec2(pixel), b_frame.f.frame.x, b_frame.f.frame.y);
        vec2 ndc = film_ndc(vec2(pixel), rng_next2(rng), vec2(size));
        vec3 origin;
        vec3 dir;
        camera_ray(b_frame.f.camera, ndc, aspect, rng_next2(rng), origin, dir);
        vec3 sample_emission;
        vec3 sample_albedo;
        primary_hit(origin, dir, max_depth, sample_emission, sample_albedo);
        illumination = svgf_demodulate(radiance, sample_emission, sample_albedo);
    } else {
        illumination = svgf_demodulate(radiance, emission, albedo);
    }
    imageStore(u_illumination, pixel, vec4(illumination, 0.0));
}
