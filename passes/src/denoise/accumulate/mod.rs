//! Progressive accumulation of HDR frames while camera and scene are still
//! (`shaders/accumulate/accumulate.comp`), over a keyed history image.

use crate::shaders::accumulate::ACCUMULATE;
use lucid_engine::graph::{ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;

/// The history key of the accumulated image.
pub const HISTORY_KEY: &str = "accumulate.radiance";

/// Adds accumulation of `input`: with `accumulated` = n frames already averaged (0 restarts), the
/// result is the mean of the last n + 1 frames.
pub fn add_accumulate(
    g: &mut RenderGraph,
    input: ImageHandle,
    width: u32,
    height: u32,
    accumulated: u32,
) -> ImageHandle {
    add_accumulate_keyed(g, HISTORY_KEY, input, (width, height), accumulated)
}

/// Adds accumulation of the `rgba32f` image `input` into the history `key` (also the pass name),
/// as [`add_accumulate`] does.
pub fn add_accumulate_keyed(
    g: &mut RenderGraph,
    key: &str,
    input: ImageHandle,
    (width, height): (u32, u32),
    accumulated: u32,
) -> ImageHandle {
    let history = g.temporal_image(key, ImageDesc::rgba32f(width, height));
    let mut pass = g.compute_pass(key, &ACCUMULATE);
    pass.read("u_new", input);
    let cur = pass.history("u_prev", "u_cur", history);
    pass.push_with(move |ctx| {
        if ctx.history_valid(history.prev) {
            accumulated
        } else {
            0
        }
    });
    pass.dispatch([width, height, 1]);
    cur
}
