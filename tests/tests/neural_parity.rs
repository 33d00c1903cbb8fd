//! The learned denoiser's Vulkan inference against its PyTorch definition (`training/model.py`):
//! two consecutive frames of a committed fixture (`references/neural_parity.safetensors`, made by
//! `training/make_parity.py` with the committed weights), so the features, every convolution,
//! pooling and upsampling, the history warp and the recurrent blend are all covered. The running
//! mean of the noisy radiance and its second moment (reprojected in the second frame) are also
//! compared directly, so they are checked whatever weight the network gives them. Every inference
//! path the device runs is checked (lavapipe: the portable one; NVIDIA: the tensor-core one too),
//! so where both run they agree within twice the tolerance.

use lucid_engine::graph::{Access, RenderGraph};
use lucid_passes::denoise::neural::{
    self, InferencePath, Network, NetworkWeights, RECORD_CHANNELS,
};
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

/// The fixture: its records (frames x channels x height x width) and PyTorch's outputs: radiance
/// (frames x 3 x height x width), running mean and length (frames x 4 x ...) and second moment
/// (frames x 1 x ...).
struct Fixture {
    record: Vec<f32>,
    expected: Vec<f32>,
    accum: Vec<f32>,
    moment: Vec<f32>,
    frames: usize,
    size: (usize, usize),
}

fn fixture() -> Fixture {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/references/neural_parity.safetensors"
    );
    let bytes = std::fs::read(path).expect("read the parity fixture");
    let tensors = SafeTensors::deserialize(&bytes).expect("parse the parity fixture");
    let (shape, record) = floats(&tensors, "record");
    let (_, expected) = floats(&tensors, "expected");
    let (_, accum) = floats(&tensors, "accum");
    let (_, moment) = floats(&tensors, "moment");
    assert_eq!(shape[1], RECORD_CHANNELS as usize);
    Fixture {
        record,
        expected,
        accum,
        moment,
        frames: shape[0],
        size: (shape[3], shape[2]),
    }
}

/// One frame's results: the denoised radiance, the running mean (rgb) with its length (a), and the
/// second moment of luminance (r), pixel by pixel.
struct Frame {
    radiance: Vec<[f32; 4]>,
    accum: Vec<[f32; 4]>,
    moment: Vec<[f32; 4]>,
}

/// The results of consecutive frames of `records` (each a planar record of `size`), by `network`
/// from no history (each path keeps its own).
fn denoise(
    executor: &mut lucid_engine::graph::Executor,
    network: &Network,
    records: &[Vec<f32>],
    (w, h): (usize, usize),
) -> Vec<Frame> {
    let prefix = format!("neural.{}", network.path().short_name());
    let mut images = Vec::new();
    for record in records {
        let data: Vec<u8> = bytemuck::cast_slice(record).to_vec();
        let mut g = RenderGraph::new();
        let mut p = g.add_pass("upload_record");
        let buffer = p.create_buffer("record", data.len() as u64);
        let buffer = p.write(buffer, Access::TransferWrite);
        p.execute(move |ctx| ctx.update_buffer(buffer, &data));
        let images_of = neural::add_neural(&mut g, network, buffer, (w as u32, h as u32), &prefix);
        let readbacks =
            [images_of.radiance, images_of.accum, images_of.moment].map(|i| g.readback(i));
        let outputs = lucid_tests::run(executor, g);
        let [radiance, accum, moment] =
            readbacks.map(|r| outputs.image(r).expect("read back").pixels.clone());
        images.push(Frame {
            radiance,
            accum,
            moment,
        });
    }
    images
}

#[test]
fn vulkan_inference_matches_pytorch_over_two_frames() {
    let fixture = fixture();
    let (w, h) = fixture.size;
    let frame_len = RECORD_CHANNELS as usize * h * w;
    let records: Vec<Vec<f32>> = fixture
        .record
        .chunks(frame_len)
        .map(<[f32]>::to_vec)
        .collect();
    let (ctx, mut executor) = lucid_tests::executor(false);
    let paths = InferencePath::available(&ctx);
    assert!(paths.contains(&InferencePath::Portable));
    for path in paths {
        let network =
            Network::with_path(&ctx, &NetworkWeights::builtin(), path).expect("upload weights");
        let images = denoise(&mut executor, &network, &records, (w, h));
        let mut worst_per_frame = Vec::new();
        let mut worst_accum_per_frame = Vec::new();
        for (t, frame) in images.iter().enumerate() {
            let mut worst_accum = 0.0f32;
            for y in 0..h {
                for x in 0..w {
                    let i = y * w + x;
                    let channels = (0..4).map(|c| {
                        (
                            frame.accum[i][c],
                            fixture.accum[((t * 4 + c) * h + y) * w + x],
                        )
                    });
                    let second = (frame.moment[i][0], fixture.moment[(t * h + y) * w + x]);
                    for (c, (got, want)) in channels.chain([second]).enumerate() {
                        let err = (got - want).abs() / (want.abs() + 0.05);
                        assert!(
                            err <= ACCUM_TOLERANCE,
                            "frame {t} pixel ({x}, {y}) accumulation channel {c}: Vulkan {got}, \
                             PyTorch {want}"
                        );
                        worst_accum = worst_accum.max(err);
                    }
                }
            }
            worst_accum_per_frame.push(worst_accum);
            let mut worst = 0.0f32;
            for y in 0..h {
                for x in 0..w {
                    for (c, &got) in frame.radiance[y * w + x][..3].iter().enumerate() {
                        let want = fixture.expected[((t * 3 + c) * h + y) * w + x];
                        let err = (got - want).abs() / (want.abs() + 0.05);
                        assert!(
                            err <= TOLERANCE,
                            "{} path, frame {t} pixel ({x}, {y}) channel {c}: Vulkan {got}, \
                             PyTorch {want}",
                            path.short_name()
                        );
                        worst = worst.max(err);
                    }
                }
            }
            worst_per_frame.push(worst);
        }
        eprintln!(
            "{} path: worst relative difference per frame: {worst_per_frame:?}, accumulation: \
             {worst_accum_per_frame:?}",
            path.short_name()
        );
    }
    lucid_tests::assert_no_validation_messages(&ctx);
}

/// Where a device runs both paths (NVIDIA), they agree on a crop of the fixture of odd width and
/// height, so partial tiles, odd pooling edges and upsampling are covered too. On a device with
/// one path (lavapipe) there is nothing to compare: the test says so and checks nothing.
#[test]
fn inference_paths_agree_at_odd_sizes() {
    let fixture = fixture();
    let (w, h) = fixture.size;
    let (cw, ch) = (w - 3, h - 5);
    assert!(
        cw % 2 == 1 && ch % 2 == 1,
        "an odd crop of the {w}x{h} fixture"
    );
    let channels = RECORD_CHANNELS as usize;
    let records: Vec<Vec<f32>> = (0..fixture.frames)
        .map(|t| {
            let mut crop = Vec::with_capacity(channels * cw * ch);
            for c in 0..channels {
                for y in 0..ch {
                    let row = ((t * channels + c) * h + y) * w;
                    crop.extend_from_slice(&fixture.record[row..row + cw]);
                }
            }
            crop
        })
        .collect();
    let (ctx, mut executor) = lucid_tests::executor(false);
    let paths = InferencePath::available(&ctx);
    if paths.len() < 2 {
        eprintln!(
            "{} runs one inference path: nothing to compare",
            ctx.info().name
        );
        return;
    }
    let weights = NetworkWeights::builtin();
    let mut results = Vec::new();
    for &path in &paths {
        let network = Network::with_path(&ctx, &weights, path).expect("upload weights");
        results.push(denoise(&mut executor, &network, &records, (cw, ch)));
    }
    let mut worst = 0.0f32;
    for (t, (a, b)) in results[0].iter().zip(&results[1]).enumerate() {
        for (i, (pa, pb)) in a.radiance.iter().zip(&b.radiance).enumerate() {
            for c in 0..3 {
                let err = (pa[c] - pb[c]).abs() / (pa[c].abs() + 0.05);
                assert!(
                    err <= 2.0 * TOLERANCE,
                    "frame {t} pixel {i} channel {c}: {} {}, {} {}",
                    paths[0].short_name(),
                    pa[c],
                    paths[1].short_name(),
                    pb[c]
                );
                worst = worst.max(err);
            }
        }
    }
    eprintln!("{cw}x{ch}: worst relative difference between the paths: {worst}");
    lucid_tests::assert_no_validation_messages(&ctx);
}
