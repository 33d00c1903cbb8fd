// The wavefront path tracer's path state, one element per path (a path per pixel per sample,
// index y * width + x), structure of arrays: what a path carries between its kernels (the
// PathState of common/path.glsl, its ray, random-number state and radiance so far, and the first
// hit's albedo and emission for the denoisers). Read and written by generate and shade.
#ifndef LUCID_WAVEFRONT_PATH_STATE_GLSL
#define LUCID_WAVEFRONT_PATH_STATE_GLSL

layout(set = 0, binding = 16, std430) buffer RayOrigin { vec4 v[]; } b_ray_origin;       // origin, prev_pdf
layout(set = 0, binding = 17, std430) buffer RayDirection { vec4 v[]; } b_ray_direction; // direction, 0
layout(set = 0, binding = 18, std430) buffer Throughput { vec4 v[]; } b_throughput;     // beta, prev_delta
// prev_p; w: the camera ray's cone spread (pixel_spread) after generate, for the first hit's
// texture filtering, 0 after shade.
layout(set = 0, binding = 19, std430) buffer PrevVertex { vec4 v[]; } b_prev_vertex;
layout(set = 0, binding = 20, std430) buffer PathRng { uint s[]; } b_path_rng;
layout(set = 0, binding = 21, std430) buffer PathRadiance { vec4 v[]; } b_path_radiance;
// The first hit's albedo (2 path) and emission (2 path + 1); one element only without
// SURFACE_OUTPUTS.
layout(set = 0, binding = 22, std430) buffer FirstHit { vec4 v[]; } b_first_hit;

PathState load_path_state(uint path) {
    PathState st;
    vec4 origin = b_ray_origin.v[path];
    vec4 throughput = b_throughput.v[path];
    st.beta = throughput.xyz;
    st.prev_delta = throughput.w != 0.0;
    st.prev_pdf = origin.w;
    st.prev_p = b_prev_vertex.v[path].xyz;
    return st;
}

// Stores `st` and its next ray (o, d), whose cone widens by `spread` radians per unit distance
// (the camera ray's; 0 for later rays, whose hits read level 0 of the textures).
void store_path_state(uint path, PathState st, vec3 o, vec3 d, float spread) {
    b_ray_origin.v[path] = vec4(o, st.prev_pdf);
    b_ray_direction.v[path] = vec4(d, 0.0);
    b_throughput.v[path] = vec4(st.beta, st.prev_delta ? 1.0 : 0.0);
    b_prev_vertex.v[path] = vec4(st.prev_p, spread);
}

#endif
