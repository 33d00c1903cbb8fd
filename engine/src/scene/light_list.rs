//! The light distribution used by next-event estimation and BDPT's light subpaths.
//!
//! Every emissive triangle (per instance), emissive sphere and punctual
//! light becomes one entry with its emitted power, measured on its strongest
//! colour channel ([`selection_power`]): `π · area · L` for a one-sided
//! Lambertian emitting triangle, `π · 4πr² · L` for a sphere, and
//! [`PunctualLight::power`] for point and spot lights. NEE picks an entry with
//! probability
//!
//! `p_i = (1 − u) · P_i / ΣP + u / n`
//!
//! (`u` = [`UNIFORM_SELECTION`], `n` the entries with power), then samples a
//! point on it: half in proportion to power, half uniformly, so that a dim or a
//! coloured light still gets at least `u / n` of the samples (by luminance alone a
//! pure-blue light, luminance 0.07 of its power, was all but never picked). The
//! shaders recompute `p_i` from an emitter's power for MIS (`light_selection` in
//! `shaders/common/lights.glsl`, from `GpuSceneParams::light`). The sun and the
//! environment are not in the table; they are sampled as separate strategies
//! and combined with multiple importance sampling.

use glam::Vec3;

use super::{AliasTable, PunctualLight, Scene};

/// The share of light selection spread uniformly over the lights with power (the rest goes in
/// proportion to power).
pub const UNIFORM_SELECTION: f32 = 0.5;

/// The power by which lights are selected, of an emission or intensity (per channel): its
/// largest channel, so that a light's colour does not make it dimmer to sampling than the
/// strongest channel it lights with.
pub fn selection_power(c: Vec3) -> f32 {
    c.max_element().max(0.0)
}

/// The emitter behind one light-table entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSource {
    /// An emissive triangle of a mesh instance.
    Triangle {
        /// Index into `Scene::instances`.
        instance: u32,
        /// Triangle index within the instanced mesh.
        triangle: u32,
    },
    /// An emissive analytic sphere (index into `Scene::spheres`).
    Sphere {
        /// Index into `Scene::spheres`.
        sphere: u32,
    },
    /// A point or spot light (index into `Scene::punctual_lights`).
    Punctual {
        /// Index into `Scene::punctual_lights`.
        light: u32,
    },
}

/// One light with its emitted power.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightEntry {
    /// The emitter.
    pub source: LightSource,
    /// Emitted power on the strongest channel (watts, see [`selection_power`]).
    pub power: f32,
    /// Emitted radiance (area lights) or intensity (punctual), RGB.
    pub emission: Vec3,
}

/// All NEE-sampled lights with their selection distribution (power and uniform, see the module).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LightDistribution {
    /// Light entries, in table order.
    pub entries: Vec<LightEntry>,
    /// Sampling distribution over `entries`.
    pub table: AliasTable,
    /// What the shaders need to recompute an entry's selection probability from its power
    /// (`p = power * power_scale + uniform` for power > 0, else 0).
    pub selection: Selection,
}

/// Selection probability of a light of power `P > 0`: `P · power_scale + uniform`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Selection {
    /// `(1 − u) / ΣP` (0 without lights).
    pub power_scale: f32,
    /// `u / n` over the `n` lights with power (0 without lights).
    pub uniform: f32,
}

impl Selection {
    /// The selection probability of a light of power `power`.
    pub fn probability(&self, power: f32) -> f32 {
        if power > 0.0 {
            power * self.power_scale + self.uniform
        } else {
            0.0
        }
    }
}

impl LightDistribution {
    /// Collects the lights of a (validated) scene.
    pub fn build(scene: &Scene) -> Self {
        let mut entries = Vec::new();
        let pi = std::f32::consts::PI;
        for (ii, inst) in scene.instances.iter().enumerate() {
            let mat = &scene.materials[scene.instance_material(ii) as usize];
            if !mat.is_emissive() {
                continue;
            }
            let mesh = &scene.meshes[inst.mesh as usize];
            let strength = selection_power(mat.emission);
            for t in 0..mesh.triangle_count() {
                let [a, b, c] = mesh.triangle(t).map(|p| inst.transform.transform_point3(p));
                let area = 0.5 * (b - a).cross(c - a).length();
                entries.push(LightEntry {
                    source: LightSource::Triangle {
                        instance: ii as u32,
                        triangle: t as u32,
                    },
                    power: pi * area * strength,
                    emission: mat.emission,
                });
            }
        }
        for (si, s) in scene.spheres.iter().enumerate() {
            let mat = &scene.materials[s.material as usize];
            if mat.is_emissive() {
                entries.push(LightEntry {
                    source: LightSource::Sphere { sphere: si as u32 },
                    power: pi * 4.0 * pi * s.radius * s.radius * selection_power(mat.emission),
                    emission: mat.emission,
                });
            }
        }
        for (li, l) in scene.punctual_lights.iter().enumerate() {
            let (PunctualLight::Point { intensity, .. } | PunctualLight::Spot { intensity, .. }) =
                *l;
            entries.push(LightEntry {
                source: LightSource::Punctual { light: li as u32 },
                power: l.power(),
                emission: intensity,
            });
        }
        let powered = |p: f32| p.is_finite() && p > 0.0;
        let total: f64 = entries
            .iter()
            .filter(|e| powered(e.power))
            .map(|e| f64::from(e.power))
            .sum();
        let count = entries.iter().filter(|e| powered(e.power)).count();
        let selection = if count == 0 || total <= 0.0 {
            Selection::default()
        } else {
            Selection {
                power_scale: ((1.0 - f64::from(UNIFORM_SELECTION)) / total) as f32,
                uniform: (f64::from(UNIFORM_SELECTION) / count as f64) as f32,
            }
        };
        let weights: Vec<f32> = entries
            .iter()
            .map(|e| {
                if powered(e.power) {
                    selection.probability(e.power)
                } else {
                    0.0
                }
            })
            .collect();
        let table = AliasTable::new(&weights);
        Self {
            entries,
            table,
            selection,
        }
    }

    /// Sum of all entry powers (on their strongest channels).
    pub fn total_power(&self) -> f32 {
        self.entries.iter().map(|e| e.power).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn dim_and_coloured_lights_keep_a_share_of_the_samples() {
        let mut scene = Scene::new("lights");
        let point = |intensity: Vec3| PunctualLight::Point {
            position: Vec3::ZERO,
            intensity,
        };
        scene.punctual_lights = vec![
            point(Vec3::splat(10.0)),
            point(Vec3::new(0.0, 0.0, 1.0)),
            point(Vec3::ZERO),
        ];
        let d = LightDistribution::build(&scene);
        let pi4 = 4.0 * std::f32::consts::PI;
        assert_eq!(
            d.entries[1].power, pi4,
            "a pure-blue light weighs its blue channel"
        );
        // Half by power (10 : 1), half uniform over the two lights with power; none for the dark one.
        let want = [0.5 * 10.0 / 11.0 + 0.25, 0.5 / 11.0 + 0.25, 0.0];
        for (i, w) in want.iter().enumerate() {
            assert!((d.table.pdf[i] - w).abs() < 1e-6, "{i}: {}", d.table.pdf[i]);
            let again = d.selection.probability(d.entries[i].power);
            assert!(
                (again - w).abs() < 1e-6,
                "the shaders' formula, {i}: {again}"
            );
        }
        // By luminance alone the blue light would get 0.0722 / 10.0722 of the samples.
        assert!(d.table.pdf[1] > 30.0 * 0.0722 / 10.0722);
        assert_eq!(
            LightDistribution::build(&Scene::new("dark")).selection,
            Selection::default()
        );
    }
}
