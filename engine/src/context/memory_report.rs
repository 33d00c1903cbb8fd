//! Bookkeeping of GPU memory by category (scene, transients, history, staging, ...).

use std::collections::BTreeMap;
use std::fmt;
use std::sync::Mutex;

/// Live allocation counts and bytes per category.
#[derive(Default)]
pub struct MemoryTracker(Mutex<BTreeMap<&'static str, (u64, u64)>>);

impl MemoryTracker {
    pub(crate) fn record(&self, category: &'static str, bytes: u64) {
        let mut map = self.0.lock().unwrap_or_else(|p| p.into_inner());
        let entry = map.entry(category).or_default();
        entry.0 += 1;
        entry.1 += bytes;
    }

    pub(crate) fn release(&self, category: &'static str, bytes: u64) {
        let mut map = self.0.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(entry) = map.get_mut(category) {
            entry.0 = entry.0.saturating_sub(1);
            entry.1 = entry.1.saturating_sub(bytes);
            if entry.0 == 0 {
                map.remove(category);
            }
        }
    }

    /// Bytes of every live allocation.
    pub(crate) fn total_bytes(&self) -> u64 {
        let map = self.0.lock().unwrap_or_else(|p| p.into_inner());
        map.values().map(|&(_, bytes)| bytes).sum()
    }

    pub(crate) fn report(&self, allocated: u64, reserved: u64) -> MemoryReport {
        let map = self.0.lock().unwrap_or_else(|p| p.into_inner());
        MemoryReport {
            categories: map
                .iter()
                .map(|(name, &(count, bytes))| CategoryUsage {
                    category: name.to_string(),
                    allocations: count,
                    bytes,
                })
                .collect(),
            allocated_bytes: allocated,
            reserved_bytes: reserved,
        }
    }
}

/// Memory of one category.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CategoryUsage {
    /// The category (e.g. `scene`, `graph.transient`, `graph.history`, `staging`).
    pub category: String,
    /// Live allocations.
    pub allocations: u64,
    /// Bytes in those allocations.
    pub bytes: u64,
}

/// A snapshot of GPU memory use.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MemoryReport {
    /// Per-category usage, sorted by name.
    pub categories: Vec<CategoryUsage>,
    /// Bytes handed out by the allocator.
    pub allocated_bytes: u64,
    /// Bytes of device memory blocks the allocator holds.
    pub reserved_bytes: u64,
}

impl MemoryReport {
    /// Bytes in use by `category` (0 when it has none).
    pub fn bytes(&self, category: &str) -> u64 {
        self.categories
            .iter()
            .find(|c| c.category == category)
            .map_or(0, |c| c.bytes)
    }
}

fn mib(bytes: u64) -> f64 {
    bytes as f64 / (1024.0 * 1024.0)
}

impl fmt::Display for MemoryReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "GPU memory: {:.1} MiB allocated in {:.1} MiB of blocks",
            mib(self.allocated_bytes),
            mib(self.reserved_bytes)
        )?;
        for c in &self.categories {
            writeln!(
                f,
                "  {:<20} {:>6} allocations {:>10.2} MiB",
                c.category,
                c.allocations,
                mib(c.bytes)
            )?;
        }
        Ok(())
    }
}
