//! Typed, versioned resource handles. Writing a resource yields a new version, so the order of
//! writers is explicit and a pass cannot read a version that was never written.

use std::fmt;

/// Index of a resource declared in one graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ResourceId(pub u32);

/// A version of an image resource.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ImageHandle {
    pub(crate) id: ResourceId,
    pub(crate) version: u32,
}

/// A version of a buffer resource.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BufferHandle {
    pub(crate) id: ResourceId,
    pub(crate) version: u32,
}

/// What both handle types share: the graph uses it to treat images and buffers alike.
pub trait Handle: Copy + fmt::Debug {
    /// The resource.
    fn id(&self) -> ResourceId;
    /// The version (0: contents at frame start).
    fn version(&self) -> u32;
    /// The same resource at another version.
    fn with_version(self, version: u32) -> Self;
    /// Whether it is an image.
    const IS_IMAGE: bool;
}

impl Handle for ImageHandle {
    fn id(&self) -> ResourceId {
        self.id
    }
    fn version(&self) -> u32 {
        self.version
    }
    fn with_version(self, version: u32) -> Self {
        Self { version, ..self }
    }
    const IS_IMAGE: bool = true;
}

impl Handle for BufferHandle {
    fn id(&self) -> ResourceId {
        self.id
    }
    fn version(&self) -> u32 {
        self.version
    }
    fn with_version(self, version: u32) -> Self {
        Self { version, ..self }
    }
    const IS_IMAGE: bool = false;
}

/// A temporal (history) image: `prev` holds what `cur` held last frame. Write `cur` each frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TemporalImage {
    /// Last frame's contents (read-only this frame; cleared to zero after a reset).
    pub prev: ImageHandle,
    /// This frame's history, to be written.
    pub cur: ImageHandle,
}
