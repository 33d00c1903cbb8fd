//! BDPT's camera pass walks next-event estimation's shadow ray together with the first
//! connection's where `bdpt::pairs_shadow_rays` says so (the Cornell box), and at once otherwise
//! (the same box with a small sphere behind its back wall, which no ray reaches). With connection
//! roulette off, which is the only thing that reads NEE's share before its ray is walked, the two
//! render the same image bit for bit: the paired walks find the same occluders as the single ones.

use glam::Vec3;
use lucid_engine::scene::{Material, SceneFeatures};
use lucid_passes::light_transport::bdpt::pairs_shadow_rays;
use lucid_passes::renderer::{Algorithm, SamplesPerPixel, Settings};
use lucid_tests::render::{render_accumulated, scene};

#[test]
fn paired_shadow_rays_render_the_image_of_single_ones() {
    let paired = scene("cornell-box");
    let mut single = scene("cornell-box");
    let hidden = single.add_material(Material::diffuse("hidden", Vec3::ONE));
    single.add_sphere(Vec3::new(0.0, 0.0, -3.0), 0.01, hidden);
    assert!(pairs_shadow_rays(&SceneFeatures::from_scene(&paired)));
    assert!(!pairs_shadow_rays(&SceneFeatures::from_scene(&single)));
    let settings = Settings {
        algorithm: Algorithm::Bidirectional,
        samples_per_pixel: SamplesPerPixel::new(4).unwrap(),
        bdpt_connection_roulette: 0.0,
        ..Settings::default()
    };
    let with_pairs = render_accumulated(paired, (32, 32), settings, 2);
    let one_by_one = render_accumulated(single, (32, 32), settings, 2);
    assert!(
        with_pairs.pixels.iter().any(|p| p[0] > 0.0),
        "a black image"
    );
    assert_eq!(
        with_pairs.pixels, one_by_one.pixels,
        "paired and single shadow rays rendered different images"
    );
}
