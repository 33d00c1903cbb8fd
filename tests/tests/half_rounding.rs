//! Every way Lucid's shaders round to half precision rounds to nearest with ties to even, as
//! PyTorch's `half()` does in training: the learned denoiser's packing (`pack_channels`,
//! `shaders/neural/tensor.glsl`), which rounds its activations and its output's history (fed back
//! frame after frame, where a truncation would compound into a darker image), the round trip
//! through it that rounds values in place, and `round_to_half` (`shaders/common/half_round.glsl`)
//! before an `rgba16f` image store, as SVGF stores its a-trous steps. Vulkan leaves the rounding of
//! `packHalf2x16` and of a store's conversion to the implementation: lavapipe's and NVIDIA's
//! `rgba16f` stores truncate, and NVIDIA's compiler folds a packing round trip before a store into
//! it (so the denoiser's history is stored as packed halves; `neural_parity.rs` checks thirty
//! frames' light). Checked on every finite half, the points between each and the next (the tie,
//! the floats either side of it, a quarter and three quarters of the way), both signs, and on
//! overflow, infinities and NaN.

use ash::vk;
use half::f16;
use lucid_engine::graph::RenderGraph;
use lucid_engine::memory::Buffer;
use lucid_passes::debug::half_rounding::{self, IMAGE_WIDTH};
use lucid_tests::{assert_no_validation_messages, executor, run};
use std::sync::Arc;

/// The floats checked: around every finite non-negative half and its next, then their negatives,
/// then overflow and the special values, padded with zeros to whole vec4s.
fn values() -> Vec<f32> {
    let mut values = Vec::new();
    for bits in 0..0x7bffu16 {
        let low = f16::from_bits(bits).to_f32();
        let high = f16::from_bits(bits + 1).to_f32();
        let tie = 0.5 * (low + high);
        values.extend([
            low,
            low + 0.25 * (high - low),
            f32::from_bits(tie.to_bits() - 1),
            tie,
            f32::from_bits(tie.to_bits() + 1),
            low + 0.75 * (high - low),
        ]);
    }
    let negatives: Vec<f32> = values.iter().map(|v| -v).collect();
    values.extend(negatives);
    values.extend([
        65504.0,
        65519.996,
        65520.0,
        1.0e6,
        -65520.0,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ]);
    values.resize(values.len().div_ceil(4) * 4, 0.0);
    values
}

#[test]
fn half_precision_rounds_to_nearest_even() {
    let (ctx, mut executor) = executor(false);
    let values = values();
    let count = (values.len() / 4) as u32;
    let buffer = Buffer::with_data(
        &ctx,
        "values",
        "test",
        vk::BufferUsageFlags::STORAGE_BUFFER,
        bytemuck::cast_slice(&values),
    )
    .expect("upload the values");
    let mut g = RenderGraph::new();
    let input = g.import_buffer("values", Arc::new(buffer));
    let out = half_rounding::add_half_rounding(&mut g, input, count);
    let packed = g.readback(out.packed);
    let rounded = g.readback(out.rounded);
    let stored = g.readback(out.stored);
    let outputs = run(&mut executor, g);
    let words: Vec<u32> = bytemuck::pod_collect_to_vec(outputs.bytes(packed).expect("read back"));
    let halves = words
        .iter()
        .flat_map(|w| [*w as u16, (*w >> 16) as u16])
        .map(f16::from_bits);
    let rounded: Vec<f32> =
        bytemuck::pod_collect_to_vec(outputs.bytes(rounded).expect("read back"));
    // Exact halves, so converting them back to half is exact.
    let rounded = rounded.iter().map(|r| f16::from_f32(*r));
    let stored = outputs.image(stored).expect("read back");
    assert_eq!(stored.width, IMAGE_WIDTH);
    let stored = stored.pixels.iter().flatten().map(|v| f16::from_f32(*v));
    assert_no_validation_messages(&ctx);
    check("packed", &values, halves);
    check("rounded in place", &values, rounded);
    check("stored after round_to_half", &values, stored);
}

/// Panics listing the values that `got` (one half a value) does not round to nearest, ties to even.
fn check(what: &str, values: &[f32], got: impl Iterator<Item = f16>) {
    let mut wrong = Vec::new();
    let mut toward_zero = 0;
    for (value, got) in values.iter().zip(got) {
        let want = f16::from_f32(*value);
        let same = if value.is_nan() {
            got.is_nan()
        } else {
            got.to_bits() == want.to_bits()
        };
        if !same {
            if got.to_f32().abs() < want.to_f32().abs() {
                toward_zero += 1;
            }
            wrong.push(format!("{value:e}: want {want} got {got}"));
        }
    }
    assert!(
        wrong.is_empty(),
        "{what}: {} of {} values wrong ({toward_zero} of them rounded toward zero), e.g.\n{}",
        wrong.len(),
        values.len(),
        wrong[..wrong.len().min(12)].join("\n")
    );
}
