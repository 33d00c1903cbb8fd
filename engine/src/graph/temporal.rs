//! Keyed history resources that persist across frames, as plain data over any resource type.

use std::collections::HashMap;

/// One key's pair of physical resources.
struct Entry<T, D> {
    desc: D,
    pair: [T; 2],
    /// Which element is `cur` this frame.
    parity: usize,
    /// Whether `prev` holds a frame's history (false after creation or reset).
    valid: bool,
    /// Whether the pair must be cleared before use (new or reset).
    needs_clear: bool,
    /// Whether a frame declared it since the last `end_frame`.
    used: bool,
}

/// The resources of one key for this frame.
pub struct TemporalSlots<'a, T> {
    /// Last frame's history.
    pub prev: &'a T,
    /// This frame's history.
    pub cur: &'a T,
    /// Whether `prev` holds history (false after creation, resize or reset).
    pub valid: bool,
    /// Whether both must be cleared to zero before use this frame.
    pub needs_clear: bool,
}

/// Ping-pong pairs keyed by name; `prev` this frame is `cur` of the last frame that used the key.
/// A key declared with a different description, or a reset, starts a new, invalid history.
pub struct TemporalStore<T, D> {
    entries: HashMap<String, Entry<T, D>>,
}

impl<T, D> Default for TemporalStore<T, D> {
    fn default() -> Self {
        Self {
            entries: HashMap::new(),
        }
    }
}

impl<T, D: PartialEq + Copy> TemporalStore<T, D> {
    /// Returns the pair for `key` this frame, creating it with `create` when new or when `desc` changed.
    pub fn begin<E>(
        &mut self,
        key: &str,
        desc: D,
        mut create: impl FnMut(D, usize) -> Result<T, E>,
    ) -> Result<TemporalSlots<'_, T>, E> {
        let stale = self.entries.get(key).is_none_or(|e| e.desc != desc);
        if stale {
            let pair = [create(desc, 0)?, create(desc, 1)?];
            self.entries.insert(
                key.to_string(),
                Entry {
                    desc,
                    pair,
                    parity: 0,
                    valid: false,
                    needs_clear: true,
                    used: false,
                },
            );
        }
        let entry = self.entries.get_mut(key).expect("inserted above");
        entry.used = true;
        Ok(TemporalSlots {
            prev: &entry.pair[1 - entry.parity],
            cur: &entry.pair[entry.parity],
            valid: entry.valid,
            needs_clear: entry.needs_clear,
        })
    }

    /// Ends the frame: every key used this frame flips, so its `cur` becomes next frame's `prev`.
    pub fn end_frame(&mut self) {
        for entry in self.entries.values_mut() {
            if std::mem::take(&mut entry.used) {
                entry.parity = 1 - entry.parity;
                entry.valid = true;
                entry.needs_clear = false;
            }
        }
    }

    /// Marks every history invalid (cleared before next use), e.g. on a scene change.
    pub fn reset_all(&mut self) {
        for entry in self.entries.values_mut() {
            entry.valid = false;
            entry.needs_clear = true;
        }
    }

    /// Marks one key's history invalid.
    pub fn reset(&mut self, key: &str) {
        if let Some(entry) = self.entries.get_mut(key) {
            entry.valid = false;
            entry.needs_clear = true;
        }
    }

    /// Drops every key, releasing its resources.
    pub fn clear(&mut self) {
        self.entries.clear();
    }

    /// The number of keys held.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether no key is held.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}
