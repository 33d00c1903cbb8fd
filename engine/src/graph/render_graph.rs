//! Setup: passes declare the resources they create, read and write, with access types.

use super::handle::{BufferHandle, Handle, ImageHandle, ResourceId, TemporalImage};
use super::pass_context::PassContext;
use super::GraphError;
use crate::access::Access;
use crate::memory::{Buffer, Image, ImageDesc};
use std::sync::Arc;

/// What a resource is and where its memory comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ResourceKind {
    /// Created and released within the frame; its memory may be shared with other transients.
    Transient,
    /// Supplied from outside the graph (scene buffers, an application's output image).
    Imported,
    /// Last frame's contents of a keyed history resource.
    TemporalPrev(String),
    /// This frame's contents of a keyed history resource.
    TemporalCur(String),
}

/// Size and format of a resource.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ResourceDesc {
    /// A 2D image.
    Image(ImageDesc),
    /// A buffer of this many bytes.
    Buffer(u64),
}

impl ResourceDesc {
    /// Bytes of data it holds (an estimate of memory for images).
    pub fn byte_size(&self) -> u64 {
        match self {
            Self::Image(d) => d.byte_size(),
            Self::Buffer(size) => *size,
        }
    }
}

/// A resource declared in a graph.
#[derive(Clone, Debug)]
pub struct ResourceDecl {
    /// Debug name.
    pub name: String,
    /// Transient, imported or temporal.
    pub kind: ResourceKind,
    /// Size and format.
    pub desc: ResourceDesc,
    pub(crate) latest: u32,
}

/// The physical resource behind an imported handle.
#[derive(Clone)]
pub(crate) enum External {
    Image(Arc<Image>),
    Buffer(Arc<Buffer>),
    /// Declared by description only (for compiling without a device).
    Described,
}

/// What a pass does when executed.
pub(crate) enum PassWork {
    /// Not given yet (an error at compile time).
    Missing,
    /// Records commands through a callback.
    Callback(Box<PassFn>),
    /// Copies a resource into a host-visible buffer, returned after the frame.
    Readback,
}

/// The callback a pass records its commands with.
pub type PassFn = dyn FnOnce(&mut PassContext<'_>) -> crate::Result<()>;

/// A declared pass.
pub(crate) struct PassDecl {
    pub name: String,
    pub reads: Vec<(ResourceId, u32, Access)>,
    pub writes: Vec<(ResourceId, u32, Access)>,
    pub side_effect: bool,
    pub work: PassWork,
}

/// Identifies a readback requested with [`RenderGraph::readback`]; redeem it after the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ReadbackId(pub(crate) usize);

/// A frame's render graph under construction.
#[derive(Default)]
pub struct RenderGraph {
    pub(crate) resources: Vec<ResourceDecl>,
    pub(crate) externals: Vec<(ResourceId, External)>,
    pub(crate) passes: Vec<PassDecl>,
    pub(crate) readbacks: Vec<(usize, ResourceId)>,
    pub(crate) errors: Vec<GraphError>,
}

impl RenderGraph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    fn declare(&mut self, name: &str, kind: ResourceKind, desc: ResourceDesc) -> ResourceId {
        let id = ResourceId(self.resources.len() as u32);
        self.resources.push(ResourceDecl {
            name: name.to_string(),
            kind,
            desc,
            latest: 0,
        });
        id
    }

    /// Imports an image that lives outside the graph; its contents at frame start are version 0.
    pub fn import_image(&mut self, name: &str, image: Arc<Image>) -> ImageHandle {
        let id = self.declare(
            name,
            ResourceKind::Imported,
            ResourceDesc::Image(image.desc()),
        );
        self.externals.push((id, External::Image(image)));
        ImageHandle { id, version: 0 }
    }

    /// Imports a buffer that lives outside the graph (scene data, parameters).
    pub fn import_buffer(&mut self, name: &str, buffer: Arc<Buffer>) -> BufferHandle {
        let id = self.declare(
            name,
            ResourceKind::Imported,
            ResourceDesc::Buffer(buffer.size()),
        );
        self.externals.push((id, External::Buffer(buffer)));
        BufferHandle { id, version: 0 }
    }

    /// Declares an imported image by description only, to compile, dump or test a graph without a
    /// device. Executing a graph that contains one is an error.
    pub fn import_image_desc(&mut self, name: &str, desc: ImageDesc) -> ImageHandle {
        let id = self.declare(name, ResourceKind::Imported, ResourceDesc::Image(desc));
        self.externals.push((id, External::Described));
        ImageHandle { id, version: 0 }
    }

    /// Declares the keyed history image `key`, which persists across frames: `prev` is what `cur` held
    /// at the end of the last frame that wrote it. A change of `desc` resets the history.
    pub fn temporal_image(&mut self, key: &str, desc: ImageDesc) -> TemporalImage {
        let duplicate = self
            .resources
            .iter()
            .any(|r| r.kind == ResourceKind::TemporalCur(key.into()));
        if duplicate {
            self.errors
                .push(GraphError::DuplicateTemporalKey(key.to_string()));
        }
        let prev = self.declare(
            &format!("{key} (prev)"),
            ResourceKind::TemporalPrev(key.to_string()),
            ResourceDesc::Image(desc),
        );
        let cur = self.declare(
            key,
            ResourceKind::TemporalCur(key.to_string()),
            ResourceDesc::Image(desc),
        );
        TemporalImage {
            prev: ImageHandle {
                id: prev,
                version: 0,
            },
            cur: ImageHandle {
                id: cur,
                version: 0,
            },
        }
    }

    /// Adds a pass. Declare its resources on the returned builder, then give it work with
    /// [`PassBuilder::execute`].
    pub fn add_pass(&mut self, name: &str) -> PassBuilder<'_> {
        let index = self.passes.len();
        self.passes.push(PassDecl {
            name: name.to_string(),
            reads: Vec::new(),
            writes: Vec::new(),
            side_effect: false,
            work: PassWork::Missing,
        });
        PassBuilder { graph: self, index }
    }

    /// Copies `handle`'s contents to the CPU after the frame (a pass with a side effect, never culled).
    pub fn readback<H: Handle>(&mut self, handle: H) -> ReadbackId {
        let name = format!(
            "readback {}",
            self.resources
                .get(handle.id().0 as usize)
                .map_or("?", |r| r.name.as_str())
        );
        let mut pass = self.add_pass(&name);
        pass.read(handle, Access::TransferRead);
        pass.side_effect();
        let index = pass.index;
        self.passes[index].work = PassWork::Readback;
        let id = ReadbackId(self.readbacks.len());
        self.readbacks.push((index, handle.id()));
        id
    }

    /// The declared resources, indexed by [`ResourceId`].
    pub fn resources(&self) -> &[ResourceDecl] {
        &self.resources
    }
}

/// Declares one pass's resources and work.
pub struct PassBuilder<'g> {
    graph: &'g mut RenderGraph,
    index: usize,
}

impl PassBuilder<'_> {
    fn decl(&mut self) -> &mut PassDecl {
        &mut self.graph.passes[self.index]
    }

    fn pass_name(&self) -> String {
        self.graph.passes[self.index].name.clone()
    }

    /// Creates a transient image; write it before any pass reads it.
    pub fn create_image(&mut self, name: &str, desc: ImageDesc) -> ImageHandle {
        let id = self
            .graph
            .declare(name, ResourceKind::Transient, ResourceDesc::Image(desc));
        ImageHandle { id, version: 0 }
    }

    /// Creates a transient buffer of `size` bytes; write it before any pass reads it.
    pub fn create_buffer(&mut self, name: &str, size: u64) -> BufferHandle {
        let id = self
            .graph
            .declare(name, ResourceKind::Transient, ResourceDesc::Buffer(size));
        BufferHandle { id, version: 0 }
    }

    fn check_readable<H: Handle>(&mut self, handle: H) -> bool {
        let pass = self.pass_name();
        let Some(res) = self.graph.resources.get(handle.id().0 as usize) else {
            self.graph.errors.push(GraphError::UnknownHandle { pass });
            return false;
        };
        if H::IS_IMAGE != matches!(res.desc, ResourceDesc::Image(_)) {
            self.graph.errors.push(GraphError::UnknownHandle { pass });
            return false;
        }
        let initial_valid = matches!(
            res.kind,
            ResourceKind::Imported | ResourceKind::TemporalPrev(_)
        );
        if handle.version() == 0 && !initial_valid {
            let resource = res.name.clone();
            self.graph
                .errors
                .push(GraphError::ReadUnwritten { pass, resource });
            return false;
        }
        if handle.version() < res.latest {
            let resource = res.name.clone();
            let (version, latest) = (handle.version(), res.latest);
            self.graph.errors.push(GraphError::ReadOverwritten {
                pass,
                resource,
                version,
                latest,
            });
            return false;
        }
        true
    }

    /// Declares that this pass reads `handle` with `access` (which must not write).
    pub fn read<H: Handle>(&mut self, handle: H, access: Access) -> H {
        if access.info().writes {
            let pass = self.pass_name();
            self.graph
                .errors
                .push(GraphError::WriteAccessInRead { pass, access });
        } else if self.check_readable(handle) {
            self.decl()
                .reads
                .push((handle.id(), handle.version(), access));
        }
        handle
    }

    /// Declares that this pass writes `handle` with `access`; returns the new version, which later
    /// passes read. An access that also reads (e.g. `ComputeReadWrite`) reads the given version.
    pub fn write<H: Handle>(&mut self, handle: H, access: Access) -> H {
        let pass = self.pass_name();
        let Some(res) = self.graph.resources.get(handle.id().0 as usize) else {
            self.graph.errors.push(GraphError::UnknownHandle { pass });
            return handle;
        };
        if matches!(res.kind, ResourceKind::TemporalPrev(_)) {
            let resource = res.name.clone();
            self.graph
                .errors
                .push(GraphError::WritePrevHistory { pass, resource });
            return handle;
        }
        if !access.info().writes {
            self.graph
                .errors
                .push(GraphError::ReadAccessInWrite { pass, access });
            return handle;
        }
        if handle.version() != res.latest {
            let resource = res.name.clone();
            let (version, latest) = (handle.version(), res.latest);
            self.graph.errors.push(GraphError::StaleWrite {
                pass,
                resource,
                version,
                latest,
            });
            return handle;
        }
        if access.info().reads && !self.check_readable(handle) {
            return handle;
        }
        let res = &mut self.graph.resources[handle.id().0 as usize];
        res.latest += 1;
        let new = handle.with_version(res.latest);
        if access.info().reads {
            self.decl()
                .reads
                .push((handle.id(), handle.version(), access));
        }
        self.decl().writes.push((new.id(), new.version(), access));
        new
    }

    /// Marks the pass as having effects outside the graph, so it is never culled.
    pub fn side_effect(&mut self) {
        self.decl().side_effect = true;
    }

    /// Gives the pass its work: `record` is called at execution with a context that binds declared
    /// resources by the shader's reflected names.
    pub fn execute(
        mut self,
        record: impl FnOnce(&mut PassContext<'_>) -> crate::Result<()> + 'static,
    ) {
        self.decl().work = PassWork::Callback(Box::new(record));
    }
}
