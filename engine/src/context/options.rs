//! How a context is asked for: validation level, device choice, window support.

use std::ffi::CString;

/// How much validation the context enables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Validation {
    /// No validation layer.
    Off,
    /// `VK_LAYER_KHRONOS_validation` with its default checks.
    On,
    /// The validation layer plus synchronization validation (hazards between commands).
    Sync,
}

/// Everything [`crate::Context::new`] needs to know.
#[derive(Clone, Debug)]
pub struct ContextDesc {
    /// Application name reported to the driver.
    pub app_name: String,
    /// Validation level.
    pub validation: Validation,
    /// When true and the validation layer is not installed, creation fails instead of warning.
    pub require_validation: bool,
    /// A substring of the device name to use, or `#N` for the N-th device the loader lists (the
    /// `LUCID_DEVICE` variable).
    pub device: Option<String>,
    /// Extra instance extensions (e.g. the surface extensions a window needs).
    pub instance_extensions: Vec<CString>,
    /// Frames the CPU may record ahead of the GPU.
    pub frames_in_flight: usize,
    /// Capture each compute pipeline's executable statistics (registers, instructions, ...) through
    /// `VK_KHR_pipeline_executable_properties` when the device supports it (the
    /// `LUCID_PIPELINE_STATISTICS` variable). Unsupported devices log a warning and capture nothing.
    pub pipeline_statistics: bool,
    /// Fault injection: the frame submission with this 1-based index reports
    /// `VK_ERROR_DEVICE_LOST` instead of running, and the device counts as lost from then on (the
    /// `LUCID_INJECT_DEVICE_LOST` variable). For testing what happens on a device loss.
    pub inject_device_lost_at_frame: Option<u64>,
    /// Caps the device memory Lucid holds at once below the device-local heap, in MiB (the
    /// `LUCID_MEMORY_BUDGET_MIB` variable): an allocation or a frame beyond it is an error.
    pub memory_budget_mib: Option<u64>,
}

impl Default for ContextDesc {
    fn default() -> Self {
        Self {
            app_name: "lucid".into(),
            validation: if cfg!(debug_assertions) {
                Validation::On
            } else {
                Validation::Off
            },
            require_validation: false,
            device: None,
            instance_extensions: Vec::new(),
            frames_in_flight: 2,
            pipeline_statistics: false,
            inject_device_lost_at_frame: None,
            memory_budget_mib: None,
        }
    }
}

impl ContextDesc {
    /// The default description, adjusted by `LUCID_DEVICE` (device name substring or `#N`),
    /// `LUCID_VALIDATION` (`0`/`off`, `1`/`on`, `sync`) and `LUCID_PIPELINE_STATISTICS`
    /// (`1`/`on`/`true` captures pipeline statistics) and `LUCID_INJECT_DEVICE_LOST` (`N`: the N-th
    /// frame reports a device loss, see [`ContextDesc::inject_device_lost_at_frame`]) and
    /// `LUCID_MEMORY_BUDGET_MIB` (see [`ContextDesc::memory_budget_mib`]).
    pub fn from_env() -> Self {
        let mut desc = Self {
            device: std::env::var("LUCID_DEVICE").ok().filter(|s| !s.is_empty()),
            pipeline_statistics: std::env::var("LUCID_PIPELINE_STATISTICS").is_ok_and(|value| {
                matches!(value.to_lowercase().as_str(), "1" | "on" | "true" | "yes")
            }),
            inject_device_lost_at_frame: std::env::var("LUCID_INJECT_DEVICE_LOST")
                .ok()
                .and_then(|value| value.trim().parse().ok())
                .filter(|&frame| frame > 0),
            memory_budget_mib: std::env::var("LUCID_MEMORY_BUDGET_MIB")
                .ok()
                .and_then(|value| value.trim().parse().ok()),
            ..Self::default()
        };
        if let Ok(value) = std::env::var("LUCID_VALIDATION") {
            desc.validation = match value.to_lowercase().as_str() {
                "0" | "off" | "false" => Validation::Off,
                "sync" => Validation::Sync,
                _ => Validation::On,
            };
        }
        desc
    }

    /// The description tests use: validation required (with synchronization validation when `sync`),
    /// and the device from `LUCID_DEVICE` if set.
    pub fn for_tests(sync: bool) -> Self {
        Self {
            validation: if sync {
                Validation::Sync
            } else {
                Validation::On
            },
            require_validation: true,
            device: std::env::var("LUCID_DEVICE").ok().filter(|s| !s.is_empty()),
            ..Self::default()
        }
    }
}
