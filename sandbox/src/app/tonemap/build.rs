//! The sandbox's build script: compiles the app's tone-mapping shader with `glslc` into OUT_DIR
//! (the same compiler and target as the `lucid-passes` shaders).

use std::path::PathBuf;
use std::process::Command;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("set by cargo"));
    let source = manifest.join("src/app/tonemap/tonemap.comp");
    println!("cargo:rerun-if-changed={}", source.display());
    println!("cargo:rerun-if-env-changed=GLSLC");
    let glslc = std::env::var("GLSLC").unwrap_or_else(|_| "glslc".into());
    let result = Command::new(&glslc)
        .args(["--target-env=vulkan1.2", "-O", "-g"])
        .arg(&source)
        .arg("-o")
        .arg(out.join("tonemap.spv"))
        .output();
    match result {
        Ok(output) if output.status.success() => {}
        Ok(output) => fail(&format!(
            "compiling {} failed:\n{}",
            source.display(),
            String::from_utf8_lossy(&output.stderr)
        )),
        Err(e) => fail(&format!(
            "`{glslc}` could not be run ({e}): install it with `apt-get install glslc`, or set GLSLC"
        )),
    }
}

fn fail(message: &str) -> ! {
    for line in message.lines() {
        println!("cargo:warning={line}");
    }
    eprintln!("{message}");
    std::process::exit(1);
}
