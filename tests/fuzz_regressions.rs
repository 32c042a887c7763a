//! Replays the fuzz targets' committed inputs on stable, through the same checks the fuzz targets
//! run (fuzz/src/lib.rs, compiled here as a module): every seed of `fuzz/corpus/TARGET/` and every
//! input of `fuzz/regressions/TARGET/` (each crash a fuzzer found, kept once fixed). A crash
//! that is a library bug not yet fixed has its own `#[ignore]`d test below instead.

// The fuzz crate is edition 2021, where an unsafe fn's body is an unsafe block.
#[path = "../fuzz/src/lib.rs"]
#[allow(dead_code, unsafe_op_in_unsafe_fn)]
mod fuzz_checks;

use std::path::Path;

/// Runs `check` on every file of `fuzz/corpus/TARGET` and `fuzz/regressions/TARGET`; returns how
/// many it ran.
fn replay(target: &str, check: fn(&[u8])) -> usize {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    let mut n = 0;
    for dir in ["corpus", "regressions"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir).join(target)) else {
            continue;
        };
        let mut files: Vec<_> = entries.map(|e| e.unwrap().path()).collect();
        files.sort();
        for f in files {
            let data = std::fs::read(&f).unwrap();
            let r = std::panic::catch_unwind(|| check(&data));
            assert!(r.is_ok(), "{} fails its checks", f.display());
            n += 1;
        }
    }
    n
}

#[test]
fn build_protocol_inputs() {
    assert!(replay("build_protocol", fuzz_checks::build_protocol) >= 10);
}

#[test]
fn query_inputs() {
    assert!(replay("queries", fuzz_checks::queries) >= 10);
}

#[test]
fn more_query_inputs() {
    assert!(replay("more_queries", fuzz_checks::more_queries) >= 10);
}

#[test]
fn convex_inputs() {
    assert!(replay("convex", fuzz_checks::convex) >= 10);
}

#[test]
fn deserialize_inputs() {
    assert!(replay("deserialize", fuzz_checks::deserialize) >= 10);
}

/// Found by the convex fuzz target: the hull of a valid tetrahedron whose coordinates mix 1e140
/// and 1e-140 failed with PQP_ERR_INTERNAL (coordinates of any magnitude up to 1e150 are
/// accepted): a face's area vector, taken after scaling the whole set to at most 1, underflowed
/// to zero. Area vectors are now rescaled per face and fall back to exact integers.
#[test]
fn hull_of_extreme_spread() {
    use pqp::capi::*;
    let pts = [
        1e140, 0.0, 0.0, //
        0.0, 1e-140, 0.0, //
        0.0, 0.0, 1e-140, //
        0.0, 0.0, 0.0,
    ];
    let mut m = std::ptr::null_mut();
    let rc = unsafe { pqp_convex_model_from_points(&mut m, pts.as_ptr(), 4) };
    assert_eq!(rc, PQP_OK);
    assert_eq!(unsafe { pqp_convex_model_num_vertices(m) }, 4);
    unsafe { pqp_convex_model_destroy(m) };
}

/// The same bug seen from the other side (fuzz regression `convex/hull-faces-refused`): the hull
/// of five points mixing 1e140, 1e-140 and ordinary values came back from
/// pqp_convex_model_from_points as five vertices, but its own faces, fanned into triangles, were
/// refused by pqp_convex_model_from_triangles (PQP_ERR_INVALID_CONVEX_MESH): a face's underflowed
/// area vector chose a coordinate plane the face projects onto as a segment.
#[test]
fn hull_faces_of_extreme_spread() {
    use pqp::capi::*;
    let xyz = [
        -4.0,
        -4.0,
        -2.28125, //
        -2.15625,
        -2.71875e140,
        2.53125e-140, //
        -2.03125,
        -2.03125,
        2.5, //
        2.5e-140,
        2.5e-140,
        -2.03125e-140, //
        2.5e-140,
        2.5e-140,
        2.5e-140,
    ];
    let mut hull = std::ptr::null_mut();
    assert_eq!(
        unsafe { pqp_convex_model_from_points(&mut hull, xyz.as_ptr(), 5) },
        PQP_OK
    );
    assert_eq!(unsafe { pqp_convex_model_num_vertices(hull) }, 5);
    unsafe { pqp_convex_model_destroy(hull) };
    let idx = [0, 1, 2, 1, 4, 2, 2, 4, 3, 2, 3, 0, 4, 1, 3, 1, 0, 3];
    let mut m = std::ptr::null_mut();
    let rc = unsafe { pqp_convex_model_from_triangles(&mut m, xyz.as_ptr(), 5, idx.as_ptr(), 6) };
    assert_eq!(rc, PQP_OK);
    unsafe { pqp_convex_model_destroy(m) };
}
