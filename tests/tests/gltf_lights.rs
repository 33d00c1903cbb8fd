//! `KHR_lights_punctual` in the units the extension gives (candela, lux) and light selection that
//! does not starve dim or coloured lights, rendered on lavapipe and checked against closed forms.

use glam::{Quat, Vec3};
use lucid_engine::capture::ImageData;
use lucid_engine::scene::{LightDistribution, Scene, LUMENS_PER_WATT};
use lucid_passes::renderer::Algorithm;
use lucid_tests::gltf::{plane, Doc};
use lucid_tests::render::render_once;

const ALBEDO: f32 = 0.8;

/// One frame of direct light only: the closed forms below are for one bounce.
fn render(scene: Scene, algorithm: Algorithm, spp: u32, size: u32) -> ImageData {
    render_once(scene, algorithm, spp, 2, size)
}

/// glTF `rotation` of a node whose -Z axis (where lights shine and cameras look) points along
/// `dir`.
fn aim(dir: Vec3) -> String {
    let q = Quat::from_rotation_arc(Vec3::NEG_Z, dir.normalize());
    format!(r#""rotation": [{}, {}, {}, {}]"#, q.x, q.y, q.z, q.w)
}

/// A white (albedo 0.8) floor of side `2 * half` at y = 0.
fn floor(doc: &mut Doc, half: f32) {
    let (positions, indices) = plane(half);
    let p = doc.floats(&positions);
    let i = doc.indices(&indices);
    let m = doc.lambertian([ALBEDO; 3], "");
    let mesh = doc.mesh(&[("POSITION", p)], Some(i), Some(m));
    doc.node(&format!(r#"{{"mesh": {mesh}}}"#));
}

/// The mean of the central `k`x`k` pixels.
fn centre(image: &ImageData, k: u32) -> [f64; 3] {
    let (x0, y0) = ((image.width - k) / 2, (image.height - k) / 2);
    let mut sum = [0.0; 3];
    for y in y0..y0 + k {
        for x in x0..x0 + k {
            let p = image.get(x, y).unwrap();
            for c in 0..3 {
                sum[c] += f64::from(p[c]) / f64::from(k * k);
            }
        }
    }
    sum
}

/// The floor lit by `light` (its JSON) on a node 1 m above the origin aimed down, seen from
/// straight above through a narrow field of view.
fn lit_floor(light: &str) -> Scene {
    let mut doc = Doc::new();
    floor(&mut doc, 2.0);
    doc.light(
        light,
        &format!(r#"{}, "translation": [0, 1, 0]"#, aim(Vec3::NEG_Y)),
    );
    doc.camera(
        0.05,
        &format!(r#"{}, "translation": [0, 2, 0]"#, aim(Vec3::NEG_Y)),
    );
    doc.load("lamp.gltf")
}

#[test]
fn punctual_lights_are_in_candela_and_lux() {
    // Lambertian floor 1 m under the light: L = albedo / π × E, with E = I / 683 W/m² for I
    // candela at 1 m, and E = lux / 683 for a directional light.
    let expected = |e: f64| f64::from(ALBEDO) / std::f64::consts::PI * e;
    let mut measured = Vec::new();
    for (light, e) in [
        (r#"{"type": "point", "intensity": 1000}"#, 1000.0),
        (r#"{"type": "point", "intensity": 500}"#, 500.0),
        (
            r#"{"type": "spot", "intensity": 1000, "spot": {"outerConeAngle": 0.5}}"#,
            1000.0,
        ),
        (r#"{"type": "directional", "intensity": 1000}"#, 1000.0),
        (
            r#"{"type": "point", "intensity": 1000, "color": [1, 0.5, 0.25]}"#,
            1000.0,
        ),
    ] {
        let scene = lit_floor(light);
        let colour = if light.contains("color") {
            [1.0, 0.5, 0.25]
        } else {
            [1.0; 3]
        };
        let got = centre(&render(scene, Algorithm::PathTracing, 1, 16), 4);
        for c in 0..3 {
            let want = expected(e / f64::from(LUMENS_PER_WATT)) * colour[c];
            let rel = (got[c] - want).abs() / want;
            println!(
                "{light}: channel {c} {:.5} vs {want:.5} ({:.3}%)",
                got[c],
                100.0 * rel
            );
            assert!(rel < 0.005, "{light}: channel {c}: {} vs {want}", got[c]);
        }
        measured.push(got[0]);
    }
    let ratio = measured[0] / measured[1];
    println!("1000 cd / 500 cd: {ratio:.4}");
    assert!((ratio - 2.0).abs() < 0.01, "{ratio}");
}

/// Two spot lights aimed at the floor side by side, their pools of light apart: a bright white
/// one (10000 cd) and a dim pure-blue one (1000 cd), or only the blue one; seen from above.
fn two_spots(with_white: bool) -> Scene {
    let mut doc = Doc::new();
    floor(&mut doc, 2.0);
    let spot = r#""spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.4}"#;
    if with_white {
        doc.light(
            &format!(r#"{{"type": "spot", "intensity": 10000, {spot}}}"#),
            &format!(r#"{}, "translation": [-1, 1, 0]"#, aim(Vec3::NEG_Y)),
        );
    }
    doc.light(
        &format!(r#"{{"type": "spot", "intensity": 1000, "color": [0, 0, 1], {spot}}}"#),
        &format!(r#"{}, "translation": [1, 1, 0]"#, aim(Vec3::NEG_Y)),
    );
    doc.camera(
        1.0,
        &format!(r#"{}, "translation": [0, 3, 0]"#, aim(Vec3::NEG_Y)),
    );
    doc.load("two-spots.gltf")
}

#[test]
fn a_dim_blue_spot_beside_a_bright_white_one_gets_samples() {
    let size = 64;
    let both = two_spots(true);
    let dist = LightDistribution::build(&both);
    let p_blue = dist.table.pdf[1];
    println!(
        "blue selection probability {p_blue:.3} (by luminance alone: {:.4})",
        {
            let blue = 0.0722 * 1000.0;
            blue / (blue + 10000.0)
        }
    );
    // The blue light's pool: the pixels it lights when it is alone (then every sample picks it).
    let alone = render(two_spots(false), Algorithm::PathTracing, 1, size);
    let pool: Vec<usize> = (0..alone.pixels.len())
        .filter(|&i| alone.pixels[i][2] > 0.0)
        .collect();
    assert!(pool.len() > 200, "{} pixels in the pool", pool.len());
    let image = render(both.clone(), Algorithm::PathTracing, 1, size);
    let lit = pool.iter().filter(|&&i| image.pixels[i][2] > 0.0).count();
    let share = lit as f32 / pool.len() as f32;
    println!(
        "1 spp: {:.1}% of the blue pool's {} pixels lit",
        100.0 * share,
        pool.len()
    );
    // The table alone would light a share p_blue of them (each pixel's one light sample picks the
    // blue light with that probability); resampling four candidates keeps the blue one wherever
    // it is drawn, since the white spot brings nothing there.
    assert!(p_blue > 0.25);
    assert!(share > 0.5, "the blue pool is mostly black: {share}");
    // And the blue light's contribution is what it is alone (unbiased).
    const SPP: u32 = 64;
    let blue = |image: &ImageData| {
        pool.iter()
            .map(|&i| f64::from(image.pixels[i][2]))
            .sum::<f64>()
    };
    let want = blue(&render(two_spots(false), Algorithm::PathTracing, SPP, size));
    let got = blue(&render(both, Algorithm::PathTracing, SPP, size));
    println!("blue in the pool: {got:.3} with the white spot, {want:.3} alone");
    assert!((got - want).abs() < 0.01 * want, "{got} vs {want}");
}

/// A black, emissive square of side 0.5 facing `facing` (±Y), `strength` × `colour`, centred at
/// `at`.
fn emitter(doc: &mut Doc, colour: [f32; 3], strength: f32, facing: f32, at: Vec3) {
    doc.uses("KHR_materials_emissive_strength");
    doc.uses("KHR_materials_specular");
    let (positions, indices) = plane(0.25);
    let p = doc.floats(&positions);
    let i = doc.indices(&indices);
    let m = doc.material(&format!(
        r#"{{"pbrMetallicRoughness": {{"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
            "emissiveFactor": {colour:?},
            "extensions": {{"KHR_materials_emissive_strength": {{"emissiveStrength": {strength}}},
                "KHR_materials_specular": {{"specularFactor": 0}}}}}}"#
    ));
    let mesh = doc.mesh(&[("POSITION", p)], Some(i), Some(m));
    let q = if facing > 0.0 {
        Quat::IDENTITY
    } else {
        Quat::from_rotation_x(std::f32::consts::PI)
    };
    doc.node(&format!(
        r#"{{"mesh": {mesh}, "rotation": [{}, {}, {}, {}], "translation": [{}, {}, {}]}}"#,
        q.x, q.y, q.z, q.w, at.x, at.y, at.z
    ));
}

#[test]
fn area_lights_stay_unbiased_beside_a_brighter_one() {
    // A dim blue square light 0.5 m above the floor facing it, and a white one 20 times as
    // bright facing up (it lights nothing here but takes most of the power-based selection).
    // The floor under the blue light's centre: L = albedo × L_e × F, with F the form factor of
    // the square to a parallel patch under its centre (four corner rectangles of X = Y = 0.5):
    // F = 4 / (2π) × 2 X / sqrt(1 + X²) × atan(Y / sqrt(1 + X²)).
    let (radiance, h, half) = (2.0f64, 0.5f64, 0.25f64);
    let x = half / h;
    let s = (1.0 + x * x).sqrt();
    let form = 4.0 / (2.0 * std::f64::consts::PI) * 2.0 * x / s * (x / s).atan();
    let want = f64::from(ALBEDO) * radiance * form;
    let mut doc = Doc::new();
    floor(&mut doc, 3.0);
    emitter(
        &mut doc,
        [0.0, 0.0, 1.0],
        radiance as f32,
        -1.0,
        Vec3::new(1.0, h as f32, 0.0),
    );
    emitter(
        &mut doc,
        [1.0, 1.0, 1.0],
        40.0,
        1.0,
        Vec3::new(-1.0, h as f32, 0.0),
    );
    // Looking at the spot under the blue light from the side, below the light.
    let eye = Vec3::new(2.5, 0.3, 0.0);
    doc.camera(
        0.02,
        &format!(
            r#"{}, "translation": [{}, {}, {}]"#,
            aim(Vec3::new(1.0, 0.0, 0.0) - eye),
            eye.x,
            eye.y,
            eye.z
        ),
    );
    let scene = doc.load("two-squares.gltf");
    let dist = LightDistribution::build(&scene);
    println!("selection of a blue triangle: {:.3}", dist.table.pdf[0]);
    for algorithm in Algorithm::ALL {
        let got = centre(&render(scene.clone(), algorithm, 4096, 8), 4)[2];
        let rel = (got - want).abs() / want;
        println!(
            "{}: {got:.5} vs closed form {want:.5} ({:.2}%)",
            algorithm.short_name(),
            100.0 * rel
        );
        assert!(rel < 0.01, "{}: {got} vs {want}", algorithm.short_name());
    }
}
