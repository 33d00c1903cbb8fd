//! Long paths parked (`shaders/parking/parking.glsl`): with one sample a pixel, a light transport
//! kernel parks every path still alive after the Russian roulette's first segments, and two passes
//! continue them over a compacted list: `<algorithm>.long_list` (`shaders/parking/list.comp`)
//! lists the pixels that parked one, and the algorithm's continuation kernel traces them on, one
//! invocation each, adding what they bring to the pixels' radiance. A subgroup of the first kernel
//! then waits for its longest path up to that depth only, not for the few paths the roulette keeps
//! to the maximum depth (bench/README.md: 10% off the path tracer's Cornell box image on an H200,
//! 5% off `classroom`'s). The same paths and random numbers as one kernel: only the order in which
//! a path's contributions are summed changes. The path tracer and BDPT's camera pass park.

use crate::light_transport::{Frame, Images};
use crate::plumbing::stats::add_zeroed;
use crate::samples_per_pixel::SamplesPerPixel;
use crate::shaders::parking::LIST;
use lucid_engine::graph::{BufferHandle, ComputePass, RenderGraph};
use lucid_engine::shader::ShaderSource;

/// Bytes of a parked path's record (`ParkedPath` in `shaders/path_trace/long_paths.glsl`,
/// `ParkedCameraPath` in `shaders/bdpt/long_paths.glsl`).
const PARKED_PATH_BYTES: u64 = 64;

/// Pixels whose flags one invocation of the list pass reads (`FLAGS_PER_INVOCATION` in
/// `shaders/parking/list.comp`).
const LIST_FLAGS_PER_INVOCATION: u32 = 8;

/// The most bytes of parked paths: the storage-buffer range every Vulkan device supports (128 MiB,
/// a 1920x1080 frame's records). Larger frames trace every path in one kernel.
const MAX_PARKED_BYTES: u64 = 128 << 20;

/// The zeroed buffers of one frame's parking, made before the parking pass.
pub struct Parking {
    prefix: &'static str,
    depth: u32,
    pixels: u32,
    flags: BufferHandle,
    count: BufferHandle,
    args: BufferHandle,
}

/// What the parking pass parked, for [`add_continuation`].
pub struct Parked {
    parking: Parking,
    records: BufferHandle,
    flags: BufferHandle,
}

impl Parking {
    /// The parking of the frame `sampling` describes, after `depth` segments, its flags, list
    /// length and indirect arguments cleared (named `<prefix>.parked_flags` and so on); `None`
    /// without a depth, with more than one sample a pixel, or when one record a pixel would pass
    /// [`MAX_PARKED_BYTES`].
    pub fn clear(
        g: &mut RenderGraph,
        prefix: &'static str,
        depth: Option<u32>,
        sampling: &Frame,
    ) -> Option<Self> {
        let pixels = sampling.width * sampling.height;
        let fits = u64::from(pixels) * PARKED_PATH_BYTES <= MAX_PARKED_BYTES;
        let depth = depth
            .filter(|&d| d > 0 && fits && sampling.samples_per_pixel == SamplesPerPixel::ONE)?;
        Some(Self {
            prefix,
            depth,
            pixels,
            flags: add_zeroed(g, &format!("{prefix}.parked_flags"), u64::from(pixels) * 4),
            count: add_zeroed(g, &format!("{prefix}.parked_count"), 16),
            args: add_zeroed(g, &format!("{prefix}.parked_args"), 16),
        })
    }
}

/// Binds the parking buffers to the parking `pass` (`b_parked`, `b_parked_flags`) and sets
/// `PARK_DEPTH`: placeholders and 0 without `parking`, since the shader declares them either way.
pub fn bind(pass: &mut ComputePass<'_>, prefix: &str, parking: Option<Parking>) -> Option<Parked> {
    let records = format!("{prefix}.parked");
    match parking {
        Some(parking) => {
            let bytes = u64::from(parking.pixels) * PARKED_PATH_BYTES;
            let records = pass.create_buffer("b_parked", &records, bytes);
            let flags = pass.read_write("b_parked_flags", parking.flags);
            pass.specialize("PARK_DEPTH", parking.depth);
            Some(Parked {
                parking,
                records,
                flags,
            })
        }
        None => {
            pass.create_buffer("b_parked", &records, PARKED_PATH_BYTES);
            let flags = format!("{prefix}.parked_flags");
            pass.create_buffer("b_parked_flags", &flags, 16);
            pass.specialize("PARK_DEPTH", 0u32);
            None
        }
    }
}

/// Adds the passes that list the parked paths (`<prefix>.long_list`) and continue them
/// (`<prefix>.long`, running `continuation` with what `bind_inputs` binds besides the parking's
/// buffers, the images and the stats), adding to `images`' radiance (and demodulated radiance
/// where the denoiser's images are written) and counting in `stats`; returns both written.
pub fn add_continuation(
    g: &mut RenderGraph,
    continuation: &ShaderSource,
    bind_inputs: impl FnOnce(&mut ComputePass<'_>),
    parked: Parked,
    (mut images, stats): (Images, BufferHandle),
) -> (Images, BufferHandle) {
    let Parked {
        parking,
        records,
        flags,
    } = parked;
    let prefix = parking.prefix;
    let mut list = g.compute_pass(&format!("{prefix}.long_list"), &LIST);
    list.read("b_parked_flags", flags);
    let pixels = list.create_buffer(
        "b_parked_list",
        &format!("{prefix}.parked_list"),
        u64::from(parking.pixels) * 4,
    );
    let count = list.read_write("b_parked_count", parking.count);
    let args = list.read_write("b_parked_args", parking.args);
    list.push(&parking.pixels);
    list.dispatch([parking.pixels.div_ceil(LIST_FLAGS_PER_INVOCATION), 1, 1]);

    let mut pass = g.compute_pass(&format!("{prefix}.long"), continuation);
    bind_inputs(&mut pass);
    pass.specialize("PARK_DEPTH", parking.depth)
        .read("b_parked", records)
        .read("b_parked_list", pixels)
        .read("b_parked_count", count);
    let stats = pass.read_write("b_stats", stats);
    pass.specialize("SURFACE_OUTPUTS", images.surface_written)
        .read("u_albedo", images.surface.albedo)
        .read("u_emission", images.surface.emission);
    images.radiance = pass.read_write("u_radiance", images.radiance);
    images.surface.demodulated = pass.read_write("u_demodulated", images.surface.demodulated);
    pass.dispatch_indirect(args, 0);
    (images, stats)
}
