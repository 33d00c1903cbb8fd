//! Logical-device creation: choose the physical device, its compute queue, and enable what Lucid uses.

use super::cooperative_matrix::supports_tensor_cores;
use super::select::{select_device, DeviceCandidate, DeviceKind};
use crate::error::{EngineError, Result, VkResultExt};
use ash::vk;

/// What the engine knows about the device it runs on.
#[derive(Clone, Debug)]
pub struct DeviceInfo {
    /// The driver's device name.
    pub name: String,
    /// Discrete GPU, CPU implementation, ...
    pub kind: DeviceKind,
    /// The Vulkan version the device supports.
    pub api_version: (u32, u32, u32),
    /// Nanoseconds per timestamp tick.
    pub timestamp_period_ns: f32,
    /// Whether the compute queue supports timestamp queries.
    pub timestamps: bool,
    /// The subgroup (warp) size.
    pub subgroup_size: u32,
    /// Shared memory per workgroup, in bytes.
    pub max_shared_memory: u32,
    /// Whether 16-bit floats are enabled in shaders.
    pub shader_float16: bool,
    /// Whether NVIDIA cooperative matrices (fp16 16x16x16 products on 32-wide subgroups) and the
    /// Vulkan memory model are enabled: the tensor-core kernels run.
    pub tensor_cores: bool,
    /// Whether a present-capable queue is in use (a window was given).
    pub present: bool,
    /// Whether shaders may use 64-bit integers and `atomicAdd` them in
    /// buffers (`shaderInt64`, `shaderBufferInt64Atomics`): light tracing
    /// splats in 64-bit fixed point with them, so that its sums do not depend
    /// on the order threads add in.
    pub int64_atomics: bool,
    /// Whether compute pipelines capture their executable statistics
    /// (`VK_KHR_pipeline_executable_properties`; requested with
    /// [`super::ContextDesc::pipeline_statistics`]).
    pub pipeline_statistics: bool,
}

/// The chosen physical device, its queue family and the created logical device.
pub(crate) struct CreatedDevice {
    pub physical_device: vk::PhysicalDevice,
    pub device: ash::Device,
    pub queue_family: u32,
    pub queue: vk::Queue,
    pub info: DeviceInfo,
}

/// Returns the queue family with compute (and present support, when `present` says so), if any.
fn compute_family(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    present: &dyn Fn(vk::PhysicalDevice, u32) -> bool,
) -> Option<(u32, bool)> {
    // SAFETY: physical comes from this instance.
    let families = unsafe { instance.get_physical_device_queue_family_properties(physical) };
    families
        .iter()
        .enumerate()
        .filter(|(i, f)| {
            f.queue_flags.contains(vk::QueueFlags::COMPUTE) && present(physical, *i as u32)
        })
        .map(|(i, f)| (i as u32, f.timestamp_valid_bits > 0))
        .next()
}

fn kind_of(t: vk::PhysicalDeviceType) -> DeviceKind {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => DeviceKind::Discrete,
        vk::PhysicalDeviceType::INTEGRATED_GPU => DeviceKind::Integrated,
        vk::PhysicalDeviceType::VIRTUAL_GPU => DeviceKind::Virtual,
        vk::PhysicalDeviceType::CPU => DeviceKind::Cpu,
        _ => DeviceKind::Other,
    }
}

fn device_extensions(instance: &ash::Instance, physical: vk::PhysicalDevice) -> Vec<String> {
    // SAFETY: physical comes from this instance.
    unsafe { instance.enumerate_device_extension_properties(physical) }
        .unwrap_or_default()
        .iter()
        .filter_map(|e| e.extension_name_as_c_str().ok())
        .map(|n| n.to_string_lossy().into_owned())
        .collect()
}

/// Why `physical` cannot run Lucid, or `None` when it can.
fn unusable_reason(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    props: &vk::PhysicalDeviceProperties,
    present: &dyn Fn(vk::PhysicalDevice, u32) -> bool,
    need_swapchain: bool,
) -> Option<String> {
    if props.api_version < vk::API_VERSION_1_3 {
        return Some(format!(
            "Vulkan {}.{} < 1.3",
            vk::api_version_major(props.api_version),
            vk::api_version_minor(props.api_version)
        ));
    }
    if compute_family(instance, physical, present).is_none() {
        return Some("no compute queue that can present".into());
    }
    let exts = device_extensions(instance, physical);
    let has = |n: &std::ffi::CStr| exts.iter().any(|e| e.as_bytes() == n.to_bytes());
    if !has(ash::khr::push_descriptor::NAME) {
        return Some("no VK_KHR_push_descriptor".into());
    }
    if need_swapchain && !has(ash::khr::swapchain::NAME) {
        return Some("no VK_KHR_swapchain".into());
    }
    let mut f12 = vk::PhysicalDeviceVulkan12Features::default();
    let mut f13 = vk::PhysicalDeviceVulkan13Features::default();
    let mut features = vk::PhysicalDeviceFeatures2::default()
        .push_next(&mut f12)
        .push_next(&mut f13);
    // SAFETY: physical comes from this instance; the chain points at locals.
    unsafe { instance.get_physical_device_features2(physical, &mut features) };
    if f12.timeline_semaphore == vk::FALSE {
        return Some("no timeline semaphores".into());
    }
    if f13.synchronization2 == vk::FALSE {
        return Some("no synchronization2".into());
    }
    None
}

/// Whether `physical` lists `VK_KHR_pipeline_executable_properties` and its `pipelineExecutableInfo`
/// feature (`extensions` are the device's extension names).
fn supports_pipeline_statistics(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    extensions: &[String],
) -> bool {
    let name = ash::khr::pipeline_executable_properties::NAME.to_bytes();
    if !extensions.iter().any(|e| e.as_bytes() == name) {
        return false;
    }
    let mut supported = vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR::default();
    let mut query = vk::PhysicalDeviceFeatures2::default().push_next(&mut supported);
    // SAFETY: physical comes from this instance; the chain points at locals.
    unsafe { instance.get_physical_device_features2(physical, &mut query) };
    supported.pipeline_executable_info == vk::TRUE
}

/// Picks a physical device (`requested` is a name substring) and creates the logical device with one
/// compute queue. `present` says whether a queue family can present to the window's surface;
/// `want_statistics` enables pipeline statistics capture where the device supports it.
pub(crate) fn create_device(
    entry: &ash::Entry,
    instance: &ash::Instance,
    requested: Option<&str>,
    present: &dyn Fn(vk::PhysicalDevice, u32) -> bool,
    need_swapchain: bool,
    want_statistics: bool,
) -> Result<CreatedDevice> {
    // SAFETY: instance is valid.
    let physicals =
        unsafe { instance.enumerate_physical_devices() }.vk("vkEnumeratePhysicalDevices")?;
    let mut candidates = Vec::new();
    for &physical in &physicals {
        // SAFETY: physical comes from this instance.
        let props = unsafe { instance.get_physical_device_properties(physical) };
        candidates.push(DeviceCandidate {
            name: props
                .device_name_as_c_str()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|_| "<unnamed>".into()),
            kind: kind_of(props.device_type),
            unusable: unusable_reason(instance, physical, &props, present, need_swapchain),
        });
    }
    let index = select_device(&candidates, requested)?;
    let physical = physicals[index];
    let (queue_family, queue_timestamps) =
        compute_family(instance, physical, present).ok_or_else(|| {
            EngineError::NoSuitableDevice {
                reason: "the chosen device lost its compute queue".into(),
                available: vec![candidates[index].name.clone()],
            }
        })?;

    let mut supported12 = vk::PhysicalDeviceVulkan12Features::default();
    let mut supported_base = vk::PhysicalDeviceFeatures2::default().push_next(&mut supported12);
    // SAFETY: physical comes from this instance.
    unsafe { instance.get_physical_device_features2(physical, &mut supported_base) };
    let base_supported = supported_base.features;
    let shader_float16 = supported12.shader_float16 == vk::TRUE;
    let int64_atomics = base_supported.shader_int64 == vk::TRUE
        && supported12.shader_buffer_int64_atomics == vk::TRUE;

    let available_extensions = device_extensions(instance, physical);
    let tensor_cores = supports_tensor_cores(entry, instance, physical, &available_extensions);
    let mut f12 = vk::PhysicalDeviceVulkan12Features::default()
        .timeline_semaphore(true)
        .vulkan_memory_model(tensor_cores)
        .vulkan_memory_model_device_scope(tensor_cores)
        .scalar_block_layout(supported12.scalar_block_layout == vk::TRUE)
        .shader_float16(shader_float16)
        .shader_buffer_int64_atomics(int64_atomics)
        .host_query_reset(supported12.host_query_reset == vk::TRUE);
    let mut f13 = vk::PhysicalDeviceVulkan13Features::default()
        .synchronization2(true)
        .dynamic_rendering(true);
    let base = vk::PhysicalDeviceFeatures::default()
        .shader_int64(base_supported.shader_int64 == vk::TRUE)
        .shader_storage_image_write_without_format(
            base_supported.shader_storage_image_write_without_format == vk::TRUE,
        )
        .shader_storage_image_read_without_format(
            base_supported.shader_storage_image_read_without_format == vk::TRUE,
        );
    let mut features = vk::PhysicalDeviceFeatures2::default()
        .features(base)
        .push_next(&mut f12)
        .push_next(&mut f13);
    let pipeline_statistics =
        want_statistics && supports_pipeline_statistics(instance, physical, &available_extensions);
    if want_statistics && !pipeline_statistics {
        tracing::warn!(
            "pipeline statistics were requested but {} lacks VK_KHR_pipeline_executable_properties \
             (pipelineExecutableInfo): none are captured",
            candidates[index].name
        );
    }
    let mut executable_info = vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR::default()
        .pipeline_executable_info(true);
    if pipeline_statistics {
        features = features.push_next(&mut executable_info);
    }
    let mut cooperative_matrix =
        vk::PhysicalDeviceCooperativeMatrixFeaturesNV::default().cooperative_matrix(true);
    if tensor_cores {
        features = features.push_next(&mut cooperative_matrix);
    }
    let mut extensions = vec![ash::khr::push_descriptor::NAME.as_ptr()];
    if tensor_cores {
        extensions.push(ash::nv::cooperative_matrix::NAME.as_ptr());
    }
    if pipeline_statistics {
        extensions.push(ash::khr::pipeline_executable_properties::NAME.as_ptr());
    }
    if need_swapchain {
        extensions.push(ash::khr::swapchain::NAME.as_ptr());
    }
    let priorities = [1.0f32];
    let queue_infos = [vk::DeviceQueueCreateInfo::default()
        .queue_family_index(queue_family)
        .queue_priorities(&priorities)];
    let info = vk::DeviceCreateInfo::default()
        .queue_create_infos(&queue_infos)
        .enabled_extension_names(&extensions)
        .push_next(&mut features);
    // SAFETY: all pointers in `info` refer to locals that outlive the call.
    let device = unsafe { instance.create_device(physical, &info, None) }.vk("vkCreateDevice")?;
    // SAFETY: the queue family and index were requested at device creation.
    let queue = unsafe { device.get_device_queue(queue_family, 0) };

    let mut subgroup = vk::PhysicalDeviceSubgroupProperties::default();
    let mut props2 = vk::PhysicalDeviceProperties2::default().push_next(&mut subgroup);
    // SAFETY: physical comes from this instance.
    unsafe { instance.get_physical_device_properties2(physical, &mut props2) };
    let props = props2.properties;
    let info = DeviceInfo {
        name: candidates[index].name.clone(),
        kind: candidates[index].kind,
        api_version: (
            vk::api_version_major(props.api_version),
            vk::api_version_minor(props.api_version),
            vk::api_version_patch(props.api_version),
        ),
        timestamp_period_ns: props.limits.timestamp_period,
        timestamps: queue_timestamps && props.limits.timestamp_period > 0.0,
        subgroup_size: subgroup.subgroup_size,
        max_shared_memory: props.limits.max_compute_shared_memory_size,
        shader_float16,
        tensor_cores,
        present: need_swapchain,
        int64_atomics,
        pipeline_statistics,
    };
    tracing::info!(
        "Vulkan device: {} (Vulkan {}.{}.{})",
        info.name,
        info.api_version.0,
        info.api_version.1,
        info.api_version.2
    );
    Ok(CreatedDevice {
        physical_device: physical,
        device,
        queue_family,
        queue,
        info,
    })
}
