//! Triangle meshes.

use glam::{UVec3, Vec2, Vec3, Vec4};

use super::SceneError;
use crate::bvh::Aabb;

/// An indexed triangle mesh in object space with a single material.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Name used in messages.
    pub name: String,
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit shading normals, one per vertex.
    pub normals: Vec<Vec3>,
    /// Texture coordinates, one per vertex, or empty.
    pub uvs: Vec<Vec2>,
    /// Vertex colours (linear RGB in `[0, 1]`, multiplying the material's base colour), one per
    /// vertex, or empty (white).
    pub colors: Vec<Vec3>,
    /// Vertex colour alphas (`[0, 1]`, multiplying the material's opacity), one per vertex, or
    /// empty (opaque).
    pub alphas: Vec<f32>,
    /// Unit tangents (xyz, along increasing u) with the bitangent's sign (w = ±1: the bitangent
    /// is `w * cross(normal, tangent)`), one per vertex, or empty. Only meshes whose material
    /// has a normal map carry them.
    pub tangents: Vec<Vec4>,
    /// Triangles as vertex index triples.
    pub indices: Vec<UVec3>,
    /// Index into `Scene::materials`.
    pub material: u32,
}

impl Mesh {
    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// Object-space bounds.
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(self.positions.iter().copied())
    }

    /// The three corners of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        let i = self.indices[t];
        [
            self.positions[i.x as usize],
            self.positions[i.y as usize],
            self.positions[i.z as usize],
        ]
    }

    /// Replaces the normals by area-weighted smooth vertex normals.
    pub fn compute_normals(&mut self) {
        let mut n = vec![Vec3::ZERO; self.positions.len()];
        for (t, i) in self.indices.iter().enumerate() {
            let [a, b, c] = self.triangle(t);
            let face = (b - a).cross(c - a);
            for k in i.to_array() {
                n[k as usize] += face;
            }
        }
        self.normals = n
            .into_iter()
            .map(|v| v.try_normalize().unwrap_or(Vec3::Y))
            .collect();
    }

    /// Gives every triangle its own three vertices with the triangle's (flat) normal, as glTF
    /// requires of a mesh without normals; UVs, colours and tangents are copied to the new vertices. A
    /// degenerate triangle gets `+Y`.
    pub fn make_flat(&mut self) {
        fn corners<T: Copy>(indices: &[UVec3], v: &[T]) -> Vec<T> {
            if v.is_empty() {
                return Vec::new();
            }
            indices
                .iter()
                .flat_map(|i| i.to_array().map(|k| v[k as usize]))
                .collect()
        }
        let positions = corners(&self.indices, &self.positions);
        let uvs = corners(&self.indices, &self.uvs);
        let colors = corners(&self.indices, &self.colors);
        let alphas = corners(&self.indices, &self.alphas);
        let tangents = corners(&self.indices, &self.tangents);
        self.normals = positions
            .chunks_exact(3)
            .flat_map(|t| {
                let n = (t[1] - t[0]).cross(t[2] - t[0]).try_normalize();
                [n.unwrap_or(Vec3::Y); 3]
            })
            .collect();
        self.indices = (0..self.indices.len() as u32)
            .map(|t| UVec3::new(3 * t, 3 * t + 1, 3 * t + 2))
            .collect();
        self.positions = positions;
        self.uvs = uvs;
        self.colors = colors;
        self.alphas = alphas;
        self.tangents = tangents;
    }

    /// Checks attribute counts, index ranges and that positions, normals,
    /// UVs, colours and tangents are finite (colours and alphas also in `[0, 1]`).
    pub fn validate(&self) -> Result<(), SceneError> {
        let fail = |reason: String| {
            Err(SceneError::InvalidMesh {
                name: self.name.clone(),
                reason,
            })
        };
        let nv = self.positions.len();
        if self.normals.len() != nv {
            return fail(format!(
                "{} normals for {} positions",
                self.normals.len(),
                nv
            ));
        }
        if !self.uvs.is_empty() && self.uvs.len() != nv {
            return fail(format!("{} uvs for {} positions", self.uvs.len(), nv));
        }
        if let Some(p) = self.positions.iter().position(|p| !p.is_finite()) {
            return fail(format!("position {p} is not finite"));
        }
        if self.normals.iter().any(|n| !n.is_finite()) || self.uvs.iter().any(|u| !u.is_finite()) {
            return fail("normals and uvs must be finite".into());
        }
        if !self.colors.is_empty() && self.colors.len() != nv {
            return fail(format!(
                "{} colours for {} positions",
                self.colors.len(),
                nv
            ));
        }
        if let Some(c) = self
            .colors
            .iter()
            .position(|c| !(c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0))
        {
            return fail(format!("colour {c} is not finite or outside [0, 1]"));
        }
        for (name, len) in [
            ("alphas", self.alphas.len()),
            ("tangents", self.tangents.len()),
        ] {
            if len != 0 && len != nv {
                return fail(format!("{len} {name} for {nv} positions"));
            }
        }
        if self.alphas.iter().any(|a| !(0.0..=1.0).contains(a)) {
            return fail("vertex alphas must lie in [0, 1]".into());
        }
        if self.tangents.iter().any(|t| !t.is_finite()) {
            return fail("tangents must be finite".into());
        }
        if let Some(t) = self
            .indices
            .iter()
            .position(|i| i.max_element() as usize >= nv)
        {
            return fail(format!("triangle {t} indexes past the {nv} vertices"));
        }
        Ok(())
    }
}
