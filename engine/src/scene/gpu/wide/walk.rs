//! The GPU traversal of a wide tree, on the CPU: `shaders/common/traverse.glsl` step for step (the
//! same slab test, near-to-far order and stack of node groups), for tests and for checking the
//! stack depth a tree needs.

use glam::Vec3;

use super::node::{WideNode, INNER_BIT, WIDTH};
use super::EMPTY;

/// What a walk did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Walked {
    /// Whether the callback stopped the walk.
    pub stopped: bool,
    /// The most node groups the stack held at once.
    pub stack_depth: usize,
}

/// The ray's reciprocal direction as the shader computes it (`safe_inverse`).
fn safe_inverse(d: Vec3) -> Vec3 {
    const TINY: f32 = 1e-20;
    let clamp = |x: f32| {
        if x.abs() > TINY {
            x
        } else if x >= 0.0 {
            TINY
        } else {
            -TINY
        }
    };
    Vec3::new(clamp(d.x), clamp(d.y), clamp(d.z)).recip()
}

/// The hit mask of `node`'s children for a ray in octant order `octant_inverse` (`7 - octant`):
/// inner children at bits `24 + (slot ^ octant_inverse)`, leaf primitives at their offsets.
fn intersect(
    node: &WideNode,
    scaled_origin: Vec3,
    inv_dir: Vec3,
    octant_inverse: u32,
    t_max: f32,
) -> u32 {
    let adjusted_inv = node.scale() * inv_dir;
    let origin = node.origin();
    let adjusted_origin = Vec3::new(
        origin.x.mul_add(inv_dir.x, -scaled_origin.x),
        origin.y.mul_add(inv_dir.y, -scaled_origin.y),
        origin.z.mul_add(inv_dir.z, -scaled_origin.z),
    );
    let mut hits = 0;
    for slot in 0..WIDTH {
        let mut enter = 0.0f32;
        let mut leave = t_max;
        for axis in 0..3 {
            let (near, far) = if inv_dir[axis] >= 0.0 {
                (node.lo[axis][slot], node.hi[axis][slot])
            } else {
                (node.hi[axis][slot], node.lo[axis][slot])
            };
            let t = |q: u8| (q as f32).mul_add(adjusted_inv[axis], adjusted_origin[axis]);
            enter = enter.max(t(near));
            leave = leave.min(t(far));
        }
        if enter > leave {
            continue;
        }
        let meta = u32::from(node.meta[slot]);
        let mut bit = meta & 31;
        if node.inner_mask & (1 << slot) != 0 {
            bit ^= octant_inverse;
        }
        hits |= (meta >> 5) << bit;
    }
    hits
}

/// Walks the tree `nodes` from `root` for the ray `origin + t dir`, `t` in `(0, *t_max)`, as the GPU
/// does: calls `primitive(index, t_max)` for every primitive of each leaf child whose box the ray
/// enters; the callback may shrink `t_max` (closest hit) and returns `true` to stop (any hit).
pub fn walk(
    nodes: &[WideNode],
    root: u32,
    origin: Vec3,
    dir: Vec3,
    t_max: &mut f32,
    mut primitive: impl FnMut(u32, &mut f32) -> bool,
) -> Walked {
    let mut walked = Walked::default();
    if root == EMPTY {
        return walked;
    }
    let inv_dir = safe_inverse(dir);
    let scaled_origin = origin * inv_dir;
    let octant = u32::from(dir.x < 0.0) | u32::from(dir.y < 0.0) << 1 | u32::from(dir.z < 0.0) << 2;
    let octant_inverse = 7 - octant;
    // A node group: the base of a node's inner children and its hit mask (inner hits in bits
    // 24-31, the inner mask in bits 0-7).
    let mut group = (root, 1u32 << (u32::from(INNER_BIT) + octant_inverse) | 1);
    let mut triangles = (0u32, 0u32);
    let mut stack: Vec<(u32, u32)> = Vec::new();
    loop {
        while triangles.1 != 0 {
            let k = triangles.1.trailing_zeros();
            triangles.1 &= triangles.1 - 1;
            if primitive(triangles.0 + k, t_max) {
                walked.stopped = true;
                return walked;
            }
        }
        if group.1 <= 0x00ff_ffff {
            match stack.pop() {
                Some(g) => group = g,
                None => return walked,
            }
        }
        let bit = 31 - group.1.leading_zeros();
        group.1 &= !(1 << bit);
        let slot = (bit - u32::from(INNER_BIT)) ^ octant_inverse;
        let rank = (group.1 & 0xff & ((1 << slot) - 1)).count_ones();
        let node = &nodes[(group.0 + rank) as usize];
        if group.1 > 0x00ff_ffff {
            stack.push(group);
            walked.stack_depth = walked.stack_depth.max(stack.len());
        }
        let hits = intersect(node, scaled_origin, inv_dir, octant_inverse, *t_max);
        group = (
            node.child_base,
            (hits & 0xff00_0000) | u32::from(node.inner_mask),
        );
        triangles = (node.primitive_base, hits & 0x00ff_ffff);
    }
}

#[cfg(test)]
mod tests {
    use super::super::pack_tree;
    use super::*;
    use crate::bvh::build::{build, PrimRef};
    use crate::bvh::{walk as binary_walk, Aabb};

    /// Boxes as primitives: the wide walk over the packed tree reaches the same closest box as the
    /// binary walk (the rays aim off the boxes' grid: at an exact edge the two may round apart).
    #[test]
    fn wide_walk_finds_the_closest_box_like_the_binary_walk() {
        let boxes: Vec<Aabb> = (0..3000)
            .map(|i| {
                let p = Vec3::new((i % 29) as f32, (i / 29 % 13) as f32, (i * 7 % 17) as f32);
                Aabb::new(p, p + Vec3::new(0.6, 0.2, 0.9))
            })
            .collect();
        let tree = build(
            boxes
                .iter()
                .enumerate()
                .map(|(i, b)| PrimRef::new(b, i as u32))
                .collect(),
        );
        let mut nodes = Vec::new();
        let packed = pack_tree(&tree.nodes, 0, &mut nodes);
        let hit =
            |b: &Aabb, o: Vec3, d: Vec3, t_max: f32| b.intersect_ray(o, d.recip(), 0.0, t_max);
        for i in 0..500 {
            let a = i as f32 * 0.37;
            let origin = Vec3::new(14.0 + 20.0 * a.cos(), 6.0 + 3.0 * (a * 1.3).sin(), -5.0);
            let dir = if i % 10 == 0 {
                [Vec3::X, Vec3::NEG_Z, Vec3::Y][i % 3]
            } else {
                (Vec3::new(14.13, 6.07, 8.31) - origin + Vec3::new(a.sin(), 0.0, 0.0) * 9.0)
                    .normalize()
            };
            let mut want = f32::INFINITY;
            binary_walk(
                &tree.nodes,
                origin,
                dir,
                0.0,
                &mut want,
                |first, count, t| {
                    for k in first..first + count {
                        let b = &boxes[tree.order[k as usize] as usize];
                        if let Some(h) = hit(b, origin, dir, *t) {
                            *t = t.min(h.max(1e-30));
                        }
                    }
                    false
                },
            );
            let mut got = f32::INFINITY;
            let walked = walk(&nodes, packed.root, origin, dir, &mut got, |k, t| {
                let b = &boxes[tree.order[packed.order[k as usize] as usize] as usize];
                if let Some(h) = hit(b, origin, dir, *t) {
                    *t = t.min(h.max(1e-30));
                }
                false
            });
            assert_eq!(want, got, "ray {i}");
            assert!(walked.stack_depth < packed.depth as usize);
        }
    }
}
