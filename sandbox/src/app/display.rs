//! Whether there is a display to open a window on.

/// The one-line explanation when there is none.
pub const NO_DISPLAY: &str =
    "no display found (DISPLAY/WAYLAND_DISPLAY unset): use `lucid render` for headless output";

/// Fails with [`NO_DISPLAY`] on X11/Wayland systems where neither variable is set.
pub fn check() -> anyhow::Result<()> {
    let unix_desktop = cfg!(all(
        unix,
        not(target_os = "macos"),
        not(target_os = "android")
    ));
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty());
    if unix_desktop && !set("DISPLAY") && !set("WAYLAND_DISPLAY") {
        anyhow::bail!(NO_DISPLAY);
    }
    Ok(())
}
