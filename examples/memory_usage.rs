//! Bytes per triangle that a built model keeps (`Model::memory_usage`), on the benchmark meshes and
//! on a triangle soup (no shared vertices, the worst case for the shared vertex array); and, through
//! the C ABI (`pqp_model_memory_usage`), once PQP 1.3's view of it has been asked for (the triangles
//! and volumes as double, `pqp_model_tris` and `pqp_model_bvs`; or as float).
//!
//! `cargo run --release --example memory_usage`

mod workloads;

use pqp::Model;
use pqp::capi::*;
use std::path::Path;
use std::ptr;
use workloads::{Tri, read_tris, uv_sphere};

/// Bytes per triangle of a C model of `tris`: bare, with the double view, with the float view.
fn with_views(tris: &[Tri]) -> [f64; 3] {
    let per = |bytes: u64| bytes as f64 / tris.len() as f64;
    // SAFETY: every pointer passed is a live handle or a local out-parameter.
    unsafe {
        let build = || {
            let m = pqp_model_create();
            for &(a, b, c, id) in tris {
                assert_eq!(
                    pqp_model_add_tri(m, a.as_ptr(), b.as_ptr(), c.as_ptr(), id),
                    PQP_OK
                );
            }
            assert_eq!(pqp_model_end(m), PQP_OK);
            m
        };
        let (m, f) = (build(), build());
        let bare = per(pqp_model_memory_usage(m));
        let (mut t, mut b, mut n) = (ptr::null(), ptr::null(), 0);
        assert_eq!(pqp_model_tris(m, &mut t, &mut n), PQP_OK);
        assert_eq!(pqp_model_bvs(m, &mut b, &mut n), PQP_OK);
        let (mut tf, mut bf) = (ptr::null(), ptr::null());
        assert_eq!(pqp_model_tris_float(f, &mut tf, &mut n), PQP_OK);
        assert_eq!(pqp_model_bvs_float(f, &mut bf, &mut n), PQP_OK);
        let out = [
            bare,
            per(pqp_model_memory_usage(m)),
            per(pqp_model_memory_usage(f)),
        ];
        pqp_model_destroy(m);
        pqp_model_destroy(f);
        out
    }
}

fn report(name: &str, tris: &[Tri]) {
    let m = Model::from_triangles(tris.iter().copied()).expect("model");
    let [bare, double, float] = with_views(tris);
    println!(
        "| {name} | {} | {:.1} | {bare:.1} | {double:.1} | {float:.1} |",
        tris.len(),
        m.memory_usage() as f64 / tris.len() as f64
    );
}

fn main() {
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/models");
    println!(
        "| mesh | triangles | bytes/triangle | C handle | with PQP 1.3's view (double) | \
         with the view (float) |\n|---|---:|---:|---:|---:|---:|"
    );
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
