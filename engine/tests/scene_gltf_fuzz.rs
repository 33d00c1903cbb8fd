//! Property: importing mutated glTF / GLB files never panics and never hangs, and every error is
//! one line naming the file. The seeds are the committed corpus in `tests/corpus/gltf/`
//! (`features.gltf` uses every feature the importer reads); mutations change bytes (flips,
//! deletions, insertions, truncations, literals, binary words) and the JSON tree (huge, negative
//! and fractional numbers, wrong types, removed keys, out-of-range indices). What loads is also
//! prepared for the GPU on the CPU (flattening, BVH, packing), as `Renderer::new` does.
//!
//! The run is reproducible: the random seed is fixed (`LUCID_FUZZ_SEED` changes it) and each
//! property runs `LUCID_FUZZ_CASES` cases (default 1000, a few seconds); e.g.
//! `LUCID_FUZZ_CASES=100000 cargo test --release -p lucid-engine --test scene_gltf_fuzz`.

mod gltf_fuzz;

use gltf_fuzz::bytes::{self, byte_mutation, in_place_byte_mutation, ByteMutation};
use gltf_fuzz::check::import;
use gltf_fuzz::corpus::{self, embed_first_buffer, glb, seeds, take_first_buffer};
use gltf_fuzz::json::{self, json_mutation, JsonMutation};
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

/// Cases per property: `LUCID_FUZZ_CASES`, else 1000.
fn cases() -> u32 {
    std::env::var("LUCID_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1000)
}

/// The random seed: `LUCID_FUZZ_SEED`, else a fixed one, so that a failure repeats.
fn seed() -> u64 {
    std::env::var("LUCID_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(20_261_123)
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: cases(),
        rng_seed: RngSeed::Fixed(seed()),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// What to change in a seed file.
#[derive(Default)]
struct Mutations<'a> {
    /// Changes to the JSON tree.
    json: &'a [JsonMutation],
    /// Changes to the bytes of buffer 0 (vertex, index and image data).
    buffer: &'a [ByteMutation],
    /// Changes to the file's bytes, last.
    file: &'a [ByteMutation],
}

/// Seed `file` with `mutations`, as a `.gltf` (buffer 0 as a data URI, unless it is a file left
/// unchanged) or a `.glb` (buffer 0 in the binary chunk).
fn mutated(file: usize, mutations: &Mutations, as_glb: bool) -> Vec<u8> {
    let seeds = seeds();
    let mut document = seeds[file % seeds.len()].json.clone();
    let bin = if as_glb || !mutations.buffer.is_empty() {
        take_first_buffer(&mut document).map(|data| bytes::apply(data, mutations.buffer))
    } else {
        None
    };
    let mut document = json::apply(document, mutations.json);
    if let (false, Some(data)) = (as_glb, &bin) {
        embed_first_buffer(&mut document, data);
    }
    let text = serde_json::to_vec_pretty(&document).unwrap();
    let data = if as_glb {
        glb(&text, bin.as_deref())
    } else {
        text
    };
    bytes::apply(data, mutations.file)
}

fn label(as_glb: bool) -> &'static str {
    if as_glb {
        "fuzz.glb"
    } else {
        "fuzz.gltf"
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn gltf_with_mutated_json_never_panics(file in 0..16usize, json in vec(json_mutation(), 1..4)) {
        let mutations = Mutations { json: &json, ..Mutations::default() };
        let _ = import(mutated(file, &mutations, false), "fuzz.gltf");
    }

    #[test]
    fn glb_with_mutated_json_never_panics(file in 0..16usize, json in vec(json_mutation(), 1..4)) {
        let mutations = Mutations { json: &json, ..Mutations::default() };
        let _ = import(mutated(file, &mutations, true), "fuzz.glb");
    }

    #[test]
    fn mutated_buffer_data_never_panics(
        file in 0..16usize,
        buffer in vec(in_place_byte_mutation(), 1..5),
        as_glb in any::<bool>(),
    ) {
        let mutations = Mutations { buffer: &buffer, ..Mutations::default() };
        let _ = import(mutated(file, &mutations, as_glb), label(as_glb));
    }

    #[test]
    fn mutated_file_bytes_never_panic(
        file in 0..16usize,
        bytes in vec(byte_mutation(), 1..5),
        as_glb in any::<bool>(),
    ) {
        let mutations = Mutations { file: &bytes, ..Mutations::default() };
        let _ = import(mutated(file, &mutations, as_glb), label(as_glb));
    }

    #[test]
    fn arbitrary_bytes_never_panic(data in vec(any::<u8>(), 0..256), glb_header in any::<bool>()) {
        let mut bytes = if glb_header { b"glTF\x02\0\0\0".to_vec() } else { Vec::new() };
        bytes.extend(data);
        let _ = import(bytes, "noise.glb");
    }
}

#[test]
fn unmutated_corpus_loads_from_both_containers() {
    for file in 0..seeds().len() {
        for as_glb in [false, true] {
            let data = mutated(file, &Mutations::default(), as_glb);
            import(data, "seed.gltf").unwrap_or_else(|e| panic!("{}: {e}", seeds()[file].name));
        }
    }
    assert!(corpus::dir().join("features.gltf").exists());
}
