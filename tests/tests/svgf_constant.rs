//! SVGF and the per-frame a-trous filter keep a noise-free constant exactly: the white furnace (a
//! diffuse sphere of albedo 0.8 in a uniform environment, which path tracing renders without noise)
//! at an environment radiance that half precision cannot hold (0.7), so the filter's `rgba16f`
//! steps must round it. Every pixel of the sphere's centre must be 0.8 times 0.7 rounded to half
//! precision, to float precision: a store that truncated instead (as lavapipe's and NVIDIA's own
//! conversions do) made both filters 0.19% darker here, since every a-trous step's normalised sum
//! lands just below the value and truncation then drops a whole step of half precision.

use glam::Vec3;
use half::f16;
use lucid_engine::scene::Environment;
use lucid_tests::render::scene;
use lucid_tests::svgf::{frame, renderer, settings, Method, SIZE};

/// The environment's radiance: between two half-precision values, nearer the upper.
const RADIANCE: f32 = 0.7;
/// The furnace sphere's albedo (`engine/src/scene/builtin/furnace.rs`).
const ALBEDO: f32 = 0.8;
/// Frames rendered by each method.
const FRAMES: usize = 8;

#[test]
fn svgf_keeps_a_constant_that_half_precision_rounds() {
    let ctx = lucid_tests::context(false);
    let mut furnace = scene("furnace");
    furnace.environment = Environment::Constant(Vec3::splat(RADIANCE));
    let want = ALBEDO * f16::from_f32(RADIANCE).to_f32();
    assert!(
        f16::from_f32(RADIANCE).to_f32() > RADIANCE,
        "the radiance rounds up to half precision, so truncating it is an error"
    );
    for method in [Method::PerFrame, Method::Svgf] {
        let mut r = renderer(&ctx, furnace.clone(), settings(method, 8));
        for t in 0..FRAMES {
            let image = frame(&mut r);
            for y in 0..SIZE {
                for x in 0..SIZE {
                    let centre = SIZE as f32 / 2.0;
                    let d = (x as f32 + 0.5 - centre).hypot(y as f32 + 0.5 - centre);
                    if d >= 0.2 * SIZE as f32 {
                        continue;
                    }
                    let got = image.get(x, y).expect("inside the image");
                    for &c in &got[..3] {
                        assert!(
                            (c - want).abs() <= 2e-5 * want,
                            "{method:?}, frame {t}, pixel ({x}, {y}): {c}, want {want} (0.8 times \
                             {RADIANCE} rounded to half precision)"
                        );
                    }
                }
            }
        }
    }
    lucid_tests::assert_no_validation_messages(&ctx);
}
