//! `random-room-<seed>`: procedurally generated rooms, deterministic for a
//! seed, meant as varied training data (for example for a learned
//! denoiser).
//!
//! Each seed draws a closed box room 3 to 10 m wide and deep and 2.5 to
//! 4.5 m high (plain or accent-coloured walls, sometimes a wainscot band, a
//! plain or tiled floor, matte or now and then polished or metal), 4 to 16
//! objects (cuboids, analytic spheres, cylinders and now and then a Utah
//! teapot, on the floor or stacked on a cuboid) whose materials are diffuse, conductor (GGX alpha 0.02 to 0.5),
//! glass (IOR 1.5, smooth or rough) or emissive, and its lights: one to
//! three emissive panels or hanging boxes, or, in rooms with windows in the
//! back wall, the sun and sky of `blinds-room` shining in plus up to two of
//! those (so some rooms are lit only through the windows); and in about
//! two rooms of five a caustic: a smooth glass sphere on the floor under a
//! small, bright lamp hanging beside it. The default
//! camera path is one continuous 4 to 6 s move inside the room: a slow
//! pan, a dolly forward or back, a fast turn (a large yaw within about
//! half a second) or an orbit around an object. Scenes stay well under
//! 200 k triangles.
//!
//! The generator uses its own SplitMix64 stream, so a seed gives the same
//! scene (same [`Scene::content_hash`]) on every run and platform with the
//! same floating-point maths. These scenes are reachable by name through
//! [`super::build`] and [`super::build_with`] (`random-room-17`) but are
//! not listed in [`super::names`], so the list of built-in scenes stays
//! the same.

mod camera_moves;
mod caustic;
mod lights;
mod materials;
mod objects;
mod placement;
mod rng;
mod room;

use glam::Vec3;

use crate::scene::{Camera, Scene, SceneError};
use placement::SharedMeshes;
use rng::Rng;
use room::Room;

/// Prefix of the scene names, followed by the seed in decimal.
pub const NAME_PREFIX: &str = "random-room-";

/// Mixed into the seed for the floor's finish, drawn apart from the layout so that adding the
/// finish left every seed's room otherwise as it was.
const FLOOR_FINISH_STREAM: u64 = 0x666c_6f6f_7246_494e;

/// Mixed into the seed for the caustic, drawn apart from the layout so that adding it left the
/// rooms without one as they were (those with one differ only where the camera steers clear of
/// it).
const CAUSTIC_STREAM: u64 = 0x6361_7573_7469_6373;

pub use caustic::{GLASS as CAUSTIC_GLASS, LAMP as CAUSTIC_LAMP};

/// Builds the random room of `seed`, named `random-room-<seed>`.
pub fn random_room(seed: u64) -> Result<Scene, SceneError> {
    let mut rng = Rng::new(seed);
    let mut finish = Rng::new(seed ^ FLOOR_FINISH_STREAM);
    let mut scene = Scene::new(&format!("{NAME_PREFIX}{seed}"));
    let room = Room::random(&mut rng);
    let windows = room::add(&mut scene, &mut rng, &mut finish, &room);
    let mut meshes = SharedMeshes::default();
    let mut obstacles = lights::add(&mut scene, &mut rng, &room, windows, &mut meshes);
    objects::add(&mut scene, &mut rng, &room, &mut obstacles, &mut meshes);
    caustic::add(
        &mut scene,
        &mut Rng::new(seed ^ CAUSTIC_STREAM),
        &room,
        &mut obstacles,
    );
    let path = camera_moves::random_path(&mut rng, &room, &obstacles)?;
    let first = path.keys()[0];
    scene.camera = Camera::look_at(first.position, first.target, Vec3::Y, first.vfov_degrees);
    scene.camera_path = Some(path);
    scene.validate()?;
    Ok(scene)
}

/// The random room `name` asks for, or `None` if `name` does not start
/// with [`NAME_PREFIX`]; a seed that is not a decimal `u64` is an error.
pub(super) fn from_name(name: &str) -> Option<Result<Scene, SceneError>> {
    let digits = name.strip_prefix(NAME_PREFIX)?;
    let seed = digits
        .bytes()
        .all(|b| b.is_ascii_digit())
        .then(|| digits.parse::<u64>().ok())
        .flatten();
    let invalid = || {
        SceneError::Invalid(format!(
            "scene `{name}`: the seed after `{NAME_PREFIX}` must be a whole number from 0 to {}",
            u64::MAX
        ))
    };
    Some(seed.ok_or_else(invalid).and_then(random_room))
}
