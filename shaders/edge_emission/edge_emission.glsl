// The mark the edge pass (edge_emission.comp) leaves in the alpha of the emission it supersampled
// at an emitter's edge (the light transport writes 1), and how much a denoiser's average over time
// weighs such a pixel's emission this frame.
#ifndef LUCID_EDGE_EMISSION_GLSL
#define LUCID_EDGE_EMISSION_GLSL

// Negative: no light transport writes it, nor anything that fills the image from records.
const float SUPERSAMPLED = -1.0;

// Whether the edge pass supersampled this emission texel (rgb, alpha).
bool supersampled(vec4 emission) {
    return emission.a == SUPERSAMPLED;
}

// The least weight of this frame's emission in a denoiser's average over time: for an emission the
// edge pass supersampled, the pixel's motion in pixels, up to 1 (so this frame's alone from a pixel a
// frame up); else 0. Under sub-pixel motion the average still smooths the grid's jitter; under
// faster motion, the history, reprojected from pixels of one object or the other as the edge
// moves, would blur and lag what the grid already covers.
float edge_emission_weight(vec4 emission, vec2 motion) {
    return supersampled(emission) ? min(length(motion), 1.0) : 0.0;
}

#endif
