//! Mutations of a file's bytes: flips, deletions, insertions, truncations, literal swaps in the
//! JSON text, 32-bit words in binary data, and copies of one part over another.

use proptest::prelude::*;

/// One change to a file's bytes; positions are fractions of the file's length.
#[derive(Clone, Debug)]
pub enum ByteMutation {
    /// Overwrite one byte.
    Set(f64, u8),
    /// Flip one bit.
    Flip(f64, u8),
    /// Delete a run of bytes.
    Delete(f64, u8),
    /// Insert bytes.
    Insert(f64, Vec<u8>),
    /// Cut the file.
    Truncate(f64),
    /// Replace the number literal at or after a position.
    Number(f64, &'static str),
    /// Replace the string literal at or after a position.
    Text(f64, &'static str),
    /// Write a little-endian 32-bit word at a 4-byte aligned position (NaN, infinity, huge
    /// indices in binary chunks).
    Word(f64, u32),
    /// Copy a slice over another place.
    Splice(f64, f64, u8),
}

/// Number literals that break ranges, types and counts (JSON has no NaN, so a few are not JSON).
const NUMBERS: [&str; 24] = [
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
    "1e999",
    "-0",
    "NaN",
    "Infinity",
    "2147483648",
    "9007199254740993",
];

/// String literals that name missing files, bad data URIs and unsupported things.
const TEXTS: [&str; 14] = [
    "",
    "quad.bin",
    "../quad.bin",
    "missing.bin",
    "/",
    "data:;base64,!!!",
    "data:application/octet-stream;base64,AAAA",
    "data:image/png;base64,iVBORw0KGgo=",
    "KHR_draco_mesh_compression",
    "VEC4",
    "MAT4",
    "spot",
    "directional",
    "%ff%fe",
];

/// Words that become NaN, infinity, huge floats or out-of-range indices.
const WORDS: [u32; 8] = [
    0x7fc0_0000,
    0x7f80_0000,
    0xff80_0000,
    0x7f7f_ffff,
    0xffff_ffff,
    0x0000_ffff,
    0x8000_0000,
    0x0001_0000,
];

/// Any byte mutation.
pub fn byte_mutation() -> impl Strategy<Value = ByteMutation> {
    let at = 0.0..1.0f64;
    prop_oneof![
        (at.clone(), any::<u8>()).prop_map(|(a, b)| ByteMutation::Set(a, b)),
        (at.clone(), 0..8u8).prop_map(|(a, b)| ByteMutation::Flip(a, b)),
        (at.clone(), 1..16u8).prop_map(|(a, n)| ByteMutation::Delete(a, n)),
        (at.clone(), proptest::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(a, b)| ByteMutation::Insert(a, b)),
        at.clone().prop_map(ByteMutation::Truncate),
        (at.clone(), proptest::sample::select(&NUMBERS[..]))
            .prop_map(|(a, n)| ByteMutation::Number(a, n)),
        (at.clone(), proptest::sample::select(&TEXTS[..]))
            .prop_map(|(a, t)| ByteMutation::Text(a, t)),
        (at.clone(), proptest::sample::select(&WORDS[..]))
            .prop_map(|(a, w)| ByteMutation::Word(a, w)),
        (at.clone(), at, 1..64u8).prop_map(|(a, b, n)| ByteMutation::Splice(a, b, n)),
    ]
}

/// A mutation that keeps the length: for binary data, whose length the JSON states.
pub fn in_place_byte_mutation() -> impl Strategy<Value = ByteMutation> {
    let at = 0.0..1.0f64;
    prop_oneof![
        (at.clone(), any::<u8>()).prop_map(|(a, b)| ByteMutation::Set(a, b)),
        (at.clone(), 0..8u8).prop_map(|(a, b)| ByteMutation::Flip(a, b)),
        (at.clone(), proptest::sample::select(&WORDS[..]))
            .prop_map(|(a, w)| ByteMutation::Word(a, w)),
        (at.clone(), at, 1..64u8).prop_map(|(a, b, n)| ByteMutation::Splice(a, b, n)),
    ]
}

fn pos(len: usize, at: f64) -> usize {
    ((len as f64 * at) as usize).min(len)
}

/// Finds the literal (number or quoted string) at or after `start` and replaces it.
fn replace_literal(data: &mut Vec<u8>, start: usize, number: bool, with: &str) {
    let is_num = |c: u8| c.is_ascii_digit() || matches!(c, b'-' | b'.' | b'e' | b'E' | b'+');
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

/// Applies `mutations` in order.
pub fn apply(mut data: Vec<u8>, mutations: &[ByteMutation]) -> Vec<u8> {
    for m in mutations {
        let len = data.len();
        match m {
            ByteMutation::Set(a, b) if len > 0 => {
                let i = pos(len - 1, *a);
                data[i] = *b;
            }
            ByteMutation::Flip(a, bit) if len > 0 => {
                let i = pos(len - 1, *a);
                data[i] ^= 1 << bit;
            }
            ByteMutation::Set(..) | ByteMutation::Flip(..) => {}
            ByteMutation::Delete(a, n) => {
                let i = pos(len, *a);
                data.drain(i..(i + *n as usize).min(len));
            }
            ByteMutation::Insert(a, b) => {
                let i = pos(len, *a);
                data.splice(i..i, b.iter().copied());
            }
            ByteMutation::Truncate(a) => data.truncate(pos(len, *a)),
            ByteMutation::Number(a, n) => replace_literal(&mut data, pos(len, *a), true, n),
            ByteMutation::Text(a, t) => replace_literal(&mut data, pos(len, *a), false, t),
            ByteMutation::Word(a, w) => {
                let i = pos(len / 4, *a) * 4;
                if i + 4 <= len {
                    data[i..i + 4].copy_from_slice(&w.to_le_bytes());
                }
            }
            ByteMutation::Splice(a, b, n) => {
                let (src, dst) = (pos(len, *a), pos(len, *b));
                let chunk: Vec<u8> = data[src..(src + *n as usize).min(len)].to_vec();
                let end = (dst + chunk.len()).min(len);
                data.splice(dst..end, chunk);
            }
        }
    }
    data
}
