//! glTF mesh primitives to Lucid meshes.

use glam::{UVec3, Vec2, Vec3};
use gltf::mesh::Mode;
use gltf::{Primitive, Semantic};

use super::accessor::{read_floats, read_indices};
use crate::scene::{Mesh, Scene};

/// Converts one triangle primitive into a scene mesh and returns its id,
/// or `None` (with a warning) for non-triangle primitives.
pub fn primitive(
    scene: &mut Scene,
    mesh: &gltf::Mesh,
    prim: &Primitive,
    buffers: &[Vec<u8>],
    material: u32,
) -> Result<Option<u32>, String> {
    let name = format!(
        "{}/{}",
        mesh.name()
            .map_or_else(|| format!("mesh {}", mesh.index()), str::to_owned),
        prim.index()
    );
    if prim.mode() != Mode::Triangles {
        scene.warnings.push(format!(
            "mesh `{name}`: {:?} primitives are not supported; skipped",
            prim.mode()
        ));
        return Ok(None);
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
    let nv = positions.len();
    let normals = match prim.get(&Semantic::Normals) {
        Some(a) => read_floats::<3>(&a, buffers, false).map_err(ctx)?,
        None => Vec::new(),
    };
    let uvs = match prim.get(&Semantic::TexCoords(0)) {
        Some(a) => read_floats::<2>(&a, buffers, true).map_err(ctx)?,
        None => Vec::new(),
    };
    if (!normals.is_empty() && normals.len() != nv) || (!uvs.is_empty() && uvs.len() != nv) {
        return Err(ctx("attribute counts differ from the POSITION count".into()));
    }
    let flat = match prim.indices() {
        Some(a) => read_indices(&a, buffers).map_err(ctx)?,
        None => (0..nv as u32).collect(),
    };
    if flat.len() % 3 != 0 {
        return Err(ctx(format!(
            "{} indices do not form whole triangles",
            flat.len()
        )));
    }
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
        indices: flat
            .chunks_exact(3)
            .map(|t| UVec3::new(t[0], t[1], t[2]))
            .collect(),
        material,
    };
    if m.normals.is_empty() {
        m.compute_normals();
    }
    Ok(Some(scene.add_mesh(m)))
}
