//! Compiles every compute shader under `shaders/` with `glslc` into SPIR-V (Vulkan 1.2 target) and
//! keeps debug names (reflection binds by them; drivers optimise the SPIR-V themselves), and
//! generates `shaders.rs`: one module per folder, one `ShaderSource` static per `.comp` file.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let root = manifest
        .parent()
        .expect("passes/ has a parent")
        .to_path_buf();
    let shaders = root.join("shaders");
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("set by cargo"));
    println!("cargo:rerun-if-changed={}", shaders.display());
    println!("cargo:rerun-if-env-changed=GLSLC");
    let glslc = std::env::var("GLSLC").unwrap_or_else(|_| "glslc".into());
    if Command::new(&glslc).arg("--version").output().is_err() {
        fail(&format!(
            "`{glslc}` was not found. Lucid compiles its GLSL shaders with glslc: install it with \
             `apt-get install glslc` (Debian/Ubuntu), or set GLSLC to its path."
        ));
    }
    let mut sources = Vec::new();
    collect(&shaders, &mut sources);
    sources.sort();
    let jobs: Vec<_> = sources
        .iter()
        .map(|src| {
            let rel = src
                .strip_prefix(&shaders)
                .expect("under shaders/")
                .to_path_buf();
            let spv = out.join(rel.with_extension("spv"));
            std::fs::create_dir_all(spv.parent().expect("has parent"))
                .expect("create OUT_DIR subfolder");
            let (glslc, shaders, src) = (glslc.clone(), shaders.clone(), src.clone());
            let spv2 = spv.clone();
            let handle = std::thread::spawn(move || {
                Command::new(&glslc)
                    .arg("--target-env=vulkan1.2")
                    .arg("-I")
                    .arg(&shaders)
                    .arg(&src)
                    .arg("-o")
                    .arg(&spv2)
                    .output()
            });
            (rel, spv, handle)
        })
        .collect();
    let mut errors = String::new();
    let mut modules: std::collections::BTreeMap<String, Vec<(String, String, PathBuf)>> =
        Default::default();
    for (rel, spv, handle) in jobs {
        let output = handle.join().expect("glslc thread").expect("run glslc");
        if !output.status.success() {
            errors.push_str(&String::from_utf8_lossy(&output.stderr));
            errors.push_str(&String::from_utf8_lossy(&output.stdout));
            continue;
        }
        let folder = rel
            .parent()
            .map(|p| p.to_string_lossy().replace(['/', '\\', '-'], "_"))
            .unwrap_or_default();
        let stem = rel
            .file_stem()
            .expect("file")
            .to_string_lossy()
            .into_owned();
        let name = format!(
            "{}/{}",
            rel.parent()
                .map(|p| p.to_string_lossy().into_owned())
                .unwrap_or_default(),
            stem
        );
        modules.entry(folder).or_default().push((stem, name, spv));
    }
    if !errors.is_empty() {
        fail(&format!("shader compilation failed:\n{errors}"));
    }
    let mut code = String::new();
    let mut all = Vec::new();
    for (folder, files) in &modules {
        let _ = writeln!(code, "/// Shaders in `shaders/{folder}/`.\npub mod {folder} {{\n    use lucid_engine::shader::ShaderSource;");
        for (stem, name, spv) in files {
            let ident = stem.to_uppercase().replace('-', "_");
            let _ = writeln!(
                code,
                "    /// `shaders/{name}.comp`.\n    pub static {ident}: ShaderSource = ShaderSource {{ name: {name:?}, path: {path:?}, spirv: include_bytes!({spv:?}) }};",
                path = format!("shaders/{name}.comp"),
                spv = spv.display().to_string(),
            );
            all.push(format!("&{folder}::{ident}"));
        }
        code.push_str("}\n");
    }
    let _ = writeln!(
        code,
        "/// Every embedded shader (for hot reload and listings).\npub static ALL: &[&lucid_engine::shader::ShaderSource] = &[{}];",
        all.join(", ")
    );
    std::fs::write(out.join("shaders.rs"), code).expect("write shaders.rs");
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect(&path, out);
        } else if path.extension().is_some_and(|e| e == "comp") {
            out.push(path);
        }
    }
}

fn fail(message: &str) -> ! {
    for line in message.lines() {
        println!("cargo:warning={line}");
    }
    eprintln!("{message}");
    std::process::exit(1);
}
