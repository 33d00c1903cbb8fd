//! The emission supersampled at emitters' edges (`Settings::edge_emission`): where an emitter's
//! edge crosses a pixel, the emission the denoisers add back is the pixel's coverage, not what one
//! sample saw; every other pixel keeps the light transport's own.

use lucid_engine::capture::rec709_luminance;
use lucid_passes::denoise::neural::{record_image, RECORD_EMISSION};
use lucid_passes::renderer::{Denoiser, EdgeEmission, Renderer, Settings};
use lucid_tests::render::scene;
use lucid_tests::{assert_no_validation_messages, context};

const SIZE: u32 = 48;

/// The luminance of the emission the learned denoiser reads in the first frame of a still Cornell
/// box, per pixel.
fn first_frame_emission(edge_emission: EdgeEmission) -> Vec<f32> {
    let ctx = context(false);
    let settings = Settings {
        denoiser: Denoiser::Neural,
        edge_emission,
        ..Settings::default()
    };
    let mut r = Renderer::new(&ctx, scene("cornell-box"), SIZE, SIZE, settings).expect("renderer");
    let (_, record) = r.render_and_read_record().expect("frame");
    drop(r);
    assert_no_validation_messages(&ctx);
    let emission = record_image(&record, (SIZE, SIZE), RECORD_EMISSION).expect("emission");
    emission
        .pixels
        .iter()
        .map(|&p| rec709_luminance(p))
        .collect()
}

#[test]
fn the_light_edges_get_their_coverage_and_nothing_else_changes() {
    let traced = first_frame_emission(EdgeEmission::Off);
    let supersampled = first_frame_emission(EdgeEmission::On);
    let light = traced.iter().copied().fold(0.0, f32::max);
    assert!(light > 0.0, "the light is in view");
    // One sample a pixel sees the light or not.
    assert!(
        traced.iter().all(|&e| e == 0.0 || e == light),
        "one sample: the light's emission or none"
    );
    let changed: Vec<f32> = traced
        .iter()
        .zip(&supersampled)
        .filter(|(a, b)| a != b)
        .map(|(_, &b)| b)
        .collect();
    let share = changed.len() as f64 / traced.len() as f64;
    eprintln!("{} pixels changed ({:.1}%)", changed.len(), 100.0 * share);
    assert!(
        !changed.is_empty() && share < 0.1,
        "only the light's edge pixels change: {:.1}% did",
        100.0 * share
    );
    assert!(
        changed.iter().all(|&e| (0.0..=light).contains(&e)),
        "a coverage of the light lies between none and all of it"
    );
    let partial = changed
        .iter()
        .filter(|&&e| e > 0.1 * light && e < 0.9 * light)
        .count();
    assert!(
        partial > 0,
        "edge pixels partly covered by the light: {changed:?}"
    );
}

/// Unless told otherwise, the learned denoiser reads the supersampled emission.
#[test]
fn the_learned_denoiser_supersamples_the_edges_by_default() {
    let by_default = first_frame_emission(EdgeEmission::default());
    assert_eq!(by_default, first_frame_emission(EdgeEmission::On));
    assert_ne!(by_default, first_frame_emission(EdgeEmission::Off));
}
