//! Bytes per triangle that a built model keeps (`Model::memory_usage`), on the benchmark meshes and
//! on a triangle soup (no shared vertices, the worst case for the shared vertex array).
//!
//! `cargo run --release --example memory_usage`

mod workloads;

use pqp::Model;
use std::path::Path;
use workloads::{read_tris, uv_sphere, Tri};

fn report(name: &str, tris: &[Tri]) {
    let m = Model::from_triangles(tris.iter().copied()).expect("model");
    println!(
        "| {name} | {} | {:.1} |",
        tris.len(),
        m.memory_usage() as f64 / tris.len() as f64
    );
}

fn main() {
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/models");
    println!("| mesh | triangles | bytes/triangle |\n|---|---:|---:|");
    report("sphere 40k", &uv_sphere(1.0, 101, 200));
    report("sphere 1M", &uv_sphere(1.0, 501, 1000));
    for name in ["bunny", "torus"] {
        report(
            name,
            &read_tris(&models.join(format!("{name}.tris"))).expect("model"),
        );
    }
    // The bunny as a soup: every triangle nudged so that no two share a vertex.
    let bunny = read_tris(&models.join("bunny.tris")).expect("model");
    let soup: Vec<Tri> = bunny
        .iter()
        .enumerate()
        .map(|(i, &(a, b, c, id))| {
            let e = 1e-9 * (i + 1) as f64;
            let nudge = |p: [f64; 3]| [p[0] + e, p[1], p[2]];
            (nudge(a), nudge(b), nudge(c), id)
        })
        .collect();
    report("bunny as a soup", &soup);
}
