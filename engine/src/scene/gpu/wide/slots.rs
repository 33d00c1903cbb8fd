//! Which slot each child of a node takes, so that rays visit inner children near to far.
//!
//! The traversal visits a node's inner children in the order of its ray's octant `o` (bit 0: x
//! negative, bit 1: y, bit 2: z): slot `o` first, then `o ^ 1`, `o ^ 2`, ... (it pops hit-mask bits
//! `24 + (slot ^ (7 - o))` from the highest). So slot `s` should hold the child that a ray going
//! in octant `s` reaches first: the one lying farthest back along that octant's diagonal.

use glam::Vec3;

use super::node::WIDTH;

/// The diagonal of octant `s`.
fn diagonal(s: usize) -> Vec3 {
    let sign = |bit: usize| if s & bit == 0 { 1.0 } else { -1.0 };
    Vec3::new(sign(1), sign(2), sign(4))
}

/// Slots for children with centres `centers` (at most [`WIDTH`]) in a node centred at `center`:
/// `slots[s]` is the child in slot `s`, if any. Greedy: the (child, slot) pairs are taken in order
/// of how far back the child lies along the slot's diagonal, each while both are free.
pub fn assign(centers: &[Vec3], center: Vec3) -> [Option<usize>; WIDTH] {
    assert!(centers.len() <= WIDTH, "{} children", centers.len());
    // Sort keys: the order-preserving bits of the distance along the diagonal, then child, slot.
    let mut keys = [u64::MAX; WIDTH * WIDTH];
    for (child, c) in centers.iter().enumerate() {
        for s in 0..WIDTH {
            let bits = (*c - center).dot(diagonal(s)).to_bits();
            let ordered = if bits >> 31 == 0 {
                bits | 1 << 31
            } else {
                !bits
            };
            keys[child * WIDTH + s] = u64::from(ordered) << 32 | (child * WIDTH + s) as u64;
        }
    }
    let keys = &mut keys[..centers.len() * WIDTH];
    keys.sort_unstable();
    let mut slots = [None; WIDTH];
    let mut placed = [false; WIDTH];
    for key in keys.iter() {
        let (child, s) = ((key & 0xff) as usize / WIDTH, (key & 0xff) as usize % WIDTH);
        if slots[s].is_none() && !placed[child] {
            slots[s] = Some(child);
            placed[child] = true;
        }
    }
    slots
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_child_gets_one_slot() {
        let centers: Vec<Vec3> = (0..5).map(|i| Vec3::new(i as f32, 0.5, -1.0)).collect();
        let slots = assign(&centers, Vec3::ZERO);
        let mut seen: Vec<usize> = slots.iter().flatten().copied().collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..5).collect::<Vec<_>>());
    }

    #[test]
    fn the_corner_children_of_a_cube_go_to_their_octants() {
        // Child k sits at the corner a ray of octant k reaches first: minus its diagonal.
        let centers: Vec<Vec3> = (0..WIDTH).map(|k| -diagonal(k)).collect();
        let slots = assign(&centers, Vec3::ZERO);
        assert_eq!(slots, std::array::from_fn(Some));
    }
}
