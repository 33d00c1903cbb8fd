//! Tessellation of the Utah teapot from its Bézier patches.

use glam::{UVec3, Vec3};

use super::shapes::MeshBuilder;
use super::teapot_data::{PATCHES, VERTICES};
use crate::scene::Mesh;

fn bernstein(t: f32) -> [f32; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
}

fn bernstein_derivative(t: f32) -> [f32; 4] {
    let s = 1.0 - t;
    [
        -3.0 * s * s,
        3.0 * s * s - 6.0 * t * s,
        6.0 * t * s - 3.0 * t * t,
        3.0 * t * t,
    ]
}

/// Evaluates `Σ a[i] b[j] cp[4i + j]`.
fn eval(cp: &[Vec3; 16], a: [f32; 4], b: [f32; 4]) -> Vec3 {
    let mut p = Vec3::ZERO;
    for i in 0..4 {
        for j in 0..4 {
            p += cp[i * 4 + j] * (a[i] * b[j]);
        }
    }
    p
}

/// The teapot tessellated with `divs x divs` quads per patch, converted to
/// `y` up (data `(x, y, z)` becomes `(x, z, -y)`), standing on `y = 0`.
/// Normals come from the patch derivatives (nudged off the degenerate
/// patch corners at the lid knob and bottom centre); zero-area triangles
/// at those cusps are dropped.
pub fn teapot(name: &str, material: u32, divs: u32) -> Mesh {
    let divs = divs.max(2);
    let mut b = MeshBuilder::new();
    for patch in &PATCHES {
        let cp: [Vec3; 16] = std::array::from_fn(|k| {
            let [x, y, z] = VERTICES[patch[k] as usize - 1];
            Vec3::new(x, z, -y)
        });
        b.grid(divs, divs, |u, v| {
            let p = eval(&cp, bernstein(v), bernstein(u));
            let (un, vn) = (u.clamp(1e-3, 1.0 - 1e-3), v.clamp(1e-3, 1.0 - 1e-3));
            let du = eval(&cp, bernstein(vn), bernstein_derivative(un));
            let dv = eval(&cp, bernstein_derivative(vn), bernstein(un));
            (p, du.cross(dv).normalize_or_zero())
        });
    }
    let mut mesh = b.build(name, material);
    let positions = &mesh.positions;
    mesh.indices.retain(|t: &UVec3| {
        let [a, b, c] = t.to_array().map(|i| positions[i as usize]);
        (b - a).cross(c - a).length_squared() > 1e-14
    });
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn teapot_is_closed_enough_and_faces_out() {
        let m = teapot("teapot", 0, 4);
        m.validate().unwrap();
        assert!(m.triangle_count() > 900 && m.triangle_count() <= 32 * 32);
        let b = m.bounds();
        assert!((b.min.y).abs() < 1e-5 && (b.max.y - 3.15).abs() < 1e-3);
        // Body vertices (patches 4..12) have normals pointing away from the axis.
        let per_patch = 25;
        for k in 4 * per_patch..12 * per_patch {
            let p = m.positions[k];
            let radial = Vec3::new(p.x, 0.0, p.z);
            assert!(m.normals[k].dot(radial) > 0.0, "vertex {k}");
        }
    }
}
