//! Rays and hit records for the CPU traversal.

use glam::{Vec2, Vec3};

/// A ray segment `origin + t * dir` for `t` in `[t_min, t_max]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Ray origin.
    pub origin: Vec3,
    /// Ray direction (need not be normalised; distances are in its units).
    pub dir: Vec3,
    /// Nearest accepted distance.
    pub t_min: f32,
    /// Farthest accepted distance.
    pub t_max: f32,
}

impl Ray {
    /// A ray over `[0, inf)`.
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Self {
            origin,
            dir,
            t_min: 0.0,
            t_max: f32::INFINITY,
        }
    }

    /// The point at distance `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// What a ray hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HitKind {
    /// A triangle of a mesh instance: scene instance index and triangle
    /// index within the instanced mesh.
    Triangle {
        /// Index into `Scene::instances`.
        instance: u32,
        /// Index into the mesh's triangle list.
        triangle: u32,
    },
    /// An analytic sphere: index into `Scene::spheres`.
    Sphere {
        /// Index into `Scene::spheres`.
        sphere: u32,
    },
}

/// The closest intersection found along a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the ray.
    pub t: f32,
    /// The primitive hit.
    pub kind: HitKind,
    /// Barycentric `(u, v)` of the hit on a triangle (zero for spheres).
    pub barycentrics: Vec2,
    /// Unit geometric normal in world space (not flipped towards the ray).
    pub normal: Vec3,
}
