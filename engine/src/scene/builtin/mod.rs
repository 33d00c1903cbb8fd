//! Built-in procedural scenes, built deterministically (no downloads, no
//! randomness), each with a default camera and camera path.

mod blinds_room;
mod caustics;
mod classroom;
pub mod cornell_box;
mod cornell_teapot;
mod covered_light;
mod displaced_sphere;
mod furnace;
mod paths;
pub mod shapes;
mod teapot;
mod teapot_data;

pub use teapot::teapot;

use super::{Scene, SceneError};

/// Options for building a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildOptions {
    /// Fraction in `(0, 1]` of the default triangle budget of the
    /// tessellated scenes (`cornell-teapot`, `covered-light`, `classroom`);
    /// 1 is the full-size scene. Scenes without tessellation ignore it.
    pub detail: f32,
}

impl Default for BuildOptions {
    fn default() -> Self {
        Self { detail: 1.0 }
    }
}

const NAMES: [&str; 7] = [
    "cornell-box",
    "cornell-teapot",
    "covered-light",
    "blinds-room",
    "classroom",
    "furnace",
    "caustics",
];

/// Names of all built-in scenes.
pub fn names() -> &'static [&'static str] {
    &NAMES
}

/// Builds a built-in scene at full detail.
pub fn build(name: &str) -> Result<Scene, SceneError> {
    build_with(name, &BuildOptions::default())
}

/// Builds a built-in scene with options; an unknown name is an error that
/// lists the valid names.
pub fn build_with(name: &str, options: &BuildOptions) -> Result<Scene, SceneError> {
    match name {
        "cornell-box" => cornell_box::build(),
        "cornell-teapot" => cornell_teapot::build(options),
        "covered-light" => covered_light::build(options),
        "blinds-room" => blinds_room::build(),
        "classroom" => classroom::build(options),
        "furnace" => furnace::build(),
        "caustics" => caustics::build(),
        _ => Err(SceneError::UnknownScene {
            name: name.to_owned(),
            available: NAMES.join(", "),
        }),
    }
}
