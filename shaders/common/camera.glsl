// Primary rays: pinhole or thin lens, box-filtered over the pixel. Requires math.glsl, scene.glsl.
#ifndef LUCID_CAMERA_GLSL
#define LUCID_CAMERA_GLSL

// The ray through film position `ndc` in [-1, 1]^2 (+y up), with lens sample `lens`.
void camera_ray(Camera c, vec2 ndc, float aspect, vec2 lens, out vec3 origin, out vec3 dir) {
    float tan_half = c.up_tan_half_fov.w;
    vec3 d = normalize(c.forward.xyz + c.right_focus.xyz * (ndc.x * tan_half * aspect)
                       + c.up_tan_half_fov.xyz * (ndc.y * tan_half));
    origin = c.position_aperture.xyz;
    dir = d;
    float aperture = c.position_aperture.w;
    if (aperture > 0.0) {
        float focus = c.right_focus.w / max(dot(d, c.forward.xyz), 1e-6);
        vec3 focal_point = origin + d * focus;
        vec2 offset = sample_disk(lens) * aperture;
        origin += c.right_focus.xyz * offset.x + c.up_tan_half_fov.xyz * offset.y;
        dir = normalize(focal_point - origin);
    }
}

// `previous ? prev : current`, member by member: a select of whole structs is SPIR-V 1.4's.
Camera camera_select(bool previous, Camera current, Camera prev) {
    Camera c;
    c.position_aperture = previous ? prev.position_aperture : current.position_aperture;
    c.right_focus = previous ? prev.right_focus : current.right_focus;
    c.up_tan_half_fov = previous ? prev.up_tan_half_fov : current.up_tan_half_fov;
    c.forward = previous ? prev.forward : current.forward;
    return c;
}

// The angle one pixel of an image `height` pixels high spans at the centre of camera c's film:
// how fast primary ray cones widen (texture filtering, cone_lod in surface.glsl).
float pixel_spread(Camera c, float height) {
    return 2.0 * c.up_tan_half_fov.w / height;
}

// Film position of `pixel` + `jitter` (in [0,1)^2) for an image of `size` (row 0 at the top).
vec2 film_ndc(vec2 pixel, vec2 jitter, vec2 size) {
    vec2 uv = (pixel + jitter) / size;
    return vec2(2.0 * uv.x - 1.0, 1.0 - 2.0 * uv.y);
}

// Projects a world point to film uv in [0,1]^2 (row 0 at the top); w < 0 when behind the camera.
vec3 camera_project(Camera c, vec3 p, float aspect) {
    vec3 d = p - c.position_aperture.xyz;
    float z = dot(d, c.forward.xyz);
    float tan_half = c.up_tan_half_fov.w;
    float x = dot(d, c.right_focus.xyz) / (z * tan_half * aspect);
    float y = dot(d, c.up_tan_half_fov.xyz) / (z * tan_half);
    return vec3(0.5 * x + 0.5, 0.5 - 0.5 * y, z);
}

#endif
