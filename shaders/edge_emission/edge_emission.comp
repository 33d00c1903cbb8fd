#version 460
// The emission seen directly, supersampled where an emitter's (or the sky's) edge crosses the
// pixel: a 4x4 grid of jittered camera rays there, the light transport's own average elsewhere.
// With one sample a pixel, an edge pixel sees the emitter or what is beside it, so the emission a
// denoiser adds back jumps between the two from frame to frame and flickers, where the reference
// shows the pixel's coverage. A pixel is on such an edge when a pixel of its 3x3 neighbourhood
// sees another object at its centre (the G-buffer's ids) and either of the two emits. The alpha of
// a supersampled pixel is SUPERSAMPLED (the light transport's is 1): the denoisers average its
// emission over time only as far as it moves less than a pixel a frame (edge_emission.glsl).
#include "common/math.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"
#include "common/rng.glsl"
#include "common/image_coords.glsl"
#include "edge_emission/edge_emission.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
const uint WORKGROUP = 64u;

layout(set = 0, binding = 16, rgba32ui) uniform readonly uimage2D u_ids;      // the G-buffer's
layout(set = 0, binding = 17, rgba16f) uniform readonly image2D u_centre_emission; // the G-buffer's
layout(set = 0, binding = 18, rgba32f) uniform readonly image2D u_traced_emission; // the transport's
layout(set = 0, binding = 19, rgba32f) uniform writeonly image2D u_emission;

// Rays a side of the grid over an edge pixel.
const uint GRID = 4u;
// Mixed into the seed, so that the grid's jitter is independent of the path tracer's samples.
const uint SEED_SALT = 0x9e3779b9u;

// Whether the pixel lies on the edge of something that emits (see above).
bool on_emitter_edge(ivec2 pixel, ivec2 size) {
    uint object = imageLoad(u_ids, pixel).x;
    bool emits = max3(imageLoad(u_centre_emission, pixel).rgb) > 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if ((dx == 0 && dy == 0) || !inside_image(q, size)) {
                continue;
            }
            if (imageLoad(u_ids, q).x != object
                && (emits || max3(imageLoad(u_centre_emission, q).rgb) > 0.0)) {
                return true;
            }
        }
    }
    return false;
}

// The emission a camera ray sees first (the sky's where it hits nothing), as the path tracer
// counts it at the first vertex (trace_path in path.glsl).
vec3 first_emission(vec3 origin, vec3 dir) {
    Hit hit;
    if (!trace_closest(origin, dir, T_INFINITY, hit)) {
        return environment_radiance(dir) + sun_radiance(dir);
    }
    return surface_emission(surface_at(hit, origin, dir), dir);
}

// The workgroup's edge pixels (packed x | y << 16), the emission each invocation's ray saw, and the
// edge pixels' means: the grid's rays of all the workgroup's edge pixels are spread over all its
// invocations, GRID * GRID a pixel, so that a few edge pixels do not hold the others idle.
shared uint s_count;
shared uint s_pixels[WORKGROUP];
shared vec3 s_rays[WORKGROUP];
shared vec3 s_means[WORKGROUP];

// The emission the `cell`-th ray of the grid over `pixel` sees, jittered within its cell.
vec3 grid_ray(ivec2 pixel, uint cell, ivec2 size) {
    uint rng = rng_init(uvec2(pixel), b_frame.f.frame_index * GRID * GRID + cell, b_frame.f.seed ^ SEED_SALT);
    vec2 jitter = (vec2(float(cell % GRID), float(cell / GRID)) + rng_next2(rng)) / float(GRID);
    vec3 origin;
    vec3 dir;
    float aspect = float(size.x) / float(size.y);
    camera_ray(b_frame.f.camera, film_ndc(vec2(pixel), jitter, vec2(size)), aspect, rng_next2(rng), origin, dir);
    return first_emission(origin, dir);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(b_frame.f.width, b_frame.f.height);
    uint local = gl_LocalInvocationIndex;
    if (local == 0u) {
        s_count = 0u;
    }
    barrier();
    bool inside = pixel_in_bounds(pixel, size);
    bool edge = inside && on_emitter_edge(pixel, size);
    uint slot = 0u;
    if (edge) {
        slot = atomicAdd(s_count, 1u);
        s_pixels[slot] = uint(pixel.x) | (uint(pixel.y) << 16u);
    }
    barrier();
    uint count = s_count;
    const uint per_pass = WORKGROUP / (GRID * GRID);
    for (uint first = 0u; first < count; first += per_pass) {
        uint index = first + local / (GRID * GRID);
        vec3 seen = vec3(0.0);
        if (index < count) {
            uint packed = s_pixels[index];
            ivec2 target = ivec2(packed & 0xffffu, packed >> 16u);
            seen = grid_ray(target, local % (GRID * GRID), size);
        }
        s_rays[local] = seen;
        barrier();
        if (local < per_pass && first + local < count) {
            vec3 sum = vec3(0.0);
            for (uint i = 0u; i < GRID * GRID; ++i) {
                sum += s_rays[local * GRID * GRID + i];
            }
            s_means[first + local] = sum / float(GRID * GRID);
        }
        barrier();
    }
    if (!inside) {
        return;
    }
    vec4 emission = edge ? vec4(s_means[slot], SUPERSAMPLED) : imageLoad(u_traced_emission, pixel);
    imageStore(u_emission, pixel, emission);
}
