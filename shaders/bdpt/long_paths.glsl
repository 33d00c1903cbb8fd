// BDPT's parked camera subpaths (parking/parking.glsl): with PARK_DEPTH set, a camera subpath still
// alive after PARK_DEPTH segments goes to its pixel's record in b_parked and camera_long.comp
// continues it. Requires parking/parking.glsl.
#ifndef LUCID_BDPT_LONG_PATHS_GLSL
#define LUCID_BDPT_LONG_PATHS_GLSL

// What trace_camera_from needs to go on with a camera subpath: its next ray, throughput, MIS state
// and random number generator, 64 bytes. prev_pdf is negative after a delta BSDF, whose pdf the
// weights never read.
struct ParkedCameraPath {
    vec3 o;
    uint rng;
    vec3 d;
    float prev_pdf;
    vec3 beta;
    float dvcm;
    vec3 prev_p;
    float dvc;
};

#ifdef PARKING_CONTINUE
layout(set = 0, binding = 27, std430) readonly buffer Parked { ParkedCameraPath p[]; } b_parked;
#else
layout(set = 0, binding = 27, std430) writeonly buffer Parked { ParkedCameraPath p[]; } b_parked;

// Parks the camera subpath of this invocation's pixel (a plain store, as the path tracer's).
#define CAMERA_PARK(o, d, beta, dvcm, dvc, prev_pdf, prev_delta, prev_p, rng) if (PARK_DEPTH != 0u) { \
    uint parked_pixel = parking_pixel(); \
    b_parked.p[parked_pixel] = ParkedCameraPath(o, rng, d, prev_delta ? -1.0 : prev_pdf, beta, dvcm, prev_p, dvc); \
    b_parked_flags.f[parked_pixel] = 1u; }
#endif

#endif
