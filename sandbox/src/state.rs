//! Everything the user can change in the app, and the note shown to them.

use super::auto::AutoState;
use super::camera::{Bookmarks, FlyCamera, PathPlayer, PathRecorder, Pose};
use super::scene::SceneInfo;
use super::settings::{DisplaySettings, RenderSettings};

/// A camera path being recorded or replayed, with its start time (app seconds).
pub enum PathMode {
    /// Neither.
    Idle,
    /// Recording since the time given.
    Recording(PathRecorder, f64),
    /// Replaying since the time given.
    Replaying(PathPlayer, f64),
}

/// The app's editable state.
pub struct AppState {
    /// The loaded scene, or why it failed to load.
    pub scene: Result<SceneInfo, String>,
    /// The scene field of the panel (name or file).
    pub scene_field: String,
    /// Renderer settings (of the left half while the split view is on).
    pub render: RenderSettings,
    /// The right half's renderer settings while the split view is on.
    pub split: Option<RenderSettings>,
    /// The calibration's goal and last choice.
    pub auto: AutoState,
    /// Display settings.
    pub display: DisplaySettings,
    /// The camera.
    pub camera: FlyCamera,
    /// Camera bookmarks.
    pub bookmarks: Bookmarks,
    /// Path recording or replay.
    pub path: PathMode,
    /// The path file field of the panel.
    pub path_file: String,
    /// The last message for the user (captures, errors), if any.
    pub message: Option<String>,
}

impl AppState {
    /// The state for `scene` (loaded or failed), camera at the scene's camera.
    pub fn new(spec: &str, scene: anyhow::Result<SceneInfo>) -> Self {
        let scene = scene.map_err(|e| format!("{e:#}"));
        let pose = match &scene {
            Ok(info) => Pose::from_camera(&info.camera),
            Err(_) => Pose {
                position: glam::Vec3::new(0.0, 1.0, 4.0),
                yaw: 0.0,
                pitch: 0.0,
                vfov_degrees: 45.0,
            },
        };
        Self {
            scene_field: spec.to_string(),
            message: scene.as_ref().err().cloned(),
            scene,
            render: RenderSettings::default(),
            split: None,
            auto: AutoState::default(),
            display: DisplaySettings::default(),
            camera: FlyCamera::new(pose, 1.0),
            bookmarks: Bookmarks::default(),
            path: PathMode::Idle,
            path_file: "camera-path.txt".into(),
        }
    }

    /// Replaces the scene (on success the camera jumps to the scene's camera).
    pub fn set_scene(&mut self, scene: anyhow::Result<SceneInfo>) {
        match scene {
            Ok(info) => {
                self.camera.pose = Pose::from_camera(&info.camera);
                self.message = Some(format!("loaded {}", info.source));
                self.scene = Ok(info);
            }
            Err(e) => {
                let text = format!("{e:#}");
                self.message = Some(text.clone());
                self.scene = Err(text);
            }
        }
    }
}
