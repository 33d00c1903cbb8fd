//! The render graph's setup and execution errors.

use crate::access::Access;
use thiserror::Error;

/// A graph that was set up wrongly, or could not be executed as declared.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum GraphError {
    /// A handle that does not belong to this graph (or of the wrong type).
    #[error("pass {pass} uses a handle that does not belong to this graph")]
    UnknownHandle {
        /// The pass.
        pass: String,
    },
    /// A transient read before any pass wrote it.
    #[error("pass {pass} reads {resource}, which no earlier pass wrote")]
    ReadUnwritten {
        /// The pass.
        pass: String,
        /// The resource.
        resource: String,
    },
    /// A read of a version that a later-declared write already replaced.
    #[error("pass {pass} reads {resource} version {version}, but it was already overwritten (latest version {latest}); declare the read before the write")]
    ReadOverwritten {
        /// The pass.
        pass: String,
        /// The resource.
        resource: String,
        /// The version read.
        version: u32,
        /// The latest version.
        latest: u32,
    },
    /// A write through a handle that is not the latest version.
    #[error("pass {pass} writes {resource} through version {version}, but the latest is {latest}: use the handle returned by the last write")]
    StaleWrite {
        /// The pass.
        pass: String,
        /// The resource.
        resource: String,
        /// The version given.
        version: u32,
        /// The latest version.
        latest: u32,
    },
    /// `read` with an access that writes.
    #[error("pass {pass} declares a read with the writing access {access:?}; use write()")]
    WriteAccessInRead {
        /// The pass.
        pass: String,
        /// The access.
        access: Access,
    },
    /// `write` with an access that does not write.
    #[error("pass {pass} declares a write with the read-only access {access:?}; use read()")]
    ReadAccessInWrite {
        /// The pass.
        pass: String,
        /// The access.
        access: Access,
    },
    /// A write to the previous frame's history.
    #[error(
        "pass {pass} writes {resource}, last frame's history, which is read-only: write `cur`"
    )]
    WritePrevHistory {
        /// The pass.
        pass: String,
        /// The resource.
        resource: String,
    },
    /// Two temporal resources with one key in one graph.
    #[error("temporal key {0:?} is declared twice in one graph")]
    DuplicateTemporalKey(String),
    /// A pass that was never given work.
    #[error("pass {0} has no execute callback")]
    NoWork(String),
    /// A pass bound a resource it did not declare.
    #[error("pass {pass} binds {resource} as {binding} without declaring that version with read() or write()")]
    Undeclared {
        /// The pass.
        pass: String,
        /// The resource.
        resource: String,
        /// The shader binding.
        binding: String,
    },
    /// A graph declared by description only was executed.
    #[error("resource {0} was imported by description only and cannot be executed")]
    DescribedOnly(String),
    /// An imported resource lacks a usage flag that its accesses need.
    #[error("imported {resource} lacks usage {missing}")]
    ImportUsage {
        /// The resource.
        resource: String,
        /// What is missing.
        missing: String,
    },
    /// A readback that does not belong to the frame, or of the wrong kind.
    #[error("readback {0} is not available in this frame's outputs")]
    NoSuchReadback(usize),
}
