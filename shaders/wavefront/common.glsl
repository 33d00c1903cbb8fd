// What every wavefront kernel includes: the path tracer's shared GLSL (common/path.glsl and what
// it requires), so that each kernel has every specialization constant the scene sets (the graph
// sets them by name and a name the shader lacks is an error), and the queues' layout.
#ifndef LUCID_WAVEFRONT_COMMON_GLSL
#define LUCID_WAVEFRONT_COMMON_GLSL

#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"
#include "common/path.glsl"
#include "common/transport_outputs.glsl"
#include "wavefront/queues.glsl"

#endif
