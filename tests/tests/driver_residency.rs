//! Threads that rendered and end while another thread creates and drops contexts, as a test
//! harness's threads and an application's worker threads do. On NVIDIA (driver 580, H200) the
//! Vulkan loader unloaded the driver with each process's last instance, and loaded it again for
//! the next; a thread that had used the driver then ran the driver's stale thread-exit hook when it
//! ended: `traversal_gpu`, whose shorter test ends while its longer test cycles contexts, crashed
//! in 10 of 12 runs. The engine keeps the drivers loaded (`engine/src/context/driver_residency.rs`).
//! Without that, this test crashed (segmentation fault) in 4 of 12 runs on the H200; with it, in
//! none of 12. It holds the binary alone, so that no other test's context keeps the drivers loaded.

use lucid_passes::renderer::Algorithm;
use lucid_tests::render::{render_once, scene};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// One context's life on the calling thread: a 16x16 path-traced Cornell box, checked for light.
fn render_on_a_fresh_context(what: &str) {
    let image = render_once(scene("cornell-box"), Algorithm::PathTracing, 1, 4, 16);
    let lit = image
        .pixels
        .iter()
        .filter(|p| p[0] + p[1] + p[2] > 0.0)
        .count();
    assert!(lit > 0, "{what}: a black image");
}

#[test]
fn threads_that_rendered_end_safely_while_contexts_come_and_go() {
    let stop = Arc::new(AtomicBool::new(false));
    let cycler = {
        let stop = Arc::clone(&stop);
        std::thread::spawn(move || {
            let mut cycles = 0;
            while !stop.load(Ordering::Relaxed) || cycles == 0 {
                render_on_a_fresh_context(&format!("cycling context {cycles}"));
                cycles += 1;
            }
        })
    };
    for round in 0..4 {
        std::thread::spawn(move || {
            render_on_a_fresh_context(&format!("short-lived thread {round}"))
        })
        .join()
        .expect("a short-lived thread panicked");
    }
    stop.store(true, Ordering::Relaxed);
    cycler.join().expect("the cycling thread panicked");
}
