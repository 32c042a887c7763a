//! Fuzz target: see pqp_fuzz::more_queries (fuzz/src/lib.rs) for what it drives and checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| pqp_fuzz::more_queries(data));
