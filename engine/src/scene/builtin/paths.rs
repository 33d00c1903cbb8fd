//! Default camera paths of the built-in scenes.

use glam::{Quat, Vec3};

use crate::scene::{CameraKey, CameraPath, PathInterpolation};

/// A four-second Catmull-Rom path swaying the eye ±12° around the target
/// (about the vertical axis) with a slight vertical bob, returning to the
/// start.
pub fn sway(eye: Vec3, target: Vec3, vfov_degrees: f32) -> CameraPath {
    let offset = eye - target;
    let keys = [
        (0.0, 0.0, 0.0),
        (1.0, 12.0, 0.05),
        (2.0, 0.0, 0.0),
        (3.0, -12.0, -0.05),
        (4.0, 0.0, 0.0),
    ]
    .into_iter()
    .map(|(time, degrees, bob): (f32, f32, f32)| CameraKey {
        time,
        position: target
            + Quat::from_rotation_y(degrees.to_radians()) * offset
            + Vec3::Y * bob * offset.length(),
        target,
        vfov_degrees,
    })
    .collect();
    CameraPath::new(keys, PathInterpolation::CatmullRom)
        .expect("sway keys are valid by construction")
}

/// A linear walk from `from` to `to` over `seconds`, looking at `target`.
pub fn dolly(from: Vec3, to: Vec3, target: Vec3, vfov_degrees: f32, seconds: f32) -> CameraPath {
    let key = |time: f32, position: Vec3| CameraKey {
        time,
        position,
        target,
        vfov_degrees,
    };
    CameraPath::new(
        vec![key(0.0, from), key(seconds, to)],
        PathInterpolation::Linear,
    )
    .expect("dolly keys are valid by construction")
}
