//! Running the `lucid` binary in tests: with validation on, into per-process temporary paths.

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs `lucid` with `args` and validation on; its output.
pub fn lucid(args: &[&str]) -> Output {
    lucid_with_env(args, &[])
}

/// Runs `lucid` with `args`, validation on and the environment variables `env`; its output.
pub fn lucid_with_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lucid"))
        .args(args)
        .env("LUCID_VALIDATION", "1")
        .envs(env.iter().copied())
        .output()
        .expect("run lucid")
}

/// A path in the temporary folder, unique to this test process and `name`.
pub fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("lucid-test-{}-{name}", std::process::id()))
}

/// The run's standard error, as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}
