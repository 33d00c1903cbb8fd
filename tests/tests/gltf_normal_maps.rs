//! glTF normal maps: the tangent-space normal of `normalTexture` (scaled by `scale`) bends the
//! shading normal in the G-buffer and in light transport, with the file's TANGENT or MikkTSpace
//! tangents, which must agree.

use glam::{Quat, Vec3};
use lucid_engine::capture::ImageData;
use lucid_engine::scene::Scene;
use lucid_passes::renderer::Algorithm;
use lucid_tests::gltf::{uv_plane, Doc, TopView};
use lucid_tests::render::{gbuffer_once, mean_at, render_once};

const VIEW: TopView = TopView {
    height: 1.0,
    yfov: 1.0,
    size: 32,
};

/// A tangent-space normal as a linear RGB8 texel.
fn texel(n: Vec3) -> [u8; 4] {
    let n = n.normalize();
    let q = |v: f32| ((v * 0.5 + 0.5) * 255.0).round() as u8;
    [q(n.x), q(n.y), q(n.z), 255]
}

/// A white diffuse floor (u along +x, v along +z) under a sun in direction `towards_sun`, its
/// material normal-mapped by the one texel `normal` when given (with `scale`), with TANGENT
/// `tangent` when given.
fn floor(normal: Option<Vec3>, scale: f32, tangent: Option<[f32; 4]>, towards_sun: Vec3) -> Scene {
    let mut doc = Doc::new();
    let material = match normal {
        Some(n) => {
            let t = doc.texture(1, 1, &[texel(n)], None);
            doc.material(&format!(
                r#"{{"pbrMetallicRoughness": {{"metallicFactor": 0}},
                    "normalTexture": {{"index": {t}, "scale": {scale}}}}}"#
            ))
        }
        None => doc.material(r#"{"pbrMetallicRoughness": {"metallicFactor": 0}}"#),
    };
    let normals = doc.floats(&[[0.0f32, 1.0, 0.0]; 4]);
    let mut extra = vec![("NORMAL", normals)];
    if let Some(t) = tangent {
        extra.push(("TANGENT", doc.floats(&[t; 4])));
    }
    uv_plane(&mut doc, 1.0, 0.0, false, material, &extra);
    let q = Quat::from_rotation_arc(Vec3::NEG_Z, -towards_sun.normalize());
    doc.light(
        r#"{"type": "directional", "intensity": 1000}"#,
        &format!(r#""rotation": [{}, {}, {}, {}]"#, q.x, q.y, q.z, q.w),
    );
    VIEW.add_to(&mut doc);
    doc.load("normal-mapped.gltf")
}

/// Mean red of direct sunlight on the whole view of the floor.
fn brightness(scene: Scene) -> (f32, ImageData) {
    let image = render_once(scene, Algorithm::PathTracing, 1, 2, VIEW.size);
    let all = VIEW.pixels_in([-1.0, 1.0], [-1.0, 1.0]);
    (mean_at(&image, &all, 0), image)
}

#[test]
fn a_normal_map_tilts_shading_towards_its_normal() {
    let sun = Vec3::new(1.0, 1.0, 0.0); // 45° above the floor, from +x
    let tilt = |x: f32| Vec3::new(x, 0.0, 1.0); // tilted along the tangent (+x)
    let towards = floor(Some(tilt(30f32.to_radians().tan())), 1.0, None, sun);
    assert!(towards.features().normal_maps, "{}", towards.features());
    assert!(towards.warnings.is_empty(), "{:?}", towards.warnings);
    assert_eq!(towards.meshes[0].tangents.len(), 4, "MikkTSpace tangents");
    let (plain, _) = brightness(floor(None, 1.0, None, sun));
    let (lit, _) = brightness(towards);
    let (away, _) = brightness(floor(
        Some(tilt(-(30f32.to_radians().tan()))),
        1.0,
        None,
        sun,
    ));
    let (flattened, _) = brightness(floor(Some(tilt(1.0)), 0.0, None, sun));
    println!("plain {plain}, towards the sun {lit}, away {away}, scale 0 {flattened}");
    // Lambert: cos 45° flat, cos 15° tilted 30° towards the sun, cos 75° away from it.
    let cos = |deg: f32| deg.to_radians().cos();
    assert!(
        (lit / plain - cos(15.0) / cos(45.0)).abs() < 0.05,
        "{lit} / {plain}"
    );
    assert!(
        (away / plain - cos(75.0) / cos(45.0)).abs() < 0.05,
        "{away} / {plain}"
    );
    // A scale of 0 flattens the map's x and y: the mesh normal again.
    assert!(
        (flattened / plain - 1.0).abs() < 0.01,
        "{flattened} / {plain}"
    );
}

#[test]
fn the_gbuffer_normal_is_the_mapped_one() {
    let n = Vec3::new(0.5, 0.0, 1.0);
    let [_, normal] = gbuffer_once(floor(Some(n), 1.0, None, Vec3::Y), VIEW.size);
    let all = VIEW.pixels_in([-1.0, 1.0], [-1.0, 1.0]);
    let want = Vec3::new(n.x, n.z, 0.0).normalize(); // tangent +x, normal +y
    let got = Vec3::new(mean_at(&normal, &all, 0), mean_at(&normal, &all, 1), 0.0);
    assert!(got.abs_diff_eq(want, 0.02), "{got} vs {want}");
}

#[test]
fn file_tangents_and_mikktspace_tangents_agree() {
    // Tilted along both tangent and bitangent, lit from a side that tells them apart.
    let n = Vec3::new(0.5, 0.5, 0.7);
    let sun = Vec3::new(1.0, 1.0, 1.0);
    // u grows along +x and v along +z: tangent +x, bitangent +z = -1 * cross(+y, +x).
    let given = floor(Some(n), 1.0, Some([1.0, 0.0, 0.0, -1.0]), sun);
    let generated = floor(Some(n), 1.0, None, sun);
    let mirrored = floor(Some(n), 1.0, Some([1.0, 0.0, 0.0, 1.0]), sun);
    assert_eq!(given.meshes[0].tangents, generated.meshes[0].tangents);
    let (a, ia) = brightness(given);
    let (b, ib) = brightness(generated);
    let (c, _) = brightness(mirrored);
    println!("file tangents {a}, MikkTSpace {b}, opposite bitangent {c}");
    let diff = ia
        .pixels
        .iter()
        .zip(&ib.pixels)
        .map(|(p, q)| (p[0] - q[0]).abs())
        .fold(0.0f32, f32::max);
    assert!(diff <= 1e-4 * a, "largest difference {diff}");
    // The test can tell: flipping the bitangent's sign changes the shading.
    assert!((c - a).abs() > 0.1 * a, "{c} vs {a}");
}
