//! Recording the camera to a path file and replaying one, in the engine's camera path format
//! (one keyframe per line: `t px py pz tx ty tz fov`), which `lucid render` reads too.
//! Times are passed in by the caller, so the logic is independent of any clock.

use super::Pose;
use anyhow::Context as _;
use lucid_engine::scene::{CameraKey, CameraPath, PathInterpolation};
use std::path::Path;

/// Seconds between recorded keyframes.
const KEY_INTERVAL: f32 = 0.1;

/// Collects keyframes while the user flies.
#[derive(Clone, Debug, Default)]
pub struct PathRecorder {
    keys: Vec<CameraKey>,
}

impl PathRecorder {
    /// Offers the pose at `time` seconds since recording began; keeps one every 0.1 s.
    pub fn record(&mut self, time: f32, pose: &Pose) {
        let due = self
            .keys
            .last()
            .is_none_or(|last| time >= last.time + KEY_INTERVAL);
        if due {
            self.keys.push(CameraKey {
                time,
                position: pose.position,
                target: pose.position + pose.forward(),
                vfov_degrees: pose.vfov_degrees,
            });
        }
    }

    /// Keyframes recorded so far.
    pub fn len(&self) -> usize {
        self.keys.len()
    }

    /// The recorded path.
    pub fn finish(self) -> anyhow::Result<CameraPath> {
        Ok(CameraPath::new(self.keys, PathInterpolation::CatmullRom)?)
    }

    /// Writes the recorded path to `file`.
    pub fn save(self, file: &Path) -> anyhow::Result<()> {
        let path = self.finish()?;
        path.save(file)
            .with_context(|| format!("writing camera path {}", file.display()))
    }
}

/// Replays a camera path.
#[derive(Clone, Debug)]
pub struct PathPlayer {
    path: CameraPath,
}

impl PathPlayer {
    /// Loads a path file.
    pub fn load(file: &Path) -> anyhow::Result<Self> {
        let path = CameraPath::load(file)
            .with_context(|| format!("reading camera path {}", file.display()))?;
        Ok(Self { path })
    }

    /// The pose at `time` seconds into the replay, or `None` once the path has ended.
    pub fn sample(&self, time: f32) -> Option<Pose> {
        (time <= self.path.duration()).then(|| Pose::from_camera(&self.path.sample(time)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn records_at_intervals_and_replays_from_a_file() {
        let mut rec = PathRecorder::default();
        for i in 0..=20 {
            let t = i as f32 * 0.06;
            let pose = Pose {
                position: Vec3::new(t, 0.0, 0.0),
                yaw: 0.0,
                pitch: 0.0,
                vfov_degrees: 45.0,
            };
            rec.record(t, &pose);
        }
        assert_eq!(rec.len(), 11);
        let file = std::env::temp_dir().join(format!("lucid-path-{}.txt", std::process::id()));
        rec.save(&file).unwrap();
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(text.lines().any(|l| l.split_whitespace().count() == 8));
        let player = PathPlayer::load(&file).unwrap();
        std::fs::remove_file(&file).unwrap();
        let mid = player.sample(0.5).unwrap();
        assert!((mid.position.x - 0.5).abs() < 1e-3);
        assert!(mid.forward().z < -0.99);
        assert!(player.sample(2.0).is_none());
    }

    #[test]
    fn an_empty_recording_is_an_error() {
        assert!(PathRecorder::default().finish().is_err());
    }
}
