//! The seed files: every `.gltf` in `tests/corpus/gltf/`, and each as a `.glb` with its first
//! buffer moved into the binary chunk.

use std::path::PathBuf;

use serde_json::Value;

/// The folder of the seed files (external buffers resolve against it).
pub fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/gltf")
}

/// A seed file: its name and its JSON.
pub struct Seed {
    /// File name, e.g. `features.gltf`.
    pub name: String,
    /// The parsed JSON document.
    pub json: Value,
}

/// Every `.gltf` seed, sorted by name (so that a seed index is stable).
pub fn seeds() -> Vec<Seed> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir())
        .expect("corpus folder")
        .map(|e| e.expect("corpus entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "gltf"))
        .collect();
    files.sort();
    assert!(files.len() >= 4, "the glTF corpus is missing files");
    files
        .into_iter()
        .map(|path| Seed {
            name: path.file_name().unwrap().to_string_lossy().into_owned(),
            json: serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap(),
        })
        .collect()
}

/// Takes the bytes of buffer 0 out of `json` (a data URI or a file next to the seeds) for a GLB's
/// binary chunk, leaving the buffer without a URI. `None` when buffer 0 has no readable URI.
pub fn take_first_buffer(json: &mut Value) -> Option<Vec<u8>> {
    let buffer = json.pointer_mut("/buffers/0")?.as_object_mut()?;
    let uri = buffer.get("uri")?.as_str()?.to_owned();
    let data = match uri.split_once(";base64,") {
        Some((_, data)) => base64::decode(data).ok()?,
        None => std::fs::read(dir().join(&uri)).ok()?,
    };
    buffer.remove("uri");
    Some(data)
}

/// Puts `data` back into buffer 0 of `json` as a base64 data URI.
pub fn embed_first_buffer(json: &mut Value, data: &[u8]) {
    if let Some(buffer) = json
        .pointer_mut("/buffers/0")
        .and_then(Value::as_object_mut)
    {
        let uri = format!(
            "data:application/octet-stream;base64,{}",
            base64::encode(data)
        );
        buffer.insert("uri".into(), Value::String(uri));
    }
}

/// A GLB container of `json` text and an optional binary chunk (both padded to 4 bytes).
pub fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
    let mut json = json.to_vec();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let mut bin = bin.map(<[u8]>::to_vec);
    if let Some(bin) = &mut bin {
        while bin.len() % 4 != 0 {
            bin.push(0);
        }
    }
    let total = 12 + 8 + json.len() + bin.as_ref().map_or(0, |b| 8 + b.len());
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    if let Some(bin) = bin {
        out.extend((bin.len() as u32).to_le_bytes());
        out.extend(b"BIN\0");
        out.extend(bin);
    }
    out
}
