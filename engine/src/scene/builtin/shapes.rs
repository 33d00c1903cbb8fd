//! Procedural mesh construction helpers shared by the built-in scenes.

use glam::{Affine3A, UVec3, Vec2, Vec3};

use crate::scene::Mesh;

/// Accumulates triangles, optionally under a transform, into one mesh.
#[derive(Default)]
pub struct MeshBuilder {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    indices: Vec<UVec3>,
}

impl MeshBuilder {
    /// An empty builder.
    pub fn new() -> Self {
        Self::default()
    }

    /// Finishes the mesh.
    pub fn build(self, name: &str, material: u32) -> Mesh {
        Mesh {
            name: name.to_owned(),
            positions: self.positions,
            normals: self.normals,
            uvs: self.uvs,
            indices: self.indices,
            material,
            ..Default::default()
        }
    }

    fn vertex(&mut self, p: Vec3, n: Vec3, uv: Vec2) -> u32 {
        self.positions.push(p);
        self.normals.push(n);
        self.uvs.push(uv);
        (self.positions.len() - 1) as u32
    }

    /// A `(nu+1) x (nv+1)` vertex grid from `f(u, v) -> (position,
    /// normal)` over `[0,1]²`, triangulated so that the front face is the
    /// side the normals point to when `du x dv` agrees with them.
    pub fn grid(&mut self, nu: u32, nv: u32, f: impl Fn(f32, f32) -> (Vec3, Vec3)) {
        let base = self.positions.len() as u32;
        for j in 0..=nv {
            for i in 0..=nu {
                let uv = Vec2::new(i as f32 / nu as f32, j as f32 / nv as f32);
                let (p, n) = f(uv.x, uv.y);
                self.vertex(p, n, uv);
            }
        }
        let row = nu + 1;
        for j in 0..nv {
            for i in 0..nu {
                let a = base + j * row + i;
                self.indices.push(UVec3::new(a, a + 1, a + row + 1));
                self.indices.push(UVec3::new(a, a + row + 1, a + row));
            }
        }
    }

    /// A planar quad `corner + u*e1 + v*e2` with normal `e1 x e2`,
    /// subdivided `nu x nv` times.
    pub fn quad(&mut self, corner: Vec3, e1: Vec3, e2: Vec3, nu: u32, nv: u32) {
        let n = e1.cross(e2).normalize();
        self.grid(nu, nv, |u, v| (corner + e1 * u + e2 * v, n));
    }

    /// An axis-aligned box `[-1, 1]³` (Mitsuba's `cube`) under `m`, with
    /// outward flat normals, each face subdivided `s x s` times.
    pub fn cube(&mut self, m: &Affine3A, s: u32) {
        let faces = [
            (Vec3::X, Vec3::NEG_Z, Vec3::Y),
            (Vec3::NEG_X, Vec3::Z, Vec3::Y),
            (Vec3::Y, Vec3::X, Vec3::NEG_Z),
            (Vec3::NEG_Y, Vec3::X, Vec3::Z),
            (Vec3::Z, Vec3::X, Vec3::Y),
            (Vec3::NEG_Z, Vec3::NEG_X, Vec3::Y),
        ];
        let normal_m = m.matrix3.inverse().transpose();
        for (n, a, b) in faces {
            let corner = n - a - b;
            let wn = (normal_m * n).normalize();
            self.grid(s, s, |u, v| {
                let p = corner + a * (2.0 * u) + b * (2.0 * v);
                (m.transform_point3(p), wn)
            });
        }
    }

    /// An axis-aligned box from its minimum and maximum corners.
    pub fn cuboid(&mut self, min: Vec3, max: Vec3, s: u32) {
        let m = Affine3A::from_scale_rotation_translation(
            (max - min) * 0.5,
            glam::Quat::IDENTITY,
            (min + max) * 0.5,
        );
        self.cube(&m, s);
    }

    /// A closed cylinder along `+Y` from `base` with `radius` and `height`,
    /// `segments` around and `rings` along its side.
    pub fn cylinder(&mut self, base: Vec3, radius: f32, height: f32, segments: u32, rings: u32) {
        let tau = std::f32::consts::TAU;
        self.grid(segments, rings, |u, v| {
            let a = -u * tau;
            let n = Vec3::new(a.cos(), 0.0, a.sin());
            (base + n * radius + Vec3::Y * (v * height), n)
        });
        for (y, n) in [(0.0, Vec3::NEG_Y), (height, Vec3::Y)] {
            let c = self.vertex(base + Vec3::Y * y, n, Vec2::splat(0.5));
            let first = self.positions.len() as u32;
            for k in 0..segments {
                let a = k as f32 / segments as f32 * tau;
                let d = Vec3::new(a.cos(), 0.0, a.sin());
                self.vertex(
                    base + d * radius + Vec3::Y * y,
                    n,
                    Vec2::new(d.x, d.z) * 0.5 + 0.5,
                );
            }
            for k in 0..segments {
                let (i, j) = (first + k, first + (k + 1) % segments);
                let tri = if n.y > 0.0 {
                    UVec3::new(c, j, i)
                } else {
                    UVec3::new(c, i, j)
                };
                self.indices.push(tri);
            }
        }
    }
}

/// Mitsuba's `rectangle`: `[-1, 1]²` in the `z = 0` plane facing `+Z`.
pub fn rectangle(name: &str, material: u32) -> Mesh {
    let mut b = MeshBuilder::new();
    b.quad(
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::X * 2.0,
        Vec3::Y * 2.0,
        1,
        1,
    );
    b.build(name, material)
}

/// Mitsuba's `cube`: `[-1, 1]³` with outward normals, 12 triangles.
pub fn cube(name: &str, material: u32) -> Mesh {
    let mut b = MeshBuilder::new();
    b.cube(&Affine3A::IDENTITY, 1);
    b.build(name, material)
}

/// A rectangular wall `origin + u*e1 + v*e2` (`u, v` in `[0, 1]`) with
/// rectangular openings `(u0, v0, u1, v1)` cut out; the openings must not
/// overlap. The wall faces `e1 x e2`.
pub fn wall_with_openings(
    b: &mut MeshBuilder,
    origin: Vec3,
    e1: Vec3,
    e2: Vec3,
    openings: &[[f32; 4]],
) {
    let mut us: Vec<f32> = vec![0.0, 1.0];
    us.extend(openings.iter().flat_map(|o| [o[0], o[2]]));
    us.sort_by(f32::total_cmp);
    us.dedup();
    for w in us.windows(2) {
        let (u0, u1) = (w[0], w[1]);
        let mid = 0.5 * (u0 + u1);
        let mut vs: Vec<[f32; 2]> = openings
            .iter()
            .filter(|o| o[0] <= mid && mid <= o[2])
            .map(|o| [o[1], o[3]])
            .collect();
        vs.sort_by(|a, b| a[0].total_cmp(&b[0]));
        let mut v = 0.0;
        for hole in vs.iter().chain([&[1.0, 1.0]]) {
            if hole[0] > v {
                b.quad(
                    origin + e1 * u0 + e2 * v,
                    e1 * (u1 - u0),
                    e2 * (hole[0] - v),
                    1,
                    1,
                );
            }
            v = v.max(hole[1]);
        }
    }
}
