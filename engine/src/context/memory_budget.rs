//! What fits in device memory. Allocations and a frame's transients are checked against the
//! device's largest device-local heap (or a smaller budget, `LUCID_MEMORY_BUDGET_MIB`) and its
//! largest single allocation before Vulkan is asked, so a frame or scene too big for the device
//! is a clear error rather than a driver failure, a swapping machine (lavapipe's device memory
//! is host memory) or an abort.

use crate::error::{EngineError, Result};
use ash::vk;

/// The device's memory limits Lucid checks allocations against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryBudget {
    /// Bytes of the device's largest device-local heap.
    pub heap_bytes: u64,
    /// A smaller budget asked for ([`super::ContextDesc::memory_budget_mib`]), in bytes.
    pub limit_bytes: Option<u64>,
    /// The largest single allocation the device makes (`maxMemoryAllocationSize`).
    pub max_allocation_bytes: u64,
}

fn mib(bytes: u64) -> String {
    format!("{:.1} MiB", bytes as f64 / (1024.0 * 1024.0))
}

impl MemoryBudget {
    /// Reads the heaps and limits of `physical`; `limit_mib` caps the budget.
    pub(crate) fn query(
        instance: &ash::Instance,
        physical: vk::PhysicalDevice,
        limit_mib: Option<u64>,
    ) -> Self {
        // SAFETY: physical comes from this instance.
        let memory = unsafe { instance.get_physical_device_memory_properties(physical) };
        let heaps = &memory.memory_heaps[..memory.memory_heap_count as usize];
        let heap_bytes = heaps
            .iter()
            .filter(|h| h.flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL))
            .map(|h| h.size)
            .max()
            .or_else(|| heaps.iter().map(|h| h.size).max())
            .unwrap_or(0);
        let mut maintenance3 = vk::PhysicalDeviceMaintenance3Properties::default();
        let mut props = vk::PhysicalDeviceProperties2::default().push_next(&mut maintenance3);
        // SAFETY: physical comes from this instance (Vulkan 1.1 or later).
        unsafe { instance.get_physical_device_properties2(physical, &mut props) };
        Self {
            heap_bytes,
            limit_bytes: limit_mib.map(|m| m.saturating_mul(1024 * 1024)),
            max_allocation_bytes: maintenance3.max_memory_allocation_size,
        }
    }

    /// The bytes Lucid may hold at once.
    pub fn bytes(&self) -> u64 {
        self.limit_bytes
            .map_or(self.heap_bytes, |l| l.min(self.heap_bytes))
    }

    /// Fails when `what`, `bytes` in one allocation (`single`) or in several, does not fit next to
    /// the `held` bytes Lucid holds already.
    pub(crate) fn check(&self, what: &str, bytes: u64, held: u64, single: bool) -> Result<()> {
        let limit = if single && bytes > self.max_allocation_bytes {
            format!(
                "the {} the device allocates at once (maxMemoryAllocationSize)",
                mib(self.max_allocation_bytes)
            )
        } else if held.saturating_add(bytes) > self.bytes() {
            let left = mib(self.bytes().saturating_sub(held));
            match self.limit_bytes.filter(|&l| l < self.heap_bytes) {
                Some(l) => format!(
                    "the {left} left of the budget LUCID_MEMORY_BUDGET_MIB={}",
                    l / (1024 * 1024)
                ),
                None => format!(
                    "the {left} left of the device's {} heap (Lucid holds {})",
                    mib(self.heap_bytes),
                    mib(held)
                ),
            }
        } else {
            return Ok(());
        };
        Err(EngineError::DoesNotFit {
            what: what.to_string(),
            bytes,
            limit,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::MemoryBudget;

    const MIB: u64 = 1024 * 1024;

    fn budget(limit: Option<u64>) -> MemoryBudget {
        MemoryBudget {
            heap_bytes: 1024 * MIB,
            limit_bytes: limit,
            max_allocation_bytes: 256 * MIB,
        }
    }

    #[test]
    fn allocations_must_fit_the_heap_the_budget_and_the_largest_allocation() {
        let b = budget(None);
        assert!(b.check("a", 256 * MIB, 0, true).is_ok());
        let e = b
            .check("image x", 257 * MIB, 0, true)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("257.0 MiB for image x is more than the 256.0 MiB"),
            "{e}"
        );
        assert!(e.contains("maxMemoryAllocationSize"), "{e}");
        assert!(b.check("frame", 600 * MIB, 0, false).is_ok());
        let e = b
            .check("frame", 600 * MIB, 500 * MIB, false)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("524.0 MiB left of the device's 1024.0 MiB heap"),
            "{e}"
        );
        let limited = budget(Some(64 * MIB));
        assert_eq!(limited.bytes(), 64 * MIB);
        let e = limited
            .check("scene", 65 * MIB, 0, true)
            .unwrap_err()
            .to_string();
        assert!(e.contains("LUCID_MEMORY_BUDGET_MIB=64"), "{e}");
        assert_eq!(budget(Some(4096 * MIB)).bytes(), 1024 * MIB);
    }
}
