//! White furnace: a diffuse sphere of albedo a inside a uniform environment L must render as a·L,
//! the background as L (within 1%), for path tracing at every path depth that reaches the sky.

use lucid_passes::renderer::{SamplesPerPixel, Settings};
use lucid_tests::render::{render_accumulated, scene};

#[test]
fn furnace_matches_the_analytic_radiance() {
    let furnace = scene("furnace");
    let analytic = furnace
        .analytic_radiance()
        .expect("furnace has a closed form");
    let size = 64;
    let image = render_accumulated(
        furnace,
        (size, size),
        Settings {
            samples_per_pixel: SamplesPerPixel::new(8).unwrap(),
            ..Settings::default()
        },
        4,
    );
    let pixel = |x: u32, y: u32| image.get(x, y).unwrap();
    // The sphere fills the centre; the corners see only the environment.
    let mut checked = (0, 0);
    for y in 0..size {
        for x in 0..size {
            let d = ((x as f32 + 0.5 - size as f32 / 2.0).powi(2)
                + (y as f32 + 0.5 - size as f32 / 2.0).powi(2))
            .sqrt();
            let (want, region) = if d < size as f32 * 0.2 {
                (analytic.object, &mut checked.0)
            } else if d > size as f32 * 0.5 {
                (analytic.background, &mut checked.1)
            } else {
                continue;
            };
            let got = pixel(x, y);
            for c in 0..3 {
                let rel = (got[c] - want[c]).abs() / want[c];
                assert!(
                    rel < 0.01,
                    "pixel ({x},{y}) channel {c}: {} vs analytic {}",
                    got[c],
                    want[c]
                );
            }
            *region += 1;
        }
    }
    assert!(
        checked.0 > 100 && checked.1 > 100,
        "both regions were checked: {checked:?}"
    );
}

#[test]
fn furnace_needs_a_second_bounce() {
    // With max_depth 1 only emitters (none here) and the sky are seen directly: the sphere is black.
    // This guards the depth convention that the Mitsuba comparison relies on.
    let image = render_accumulated(
        scene("furnace"),
        (32, 32),
        Settings {
            max_depth: 1,
            ..Settings::default()
        },
        1,
    );
    let centre = image.get(16, 16).unwrap();
    assert_eq!(&centre[..3], &[0.0, 0.0, 0.0]);
    let corner = image.get(0, 0).unwrap();
    assert!(
        corner[0] > 0.5,
        "the sky is seen directly at depth 1: {corner:?}"
    );
}
