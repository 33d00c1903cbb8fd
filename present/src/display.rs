//! Whether there is a display to open a window on.

/// Whether a window can be opened: false on X11/Wayland systems where neither `DISPLAY` nor
/// `WAYLAND_DISPLAY` is set (winit would fail there).
///
/// ```
/// if !lucid_present::display_available() {
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
