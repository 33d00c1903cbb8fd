//! Shadows from the sun: its shadow rays are walked from where they leave the scene's box
//! (`light_shadow_ray` in `shaders/common/lights.glsl`), so the box must hold every occluder, also
//! after an instance moves out of where the scene first lay. A slab hangs over a ground plane under
//! a sun straight above, against a black sky: the ground beneath it gets no light at all, the
//! ground beside it does, and so it stays after the slab is lifted well above the scene's first box.

use glam::{Affine3A, Quat, Vec3};
use lucid_engine::scene::builtin::shapes;
use lucid_engine::scene::{Camera, Material, Scene, Sun};
use lucid_passes::renderer::{Renderer, SamplesPerPixel, Settings};
use lucid_tests::{assert_no_validation_messages, context};

const SIZE: u32 = 16;

/// The ground (8 m square at y = 0) and the slab (2 m square, 0.1 m thick, its middle at y = 1),
/// lit by the sun straight above; returns the scene and the slab's instance.
fn scene() -> (Scene, usize) {
    let mut scene = Scene::new("sun-shadows");
    let grey = scene.add_material(Material::diffuse("grey", Vec3::splat(0.5)));
    let ground = scene.add_mesh(shapes::rectangle("ground", grey));
    scene.add_instance(
        ground,
        Affine3A::from_scale_rotation_translation(
            Vec3::splat(4.0),
            Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2),
            Vec3::ZERO,
        ),
        None,
    );
    let slab = scene.add_mesh(shapes::cube("slab", grey));
    let slab = scene.add_instance(slab, slab_at(1.0), None) as usize;
    scene.sun = Some(Sun {
        direction: Vec3::Y,
        irradiance: Vec3::splat(5.0),
        angular_radius: 0.00465,
    });
    (scene, slab)
}

fn slab_at(height: f32) -> Affine3A {
    Affine3A::from_scale_rotation_translation(
        Vec3::new(1.0, 0.05, 1.0),
        Quat::IDENTITY,
        Vec3::new(0.0, height, 0.0),
    )
}

/// The mean radiance of the ground seen straight down from half a metre above (x, 0, 0): direct
/// sunlight and one bounce.
fn ground_seen_from(renderer: &mut Renderer, x: f32) -> f32 {
    renderer.set_camera(Camera::look_at(
        Vec3::new(x, 0.5, 0.0),
        Vec3::new(x, 0.0, 0.0),
        Vec3::Z,
        40.0,
    ));
    let image = renderer.render_and_read().expect("frame");
    image.pixels.iter().map(|p| p[0] + p[1] + p[2]).sum::<f32>() / image.pixels.len() as f32
}

#[test]
fn the_sun_leaves_the_ground_under_a_slab_dark_wherever_the_slab_moves() {
    let ctx = context(false);
    let (scene, slab) = scene();
    let settings = Settings {
        samples_per_pixel: SamplesPerPixel::new(4).unwrap(),
        max_depth: 2,
        accumulate: false,
        ..Settings::default()
    };
    let mut renderer = Renderer::new(&ctx, scene, SIZE, SIZE, settings).expect("renderer");
    for height in [1.0, 3.0] {
        renderer
            .set_instance_transform(slab, slab_at(height))
            .expect("move the slab");
        let beneath = ground_seen_from(&mut renderer, 0.0);
        let beside = ground_seen_from(&mut renderer, 3.0);
        assert_eq!(beneath, 0.0, "slab at {height} m: light under it");
        // 5 W/m² on a grey diffuse ground: 0.5 / pi x 5 a channel.
        assert!(
            (beside / 3.0 - 2.5 / std::f32::consts::PI).abs() < 0.05,
            "slab at {height} m: the lit ground's radiance {}",
            beside / 3.0
        );
    }
    drop(renderer);
    assert_no_validation_messages(&ctx);
}
