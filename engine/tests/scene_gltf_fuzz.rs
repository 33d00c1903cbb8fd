//! Property: importing mutated glTF / GLB files (bytes, and JSON number and
//! string fields) never panics and never hangs (errors are fine). Seeds come
//! from the committed corpus in `tests/corpus/gltf/`.

use std::path::PathBuf;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use lucid_engine::scene::load_gltf_slice;
use proptest::prelude::*;

fn corpus_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/gltf")
}

fn corpus() -> Vec<Vec<u8>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(corpus_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "gltf"))
        .collect();
    files.sort();
    assert!(files.len() >= 3, "corpus is missing");
    files
        .into_iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect()
}

/// The corpus as GLB files, external buffers moved into the BIN chunk.
fn glb_corpus() -> Vec<Vec<u8>> {
    let bin = std::fs::read(corpus_dir().join("quad.bin")).unwrap();
    corpus()
        .into_iter()
        .map(|json| {
            let text = String::from_utf8(json)
                .unwrap()
                .replace(r#""uri": "quad.bin""#, r#""byteOffset": 0"#);
            let mut j = text.into_bytes();
            while j.len() % 4 != 0 {
                j.push(b' ');
            }
            let mut out = b"glTF".to_vec();
            out.extend(2u32.to_le_bytes());
            out.extend(((12 + 8 + j.len() + 8 + bin.len()) as u32).to_le_bytes());
            out.extend((j.len() as u32).to_le_bytes());
            out.extend(b"JSON");
            out.extend(j);
            out.extend((bin.len() as u32).to_le_bytes());
            out.extend(b"BIN\0");
            out.extend(&bin);
            out
        })
        .collect()
}

#[derive(Clone, Debug)]
enum Mutation {
    /// Overwrite one byte.
    Set(f64, u8),
    /// Delete a run of bytes.
    Delete(f64, u8),
    /// Insert bytes.
    Insert(f64, Vec<u8>),
    /// Cut the file.
    Truncate(f64),
    /// Replace the number literal nearest to a position.
    Number(f64, &'static str),
    /// Replace the string literal nearest to a position.
    Text(f64, &'static str),
    /// Copy a slice over another place.
    Splice(f64, f64, u8),
}

const NUMBERS: [&str; 18] = [
    "0",
    "-1",
    "1",
    "2",
    "3",
    "5",
    "6",
    "7",
    "65535",
    "4294967295",
    "18446744073709551616",
    "1e39",
    "3e38",
    "1e30",
    "-1e39",
    "0.5",
    "1e-45",
    "5126",
];
const TEXTS: [&str; 12] = [
    "",
    "quad.bin",
    "../quad.bin",
    "missing.bin",
    "data:;base64,!!!",
    "data:application/octet-stream;base64,AAAA",
    "KHR_draco_mesh_compression",
    "VEC4",
    "MAT4",
    "spot",
    "directional",
    "%ff%fe",
];

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = 0.0..1.0f64;
    prop_oneof![
        (at.clone(), any::<u8>()).prop_map(|(a, b)| Mutation::Set(a, b)),
        (at.clone(), 1..16u8).prop_map(|(a, n)| Mutation::Delete(a, n)),
        (at.clone(), proptest::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(a, b)| Mutation::Insert(a, b)),
        at.clone().prop_map(Mutation::Truncate),
        (at.clone(), proptest::sample::select(&NUMBERS[..]))
            .prop_map(|(a, n)| Mutation::Number(a, n)),
        (at.clone(), proptest::sample::select(&TEXTS[..])).prop_map(|(a, t)| Mutation::Text(a, t)),
        (at.clone(), at, 1..64u8).prop_map(|(a, b, n)| Mutation::Splice(a, b, n)),
    ]
}

fn pos(len: usize, at: f64) -> usize {
    ((len as f64 * at) as usize).min(len)
}

/// Finds the literal (number or quoted string) around `start` and replaces it.
fn replace_literal(data: &mut Vec<u8>, start: usize, number: bool, with: &str) {
    let is_num = |c: u8| c.is_ascii_digit() || c == b'-' || c == b'.' || c == b'e' || c == b'+';
    let found = if number {
        (start..data.len())
            .find(|&i| data[i].is_ascii_digit())
            .map(|i| {
                let mut a = i;
                while a > 0 && is_num(data[a - 1]) {
                    a -= 1;
                }
                let mut b = i;
                while b < data.len() && is_num(data[b]) {
                    b += 1;
                }
                (a, b)
            })
    } else {
        (start..data.len())
            .find(|&i| data[i] == b'"')
            .and_then(|a| {
                (a + 1..data.len())
                    .find(|&i| data[i] == b'"')
                    .map(|b| (a + 1, b))
            })
    };
    if let Some((a, b)) = found {
        data.splice(a..b, with.bytes());
    }
}

fn apply(mut data: Vec<u8>, mutations: &[Mutation]) -> Vec<u8> {
    for m in mutations {
        let len = data.len();
        match m {
            Mutation::Set(a, b) if len > 0 => {
                let i = pos(len - 1, *a);
                data[i] = *b;
            }
            Mutation::Delete(a, n) => {
                let i = pos(len, *a);
                data.drain(i..(i + *n as usize).min(len));
            }
            Mutation::Insert(a, b) => {
                let i = pos(len, *a);
                data.splice(i..i, b.iter().copied());
            }
            Mutation::Truncate(a) => data.truncate(pos(len, *a)),
            Mutation::Number(a, n) => replace_literal(&mut data, pos(len, *a), true, n),
            Mutation::Text(a, t) => replace_literal(&mut data, pos(len, *a), false, t),
            Mutation::Splice(a, b, n) => {
                let (src, dst) = (pos(len, *a), pos(len, *b));
                let chunk: Vec<u8> = data[src..(src + *n as usize).min(len)].to_vec();
                let end = (dst + chunk.len()).min(len);
                data.splice(dst..end, chunk);
            }
            Mutation::Set(..) => {}
        }
    }
    data
}

/// The longest an import of a small file may take before it counts as a hang.
const DEADLINE: Duration = Duration::from_secs(10);

/// Imports `data` on its own thread: a panic or a hang past [`DEADLINE`]
/// fails the test (a hang does not stall the run).
fn import_checked(data: Vec<u8>, base: Option<PathBuf>, label: &'static str) {
    let (done, finished) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = load_gltf_slice(&data, base.as_deref(), label);
        let _ = done.send(());
    });
    match finished.recv_timeout(DEADLINE) {
        Ok(()) => {}
        Err(RecvTimeoutError::Timeout) => panic!("import hung for more than {DEADLINE:?}"),
        Err(RecvTimeoutError::Disconnected) => panic!("import panicked"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn mutated_gltf_never_panics(file in 0..3usize, mutations in proptest::collection::vec(mutation(), 1..5)) {
        let seeds = corpus();
        let data = apply(seeds[file % seeds.len()].clone(), &mutations);
        import_checked(data, Some(corpus_dir()), "fuzz.gltf");
    }

    #[test]
    fn mutated_glb_never_panics(file in 0..3usize, mutations in proptest::collection::vec(mutation(), 1..5)) {
        let seeds = glb_corpus();
        let data = apply(seeds[file % seeds.len()].clone(), &mutations);
        import_checked(data, Some(corpus_dir()), "fuzz.glb");
    }

    #[test]
    fn arbitrary_bytes_never_panic(data in proptest::collection::vec(any::<u8>(), 0..256), glb_header in any::<bool>()) {
        let mut bytes = if glb_header { b"glTF\x02\0\0\0".to_vec() } else { Vec::new() };
        bytes.extend(data);
        import_checked(bytes, None, "noise");
    }
}

#[test]
fn unmutated_corpus_loads_from_both_containers() {
    for data in corpus().into_iter().chain(glb_corpus()) {
        load_gltf_slice(&data, Some(&corpus_dir()), "seed").unwrap();
    }
}
