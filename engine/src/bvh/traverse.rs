//! Stack-based traversal of a flattened BVH.

use glam::Vec3;

use super::BvhNode;

/// Walks the nodes a ray segment `(t_min, *t_max)` overlaps, nearer child
/// first, calling `leaf(first, count, t_max)` for each leaf reached. The
/// callback may shrink `t_max` (closest hit) and returns `true` to stop the
/// walk early (any hit). Returns whether the walk was stopped.
pub fn walk(
    nodes: &[BvhNode],
    origin: Vec3,
    dir: Vec3,
    t_min: f32,
    t_max: &mut f32,
    mut leaf: impl FnMut(u32, u32, &mut f32) -> bool,
) -> bool {
    let Some(root) = nodes.first() else {
        return false;
    };
    let inv_dir = dir.recip();
    if root
        .bounds()
        .intersect_ray(origin, inv_dir, t_min, *t_max)
        .is_none()
    {
        return false;
    }
    let mut stack: Vec<u32> = Vec::with_capacity(64);
    stack.push(0);
    while let Some(i) = stack.pop() {
        let node = &nodes[i as usize];
        if node.is_leaf() {
            if leaf(node.left_or_first, node.count, t_max) {
                return true;
            }
            continue;
        }
        let l = node.left_or_first;
        if l == 0 {
            // An empty tree: a lone non-leaf root without children.
            continue;
        }
        let r = l + 1;
        let hl = nodes[l as usize]
            .bounds()
            .intersect_ray(origin, inv_dir, t_min, *t_max);
        let hr = nodes[r as usize]
            .bounds()
            .intersect_ray(origin, inv_dir, t_min, *t_max);
        match (hl, hr) {
            (Some(a), Some(b)) => {
                // Push the farther child first so the nearer pops next.
                if a <= b {
                    stack.push(r);
                    stack.push(l);
                } else {
                    stack.push(l);
                    stack.push(r);
                }
            }
            (Some(_), None) => stack.push(l),
            (None, Some(_)) => stack.push(r),
            (None, None) => {}
        }
    }
    false
}
