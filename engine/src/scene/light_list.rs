//! The power-based light distribution used by next-event estimation.
//!
//! Every emissive triangle (per instance), emissive sphere and punctual
//! light becomes one entry whose weight is its emitted power (luminance):
//! `π · area · L` for a one-sided Lambertian emitting triangle,
//! `π · 4πr² · L` for a sphere, and [`PunctualLight::power`] for point and
//! spot lights. NEE picks an entry from the alias table with probability
//! proportional to power, then samples a point on it. The sun and the
//! environment are not in the table; they are sampled as separate
//! strategies and combined with multiple importance sampling.

use glam::Vec3;

use super::light::luminance;
use super::{AliasTable, PunctualLight, Scene};

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
    /// Emitted power (luminance-weighted watts).
    pub power: f32,
    /// Emitted radiance (area lights) or intensity (punctual), RGB.
    pub emission: Vec3,
}

/// All NEE-sampled lights with a power-proportional distribution.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LightDistribution {
    /// Light entries, in table order.
    pub entries: Vec<LightEntry>,
    /// Sampling distribution over `entries`.
    pub table: AliasTable,
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
            let lum = luminance(mat.emission);
            for t in 0..mesh.triangle_count() {
                let [a, b, c] = mesh.triangle(t).map(|p| inst.transform.transform_point3(p));
                let area = 0.5 * (b - a).cross(c - a).length();
                entries.push(LightEntry {
                    source: LightSource::Triangle {
                        instance: ii as u32,
                        triangle: t as u32,
                    },
                    power: pi * area * lum,
                    emission: mat.emission,
                });
            }
        }
        for (si, s) in scene.spheres.iter().enumerate() {
            let mat = &scene.materials[s.material as usize];
            if mat.is_emissive() {
                entries.push(LightEntry {
                    source: LightSource::Sphere { sphere: si as u32 },
                    power: pi * 4.0 * pi * s.radius * s.radius * luminance(mat.emission),
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
        let table = AliasTable::new(&entries.iter().map(|e| e.power).collect::<Vec<_>>());
        Self { entries, table }
    }

    /// Sum of all entry powers.
    pub fn total_power(&self) -> f32 {
        self.entries.iter().map(|e| e.power).sum()
    }
}
