//! The 80-byte compressed node and the quantization of its children's boxes.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::bvh::Aabb;

/// Children per node.
pub const WIDTH: usize = 8;
/// Most primitives one leaf child names (the meta byte counts them in unary, 3 bits).
pub const MAX_LEAF_PRIMITIVES: u32 = 3;
/// Most primitives one node's leaf children name together (their offsets take bits 0 to 23 of
/// the traversal's hit mask; inner children take bits 24 to 31).
pub const MAX_NODE_PRIMITIVES: u32 = 24;
/// The first hit-mask bit of inner children: an inner child in slot `s` has meta `0b001` in its
/// top three bits and `INNER_BIT + s` in its low five.
pub const INNER_BIT: u8 = 24;

/// A node of the compressed wide BVH, 80 bytes (five `uvec4` in GLSL):
/// ```glsl
/// // n[0]: origin.xyz (float bits), exponent x | y << 8 | z << 16 | inner mask << 24
/// // n[1]: child base, primitive base, meta bytes 0-3, meta bytes 4-7
/// // n[2]: lo.x bytes 0-7, lo.y bytes 0-7
/// // n[3]: lo.z bytes 0-7, hi.x bytes 0-7
/// // n[4]: hi.y bytes 0-7, hi.z bytes 0-7
/// ```
/// Child `i`'s box is `origin + 2^(exponent - 127) * [lo[i], hi[i]]` per axis (conservative: it
/// contains the child's exact box). Inner children are stored contiguously from `child_base` in slot
/// order (an inner child's node is `child_base` plus the number of inner slots before its own);
/// leaf children name primitives from `primitive_base`. Meta byte `i`: 0 for an empty slot; an inner
/// child `0b001 << 5 | (24 + i)`; a leaf child its primitive count in unary in the top three bits
/// (`0b001`, `0b011`, `0b111`) and its first primitive's offset from `primitive_base` (0 to 23) in
/// the low five.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct WideNode {
    /// The quantization origin (the node box's smallest corner).
    pub origin: [f32; 3],
    /// Biased exponents (`f32` exponent bits) of the per-axis scales.
    pub exponents: [u8; 3],
    /// Bit `i` set: slot `i` is an inner child.
    pub inner_mask: u8,
    /// Index of the first inner child's node.
    pub child_base: u32,
    /// Index of the first primitive of the leaf children.
    pub primitive_base: u32,
    /// Per slot: what the child is (see the type's documentation).
    pub meta: [u8; WIDTH],
    /// Quantized smallest corners, per axis then per slot.
    pub lo: [[u8; WIDTH]; 3],
    /// Quantized largest corners, per axis then per slot.
    pub hi: [[u8; WIDTH]; 3],
}

/// What fills one slot of a node being built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Slot {
    /// Nothing.
    Empty,
    /// An inner child with these bounds.
    Inner(Aabb),
    /// A leaf child with these bounds over `count` primitives from `offset` (relative to the
    /// node's primitive base).
    Leaf {
        /// Bounds of the primitives.
        bounds: Aabb,
        /// First primitive, relative to the node's primitive base.
        offset: u32,
        /// Number of primitives, 1 to [`MAX_LEAF_PRIMITIVES`].
        count: u32,
    },
}

impl Slot {
    fn bounds(&self) -> Option<Aabb> {
        match *self {
            Slot::Empty => None,
            Slot::Inner(b) | Slot::Leaf { bounds: b, .. } => Some(b),
        }
    }
}

impl WideNode {
    /// A node over `slots`, its inner children's nodes from `child_base` and its leaves'
    /// primitives from `primitive_base`.
    pub fn new(slots: &[Slot; WIDTH], child_base: u32, primitive_base: u32) -> Self {
        let bounds = slots
            .iter()
            .filter_map(Slot::bounds)
            .fold(Aabb::EMPTY, Aabb::union);
        let mut node = WideNode {
            child_base,
            primitive_base,
            ..Default::default()
        };
        if bounds.is_empty() {
            return node;
        }
        for axis in 0..3 {
            let (origin, exponent, lo, hi) = quantize_axis(
                bounds.min[axis],
                bounds.max[axis],
                slots.map(|s| s.bounds().map(|b| (b.min[axis], b.max[axis]))),
            );
            node.origin[axis] = origin;
            node.exponents[axis] = exponent;
            node.lo[axis] = lo;
            node.hi[axis] = hi;
        }
        for (i, slot) in slots.iter().enumerate() {
            node.meta[i] = match *slot {
                Slot::Empty => 0,
                Slot::Inner(_) => {
                    node.inner_mask |= 1 << i;
                    0b001 << 5 | (INNER_BIT + i as u8)
                }
                Slot::Leaf { offset, count, .. } => {
                    assert!(
                        (1..=MAX_LEAF_PRIMITIVES).contains(&count)
                            && offset + count <= MAX_NODE_PRIMITIVES,
                        "leaf of {count} primitives at offset {offset} does not fit a wide node"
                    );
                    (((1u32 << count) - 1) << 5 | offset) as u8
                }
            };
        }
        node
    }

    /// The quantization origin.
    pub fn origin(&self) -> Vec3 {
        Vec3::from(self.origin)
    }

    /// The per-axis scales (powers of two).
    pub fn scale(&self) -> Vec3 {
        Vec3::from(self.exponents.map(|e| f32::from_bits(u32::from(e) << 23)))
    }

    /// The box slot `i` stands for after dequantization (`origin + scale * q`, as `f32`).
    pub fn child_bounds(&self, i: usize) -> Aabb {
        let (o, s) = (self.origin(), self.scale());
        let q = |c: &[[u8; WIDTH]; 3]| Vec3::new(c[0][i] as f32, c[1][i] as f32, c[2][i] as f32);
        Aabb::new(o + s * q(&self.lo), o + s * q(&self.hi))
    }
}

/// Smallest and largest biased exponents of a scale (normal `f32` powers of two).
const MIN_EXPONENT: u8 = 1;
const MAX_EXPONENT: u8 = 254;

/// The biased exponent of the smallest power of two at or above `x` (clamped to normal scales).
fn exponent_at_least(x: f32) -> u8 {
    if x.is_nan() || x <= 0.0 {
        return MIN_EXPONENT;
    }
    let bits = x.to_bits();
    let biased = (bits >> 23) + u32::from(bits & 0x7f_ffff != 0);
    biased.clamp(u32::from(MIN_EXPONENT), u32::from(MAX_EXPONENT)) as u8
}

/// Quantizes the intervals `children` (per slot, `None` for empty) of the node interval
/// `[min, max]` to bytes: the origin, the biased exponent of the smallest power-of-two scale whose
/// 255 steps cover the node, and conservative lows and highs (`origin + scale * q`, computed in
/// `f32`, lies at or beyond each child's own bound).
fn quantize_axis(
    min: f32,
    max: f32,
    children: [Option<(f32, f32)>; WIDTH],
) -> (f32, u8, [u8; WIDTH], [u8; WIDTH]) {
    let mut exponent = exponent_at_least((max - min) / 255.0);
    loop {
        let scale = f32::from_bits(u32::from(exponent) << 23);
        // Exact: both are powers of two within the normal range.
        let inv_scale = 1.0 / scale;
        let decode = |q: u32| min + scale * q as f32;
        let mut lo = [0u8; WIDTH];
        let mut hi = [0u8; WIDTH];
        let mut fits = true;
        for (i, child) in children.iter().enumerate() {
            let Some((a, b)) = *child else { continue };
            // `as u32` floors non-negative values (and saturates); no libm calls in this loop.
            let mut q_lo = (((a - min) * inv_scale) as u32).min(255);
            while q_lo > 0 && decode(q_lo) > a {
                q_lo -= 1;
            }
            let x = (b - min) * inv_scale;
            let mut q_hi = (x as u32 + u32::from((x as u32 as f32) < x)).min(256);
            while q_hi <= 255 && decode(q_hi) < b {
                q_hi += 1;
            }
            if q_hi > 255 || decode(q_lo) > a {
                fits = false;
                break;
            }
            lo[i] = q_lo as u8;
            hi[i] = q_hi as u8;
        }
        if fits || exponent == MAX_EXPONENT {
            return (min, exponent, lo, hi);
        }
        exponent += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contains(outer: &Aabb, inner: &Aabb) -> bool {
        outer.min.cmple(inner.min).all() && outer.max.cmpge(inner.max).all()
    }

    #[test]
    fn node_is_80_bytes() {
        assert_eq!(std::mem::size_of::<WideNode>(), 80);
    }

    #[test]
    fn dequantized_boxes_contain_the_children_and_stay_tight() {
        let boxes = [
            Aabb::new(Vec3::new(-3.1, 0.25, 7.0), Vec3::new(-1.0, 0.3, 7.0)),
            Aabb::new(Vec3::new(2.0, -1e-3, 6.5), Vec3::new(2.0, 0.9, 9.75)),
            Aabb::new(
                Vec3::new(-0.1, 0.1, 8.0),
                Vec3::new(0.123_456, 0.2, 8.000_001),
            ),
        ];
        let mut slots = [Slot::Empty; WIDTH];
        slots[0] = Slot::Inner(boxes[0]);
        slots[3] = Slot::Leaf {
            bounds: boxes[1],
            offset: 0,
            count: 3,
        };
        slots[7] = Slot::Leaf {
            bounds: boxes[2],
            offset: 21,
            count: 3,
        };
        let node = WideNode::new(&slots, 5, 100);
        assert_eq!(node.inner_mask, 1);
        assert_eq!(node.meta, [0x20 | 24, 0, 0, 0xe0, 0, 0, 0, 0xe0 | 21]);
        let extent = Vec3::new(5.1, 0.901, 3.25);
        for (slot, b) in [(0, boxes[0]), (3, boxes[1]), (7, boxes[2])] {
            let q = node.child_bounds(slot);
            assert!(contains(&q, &b), "{q:?} must contain {b:?}");
            // At most two steps of slack per side: a step is at most extent / 127.5.
            assert!((q.min - b.min).max_element() <= 0.0);
            assert!(((b.min - q.min) / extent).max_element() <= 2.0 / 127.5);
            assert!(((q.max - b.max) / extent).max_element() <= 2.0 / 127.5);
        }
    }

    #[test]
    fn scales_are_the_smallest_powers_of_two_at_or_above() {
        assert_eq!(exponent_at_least(1.0), 127);
        assert_eq!(exponent_at_least(1.5), 128);
        assert_eq!(exponent_at_least(0.25), 125);
        assert_eq!(exponent_at_least(0.0), MIN_EXPONENT);
        assert_eq!(exponent_at_least(f32::MAX), MAX_EXPONENT);
    }

    #[test]
    fn flat_and_point_boxes_quantize() {
        let flat = Aabb::new(Vec3::new(0.0, 1.0, 0.0), Vec3::new(2.0, 1.0, 3.0));
        let point = Aabb::new(Vec3::splat(1e6), Vec3::splat(1e6));
        for b in [flat, point] {
            let mut slots = [Slot::Empty; WIDTH];
            slots[1] = Slot::Inner(b);
            let node = WideNode::new(&slots, 0, 0);
            assert!(contains(&node.child_bounds(1), &b));
        }
    }
}
