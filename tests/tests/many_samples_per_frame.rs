//! Many samples per pixel in one frame give the image that as many samples over several frames
//! give: 512 samples in one frame of the Cornell box against 32 accumulated frames of 16, mean
//! per channel within 2%, for path tracing and BDPT. llvmpipe (lavapipe) ends every loop of a
//! shader invocation once their iterations add up to 65535, which a pixel's sample loop reached
//! after about 200 Cornell-box paths: 512 samples in one frame came out 60% dark until the
//! samples were traced in batches of a few per dispatch.

use lucid_engine::capture::ImageData;
use lucid_engine::metrics;
use lucid_passes::renderer::{Algorithm, SamplesPerPixel, Settings};
use lucid_tests::render::{render_accumulated, scene};
use std::time::Instant;

const SIZE: u32 = 32;
const TOLERANCE: f64 = 0.02;

fn render(algorithm: Algorithm, spp: u32, frames: u32) -> ImageData {
    let start = Instant::now();
    let settings = Settings {
        algorithm,
        samples_per_pixel: SamplesPerPixel::new(spp).expect("at least one sample per pixel"),
        ..Settings::default()
    };
    let image = render_accumulated(scene("cornell-box"), (SIZE, SIZE), settings, frames);
    eprintln!(
        "{algorithm:?}: {frames} frame(s) of {spp} spp in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    image
}

fn one_frame_matches_many(algorithm: Algorithm) {
    let one = metrics::mean_per_channel(&render(algorithm, 512, 1)).expect("mean");
    let many = metrics::mean_per_channel(&render(algorithm, 16, 32)).expect("mean");
    eprintln!("{algorithm:?}: one frame {one:?}, 32 frames {many:?}");
    for c in 0..3 {
        let ratio = one[c] / many[c];
        assert!(
            (ratio - 1.0).abs() < TOLERANCE,
            "{algorithm:?} channel {c}: 512 spp in one frame {:.4} vs 32 frames of 16 {:.4} \
             (ratio {ratio:.3})",
            one[c],
            many[c]
        );
    }
}

#[test]
fn path_tracing_512_spp_in_one_frame() {
    one_frame_matches_many(Algorithm::PathTracing);
}

#[test]
fn bdpt_512_spp_in_one_frame() {
    one_frame_matches_many(Algorithm::Bidirectional);
}
