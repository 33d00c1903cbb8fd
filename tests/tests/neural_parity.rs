//! The learned denoiser's Vulkan inference against its PyTorch definition (`training/model.py`):
//! two consecutive frames of a committed fixture (`references/neural_parity.safetensors`, made by
//! `training/make_parity.py` with the committed weights), so the features, every convolution,
//! pooling and upsampling, the history warp and the recurrent blend are all covered. The running
//! mean of the noisy radiance and its second moment (reprojected in the second frame) are also
//! compared directly, so they are checked whatever weight the network gives them.

use lucid_engine::graph::{Access, RenderGraph};
use lucid_passes::denoise::neural::{self, Network, NetworkWeights, RECORD_CHANNELS};
use safetensors::SafeTensors;

/// Half-precision activations give relative differences of about 1e-4 per layer, after seven layers still well under 5e-3.
const TOLERANCE: f32 = 5e-3;
/// The accumulation is float32 throughout: only rounding differences.
const ACCUM_TOLERANCE: f32 = 1e-4;

fn floats(tensors: &SafeTensors<'_>, name: &str) -> (Vec<usize>, Vec<f32>) {
    let view = tensors.tensor(name).expect("fixture tensor");
    let values = bytemuck::pod_collect_to_vec(view.data());
    (view.shape().to_vec(), values)
}

#[test]
fn vulkan_inference_matches_pytorch_over_two_frames() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/references/neural_parity.safetensors"
    );
    let bytes = std::fs::read(path).expect("read the parity fixture");
    let fixture = SafeTensors::deserialize(&bytes).expect("parse the parity fixture");
    let (shape, record) = floats(&fixture, "record");
    let (_, expected) = floats(&fixture, "expected");
    let (_, expected_accum) = floats(&fixture, "accum");
    let (_, expected_moment) = floats(&fixture, "moment");
    let (frames, channels, h, w) = (shape[0], shape[1], shape[2], shape[3]);
    assert_eq!(channels, RECORD_CHANNELS as usize);
    let (ctx, mut executor) = lucid_tests::executor(false);
    let network = Network::new(&ctx, &NetworkWeights::builtin()).expect("upload weights");
    let frame_len = channels * h * w;
    let mut worst_per_frame = Vec::new();
    let mut worst_accum_per_frame = Vec::new();
    for t in 0..frames {
        let data: Vec<u8> =
            bytemuck::cast_slice(&record[t * frame_len..(t + 1) * frame_len]).to_vec();
        let mut g = RenderGraph::new();
        let mut p = g.add_pass("upload_record");
        let buffer = p.create_buffer("record", data.len() as u64);
        let buffer = p.write(buffer, Access::TransferWrite);
        p.execute(move |ctx| ctx.update_buffer(buffer, &data));
        let images = neural::add_neural(&mut g, &network, buffer, (w as u32, h as u32), "neural");
        let readback = g.readback(images.radiance);
        let accum_readback = g.readback(images.accum);
        let moment_readback = g.readback(images.moment);
        let outputs = lucid_tests::run(&mut executor, g);
        let image = outputs.image(readback).expect("read back");
        let accum = outputs
            .image(accum_readback)
            .expect("read back the accumulation");
        let moment = outputs
            .image(moment_readback)
            .expect("read back the moment");
        let mut worst_accum = 0.0f32;
        for y in 0..h {
            for x in 0..w {
                let got = accum.pixels[y * w + x];
                let channels =
                    (0..4).map(|c| (got[c], expected_accum[((t * 4 + c) * h + y) * w + x]));
                let second = (
                    moment.pixels[y * w + x][0],
                    expected_moment[(t * h + y) * w + x],
                );
                for (c, (got, want)) in channels.chain([second]).enumerate() {
                    let err = (got - want).abs() / (want.abs() + 0.05);
                    assert!(
                        err <= ACCUM_TOLERANCE,
                        "frame {t} pixel ({x}, {y}) accumulation channel {c}: Vulkan {got}, PyTorch {want}"
                    );
                    worst_accum = worst_accum.max(err);
                }
            }
        }
        worst_accum_per_frame.push(worst_accum);
        let mut worst = 0.0f32;
        for y in 0..h {
            for x in 0..w {
                for c in 0..3 {
                    let want = expected[((t * 3 + c) * h + y) * w + x];
                    let got = image.pixels[y * w + x][c];
                    let err = (got - want).abs() / (want.abs() + 0.05);
                    assert!(
                        err <= TOLERANCE,
                        "frame {t} pixel ({x}, {y}) channel {c}: Vulkan {got}, PyTorch {want}"
                    );
                    worst = worst.max(err);
                }
            }
        }
        worst_per_frame.push(worst);
    }
    eprintln!("worst relative difference per frame: {worst_per_frame:?}");
    eprintln!("accumulation: {worst_accum_per_frame:?}");
    lucid_tests::assert_no_validation_messages(&ctx);
}
