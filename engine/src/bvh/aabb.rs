//! Axis-aligned bounding boxes.

use glam::{Affine3A, Vec3};

/// An axis-aligned bounding box. An empty box has `min > max` on every axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    /// The empty box: growing it by anything yields that thing's bounds.
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// A box from its two corners.
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    /// The bounds of a set of points (empty for no points).
    pub fn from_points<I: IntoIterator<Item = Vec3>>(points: I) -> Self {
        points
            .into_iter()
            .fold(Self::EMPTY, |b, p| b.grown_by_point(p))
    }

    /// Whether the box contains nothing.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// The box grown to include `p`.
    pub fn grown_by_point(self, p: Vec3) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The union of two boxes.
    pub fn union(self, other: Aabb) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Box extent (`max - min`), zero for an empty box.
    pub fn extent(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            self.max - self.min
        }
    }

    /// Centre of the box.
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Surface area, zero for an empty box.
    pub fn surface_area(&self) -> f32 {
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// Bounds of this box after an affine transform (all eight corners).
    pub fn transformed(&self, m: &Affine3A) -> Self {
        if self.is_empty() {
            return *self;
        }
        (0..8)
            .map(|i| {
                Vec3::new(
                    if i & 1 == 0 { self.min.x } else { self.max.x },
                    if i & 2 == 0 { self.min.y } else { self.max.y },
                    if i & 4 == 0 { self.min.z } else { self.max.z },
                )
            })
            .fold(Self::EMPTY, |b, c| b.grown_by_point(m.transform_point3(c)))
    }

    /// Slab test: the entry distance of a ray into the box if it enters
    /// within `[t_min, t_max]`. `inv_dir` is the component-wise reciprocal
    /// of the ray direction.
    pub fn intersect_ray(
        &self,
        origin: Vec3,
        inv_dir: Vec3,
        t_min: f32,
        t_max: f32,
    ) -> Option<f32> {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        let near = t0.min(t1).max_element().max(t_min);
        let far = t0.max(t1).min_element().min(t_max);
        (near <= far).then_some(near)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_area_and_ray() {
        let b = Aabb::from_points([Vec3::ZERO, Vec3::ONE]);
        assert_eq!(b.surface_area(), 6.0);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
        let inv = Vec3::new(1.0, f32::INFINITY, f32::INFINITY);
        let hit = b.intersect_ray(Vec3::new(-1.0, 0.5, 0.5), inv, 0.0, 10.0);
        assert_eq!(hit, Some(1.0));
        assert!(b
            .intersect_ray(Vec3::new(-1.0, 2.0, 0.5), inv, 0.0, 10.0)
            .is_none());
        let moved = b.transformed(&Affine3A::from_translation(Vec3::X));
        assert_eq!(moved.min, Vec3::X);
    }
}
