//! The wavefront path tracer's buffers, transient per frame: the path state (structure of arrays,
//! `shaders/wavefront/path_state.glsl`), hit records, shadow rays, the queues and their lengths
//! and indirect arguments. Each buffer keeps the handle of its latest version as the kernels
//! write it, so that the graph orders them and puts the barriers between them.

use super::queues;
use lucid_engine::graph::{BufferHandle, ComputePass};

/// One transient buffer and its latest version.
pub struct Tracked {
    name: String,
    bytes: u64,
    handle: Option<BufferHandle>,
}

impl Tracked {
    fn new(name: &str, bytes: u64) -> Self {
        Self {
            name: format!("wavefront.{name}"),
            bytes: bytes.max(4),
            handle: None,
        }
    }

    /// The latest version (e.g. for an indirect dispatch).
    pub fn latest(&self) -> BufferHandle {
        self.handle
            .unwrap_or_else(|| panic!("{} is read before a kernel writes it", self.name))
    }

    /// Writes the buffer through `binding` (creating it on its first write).
    pub fn write(&mut self, pass: &mut ComputePass<'_>, binding: &str) {
        self.handle = Some(match self.handle {
            None => pass.create_buffer(binding, &self.name, self.bytes),
            Some(h) => pass.write(binding, h),
        });
    }

    /// Reads and writes the buffer through `binding`.
    pub fn read_write(&mut self, pass: &mut ComputePass<'_>, binding: &str) {
        self.handle = Some(pass.read_write(binding, self.latest()));
    }

    /// Reads the buffer through `binding`.
    pub fn read(&self, pass: &mut ComputePass<'_>, binding: &str) {
        pass.read(binding, self.latest());
    }
}

/// Every buffer of the wavefront for `paths` paths. The shade kernel binds most of them besides
/// the scene's 16: few enough that a device's 32 push descriptors and storage buffers per stage
/// hold them all (hence the first hit's two vectors and a shadow ray's three in one buffer each).
pub struct WaveBuffers {
    /// The path state bound as `path_state.glsl` names it, in its order.
    pub path_state: Vec<(&'static str, Tracked)>,
    /// Hit records (`Hit` of `common/traverse.glsl`, 24 bytes).
    pub hits: Tracked,
    /// The two ray queues: bounce `k` reads `ray_queues[k % 2]` and appends to the other.
    pub ray_queues: [Tracked; 2],
    /// The shadow-ray queue, refilled every bounce.
    pub shadow_queue: Tracked,
    /// Shadow rays by path (`ShadowRecord` of `queues.glsl`: origin and extent, direction, what
    /// they bring; 48 bytes).
    pub shadow_rays: Tracked,
    /// The material bins' queues, `queues::MATERIAL_BINS` of `paths` places (a single element
    /// without binning).
    pub binned_queue: Tracked,
    /// Queue lengths, a u32 per slot ([`queues`]).
    pub counts: Tracked,
    /// Indirect arguments by parity ([`queues::args_buffer`]).
    pub args: [Tracked; 2],
}

/// Bytes of a `vec4` per path.
const VEC4: u64 = 16;

impl WaveBuffers {
    /// The buffers for `paths` paths of at most `max_depth` segments; the first hit's albedo and
    /// emission per path only with `surface`, the material bins only when `binned` (a single
    /// element otherwise).
    pub fn new(paths: u64, max_depth: u32, surface: bool, binned: bool) -> Self {
        let per_path = |bytes: u64| paths * bytes;
        let surface_bytes = if surface { per_path(2 * VEC4) } else { VEC4 };
        let path_state = [
            ("b_ray_origin", "ray_origin", per_path(VEC4)),
            ("b_ray_direction", "ray_direction", per_path(VEC4)),
            ("b_throughput", "throughput", per_path(VEC4)),
            ("b_prev_vertex", "prev_vertex", per_path(VEC4)),
            ("b_path_rng", "rng", per_path(4)),
            ("b_path_radiance", "radiance", per_path(VEC4)),
            ("b_first_hit", "first_hit", surface_bytes),
        ]
        .into_iter()
        .map(|(binding, name, bytes)| (binding, Tracked::new(name, bytes)))
        .collect();
        Self {
            path_state,
            hits: Tracked::new("hits", per_path(24)),
            ray_queues: [
                Tracked::new("ray_queue_even", per_path(4)),
                Tracked::new("ray_queue_odd", per_path(4)),
            ],
            shadow_queue: Tracked::new("shadow_queue", per_path(4)),
            shadow_rays: Tracked::new("shadow_rays", per_path(3 * VEC4)),
            binned_queue: Tracked::new(
                "binned_queue",
                if binned {
                    per_path(4) * u64::from(queues::MATERIAL_BINS)
                } else {
                    4
                },
            ),
            counts: Tracked::new(
                "queue_counts",
                u64::from(queues::counters(max_depth, binned)) * 4,
            ),
            args: [
                Tracked::new("args_even", queues::args_bytes(max_depth)),
                Tracked::new("args_odd", queues::args_bytes(max_depth)),
            ],
        }
    }

    /// The path-state buffer bound as `binding`.
    pub fn state(&mut self, binding: &str) -> &mut Tracked {
        self.path_state
            .iter_mut()
            .find(|(b, _)| *b == binding)
            .map(|(_, t)| t)
            .unwrap_or_else(|| panic!("no path-state buffer {binding}"))
    }
}
