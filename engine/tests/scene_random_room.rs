//! Procedural rooms (`random-room-<seed>`): determinism, variety,
//! validity, lighting, camera paths, the mix of materials and the caustics.

use std::collections::HashSet;

use lucid_engine::scene::builtin::{self, random_room, CAUSTIC_GLASS, CAUSTIC_LAMP};
use lucid_engine::scene::{Material, MaterialKind, Scene, SceneError};

const SEEDS: std::ops::Range<u64> = 0..200;

fn rooms(seeds: std::ops::Range<u64>) -> Vec<Scene> {
    seeds.map(|s| random_room(s).unwrap()).collect()
}

#[test]
fn same_seed_same_scene_and_reachable_by_name() {
    for seed in [0, 17, u64::MAX] {
        let a = random_room(seed).unwrap();
        let b = builtin::build(&format!("random-room-{seed}")).unwrap();
        assert_eq!(a.name, format!("random-room-{seed}"));
        assert_eq!(a.content_hash(), b.content_hash(), "{seed}");
        assert_eq!(a, b, "{seed}");
    }
    assert!(!builtin::names()
        .iter()
        .any(|n| n.starts_with("random-room")));
}

#[test]
fn bad_seeds_are_clear_errors() {
    for name in [
        "random-room-",
        "random-room-x",
        "random-room--1",
        "random-room-+1",
        "random-room-1.5",
        "random-room-18446744073709551616",
    ] {
        match builtin::build(name) {
            Err(SceneError::Invalid(message)) => {
                assert!(
                    message.contains(name) && message.contains("seed"),
                    "{message}"
                )
            }
            other => panic!("{name}: {other:?}"),
        }
    }
    let unknown = builtin::build("no-such-scene").unwrap_err().to_string();
    assert!(unknown.contains("random-room-<seed>"), "{unknown}");
}

#[test]
fn seeds_differ() {
    let scenes = rooms(0..50);
    let hashes: HashSet<u64> = scenes.iter().map(Scene::content_hash).collect();
    assert_eq!(hashes.len(), scenes.len());
    let object_counts: HashSet<usize> = scenes
        .iter()
        .map(|s| s.instances.len() + s.spheres.len())
        .collect();
    assert!(object_counts.len() > 5, "{object_counts:?}");
    let windows = scenes.iter().filter(|s| s.sun.is_some()).count();
    assert!(windows > 5 && windows < 45, "{windows} of 50 have windows");
}

#[test]
fn every_seed_is_valid_lit_and_small() {
    for mut scene in rooms(SEEDS) {
        let name = scene.name.clone();
        scene.validate().unwrap();
        assert!(scene.warnings.is_empty(), "{name}: {:?}", scene.warnings);
        assert!(scene.has_light(), "{name}");
        assert!(scene.triangle_count() < 200_000, "{name}");
    }
}

#[test]
fn camera_paths_stay_inside_the_room() {
    for scene in rooms(SEEDS) {
        let name = &scene.name;
        let room = scene.bounds();
        let path = scene.camera_path.as_ref().unwrap();
        assert!((4.0..=6.0).contains(&path.duration()), "{name}");
        assert!((path.sample(0.0).position - scene.camera.position).length() < 1e-4);
        for k in path.keys() {
            assert!(
                k.position.cmpgt(room.min + 0.3).all() && k.position.cmplt(room.max - 0.3).all(),
                "{name}: key {k:?} outside {room:?}"
            );
        }
        for i in 0..=100 {
            let p = path.sample(i as f32 * path.duration() / 100.0).position;
            assert!(
                p.cmpgt(room.min).all() && p.cmplt(room.max).all(),
                "{name}: {p} outside {room:?}"
            );
        }
    }
}

/// Some floors are glossy (polished or metal, GGX alpha up to 0.25, the reflections that smear under
/// reprojection), most are matte, and tiles share their floor's finish.
#[test]
fn some_floors_are_glossy() {
    let scenes = rooms(0..60);
    let floors = |s: &Scene| -> Vec<Material> {
        s.materials
            .iter()
            .filter(|m| m.name == "floor" || m.name == "floor-tile")
            .cloned()
            .collect()
    };
    let mut glossy = 0;
    for s in &scenes {
        let f = floors(s);
        assert!(!f.is_empty(), "{}: no floor", s.name);
        assert!(
            f.iter()
                .all(|m| m.kind == f[0].kind && m.alpha == f[0].alpha),
            "{}: the tiles' finish differs from the floor's",
            s.name
        );
        match f[0].kind {
            MaterialKind::Diffuse => {}
            MaterialKind::Conductor | MaterialKind::MetalRough => {
                assert!(f[0].alpha > 0.0 && f[0].alpha <= 0.25, "{}", s.name);
                glossy += 1;
            }
            kind => panic!("{}: a {kind:?} floor", s.name),
        }
    }
    assert!((9..=30).contains(&glossy), "{glossy} glossy floors of 60");
}

#[test]
fn every_material_kind_appears() {
    let scenes = rooms(0..50);
    let materials = || scenes.iter().flat_map(|s| &s.materials);
    for kind in [
        MaterialKind::Diffuse,
        MaterialKind::Conductor,
        MaterialKind::Dielectric,
    ] {
        assert!(materials().any(|m| m.kind == kind), "{kind:?}");
    }
    assert!(materials().any(|m| m.kind == MaterialKind::Dielectric && m.alpha > 0.0));
    assert!(materials().any(|m| m.name.ends_with("emissive") && m.is_emissive()));
    let teapots = scenes
        .iter()
        .filter(|s| s.meshes.iter().any(|m| m.name == "teapot"))
        .count();
    assert!(teapots > 0);
    let sun_only = scenes
        .iter()
        .filter(|s| !s.materials.iter().any(|m| m.name.starts_with("light-")))
        .count();
    assert!(sun_only > 0, "no room is lit only through its windows");
}

/// About two rooms of five have a caustic: a smooth glass sphere resting on the floor, and a small
/// lamp facing down from above its top and beside its centre (so that the focused light falls on
/// the floor next to it), the two clear of every other sphere; the rooms without one are the same
/// as before it was added (their layout drawn from the same stream).
#[test]
fn some_rooms_have_a_caustic() {
    let scenes = rooms(0..50);
    let mut with = 0;
    for s in &scenes {
        let glass = s.materials.iter().position(|m| m.name == CAUSTIC_GLASS);
        let lamp = s.materials.iter().position(|m| m.name == CAUSTIC_LAMP);
        assert_eq!(glass.is_some(), lamp.is_some(), "{}", s.name);
        let (Some(glass), Some(lamp)) = (glass, lamp) else {
            continue;
        };
        with += 1;
        let material = &s.materials[glass];
        assert_eq!(material.kind, MaterialKind::Dielectric, "{}", s.name);
        assert_eq!(material.alpha, 0.0, "{}: a rough caustic glass", s.name);
        assert!(s.materials[lamp].is_emissive(), "{}", s.name);
        let spheres: Vec<_> = s
            .spheres
            .iter()
            .filter(|sp| sp.material == glass as u32)
            .collect();
        assert_eq!(spheres.len(), 1, "{}", s.name);
        let sphere = spheres[0];
        assert!(
            (sphere.center.y - sphere.radius).abs() < 1e-5,
            "{}: not on the floor",
            s.name
        );
        let panel = s
            .meshes
            .iter()
            .find(|m| m.name == CAUSTIC_LAMP)
            .unwrap_or_else(|| panic!("{}: no lamp mesh", s.name));
        let lowest = panel.positions.iter().map(|p| p.y).fold(f32::MAX, f32::min);
        let middle =
            panel.positions.iter().copied().sum::<glam::Vec3>() / panel.positions.len() as f32;
        assert!(
            lowest > sphere.center.y + sphere.radius + 0.3,
            "{}: the lamp is not above",
            s.name
        );
        let beside =
            glam::Vec2::new(middle.x - sphere.center.x, middle.z - sphere.center.z).length();
        assert!(
            beside > 0.2 * sphere.radius && beside < 1.3 * sphere.radius,
            "{}: {beside}",
            s.name
        );
        for other in s.spheres.iter().filter(|sp| sp.material != glass as u32) {
            assert!(
                other.center.distance(sphere.center) > other.radius + sphere.radius,
                "{}: a sphere inside the caustic's glass",
                s.name
            );
        }
    }
    assert!(
        (10..=30).contains(&with),
        "{with} of 50 rooms have a caustic"
    );
}
