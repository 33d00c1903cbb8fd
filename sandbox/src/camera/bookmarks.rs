//! Nine camera bookmarks: Shift+digit stores the current pose, the digit recalls it.

use super::Pose;

/// Poses stored under the keys 1 to 9.
#[derive(Clone, Debug, Default)]
pub struct Bookmarks {
    slots: [Option<Pose>; 9],
}

impl Bookmarks {
    /// Stores `pose` under `key` (1 to 9); other keys are ignored.
    pub fn store(&mut self, key: u8, pose: Pose) {
        if let Some(slot) = Self::index(key).and_then(|i| self.slots.get_mut(i)) {
            *slot = Some(pose);
        }
    }

    /// The pose stored under `key`, if any.
    pub fn recall(&self, key: u8) -> Option<Pose> {
        Self::index(key).and_then(|i| self.slots.get(i).copied().flatten())
    }

    /// The keys that hold a pose.
    pub fn stored_keys(&self) -> Vec<u8> {
        (1..=9).filter(|&k| self.recall(k).is_some()).collect()
    }

    fn index(key: u8) -> Option<usize> {
        (1..=9).contains(&key).then(|| usize::from(key - 1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn stores_and_recalls_keys_one_to_nine() {
        let pose = Pose {
            position: Vec3::X,
            yaw: 1.0,
            pitch: 0.5,
            vfov_degrees: 40.0,
        };
        let mut marks = Bookmarks::default();
        assert_eq!(marks.recall(3), None);
        marks.store(3, pose);
        marks.store(0, pose);
        marks.store(10, pose);
        assert_eq!(marks.recall(3), Some(pose));
        assert_eq!(marks.stored_keys(), vec![3]);
    }
}
