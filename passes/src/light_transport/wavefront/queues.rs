//! Where the wavefront path tracer's queues keep their lengths and indirect arguments
//! (`shaders/wavefront/queues.glsl`): per sample, slot `2k` is bounce `k`'s ray queue and `2k + 1`
//! its shadow-ray queue. The lengths sit in one buffer (a u32 per slot); the indirect arguments
//! (a `VkDispatchIndirectCommand` per slot, 16 bytes apart) in two buffers by parity, so that the
//! shade kernel reads its own queue's arguments for its dispatch and appends to the other buffer:
//! a pass may not read one buffer both as indirect arguments and as storage. The binned kernels
//! also count each bounce's hits per material bin, after the slots' lengths.

/// Invocations per workgroup of the kernels that run over a queue (`QUEUE_GROUP`).
pub const QUEUE_GROUP: u32 = 128;

/// Bytes between two slots' indirect arguments.
const ARGS_STRIDE: u64 = 16;

/// The most paths one wave traces: a queue of them must fit in the workgroup counts every device
/// takes in x (`maxComputeWorkGroupCount[0]` is at least 65535).
pub const MAX_PATHS: u64 = 65535 * QUEUE_GROUP as u64;

/// The queue slots of a frame of paths at most `max_depth` segments long: a ray and a shadow
/// queue per bounce, and the ray queue after the last bounce (the last shade kernel ends every
/// path, but its code may name the slot).
pub fn slots(max_depth: u32) -> u32 {
    2 * max_depth + 1
}

/// The bins the binned kernels sort each bounce's hits into: a miss, or the kind of the material
/// hit (`MATERIAL_BINS` in `queues.glsl`).
pub const MATERIAL_BINS: u32 = 5;

/// The queue lengths kept per sample: a length per slot, and with `binned` one per material bin
/// and bounce after them.
pub fn counters(max_depth: u32, binned: bool) -> u32 {
    slots(max_depth) + if binned { max_depth * MATERIAL_BINS } else { 0 }
}

/// The slot of bounce `depth`'s ray queue.
pub fn ray_slot(depth: u32) -> u32 {
    2 * depth
}

/// The slot of bounce `depth`'s shadow-ray queue.
pub fn shadow_slot(depth: u32) -> u32 {
    2 * depth + 1
}

/// Which of the two indirect-argument buffers (0: even, 1: odd) holds `slot`'s arguments: the ray
/// queue of bounce `k` in `k % 2`, its shadow queue in `(k + 1) % 2`, where bounce `k`'s shade
/// kernel appends.
pub fn args_buffer(slot: u32) -> usize {
    let depth = slot / 2;
    ((depth + slot % 2) % 2) as usize
}

/// The byte offset of `slot`'s arguments in its buffer.
pub fn args_offset(slot: u32) -> u64 {
    u64::from(slot) * ARGS_STRIDE
}

/// The size of each indirect-argument buffer in bytes.
pub fn args_bytes(max_depth: u32) -> u64 {
    u64::from(slots(max_depth)) * ARGS_STRIDE
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shade_reads_its_arguments_from_one_buffer_and_appends_to_the_other() {
        for depth in 0..8 {
            let own = args_buffer(ray_slot(depth));
            assert_eq!(own, (depth % 2) as usize);
            assert_ne!(args_buffer(shadow_slot(depth)), own);
            assert_ne!(args_buffer(ray_slot(depth + 1)), own);
        }
    }

    #[test]
    fn the_material_bins_count_after_the_slots() {
        assert_eq!(counters(8, false), slots(8));
        assert_eq!(counters(8, true), slots(8) + 8 * MATERIAL_BINS);
    }

    #[test]
    fn every_slot_a_shade_kernel_appends_to_fits() {
        let max_depth = 8;
        let last = ray_slot(max_depth);
        assert!(last < slots(max_depth));
        assert!(args_offset(last) + 12 <= args_bytes(max_depth));
    }
}
