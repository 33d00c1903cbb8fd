//! The Vulkan context: instance, validation, device, compute queue and the memory allocator with
//! its bookkeeping by category.
//!
//! Headless is the default: [`Context::new`] needs no window. A windowed app uses
//! [`Context::with_surface`]; an application that already has Vulkan uses [`Context::from_existing`].

mod cooperative_matrix;
mod debug;
mod device;
mod device_loss;
mod driver_residency;
mod instance;
mod loader_lock;
mod memory_budget;
pub(crate) mod memory_report;
mod options;
mod select;

pub use debug::{ValidationLog, ValidationMessage};
pub use device::DeviceInfo;
pub use memory_budget::MemoryBudget;
pub use options::{ContextDesc, Validation};
pub use select::{select_device, DeviceCandidate, DeviceKind};

use crate::error::{EngineError, Result, VkResultExt};
use ash::vk;
use device_loss::DeviceLoss;
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};
use memory_report::MemoryTracker;
use std::ffi::CString;
use std::mem::ManuallyDrop;
use std::sync::{Arc, Mutex, MutexGuard};

/// The Vulkan objects an application that already uses Vulkan hands to Lucid.
///
/// The device must have been created with Vulkan 1.3, `synchronization2`, `timelineSemaphore` and
/// `VK_KHR_push_descriptor` enabled; Lucid never destroys these objects.
pub struct ExistingVulkan {
    /// The loader entry the instance was created from.
    pub entry: ash::Entry,
    /// The application's instance.
    pub instance: ash::Instance,
    /// The physical device behind `device`.
    pub physical_device: vk::PhysicalDevice,
    /// The application's logical device.
    pub device: ash::Device,
    /// A queue family with compute support.
    pub queue_family: u32,
    /// A queue of that family. Lucid locks its own mutex around submissions; the application must not
    /// submit to this queue concurrently with Lucid.
    pub queue: vk::Queue,
    /// Whether `device` was created with `shaderInt64` and `shaderBufferInt64Atomics` enabled
    /// (bidirectional path tracing needs them; Lucid cannot query what a device enabled).
    pub int64_atomics: bool,
}

pub(crate) struct Shared {
    pub entry: ash::Entry,
    pub instance: ash::Instance,
    pub physical_device: vk::PhysicalDevice,
    pub device: ash::Device,
    pub queue_family: u32,
    queue: Mutex<vk::Queue>,
    pub allocator: ManuallyDrop<Mutex<Allocator>>,
    pub push_descriptor: ash::khr::push_descriptor::Device,
    pub executable_properties: Option<ash::khr::pipeline_executable_properties::Device>,
    debug_utils_instance: Option<ash::ext::debug_utils::Instance>,
    pub debug_utils: Option<ash::ext::debug_utils::Device>,
    messenger: vk::DebugUtilsMessengerEXT,
    pub validation: ValidationLog,
    pub info: DeviceInfo,
    pub memory: MemoryTracker,
    pub frames_in_flight: usize,
    pub device_loss: DeviceLoss,
    pub budget: MemoryBudget,
    validation_level: Validation,
    owns_vulkan: bool,
}

/// What [`Context`] construction takes from [`ContextDesc`] besides the device.
struct AssembleOptions {
    frames_in_flight: usize,
    inject_device_lost_at_frame: Option<u64>,
    memory_budget_mib: Option<u64>,
}

/// A cheaply clonable handle to the Vulkan device and everything created with it.
#[derive(Clone)]
pub struct Context {
    pub(crate) shared: Arc<Shared>,
}

impl Context {
    /// Creates a headless context (no window, no surface).
    pub fn new(desc: &ContextDesc) -> Result<Self> {
        Self::create(
            desc,
            None::<fn(&ash::Entry, &ash::Instance) -> Result<vk::SurfaceKHR>>,
        )
        .map(|(ctx, _)| ctx)
    }

    /// Creates a context whose queue can present to the surface that `create_surface` makes
    /// (the caller owns the returned surface and destroys it before dropping the context).
    /// `desc.instance_extensions` must list the surface extensions the window needs.
    pub fn with_surface(
        desc: &ContextDesc,
        create_surface: impl FnOnce(&ash::Entry, &ash::Instance) -> Result<vk::SurfaceKHR>,
    ) -> Result<(Self, vk::SurfaceKHR)> {
        Self::create(desc, Some(create_surface))
    }

    fn create(
        desc: &ContextDesc,
        create_surface: Option<impl FnOnce(&ash::Entry, &ash::Instance) -> Result<vk::SurfaceKHR>>,
    ) -> Result<(Self, vk::SurfaceKHR)> {
        if desc.frames_in_flight == 0 {
            return Err(EngineError::InvalidArgument(
                "frames_in_flight must be at least 1".into(),
            ));
        }
        let validation = ValidationLog::default();
        let _loader = loader_lock::exclusive();
        driver_residency::pin_drivers();
        let created = instance::create_instance(desc, &validation)?;
        let destroy_instance = |c: &instance::CreatedInstance| {
            // SAFETY: nothing else was created from the instance that is still alive.
            unsafe {
                if let Some(utils) = &c.debug_utils {
                    utils.destroy_debug_utils_messenger(c.messenger, None);
                }
                c.instance.destroy_instance(None);
            }
        };
        let surface = match create_surface {
            Some(make) => match make(&created.entry, &created.instance) {
                Ok(surface) => surface,
                Err(e) => {
                    destroy_instance(&created);
                    return Err(e);
                }
            },
            None => vk::SurfaceKHR::null(),
        };
        let surface_loader = ash::khr::surface::Instance::new(&created.entry, &created.instance);
        let present = |physical: vk::PhysicalDevice, family: u32| {
            surface == vk::SurfaceKHR::null()
                // SAFETY: physical and surface come from the same instance.
                || unsafe {
                    surface_loader.get_physical_device_surface_support(physical, family, surface)
                }
                .unwrap_or(false)
        };
        let dev = match device::create_device(
            &created.entry,
            &created.instance,
            desc.device.as_deref(),
            &present,
            surface != vk::SurfaceKHR::null(),
            desc.pipeline_statistics,
        ) {
            Ok(dev) => dev,
            Err(e) => {
                if surface != vk::SurfaceKHR::null() {
                    // SAFETY: the surface was created from this instance and is unused.
                    unsafe { surface_loader.destroy_surface(surface, None) };
                }
                destroy_instance(&created);
                return Err(e);
            }
        };
        let ctx = Self::assemble(
            ExistingVulkan {
                entry: created.entry,
                instance: created.instance,
                physical_device: dev.physical_device,
                device: dev.device,
                queue_family: dev.queue_family,
                queue: dev.queue,
                int64_atomics: dev.info.int64_atomics,
            },
            dev.info,
            created.debug_utils,
            created.messenger,
            (validation, created.validation),
            AssembleOptions {
                frames_in_flight: desc.frames_in_flight,
                inject_device_lost_at_frame: desc.inject_device_lost_at_frame,
                memory_budget_mib: desc.memory_budget_mib,
            },
            true,
        )?;
        Ok((ctx, surface))
    }

    /// Wraps an application's own instance, device and queue (bring your own Vulkan).
    /// Validation messages are not collected here: the application owns the instance and its messenger.
    pub fn from_existing(existing: ExistingVulkan, frames_in_flight: usize) -> Result<Self> {
        let instance = &existing.instance;
        // SAFETY: the caller guarantees the handles are valid and related.
        let props = unsafe { instance.get_physical_device_properties(existing.physical_device) };
        // SAFETY: as above.
        let families = unsafe {
            instance.get_physical_device_queue_family_properties(existing.physical_device)
        };
        let family = families
            .get(existing.queue_family as usize)
            .ok_or_else(|| EngineError::InvalidArgument("queue_family out of range".into()))?;
        if !family.queue_flags.contains(vk::QueueFlags::COMPUTE) {
            return Err(EngineError::InvalidArgument(
                "the queue family given to Lucid has no compute support".into(),
            ));
        }
        let info = DeviceInfo {
            name: props
                .device_name_as_c_str()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            kind: DeviceKind::Other,
            api_version: (
                vk::api_version_major(props.api_version),
                vk::api_version_minor(props.api_version),
                vk::api_version_patch(props.api_version),
            ),
            timestamp_period_ns: props.limits.timestamp_period,
            timestamps: family.timestamp_valid_bits > 0 && props.limits.timestamp_period > 0.0,
            subgroup_size: 32,
            max_shared_memory: props.limits.max_compute_shared_memory_size,
            shader_float16: false,
            tensor_cores: false,
            present: false,
            int64_atomics: existing.int64_atomics,
            pipeline_statistics: false,
        };
        Self::assemble(
            existing,
            info,
            None,
            vk::DebugUtilsMessengerEXT::null(),
            (ValidationLog::default(), Validation::Off),
            AssembleOptions {
                frames_in_flight: frames_in_flight.max(1),
                inject_device_lost_at_frame: None,
                memory_budget_mib: None,
            },
            false,
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn assemble(
        v: ExistingVulkan,
        info: DeviceInfo,
        debug_utils_instance: Option<ash::ext::debug_utils::Instance>,
        messenger: vk::DebugUtilsMessengerEXT,
        (validation, validation_level): (ValidationLog, Validation),
        options: AssembleOptions,
        owns_vulkan: bool,
    ) -> Result<Self> {
        let budget = MemoryBudget::query(&v.instance, v.physical_device, options.memory_budget_mib);
        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: v.instance.clone(),
            device: v.device.clone(),
            physical_device: v.physical_device,
            debug_settings: Default::default(),
            buffer_device_address: false,
            allocation_sizes: Default::default(),
        })
        .map_err(|e| EngineError::InvalidArgument(format!("creating the memory allocator: {e}")))?;
        let push_descriptor = ash::khr::push_descriptor::Device::new(&v.instance, &v.device);
        let executable_properties = info
            .pipeline_statistics
            .then(|| ash::khr::pipeline_executable_properties::Device::new(&v.instance, &v.device));
        let debug_utils = debug_utils_instance
            .as_ref()
            .map(|_| ash::ext::debug_utils::Device::new(&v.instance, &v.device));
        Ok(Self {
            shared: Arc::new(Shared {
                entry: v.entry,
                instance: v.instance,
                physical_device: v.physical_device,
                device: v.device,
                queue_family: v.queue_family,
                queue: Mutex::new(v.queue),
                allocator: ManuallyDrop::new(Mutex::new(allocator)),
                push_descriptor,
                executable_properties,
                debug_utils_instance,
                debug_utils,
                messenger,
                validation,
                info,
                memory: MemoryTracker::default(),
                frames_in_flight: options.frames_in_flight,
                device_loss: DeviceLoss::new(options.inject_device_lost_at_frame),
                budget,
                validation_level,
                owns_vulkan,
            }),
        })
    }

    /// The logical device.
    pub fn device(&self) -> &ash::Device {
        &self.shared.device
    }

    /// The instance.
    pub fn instance(&self) -> &ash::Instance {
        &self.shared.instance
    }

    /// The loader entry.
    pub fn entry(&self) -> &ash::Entry {
        &self.shared.entry
    }

    /// The physical device in use.
    pub fn physical_device(&self) -> vk::PhysicalDevice {
        self.shared.physical_device
    }

    /// The family of the compute (and present) queue.
    pub fn queue_family(&self) -> u32 {
        self.shared.queue_family
    }

    /// Facts about the device: name, timestamp period, subgroup size, ...
    pub fn info(&self) -> &DeviceInfo {
        &self.shared.info
    }

    /// How many frames the CPU may record ahead of the GPU.
    pub fn frames_in_flight(&self) -> usize {
        self.shared.frames_in_flight
    }

    /// The validation messages collected so far (tests fail on any).
    pub fn validation_log(&self) -> &ValidationLog {
        &self.shared.validation
    }

    /// The validation level in effect (Off when the layer is absent and was not required).
    pub fn validation(&self) -> Validation {
        self.shared.validation_level
    }

    /// Runs `f` with the queue locked (for submissions and presentation).
    pub fn with_queue<T>(&self, f: impl FnOnce(vk::Queue) -> T) -> T {
        let queue = self.lock_queue();
        f(*queue)
    }

    fn lock_queue(&self) -> MutexGuard<'_, vk::Queue> {
        self.shared
            .queue
            .lock()
            .unwrap_or_else(|poison| poison.into_inner())
    }

    /// Submits work to the queue. After a device loss (see [`Context::is_device_lost`]) it fails
    /// at once.
    pub fn submit(&self, submits: &[vk::SubmitInfo2<'_>], fence: vk::Fence) -> Result<()> {
        let loss = &self.shared.device_loss;
        if loss.is_lost() {
            return Err(loss.error("vkQueueSubmit2, after the loss"));
        }
        let queue = self.lock_queue();
        // SAFETY: the queue is locked; the submit infos reference live objects.
        unsafe { self.device().queue_submit2(*queue, submits, fence) }
            .vk("vkQueueSubmit2")
            .map_err(|e| loss.observe(e))
    }

    /// Submits a frame of the render graph: like [`Context::submit`], and where a fault is injected
    /// ([`ContextDesc::inject_device_lost_at_frame`]) the chosen frame reports device loss instead.
    pub(crate) fn submit_frame(&self, submits: &[vk::SubmitInfo2<'_>]) -> Result<()> {
        let loss = &self.shared.device_loss;
        if !loss.is_lost() && loss.frame_submitted() {
            return Err(loss.error("vkQueueSubmit2"));
        }
        self.submit(submits, vk::Fence::null())
    }

    /// The memory limits allocations are checked against.
    pub fn memory_budget(&self) -> MemoryBudget {
        self.shared.budget
    }

    /// Fails with [`EngineError::DoesNotFit`] when `bytes` more for `what` would not fit in the
    /// memory budget next to what Lucid holds now: to refuse work that cannot fit before doing
    /// it (e.g. building the BVH of a scene too big for the device).
    pub fn check_fits(&self, what: &str, bytes: u64) -> Result<()> {
        self.shared
            .budget
            .check(what, bytes, self.shared.memory.total_bytes(), false)
    }

    /// Whether the device was lost: a Vulkan call reported `VK_ERROR_DEVICE_LOST` (or a fault was
    /// injected). Nothing more runs on it; recreate the context.
    pub fn is_device_lost(&self) -> bool {
        self.shared.device_loss.is_lost()
    }

    /// Records `error` (marking the device lost when it says so) and returns it: also for errors
    /// of Vulkan calls made outside the engine on its device and queue (presenting to a window).
    pub fn observe(&self, error: EngineError) -> EngineError {
        self.shared.device_loss.observe(error)
    }

    /// The error of a call made after a device loss, `during` what.
    pub(crate) fn device_lost_error(&self, during: impl Into<String>) -> EngineError {
        self.shared.device_loss.error(during)
    }

    /// Waits until the device is idle.
    pub fn wait_idle(&self) -> Result<()> {
        let _queue = self.lock_queue();
        // SAFETY: the device is valid; holding the queue lock keeps submissions out.
        unsafe { self.device().device_wait_idle() }.vk("vkDeviceWaitIdle")
    }

    /// Gives a Vulkan object a debug name (seen in validation messages and GPU captures).
    pub fn set_name<H: vk::Handle>(&self, handle: H, name: &str) {
        if let Some(utils) = &self.shared.debug_utils {
            let name = CString::new(name.replace('\0', " ")).unwrap_or_default();
            let info = vk::DebugUtilsObjectNameInfoEXT::default()
                .object_handle(handle)
                .object_name(&name);
            let _loader = loader_lock::shared();
            // SAFETY: the handle belongs to this device. Naming is best-effort.
            let _ = unsafe { utils.set_debug_utils_object_name(&info) };
        }
    }

    /// Opens a debug label region in a command buffer.
    pub fn begin_label(&self, cmd: vk::CommandBuffer, name: &str) {
        if let Some(utils) = &self.shared.debug_utils {
            let name = CString::new(name.replace('\0', " ")).unwrap_or_default();
            let label = vk::DebugUtilsLabelEXT::default().label_name(&name);
            // SAFETY: cmd is in the recording state.
            unsafe { utils.cmd_begin_debug_utils_label(cmd, &label) };
        }
    }

    /// Closes the innermost debug label region.
    pub fn end_label(&self, cmd: vk::CommandBuffer) {
        if let Some(utils) = &self.shared.debug_utils {
            // SAFETY: cmd is recording and has an open label region.
            unsafe { utils.cmd_end_debug_utils_label(cmd) };
        }
    }

    /// Records commands with `record`, submits them and waits for completion (for uploads, readbacks
    /// and setup work outside the frame loop).
    pub fn submit_and_wait(
        &self,
        what: &str,
        record: impl FnOnce(vk::CommandBuffer),
    ) -> Result<()> {
        let device = self.device();
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(self.queue_family())
            .flags(vk::CommandPoolCreateFlags::TRANSIENT);
        // SAFETY: device is valid.
        let pool =
            unsafe { device.create_command_pool(&pool_info, None) }.vk("vkCreateCommandPool")?;
        let result = (|| {
            let alloc = vk::CommandBufferAllocateInfo::default()
                .command_pool(pool)
                .level(vk::CommandBufferLevel::PRIMARY)
                .command_buffer_count(1);
            // SAFETY: pool is valid.
            let cmd = unsafe { device.allocate_command_buffers(&alloc) }
                .vk("vkAllocateCommandBuffers")?[0];
            self.set_name(cmd, what);
            let begin = vk::CommandBufferBeginInfo::default()
                .flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
            // SAFETY: cmd was just allocated.
            unsafe { device.begin_command_buffer(cmd, &begin) }.vk("vkBeginCommandBuffer")?;
            self.begin_label(cmd, what);
            record(cmd);
            self.end_label(cmd);
            // SAFETY: cmd is recording.
            unsafe { device.end_command_buffer(cmd) }.vk("vkEndCommandBuffer")?;
            // SAFETY: device is valid.
            let fence = unsafe { device.create_fence(&vk::FenceCreateInfo::default(), None) }
                .vk("vkCreateFence")?;
            let cmds = [vk::CommandBufferSubmitInfo::default().command_buffer(cmd)];
            let submit = [vk::SubmitInfo2::default().command_buffer_infos(&cmds)];
            let limit = self.info().kind.wait_limit();
            let waited = self.submit(&submit, fence).and_then(|()| {
                // SAFETY: fence was submitted above.
                unsafe { device.wait_for_fences(&[fence], true, limit.as_nanos() as u64) }.map_err(
                    |e| match e {
                        vk::Result::TIMEOUT => EngineError::Timeout {
                            during: what.to_string(),
                            seconds: limit.as_secs(),
                        },
                        other => self.observe(crate::error::from_vk("vkWaitForFences", other)),
                    },
                )
            });
            // SAFETY: the fence is no longer in use (waited, or the submit failed).
            unsafe { device.destroy_fence(fence, None) };
            waited
        })();
        if result.is_err() {
            let _ = self.wait_idle();
        }
        // SAFETY: all command buffers from the pool have completed or were never submitted.
        unsafe { device.destroy_command_pool(pool, None) };
        result
    }
}

impl Drop for Shared {
    fn drop(&mut self) {
        // SAFETY: this is the last reference to the device; every object created from it has been
        // dropped (they hold this Arc). The allocator is dropped before the device is destroyed.
        unsafe {
            let _ = self.device.device_wait_idle();
            ManuallyDrop::drop(&mut self.allocator);
            if self.owns_vulkan {
                let _loader = loader_lock::exclusive();
                self.device.destroy_device(None);
                if let Some(utils) = &self.debug_utils_instance {
                    utils.destroy_debug_utils_messenger(self.messenger, None);
                }
                self.instance.destroy_instance(None);
            }
        }
    }
}
