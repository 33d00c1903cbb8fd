//! glTF vertex attributes: flat normals for primitives without NORMAL (as the spec requires) and
//! vertex colours (`COLOR_0`) multiplying the base colour, only paid for by scenes that have them.

use glam::{Quat, Vec3};
use lucid_engine::capture::ImageData;
use lucid_engine::scene::gpu::GpuScene;
use lucid_engine::scene::{Bvh, Scene};
use lucid_passes::renderer::Algorithm;
use lucid_tests::gltf::{cube, plane, Doc};
use lucid_tests::render::render_once as render;

/// A grey cube of 8 shared corners (optionally with `normals`) under a directional light from
/// `towards_sun`, no camera.
fn lit_cube(normals: Option<&[[f32; 3]]>, towards_sun: Vec3) -> Scene {
    let mut doc = Doc::new();
    let (positions, indices) = cube(0.5);
    let p = doc.floats(&positions);
    let i = doc.indices(&indices);
    let mut attributes = vec![("POSITION", p)];
    if let Some(n) = normals {
        attributes.push(("NORMAL", doc.floats(n)));
    }
    let m = doc.lambertian([0.5; 3], "");
    let mesh = doc.mesh(&attributes, Some(i), Some(m));
    doc.node(&format!(r#"{{"mesh": {mesh}}}"#));
    let q = Quat::from_rotation_arc(Vec3::NEG_Z, -towards_sun.normalize());
    doc.light(
        r#"{"type": "directional", "intensity": 2000}"#,
        &format!(r#""rotation": [{}, {}, {}, {}]"#, q.x, q.y, q.z, q.w),
    );
    doc.load("cube.gltf")
}

#[test]
fn a_primitive_without_normals_gets_flat_ones() {
    let towards_sun = Vec3::new(1.0, 2.0, 3.0);
    let scene = lit_cube(None, towards_sun);
    let mesh = &scene.meshes[0];
    assert_eq!(
        mesh.positions.len(),
        36,
        "three vertices of its own per triangle"
    );
    for t in 0..mesh.triangle_count() {
        let [a, b, c] = mesh.triangle(t);
        let face = (b - a).cross(c - a).normalize();
        for k in mesh.indices[t].to_array() {
            assert!((mesh.normals[k as usize] - face).length() < 1e-6);
        }
    }
    // Direct light only, one sample per pixel: with flat normals every pixel of the cube is one of
    // three values, albedo / π × E × cos for the three faces in view (+x, +y, +z).
    let sun = scene.sun.unwrap();
    let faces = [Vec3::X, Vec3::Y, Vec3::Z]
        .map(|n| 0.5 / std::f32::consts::PI * sun.irradiance.x * n.dot(sun.direction).max(0.0));
    let off_face = |scene: Scene| {
        let image = render(scene, Algorithm::PathTracing, 1, 2, 64);
        let lit: Vec<f32> = image
            .pixels
            .iter()
            .map(|p| p[0])
            .filter(|&v| v > 1e-4)
            .collect();
        let off = lit
            .iter()
            .filter(|&&v| faces.iter().all(|f| (v - f).abs() > 0.03 * f))
            .count();

        (off as f32 / lit.len() as f32, lit.len())
    };
    let (flat_off, flat_lit) = off_face(scene);
    println!(
        "flat normals: {flat_lit} lit pixels, {:.1}% off the three face values",
        100.0 * flat_off
    );
    assert!(flat_lit > 500, "the cube fills the frame");
    assert_eq!(flat_off, 0.0, "each face is uniformly shaded");
    // The same cube with smooth (corner-averaged) normals, as the importer made before: shading
    // varies across each face.
    let (positions, _) = cube(0.5);
    let smooth: Vec<[f32; 3]> = positions
        .iter()
        .map(|p| Vec3::from(*p).normalize().to_array())
        .collect();
    let (smooth_off, _) = off_face(lit_cube(Some(&smooth), towards_sun));
    println!("smooth normals: {:.1}% off", 100.0 * smooth_off);
    assert!(smooth_off > 0.5, "{smooth_off}");
}

/// Writes a plane with `COLOR_0` from `colors` (an accessor the closure adds), or none.
fn colored_plane(colors: Option<&dyn Fn(&mut Doc) -> usize>) -> Scene {
    let mut doc = Doc::new();
    let (positions, indices) = plane(1.0);
    let p = doc.floats(&positions);
    let i = doc.indices(&indices);
    let mut attributes = vec![("POSITION", p)];
    if let Some(colors) = colors {
        attributes.push(("COLOR_0", colors(&mut doc)));
    }
    let m = doc.lambertian([1.0; 3], "");
    let mesh = doc.mesh(&attributes, Some(i), Some(m));
    doc.node(&format!(r#"{{"mesh": {mesh}}}"#));
    doc.load("plane.gltf")
}

#[test]
fn vertex_colours_import_in_every_format_and_only_their_scenes_pay() {
    let want = [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 1.0, 1.0),
    ];
    let f32x3 = |d: &mut Doc| d.floats(&want.map(|c| c.to_array()));
    let f32x4 = |d: &mut Doc| d.floats(&want.map(|c| c.extend(0.5).to_array()));
    let u8x4 = |d: &mut Doc| {
        d.unorm8(&want.map(|c| (c * 255.0).extend(255.0).to_array().map(|x| x as u8)))
    };
    let u16x3 = |d: &mut Doc| d.unorm16(&want.map(|c| (c * 65535.0).to_array().map(|x| x as u16)));
    for (name, colors) in [
        ("f32 vec3", &f32x3 as &dyn Fn(&mut Doc) -> usize),
        ("f32 vec4", &f32x4),
        ("u8 vec4", &u8x4),
        ("u16 vec3", &u16x3),
    ] {
        let scene = colored_plane(Some(colors));
        // No NORMAL: flat, so the vertices are the corners of the two triangles.
        let mesh = &scene.meshes[0];
        for (k, v) in mesh.indices.iter().flat_map(|t| t.to_array()).enumerate() {
            let corner = [0, 1, 2, 0, 2, 3][k];
            assert_eq!(mesh.colors[v as usize], want[corner], "{name}");
        }
        assert!(scene.features().vertex_colors, "{name}");
        let gpu = GpuScene::new(&scene, &Bvh::build(&scene));
        assert_eq!(gpu.vertex_attributes.len(), gpu.vertices.len(), "{name}");
    }
    // Without COLOR_0 there is neither the buffer nor the shader code.
    let plain = colored_plane(None);
    assert!(plain.meshes[0].colors.is_empty());
    assert!(!plain.features().vertex_colors);
    assert!(plain
        .features()
        .specialization_constants()
        .contains(&("HAS_VERTEX_COLORS", false)));
    let gpu = GpuScene::new(&plain, &Bvh::build(&plain));
    assert!(gpu.vertex_attributes.is_empty());
    // A colour accessor of the wrong shape or count is an error naming it, not a panic.
    let mut doc = Doc::new();
    let (positions, indices) = plane(1.0);
    let p = doc.floats(&positions);
    let i = doc.indices(&indices);
    let c = doc.floats(&[[1.0, 0.0]; 4]);
    let short = doc.floats(&[[1.0, 0.0, 0.0]; 3]);
    for (label, color) in [("vec2", c), ("short", short)] {
        let mut bad = doc.clone();
        let mesh = bad.mesh(&[("POSITION", p), ("COLOR_0", color)], Some(i), None);
        bad.node(&format!(r#"{{"mesh": {mesh}}}"#));
        let err = lucid_engine::scene::load_gltf_slice(bad.json().as_bytes(), None, "bad.gltf")
            .unwrap_err()
            .to_string();
        assert!(err.contains("bad.gltf"), "{label}: {err}");
        assert!(
            err.contains("COLOR_0") || err.contains("counts differ"),
            "{label}: {err}"
        );
    }
}

/// A floor with red vertex colours (on a white material), or none, lit by a narrow spot light, and
/// a white wall behind it that only the floor's bounce lights; no camera.
fn red_floor_and_wall(red: bool) -> Scene {
    let mut doc = Doc::new();
    let (positions, indices) = plane(1.0);
    let p = doc.floats(&positions);
    let i = doc.indices(&indices);
    let mut floor = vec![("POSITION", p)];
    if red {
        floor.push(("COLOR_0", doc.unorm8(&[[255u8, 0, 0]; 4])));
    }
    let m = doc.lambertian([1.0; 3], "");
    let floor = doc.mesh(&floor, Some(i), Some(m));
    doc.node(&format!(r#"{{"mesh": {floor}}}"#));
    let wall = doc.mesh(&[("POSITION", p)], Some(i), Some(m));
    // The plane turned to face +z, standing on the floor's far edge.
    let q = Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
    doc.node(&format!(
        r#"{{"mesh": {wall}, "rotation": [{}, {}, {}, {}], "translation": [0, 1, -1]}}"#,
        q.x, q.y, q.z, q.w
    ));
    let down = Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2);
    doc.light(
        r#"{"type": "spot", "intensity": 200000, "spot": {"outerConeAngle": 0.7, "innerConeAngle": 0.5}}"#,
        &format!(
            r#""rotation": [{}, {}, {}, {}], "translation": [0, 1, 0.5]"#,
            down.x, down.y, down.z, down.w
        ),
    );
    doc.load("red-floor.gltf")
}

#[test]
fn vertex_colours_tint_the_surface_and_its_bounce_with_both_algorithms() {
    let size = 32;
    // (share of pixels with red light, share with green or blue light)
    let shares = |image: &ImageData| {
        let n = image.pixels.len() as f32;
        let red = image.pixels.iter().filter(|p| p[0] > 0.0).count() as f32 / n;
        let other = image
            .pixels
            .iter()
            .filter(|p| p[1] > 0.0 || p[2] > 0.0)
            .count() as f32
            / n;
        (red, other)
    };
    let white = render(
        red_floor_and_wall(false),
        Algorithm::PathTracing,
        64,
        4,
        size,
    );
    let (lit, other) = shares(&white);
    println!("white floor: {lit} lit, {other} green or blue");
    assert!(lit > 0.25 && other == lit, "floor and wall are lit white");
    for algorithm in Algorithm::ALL {
        let image = render(red_floor_and_wall(true), algorithm, 64, 4, size);
        let (red, other) = shares(&image);
        println!(
            "{}: red floor: {red} red, {other} green or blue",
            algorithm.short_name()
        );
        // The spot lights the wall only through the red floor: floor and wall are red, with no
        // green or blue anywhere (a white vertex colour in BDPT's cached light vertices would
        // bring them back).
        assert!(red > 0.8 * lit, "{}: {red}", algorithm.short_name());
        assert_eq!(other, 0.0, "{}", algorithm.short_name());
    }
}
