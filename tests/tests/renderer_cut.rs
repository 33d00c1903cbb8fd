//! `Renderer::cut`: the next frame starts a new shot, so accumulation and the denoisers' histories
//! start afresh.

use lucid_passes::renderer::{Denoiser, Renderer, Settings};
use lucid_tests::render::scene;
use lucid_tests::{assert_no_validation_messages, context};

/// The fourth frame of a still Cornell box with `denoiser`, with a cut before it or not.
fn fourth_frame(denoiser: Denoiser, cut: bool) -> (Vec<[f32; 4]>, u32) {
    let ctx = context(false);
    let settings = Settings {
        denoiser,
        ..Settings::default()
    };
    let mut r = Renderer::new(&ctx, scene("cornell-box"), 24, 24, settings).expect("renderer");
    for _ in 0..3 {
        r.render().expect("frame");
    }
    if cut {
        r.cut();
    }
    let accumulated = r.accumulated_frames();
    let image = r.render_and_read().expect("frame");
    drop(r);
    assert_no_validation_messages(&ctx);
    (image.pixels, accumulated)
}

#[test]
fn a_cut_restarts_accumulation_and_drops_the_denoisers_history() {
    let (_, accumulated) = fourth_frame(Denoiser::None, true);
    assert_eq!(accumulated, 0, "accumulation restarts");
    for denoiser in [Denoiser::Svgf, Denoiser::Neural] {
        let (cut, _) = fourth_frame(denoiser, true);
        let (kept, _) = fourth_frame(denoiser, false);
        // The frames trace the same samples; only the history differs.
        assert_ne!(
            cut, kept,
            "{denoiser:?}: the history must not be used after a cut"
        );
    }
}
