//! Resolution of buffer and image URIs: `data:` URIs (base64) and files
//! relative to the glTF file.

use std::path::Path;

/// Reads the bytes a URI refers to. Relative references need `base`;
/// only regular files are read.
pub fn read(uri: &str, base: Option<&Path>) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or_else(|| "data URI is not base64 encoded".to_string())?;
        return base64_decode(payload);
    }
    if uri.contains(':') || uri.starts_with('/') || uri.starts_with('\\') {
        return Err(format!(
            "URI `{}` is not a relative file reference or data URI",
            shorten(uri)
        ));
    }
    let base = base.ok_or_else(|| {
        format!("external file `{uri}` cannot be resolved without a base directory")
    })?;
    let path = base.join(percent_decode(uri)?);
    let meta =
        std::fs::metadata(&path).map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
    if !meta.is_file() {
        return Err(format!("`{}` is not a regular file", path.display()));
    }
    std::fs::read(&path).map_err(|e| format!("cannot read `{}`: {e}", path.display()))
}

/// The first characters of a long URI, for messages.
pub fn shorten(uri: &str) -> String {
    if uri.chars().count() > 60 {
        format!("{}…", uri.chars().take(60).collect::<String>())
    } else {
        uri.to_owned()
    }
}

fn percent_decode(s: &str) -> Result<String, String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = b
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("URI `{}` has a bad percent escape", shorten(s)))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("URI `{}` is not UTF-8 after decoding", shorten(s)))
}

fn base64_decode(s: &str) -> Result<Vec<u8>, String> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => return None,
        } as u32)
    };
    let data = s.trim_end_matches('=').as_bytes();
    if data.len() % 4 == 1 {
        return Err("base64 data has an impossible length".into());
    }
    let mut out = Vec::with_capacity(data.len() / 4 * 3 + 2);
    for chunk in data.chunks(4) {
        let mut acc = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            let v = value(c).ok_or_else(|| format!("invalid base64 character `{}`", c as char))?;
            acc |= v << (18 - 6 * k);
        }
        let bytes = acc.to_be_bytes();
        out.extend_from_slice(&bytes[1..chunk.len()]);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decodes_data_uris_and_rejects_bad_ones() {
        assert_eq!(
            read("data:application/octet-stream;base64,aGVsbG8=", None).unwrap(),
            b"hello"
        );
        assert_eq!(
            read("data:;base64,AAECAw==", None).unwrap(),
            vec![0, 1, 2, 3]
        );
        assert_eq!(read("data:;base64,", None).unwrap(), Vec::<u8>::new());
        assert!(read("data:;base64,a", None).is_err());
        assert!(read("data:;base64,a*bc", None).is_err());
        assert!(read("data:text/plain,hello", None).is_err());
        assert!(read("http://example.com/x.bin", None).is_err());
        assert!(read("/etc/passwd", Some(Path::new("."))).is_err());
        assert!(read("x.bin", None).unwrap_err().contains("base directory"));
        assert!(read("%zz.bin", Some(Path::new(".")))
            .unwrap_err()
            .contains("percent"));
        assert!(read(".", Some(Path::new("/")))
            .unwrap_err()
            .contains("regular file"));
        assert_eq!(percent_decode("a%20b.bin").unwrap(), "a b.bin");
    }
}
