//! `--algo auto` on lavapipe, small: the calibration measures the candidates on each scene and the
//! same quality target picks bidirectional path tracing where light reaches the room only through
//! gaps (`covered-light`, where path tracing's next-event estimation is blocked) and path tracing
//! with a denoiser on the Cornell box (where a denoised path-traced frame is cheapest). Nothing
//! here names the expected configuration beyond its algorithm and whether it denoises: each pick
//! is what the measurements give.

use lucid_engine::scene::builtin::{build_with, BuildOptions};
use lucid_passes::renderer::{Algorithm, Denoiser, Renderer, SamplesPerPixel, Settings};
use lucid_passes::tradeoff::{calibrate, Calibration, CalibrationOptions, Choice, Goal, Metric};
use lucid_tests::{assert_no_validation_messages, context};

const SIZE: u32 = 48;

/// The target both scenes are calibrated for: a real-time frame whose DSSIM is at most 0.5.
const GOAL: Goal = Goal::Quality {
    metric: Metric::Dssim,
    target: 0.5,
};

/// Calibrates `name` (the tessellated scenes at 5% of their triangles) over both algorithms,
/// without a denoiser and with SVGF, at 1 and 2 samples per pixel (the learned denoiser is left
/// out only to keep the test short on lavapipe), prints the measurements and returns the choice.
fn calibrated_choice(name: &str) -> (Calibration, Choice) {
    let ctx = context(false);
    let scene = build_with(name, &BuildOptions { detail: 0.05 }).expect("scene");
    let mut renderer = Renderer::new(&ctx, scene, SIZE, SIZE, Settings::default()).unwrap();
    let options = CalibrationOptions {
        denoisers: vec![Denoiser::None, Denoiser::Svgf],
        spp: [1, 2].map(|n| SamplesPerPixel::new(n).unwrap()).to_vec(),
        ..CalibrationOptions::default()
    };
    let mut frames = 0;
    let calibration = calibrate(&mut renderer, &options, &mut || frames += 1).unwrap();
    assert_eq!(frames, options.total_frames(calibration.results.len()));
    assert_eq!(calibration.results.len(), 8, "{:?}", calibration.notes);
    assert_eq!(
        *renderer.settings(),
        Settings::default(),
        "settings restored"
    );
    assert_no_validation_messages(&ctx);
    let choice = calibration.choose(GOAL).unwrap();
    for r in &calibration.results {
        let m = r.last().unwrap();
        eprintln!(
            "{name} {:<12} {:8.2} ms  DSSIM {:.4}  FLIP {:.4}",
            r.config.name(),
            r.ms_per_frame(),
            m.dssim,
            m.flip
        );
    }
    eprintln!("{name}: {}", choice.reason);
    // The choice is the cheapest measured configuration meeting the target.
    assert!(choice.met, "{}", choice.reason);
    assert!(choice.error <= 0.5);
    for r in &calibration.results {
        let error = r.last().unwrap().dssim;
        assert!(
            error > 0.5 || r.ms_per_frame() >= choice.ms_per_frame,
            "{} meets the target faster: {}",
            r.config.name(),
            choice.reason
        );
    }
    (calibration, choice)
}

#[test]
fn auto_picks_bidirectional_path_tracing_where_the_light_is_hidden() {
    let (_, choice) = calibrated_choice("covered-light");
    assert_eq!(
        choice.config.algorithm,
        Algorithm::Bidirectional,
        "{}",
        choice.reason
    );
    assert!(
        choice.reason.contains("no path tracing does"),
        "{}",
        choice.reason
    );
}

#[test]
fn auto_picks_denoised_path_tracing_on_the_cornell_box() {
    let (calibration, choice) = calibrated_choice("cornell-box");
    assert_eq!(
        choice.config.algorithm,
        Algorithm::PathTracing,
        "{}",
        choice.reason
    );
    assert_ne!(choice.config.denoiser, Denoiser::None, "{}", choice.reason);
    // Bidirectional path tracing can meet the target too, at a higher cost.
    assert!(
        calibration.results.iter().any(|r| {
            r.config.algorithm == Algorithm::Bidirectional && r.last().unwrap().dssim <= 0.5
        }),
        "{}",
        choice.reason
    );
}
