//! A compute pass (one dispatch, or several of one shader) declared and bound in one place: each call names a shader
//! binding and a resource once, and both declares the access in the graph and binds the resource
//! by that name, so what a pass declares and what its shader is given cannot differ.
//!
//! ```no_run
//! # use lucid_engine::graph::*; use lucid_engine::memory::ImageDesc;
//! # fn demo(g: &mut RenderGraph, input: ImageHandle, shader: &lucid_engine::shader::ShaderSource) -> ImageHandle {
//! let mut pass = g.compute_pass("blur", shader);
//! pass.read("u_in", input).push(&2.0f32);
//! let out = pass.create_image("u_out", "blur.out", ImageDesc::rgba32f(64, 64));
//! pass.dispatch([64, 64, 1]);
//! # out }
//! ```
//!
//! The shader's reflection is checked when the pass records (against the SPIR-V the shader
//! library holds then, hot-reloaded or not): every name must be one of its bindings, every binding
//! must be bound, each access must suit its binding's kind, and the push constants must have the
//! size of its push-constant block.

use super::handle::{BufferHandle, Handle, ImageHandle, TemporalImage};
use super::pass_context::{Dispatch, PassContext};
use super::render_graph::{PassBuilder, RenderGraph};
use crate::access::Access;
use crate::error::Result;
use crate::memory::ImageDesc;
use crate::shader::{ShaderSource, SpecValue, Specialization};

/// A resource bound to a shader binding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Bound {
    Image(ImageHandle),
    Buffer(BufferHandle),
}

impl Bound {
    fn of<H: Handle>(handle: H) -> Self {
        let (id, version) = (handle.id(), handle.version());
        if H::IS_IMAGE {
            Self::Image(ImageHandle { id, version })
        } else {
            Self::Buffer(BufferHandle { id, version })
        }
    }
}

/// How many workgroups a [`ComputePass`] dispatches.
#[derive(Clone, Copy)]
enum Size {
    /// Enough to cover this many invocations.
    Threads([u32; 3]),
    /// What the buffer holds at this byte offset when the pass runs.
    Indirect(BufferHandle, u64),
}

/// Push constants of any plain-data type, applied to a dispatch.
trait PushConstants {
    fn apply<'p, 'a>(&self, dispatch: Dispatch<'p, 'a>) -> Dispatch<'p, 'a>;
}

impl<T: bytemuck::Pod> PushConstants for T {
    fn apply<'p, 'a>(&self, dispatch: Dispatch<'p, 'a>) -> Dispatch<'p, 'a> {
        dispatch.push(self)
    }
}

/// Computes the push constants while the pass records.
type PushFn = dyn FnOnce(&PassContext<'_>) -> Box<dyn PushConstants>;
/// A precondition checked while the pass records.
type RequireFn = dyn FnOnce(&PassContext<'_>) -> Result<()>;

/// One compute dispatch being declared; see [`RenderGraph::compute_pass`]. Each method that takes
/// a binding name declares the resource's access and binds it to that shader binding.
pub struct ComputePass<'g> {
    pass: PassBuilder<'g>,
    shader: ShaderSource,
    bindings: Vec<(String, Bound)>,
    spec: Specialization,
    push: Option<Box<PushFn>>,
    require: Vec<Box<RequireFn>>,
}

impl RenderGraph {
    /// Adds a pass that runs `shader` once; declare and bind its resources on the returned
    /// [`ComputePass`], then [`ComputePass::dispatch`] it.
    pub fn compute_pass(&mut self, name: &str, shader: &ShaderSource) -> ComputePass<'_> {
        ComputePass {
            pass: self.add_pass(name),
            shader: *shader,
            bindings: Vec::new(),
            spec: Specialization::new(),
            push: None,
            require: Vec::new(),
        }
    }
}

impl ComputePass<'_> {
    fn bind<H: Handle>(&mut self, binding: &str, handle: H) {
        self.bindings.push((binding.to_string(), Bound::of(handle)));
    }

    /// Reads `handle` (a storage image, or a storage or uniform buffer) through `binding`.
    pub fn read<H: Handle>(&mut self, binding: &str, handle: H) -> &mut Self {
        let handle = self.pass.read(handle, Access::ComputeRead);
        self.bind(binding, handle);
        self
    }

    /// Samples `image` through the `sampler2D` `binding`.
    pub fn sample(&mut self, binding: &str, image: ImageHandle) -> &mut Self {
        let image = self.pass.read(image, Access::ComputeSampled);
        self.bind(binding, image);
        self
    }

    /// Writes `handle` through `binding`; returns the new version, which later passes read.
    pub fn write<H: Handle>(&mut self, binding: &str, handle: H) -> H {
        let new = self.pass.write(handle, Access::ComputeWrite);
        self.bind(binding, new);
        new
    }

    /// Reads and writes `handle` through `binding` (e.g. atomic counters); returns the new version.
    pub fn read_write<H: Handle>(&mut self, binding: &str, handle: H) -> H {
        let new = self.pass.write(handle, Access::ComputeReadWrite);
        self.bind(binding, new);
        new
    }

    /// Creates the transient image `name` and writes it through `binding`; returns it written.
    pub fn create_image(&mut self, binding: &str, name: &str, desc: ImageDesc) -> ImageHandle {
        let image = self.pass.create_image(name, desc);
        self.write(binding, image)
    }

    /// Creates the transient buffer `name` of `size` bytes and writes it through `binding`;
    /// returns it written.
    pub fn create_buffer(&mut self, binding: &str, name: &str, size: u64) -> BufferHandle {
        let buffer = self.pass.create_buffer(name, size);
        self.write(binding, buffer)
    }

    /// Reads last frame's `history` through `prev_binding` and writes this frame's through
    /// `cur_binding`; returns this frame's, written. Whether `history.prev` holds a frame is
    /// [`PassContext::history_valid`], e.g. in [`ComputePass::push_with`].
    pub fn history(
        &mut self,
        prev_binding: &str,
        cur_binding: &str,
        history: TemporalImage,
    ) -> ImageHandle {
        self.read(prev_binding, history.prev);
        self.write(cur_binding, history.cur)
    }

    /// Sets the specialization constant `name`.
    pub fn specialize(&mut self, name: &str, value: impl Into<SpecValue>) -> &mut Self {
        self.spec = std::mem::take(&mut self.spec).set(name, value);
        self
    }

    /// Sets every constant of `spec`.
    pub fn specialization(&mut self, spec: &Specialization) -> &mut Self {
        for (name, value) in spec.values() {
            self.specialize(name, *value);
        }
        self
    }

    /// Sets the push constants (their size must equal the shader's push-constant block).
    pub fn push<T: bytemuck::Pod>(&mut self, data: &T) -> &mut Self {
        let data = *data;
        self.push_with(move |_| data)
    }

    /// Sets push constants computed while the pass records, from what only then is known (e.g.
    /// [`PassContext::history_valid`]).
    pub fn push_with<T: bytemuck::Pod>(
        &mut self,
        data: impl FnOnce(&PassContext<'_>) -> T + 'static,
    ) -> &mut Self {
        self.push = Some(Box::new(move |ctx| Box::new(data(ctx))));
        self
    }

    /// Checks `condition` while the pass records, before the dispatch; its error fails the frame
    /// (e.g. a device feature the shader needs).
    pub fn require(
        &mut self,
        condition: impl FnOnce(&PassContext<'_>) -> Result<()> + 'static,
    ) -> &mut Self {
        self.require.push(Box::new(condition));
        self
    }

    /// Gives the pass its work: one dispatch of enough workgroups to cover `threads` invocations
    /// (the workgroup size comes from the shader, which must bounds-check).
    pub fn dispatch(self, threads: [u32; 3]) {
        self.record(Size::Threads(threads), Vec::new());
    }

    /// Gives the pass its work: one dispatch of as many workgroups as the
    /// `VkDispatchIndirectCommand` at byte `offset` of `args` holds when it runs (written by an
    /// earlier pass, e.g. from a queue's length). The pass reads `args` with
    /// [`Access::IndirectCommandRead`], so the graph puts the barrier from that write to the
    /// indirect-command stage before it; the shader must bounds-check against the queue's length.
    pub fn dispatch_indirect(mut self, args: BufferHandle, offset: u64) {
        let args = self.pass.read(args, Access::IndirectCommandRead);
        self.record(Size::Indirect(args, offset), Vec::new());
    }

    /// Gives the pass its work in several dispatches of `threads` invocations, one per element of
    /// `pushes` and in their order, each with that element as its push constants (replacing
    /// [`ComputePass::push`]) and each seeing what the ones before it wrote. For work that one
    /// dispatch cannot do safely on every device (e.g. many samples per pixel, cut in batches).
    pub fn dispatch_each<T: bytemuck::Pod>(self, threads: [u32; 3], pushes: Vec<T>) {
        let pushes = pushes
            .into_iter()
            .map(|data| Box::new(data) as Box<dyn PushConstants>)
            .collect();
        self.record(Size::Threads(threads), pushes);
    }

    /// Records the dispatches: one per element of `pushes`, or one with the pass's push constants
    /// when `pushes` is empty.
    fn record(self, size: Size, pushes: Vec<Box<dyn PushConstants>>) {
        let Self {
            pass,
            shader,
            bindings,
            spec,
            push,
            require,
        } = self;
        pass.execute(move |ctx| {
            for condition in require {
                condition(ctx)?;
            }
            let pushes: Vec<Option<Box<dyn PushConstants>>> = if pushes.is_empty() {
                vec![push.map(|data| data(ctx))]
            } else {
                pushes.into_iter().map(Some).collect()
            };
            for (i, push) in pushes.into_iter().enumerate() {
                if i > 0 {
                    ctx.compute_barrier();
                }
                let mut dispatch = ctx.compute(&shader).specialization(&spec);
                for (name, bound) in &bindings {
                    dispatch = match *bound {
                        Bound::Image(image) => dispatch.image(name, image),
                        Bound::Buffer(buffer) => dispatch.buffer(name, buffer),
                    };
                }
                if let Some(push) = push {
                    dispatch = push.apply(dispatch);
                }
                match size {
                    Size::Threads(threads) => dispatch.dispatch_threads(threads)?,
                    Size::Indirect(args, offset) => dispatch.dispatch_indirect(args, offset)?,
                }
            }
            Ok(())
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::GraphError;

    static SHADER: ShaderSource = ShaderSource {
        name: "test/blend",
        path: "shaders/test/blend.comp",
        spirv: &[],
    };

    fn desc() -> ImageDesc {
        ImageDesc::rgba32f(8, 8)
    }

    /// The access the compiled plan gives each binding's resource version in pass `name`.
    fn declared(
        plan: &crate::graph::Plan,
        name: &str,
        bindings: &[(String, Bound)],
    ) -> Vec<(String, Access)> {
        let accesses = &plan.pass(name).expect("kept").accesses;
        bindings
            .iter()
            .map(|(binding, bound)| {
                let (id, version) = match *bound {
                    Bound::Image(h) => (h.id(), h.version()),
                    Bound::Buffer(h) => (h.id(), h.version()),
                };
                let access = accesses
                    .iter()
                    .find(|&&(i, v, _)| i == id && v == version)
                    .map(|&(_, _, a)| a)
                    .expect("every binding is declared");
                (binding.clone(), access)
            })
            .collect()
    }

    #[test]
    fn every_binding_is_declared_with_its_access() {
        let mut g = RenderGraph::new();
        let input = g.import_image_desc("input", desc());
        let texture = g.import_image_desc("texture", desc());
        let history = g.temporal_image("history", desc());
        let mut clear = g.compute_pass("clear", &SHADER);
        let counter = clear.create_buffer("b_counter", "counter", 16);
        clear.dispatch([1, 1, 1]);
        let mut pass = g.compute_pass("blend", &SHADER);
        pass.read("u_in", input).sample("u_tex", texture);
        let counter = pass.read_write("b_counter", counter);
        let out = pass.create_image("u_out", "out", desc());
        let cur = pass.history("u_prev", "u_cur", history);
        assert_eq!((counter.version(), out.version(), cur.version()), (2, 1, 1));
        let bindings = pass.bindings.clone();
        pass.dispatch([8, 8, 1]);
        let plan = g.compile().unwrap().plan;
        let expected = [
            ("u_in", Access::ComputeRead),
            ("u_tex", Access::ComputeSampled),
            ("b_counter", Access::ComputeReadWrite),
            ("u_out", Access::ComputeWrite),
            ("u_prev", Access::ComputeRead),
            ("u_cur", Access::ComputeWrite),
        ]
        .map(|(name, access)| (name.to_string(), access));
        assert_eq!(declared(&plan, "blend", &bindings), expected);
    }

    #[test]
    fn written_handles_chain_passes_in_order() {
        let mut g = RenderGraph::new();
        let mut first = g.compute_pass("first", &SHADER);
        let a = first.create_image("u_out", "a", desc());
        first.dispatch([8, 8, 1]);
        let mut second = g.compute_pass("second", &SHADER);
        second.read("u_in", a);
        let b = second.create_image("u_out", "b", desc());
        second.dispatch([8, 8, 1]);
        let mut unused = g.compute_pass("unused", &SHADER);
        unused.read("u_in", a);
        unused.create_image("u_out", "c", desc());
        unused.dispatch([8, 8, 1]);
        g.readback(b);
        let plan = g.compile().unwrap().plan;
        assert_eq!(plan.order(), ["first", "second", "readback b"]);
        assert_eq!(plan.culled, ["unused"]);
    }

    #[test]
    fn setup_errors_surface_at_compile() {
        let mut g = RenderGraph::new();
        let history = g.temporal_image("history", desc());
        let mut pass = g.compute_pass("writes_prev", &SHADER);
        pass.write("u_prev", history.prev);
        pass.dispatch([8, 8, 1]);
        assert!(matches!(
            g.compile(),
            Err(GraphError::WritePrevHistory { .. })
        ));
    }

    #[test]
    fn specialization_and_push_are_kept_for_recording() {
        let mut g = RenderGraph::new();
        let mut pass = g.compute_pass("spec", &SHADER);
        pass.specialization(&Specialization::new().set("A", true))
            .specialize("B", 4u32)
            .push(&[1u32, 2]);
        let names: Vec<_> = pass.spec.values().iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["A", "B"]);
        assert!(pass.push.is_some() && pass.require.is_empty());
    }
}
