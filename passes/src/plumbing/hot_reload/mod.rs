//! Shader hot reload: watches the GLSL under `shaders/`, recompiles every embedded shader with
//! `glslc` when a file changes, and swaps the SPIR-V into a [`ShaderLibrary`]. A compile error
//! leaves the previous pipelines in use and is returned for the UI to show.

use crate::shaders::ALL;
use lucid_engine::shader::ShaderLibrary;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::SystemTime;

/// The `shaders/` folder of the source tree this binary was built from.
pub fn source_shader_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(|root| root.join("shaders"))
        .unwrap_or_else(|| PathBuf::from("shaders"))
}

/// Watches a shader folder for changes.
pub struct ShaderWatcher {
    root: PathBuf,
    stamp: Option<SystemTime>,
}

/// What a reload did.
#[derive(Debug, PartialEq, Eq)]
pub enum Reload {
    /// Every shader recompiled and swapped in (the count).
    Reloaded(usize),
    /// A shader failed to compile: glslc's message with file and line; nothing was swapped.
    Failed(String),
}

fn newest(dir: &Path, newest_so_far: &mut Option<SystemTime>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            newest(&path, newest_so_far);
        } else if let Ok(modified) = entry.metadata().and_then(|m| m.modified()) {
            if newest_so_far.is_none_or(|t| modified > t) {
                *newest_so_far = Some(modified);
            }
        }
    }
}

impl ShaderWatcher {
    /// Watches `root` (the folder that holds `common/` and one folder per pass).
    pub fn new(root: PathBuf) -> Self {
        let mut stamp = None;
        newest(&root, &mut stamp);
        Self { root, stamp }
    }

    /// Whether the watched folder exists (a binary moved away from its sources has none).
    pub fn is_available(&self) -> bool {
        self.root.is_dir()
    }

    /// Checks for changes; on one, recompiles every embedded shader and swaps them into `library`.
    pub fn poll(&mut self, library: &ShaderLibrary) -> Option<Reload> {
        let mut stamp = None;
        newest(&self.root, &mut stamp);
        if stamp == self.stamp {
            return None;
        }
        self.stamp = stamp;
        Some(self.reload(library))
    }

    fn reload(&self, library: &ShaderLibrary) -> Reload {
        let glslc = std::env::var("GLSLC").unwrap_or_else(|_| "glslc".into());
        let mut compiled = Vec::with_capacity(ALL.len());
        for shader in ALL {
            let source = self.root.join(shader.path.trim_start_matches("shaders/"));
            let output = Command::new(&glslc)
                .arg("--target-env=vulkan1.2")
                .arg("-I")
                .arg(&self.root)
                .arg(&source)
                .arg("-o")
                .arg("-")
                .output();
            match output {
                Ok(o) if o.status.success() => compiled.push((shader.name, o.stdout)),
                Ok(o) => {
                    return Reload::Failed(String::from_utf8_lossy(&o.stderr).trim().to_string())
                }
                Err(e) => return Reload::Failed(format!("running {glslc}: {e}")),
            }
        }
        for (name, spirv) in &compiled {
            if let Err(e) = library.replace_spirv(name, spirv) {
                return Reload::Failed(e.to_string());
            }
        }
        Reload::Reloaded(compiled.len())
    }
}
