//! Fuzz target: see pqp_fuzz::queries (fuzz/src/lib.rs) for what it drives and checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| pqp_fuzz::queries(data));
