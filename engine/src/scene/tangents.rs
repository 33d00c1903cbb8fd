//! MikkTSpace tangents (through `bevy_mikktspace`) for meshes whose material has a normal map
//! and whose file gives no TANGENT attribute, as glTF 2.0 asks.

use glam::{Vec3, Vec4};

use super::Mesh;

/// The mesh seen corner by corner, as MikkTSpace reads it, with a tangent slot per corner.
struct Corners<'a> {
    mesh: &'a Mesh,
    tangents: Vec<Option<Vec4>>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.indices[face][vert] as usize
    }
}

impl bevy_mikktspace::Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.indices.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.normals[self.vertex(face, vert)].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let v = self.vertex(face, vert);
        self.mesh.uvs.get(v).map_or([0.0; 2], |uv| uv.to_array())
    }

    fn set_tangent(
        &mut self,
        tangent_space: Option<bevy_mikktspace::TangentSpace>,
        face: usize,
        vert: usize,
    ) {
        self.tangents[3 * face + vert] = tangent_space.map(|t| Vec4::from(t.tangent_encoded()));
    }
}

/// A unit tangent perpendicular to `n` (for corners MikkTSpace leaves without one, e.g. of a
/// triangle whose texture coordinates are all equal).
fn any_tangent(n: Vec3) -> Vec4 {
    n.any_orthonormal_vector().extend(1.0)
}

impl Mesh {
    /// Sets `tangents` by MikkTSpace from positions, normals and `TEXCOORD_0` (normals must be
    /// set). MikkTSpace gives a tangent per triangle corner: a vertex whose corners get different
    /// tangents is split into one vertex per tangent.
    pub fn generate_tangents(&mut self) {
        let mut corners = Corners {
            mesh: self,
            tangents: vec![None; 3 * self.indices.len()],
        };
        // The crate's error type has no variants: generation cannot fail.
        let _ = bevy_mikktspace::generate_tangents(&mut corners);
        let per_corner = corners.tangents;
        let mut tangents: Vec<Option<Vec4>> = vec![None; self.positions.len()];
        for (c, corner) in per_corner.into_iter().enumerate() {
            let v = self.indices[c / 3][c % 3] as usize;
            let t = corner.unwrap_or_else(|| any_tangent(self.normals[v]));
            match tangents[v] {
                None => tangents[v] = Some(t),
                Some(have) if have.abs_diff_eq(t, 1e-5) => {}
                Some(_) => {
                    let copy = self.split_vertex(v);
                    tangents.push(Some(t));
                    self.indices[c / 3][c % 3] = copy;
                }
            }
        }
        self.tangents = tangents
            .into_iter()
            .enumerate()
            .map(|(v, t)| t.unwrap_or_else(|| any_tangent(self.normals[v])))
            .collect();
    }

    /// Appends a copy of vertex `v` (every attribute but tangents) and returns its index.
    fn split_vertex(&mut self, v: usize) -> u32 {
        fn copy<T: Copy>(a: &mut Vec<T>, v: usize) {
            if let Some(&x) = a.get(v) {
                a.push(x);
            }
        }
        copy(&mut self.positions, v);
        copy(&mut self.normals, v);
        copy(&mut self.uvs, v);
        copy(&mut self.colors, v);
        copy(&mut self.alphas, v);
        (self.positions.len() - 1) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{UVec3, Vec2};

    /// A unit square in the plane y = 0 facing +Y, u along +x and v along +z.
    fn square() -> Mesh {
        Mesh {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0),
                Vec3::new(1.0, 0.0, 1.0),
                Vec3::new(1.0, 0.0, 0.0),
            ],
            normals: vec![Vec3::Y; 4],
            uvs: vec![
                Vec2::new(0.0, 0.0),
                Vec2::new(0.0, 1.0),
                Vec2::new(1.0, 1.0),
                Vec2::new(1.0, 0.0),
            ],
            indices: vec![UVec3::new(0, 1, 2), UVec3::new(0, 2, 3)],
            ..Default::default()
        }
    }

    #[test]
    fn tangents_follow_u_and_the_bitangent_v() {
        let mut m = square();
        m.generate_tangents();
        assert_eq!(m.tangents.len(), 4, "no vertex split");
        for (t, n) in m.tangents.iter().zip(&m.normals) {
            assert!(t.truncate().abs_diff_eq(Vec3::X, 1e-5), "{t}");
            // v grows along +z: w * cross(n, t) must be +z.
            let bitangent = t.w * n.cross(t.truncate());
            assert!(bitangent.abs_diff_eq(Vec3::Z, 1e-5), "{t}");
        }
    }

    #[test]
    fn a_vertex_shared_by_mirrored_uvs_is_split() {
        let mut m = square();
        // The second triangle's u runs the other way: its corner at vertex 0 needs another
        // tangent than the first triangle's.
        m.positions.push(Vec3::new(-1.0, 0.0, 0.0));
        m.normals.push(Vec3::Y);
        m.uvs.push(Vec2::new(1.0, 0.0));
        m.indices.push(UVec3::new(0, 4, 1));
        m.generate_tangents();
        m.validate().unwrap();
        assert_eq!(m.tangents.len(), m.positions.len());
        let t = |v: u32| m.tangents[v as usize].truncate();
        let [a, b] = [m.indices[0].x, m.indices[2].x];
        assert_ne!(a, b, "vertex 0 was split");
        assert!(t(a).abs_diff_eq(Vec3::X, 1e-5) && t(b).abs_diff_eq(Vec3::NEG_X, 1e-5));
    }
}
