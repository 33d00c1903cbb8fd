//! Physical-device selection as plain data: which device the engine picks, and why the others were not.

use crate::error::EngineError;

/// What the engine knows about one physical device when choosing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeviceCandidate {
    /// The driver's device name (e.g. `NVIDIA H200`, `llvmpipe (LLVM 15.0.6, 256 bits)`).
    pub name: String,
    /// Discrete, integrated, virtual, CPU or other.
    pub kind: DeviceKind,
    /// Why the device cannot run Lucid, if it cannot (missing Vulkan 1.3, no compute queue, ...).
    pub unusable: Option<String>,
}

/// The kind of a physical device, in the order the engine prefers them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum DeviceKind {
    /// A discrete GPU.
    Discrete,
    /// A GPU integrated with the CPU.
    Integrated,
    /// A virtualised GPU.
    Virtual,
    /// A software implementation such as lavapipe.
    Cpu,
    /// Anything else.
    Other,
}

impl DeviceKind {
    /// How long one wait for the device may last before it counts as hung: a minute on a GPU, ten
    /// on a software implementation, which compiles a shader when it first dispatches it and
    /// shares the processor with whatever else the machine runs (lavapipe's first frame of a large
    /// kernel passed a minute on a two-core machine busy with a build).
    pub fn wait_limit(self) -> std::time::Duration {
        let minutes = if self == DeviceKind::Cpu { 10 } else { 1 };
        std::time::Duration::from_secs(60 * minutes)
    }
}

/// Chooses a device: with `requested` = `#N`, the N-th the loader lists (from 0; for machines of
/// several identical GPUs); with another `requested`, the first usable one whose name contains it
/// (case-insensitive); otherwise the most preferred kind (discrete first), ties broken by
/// enumeration order.
pub fn select_device(
    candidates: &[DeviceCandidate],
    requested: Option<&str>,
) -> Result<usize, EngineError> {
    let describe = || {
        candidates
            .iter()
            .enumerate()
            .map(|(i, c)| match &c.unusable {
                Some(why) => format!("#{i} {} ({why})", c.name),
                None => format!("#{i} {}", c.name),
            })
            .collect::<Vec<_>>()
    };
    let no_such = |requested: &str| EngineError::NoSuchDevice {
        requested: requested.to_string(),
        available: describe(),
    };
    let unusable = |requested: &str| EngineError::NoSuitableDevice {
        reason: format!("every device matching {requested:?} is unusable"),
        available: describe(),
    };
    if let Some(requested) = requested.filter(|r| !r.is_empty()) {
        if let Some(digits) = requested.strip_prefix('#') {
            let index = digits
                .parse::<usize>()
                .ok()
                .filter(|&i| i < candidates.len())
                .ok_or_else(|| no_such(requested))?;
            return match candidates[index].unusable {
                None => Ok(index),
                Some(_) => Err(unusable(requested)),
            };
        }
        let needle = requested.to_lowercase();
        let matching: Vec<usize> = (0..candidates.len())
            .filter(|&i| candidates[i].name.to_lowercase().contains(&needle))
            .collect();
        if matching.is_empty() {
            return Err(no_such(requested));
        }
        return matching
            .iter()
            .copied()
            .find(|&i| candidates[i].unusable.is_none())
            .ok_or_else(|| unusable(requested));
    }
    (0..candidates.len())
        .filter(|&i| candidates[i].unusable.is_none())
        .min_by_key(|&i| (candidates[i].kind, i))
        .ok_or_else(|| EngineError::NoSuitableDevice {
            reason: if candidates.is_empty() {
                "the Vulkan loader reported no physical devices".to_string()
            } else {
                "none supports Vulkan 1.3 compute with the features Lucid needs".to_string()
            },
            available: describe(),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn software_devices_may_take_longer_than_gpus() {
        for gpu in [
            DeviceKind::Discrete,
            DeviceKind::Integrated,
            DeviceKind::Virtual,
        ] {
            assert_eq!(gpu.wait_limit().as_secs(), 60);
        }
        assert_eq!(DeviceKind::Cpu.wait_limit().as_secs(), 600);
    }

    fn candidate(name: &str, kind: DeviceKind, unusable: Option<&str>) -> DeviceCandidate {
        DeviceCandidate {
            name: name.into(),
            kind,
            unusable: unusable.map(str::to_string),
        }
    }

    #[test]
    fn prefers_discrete_gpu() {
        let list = [
            candidate("llvmpipe", DeviceKind::Cpu, None),
            candidate("NVIDIA H200", DeviceKind::Discrete, None),
        ];
        assert_eq!(select_device(&list, None).unwrap(), 1);
    }

    #[test]
    fn skips_unusable_devices() {
        let list = [
            candidate("old gpu", DeviceKind::Discrete, Some("Vulkan 1.1")),
            candidate("llvmpipe", DeviceKind::Cpu, None),
        ];
        assert_eq!(select_device(&list, None).unwrap(), 1);
    }

    #[test]
    fn request_by_substring_is_case_insensitive() {
        let list = [
            candidate("NVIDIA H200", DeviceKind::Discrete, None),
            candidate("llvmpipe (LLVM 15)", DeviceKind::Cpu, None),
        ];
        assert_eq!(select_device(&list, Some("LLVMPIPE")).unwrap(), 1);
    }

    #[test]
    fn request_by_index_picks_one_of_identical_gpus() {
        let list = [
            candidate("NVIDIA H100", DeviceKind::Discrete, None),
            candidate("NVIDIA H100", DeviceKind::Discrete, None),
            candidate(
                "NVIDIA H100",
                DeviceKind::Discrete,
                Some("no compute queue"),
            ),
        ];
        assert_eq!(select_device(&list, Some("#1")).unwrap(), 1);
        assert_eq!(select_device(&list, Some("#0")).unwrap(), 0);
        let err = select_device(&list, Some("#3")).unwrap_err();
        assert!(matches!(err, EngineError::NoSuchDevice { .. }), "{err}");
        let text = err.to_string();
        assert!(text.contains("#1 NVIDIA H100"), "{text}");
        assert!(matches!(
            select_device(&list, Some("#x")).unwrap_err(),
            EngineError::NoSuchDevice { .. }
        ));
        let err = select_device(&list, Some("#2")).unwrap_err();
        assert!(matches!(err, EngineError::NoSuitableDevice { .. }), "{err}");
    }

    #[test]
    fn unknown_request_lists_available_devices() {
        let list = [candidate("llvmpipe", DeviceKind::Cpu, None)];
        let err = select_device(&list, Some("radeon")).unwrap_err();
        let text = err.to_string();
        assert!(matches!(err, EngineError::NoSuchDevice { .. }));
        assert!(
            text.contains("radeon") && text.contains("llvmpipe"),
            "{text}"
        );
    }

    #[test]
    fn no_usable_device_is_an_error_naming_why() {
        let list = [candidate(
            "old gpu",
            DeviceKind::Discrete,
            Some("Vulkan 1.1"),
        )];
        let text = select_device(&list, None).unwrap_err().to_string();
        assert!(text.contains("old gpu (Vulkan 1.1)"), "{text}");
    }
}
