//! Build time of the benchmark spheres (40,000 and 1,000,000 triangles), and a fingerprint of each
//! built model (FNV-1a of its saved bytes: equal fingerprints, the same hierarchy bit for bit).
//!
//! `cargo run --release --example build_speed [-- --rounds N] [--only 40k|1m] [--threads T] [--cpu]
//! [--end]` (`--threads`: `Model::end_threads(T)`, 0 every core; default 1, `Model::end`)
//!
//! `--end`: time the build call alone (`Model::end_threads`), without the triangles' adds before
//! it, which are on one thread whatever `--threads` says.
//!
//! `--cpu`: time on the processor (this thread's, from `/proc/thread-self/schedstat`, Linux)
//! rather than elapsed time, so that a loaded machine's preemptions do not count (one thread only:
//! with `--threads` above 1 the other threads' time is not counted).

mod workloads;

use pqp::Model;
use std::time::Instant;
use workloads::{Tri, median, uv_sphere};

fn fingerprint(m: &Model) -> u64 {
    let bytes = m.to_bytes().expect("saved bytes");
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
    })
}

/// A model of `tris`, begun and added to, not yet built.
fn added(tris: &[Tri]) -> Model {
    let mut m = Model::new();
    m.begin(tris.len()).unwrap();
    for &(a, b, c, id) in tris {
        m.add_triangle(a, b, c, id).unwrap();
    }
    m
}

/// This thread's time on the processor so far, in ms (Linux), or `None`.
fn cpu_ms() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-6)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1).cloned())
    };
    let rounds: usize = arg("--rounds").map_or(5, |r| r.parse().expect("--rounds N"));
    let only = arg("--only");
    let threads: usize = arg("--threads").map_or(1, |t| t.parse().expect("--threads T"));
    let cpu = args.iter().any(|a| a == "--cpu");
    let end_only = args.iter().any(|a| a == "--end");
    for (name, lat, lon) in [("40k", 101, 200), ("1m", 501, 1000)] {
        if only.as_deref().is_some_and(|o| o != name) {
            continue;
        }
        let tris = uv_sphere(1.0, lat, lon);
        let mut times = Vec::new();
        let mut print = 0;
        for _ in 0..rounds {
            // With `--end` the clocks start after the adds.
            let mut m = if end_only { added(&tris) } else { Model::new() };
            let (t, c) = (Instant::now(), cpu_ms());
            if !end_only {
                m = added(&tris);
            }
            m.end_threads(threads).unwrap();
            times.push(match (cpu, c, cpu_ms()) {
                (true, Some(c0), Some(c1)) => c1 - c0,
                _ => t.elapsed().as_secs_f64() * 1e3,
            });
            print = fingerprint(&m);
        }
        println!(
            "{name}: {} triangles, {} {:.2} ms (median of {rounds}, {threads} threads), tree {print:016x}",
            tris.len(),
            if end_only { "end" } else { "build" },
            median(times)
        );
    }
}
