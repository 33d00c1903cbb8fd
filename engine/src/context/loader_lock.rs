//! One process-wide lock around the Vulkan loader's list of logical devices.
//!
//! The loader adds a device to its per-instance list in `vkCreateDevice` and frees it in
//! `vkDestroyDevice` without a lock, while other threads walk every instance's list in
//! `vkGetDeviceProcAddr` and in debug-utils object naming (KhronosGroup/Vulkan-Loader#2018,
//! present in the Debian loader 1.3.239 and in 1.4.341). Contexts created and dropped on several
//! threads of one process (the test harness, an application with a context per window) then read
//! freed memory and corrupt the heap. Creating and destroying instances and devices (and loading a
//! device's functions) take this lock exclusively; naming objects takes it shared.

use std::sync::{RwLock, RwLockReadGuard, RwLockWriteGuard};

static DEVICE_LIST: RwLock<()> = RwLock::new(());

/// Held while instances and devices are created or destroyed.
pub(crate) fn exclusive() -> RwLockWriteGuard<'static, ()> {
    DEVICE_LIST
        .write()
        .unwrap_or_else(|poison| poison.into_inner())
}

/// Held while a call walks the loader's device lists (debug-utils object naming).
pub(crate) fn shared() -> RwLockReadGuard<'static, ()> {
    DEVICE_LIST
        .read()
        .unwrap_or_else(|poison| poison.into_inner())
}
