//! The context with presentation support and the window's surface, which can be made anew when
//! the window system reports it lost.

use crate::vk_error;
use anyhow::Context as _;
use ash::vk;
use lucid_engine::{Context, ContextDesc};
use std::ffi::CStr;
use winit::raw_window_handle::{HasDisplayHandle, HasWindowHandle};
use winit::window::Window;

/// A window's Vulkan surface (destroyed on drop).
pub struct WindowSurface {
    loader: ash::khr::surface::Instance,
    raw: vk::SurfaceKHR,
    ctx: Context,
}

/// Creates a context (validation and device from the environment) that can present to `window`,
/// and the window's surface.
pub fn create_context(window: &Window) -> anyhow::Result<(Context, WindowSurface)> {
    let display = window.display_handle()?.as_raw();
    let extensions = ash_window::enumerate_required_extensions(display)
        .map_err(vk_error("vkEnumerateInstanceExtensionProperties"))
        .context("this window system has no Vulkan surface support")?;
    let desc = ContextDesc {
        app_name: "lucid sandbox".into(),
        instance_extensions: extensions
            .iter()
            // SAFETY: ash-window returns pointers to static NUL-terminated extension names.
            .map(|&name| unsafe { CStr::from_ptr(name) }.to_owned())
            .collect(),
        ..ContextDesc::from_env()
    };
    let (ctx, raw) = Context::with_surface(&desc, |entry, instance| {
        raw_surface(entry, instance, window)
    })?;
    let loader = ash::khr::surface::Instance::new(ctx.entry(), ctx.instance());
    Ok((ctx.clone(), WindowSurface { loader, raw, ctx }))
}

fn raw_surface(
    entry: &ash::Entry,
    instance: &ash::Instance,
    window: &Window,
) -> lucid_engine::Result<vk::SurfaceKHR> {
    let handles = window
        .display_handle()
        .and_then(|d| window.window_handle().map(|w| (d.as_raw(), w.as_raw())));
    let (display, handle) = handles.map_err(|e| {
        lucid_engine::EngineError::InvalidArgument(format!("the window has no handle: {e}"))
    })?;
    // SAFETY: the handles belong to a live window, which outlives the surface (the session drops
    // the surface before the window).
    unsafe { ash_window::create_surface(entry, instance, display, handle, None) }
        .map_err(vk_error("vkCreateSurfaceKHR"))
}

impl WindowSurface {
    /// The surface.
    pub fn raw(&self) -> vk::SurfaceKHR {
        self.raw
    }

    /// The surface extension's functions.
    pub fn loader(&self) -> &ash::khr::surface::Instance {
        &self.loader
    }

    /// Replaces a lost surface with a new one for `window` (the swapchain must be gone).
    pub fn recreate(&mut self, window: &Window) -> anyhow::Result<()> {
        let raw = raw_surface(self.ctx.entry(), self.ctx.instance(), window)?;
        // SAFETY: the old surface has no swapchain any more.
        unsafe { self.loader.destroy_surface(self.raw, None) };
        self.raw = raw;
        let family = self.ctx.queue_family();
        // SAFETY: the physical device and surface belong to this instance.
        let supported = unsafe {
            self.loader
                .get_physical_device_surface_support(self.ctx.physical_device(), family, raw)
        }
        .unwrap_or(false);
        anyhow::ensure!(
            supported,
            "the new window surface cannot be presented from queue family {family}"
        );
        Ok(())
    }
}

impl Drop for WindowSurface {
    fn drop(&mut self) {
        // SAFETY: the swapchain using it was destroyed first (it owns this surface).
        unsafe { self.loader.destroy_surface(self.raw, None) };
    }
}
