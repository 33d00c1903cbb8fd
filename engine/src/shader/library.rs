//! The shader library: reflection and compute pipelines created on first use, cached by shader and
//! specialization, with a Vulkan pipeline cache and hot replacement of a shader's SPIR-V.

use super::reflect::{reflect, spirv_words, DescriptorKind, Reflection};
use super::specialization::{map_entries, Specialization};
use super::statistics::{self, PipelineStatistic, PipelineStatistics};
use super::ShaderSource;
use crate::context::{Context, Shared};
use crate::error::{EngineError, Result, VkResultExt};
use ash::vk;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// A compute pipeline with its layout and the reflection it was built from.
pub struct ComputePipeline {
    shared: Arc<Shared>,
    /// The shader's name.
    pub name: String,
    /// The pipeline.
    pub pipeline: vk::Pipeline,
    /// Its layout (one push-descriptor set, plus push constants).
    pub layout: vk::PipelineLayout,
    set_layout: vk::DescriptorSetLayout,
    /// Bindings, push constants and specialization constants.
    pub reflection: Arc<Reflection>,
    /// The workgroup size after specialization.
    pub workgroup_size: [u32; 3],
    /// The driver's executable statistics (registers, instructions, ...); empty unless the context
    /// captures them ([`crate::context::DeviceInfo::pipeline_statistics`]).
    pub statistics: Vec<PipelineStatistic>,
}

impl Drop for ComputePipeline {
    fn drop(&mut self) {
        // SAFETY: frames that recorded this pipeline hold an Arc to it until they complete.
        unsafe {
            self.shared.device.destroy_pipeline(self.pipeline, None);
            self.shared
                .device
                .destroy_pipeline_layout(self.layout, None);
            self.shared
                .device
                .destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}

type PipelineKey = (String, Vec<(u32, u32)>);

/// Creates and caches compute pipelines.
pub struct ShaderLibrary {
    ctx: Context,
    cache: vk::PipelineCache,
    cache_path: Option<PathBuf>,
    sampler: vk::Sampler,
    replaced: Mutex<HashMap<String, Arc<Vec<u32>>>>,
    reflections: Mutex<HashMap<String, Arc<Reflection>>>,
    pipelines: Mutex<HashMap<PipelineKey, Arc<ComputePipeline>>>,
}

impl ShaderLibrary {
    /// Creates the library. When `cache_path` names a file, the Vulkan pipeline cache is loaded from it
    /// (if present and valid) and saved back by [`ShaderLibrary::save_cache`].
    pub fn new(ctx: &Context, cache_path: Option<&Path>) -> Result<Self> {
        let initial = cache_path
            .and_then(|p| std::fs::read(p).ok())
            .unwrap_or_default();
        let info = vk::PipelineCacheCreateInfo::default().initial_data(&initial);
        let device = ctx.device();
        // SAFETY: device is valid; a cache blob from another driver is rejected by the driver itself.
        let cache = unsafe { device.create_pipeline_cache(&info, None) }
            .or_else(|_| {
                // SAFETY: as above, with no initial data.
                unsafe {
                    device.create_pipeline_cache(&vk::PipelineCacheCreateInfo::default(), None)
                }
            })
            .vk("vkCreatePipelineCache")?;
        let sampler_info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .address_mode_u(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_w(vk::SamplerAddressMode::CLAMP_TO_EDGE);
        // SAFETY: device is valid.
        let sampler =
            unsafe { device.create_sampler(&sampler_info, None) }.vk("vkCreateSampler")?;
        ctx.set_name(sampler, "linear clamp sampler");
        Ok(Self {
            ctx: ctx.clone(),
            cache,
            cache_path: cache_path.map(Path::to_path_buf),
            sampler,
            replaced: Mutex::default(),
            reflections: Mutex::default(),
            pipelines: Mutex::default(),
        })
    }

    fn words(&self, shader: &ShaderSource) -> Result<Arc<Vec<u32>>> {
        if let Some(words) = lock(&self.replaced).get(shader.name) {
            return Ok(words.clone());
        }
        spirv_words(shader.spirv)
            .map(Arc::new)
            .map_err(|message| shader_error(shader.name, message))
    }

    /// The shader's reflected interface.
    pub fn reflection(&self, shader: &ShaderSource) -> Result<Arc<Reflection>> {
        if let Some(r) = lock(&self.reflections).get(shader.name) {
            return Ok(r.clone());
        }
        let words = self.words(shader)?;
        let reflection = Arc::new(reflect(&words).map_err(|m| shader_error(shader.name, m))?);
        lock(&self.reflections).insert(shader.name.to_string(), reflection.clone());
        Ok(reflection)
    }

    /// The pipeline for `shader` with `spec` applied, created on first use.
    pub fn pipeline(
        &self,
        shader: &ShaderSource,
        spec: &Specialization,
    ) -> Result<Arc<ComputePipeline>> {
        let reflection = self.reflection(shader)?;
        let resolved = spec
            .resolve(&reflection)
            .map_err(|m| shader_error(shader.name, m))?;
        let key = (shader.name.to_string(), resolved);
        if let Some(p) = lock(&self.pipelines).get(&key) {
            return Ok(p.clone());
        }
        let words = self.words(shader)?;
        let pipeline = Arc::new(self.create(shader.name, &words, reflection, &key.1)?);
        lock(&self.pipelines).insert(key, pipeline.clone());
        Ok(pipeline)
    }

    /// Replaces a shader's SPIR-V at run time (hot reload). The new code is reflected first: on an
    /// error nothing changes and the previous pipelines stay in use.
    pub fn replace_spirv(&self, name: &str, spirv: &[u8]) -> Result<()> {
        let words = spirv_words(spirv).map_err(|m| shader_error(name, m))?;
        let reflection = reflect(&words).map_err(|m| shader_error(name, m))?;
        lock(&self.replaced).insert(name.to_string(), Arc::new(words));
        lock(&self.reflections).insert(name.to_string(), Arc::new(reflection));
        lock(&self.pipelines).retain(|(n, _), _| n != name);
        Ok(())
    }

    /// Writes the Vulkan pipeline cache to the file given at creation (no-op without one).
    pub fn save_cache(&self) -> Result<()> {
        let Some(path) = &self.cache_path else {
            return Ok(());
        };
        // SAFETY: the cache is valid.
        let data = unsafe { self.ctx.device().get_pipeline_cache_data(self.cache) }
            .vk("vkGetPipelineCacheData")?;
        if let Some(dir) = path.parent() {
            let _ = std::fs::create_dir_all(dir);
        }
        std::fs::write(path, data).map_err(|e| {
            EngineError::InvalidArgument(format!("writing pipeline cache {}: {e}", path.display()))
        })
    }

    /// The number of pipelines created so far.
    pub fn pipeline_count(&self) -> usize {
        lock(&self.pipelines).len()
    }

    /// The statistics of every pipeline created so far (and not replaced by hot reload), sorted by
    /// name and specialization. `None` when the context does not capture statistics.
    pub fn pipeline_statistics(&self) -> Option<Vec<PipelineStatistics>> {
        if !self.ctx.info().pipeline_statistics {
            return None;
        }
        let mut all: Vec<PipelineStatistics> = lock(&self.pipelines)
            .iter()
            .map(|((name, specialization), pipeline)| PipelineStatistics {
                name: name.clone(),
                specialization: specialization.clone(),
                statistics: pipeline.statistics.clone(),
            })
            .collect();
        all.sort_by(|a, b| (&a.name, &a.specialization).cmp(&(&b.name, &b.specialization)));
        Some(all)
    }

    fn create(
        &self,
        name: &str,
        words: &[u32],
        reflection: Arc<Reflection>,
        resolved: &[(u32, u32)],
    ) -> Result<ComputePipeline> {
        let device = self.ctx.device();
        let samplers = [self.sampler];
        let mut layout_bindings = Vec::new();
        for b in &reflection.bindings {
            if b.set != 0 {
                return Err(shader_error(
                    name,
                    format!(
                        "binding {} is in set {}; Lucid binds set 0 only",
                        b.name, b.set
                    ),
                ));
            }
            if b.count != 1 {
                return Err(shader_error(
                    name,
                    format!(
                        "binding {} is an array; bind arrays as buffers instead",
                        b.name
                    ),
                ));
            }
            let (ty, immutable) = match b.kind {
                DescriptorKind::StorageImage => (vk::DescriptorType::STORAGE_IMAGE, false),
                DescriptorKind::SampledImage => (vk::DescriptorType::COMBINED_IMAGE_SAMPLER, true),
                DescriptorKind::StorageBuffer => (vk::DescriptorType::STORAGE_BUFFER, false),
                DescriptorKind::UniformBuffer => (vk::DescriptorType::UNIFORM_BUFFER, false),
            };
            let mut binding = vk::DescriptorSetLayoutBinding::default()
                .binding(b.binding)
                .descriptor_type(ty)
                .descriptor_count(1)
                .stage_flags(vk::ShaderStageFlags::COMPUTE);
            if immutable {
                binding = binding.immutable_samplers(&samplers);
            }
            layout_bindings.push(binding);
        }
        let set_info = vk::DescriptorSetLayoutCreateInfo::default()
            .flags(vk::DescriptorSetLayoutCreateFlags::PUSH_DESCRIPTOR_KHR)
            .bindings(&layout_bindings);
        // SAFETY: device valid; bindings reference `samplers` which outlives the call.
        let set_layout = unsafe { device.create_descriptor_set_layout(&set_info, None) }
            .vk("vkCreateDescriptorSetLayout")?;
        let ranges = [vk::PushConstantRange::default()
            .stage_flags(vk::ShaderStageFlags::COMPUTE)
            .size(reflection.push_constant_size)];
        let set_layouts = [set_layout];
        let mut layout_info = vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts);
        if reflection.push_constant_size > 0 {
            layout_info = layout_info.push_constant_ranges(&ranges);
        }
        let destroy_set_layout = || {
            // SAFETY: the set layout is not used by any pipeline.
            unsafe { device.destroy_descriptor_set_layout(set_layout, None) }
        };
        // SAFETY: device valid.
        let layout = match unsafe { device.create_pipeline_layout(&layout_info, None) } {
            Ok(l) => l,
            Err(e) => {
                destroy_set_layout();
                return Err(crate::error::from_vk("vkCreatePipelineLayout", e));
            }
        };
        let module_info = vk::ShaderModuleCreateInfo::default().code(words);
        // SAFETY: words is reflected SPIR-V.
        let module = match unsafe { device.create_shader_module(&module_info, None) } {
            Ok(m) => m,
            Err(e) => {
                // SAFETY: unused objects.
                unsafe { device.destroy_pipeline_layout(layout, None) };
                destroy_set_layout();
                return Err(crate::error::from_vk("vkCreateShaderModule", e));
            }
        };
        let (entries, data) = map_entries(resolved);
        let spec_info = vk::SpecializationInfo::default()
            .map_entries(&entries)
            .data(&data);
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module)
            .name(c"main")
            .specialization_info(&spec_info);
        let statistics_loader = self.ctx.shared.executable_properties.as_ref();
        let flags = if statistics_loader.is_some() {
            vk::PipelineCreateFlags::CAPTURE_STATISTICS_KHR
        } else {
            vk::PipelineCreateFlags::empty()
        };
        let info = [vk::ComputePipelineCreateInfo::default()
            .flags(flags)
            .stage(stage)
            .layout(layout)];
        // SAFETY: all referenced objects are alive.
        let created = unsafe { device.create_compute_pipelines(self.cache, &info, None) };
        // SAFETY: the module is no longer needed once the pipeline exists (or failed).
        unsafe { device.destroy_shader_module(module, None) };
        let pipeline = match created {
            Ok(p) => p[0],
            Err((_, e)) => {
                // SAFETY: unused objects.
                unsafe { device.destroy_pipeline_layout(layout, None) };
                destroy_set_layout();
                return Err(crate::error::from_vk("vkCreateComputePipelines", e));
            }
        };
        self.ctx.set_name(pipeline, name);
        let statistics = match statistics_loader.map(|l| statistics::capture(l, pipeline)) {
            Some(Ok(captured)) => captured,
            Some(Err(e)) => {
                tracing::warn!("pipeline statistics of {name}: {e}");
                Vec::new()
            }
            None => Vec::new(),
        };
        let workgroup_size = Specialization::workgroup_size(&reflection, resolved);
        Ok(ComputePipeline {
            shared: self.ctx.shared.clone(),
            name: name.to_string(),
            pipeline,
            layout,
            set_layout,
            reflection,
            workgroup_size,
            statistics,
        })
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

fn shader_error(name: &str, message: String) -> EngineError {
    EngineError::Shader {
        shader: name.to_string(),
        message,
    }
}

impl Drop for ShaderLibrary {
    fn drop(&mut self) {
        if let Err(e) = self.save_cache() {
            tracing::warn!("{e}");
        }
        lock(&self.pipelines).clear();
        // SAFETY: pipelines still referenced by in-flight frames keep their own objects; the cache
        // and sampler are only used at creation and by descriptor set layouts destroyed above or
        // kept alive by those frames' Arcs — callers wait for frames before dropping the library.
        unsafe {
            self.ctx.device().destroy_pipeline_cache(self.cache, None);
            self.ctx.device().destroy_sampler(self.sampler, None);
        }
    }
}
