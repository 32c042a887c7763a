//! Fuzz target: see pqp_fuzz::convex (fuzz/src/lib.rs) for what it drives and checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| pqp_fuzz::convex(data));
