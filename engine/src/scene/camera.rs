//! The pinhole / thin-lens camera.

use glam::{Mat3, Quat, Vec2, Vec3};

use crate::bvh::{Aabb, Ray};

/// Elevation of [`Camera::framing`]'s view above the horizontal, in degrees.
pub const FRAMING_ELEVATION_DEGREES: f32 = 30.0;

/// The border [`Camera::framing`] leaves around the bounds, as a fraction of the half field of
/// view.
const FRAMING_MARGIN: f32 = 0.05;

/// A perspective camera. In camera space the view direction is `-Z`, up is
/// `+Y` and right is `+X` (the glTF convention).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// World position of the eye (centre of the lens).
    pub position: Vec3,
    /// Camera-to-world rotation.
    pub orientation: Quat,
    /// Vertical field of view in radians.
    pub vfov: f32,
    /// Thin-lens aperture radius in world units; 0 is a pinhole.
    pub aperture_radius: f32,
    /// Distance to the plane in perfect focus (thin lens only).
    pub focus_distance: f32,
}

impl Camera {
    /// A pinhole camera at `position` looking at `target` with world `up`
    /// and a vertical field of view in degrees.
    pub fn look_at(position: Vec3, target: Vec3, up: Vec3, vfov_degrees: f32) -> Self {
        Self {
            position,
            orientation: look_rotation(target - position, up),
            vfov: vfov_degrees.to_radians(),
            aperture_radius: 0.0,
            focus_distance: (target - position).length().max(1e-3),
        }
    }

    /// A pinhole camera that frames `bounds` from a three-quarter view: from above (at
    /// [`FRAMING_ELEVATION_DEGREES`]) and to the side (45° between `+X` and `+Z`, so a model facing
    /// `+Z`, the glTF convention, is seen from its front right), looking at the bounds' centre.
    /// The distance is the smallest at which all eight corners of the box lie within the vertical
    /// field of view `vfov_degrees` in both directions (so the bounds fit any image at least as
    /// wide as it is tall) with a small border: never more than the distance at which the
    /// bounding sphere fits, and less for flat or elongated bounds. An empty box frames the origin.
    pub fn framing(bounds: &Aabb, vfov_degrees: f32) -> Self {
        let (center, half) = if bounds.is_empty() {
            (Vec3::ZERO, Vec3::ZERO)
        } else {
            (bounds.center(), 0.5 * bounds.extent())
        };
        let elevation = FRAMING_ELEVATION_DEGREES.to_radians();
        let back = Vec3::new(
            elevation.cos() * std::f32::consts::FRAC_1_SQRT_2,
            elevation.sin(),
            elevation.cos() * std::f32::consts::FRAC_1_SQRT_2,
        );
        let orientation = look_rotation(-back, Vec3::Y);
        let (forward, right, up) = (
            orientation * Vec3::NEG_Z,
            orientation * Vec3::X,
            orientation * Vec3::Y,
        );
        let half_fov = 0.5 * vfov_degrees.to_radians();
        let tan = half_fov.tan() * (1.0 - FRAMING_MARGIN);
        // A corner at offset v from the centre lies at depth `distance + v·forward` and within
        // the frustum when |v·right| and |v·up| are at most `tan` times that depth.
        let mut distance: f32 = 0.0;
        for i in 0..8 {
            let sign = |bit: u32| if i & bit == 0 { -1.0 } else { 1.0 };
            let v = half * Vec3::new(sign(1), sign(2), sign(4));
            let lateral = v.dot(right).abs().max(v.dot(up).abs());
            distance = distance.max(lateral / tan - v.dot(forward));
        }
        // A point (or an empty box) still gets its camera in front of it.
        distance = distance.max(1e-3 / half_fov.sin());
        Self {
            position: center + back * distance,
            orientation,
            vfov: vfov_degrees.to_radians(),
            aperture_radius: 0.0,
            focus_distance: distance,
        }
    }

    /// This camera with a thin lens.
    pub fn with_lens(mut self, aperture_radius: f32, focus_distance: f32) -> Self {
        self.aperture_radius = aperture_radius;
        self.focus_distance = focus_distance;
        self
    }

    /// Unit view direction.
    pub fn forward(&self) -> Vec3 {
        self.orientation * Vec3::NEG_Z
    }

    /// Unit right vector.
    pub fn right(&self) -> Vec3 {
        self.orientation * Vec3::X
    }

    /// Unit up vector.
    pub fn up(&self) -> Vec3 {
        self.orientation * Vec3::Y
    }

    /// The primary ray through normalised device coordinates `ndc` (both
    /// in `[-1, 1]`, `+y` up) for an image of width/height `aspect`.
    /// `lens` in `[0, 1)²` picks the point on the aperture.
    pub fn generate_ray(&self, ndc: Vec2, aspect: f32, lens: Vec2) -> Ray {
        let tan = (0.5 * self.vfov).tan();
        let d = Vec3::new(ndc.x * tan * aspect, ndc.y * tan, -1.0);
        if self.aperture_radius <= 0.0 {
            return Ray::new(self.position, (self.orientation * d).normalize());
        }
        let focus = d * self.focus_distance;
        let l = concentric_disk(lens) * self.aperture_radius;
        let offset = Vec3::new(l.x, l.y, 0.0);
        Ray::new(
            self.position + self.orientation * offset,
            (self.orientation * (focus - offset)).normalize(),
        )
    }
}

/// The rotation taking camera space (`-Z` forward, `+Y` up) to a frame
/// looking along `forward` with the given world `up`.
pub fn look_rotation(forward: Vec3, up: Vec3) -> Quat {
    let f = forward.try_normalize().unwrap_or(Vec3::NEG_Z);
    let mut right = f.cross(up);
    if right.length_squared() < 1e-12 {
        right = f.cross(if f.y.abs() < 0.9 { Vec3::Y } else { Vec3::Z });
    }
    let right = right.normalize();
    let true_up = right.cross(f);
    Quat::from_mat3(&Mat3::from_cols(right, true_up, -f)).normalize()
}

/// Shirley–Chiu concentric mapping of `[0,1)²` onto the unit disk.
fn concentric_disk(u: Vec2) -> Vec2 {
    let o = u * 2.0 - Vec2::ONE;
    if o == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, std::f32::consts::FRAC_PI_4 * (o.y / o.x))
    } else {
        (
            o.y,
            std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (o.x / o.y),
        )
    };
    Vec2::new(theta.cos(), theta.sin()) * r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_at_frame_and_rays() {
        let c = Camera::look_at(Vec3::new(0.0, 0.0, 3.9), Vec3::ZERO, Vec3::Y, 39.3077);
        assert!((c.forward() - Vec3::NEG_Z).length() < 1e-6);
        assert!((c.up() - Vec3::Y).length() < 1e-6);
        let center = c.generate_ray(Vec2::ZERO, 1.0, Vec2::splat(0.5));
        assert!((center.dir - Vec3::NEG_Z).length() < 1e-6);
        let top = c.generate_ray(Vec2::new(0.0, 1.0), 1.0, Vec2::ZERO);
        let angle = top.dir.angle_between(Vec3::NEG_Z).to_degrees();
        assert!((angle - 39.3077 / 2.0).abs() < 1e-3);
        // Thin lens: rays from different lens points meet on the focus plane.
        let lens = c.with_lens(0.1, 3.9);
        let a = lens.generate_ray(Vec2::new(0.3, 0.2), 1.0, Vec2::new(0.1, 0.9));
        let b = lens.generate_ray(Vec2::new(0.3, 0.2), 1.0, Vec2::new(0.8, 0.3));
        assert!(a.origin != b.origin);
        let pa = a.at(-(a.origin.z) / a.dir.z);
        let pb = b.at(-(b.origin.z) / b.dir.z);
        assert!((pa - pb).length() < 1e-4);
    }

    /// Projects `p` with `c` to normalised device coordinates (aspect 1) and its depth.
    fn project(c: &Camera, p: Vec3) -> (Vec2, f32) {
        let v = p - c.position;
        let depth = v.dot(c.forward());
        let tan = (0.5 * c.vfov).tan();
        (
            Vec2::new(v.dot(c.right()), v.dot(c.up())) / (depth * tan),
            depth,
        )
    }

    #[test]
    fn framing_sees_the_whole_box_from_above_and_the_side() {
        let boxes = [
            Aabb::new(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 1.0)),
            Aabb::new(Vec3::new(2.0, -3.0, 5.0), Vec3::new(4.0, 9.0, 6.0)),
            Aabb::new(Vec3::splat(-1e4), Vec3::splat(1e4)),
        ];
        for b in boxes {
            let c = Camera::framing(&b, 45.0);
            let to_center = (b.center() - c.position).normalize();
            assert!((c.forward() - to_center).length() < 1e-4, "{b:?}");
            assert!(c.forward().y < -0.4 && c.forward().x < -0.4 && c.forward().z < -0.4);
            assert!(c.up().y > 0.0, "upright");
            let mut widest: f32 = 0.0;
            for i in 0..8 {
                let p = Vec3::select(
                    glam::BVec3::new(i & 1 == 0, i & 2 == 0, i & 4 == 0),
                    b.min,
                    b.max,
                );
                let (ndc, depth) = project(&c, p);
                assert!(depth > 0.0, "{b:?}: corner {p} behind the camera");
                assert!(ndc.abs().max_element() <= 1.0, "{b:?}: corner {p} at {ndc}");
                widest = widest.max(ndc.abs().max_element());
            }
            assert!(widest > 0.9, "{b:?}: framed tightly ({widest})");
            let sphere = 0.5 * b.extent().length() / (0.5 * c.vfov).sin();
            assert!((c.position - b.center()).length() <= sphere * 1.06);
        }
        let point = Camera::framing(&Aabb::EMPTY, 45.0);
        assert!(point.position.is_finite() && point.position.length() > 0.0);
    }
}
