//! Random object materials and light colours.

use glam::Vec3;

use super::rng::Rng;
use crate::scene::Material;

/// Linear F0 colours of common metals: gold, copper, silver, aluminium,
/// iron.
const METALS: [Vec3; 5] = [
    Vec3::new(1.0, 0.766, 0.336),
    Vec3::new(0.955, 0.638, 0.538),
    Vec3::new(0.972, 0.96, 0.915),
    Vec3::new(0.913, 0.922, 0.924),
    Vec3::new(0.562, 0.565, 0.578),
];

/// A material for object `index`: diffuse (45 %), conductor (25 %, a real
/// or random metal colour, GGX alpha 0.02 to 0.5), dielectric (20 %, IOR
/// 1.5, smooth or rough, sometimes tinted) or emissive (10 %). The name
/// says which, e.g. `object-3-glass`.
pub fn object_material(rng: &mut Rng, index: u32) -> Material {
    let name = |kind: &str| format!("object-{index}-{kind}");
    match rng.weighted(&[0.45, 0.25, 0.2, 0.1]) {
        0 => Material::diffuse(&name("diffuse"), rng.color(0.05, 0.9)),
        1 => {
            let color = if rng.chance(0.8) {
                METALS[rng.index(METALS.len())]
            } else {
                rng.color(0.3, 1.0)
            };
            Material::conductor(&name("metal"), color, rng.range(0.02, 0.5))
        }
        2 => {
            let alpha = if rng.chance(0.6) {
                0.0
            } else {
                rng.range(0.05, 0.4)
            };
            let mut glass = Material::dielectric(&name("glass"), 1.5, alpha);
            if rng.chance(0.3) {
                glass.base_color = rng.color(0.6, 1.0);
            }
            glass
        }
        _ => Material::emissive(&name("emissive"), light_tint(rng) * rng.range(1.0, 8.0)),
    }
}

/// A colour of brightness about `lo` to `hi` whose channels stray from
/// each other by up to the fraction `spread` (0 is grey).
pub fn muted(rng: &mut Rng, lo: f32, hi: f32, spread: f32) -> Vec3 {
    let grey = rng.range(lo, hi);
    (grey * (Vec3::ONE + rng.color(-spread, spread))).clamp(Vec3::ZERO, Vec3::ONE)
}

/// A light colour with its largest channel 1: mostly a white between warm
/// and cool, sometimes saturated.
pub fn light_tint(rng: &mut Rng) -> Vec3 {
    let c = if rng.chance(0.1) {
        rng.color(0.1, 1.0)
    } else {
        Vec3::new(1.0, 0.85, 0.7).lerp(Vec3::new(0.85, 0.92, 1.0), rng.unit())
    };
    c / c.max_element()
}
