//! Arbitrary arrays through the C ABI pipeline (see `harness::ffi_pipeline`).
#![no_main]

#[allow(dead_code, unused_imports)] // each target uses one function of the shared harness
#[path = "../harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::ffi_pipeline(data));
