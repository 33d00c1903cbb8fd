//! Splits `.glb` containers; `.gltf` JSON passes through.

/// The JSON document and the optional binary chunk of a glTF file.
pub struct Container<'a> {
    /// The JSON text.
    pub json: &'a [u8],
    /// The GLB `BIN` chunk, if any.
    pub bin: Option<&'a [u8]>,
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    let s = b.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
}

/// The first four bytes of every GLB file.
pub const GLB_MAGIC: [u8; 4] = *b"glTF";

/// Parses a file: GLB if it starts with the `glTF` magic, JSON otherwise.
/// Every length is bounds checked.
pub fn split(bytes: &[u8]) -> Result<Container<'_>, String> {
    if !bytes.starts_with(&GLB_MAGIC) {
        return Ok(Container {
            json: bytes,
            bin: None,
        });
    }
    let version = u32_at(bytes, 4).ok_or("GLB header is truncated")?;
    if version != 2 {
        return Err(format!("GLB version {version} is not supported (only 2)"));
    }
    let length = u32_at(bytes, 8).ok_or("GLB header is truncated")? as usize;
    if length > bytes.len() || length < 12 {
        return Err(format!(
            "GLB header length {length} does not match the file size {}",
            bytes.len()
        ));
    }
    let body = &bytes[..length];
    let mut at = 12;
    let mut chunks = Vec::new();
    while at < body.len() {
        let len = u32_at(body, at).ok_or("GLB chunk header is truncated")? as usize;
        let kind = u32_at(body, at + 4).ok_or("GLB chunk header is truncated")?;
        let start = at + 8;
        let end = start
            .checked_add(len)
            .filter(|&e| e <= body.len())
            .ok_or_else(|| format!("GLB chunk at byte {at} runs past the end of the file"))?;
        chunks.push((kind, &body[start..end]));
        at = end;
    }
    const JSON: u32 = 0x4E4F_534A;
    const BIN: u32 = 0x004E_4942;
    match chunks.as_slice() {
        [(JSON, json), rest @ ..] => Ok(Container {
            json,
            bin: rest.iter().find(|(k, _)| *k == BIN).map(|(_, b)| *b),
        }),
        _ => Err("GLB file does not start with a JSON chunk".into()),
    }
}
