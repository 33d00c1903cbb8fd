//! Atomic writes: a write that fails part way leaves the old file as it was and no temporary file
//! behind; one that succeeds replaces it.

use std::io;
use std::path::PathBuf;

use lucid_engine::atomic_write::{write_atomic, write_atomic_with};

fn folder(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lucid-atomic-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn entries(dir: &PathBuf) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_failed_write_leaves_the_old_file_intact() {
    let dir = folder("fail");
    let path = dir.join("image.png");
    std::fs::write(&path, b"the good image").unwrap();
    let result = write_atomic_with(&path, |file| {
        file.write_all(b"half an ima")?;
        Err(io::Error::new(io::ErrorKind::StorageFull, "disk full"))
    });
    assert_eq!(result.unwrap_err().kind(), io::ErrorKind::StorageFull);
    assert_eq!(std::fs::read(&path).unwrap(), b"the good image");
    assert_eq!(entries(&dir), ["image.png"], "no temporary file is left");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_successful_write_replaces_the_file() {
    let dir = folder("ok");
    let path = dir.join("metrics.csv");
    std::fs::write(&path, b"old, longer contents").unwrap();
    write_atomic(&path, b"new").unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"new");
    assert_eq!(entries(&dir), ["metrics.csv"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_missing_folder_is_an_error() {
    let path = folder("missing").join("no/such/folder/x.json");
    assert_eq!(
        write_atomic(&path, b"{}").unwrap_err().kind(),
        io::ErrorKind::NotFound
    );
}
