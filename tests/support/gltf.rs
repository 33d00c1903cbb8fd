//! Small glTF 2.0 files written by the tests themselves: a [`Doc`] collects accessors (one
//! embedded base64 buffer), meshes, materials, textures (PNG data URIs), nodes, lights and
//! cameras and writes the JSON, and a few shapes ([`plane`], [`cube`]) give the geometry;
//! [`TopView`] is a camera looking straight down at the plane y = 0.

use lucid_engine::scene::{load_gltf_slice, Scene};

/// glTF component types.
pub mod component {
    /// `UNSIGNED_BYTE`.
    pub const U8: u32 = 5121;
    /// `UNSIGNED_SHORT`.
    pub const U16: u32 = 5123;
    /// `UNSIGNED_INT`.
    pub const U32: u32 = 5125;
    /// `FLOAT`.
    pub const F32: u32 = 5126;
}

/// A glTF document being written. Every node is a root of the one scene.
#[derive(Clone, Debug, Default)]
pub struct Doc {
    bin: Vec<u8>,
    views: Vec<String>,
    accessors: Vec<String>,
    meshes: Vec<String>,
    materials: Vec<String>,
    nodes: Vec<String>,
    lights: Vec<String>,
    cameras: Vec<String>,
    images: Vec<String>,
    samplers: Vec<String>,
    textures: Vec<String>,
    extensions_used: Vec<String>,
    members: Vec<String>,
}

fn type_name(components: usize) -> &'static str {
    match components {
        1 => "SCALAR",
        2 => "VEC2",
        3 => "VEC3",
        4 => "VEC4",
        _ => panic!("{components} components"),
    }
}

impl Doc {
    /// An empty document.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds an accessor over `bytes` (`count` elements of `components` components of type
    /// `component`); returns its index. POSITION accessors get the min and max the spec requires.
    pub fn accessor(
        &mut self,
        bytes: &[u8],
        component: u32,
        components: usize,
        count: usize,
        normalized: bool,
    ) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        self.views.push(format!(
            r#"{{"buffer": 0, "byteOffset": {}, "byteLength": {}}}"#,
            self.bin.len(),
            bytes.len()
        ));
        self.bin.extend_from_slice(bytes);
        self.accessors.push(format!(
            r#"{{"bufferView": {}, "componentType": {component}, "count": {count}, "type": "{}", "normalized": {normalized}}}"#,
            self.views.len() - 1,
            type_name(components)
        ));
        self.accessors.len() - 1
    }

    /// A float accessor of `N`-component elements.
    pub fn floats<const N: usize>(&mut self, values: &[[f32; N]]) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let a = self.accessor(&bytes, component::F32, N, values.len(), false);
        if N == 3 {
            let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
            for v in values {
                for k in 0..3 {
                    lo[k] = lo[k].min(v[k]);
                    hi[k] = hi[k].max(v[k]);
                }
            }
            let last = self.accessors.last_mut().expect("just added");
            last.pop();
            last.push_str(&format!(r#", "min": {lo:?}, "max": {hi:?}}}"#));
        }
        a
    }

    /// A normalized unsigned-byte accessor of `N`-component elements.
    pub fn unorm8<const N: usize>(&mut self, values: &[[u8; N]]) -> usize {
        let bytes: Vec<u8> = values.iter().flatten().copied().collect();
        self.accessor(&bytes, component::U8, N, values.len(), true)
    }

    /// A normalized unsigned-short accessor of `N`-component elements.
    pub fn unorm16<const N: usize>(&mut self, values: &[[u16; N]]) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        self.accessor(&bytes, component::U16, N, values.len(), true)
    }

    /// An index accessor (`u32`).
    pub fn indices(&mut self, indices: &[u32]) -> usize {
        let bytes: Vec<u8> = indices.iter().flat_map(|x| x.to_le_bytes()).collect();
        self.accessor(&bytes, component::U32, 1, indices.len(), false)
    }

    /// Adds a material (its JSON object); returns its index.
    pub fn material(&mut self, json: &str) -> usize {
        self.materials.push(json.to_string());
        self.materials.len() - 1
    }

    /// Adds a Lambertian material of albedo `rgb` (glTF's dielectric with its specular layer
    /// turned off by `KHR_materials_specular`), with `more` (e.g. `, "emissiveFactor": [1, 1, 1]`)
    /// appended to its JSON, and returns its index.
    pub fn lambertian(&mut self, rgb: [f32; 3], more: &str) -> usize {
        self.uses("KHR_materials_specular");
        let [r, g, b] = rgb;
        self.material(&format!(
            r#"{{"pbrMetallicRoughness": {{"baseColorFactor": [{r}, {g}, {b}, 1], "metallicFactor": 0}},
                "extensions": {{"KHR_materials_specular": {{"specularFactor": 0}}}}{more}}}"#
        ))
    }

    /// Adds a `width` x `height` PNG texture of `rgba` texels (rows from the top) with sampler
    /// `sampler` (its JSON object, e.g. `{"wrapS": 33071}`; `None` for the default); returns the
    /// texture index.
    pub fn texture(
        &mut self,
        width: u32,
        height: u32,
        rgba: &[[u8; 4]],
        sampler: Option<&str>,
    ) -> usize {
        let image = image::RgbaImage::from_raw(width, height, rgba.concat())
            .expect("width x height texels");
        let mut png = std::io::Cursor::new(Vec::new());
        image
            .write_to(&mut png, image::ImageFormat::Png)
            .expect("PNG encoding");
        self.images.push(format!(
            r#"{{"uri": "data:image/png;base64,{}"}}"#,
            base64::encode(png.into_inner())
        ));
        let sampler = sampler.map_or(String::new(), |json| {
            self.samplers.push(json.to_string());
            format!(r#", "sampler": {}"#, self.samplers.len() - 1)
        });
        self.textures.push(format!(
            r#"{{"source": {}{sampler}}}"#,
            self.images.len() - 1
        ));
        self.textures.len() - 1
    }

    /// Adds a mesh (its JSON object); returns its index.
    pub fn mesh_json(&mut self, json: &str) -> usize {
        self.meshes.push(json.to_string());
        self.meshes.len() - 1
    }

    /// Adds a camera (its JSON object) on a node with `transform`.
    pub fn camera_json(&mut self, json: &str, transform: &str) -> usize {
        self.cameras.push(json.to_string());
        let sep = if transform.is_empty() { "" } else { ", " };
        self.node(&format!(
            r#"{{{transform}{sep}"camera": {}}}"#,
            self.cameras.len() - 1
        ))
    }

    /// Adds a top-level member the other methods do not write (e.g. `"textures": [...]`).
    pub fn member(&mut self, json: &str) {
        self.members.push(json.to_string());
    }

    /// Adds a mesh of one triangle primitive with `attributes` (semantic, accessor); returns its
    /// index.
    pub fn mesh(
        &mut self,
        attributes: &[(&str, usize)],
        indices: Option<usize>,
        material: Option<usize>,
    ) -> usize {
        let attributes: Vec<String> = attributes
            .iter()
            .map(|(name, a)| format!(r#""{name}": {a}"#))
            .collect();
        let mut primitive = format!(r#"{{"attributes": {{{}}}"#, attributes.join(", "));
        if let Some(i) = indices {
            primitive.push_str(&format!(r#", "indices": {i}"#));
        }
        if let Some(m) = material {
            primitive.push_str(&format!(r#", "material": {m}"#));
        }
        primitive.push('}');
        self.meshes
            .push(format!(r#"{{"primitives": [{primitive}]}}"#));
        self.meshes.len() - 1
    }

    /// Adds a root node (its JSON object, e.g. `{"mesh": 0}`); returns its index.
    pub fn node(&mut self, json: &str) -> usize {
        self.nodes.push(json.to_string());
        self.nodes.len() - 1
    }

    /// Adds a `KHR_lights_punctual` light (its JSON object) on a node with `transform` (JSON
    /// members such as `"translation": [0, 1, 0]`, possibly empty).
    pub fn light(&mut self, json: &str, transform: &str) -> usize {
        self.uses("KHR_lights_punctual");
        self.lights.push(json.to_string());
        let sep = if transform.is_empty() { "" } else { ", " };
        self.node(&format!(
            r#"{{{transform}{sep}"extensions": {{"KHR_lights_punctual": {{"light": {}}}}}}}"#,
            self.lights.len() - 1
        ))
    }

    /// Adds a perspective camera on a node with `transform`.
    pub fn camera(&mut self, yfov: f32, transform: &str) -> usize {
        self.camera_json(
            &format!(
                r#"{{"type": "perspective", "perspective": {{"yfov": {yfov}, "znear": 0.01}}}}"#
            ),
            transform,
        )
    }

    /// Lists `name` in `extensionsUsed`.
    pub fn uses(&mut self, name: &str) {
        if !self.extensions_used.iter().any(|e| e == name) {
            self.extensions_used.push(name.to_string());
        }
    }

    /// The glTF JSON, the buffer embedded as a base64 data URI.
    pub fn json(&self) -> String {
        let mut top = vec![r#""asset": {"version": "2.0"}"#.to_string()];
        let list = |items: &[String]| items.join(",\n    ");
        let roots: Vec<String> = (0..self.nodes.len()).map(|i| i.to_string()).collect();
        top.push(format!(
            r#""scene": 0, "scenes": [{{"nodes": [{}]}}]"#,
            roots.join(", ")
        ));
        top.push(format!(r#""nodes": [{}]"#, list(&self.nodes)));
        for (name, items) in [
            ("meshes", &self.meshes),
            ("materials", &self.materials),
            ("cameras", &self.cameras),
            ("images", &self.images),
            ("samplers", &self.samplers),
            ("textures", &self.textures),
            ("accessors", &self.accessors),
            ("bufferViews", &self.views),
        ] {
            if !items.is_empty() {
                top.push(format!(r#""{name}": [{}]"#, list(items)));
            }
        }
        if !self.bin.is_empty() {
            top.push(format!(
                r#""buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{}"}}]"#,
                self.bin.len(),
                base64::encode(&self.bin)
            ));
        }
        if !self.lights.is_empty() {
            top.push(format!(
                r#""extensions": {{"KHR_lights_punctual": {{"lights": [{}]}}}}"#,
                list(&self.lights)
            ));
        }
        top.extend(self.members.iter().cloned());
        if !self.extensions_used.is_empty() {
            let used: Vec<String> = self
                .extensions_used
                .iter()
                .map(|e| format!("\"{e}\""))
                .collect();
            top.push(format!(r#""extensionsUsed": [{}]"#, used.join(", ")));
        }
        format!("{{\n  {}\n}}\n", top.join(",\n  "))
    }

    /// Imports the document as `label` (panics with the error if it does not load).
    pub fn load(&self, label: &str) -> Scene {
        load_gltf_slice(self.json().as_bytes(), None, label)
            .unwrap_or_else(|e| panic!("{label}: {e}\n{}", self.json()))
    }
}

/// Positions and indices of a square of side `2 * half` in the plane y = 0, centred on the
/// origin, facing +Y (counter-clockwise seen from above).
pub fn plane(half: f32) -> (Vec<[f32; 3]>, Vec<u32>) {
    (
        vec![
            [-half, 0.0, -half],
            [-half, 0.0, half],
            [half, 0.0, half],
            [half, 0.0, -half],
        ],
        vec![0, 1, 2, 0, 2, 3],
    )
}

/// Positions and indices of the cube [-half, half]³ with 8 shared corners (so smooth normals
/// would average across faces), outward counter-clockwise winding.
pub fn cube(half: f32) -> (Vec<[f32; 3]>, Vec<u32>) {
    let positions = (0..8)
        .map(|i| {
            let s = |bit: u32| if i & bit == 0 { -half } else { half };
            [s(1), s(2), s(4)]
        })
        .collect();
    // Corner i has x = bit 0, y = bit 1, z = bit 2.
    let quads: [[u32; 4]; 6] = [
        [1, 3, 7, 5], // +x
        [0, 4, 6, 2], // -x
        [2, 6, 7, 3], // +y
        [0, 1, 5, 4], // -y
        [4, 5, 7, 6], // +z
        [0, 2, 3, 1], // -z
    ];
    let indices = quads
        .iter()
        .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
        .collect();
    (positions, indices)
}

/// The plane y = 0 seen straight down from `height` with vertical field of view `yfov` on a
/// square image of `size` pixels: +x to the right, +z down the image.
#[derive(Clone, Copy, Debug)]
pub struct TopView {
    /// Camera height.
    pub height: f32,
    /// Vertical field of view in radians.
    pub yfov: f32,
    /// Image width and height.
    pub size: u32,
}

impl TopView {
    /// Adds the camera to `doc`.
    pub fn add_to(&self, doc: &mut Doc) {
        let q = glam::Quat::from_rotation_arc(glam::Vec3::NEG_Z, glam::Vec3::NEG_Y);
        doc.camera(
            self.yfov,
            &format!(
                r#""rotation": [{}, {}, {}, {}], "translation": [0, {}, 0]"#,
                q.x, q.y, q.z, q.w, self.height
            ),
        );
    }

    /// The floor point (x, z) seen at the centre of pixel (column, row).
    pub fn floor_point(&self, column: u32, row: u32) -> [f32; 2] {
        let extent = self.height * (0.5 * self.yfov).tan();
        let ndc = |p: u32| ((p as f32 + 0.5) / self.size as f32) * 2.0 - 1.0;
        [ndc(column) * extent, ndc(row) * extent]
    }

    /// The pixels whose floor point lies in the axis-aligned box [x0, x1] x [z0, z1].
    pub fn pixels_in(&self, [x0, x1]: [f32; 2], [z0, z1]: [f32; 2]) -> Vec<(u32, u32)> {
        (0..self.size)
            .flat_map(|row| (0..self.size).map(move |column| (column, row)))
            .filter(|&(c, r)| {
                let [x, z] = self.floor_point(c, r);
                (x0..=x1).contains(&x) && (z0..=z1).contains(&z)
            })
            .collect()
    }
}

/// Adds the square plane(`half`) at height `y` with `material` and `TEXCOORD_0` u = 0..1 along
/// +x, v = 0..1 along +z, facing +Y, or -Y when `down`; `extra` attributes (semantic, accessor)
/// join POSITION and TEXCOORD_0. Returns the node.
pub fn uv_plane(
    doc: &mut Doc,
    half: f32,
    y: f32,
    down: bool,
    material: usize,
    extra: &[(&str, usize)],
) -> usize {
    let (positions, mut indices) = plane(half);
    let uvs: Vec<[f32; 2]> = positions
        .iter()
        .map(|p| [(p[0] + half) / (2.0 * half), (p[2] + half) / (2.0 * half)])
        .collect();
    if down {
        indices.reverse();
    }
    let positions: Vec<[f32; 3]> = positions.iter().map(|p| [p[0], y, p[2]]).collect();
    let p = doc.floats(&positions);
    let t = doc.floats(&uvs);
    let i = doc.indices(&indices);
    let mut attributes = vec![("POSITION", p), ("TEXCOORD_0", t)];
    attributes.extend_from_slice(extra);
    let mesh = doc.mesh(&attributes, Some(i), Some(material));
    doc.node(&format!(r#"{{"mesh": {mesh}}}"#))
}
