//! Bounds-checked accessor reads (no reliance on the gltf crate's reader).

use gltf::accessor::{DataType, Dimensions};
use gltf::Accessor;

/// Describes an accessor for messages.
fn name(a: &Accessor) -> String {
    format!("accessor {}", a.index())
}

/// Byte slices of each element of an accessor after checking that the
/// view and every element lie inside the buffer.
fn elements<'b>(
    a: &Accessor,
    buffers: &'b [Vec<u8>],
    elem_size: usize,
) -> Result<Vec<&'b [u8]>, String> {
    if a.sparse().is_some() {
        return Err(format!("{}: sparse accessors are not supported", name(a)));
    }
    let count = a.count();
    let Some(view) = a.view() else {
        return Err(format!("{}: has no buffer view", name(a)));
    };
    let buffer = &buffers[view.buffer().index()];
    let stride = view.stride().unwrap_or(elem_size);
    if stride < elem_size {
        return Err(format!(
            "{}: byte stride {stride} is smaller than an element ({elem_size} bytes)",
            name(a)
        ));
    }
    let view_end = view.offset().checked_add(view.length());
    if view_end.is_none_or(|e| e > buffer.len()) {
        return Err(format!(
            "buffer view {}: bytes {}..+{} lie outside buffer {} ({} bytes)",
            view.index(),
            view.offset(),
            view.length(),
            view.buffer().index(),
            buffer.len()
        ));
    }
    if count == 0 {
        return Ok(Vec::new());
    }
    let needed = (count - 1)
        .checked_mul(stride)
        .and_then(|x| x.checked_add(elem_size))
        .and_then(|x| x.checked_add(a.offset()));
    if needed.is_none_or(|n| n > view.length()) {
        return Err(format!(
            "{}: {count} elements at offset {} with stride {stride} overrun buffer view {} ({} bytes)",
            name(a),
            a.offset(),
            view.index(),
            view.length()
        ));
    }
    let start = view.offset() + a.offset();
    Ok((0..count)
        .map(|i| &buffer[start + i * stride..start + i * stride + elem_size])
        .collect())
}

fn dims(d: Dimensions) -> usize {
    d.multiplicity()
}

/// Reads an `N`-component float attribute. `normalized` integer
/// components (u8/u16) are accepted when `allow_normalized` is set. All
/// values must be finite.
pub fn read_floats<const N: usize>(
    a: &Accessor,
    buffers: &[Vec<u8>],
    allow_normalized: bool,
) -> Result<Vec<[f32; N]>, String> {
    if dims(a.dimensions()) != N {
        return Err(format!(
            "{}: expected {N} components, found {:?}",
            name(a),
            a.dimensions()
        ));
    }
    let ty = a.data_type();
    let decode: fn(&[u8]) -> f32 = match ty {
        DataType::F32 => |b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        DataType::U8 if allow_normalized && a.normalized() => |b| b[0] as f32 / 255.0,
        DataType::U16 if allow_normalized && a.normalized() => {
            |b| u16::from_le_bytes([b[0], b[1]]) as f32 / 65535.0
        }
        _ => return Err(format!("{}: unsupported component type {ty:?}", name(a))),
    };
    let cs = ty.size();
    let out: Vec<[f32; N]> = elements(a, buffers, cs * N)?
        .into_iter()
        .map(|e| std::array::from_fn(|k| decode(&e[k * cs..])))
        .collect();
    if let Some(i) = out.iter().position(|v| v.iter().any(|x| !x.is_finite())) {
        return Err(format!(
            "{}: element {i} is not finite (NaN or infinity)",
            name(a)
        ));
    }
    Ok(out)
}

/// Reads a scalar unsigned index accessor.
pub fn read_indices(a: &Accessor, buffers: &[Vec<u8>]) -> Result<Vec<u32>, String> {
    if a.dimensions() != Dimensions::Scalar {
        return Err(format!(
            "{}: indices must be scalars, found {:?}",
            name(a),
            a.dimensions()
        ));
    }
    let ty = a.data_type();
    let decode: fn(&[u8]) -> u32 = match ty {
        DataType::U8 => |b| b[0] as u32,
        DataType::U16 => |b| u16::from_le_bytes([b[0], b[1]]) as u32,
        DataType::U32 => |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        _ => {
            return Err(format!(
                "{}: index component type {ty:?} is not unsigned",
                name(a)
            ))
        }
    };
    Ok(elements(a, buffers, ty.size())?
        .into_iter()
        .map(decode)
        .collect())
}
