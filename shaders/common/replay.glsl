// Path replay for temporal gradients (A-SVGF, Schied et al. 2018): on a frame with replay on, one
// pixel p per stratum of `stratum` x `stratum` pixels does not draw a new sample: it replays the
// path that last frame's pixel q (p followed back along its motion vector) traced, with last
// frame's camera and exactly the random numbers q drew then (they are a pure function of pixel,
// frame index and seed). Comparing its radiance with what q produced last frame gives a noise-free
// temporal gradient: zero where only the camera moved, the change in shading where lights or
// objects changed. The light transport replays (path_trace/path_trace.glsl); the denoiser compares
// (svgf/gradient.comp); both pick the same pixels through these functions. Requires rng.glsl.
#ifndef LUCID_REPLAY_GLSL
#define LUCID_REPLAY_GLSL

const ivec2 NO_REPLAY = ivec2(-1);

// What decides replay on a frame: the stratum side (0: no replay this frame) and last frame's
// (0 when last frame replayed nothing).
struct ReplayParams {
    uint stratum;
    uint prev_stratum;
};

// The pixel of stratum `cell` picked on frame `frame` (afresh each frame, clamped to the image).
ivec2 replay_pick(ivec2 cell, uint stratum, uint frame, ivec2 size) {
    uint pick = pcg_hash(uint(cell.x) ^ pcg_hash(uint(cell.y) ^ pcg_hash(frame)));
    ivec2 offset = ivec2(pick % stratum, (pick / stratum) % stratum);
    return min(cell * int(stratum) + offset, size - 1);
}

// True when pixel p is its stratum's pick on frame `frame`.
bool replay_picked(ivec2 p, ReplayParams r, uint frame, ivec2 size) {
    return r.stratum > 0u && replay_pick(p / int(r.stratum), r.stratum, frame, size) == p;
}

// Last frame's pixel whose path the picked pixel p replays, given p's motion vector (pixels to
// its position last frame); NO_REPLAY when it left the image, or when q itself replayed an older
// path last frame (its random numbers were not its own then).
ivec2 replay_source(ivec2 p, vec2 motion, ReplayParams r, uint frame, ivec2 size) {
    ivec2 q = ivec2(floor(vec2(p) + motion + 0.5));
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
        return NO_REPLAY;
    }
    if (r.prev_stratum > 0u && replay_pick(q / int(r.prev_stratum), r.prev_stratum, frame - 1u, size) == q) {
        return NO_REPLAY;
    }
    return q;
}

#endif
