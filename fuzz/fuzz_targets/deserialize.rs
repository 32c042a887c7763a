//! Fuzz target: see pqp_fuzz::deserialize (fuzz/src/lib.rs) for what it drives and checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| pqp_fuzz::deserialize(data));
