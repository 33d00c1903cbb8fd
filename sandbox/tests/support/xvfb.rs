//! Running a program in a window under Xvfb (a virtual X server) in tests: start a server on a free
//! display, run the program on it with validation on, and give up after a timeout.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// How long a windowed run may take (lavapipe in a debug build is slow).
pub const TIMEOUT: Duration = Duration::from_secs(300);

/// An Xvfb server on a free display, stopped on drop.
pub struct Xvfb {
    process: Child,
    display: String,
}

impl Xvfb {
    /// Starts a 1024x768 server on a display it picks itself (`-displayfd`), so that tests and
    /// other programs starting servers at the same time never share one.
    pub fn start() -> Result<Self, String> {
        let mut process = Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", "1024x768x24", "-nolisten", "tcp"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .map_err(|e| {
                format!("Xvfb is not installed ({e}): scripts/setup.sh installs it (apt-get install xvfb)")
            })?;
        let stdout = process.stdout.take().expect("piped stdout");
        let (sender, receiver) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let read = BufReader::new(stdout).read_line(&mut line);
            let _ = sender.send(read.map(|_| line));
        });
        let display = match receiver.recv_timeout(Duration::from_secs(10)) {
            Ok(Ok(line)) if line.trim().parse::<u32>().is_ok() => format!(":{}", line.trim()),
            other => {
                let _ = process.kill();
                let _ = process.wait();
                return Err(format!("Xvfb did not report its display: {other:?}"));
            }
        };
        Ok(Self { process, display })
    }

    /// Runs `command` on this display with validation on; fails after [`TIMEOUT`].
    pub fn run(&self, mut command: Command) -> Result<Output, String> {
        let child = command
            .env("DISPLAY", &self.display)
            .env_remove("WAYLAND_DISPLAY")
            .env("LUCID_VALIDATION", "1")
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| format!("starting {command:?}: {e}"))?;
        wait_with_timeout(child, TIMEOUT)
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.process.kill();
        let _ = self.process.wait();
    }
}

fn wait_with_timeout(mut child: Child, timeout: Duration) -> Result<Output, String> {
    let start = Instant::now();
    loop {
        match child.try_wait().map_err(|e| e.to_string())? {
            Some(_) => return child.wait_with_output().map_err(|e| e.to_string()),
            None if start.elapsed() > timeout => {
                let _ = child.kill();
                let output = child.wait_with_output().map_err(|e| e.to_string())?;
                return Err(format!(
                    "the program did not exit within {timeout:?}:\n{}",
                    String::from_utf8_lossy(&output.stderr)
                ));
            }
            None => std::thread::sleep(Duration::from_millis(100)),
        }
    }
}

/// Fails unless the run exited successfully without validation messages; returns its stderr.
pub fn check_clean_exit(output: &Output) -> Result<String, String> {
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    if !output.status.success() {
        return Err(format!("exited with {}:\n{stderr}", output.status));
    }
    if stderr.contains("VUID") || stderr.contains("SYNC-HAZARD") || stderr.contains("panicked") {
        return Err(format!(
            "validation or a panic reported problems:\n{stderr}"
        ));
    }
    Ok(stderr)
}
