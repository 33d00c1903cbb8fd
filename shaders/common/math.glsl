// Constants, orthonormal frames and sampling helpers.
#ifndef LUCID_MATH_GLSL
#define LUCID_MATH_GLSL

const float PI = 3.14159265358979;
const float INV_PI = 0.31830988618379;
const float RAY_EPSILON = 1e-4;

float luminance(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

float max3(vec3 v) {
    return max(v.x, max(v.y, v.z));
}

// An orthonormal basis around n (Duff et al. 2017).
void make_frame(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 to_local(vec3 v, vec3 t, vec3 b, vec3 n) {
    return vec3(dot(v, t), dot(v, b), dot(v, n));
}

vec3 to_world(vec3 v, vec3 t, vec3 b, vec3 n) {
    return v.x * t + v.y * b + v.z * n;
}

vec3 sample_cosine_hemisphere(vec2 u) {
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}

// Uniform direction in the cone around +z with cos(half angle) = cos_max.
vec3 sample_cone(vec2 u, float cos_max) {
    float cos_t = 1.0 - u.x * (1.0 - cos_max);
    float sin_t = sqrt(max(0.0, 1.0 - cos_t * cos_t));
    float phi = 2.0 * PI * u.y;
    return vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t);
}

vec2 sample_disk(vec2 u) {
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    return r * vec2(cos(phi), sin(phi));
}

float power_heuristic(float a, float b) {
    float a2 = a * a;
    float b2 = b * b;
    return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

// Radiance without the directly seen emission, divided by the first-hit albedo: the smooth
// signal denoisers filter (emission and albedo are added back after filtering).
vec3 demodulate(vec3 radiance, vec3 emission, vec3 albedo) {
    return max(radiance - emission, vec3(0.0)) / max(albedo, vec3(1e-3));
}

// Offsets a ray origin along the geometric normal, on the side of `dir`.
vec3 offset_origin(vec3 p, vec3 ng, vec3 dir) {
    float scale = RAY_EPSILON * max(1.0, max3(abs(p)));
    return p + ng * (dot(ng, dir) >= 0.0 ? scale : -scale);
}

// Turns the ray from `origin` along unit `dir` for `reach` into the same segment walked from its
// far end (a shadow ray's occlusion does not depend on the direction it is traced in).
void reverse_segment(inout vec3 origin, inout vec3 dir, float reach) {
    origin += dir * reach;
    dir = -dir;
}

#endif
