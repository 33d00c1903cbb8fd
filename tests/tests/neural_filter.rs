//! The learned denoiser's gated a-trous filter turned off at run time
//! (`NeuralParams::gated_filter`): the renderer then gives what the same weights without the gate
//! give, and turning it off between frames keeps the history, since what the network carries from
//! frame to frame is its unfiltered output.

use lucid_passes::denoise::neural::{self, NetworkWeights, NeuralParams};
use lucid_passes::renderer::{Denoiser, Renderer, Settings};
use lucid_tests::render::scene;
use lucid_tests::{assert_no_validation_messages, context};
use safetensors::tensor::TensorView;
use safetensors::SafeTensors;

/// Frames rendered and compared: the filter differs most in the first, the history counts after.
const FRAMES: usize = 4;

/// The committed weights without their gate: the output layer's last channel and the
/// `atrous_steps` metadata dropped (what they were before the gate was trained).
fn without_gate() -> NetworkWeights {
    let (_, header) = SafeTensors::read_metadata(neural::BUILTIN).expect("parse the weights");
    let mut metadata = header.metadata().clone().unwrap_or_default();
    assert!(
        metadata.remove("atrous_steps").is_some(),
        "the committed weights have the gate"
    );
    let tensors = SafeTensors::deserialize(neural::BUILTIN).expect("parse the weights");
    let views: Vec<(String, TensorView<'_>)> = tensors
        .tensors()
        .into_iter()
        .map(|(name, view)| {
            if name != "out.weight" && name != "out.bias" {
                return (name, view);
            }
            let mut shape = view.shape().to_vec();
            let row = view.data().len() / shape[0];
            shape[0] -= 1;
            let data = &view.data()[..row * shape[0]];
            let trimmed = TensorView::new(view.dtype(), shape, data).expect("a tensor");
            (name, trimmed)
        })
        .collect();
    let bytes = safetensors::serialize(views, &Some(metadata)).expect("write the weights");
    NetworkWeights::from_bytes(&bytes, "the committed weights without the gate").expect("load")
}

/// The first `FRAMES` frames of a still Cornell box under the learned denoiser, with `weights`
/// (the committed ones if `None`) and the gated filter on in the frames `filter_on` says.
fn frames(weights: Option<&NetworkWeights>, filter_on: impl Fn(usize) -> bool) -> Vec<Vec<f32>> {
    let ctx = context(false);
    let settings = |frame| Settings {
        denoiser: Denoiser::Neural,
        neural: NeuralParams {
            gated_filter: filter_on(frame),
        },
        ..Settings::default()
    };
    let mut r = Renderer::new(&ctx, scene("cornell-box"), 32, 24, settings(0)).expect("renderer");
    if let Some(weights) = weights {
        let path = r.neural_path();
        r.set_neural_network(weights, path)
            .expect("the weights run");
    }
    let mut images = Vec::new();
    for frame in 0..FRAMES {
        r.set_settings(settings(frame)).expect("settings");
        let image = r.render_and_read().expect("frame");
        images.push(image.pixels.iter().flat_map(|p| p[..3].to_vec()).collect());
    }
    assert_eq!(
        r.accumulated_frames() as usize,
        FRAMES,
        "the filter's switch must not restart accumulation"
    );
    drop(r);
    assert_no_validation_messages(&ctx);
    images
}

/// The largest difference between two images, relative to the larger's mean.
fn difference(a: &[f32], b: &[f32]) -> f32 {
    let mean = |x: &[f32]| x.iter().sum::<f32>() / x.len() as f32;
    let scale = mean(a).max(mean(b)).max(1e-6);
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f32::max)
        / scale
}

#[test]
fn turned_off_the_filter_gives_what_the_weights_without_it_give_and_keeps_the_history() {
    let ungated = without_gate();
    let reference = frames(Some(&ungated), |_| true);
    let filtered = frames(None, |_| true);
    let off = frames(None, |_| false);
    // Turned off after two filtered frames: the history is the unfiltered output's either way.
    let turned_off = frames(None, |frame| frame < 2);
    for frame in 0..FRAMES {
        let d = difference(&off[frame], &reference[frame]);
        assert!(d < 1e-4, "frame {frame}: off, {d} from the ungated weights");
    }
    for frame in 2..FRAMES {
        let d = difference(&turned_off[frame], &reference[frame]);
        assert!(
            d < 1e-4,
            "frame {frame}: turned off, {d} from the ungated weights"
        );
    }
    let d = difference(&filtered[0], &reference[0]);
    assert!(d > 1e-2, "the filter must change the first frame ({d})");
}
