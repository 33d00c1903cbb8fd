//! Whether a scene's NEE lights are the triangles of one flat emitter: then next-event estimation
//! has nothing to resample between them (`RESAMPLE_LIGHTS` in `shaders/common/lights.glsl`).

use glam::Vec3;

use super::{light_kind, material_flags, GpuLight, GpuMaterial, GpuScene};

/// How far two emitting normals may part (1 - cosine), and two planes' offsets lie apart
/// relative to the lights' extent, for their triangles to count as one flat emitter.
const COPLANAR_TOLERANCE: f32 = 1e-5;

/// The most triangles [`GpuScene::lights_form_one_flat_emitter`] compares pairwise; more count
/// as several emitters.
const MAX_EMITTER_TRIANGLES: usize = 256;

impl GpuScene {
    /// True when the NEE lights are the triangles of one connected flat patch (each shares a
    /// vertex with another), emitting to the same side with the same radiance, untextured and not
    /// cut out: e.g. a rectangular area light, two triangles. They reach every point alike but
    /// for their distance, which parts little across one patch, so resampling candidates among
    /// them (which picks lights by what they bring unshadowed) costs more than it saves. Separate
    /// panels in one plane are not one emitter: their distances part. False without lights.
    pub fn lights_form_one_flat_emitter(&self) -> bool {
        let Some(first) = self.lights.first() else {
            return false;
        };
        if self.lights.len() > MAX_EMITTER_TRIANGLES {
            return false;
        }
        let Some((normal, offset)) = emitting_plane(first) else {
            return false;
        };
        let extent = self
            .lights
            .iter()
            .flat_map(|l| [l.p0, l.p1, l.p2])
            .map(|p| Vec3::from_slice(&p[..3]).abs().max_element())
            .fold(0.0f32, f32::max)
            .max(1.0);
        let flat = self.lights.iter().all(|light| {
            plain_emitter(light, &self.materials)
                && light.emission[..3] == first.emission[..3]
                && emitting_plane(light).is_some_and(|(n, d)| {
                    1.0 - n.dot(normal) <= COPLANAR_TOLERANCE
                        && (d - offset).abs() <= COPLANAR_TOLERANCE * extent
                })
        });
        flat && connected(&self.lights)
    }
}

/// Whether the triangles form one piece, joined where they share a vertex.
fn connected(lights: &[GpuLight]) -> bool {
    let corners = |l: &GpuLight| [l.p0, l.p1, l.p2].map(|p| [p[0], p[1], p[2]]);
    let touch = |a: &GpuLight, b: &GpuLight| {
        let cb = corners(b);
        corners(a).iter().any(|p| cb.contains(p))
    };
    let mut reached = vec![false; lights.len()];
    let mut pending = vec![0];
    reached[0] = true;
    while let Some(i) = pending.pop() {
        for j in 0..lights.len() {
            if !reached[j] && touch(&lights[i], &lights[j]) {
                reached[j] = true;
                pending.push(j);
            }
        }
    }
    reached.into_iter().all(|r| r)
}

/// A triangle light whose material neither textures its emission nor cuts its surface out.
fn plain_emitter(light: &GpuLight, materials: &[GpuMaterial]) -> bool {
    let cut_out = material_flags::ALPHA_MASK | material_flags::ALPHA_BLEND;
    light.kind == light_kind::TRIANGLE
        && materials
            .get(light.material as usize)
            .is_some_and(|m| m.emissive_texture == u32::MAX && m.flags & cut_out == 0)
}

/// A triangle light's emitting unit normal and its plane's offset along it (None when
/// degenerate).
fn emitting_plane(light: &GpuLight) -> Option<(Vec3, f32)> {
    let [a, b, c] = [light.p0, light.p1, light.p2].map(|p| Vec3::from_slice(&p[..3]));
    let normal = (b - a).cross(c - a).try_normalize()? * light.p1[3];
    Some((normal, normal.dot(a)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{builtin, Bvh};

    fn gpu(name: &str) -> GpuScene {
        let scene = builtin::build_with(name, &builtin::BuildOptions { detail: 0.01 }).unwrap();
        GpuScene::new(&scene, &Bvh::build(&scene))
    }

    #[test]
    fn a_rectangular_light_is_one_flat_emitter() {
        for name in ["cornell-box", "cornell-teapot", "covered-light", "caustics"] {
            let g = gpu(name);
            assert_eq!(g.lights.len(), 2, "{name}");
            assert!(g.lights_form_one_flat_emitter(), "{name}");
        }
    }

    #[test]
    fn separate_panels_sun_only_and_tilted_apart_or_other_coloured_halves_are_not() {
        assert!(!gpu("classroom").lights_form_one_flat_emitter());
        assert!(!gpu("blinds-room").lights_form_one_flat_emitter());
        let g = gpu("cornell-box");
        let mut tilted = g.clone();
        tilted.lights[1].p2[1] -= 0.05;
        assert!(!tilted.lights_form_one_flat_emitter());
        let mut facing_away = g.clone();
        facing_away.lights[1].p1[3] *= -1.0;
        assert!(!facing_away.lights_form_one_flat_emitter());
        let mut apart = g.clone();
        let moved = &mut apart.lights[1];
        for p in [&mut moved.p0, &mut moved.p1, &mut moved.p2] {
            p[0] += 1.0;
        }
        assert!(!apart.lights_form_one_flat_emitter());
        let mut other_colour = g.clone();
        other_colour.lights[1].emission[0] *= 2.0;
        assert!(!other_colour.lights_form_one_flat_emitter());
        let mut textured = g;
        let material = textured.lights[0].material as usize;
        textured.materials[material].emissive_texture = 0;
        assert!(!textured.lights_form_one_flat_emitter());
    }
}
