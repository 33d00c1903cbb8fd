//! The engine's error type: every failure a caller can act on, each with a message that says what to do.

mod graph_error;

pub use graph_error::GraphError;

use ash::vk;
use thiserror::Error;

/// Errors from the Vulkan context, memory, shaders and frame execution.
#[derive(Debug, Error)]
pub enum EngineError {
    /// The Vulkan loader library could not be loaded.
    #[error("the Vulkan loader (libvulkan.so.1) could not be loaded: {0}. Install it with `apt-get install libvulkan1 mesa-vulkan-drivers` (lavapipe runs Vulkan on the CPU when no GPU driver is present)")]
    NoVulkanLoader(String),
    /// Vulkan is present but no physical device is usable.
    #[error("no usable Vulkan device: {reason}. Devices found: [{}]. Install a driver (e.g. `apt-get install mesa-vulkan-drivers` for lavapipe)", .available.join(", "))]
    NoSuitableDevice {
        /// Why no device was chosen.
        reason: String,
        /// Every device the loader reported, with what disqualified it.
        available: Vec<String>,
    },
    /// A device was requested by name or index (`LUCID_DEVICE`) but none matched.
    #[error("no Vulkan device matches {requested:?}; available devices: [{}]. Set LUCID_DEVICE to a substring of one of their names, to #N for the N-th, or unset it", .available.join(", "))]
    NoSuchDevice {
        /// The requested name substring or `#N` index.
        requested: String,
        /// Names of the devices that exist.
        available: Vec<String>,
    },
    /// The device was lost (driver crash, GPU reset, or a shader fault such as an endless loop).
    /// Every later submission and wait on the context fails with this error too.
    #[error("the GPU device was lost (VK_ERROR_DEVICE_LOST) during {during}: the driver reset the GPU or a shader faulted; nothing more runs on this device, so recreate the context and the renderer; if it repeats, run with validation (LUCID_VALIDATION=1) and report the log")]
    DeviceLost {
        /// What the engine was doing when the loss was reported.
        during: String,
    },
    /// Device (GPU) memory ran out.
    #[error("out of device memory while allocating {what} ({bytes} bytes): lower the resolution or the scene's size, or free other GPU work")]
    OutOfDeviceMemory {
        /// The allocation that failed.
        what: String,
        /// Its size in bytes.
        bytes: u64,
    },
    /// An allocation or a frame's memory does not fit in the device's memory; refused before
    /// Vulkan is asked (see [`crate::context::MemoryBudget`]).
    #[error("out of device memory: {:.1} MiB for {what} is more than {limit}: lower the resolution or the scene's size", *.bytes as f64 / (1024.0 * 1024.0))]
    DoesNotFit {
        /// What was to be allocated.
        what: String,
        /// Its size in bytes.
        bytes: u64,
        /// The limit it exceeds, in words (with what is left of it).
        limit: String,
    },
    /// Any other Vulkan call failure.
    #[error("Vulkan call {call} failed: {result}")]
    Vulkan {
        /// The Vulkan entry point or step that failed.
        call: &'static str,
        /// The result code.
        result: vk::Result,
    },
    /// A shader could not be used (bad SPIR-V, reflection failure, unknown binding, wrong push constants).
    #[error("shader {shader}: {message}")]
    Shader {
        /// The shader's name.
        shader: String,
        /// What is wrong.
        message: String,
    },
    /// The render graph was set up wrongly or could not be executed.
    #[error(transparent)]
    Graph(#[from] GraphError),
    /// A required feature or extension is missing on the chosen device.
    #[error("device {device} lacks {missing}")]
    MissingFeature {
        /// Device name.
        device: String,
        /// What is missing.
        missing: String,
    },
    /// The caller passed an invalid argument (e.g. a zero-size image).
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
    /// The GPU did not finish within the wait limit.
    #[error("timed out after {seconds} s waiting for the GPU during {during}")]
    Timeout {
        /// What was being waited for.
        during: String,
        /// How long the wait lasted.
        seconds: u64,
    },
}

/// The engine's result type.
pub type Result<T, E = EngineError> = std::result::Result<T, E>;

/// Extension for converting raw `vk::Result` failures into [`EngineError`], naming the call.
pub trait VkResultExt<T> {
    /// Maps a Vulkan error to an [`EngineError`]; device loss and memory exhaustion get their own variants.
    fn vk(self, call: &'static str) -> Result<T>;
}

impl<T> VkResultExt<T> for std::result::Result<T, vk::Result> {
    fn vk(self, call: &'static str) -> Result<T> {
        self.map_err(|result| from_vk(call, result))
    }
}

/// Converts a Vulkan result code from `call` into the matching [`EngineError`].
pub fn from_vk(call: &'static str, result: vk::Result) -> EngineError {
    match result {
        vk::Result::ERROR_DEVICE_LOST => EngineError::DeviceLost {
            during: call.to_string(),
        },
        vk::Result::ERROR_OUT_OF_DEVICE_MEMORY => EngineError::OutOfDeviceMemory {
            what: call.to_string(),
            bytes: 0,
        },
        result => EngineError::Vulkan { call, result },
    }
}
