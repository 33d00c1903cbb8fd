//! A frame's samples per pixel cut into batches, one dispatch each (`SampleBatch` in
//! `shaders/common/sample_batch.glsl`). Mesa's llvmpipe (lavapipe) ends every loop of a shader
//! invocation once all its loops together have iterated 65535 times, which a pixel of a few hundred
//! paths reaches (the Cornell box: about 200 paths, far fewer in deep scenes), and the image came
//! out dark. A batch carries the generator state and running sums of the batch before it, so the
//! batches add up to what one dispatch of all the samples gives, bit for bit; the shaders count
//! the pixels whose loops were cut short all the same, and the frame fails on any.

use crate::samples_per_pixel::SamplesPerPixel;
use bytemuck::{Pod, Zeroable};

/// The most samples per pixel one dispatch traces.
pub const SAMPLES_PER_DISPATCH: u32 = 16;

/// One dispatch's samples (push constants, 8 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct SampleBatch {
    /// Index of the batch's first sample among the frame's.
    pub first: u32,
    /// Samples in the batch.
    pub count: u32,
}

impl SampleBatch {
    /// All of a frame's `spp` samples in one batch.
    pub fn whole(spp: SamplesPerPixel) -> Self {
        Self {
            first: 0,
            count: spp.get(),
        }
    }
}

/// The batches of a frame of `spp` samples per pixel, in order: all of
/// [`SAMPLES_PER_DISPATCH`] samples but the last.
pub fn sample_batches(spp: SamplesPerPixel) -> Vec<SampleBatch> {
    let spp = spp.get();
    (0..spp)
        .step_by(SAMPLES_PER_DISPATCH as usize)
        .map(|first| SampleBatch {
            first,
            count: SAMPLES_PER_DISPATCH.min(spp - first),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn batches(spp: u32) -> Vec<(u32, u32)> {
        sample_batches(SamplesPerPixel::new(spp).unwrap())
            .iter()
            .map(|b| (b.first, b.count))
            .collect()
    }

    #[test]
    fn few_samples_take_one_dispatch() {
        assert_eq!(batches(1), [(0, 1)]);
        assert_eq!(batches(SAMPLES_PER_DISPATCH), [(0, SAMPLES_PER_DISPATCH)]);
    }

    #[test]
    fn batches_cover_every_sample_once_in_order() {
        let n = SAMPLES_PER_DISPATCH;
        assert_eq!(batches(2 * n + 3), [(0, n), (n, n), (2 * n, 3)]);
    }
}
