//! Triangle meshes.

use glam::{UVec3, Vec2, Vec3};

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

    /// Checks attribute counts, index ranges and that positions, normals
    /// and UVs are finite.
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
