//! Keeps the Vulkan loader and the drivers it loads in memory for the rest of the process.
//!
//! The loader opens each driver's library when an instance is created and closes it when the
//! instance is destroyed, so a process whose last context goes unloads its drivers, and loads
//! them again for its next context. NVIDIA's driver (580, on an H200) leaves a thread-exit hook in
//! a library it pulls in (`libEGL.so.1`) for each thread that used it. A thread that ends after
//! that library was unloaded, or unloaded and loaded again, runs a stale hook: under gdb every
//! crash was in thread exit: at an address in `libEGL.so.1`, in no library, or in `free`. The test
//! harness, whose threads end after each test, crashed this way, as would an application that
//! creates contexts on worker threads (session 49: `traversal_gpu` segfaulted in 10 of 12 runs;
//! in none of 12 with the driver's library preloaded, none with every test on the main thread, and
//! none of 18 with this module). One instance without layers or extensions, created before the
//! first context and never destroyed, holds every driver library for the life of the process.

use ash::vk;
use std::sync::OnceLock;

/// The loader and the instance that pin the drivers; `None` where no instance could be created
/// (the context's own creation then reports why).
static PINNED: OnceLock<Option<(ash::Entry, ash::Instance)>> = OnceLock::new();

/// Creates the pinning instance once per process; later calls return at once. Must be called with
/// the loader lock held exclusively, as every instance creation is.
pub(crate) fn pin_drivers() {
    PINNED.get_or_init(|| {
        // SAFETY: loading the system loader library, which stays loaded: the entry is never dropped.
        let entry = unsafe { ash::Entry::load() }.ok()?;
        let app_info = vk::ApplicationInfo::default()
            .engine_name(c"lucid driver residency")
            .api_version(vk::API_VERSION_1_0);
        let info = vk::InstanceCreateInfo::default().application_info(&app_info);
        // SAFETY: `info` points at locals that outlive the call; the instance is never destroyed.
        match unsafe { entry.create_instance(&info, None) } {
            Ok(instance) => Some((entry, instance)),
            Err(e) => {
                tracing::debug!("no instance to keep the Vulkan drivers loaded: {e}");
                None
            }
        }
    });
}
