//! Errors raised while building, importing or validating scenes.

use std::path::PathBuf;

/// Everything that can go wrong with a scene.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// `builtin::build` was asked for a name it does not know.
    #[error("unknown built-in scene `{name}`; available: {available}")]
    UnknownScene {
        /// The requested name.
        name: String,
        /// Comma separated list of valid names.
        available: String,
    },
    /// A material parameter is out of range and cannot be clamped.
    #[error("material `{name}`: {reason}")]
    InvalidMaterial {
        /// Material name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// A mesh is malformed (index out of range, NaN position, ...).
    #[error("mesh `{name}`: {reason}")]
    InvalidMesh {
        /// Mesh name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// A texture is malformed.
    #[error("texture `{name}`: {reason}")]
    InvalidTexture {
        /// Texture name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// Some other scene-level inconsistency.
    #[error("invalid scene: {0}")]
    Invalid(String),
    /// A camera path file could not be parsed.
    #[error("camera path, line {line}: {message}")]
    PathParse {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// An environment map could not be loaded.
    #[error("environment map {}: {message}", path.display())]
    EnvironmentMap {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A glTF file could not be imported.
    #[error("{file}: {message}")]
    Gltf {
        /// The file (or a label for in-memory input).
        file: String,
        /// What is wrong.
        message: String,
    },
}
