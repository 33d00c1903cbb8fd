// A frame's samples per pixel in batches, one dispatch each (passes/src/light_transport/
// sample_batches.rs): Mesa's llvmpipe (lavapipe) ends every loop of a shader invocation once all its
// loops together have iterated 65535 times (LP_MAX_TGSI_LOOP_ITERATIONS, gallivm), which a pixel
// of a few hundred paths reaches. Each batch starts from the generator state and the running sums
// the batch before it left, so batches give the same result as one dispatch of all the samples.
#ifndef LUCID_SAMPLE_BATCH_GLSL
#define LUCID_SAMPLE_BATCH_GLSL

// One sample a pixel: the frame is one batch of one sample, which the shader may trace without
// the running sums.
layout(constant_id = 123) const bool ONE_SAMPLE = false;

// This dispatch's samples: `count` of them from sample `first` of the frame's samples_per_pixel.
struct SampleBatch {
    uint first;
    uint count;
};

// Whether `batch` is the frame's first, which starts the generator and the sums.
bool batch_is_first(SampleBatch batch) {
    return batch.first == 0u;
}

// Whether `batch` is the frame's last (of `spp` samples in all), which writes the averages.
bool batch_is_last(SampleBatch batch, uint spp) {
    return batch.first + batch.count >= spp;
}

// Whether a device's cap on an invocation's loop iterations has cut this invocation's loops short:
// a loop of `iterations` (at least 2, not known to the compiler) runs once only after the cap.
bool loop_limit_reached(uint iterations) {
    uint ran = 0u;
    for (uint i = 0u; i < iterations; ++i) {
        ran += 1u;
    }
    return ran < iterations;
}

#endif
