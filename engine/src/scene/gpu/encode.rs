//! Compact attribute encodings matching GLSL's unpack built-ins.

use glam::{Vec2, Vec3, Vec4};
use half::f16;

/// Octahedral encoding of a unit normal into two snorm16 values packed
/// like GLSL `packSnorm2x16` (x in the low half). Decode with
/// `unpackSnorm2x16`, then `n = vec3(e, 1 - |e.x| - |e.y|)`; if `n.z < 0`,
/// `n.xy = (1 - |n.yx|) * sign(n.xy)`; normalise.
pub fn encode_normal(n: Vec3) -> u32 {
    let n = n / (n.x.abs() + n.y.abs() + n.z.abs()).max(f32::MIN_POSITIVE);
    let mut e = Vec2::new(n.x, n.y);
    if n.z < 0.0 {
        e = (Vec2::ONE - Vec2::new(e.y.abs(), e.x.abs())) * sign(e);
    }
    let q = |v: f32| ((v.clamp(-1.0, 1.0) * 32767.0).round() as i16) as u16 as u32;
    q(e.x) | (q(e.y) << 16)
}

/// Inverse of [`encode_normal`].
pub fn decode_normal(bits: u32) -> Vec3 {
    let d = |v: u32| ((v as u16 as i16) as f32 / 32767.0).max(-1.0);
    let e = Vec2::new(d(bits & 0xffff), d(bits >> 16));
    let mut n = Vec3::new(e.x, e.y, 1.0 - e.x.abs() - e.y.abs());
    if n.z < 0.0 {
        let xy = (Vec2::ONE - Vec2::new(n.y.abs(), n.x.abs())) * sign(Vec2::new(n.x, n.y));
        n.x = xy.x;
        n.y = xy.y;
    }
    n.normalize()
}

/// Two half floats packed like GLSL `packHalf2x16` (x in the low half).
pub fn encode_uv(uv: Vec2) -> u32 {
    f16::from_f32(uv.x).to_bits() as u32 | ((f16::from_f32(uv.y).to_bits() as u32) << 16)
}

/// A linear RGBA colour as four half floats, `[packHalf2x16(r, g), packHalf2x16(b, a)]`.
pub fn encode_color(c: Vec4) -> [u32; 2] {
    [
        encode_uv(Vec2::new(c.x, c.y)),
        encode_uv(Vec2::new(c.z, c.w)),
    ]
}

fn sign(v: Vec2) -> Vec2 {
    Vec2::new(
        if v.x >= 0.0 { 1.0 } else { -1.0 },
        if v.y >= 0.0 { 1.0 } else { -1.0 },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normals_round_trip() {
        for i in 0..200 {
            let a = i as f32 * 0.7;
            let b = i as f32 * 0.31;
            let n = Vec3::new(a.sin() * b.cos(), a.cos(), a.sin() * b.sin()).normalize();
            let d = decode_normal(encode_normal(n));
            assert!(n.angle_between(d) < 1e-3, "{n} -> {d}");
        }
        assert!(decode_normal(encode_normal(Vec3::NEG_Z)).abs_diff_eq(Vec3::NEG_Z, 1e-4));
        assert_eq!(encode_uv(Vec2::new(1.0, 0.5)), 0x3c00 | (0x3800 << 16));
        assert_eq!(
            encode_color(Vec4::new(1.0, 0.5, 1.0, 0.0)),
            [0x3c00 | (0x3800 << 16), 0x3c00]
        );
    }
}
