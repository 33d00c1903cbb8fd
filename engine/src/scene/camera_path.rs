//! Camera animation paths and their line-based text format.
//!
//! A path file is plain text, one keyframe per line:
//!
//! ```text
//! # lucid camera path
//! interpolation catmull-rom      # or: linear   (optional, default catmull-rom)
//! # t   px  py  pz   tx ty tz   fov
//! 0.0   0   0   3.9  0  0  0    39.3077
//! 2.0   1   0.2 3.5  0  0  0    39.3077
//! ```
//!
//! `t` is the time in seconds (strictly increasing), `p` the eye position,
//! `t{x,y,z}` the look-at target and `fov` the vertical field of view in
//! degrees. `#` starts a comment. Positions interpolate linearly or with a
//! uniform Catmull-Rom spline, orientations (from the look-at frames, world
//! up `+Y`) with quaternion slerp, and the field of view linearly.

use std::fmt::Write as _;
use std::path::Path;

use glam::{Quat, Vec3};

use super::camera::look_rotation;
use super::{Camera, SceneError};

/// One keyframe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraKey {
    /// Time in seconds.
    pub time: f32,
    /// Eye position.
    pub position: Vec3,
    /// Look-at target.
    pub target: Vec3,
    /// Vertical field of view in degrees.
    pub vfov_degrees: f32,
}

impl CameraKey {
    fn orientation(&self) -> Quat {
        look_rotation(self.target - self.position, Vec3::Y)
    }
}

/// How positions are interpolated between keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathInterpolation {
    /// Piecewise linear.
    Linear,
    /// Uniform Catmull-Rom spline through the keys (end keys repeated).
    CatmullRom,
}

/// A keyframed camera animation.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraPath {
    keys: Vec<CameraKey>,
    /// Position interpolation.
    pub interpolation: PathInterpolation,
}

impl CameraPath {
    /// A path through `keys`, which must be non-empty, finite, with
    /// strictly increasing times and field of view in `(0, 180)`.
    pub fn new(keys: Vec<CameraKey>, interpolation: PathInterpolation) -> Result<Self, SceneError> {
        if keys.is_empty() {
            return Err(SceneError::Invalid("camera path has no keyframes".into()));
        }
        for (i, k) in keys.iter().enumerate() {
            check_key(k, keys.get(i.wrapping_sub(1)).map(|p| p.time))
                .map_err(|m| SceneError::Invalid(format!("camera path key {i}: {m}")))?;
        }
        Ok(Self {
            keys,
            interpolation,
        })
    }

    /// The keyframes.
    pub fn keys(&self) -> &[CameraKey] {
        &self.keys
    }

    /// Time of the last key.
    pub fn duration(&self) -> f32 {
        self.keys.last().map_or(0.0, |k| k.time)
    }

    /// The (pinhole) camera at time `t`, clamped to the key range.
    pub fn sample(&self, t: f32) -> Camera {
        let keys = &self.keys;
        let last = keys.len() - 1;
        let t = t.clamp(keys[0].time, keys[last].time);
        let i = keys
            .partition_point(|k| k.time <= t)
            .saturating_sub(1)
            .min(last.saturating_sub(1));
        let j = (i + 1).min(last);
        let (a, b) = (&keys[i], &keys[j]);
        let u = if b.time > a.time {
            ((t - a.time) / (b.time - a.time)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let position = match self.interpolation {
            PathInterpolation::Linear => a.position.lerp(b.position, u),
            PathInterpolation::CatmullRom => {
                let p0 = keys[i.saturating_sub(1)].position;
                let p3 = keys[(j + 1).min(last)].position;
                catmull_rom(p0, a.position, b.position, p3, u)
            }
        };
        let vfov = a.vfov_degrees + (b.vfov_degrees - a.vfov_degrees) * u;
        Camera {
            position,
            orientation: a.orientation().slerp(b.orientation(), u).normalize(),
            vfov: vfov.to_radians(),
            aperture_radius: 0.0,
            focus_distance: (a.target - a.position).length().max(1e-3),
        }
    }

    /// The path in the text format (round-trips through [`Self::parse`]).
    pub fn to_text(&self) -> String {
        let mut s = String::from("# lucid camera path\n");
        let mode = match self.interpolation {
            PathInterpolation::Linear => "linear",
            PathInterpolation::CatmullRom => "catmull-rom",
        };
        let _ = writeln!(s, "interpolation {mode}\n# t px py pz tx ty tz fov");
        for k in &self.keys {
            let (p, g) = (k.position, k.target);
            let _ = writeln!(
                s,
                "{} {} {} {} {} {} {} {}",
                k.time, p.x, p.y, p.z, g.x, g.y, g.z, k.vfov_degrees
            );
        }
        s
    }

    /// Parses the text format; errors carry the 1-based line number.
    pub fn parse(text: &str) -> Result<Self, SceneError> {
        let mut keys: Vec<CameraKey> = Vec::new();
        let mut interpolation = PathInterpolation::CatmullRom;
        let mut last_line = 0;
        for (n, raw) in text.lines().enumerate() {
            let line = n + 1;
            last_line = line;
            let err = |message: String| SceneError::PathParse { line, message };
            let content = raw.split('#').next().unwrap_or("").trim();
            if content.is_empty() {
                continue;
            }
            let fields: Vec<&str> = content.split_whitespace().collect();
            if fields[0] == "interpolation" {
                interpolation = match fields.get(1..) {
                    Some(["linear"]) => PathInterpolation::Linear,
                    Some(["catmull-rom"]) => PathInterpolation::CatmullRom,
                    _ => {
                        return Err(err(format!(
                            "expected `interpolation linear` or `interpolation catmull-rom`, found `{content}`"
                        )))
                    }
                };
                continue;
            }
            if fields.len() != 8 {
                return Err(err(format!(
                    "expected 8 numbers `t px py pz tx ty tz fov`, found {} fields",
                    fields.len()
                )));
            }
            const NAMES: [&str; 8] = ["t", "px", "py", "pz", "tx", "ty", "tz", "fov"];
            let mut v = [0f32; 8];
            for (k, f) in fields.iter().enumerate() {
                v[k] = f
                    .parse::<f32>()
                    .map_err(|_| err(format!("field `{}` is not a number: `{f}`", NAMES[k])))?;
            }
            let key = CameraKey {
                time: v[0],
                position: Vec3::new(v[1], v[2], v[3]),
                target: Vec3::new(v[4], v[5], v[6]),
                vfov_degrees: v[7],
            };
            check_key(&key, keys.last().map(|k| k.time)).map_err(err)?;
            keys.push(key);
        }
        if keys.is_empty() {
            return Err(SceneError::PathParse {
                line: last_line.max(1),
                message: "no keyframes".into(),
            });
        }
        Self::new(keys, interpolation)
    }

    /// Reads and parses a path file.
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_owned(),
            source,
        })?;
        Self::parse(&text)
    }

    /// Writes the path in the text format.
    pub fn save(&self, path: &Path) -> Result<(), SceneError> {
        std::fs::write(path, self.to_text()).map_err(|source| SceneError::Io {
            path: path.to_owned(),
            source,
        })
    }
}

fn check_key(k: &CameraKey, previous_time: Option<f32>) -> Result<(), String> {
    let finite = k.time.is_finite()
        && k.position.is_finite()
        && k.target.is_finite()
        && k.vfov_degrees.is_finite();
    if !finite {
        return Err("values must be finite".into());
    }
    if !(k.vfov_degrees > 0.0 && k.vfov_degrees < 180.0) {
        return Err(format!(
            "fov {} is outside (0, 180) degrees",
            k.vfov_degrees
        ));
    }
    if (k.target - k.position).length_squared() == 0.0 {
        return Err("target equals position".into());
    }
    if let Some(p) = previous_time {
        if k.time <= p {
            return Err(format!("time {} does not increase (previous {p})", k.time));
        }
    }
    Ok(())
}

fn catmull_rom(p0: Vec3, p1: Vec3, p2: Vec3, p3: Vec3, t: f32) -> Vec3 {
    let t2 = t * t;
    let t3 = t2 * t;
    0.5 * ((2.0 * p1)
        + (p2 - p0) * t
        + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2
        + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(mode: PathInterpolation) -> CameraPath {
        let key = |t: f32, x: f32| CameraKey {
            time: t,
            position: Vec3::new(x, 0.0, 4.0),
            target: Vec3::ZERO,
            vfov_degrees: 40.0 + t,
        };
        CameraPath::new(vec![key(0.0, -1.0), key(1.0, 0.0), key(3.0, 1.0)], mode).unwrap()
    }

    #[test]
    fn interpolates_through_keys() {
        for mode in [PathInterpolation::Linear, PathInterpolation::CatmullRom] {
            let p = path(mode);
            for k in p.keys() {
                let c = p.sample(k.time);
                assert!((c.position - k.position).length() < 1e-5);
                assert!((c.vfov.to_degrees() - k.vfov_degrees).abs() < 1e-3);
                let f = (k.target - k.position).normalize();
                assert!((c.forward() - f).length() < 1e-4);
            }
            let mid = p.sample(2.0);
            assert!(mid.position.x > 0.0 && mid.position.x < 1.0);
            assert_eq!(p.sample(-5.0).position, p.sample(0.0).position);
        }
    }

    #[test]
    fn text_round_trip_and_errors() {
        let p = path(PathInterpolation::Linear);
        assert_eq!(CameraPath::parse(&p.to_text()).unwrap(), p);

        let cases = [
            ("0 0 0 1 0 0 0 40\n0.5 0 0 1 0 0\n", 2, "8 numbers"),
            ("0 0 0 1 0 0 0 40\n1 0 0 x 0 0 0 40\n", 2, "`pz`"),
            (
                "# c\n1 0 0 1 0 0 0 40\n0.5 0 0 1 0 0 0 40\n",
                3,
                "does not increase",
            ),
            ("interpolation cubic\n", 1, "interpolation"),
            ("0 0 0 1 0 0 0 200\n", 1, "fov"),
            ("# nothing\n", 1, "no keyframes"),
        ];
        for (text, line, needle) in cases {
            match CameraPath::parse(text) {
                Err(SceneError::PathParse { line: l, message }) => {
                    assert_eq!(l, line, "{text}");
                    assert!(message.contains(needle), "{message}");
                }
                other => panic!("{text}: {other:?}"),
            }
        }
    }

    #[test]
    fn save_and_load() {
        let p = path(PathInterpolation::CatmullRom);
        let file = std::env::temp_dir().join(format!("lucid-path-{}.txt", std::process::id()));
        p.save(&file).unwrap();
        assert_eq!(CameraPath::load(&file).unwrap(), p);
        std::fs::remove_file(&file).unwrap();
        assert!(matches!(
            CameraPath::load(&file),
            Err(SceneError::Io { .. })
        ));
    }
}
