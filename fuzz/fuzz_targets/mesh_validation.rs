//! Arbitrary arrays as a polygon mesh (see `harness::mesh_validation`).
#![no_main]

#[allow(dead_code, unused_imports)] // each target uses one function of the shared harness
#[path = "../harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::mesh_validation(data));
