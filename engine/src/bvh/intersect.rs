//! Ray/primitive intersection routines.

use glam::Vec3;

/// Möller–Trumbore ray/triangle test (double sided). Returns `(t, u, v)`
/// for a hit with `t` strictly inside `(t_min, t_max)`.
pub fn ray_triangle(
    origin: Vec3,
    dir: Vec3,
    v0: Vec3,
    v1: Vec3,
    v2: Vec3,
    t_min: f32,
    t_max: f32,
) -> Option<(f32, f32, f32)> {
    let e1 = v1 - v0;
    let e2 = v2 - v0;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv_det = 1.0 / det;
    let s = origin - v0;
    let u = s.dot(p) * inv_det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv_det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv_det;
    (t > t_min && t < t_max).then_some((t, u, v))
}

/// Ray/sphere test. Returns the nearest root inside `(t_min, t_max)`.
pub fn ray_sphere(
    origin: Vec3,
    dir: Vec3,
    center: Vec3,
    radius: f32,
    t_min: f32,
    t_max: f32,
) -> Option<f32> {
    let oc = origin - center;
    let a = dir.length_squared();
    let half_b = oc.dot(dir);
    // Numerically stable form of c: project out the direction component.
    let along = oc - dir * (half_b / a);
    let disc = a * (radius * radius - along.length_squared());
    if disc < 0.0 || a == 0.0 {
        return None;
    }
    let sq = disc.sqrt();
    let q = if half_b > 0.0 {
        -half_b - sq
    } else {
        -half_b + sq
    };
    let c = oc.length_squared() - radius * radius;
    let (r0, r1) = (q / a, if q != 0.0 { c / q } else { q / a });
    let (near, far) = if r0 < r1 { (r0, r1) } else { (r1, r0) };
    if near > t_min && near < t_max {
        Some(near)
    } else if far > t_min && far < t_max {
        Some(far)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_and_sphere() {
        let hit = ray_triangle(
            Vec3::new(0.25, 0.25, -1.0),
            Vec3::Z,
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            0.0,
            10.0,
        );
        let (t, u, v) = hit.unwrap();
        assert!((t - 1.0).abs() < 1e-6 && (u - 0.25).abs() < 1e-6 && (v - 0.25).abs() < 1e-6);
        assert!(ray_triangle(
            Vec3::new(2.0, 0.0, -1.0),
            Vec3::Z,
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            0.0,
            10.0
        )
        .is_none());
        let t = ray_sphere(
            Vec3::new(0.0, 0.0, -5.0),
            Vec3::Z,
            Vec3::ZERO,
            1.0,
            0.0,
            100.0,
        )
        .unwrap();
        assert!((t - 4.0).abs() < 1e-5);
        let inside = ray_sphere(Vec3::ZERO, Vec3::Z * 2.0, Vec3::ZERO, 1.0, 0.0, 100.0).unwrap();
        assert!((inside - 0.5).abs() < 1e-6);
        assert!(ray_sphere(
            Vec3::new(0.0, 2.0, -5.0),
            Vec3::Z,
            Vec3::ZERO,
            1.0,
            0.0,
            100.0
        )
        .is_none());
    }
}
