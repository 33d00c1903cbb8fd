//! Built-in scenes: registry, determinism, Mitsuba fidelity, budgets and
//! features.

use glam::Vec3;
use lucid_engine::scene::builtin::{self, BuildOptions};
use lucid_engine::scene::{MaterialKind, SceneError};

/// Small enough for quick debug-build tests.
const REDUCED: BuildOptions = BuildOptions { detail: 0.01 };

#[test]
fn registry_lists_scenes_and_rejects_unknown_names() {
    assert_eq!(builtin::names().len(), 7);
    let err = builtin::build("no-such-scene").unwrap_err();
    assert!(matches!(err, SceneError::UnknownScene { .. }));
    let msg = err.to_string();
    for n in builtin::names() {
        assert!(msg.contains(n), "{msg}");
    }
}

#[test]
fn builtins_are_deterministic_lit_and_animated() {
    for name in builtin::names() {
        let a = builtin::build_with(name, &REDUCED).unwrap();
        let b = builtin::build_with(name, &REDUCED).unwrap();
        assert_eq!(a.content_hash(), b.content_hash(), "{name}");
        assert_eq!(a, b, "{name}");
        assert!(a.has_light(), "{name}");
        assert!(a.warnings.is_empty(), "{name}: {:?}", a.warnings);
        let path = a.camera_path.as_ref().unwrap();
        assert!(path.duration() > 0.0, "{name}");
        assert!(
            (path.sample(0.0).position - a.camera.position).length() < 1e-4,
            "{name}"
        );
    }
    let c = builtin::build("cornell-box").unwrap();
    assert_ne!(
        c.content_hash(),
        builtin::build("caustics").unwrap().content_hash()
    );
}

#[test]
fn cornell_box_matches_mitsuba_definition() {
    let s = builtin::build("cornell-box").unwrap();
    assert_eq!(s.triangle_count(), 6 * 2 + 2 * 12);
    let find = |n: &str| s.materials.iter().find(|m| m.name == n).unwrap();
    assert_eq!(
        find("white").base_color,
        Vec3::new(0.885809, 0.698859, 0.666422)
    );
    assert_eq!(
        find("green").base_color,
        Vec3::new(0.105421, 0.37798, 0.076425)
    );
    assert_eq!(
        find("red").base_color,
        Vec3::new(0.570068, 0.0430135, 0.0443706)
    );
    assert_eq!(find("light").emission, Vec3::new(18.387, 13.9873, 6.75357));
    // Light corners: x ±0.23, y 0.99, z 0.01 ± 0.19, facing down.
    let light = s
        .instances
        .iter()
        .enumerate()
        .find(|(i, _)| s.materials[s.instance_material(*i) as usize].is_emissive())
        .unwrap()
        .1;
    let mesh = &s.meshes[light.mesh as usize];
    for p in &mesh.positions {
        let w = light.transform.transform_point3(*p);
        assert!(
            (w.x.abs() - 0.23).abs() < 1e-5 && (w.y - 0.99).abs() < 1e-5,
            "{w}"
        );
        assert!(((w.z - 0.01).abs() - 0.19).abs() < 1e-5, "{w}");
    }
    let n = light
        .transform
        .transform_vector3(mesh.normals[0])
        .normalize();
    assert!((n - Vec3::NEG_Y).length() < 1e-5);
    // Walls: the green wall is at x = +1 facing -x, the red one at x = -1.
    let wall_normal = |mat: &str| {
        let (_, inst) = s
            .instances
            .iter()
            .enumerate()
            .find(|(i, inst)| {
                s.materials[s.instance_material(*i) as usize].name == mat
                    && s.meshes[inst.mesh as usize].name == "rectangle"
            })
            .unwrap();
        inst.transform.transform_vector3(Vec3::Z).normalize()
    };
    assert!((wall_normal("green") - Vec3::NEG_X).length() < 1e-5);
    assert!((wall_normal("red") - Vec3::X).length() < 1e-5);
    assert_eq!(s.camera.position, Vec3::new(0.0, 0.0, 3.9));
    assert!((s.camera.vfov.to_degrees() - 39.3077).abs() < 1e-4);
    assert!((s.camera.forward() - Vec3::NEG_Z).length() < 1e-6);
    let b = s.bounds();
    // Mitsuba's large box (y = -0.4 ± 0.61) pokes 1 cm through the floor.
    let expected_min = Vec3::new(-1.0, -1.01, -1.0);
    assert!(
        (b.min - expected_min).length() < 1e-5 && (b.max - Vec3::ONE).length() < 1e-5,
        "{b:?}"
    );
}

#[test]
fn triangle_budgets() {
    let classroom = builtin::build("classroom").unwrap();
    assert!(
        classroom.triangle_count() >= 500_000,
        "{}",
        classroom.triangle_count()
    );
    assert!(classroom.instances.len() > 100);
    let covered = builtin::build_with("covered-light", &REDUCED).unwrap();
    assert!(covered.triangle_count() >= 50_000);
    assert_eq!(covered.spheres.len(), 1);
}

#[test]
fn covered_light_full_detail_has_five_million_triangles() {
    let full = builtin::build("covered-light").unwrap();
    assert!(
        full.triangle_count() >= 5_000_000,
        "{}",
        full.triangle_count()
    );
}

#[test]
fn furnace_has_a_closed_form_and_others_do_not() {
    let f = builtin::build("furnace").unwrap();
    let a = f.analytic_radiance().unwrap();
    assert_eq!(a.background, Vec3::ONE);
    assert!((a.object - Vec3::splat(0.8)).length() < 1e-6);
    assert!(builtin::build("cornell-box")
        .unwrap()
        .analytic_radiance()
        .is_none());
}

#[test]
fn features_follow_scene_content() {
    let get = |n: &str| builtin::build_with(n, &REDUCED).unwrap().features();
    let cbox = get("cornell-box");
    assert!(cbox.diffuse && cbox.emissive && !cbox.conductor && !cbox.spheres && !cbox.environment);
    let tea = get("cornell-teapot");
    assert!(tea.conductor && tea.dielectric_smooth && !tea.dielectric_rough);
    let blinds = get("blinds-room");
    assert!(blinds.sun && blinds.environment && !blinds.emissive);
    let class = get("classroom");
    assert!(class.textures && class.emissive && class.sun);
    let furnace = get("furnace");
    assert!(furnace.spheres && furnace.environment && !furnace.emissive && furnace.diffuse);
    let caustics = get("caustics");
    assert!(caustics.dielectric_smooth && caustics.spheres);
    let consts = caustics.specialization_constants();
    assert!(consts.contains(&("HAS_DIELECTRIC", true)));
    assert!(consts.contains(&("HAS_CONDUCTOR", false)));
    let shown = caustics.to_string();
    assert!(
        shown.contains("HAS_SPHERES") && !shown.contains("HAS_SUN"),
        "{shown}"
    );
    let kinds: Vec<MaterialKind> = builtin::build("cornell-teapot")
        .unwrap()
        .materials
        .iter()
        .map(|m| m.kind)
        .collect();
    assert!(kinds.contains(&MaterialKind::Dielectric));
}
