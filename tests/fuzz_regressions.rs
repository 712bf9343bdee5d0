//! Replays the fuzz inputs kept under `fuzz/regressions/<target>/` (crashes found by
//! `scripts/fuzz.sh`, once fixed, and hand-made seeds) through the same code the fuzz
//! targets run (`fuzz/harness.rs`), so a crash once fixed stays fixed without nightly Rust.

#[allow(dead_code)]
mod harness {
    include!("../fuzz/harness.rs");
}

fn replay(target: &str, run: fn(&[u8])) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/regressions")
        .join(target);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{} holds no inputs", dir.display());
    for file in files {
        let data = std::fs::read(&file).unwrap();
        if std::panic::catch_unwind(|| run(&data)).is_err() {
            panic!("{} fails again", file.display());
        }
    }
}

#[test]
fn obj_reader() {
    replay("obj_reader", harness::obj_reader);
}

#[test]
fn mesh_validation() {
    replay("mesh_validation", harness::mesh_validation);
}

#[test]
fn ffi_pipeline() {
    replay("ffi_pipeline", harness::ffi_pipeline);
}
