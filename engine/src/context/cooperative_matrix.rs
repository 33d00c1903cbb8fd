//! NVIDIA cooperative matrices (`VK_NV_cooperative_matrix`): whether a device can run the tensor-core
//! kernels (the learned denoiser's convolutions), which multiply 16x16 half-precision matrices and
//! sum in single precision, one product per 32-wide subgroup, under the Vulkan memory model.

use ash::vk;

/// The one matrix shape the tensor-core kernels use: `M = N = K = 16`, fp16 operands, fp32 sums.
fn is_f16_16x16x16(p: &vk::CooperativeMatrixPropertiesNV) -> bool {
    p.m_size == 16
        && p.n_size == 16
        && p.k_size == 16
        && p.a_type == vk::ComponentTypeNV::FLOAT16
        && p.b_type == vk::ComponentTypeNV::FLOAT16
        && p.c_type == vk::ComponentTypeNV::FLOAT32
        && p.d_type == vk::ComponentTypeNV::FLOAT32
        && p.scope == vk::ScopeNV::SUBGROUP
}

/// Whether `physical` supports what the tensor-core kernels need: the extension (listed in
/// `extensions`) and its `cooperativeMatrix` feature, `shaderFloat16`, `vulkanMemoryModel` with
/// `vulkanMemoryModelDeviceScope` (with the memory model on, every shader's device-scope atomics,
/// e.g. BDPT's, need the latter), 32-wide subgroups and the fp16 16x16x16 shape. When it does,
/// device creation enables them.
pub(crate) fn supports_tensor_cores(
    entry: &ash::Entry,
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    extensions: &[String],
) -> bool {
    let name = ash::nv::cooperative_matrix::NAME.to_bytes();
    if !extensions.iter().any(|e| e.as_bytes() == name) {
        return false;
    }
    let mut cooperative = vk::PhysicalDeviceCooperativeMatrixFeaturesNV::default();
    let mut f12 = vk::PhysicalDeviceVulkan12Features::default();
    let mut features = vk::PhysicalDeviceFeatures2::default()
        .push_next(&mut cooperative)
        .push_next(&mut f12);
    // SAFETY: physical comes from this instance; the chain points at locals.
    unsafe { instance.get_physical_device_features2(physical, &mut features) };
    if cooperative.cooperative_matrix == vk::FALSE
        || f12.shader_float16 == vk::FALSE
        || f12.vulkan_memory_model == vk::FALSE
        || f12.vulkan_memory_model_device_scope == vk::FALSE
    {
        return false;
    }
    let mut subgroup = vk::PhysicalDeviceSubgroupProperties::default();
    let mut props = vk::PhysicalDeviceProperties2::default().push_next(&mut subgroup);
    // SAFETY: physical comes from this instance; the chain points at locals.
    unsafe { instance.get_physical_device_properties2(physical, &mut props) };
    if subgroup.subgroup_size != 32
        || !subgroup
            .supported_stages
            .contains(vk::ShaderStageFlags::COMPUTE)
    {
        return false;
    }
    let nv = ash::nv::cooperative_matrix::Instance::new(entry, instance);
    let query = nv.fp().get_physical_device_cooperative_matrix_properties_nv;
    let mut count = 0u32;
    // SAFETY: a count query with a null array, on a device of this instance.
    if unsafe { query(physical, &mut count, std::ptr::null_mut()) } != vk::Result::SUCCESS {
        return false;
    }
    let mut shapes = vec![vk::CooperativeMatrixPropertiesNV::default(); count as usize];
    // SAFETY: `shapes` holds `count` initialised structures for the driver to fill.
    let result = unsafe { query(physical, &mut count, shapes.as_mut_ptr()) };
    result == vk::Result::SUCCESS && shapes[..count as usize].iter().any(is_f16_16x16x16)
}
