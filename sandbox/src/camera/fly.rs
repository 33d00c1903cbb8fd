//! A fly camera: WASD moves in the view plane, Q/E down/up, the mouse looks around while the
//! right button is held, and the wheel changes the speed. Pure logic, no window.

use glam::{Vec2, Vec3};
use lucid_engine::scene::Camera;

/// Radians of rotation per pixel of mouse movement.
const LOOK_RADIANS_PER_PIXEL: f32 = 0.003;
/// Pitch stays this far from straight up or down, where yaw is undefined.
const MAX_PITCH: f32 = 1.55;
/// Speed factor per wheel step.
const SPEED_STEP: f32 = 1.2;
/// The slowest and fastest speeds, in world units per second.
const SPEED_RANGE: (f32, f32) = (1e-3, 1e4);

/// Where the camera is and where it looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Eye position.
    pub position: Vec3,
    /// Rotation about world `+Y` in radians; 0 looks along `-Z`.
    pub yaw: f32,
    /// Elevation in radians; positive looks up.
    pub pitch: f32,
    /// Vertical field of view in degrees.
    pub vfov_degrees: f32,
}

impl Pose {
    /// The pose of an engine camera (roll is dropped).
    pub fn from_camera(camera: &Camera) -> Self {
        let f = camera.forward();
        Self {
            position: camera.position,
            yaw: (-f.x).atan2(-f.z),
            pitch: f.y.clamp(-1.0, 1.0).asin().clamp(-MAX_PITCH, MAX_PITCH),
            vfov_degrees: camera.vfov.to_degrees(),
        }
    }

    /// The unit view direction.
    pub fn forward(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(-sy * cp, sp, -cy * cp)
    }

    /// The unit right vector (horizontal).
    pub fn right(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        Vec3::new(cy, 0.0, -sy)
    }

    /// The pinhole engine camera with this pose.
    pub fn camera(&self) -> Camera {
        Camera::look_at(
            self.position,
            self.position + self.forward(),
            Vec3::Y,
            self.vfov_degrees,
        )
    }
}

/// What the user did since the last update.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlyInput {
    /// Movement along right, up and forward, each in `[-1, 1]` (held keys).
    pub movement: Vec3,
    /// Mouse movement in pixels while looking (right button held).
    pub look: Vec2,
    /// Wheel steps (positive: faster).
    pub wheel: f32,
}

/// The fly camera controller.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    /// The current pose.
    pub pose: Pose,
    /// Movement speed in world units per second.
    pub speed: f32,
}

impl FlyCamera {
    /// A controller starting at `pose`, moving at `speed` units per second.
    pub fn new(pose: Pose, speed: f32) -> Self {
        Self {
            pose,
            speed: speed.clamp(SPEED_RANGE.0, SPEED_RANGE.1),
        }
    }

    /// Applies `input` over `dt` seconds; returns whether the pose changed.
    pub fn update(&mut self, input: &FlyInput, dt: f32) -> bool {
        if input.wheel != 0.0 {
            self.speed =
                (self.speed * SPEED_STEP.powf(input.wheel)).clamp(SPEED_RANGE.0, SPEED_RANGE.1);
        }
        let before = self.pose;
        if input.look != Vec2::ZERO {
            self.pose.yaw -= input.look.x * LOOK_RADIANS_PER_PIXEL;
            self.pose.pitch = (self.pose.pitch - input.look.y * LOOK_RADIANS_PER_PIXEL)
                .clamp(-MAX_PITCH, MAX_PITCH);
        }
        let m = input.movement.clamp(Vec3::NEG_ONE, Vec3::ONE);
        if m != Vec3::ZERO && dt > 0.0 {
            let step = self.pose.right() * m.x + Vec3::Y * m.y + self.pose.forward() * m.z;
            self.pose.position += step.normalize_or_zero() * self.speed * dt;
        }
        self.pose != before
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn start() -> FlyCamera {
        FlyCamera::new(
            Pose {
                position: Vec3::ZERO,
                yaw: 0.0,
                pitch: 0.0,
                vfov_degrees: 45.0,
            },
            2.0,
        )
    }

    #[test]
    fn moves_along_the_view_axes_at_its_speed() {
        let mut fly = start();
        let forward = FlyInput {
            movement: Vec3::Z,
            ..Default::default()
        };
        assert!(fly.update(&forward, 0.5));
        assert!((fly.pose.position - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-5);
        let right_up = FlyInput {
            movement: Vec3::new(1.0, 1.0, 0.0),
            ..Default::default()
        };
        fly.update(&right_up, 1.0);
        let expected = Vec3::new(0.0, 0.0, -1.0) + Vec3::new(1.0, 1.0, 0.0).normalize() * 2.0;
        assert!((fly.pose.position - expected).length() < 1e-5);
        assert!(!fly.update(&FlyInput::default(), 1.0));
    }

    #[test]
    fn looks_with_the_mouse_and_clamps_pitch() {
        let mut fly = start();
        let right = FlyInput {
            look: Vec2::new(100.0, 0.0),
            ..Default::default()
        };
        fly.update(&right, 0.0);
        assert!(
            fly.pose.forward().x > 0.0,
            "moving the mouse right turns right"
        );
        let up = FlyInput {
            look: Vec2::new(0.0, -1e6),
            ..Default::default()
        };
        fly.update(&up, 0.0);
        assert!((fly.pose.pitch - MAX_PITCH).abs() < 1e-6);
    }

    #[test]
    fn wheel_scales_speed_within_limits() {
        let mut fly = start();
        fly.update(
            &FlyInput {
                wheel: 2.0,
                ..Default::default()
            },
            0.0,
        );
        assert!((fly.speed - 2.0 * 1.44).abs() < 1e-4);
        fly.update(
            &FlyInput {
                wheel: -1000.0,
                ..Default::default()
            },
            0.0,
        );
        assert_eq!(fly.speed, SPEED_RANGE.0);
    }

    #[test]
    fn pose_round_trips_through_the_engine_camera() {
        let pose = Pose {
            position: Vec3::new(1.0, 2.0, 3.0),
            yaw: 0.7,
            pitch: -0.3,
            vfov_degrees: 50.0,
        };
        let back = Pose::from_camera(&pose.camera());
        assert!((back.position - pose.position).length() < 1e-5);
        assert!((back.yaw - pose.yaw).abs() < 1e-4);
        assert!((back.pitch - pose.pitch).abs() < 1e-4);
        assert!((back.vfov_degrees - 50.0).abs() < 1e-3);
    }
}
