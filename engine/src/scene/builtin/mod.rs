//! Built-in procedural scenes, built deterministically (no downloads, no
//! randomness), each with a default camera and camera path.
//!
//! Besides the named scenes of [`names`], [`build`] and [`build_with`]
//! accept `random-room-<seed>` (see [`random_room()`]): a seeded
//! procedural room, deterministic for its seed, not listed in [`names`].

mod blinds_room;
mod caustics;
mod classroom;
pub mod cornell_box;
mod cornell_teapot;
mod covered_light;
mod displaced_sphere;
mod furnace;
mod paths;
mod random_room;
pub mod shapes;
mod teapot;
mod teapot_data;

pub use random_room::{
    random_room, CAUSTIC_GLASS, CAUSTIC_LAMP, NAME_PREFIX as RANDOM_ROOM_PREFIX,
};
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
///
/// Names of the form `random-room-<seed>` (`<seed>` a decimal `u64`, e.g.
/// `random-room-17`) build [`random_room()`] of that seed, although
/// [`names`] does not list them; `options` do not apply to them, and a
/// seed that does not parse is a [`SceneError::Invalid`].
pub fn build_with(name: &str, options: &BuildOptions) -> Result<Scene, SceneError> {
    match name {
        "cornell-box" => cornell_box::build(),
        "cornell-teapot" => cornell_teapot::build(options),
        "covered-light" => covered_light::build(options),
        "blinds-room" => blinds_room::build(),
        "classroom" => classroom::build(options),
        "furnace" => furnace::build(),
        "caustics" => caustics::build(),
        _ => random_room::from_name(name).unwrap_or_else(|| {
            Err(SceneError::UnknownScene {
                name: name.to_owned(),
                available: format!("{}, {RANDOM_ROOM_PREFIX}<seed>", NAMES.join(", ")),
            })
        }),
    }
}
