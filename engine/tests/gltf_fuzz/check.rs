//! Runs one import under a deadline: a panic, a hang, or an error that does not name the file
//! fails the case.

use std::path::PathBuf;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use lucid_engine::scene::gpu::{pack_flat, BvhLayout};
use lucid_engine::scene::{load_gltf_slice, Bvh, FlatScene};

/// The longest an import of a small file (and the CPU preparation of what it loads) may take
/// before it counts as a hang.
pub const DEADLINE: Duration = Duration::from_secs(10);

/// Imports `data` as `label` on its own thread and, when it loads, prepares it for the GPU as
/// `Renderer::new` does (flattening, BVH, packing). Returns the error message, if any.
pub fn import(data: Vec<u8>, label: &'static str) -> Result<(), String> {
    let (done, finished) = mpsc::channel();
    let base = Some(super::corpus::dir());
    std::thread::spawn(move || {
        let _ = done.send(import_and_prepare(&data, base, label));
    });
    match finished.recv_timeout(DEADLINE) {
        Ok(Ok(())) => Ok(()),
        Ok(Err(message)) => {
            assert!(
                message.contains(label),
                "the error does not name the file {label}: {message}"
            );
            assert!(
                !message.contains('\n'),
                "the error is not one line: {message}"
            );
            Err(message)
        }
        Err(RecvTimeoutError::Timeout) => panic!("import hung for more than {DEADLINE:?}"),
        Err(RecvTimeoutError::Disconnected) => panic!("import panicked (see the message above)"),
    }
}

fn import_and_prepare(data: &[u8], base: Option<PathBuf>, label: &str) -> Result<(), String> {
    let scene = load_gltf_slice(data, base.as_deref(), label).map_err(|e| e.to_string())?;
    let flat = FlatScene::new(&scene, &[]);
    let bvh = Bvh::build(&flat.scene);
    for layout in BvhLayout::ALL {
        let _ = pack_flat(&flat, &scene, &bvh, layout);
    }
    Ok(())
}
