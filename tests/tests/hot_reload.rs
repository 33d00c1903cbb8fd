//! Shader hot reload: an edited shader is recompiled and used by the next frame; a compile error is
//! reported with file and line while the previous pipeline stays in use.

use lucid_engine::graph::{Executor, RenderGraph};
use lucid_passes::debug::test_pattern::{self, Params};
use lucid_passes::plumbing::hot_reload::{source_shader_dir, Reload, ShaderWatcher};
use lucid_tests::{assert_no_validation_messages, executor, run};
use std::path::Path;

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap().flatten() {
        let target = to.join(entry.file_name());
        if entry.path().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

fn red_at(executor: &mut Executor, x: u32) -> f32 {
    let mut g = RenderGraph::new();
    let out = test_pattern::add_test_pattern(&mut g, 16, 4, &Params::default());
    let readback = g.readback(out.pattern);
    run(executor, g).image(readback).unwrap().pixels[x as usize][0]
}

#[test]
fn edited_shaders_are_recompiled_and_errors_keep_the_old_pipeline() {
    let root = std::env::temp_dir().join(format!("lucid-hot-reload-{}", std::process::id()));
    copy_dir(&source_shader_dir(), &root);
    let (ctx, mut executor) = executor(false);
    let mut watcher = ShaderWatcher::new(root.clone());
    assert!(watcher.is_available());
    assert_eq!(red_at(&mut executor, 8), 0.5);
    assert_eq!(
        watcher.poll(executor.library()),
        None,
        "nothing changed yet"
    );

    let gradient = root.join("test_pattern/gradient.comp");
    let source = std::fs::read_to_string(&gradient).unwrap();
    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(
        &gradient,
        source.replace("uv * params.gain", "uv * params.gain * 2.0"),
    )
    .unwrap();
    match watcher.poll(executor.library()) {
        Some(Reload::Reloaded(n)) => assert!(n >= 5, "every shader recompiled: {n}"),
        other => panic!("expected a reload, got {other:?}"),
    }
    assert_eq!(red_at(&mut executor, 8), 1.0, "the edited shader is in use");

    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(
        &gradient,
        source.replace("imageStore(", "imageStore(undefined_name, "),
    )
    .unwrap();
    match watcher.poll(executor.library()) {
        Some(Reload::Failed(message)) => {
            assert!(
                message.contains("gradient.comp:"),
                "names the file and line: {message}"
            )
        }
        other => panic!("expected a compile error, got {other:?}"),
    }
    assert_eq!(
        red_at(&mut executor, 8),
        1.0,
        "the previous pipeline stays in use"
    );
    std::fs::remove_dir_all(&root).unwrap();
    drop(executor);
    assert_no_validation_messages(&ctx);
}
