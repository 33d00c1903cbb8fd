//! The camera path of a random room: 4 to 6 s of one continuous move, a
//! slow pan, a dolly forward or back, a fast turn or an orbit around an
//! object, with every key inside the room and aimed at objects.

use glam::{Quat, Vec2, Vec3};

use super::placement::Obstacle;
use super::rng::Rng;
use super::room::Room;
use crate::scene::builtin::paths;
use crate::scene::{CameraKey, CameraPath, PathInterpolation, SceneError};

/// Distance the camera keys keep from walls, floor and ceiling.
const WALL_MARGIN: f32 = 0.4;
/// Distance the camera tries to keep from objects and hanging lights.
const CLEARANCE: f32 = 0.6;
/// Horizontal distance the camera keys try to keep from what they look at.
const VIEW_DISTANCE: f32 = 1.2;
/// Steepest angle, in degrees, a key tries to look down or up.
const MAX_PITCH_DEGREES: f32 = 45.0;
/// Tries at a path that keeps clear of everything before taking the last.
const ATTEMPTS: usize = 48;

/// The kinds of camera move.
#[derive(Clone, Copy)]
enum Move {
    Pan,
    Dolly,
    FastTurn,
    Orbit,
}

/// What a move is built from.
struct Setting<'a> {
    room: &'a Room,
    obstacles: &'a [Obstacle],
    /// What the camera may look at (objects standing low in the room).
    targets: Vec<Obstacle>,
    vfov: f32,
    seconds: f32,
}

/// A random move around `obstacles`: the kind is drawn once; then up to
/// [`ATTEMPTS`] placements are tried until the whole path keeps clear of
/// the obstacles (otherwise the last try is used, still inside the room).
pub fn random_path(
    rng: &mut Rng,
    room: &Room,
    obstacles: &[Obstacle],
) -> Result<CameraPath, SceneError> {
    let mut targets: Vec<Obstacle> = obstacles
        .iter()
        .filter(|o| o.bottom < 0.5 * room.height)
        .copied()
        .collect();
    if targets.is_empty() {
        targets.push(Obstacle {
            center: Vec2::ZERO,
            radius: 0.0,
            bottom: 0.0,
            top: 1.6,
        });
    }
    let setting = Setting {
        room,
        obstacles,
        targets,
        vfov: rng.range(45.0, 75.0),
        seconds: rng.range(4.0, 6.0),
    };
    let kind = [Move::Pan, Move::Dolly, Move::FastTurn, Move::Orbit][rng.index(4)];
    let mut path = setting.attempt(rng, kind)?;
    for _ in 1..ATTEMPTS {
        if setting.is_clear(&path) {
            break;
        }
        path = setting.attempt(rng, kind)?;
    }
    Ok(path)
}

impl Setting<'_> {
    fn attempt(&self, rng: &mut Rng, kind: Move) -> Result<CameraPath, SceneError> {
        let eye = self.eye(rng);
        let object = self.targets[rng.index(self.targets.len())];
        let target = object.focus();
        let (keys, interpolation) = match kind {
            Move::Pan => (self.pan(rng, eye, target), PathInterpolation::CatmullRom),
            Move::Dolly => return Ok(self.dolly(rng, eye, &object)),
            Move::FastTurn => (self.fast_turn(rng, eye, target), PathInterpolation::Linear),
            Move::Orbit => (self.orbit(rng, &object), PathInterpolation::CatmullRom),
        };
        CameraPath::new(keys, interpolation)
    }

    fn key(&self, time: f32, position: Vec3, target: Vec3) -> CameraKey {
        CameraKey {
            time,
            position,
            target,
            vfov_degrees: self.vfov,
        }
    }

    /// A random eye position inside the room at about standing height.
    fn eye(&self, rng: &mut Rng) -> Vec3 {
        let reach = self.room.half - WALL_MARGIN;
        Vec3::new(
            rng.range(-reach.x, reach.x),
            rng.range(1.0, 1.9),
            rng.range(-reach.y, reach.y),
        )
    }

    /// From a fixed eye, a sweep of 20° to 70° about the vertical centred
    /// on `target`.
    fn pan(&self, rng: &mut Rng, eye: Vec3, target: Vec3) -> Vec<CameraKey> {
        let sweep = rng.range(20.0f32, 70.0).to_radians() * rng.sign();
        let look = target - eye;
        (0..=4)
            .map(|i| {
                let f = i as f32 / 4.0;
                let turn = Quat::from_rotation_y(sweep * (f - 0.5));
                self.key(f * self.seconds, eye, eye + turn * look)
            })
            .collect()
    }

    /// Walking 0.8 to 2.5 m straight towards `object` through `eye`
    /// (stopping at least 1 m short of it), or the same walk backwards.
    fn dolly(&self, rng: &mut Rng, eye: Vec3, object: &Obstacle) -> CameraPath {
        let target = object.focus();
        let flat = Vec3::new(target.x - eye.x, 0.0, target.z - eye.z);
        let length = rng.range(0.8, 2.5);
        let forward = length.min((flat.length() - object.radius - 1.0).max(0.0));
        let direction = flat.normalize_or_zero();
        let far = self
            .room
            .clamp(eye - direction * (length - forward), WALL_MARGIN);
        let near = self.room.clamp(eye + direction * forward, WALL_MARGIN);
        let (from, to) = if rng.chance(0.5) {
            (far, near)
        } else {
            (near, far)
        };
        paths::dolly(from, to, target, self.vfov, self.seconds)
    }

    /// Looking at `target`, then within 0.35 to 0.6 s turning to look at
    /// the object furthest round (or 100° to 160° away if all are near
    /// `target`'s direction), then holding.
    fn fast_turn(&self, rng: &mut Rng, eye: Vec3, target: Vec3) -> Vec<CameraKey> {
        let flat = |p: Vec3| Vec2::new(p.x - eye.x, p.z - eye.z);
        let angle = |p: Vec3| flat(p).angle_to(flat(target)).abs();
        let furthest = self
            .targets
            .iter()
            .map(Obstacle::focus)
            .max_by(|p, q| angle(*p).total_cmp(&angle(*q)))
            .filter(|p| angle(*p) > 80f32.to_radians());
        let second = furthest.unwrap_or_else(|| {
            let turn = rng.range(100.0f32, 160.0).to_radians() * rng.sign();
            eye + Quat::from_rotation_y(turn) * (target - eye)
        });
        let start = rng.range(1.2, self.seconds - 1.7);
        let end = start + rng.range(0.35, 0.6);
        vec![
            self.key(0.0, eye, target),
            self.key(start, eye, target),
            self.key(end, eye, second),
            self.key(self.seconds, eye, second),
        ]
    }

    /// Circling `object` by 60° to 150° at 1 to 2.5 m from its side, keys
    /// every half second (pulled inside the room where the circle leaves
    /// it).
    fn orbit(&self, rng: &mut Rng, object: &Obstacle) -> Vec<CameraKey> {
        let target = object.focus();
        let radius = object.radius + rng.range(1.0, 2.5);
        let height = rng.range(1.0, 1.9);
        let start = rng.range(0.0, std::f32::consts::TAU);
        let sweep = rng.range(60.0f32, 150.0).to_radians() * rng.sign();
        let steps = (self.seconds / 0.5).ceil() as u32;
        (0..=steps)
            .map(|i| {
                let f = i as f32 / steps as f32;
                let a = start + sweep * f;
                let p = Vec3::new(
                    target.x + radius * a.cos(),
                    height,
                    target.z + radius * a.sin(),
                );
                self.key(f * self.seconds, self.room.clamp(p, WALL_MARGIN), target)
            })
            .collect()
    }

    /// Whether the camera stays clear of every obstacle and of the walls
    /// all along `path`, and every key looks at something at least
    /// [`VIEW_DISTANCE`] away and no steeper than [`MAX_PITCH_DEGREES`].
    fn is_clear(&self, path: &CameraPath) -> bool {
        let steep = path.keys().iter().any(|k| {
            let d = k.target - k.position;
            let flat = Vec2::new(d.x, d.z).length();
            flat < VIEW_DISTANCE || d.y.abs() > MAX_PITCH_DEGREES.to_radians().tan() * flat
        });
        let steps = (path.duration() / 0.05).ceil() as u32;
        !steep
            && (0..=steps).all(|i| {
                let p = path.sample(i as f32 * 0.05).position;
                self.room.contains(p, 0.5 * WALL_MARGIN)
                    && !self.obstacles.iter().any(|o| o.blocks(p, CLEARANCE))
            })
    }
}
