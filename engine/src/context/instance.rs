//! Instance creation: the loader, the validation layer and its messenger.

use super::debug::{messenger_info, ValidationLog};
use super::options::{ContextDesc, Validation};
use crate::error::{EngineError, Result, VkResultExt};
use ash::vk;
use std::ffi::{CStr, CString};

const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";

/// A created instance with its optional debug messenger.
pub(crate) struct CreatedInstance {
    pub entry: ash::Entry,
    pub instance: ash::Instance,
    pub debug_utils: Option<ash::ext::debug_utils::Instance>,
    pub messenger: vk::DebugUtilsMessengerEXT,
    pub validation: Validation,
}

/// Loads Vulkan and creates an instance as `desc` asks; collects layer messages into `log`.
pub(crate) fn create_instance(desc: &ContextDesc, log: &ValidationLog) -> Result<CreatedInstance> {
    // SAFETY: loading the system loader library; no Vulkan call has been made yet.
    let entry =
        unsafe { ash::Entry::load() }.map_err(|e| EngineError::NoVulkanLoader(e.to_string()))?;
    // SAFETY: entry is a loaded Vulkan entry.
    let layers = unsafe { entry.enumerate_instance_layer_properties() }
        .vk("vkEnumerateInstanceLayerProperties")?;
    let has_layer = layers
        .iter()
        .any(|l| l.layer_name_as_c_str() == Ok(VALIDATION_LAYER));
    let mut validation = desc.validation;
    if validation != Validation::Off && !has_layer {
        if desc.require_validation {
            return Err(EngineError::MissingFeature {
                device: "the Vulkan installation".into(),
                missing: "VK_LAYER_KHRONOS_validation (install it: apt-get install vulkan-validationlayers)".into(),
            });
        }
        tracing::warn!("validation requested but VK_LAYER_KHRONOS_validation is not installed; continuing without it");
        validation = Validation::Off;
    }
    // SAFETY: entry is loaded.
    let available_exts = unsafe { entry.enumerate_instance_extension_properties(None) }
        .vk("vkEnumerateInstanceExtensionProperties")?;
    let has_ext = |name: &CStr| {
        available_exts
            .iter()
            .any(|e| e.extension_name_as_c_str() == Ok(name))
    };
    let debug_utils_available = has_ext(ash::ext::debug_utils::NAME);
    let mut extensions: Vec<*const std::ffi::c_char> = Vec::new();
    if debug_utils_available {
        extensions.push(ash::ext::debug_utils::NAME.as_ptr());
    }
    for ext in &desc.instance_extensions {
        if !has_ext(ext) {
            return Err(EngineError::MissingFeature {
                device: "the Vulkan instance".into(),
                missing: format!("instance extension {}", ext.to_string_lossy()),
            });
        }
        extensions.push(ext.as_ptr());
    }
    let mut layer_names = Vec::new();
    if validation != Validation::Off {
        layer_names.push(VALIDATION_LAYER.as_ptr());
    }
    if validation == Validation::Sync {
        // The layer provides this extension; it makes the layer read the enabled features below.
        // SAFETY: entry is loaded; the layer name is a valid C string.
        let layer_exts =
            unsafe { entry.enumerate_instance_extension_properties(Some(VALIDATION_LAYER)) }
                .vk("vkEnumerateInstanceExtensionProperties")?;
        if layer_exts
            .iter()
            .any(|e| e.extension_name_as_c_str() == Ok(ash::ext::validation_features::NAME))
        {
            extensions.push(ash::ext::validation_features::NAME.as_ptr());
        }
    }
    let app_name = CString::new(desc.app_name.replace('\0', " ")).unwrap_or_default();
    let app_info = vk::ApplicationInfo::default()
        .application_name(&app_name)
        .engine_name(c"lucid")
        .api_version(vk::API_VERSION_1_3);
    let sync_features = [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
    let mut validation_features =
        vk::ValidationFeaturesEXT::default().enabled_validation_features(&sync_features);
    let mut messenger_create = messenger_info(log);
    let mut info = vk::InstanceCreateInfo::default()
        .application_info(&app_info)
        .enabled_layer_names(&layer_names)
        .enabled_extension_names(&extensions);
    if validation != Validation::Off && debug_utils_available {
        info = info.push_next(&mut messenger_create);
    }
    if validation == Validation::Sync {
        info = info.push_next(&mut validation_features);
    }
    // SAFETY: every pointer in `info` refers to locals that outlive the call.
    let instance = unsafe { entry.create_instance(&info, None) }.vk("vkCreateInstance")?;
    let debug_utils =
        debug_utils_available.then(|| ash::ext::debug_utils::Instance::new(&entry, &instance));
    let messenger = match (&debug_utils, validation) {
        (Some(utils), v) if v != Validation::Off => {
            // SAFETY: the instance is valid and the callback data outlives the messenger (held by Context).
            unsafe { utils.create_debug_utils_messenger(&messenger_info(log), None) }
                .vk("vkCreateDebugUtilsMessengerEXT")?
        }
        _ => vk::DebugUtilsMessengerEXT::null(),
    };
    Ok(CreatedInstance {
        entry,
        instance,
        debug_utils,
        messenger,
        validation,
    })
}
