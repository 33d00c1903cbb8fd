//! glTF mesh primitives to Lucid meshes.

use glam::{UVec3, Vec2, Vec3, Vec4};
use gltf::accessor::Dimensions;
use gltf::mesh::Mode;
use gltf::{Primitive, Semantic};

use super::accessor::{read_floats, read_indices};
use super::unsupported::{Feature, Unsupported};
use crate::scene::{Mesh, Scene};

/// The largest coordinate magnitude of world-space geometry: squared distances (the bounds'
/// diagonal, the automatic camera's distance) stay within `f32`.
pub const MAX_COORDINATE: f32 = 1e18;

/// Converts one triangle, triangle-strip or triangle-fan primitive into a
/// scene mesh and returns its id, or `None` (noted in `unsupported`) for points and
/// lines. Reads POSITION, NORMAL (flat normals without it, as the spec requires), `TEXCOORD_0`,
/// `COLOR_0` (its alpha only for a cut-out `material`) and, for a normal-mapped `material`,
/// TANGENT (MikkTSpace tangents without it).
pub fn primitive(
    scene: &mut Scene,
    (mesh, prim): (&gltf::Mesh, &Primitive),
    buffers: &[Vec<u8>],
    material: u32,
    unsupported: &mut Unsupported,
) -> Result<Option<u32>, String> {
    let name = format!(
        "{}/{}",
        mesh.name()
            .map_or_else(|| format!("mesh {}", mesh.index()), str::to_owned),
        prim.index()
    );
    if !matches!(
        prim.mode(),
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        unsupported.note(Feature::PointsAndLines, "primitives", || {
            format!("mesh `{name}` ({:?})", prim.mode())
        });
        return Ok(None);
    }
    if prim.morph_targets().next().is_some() {
        unsupported.note(Feature::MorphTargets, "primitives", || {
            format!("mesh `{name}`")
        });
    }
    let ctx = |e: String| format!("mesh `{name}`: {e}");
    let pos = prim
        .get(&Semantic::Positions)
        .ok_or_else(|| ctx("primitive has no POSITION attribute".into()))?;
    let positions: Vec<Vec3> = read_floats::<3>(&pos, buffers, false)
        .map_err(ctx)?
        .into_iter()
        .map(Vec3::from)
        .collect();
    if let Some((k, p)) = positions
        .iter()
        .enumerate()
        .find(|(_, p)| p.abs().max_element() > MAX_COORDINATE)
    {
        return Err(ctx(format!(
            "POSITION {k} {p} is out of range (coordinates up to ±{MAX_COORDINATE:e} are supported)"
        )));
    }
    let nv = positions.len();
    let normals = match prim.get(&Semantic::Normals) {
        Some(a) => read_floats::<3>(&a, buffers, false).map_err(ctx)?,
        None => Vec::new(),
    };
    let uvs = match prim.get(&Semantic::TexCoords(0)) {
        Some(a) => read_floats::<2>(&a, buffers, true).map_err(ctx)?,
        None => Vec::new(),
    };
    let (colors, alphas) = match prim.get(&Semantic::Colors(0)) {
        Some(a) => read_colors(&a, buffers).map_err(ctx)?,
        None => (Vec::new(), Vec::new()),
    };
    let mat = &scene.materials[material as usize];
    let (normal_mapped, cut_out) = (mat.normal_texture.is_some(), mat.is_cut_out());
    // Opacity matters to cut-out materials only.
    let alphas = if cut_out { alphas } else { Vec::new() };
    // glTF 2.0, meshes: without normals, "the provided tangents (if present) MUST be ignored".
    let tangents = match prim.get(&Semantic::Tangents) {
        Some(a) if normal_mapped && !normals.is_empty() => read_floats::<4>(&a, buffers, false)
            .map_err(ctx)?
            .into_iter()
            .map(Vec4::from)
            .collect(),
        _ => Vec::new(),
    };
    let counts = [
        normals.len(),
        uvs.len(),
        colors.len(),
        alphas.len(),
        tangents.len(),
    ];
    if counts.iter().any(|&n| n != 0 && n != nv) {
        return Err(ctx("attribute counts differ from the POSITION count".into()));
    }
    let flat = match prim.indices() {
        Some(a) => read_indices(&a, buffers).map_err(ctx)?,
        None => (0..nv as u32).collect(),
    };
    let indices = triangles(prim.mode(), &flat).map_err(ctx)?;
    if let Some(bad) = flat.iter().find(|&&i| i as usize >= nv) {
        return Err(ctx(format!(
            "index {bad} is out of range for {nv} vertices"
        )));
    }
    let mut m = Mesh {
        name,
        positions,
        normals: normals
            .into_iter()
            .map(|n| Vec3::from(n).try_normalize().unwrap_or(Vec3::Y))
            .collect(),
        uvs: uvs.into_iter().map(Vec2::from).collect(),
        colors,
        alphas,
        tangents: tangents
            .into_iter()
            .map(|t: Vec4| {
                let xyz = t.truncate().try_normalize().unwrap_or(Vec3::X);
                xyz.extend(if t.w < 0.0 { -1.0 } else { 1.0 })
            })
            .collect(),
        indices,
        material,
    };
    if m.normals.is_empty() {
        // glTF 2.0, meshes: "When normals are not specified, client implementations MUST
        // calculate flat normals".
        m.make_flat();
    }
    if normal_mapped && m.tangents.is_empty() {
        // "When tangents are not specified, client implementations SHOULD calculate tangents
        // using default MikkTSpace algorithms".
        m.generate_tangents();
    }
    Ok(Some(scene.add_mesh(m)))
}

/// Reads a `COLOR_0` accessor: RGB or RGBA, float or normalized `u8`/`u16`, as linear RGB in
/// `[0, 1]` and, for RGBA, the alphas (floats are clamped; RGB gives no alphas).
fn read_colors(a: &gltf::Accessor, buffers: &[Vec<u8>]) -> Result<(Vec<Vec3>, Vec<f32>), String> {
    let (rgb, alphas): (Vec<Vec3>, Vec<f32>) = match a.dimensions() {
        Dimensions::Vec3 => (
            read_floats::<3>(a, buffers, true)?
                .into_iter()
                .map(Vec3::from)
                .collect(),
            Vec::new(),
        ),
        Dimensions::Vec4 => read_floats::<4>(a, buffers, true)?
            .into_iter()
            .map(|c| (Vec3::new(c[0], c[1], c[2]), c[3].clamp(0.0, 1.0)))
            .unzip(),
        d => {
            return Err(format!(
                "COLOR_0 (accessor {}) must be VEC3 or VEC4, found {d:?}",
                a.index()
            ))
        }
    };
    let rgb = rgb
        .into_iter()
        .map(|c| c.clamp(Vec3::ZERO, Vec3::ONE))
        .collect();
    Ok((rgb, alphas))
}

/// The triangles of a triangle list, strip or fan (glTF 2.0, primitive topology: strip triangle `i` is
/// `(i, i + 1, i + 2)`, its odd ones reversed to keep the winding; fan triangle `i` is
/// `(i + 1, i + 2, 0)`).
fn triangles(mode: Mode, flat: &[u32]) -> Result<Vec<UVec3>, String> {
    match mode {
        Mode::Triangles if flat.len() % 3 != 0 => Err(format!(
            "{} indices do not form whole triangles",
            flat.len()
        )),
        Mode::Triangles => Ok(flat
            .chunks_exact(3)
            .map(|t| UVec3::new(t[0], t[1], t[2]))
            .collect()),
        _ if flat.len() < 3 => Err(format!(
            "a {mode:?} of {} vertices forms no triangle",
            flat.len()
        )),
        Mode::TriangleStrip => Ok((0..flat.len() - 2)
            .map(|i| {
                let (b, c) = if i % 2 == 0 { (1, 2) } else { (2, 1) };
                UVec3::new(flat[i], flat[i + b], flat[i + c])
            })
            .collect()),
        _ => Ok((0..flat.len() - 2)
            .map(|i| UVec3::new(flat[i + 1], flat[i + 2], flat[0]))
            .collect()),
    }
}
