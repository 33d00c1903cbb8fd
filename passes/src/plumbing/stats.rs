//! Small GPU counters (e.g. non-finite samples dropped), cleared at the start of each frame.

use lucid_engine::graph::{Access, BufferHandle, RenderGraph};

/// Adds a pass that creates a zeroed 16-byte counter buffer named `name`.
pub fn add_counter(g: &mut RenderGraph, name: &str) -> BufferHandle {
    add_zeroed(g, name, 16)
}

/// Adds a pass that creates a buffer of `bytes` named `name`, zeroed.
pub fn add_zeroed(g: &mut RenderGraph, name: &str, bytes: u64) -> BufferHandle {
    let mut p = g.add_pass(&format!("{name}.clear"));
    let buffer = p.create_buffer(name, bytes);
    let buffer = p.write(buffer, Access::TransferWrite);
    p.execute(move |ctx| ctx.fill_buffer(buffer, 0));
    buffer
}
