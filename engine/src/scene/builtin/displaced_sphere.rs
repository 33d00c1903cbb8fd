//! A procedurally displaced, finely tessellated sphere (a cube-sphere
//! grid pushed in and out by a fixed sum of sines), the high-poly mesh of
//! `covered-light`.

use glam::{UVec3, Vec2, Vec3};
use rayon::prelude::*;

use crate::scene::Mesh;

/// Radial displacement factor of the unit direction `d`.
fn displacement(d: Vec3) -> f32 {
    1.0 + 0.08
        * (12.0 * d.x + 3.0 * (5.0 * d.y).sin()).sin()
        * (10.0 * d.y).sin()
        * (11.0 * d.z + 2.0).sin()
        + 0.015 * (41.0 * d.x).sin() * (43.0 * d.y).sin() * (47.0 * d.z).sin()
}

/// Cube faces as (normal, u axis, v axis) with `u x v = normal`.
const FACES: [(Vec3, Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::NEG_Z, Vec3::Y),
    (Vec3::NEG_X, Vec3::Z, Vec3::Y),
    (Vec3::Y, Vec3::X, Vec3::NEG_Z),
    (Vec3::NEG_Y, Vec3::X, Vec3::Z),
    (Vec3::Z, Vec3::X, Vec3::Y),
    (Vec3::NEG_Z, Vec3::NEG_X, Vec3::Y),
];

/// The surface point for face parameters `(s, t)` in `[-1, 1]²`. Cube
/// points are assembled per axis so seam vertices of adjacent faces are
/// bit-identical.
fn surface(face: usize, s: f32, t: f32, radius: f32) -> Vec3 {
    let (n, a, b) = FACES[face];
    let c = n + a * s + b * t;
    let d = c.normalize();
    d * (radius * displacement(d))
}

/// A displaced sphere of the given radius with `n x n` quads per cube face
/// (`12 n²` triangles), centred at the origin.
pub fn displaced_sphere(name: &str, material: u32, radius: f32, n: u32) -> Mesh {
    let n = n.max(1);
    let row = (n + 1) as usize;
    let per_face = row * row;
    let h = 0.5 / n as f32;
    let mut positions = vec![Vec3::ZERO; 6 * per_face];
    let mut normals = vec![Vec3::ZERO; 6 * per_face];
    let mut uvs = vec![Vec2::ZERO; 6 * per_face];
    positions
        .par_chunks_mut(row)
        .zip(normals.par_chunks_mut(row))
        .zip(uvs.par_chunks_mut(row))
        .enumerate()
        .for_each(|(r, ((p, nr), uv))| {
            let face = r / row;
            let j = r % row;
            let t = j as f32 / n as f32 * 2.0 - 1.0;
            for i in 0..row {
                let s = i as f32 / n as f32 * 2.0 - 1.0;
                p[i] = surface(face, s, t, radius);
                let ds = surface(face, s + h, t, radius) - surface(face, s - h, t, radius);
                let dt = surface(face, s, t + h, radius) - surface(face, s, t - h, radius);
                nr[i] = ds.cross(dt).normalize_or_zero();
                uv[i] = Vec2::new(i as f32 / n as f32, j as f32 / n as f32);
            }
        });
    let quads = (n * n) as usize;
    let mut indices = vec![UVec3::ZERO; 6 * quads * 2];
    indices
        .par_chunks_mut(2 * n as usize)
        .enumerate()
        .for_each(|(r, out)| {
            let face = r / n as usize;
            let j = (r % n as usize) as u32;
            let base = (face * per_face) as u32;
            let row = n + 1;
            for i in 0..n {
                let a = base + j * row + i;
                out[2 * i as usize] = UVec3::new(a, a + 1, a + row + 1);
                out[2 * i as usize + 1] = UVec3::new(a, a + row + 1, a + row);
            }
        });
    Mesh {
        name: name.to_owned(),
        positions,
        normals,
        uvs,
        indices,
        material,
        ..Default::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn displaced_sphere_is_valid_and_outward() {
        let m = displaced_sphere("blob", 0, 1.0, 8);
        m.validate().unwrap();
        assert_eq!(m.triangle_count(), 12 * 64);
        for (p, n) in m.positions.iter().zip(&m.normals) {
            assert!(n.dot(*p) > 0.0);
            assert!((0.85..1.15).contains(&p.length()));
        }
    }
}
