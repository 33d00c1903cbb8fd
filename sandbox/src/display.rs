//! Whether there is a display to open a window on.

/// The one-line explanation when there is none.
pub const NO_DISPLAY: &str =
    "no display found (DISPLAY/WAYLAND_DISPLAY unset): use `lucid render` for headless output";

/// Whether a window can be opened: false on X11/Wayland systems where neither `DISPLAY` nor
/// `WAYLAND_DISPLAY` is set (winit would fail there).
///
/// ```
/// if !lucid_sandbox::display_available() {
///     eprintln!("no display: rendering headless instead");
/// }
/// ```
pub fn available() -> bool {
    let unix_desktop = cfg!(all(
        unix,
        not(target_os = "macos"),
        not(target_os = "android")
    ));
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty());
    !unix_desktop || set("DISPLAY") || set("WAYLAND_DISPLAY")
}

/// Fails with [`NO_DISPLAY`] where there is no display.
pub fn check() -> anyhow::Result<()> {
    anyhow::ensure!(available(), NO_DISPLAY);
    Ok(())
}
