//! Arbitrary bytes as an OBJ file, and as every other mesh format (see `harness::obj_reader`).
#![no_main]

#[allow(dead_code, unused_imports)] // each target uses one function of the shared harness
#[path = "../harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::obj_reader(data));
