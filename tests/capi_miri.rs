//! The C ABI driven from Rust on tiny models, small enough for Miri (`.ci/run` runs
//! `cargo +nightly miri test --test capi_miri`; plain `cargo test` runs it too): every handle's
//! create, use and destroy, the PQP 1.3 views, clone, convex models, saved models, NULL pointers
//! and error paths.
//! create, use and destroy, the PQP 1.3 views, clone, convex models, ray casts (single and batched
//! on two threads), NULL pointers and error paths.
//! Miri checks what the C ABI does with the pointers it is given and hands out (out-of-bounds
//! reads and writes, use after free, leaks, invalid references).

use pqp::capi::*;
use std::ffi::{CStr, c_int};
use std::ptr::{null, null_mut};

const I: [f64; 9] = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
const O: [f64; 3] = [0.0; 3];

/// A unit right triangle in the xy-plane, lifted to height z.
fn tri(z: f64) -> [[f64; 3]; 3] {
    [[0.0, 0.0, z], [1.0, 0.0, z], [0.0, 1.0, z]]
}

/// A built model of the given triangles, ids 10, 11, ... (free it with pqp_model_destroy).
fn model(tris: &[[[f64; 3]; 3]]) -> *mut pqp_model {
    let m = pqp_model_create();
    assert!(!m.is_null());
    // SAFETY: m is a live handle just created; every vertex pointer points to 3 doubles.
    unsafe {
        assert_eq!(pqp_model_begin(m, tris.len() as c_int), PQP_OK);
        for (i, t) in tris.iter().enumerate() {
            let rc = pqp_model_add_tri(
                m,
                t[0].as_ptr(),
                t[1].as_ptr(),
                t[2].as_ptr(),
                10 + i as c_int,
            );
            assert_eq!(rc, PQP_OK);
        }
        assert_eq!(pqp_model_end(m), PQP_OK);
    }
    m
}

#[test]
fn build_views_clone_destroy() {
    unsafe {
        let m = pqp_model_create();
        assert_eq!(pqp_model_build_state(m), PQP_BUILD_STATE_EMPTY);
        assert_eq!(pqp_model_end(m), PQP_ERR_BUILD_EMPTY_MODEL);
        let t = tri(0.0);
        let bad = [f64::NAN, 0.0, 0.0];
        assert_eq!(
            pqp_model_add_tri(m, bad.as_ptr(), t[1].as_ptr(), t[2].as_ptr(), 1),
            PQP_ERR_NONFINITE_COORDINATE
        );
        assert_eq!(pqp_model_build_state(m), PQP_BUILD_STATE_BEGUN);
        for k in 0..3 {
            let t = tri(k as f64);
            assert_eq!(
                pqp_model_add_tri(m, t[0].as_ptr(), t[1].as_ptr(), t[2].as_ptr(), k),
                PQP_OK
            );
        }
        // A view of a model being built, then invalidated by the build.
        let mut tris: *const pqp_tri = null();
        let mut n = 0;
        assert_eq!(pqp_model_tris(m, &mut tris, &mut n), PQP_OK);
        assert_eq!(n, 3);
        assert_eq!((*tris.add(2)).p1[2], 2.0);
        let mut bvs: *const pqp_bv = null();
        let mut nb = 0;
        assert_eq!(
            pqp_model_bvs(m, &mut bvs, &mut nb),
            PQP_ERR_UNPROCESSED_MODEL
        );
        assert_eq!(pqp_model_set_volume(m, PQP_BV_HYBRID), PQP_OK);
        assert_eq!(pqp_model_set_volume(m, 99), PQP_ERR_INVALID_ARGUMENT);
        assert_eq!(pqp_model_end(m), PQP_OK);
        assert_eq!(pqp_model_end(m), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        let t = tri(5.0);
        assert_eq!(
            pqp_model_add_tri(m, t[0].as_ptr(), t[1].as_ptr(), t[2].as_ptr(), 9),
            PQP_ERR_BUILD_OUT_OF_SEQUENCE
        );
        assert_eq!(pqp_model_num_tris(m), 3);
        assert!(pqp_model_memory_usage(m) > 0);

        // Both views, both precisions; every volume read.
        assert_eq!(pqp_model_tris(m, &mut tris, &mut n), PQP_OK);
        assert_eq!(pqp_model_bvs(m, &mut bvs, &mut nb), PQP_OK);
        assert_eq!(nb, 5);
        let bs = std::slice::from_raw_parts(bvs, nb as usize);
        let leaves = bs.iter().filter(|b| b.first_child < 0).count();
        assert_eq!(leaves, 3);
        let mut tf: *const pqp_tri_float = null();
        let mut bf: *const pqp_bv_float = null();
        let (mut nf, mut nbf) = (0, 0);
        assert_eq!(pqp_model_tris_float(m, &mut tf, &mut nf), PQP_OK);
        assert_eq!(pqp_model_bvs_float(m, &mut bf, &mut nbf), PQP_OK);
        assert_eq!((nf, nbf), (3, 5));
        assert_eq!((*tf.add(1)).p2[0], 1.0f32);
        assert_eq!(std::slice::from_raw_parts(bf, 5).len(), 5);

        // PQP's volume functions on the view.
        let mut fit = bs[0];
        let tr = std::slice::from_raw_parts(tris, 3);
        assert_eq!(pqp_bv_fit(&mut fit, I.as_ptr(), tr.as_ptr(), 3), PQP_OK);
        assert_eq!(
            pqp_bv_fit(&mut fit, I.as_ptr(), tr.as_ptr(), 0),
            PQP_ERR_INVALID_ARGUMENT
        );
        let mut overlap = -1;
        assert_eq!(
            pqp_bv_overlap(&mut overlap, I.as_ptr(), O.as_ptr(), &bs[0], &bs[1]),
            PQP_OK
        );
        assert_eq!(overlap, 1);
        let mut d = -1.0;
        assert_eq!(
            pqp_bv_distance(&mut d, I.as_ptr(), O.as_ptr(), &bs[0], &fit),
            PQP_OK
        );
        assert!(d <= 0.0);

        // A clone outlives its original and answers alike.
        let mut copy = null_mut();
        assert_eq!(pqp_model_clone(&mut copy, m), PQP_OK);
        pqp_model_destroy(m);
        assert_eq!(pqp_model_is_built(copy), 1);
        assert_eq!(pqp_model_tris(copy, &mut tris, &mut n), PQP_OK);
        assert_eq!((n, (*tris).id), (3, 0));
        // begin on a built model clears it (and says so).
        assert_eq!(
            pqp_model_begin(copy, 1 << 30),
            PQP_ERR_BUILD_OUT_OF_SEQUENCE
        );
        assert_eq!(pqp_model_num_tris(copy), 0);
        pqp_model_destroy(copy);
        pqp_model_destroy(null_mut());
    }
}

#[test]
fn queries_and_results() {
    unsafe {
        let a = model(&[tri(0.0), tri(1.0)]);
        let b = model(&[tri(0.0)]);
        let up = [0.25, 0.25, 3.0];

        let c = pqp_collide_result_create();
        assert_eq!(
            pqp_collide(
                c,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                O.as_ptr(),
                b,
                PQP_ALL_CONTACTS
            ),
            PQP_OK
        );
        assert_eq!(pqp_collide_result_num_pairs(c), 1);
        let pairs = std::slice::from_raw_parts(pqp_collide_result_pairs(c), 1);
        assert_eq!((pairs[0].id1, pairs[0].id2), (10, 10));
        assert_eq!(pqp_collide_result_id1(c, 5), -1);
        pqp_collide_result_free_pairs(c);
        assert_eq!(pqp_collide_result_num_pairs(c), 0);
        assert_eq!(
            pqp_collide(c, I.as_ptr(), O.as_ptr(), a, I.as_ptr(), O.as_ptr(), b, 7),
            PQP_ERR_INVALID_ARGUMENT
        );
        assert_eq!(
            pqp_collide(c, null(), O.as_ptr(), a, I.as_ptr(), O.as_ptr(), b, 1),
            PQP_ERR_NULL_POINTER
        );
        pqp_collide_result_destroy(c);

        let d = pqp_distance_result_create();
        assert!(
            pqp_distance_result_distance(d).is_infinite()
                || pqp_distance_result_distance(d).is_nan()
        );
        assert_eq!(
            pqp_distance(
                d,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                up.as_ptr(),
                b,
                0.0,
                0.0,
                2
            ),
            PQP_OK
        );
        assert_eq!(pqp_distance_result_distance(d), 2.0);
        let p1 = std::slice::from_raw_parts(pqp_distance_result_p1(d), 3);
        assert_eq!(p1[2], 1.0);
        let (mut t1, mut t2) = (-5, -5);
        assert_eq!(pqp_distance_result_triangles(d, &mut t1, &mut t2), PQP_OK);
        assert_eq!((t1, t2, pqp_distance_result_id1(d)), (1, 0, 11));
        // Reuse (cache, front) with every strategy.
        for strategy in [
            PQP_SEARCH_AUTO,
            PQP_SEARCH_DEPTH_FIRST,
            PQP_SEARCH_BREADTH_FIRST,
            PQP_SEARCH_PRIORITY,
        ] {
            let mut o = pqp_search_options_default();
            o.strategy = strategy;
            o.qsize = 1;
            assert_eq!(
                pqp_distance_search(
                    d,
                    I.as_ptr(),
                    O.as_ptr(),
                    a,
                    I.as_ptr(),
                    up.as_ptr(),
                    b,
                    0.1,
                    1.0,
                    &o
                ),
                PQP_OK
            );
            assert!(pqp_distance_result_distance(d) >= 2.0);
        }
        let mut o = pqp_search_options_default();
        o.triangle_cache = 2;
        assert_eq!(
            pqp_distance_search(
                d,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                up.as_ptr(),
                b,
                0.0,
                0.0,
                &o
            ),
            PQP_ERR_INVALID_ARGUMENT
        );
        assert_eq!(
            pqp_distance(
                d,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                up.as_ptr(),
                b,
                f64::NAN,
                0.0,
                2
            ),
            PQP_ERR_INVALID_ARGUMENT
        );
        let nan_t = [f64::NAN, 0.0, 0.0];
        assert_eq!(
            pqp_distance(
                d,
                I.as_ptr(),
                nan_t.as_ptr(),
                a,
                I.as_ptr(),
                up.as_ptr(),
                b,
                0.0,
                0.0,
                2
            ),
            PQP_ERR_NONFINITE_POSE
        );
        let fresh = pqp_model_create();
        assert_eq!(
            pqp_distance(
                d,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                up.as_ptr(),
                fresh,
                0.0,
                0.0,
                2
            ),
            PQP_ERR_UNPROCESSED_MODEL
        );
        pqp_model_destroy(fresh);
        pqp_distance_result_destroy(d);

        let t = pqp_tolerance_result_create();
        assert_eq!(
            pqp_tolerance(
                t,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                up.as_ptr(),
                b,
                2.5,
                2
            ),
            PQP_OK
        );
        assert_eq!(pqp_tolerance_result_closer_than_tolerance(t), 1);
        let o = pqp_search_options_default();
        assert_eq!(
            pqp_tolerance_search(
                t,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                up.as_ptr(),
                b,
                1.5,
                &o
            ),
            PQP_OK
        );
        assert_eq!(pqp_tolerance_result_closer_than_tolerance(t), 0);
        assert!(pqp_tolerance_result_distance(t) > 1.5);
        assert_eq!(
            pqp_tolerance(
                t,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                up.as_ptr(),
                b,
                -1.0,
                2
            ),
            PQP_ERR_INVALID_ARGUMENT
        );
        pqp_tolerance_result_destroy(t);

        // Getters and destroys given NULL.
        assert!(pqp_distance_result_distance(null()).is_nan());
        assert_eq!(pqp_collide_result_num_pairs(null()), 0);
        assert!(pqp_collide_result_pairs(null()).is_null());
        pqp_collide_result_destroy(null_mut());
        pqp_distance_result_destroy(null_mut());
        pqp_tolerance_result_destroy(null_mut());
        pqp_model_destroy(a);
        pqp_model_destroy(b);
    }
}

#[test]
fn triangles_segments_and_texts() {
    unsafe {
        let s = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
        let mut t = s;
        for k in [2, 5, 8] {
            t[k] = 1.5;
        }
        let (mut d, mut p, mut q) = (0.0, [0.0; 3], [0.0; 3]);
        assert_eq!(
            pqp_triangle_distance(
                &mut d,
                p.as_mut_ptr(),
                q.as_mut_ptr(),
                s.as_ptr(),
                t.as_ptr()
            ),
            PQP_OK
        );
        assert_eq!(d, 1.5);
        assert_eq!(
            pqp_triangle_distance(&mut d, null_mut(), q.as_mut_ptr(), s.as_ptr(), t.as_ptr()),
            PQP_ERR_NULL_POINTER
        );
        let (a, da, b, db) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 0.0]);
        let rc = pqp_segment_distance(
            &mut d,
            p.as_mut_ptr(),
            q.as_mut_ptr(),
            a.as_ptr(),
            da.as_ptr(),
            b.as_ptr(),
            db.as_ptr(),
        );
        assert_eq!((rc, d), (PQP_OK, 2.0));
        for code in -13..=1 {
            assert!(!CStr::from_ptr(pqp_error_string(code)).to_bytes().is_empty());
        }
        assert!(!CStr::from_ptr(pqp_version()).to_bytes().is_empty());
    }
}

#[test]
fn convex_models() {
    unsafe {
        let cube: Vec<f64> = (0..8)
            .flat_map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        let mut a = null_mut();
        assert_eq!(
            pqp_convex_model_from_points(&mut a, cube.as_ptr(), 8),
            PQP_OK
        );
        assert_eq!(
            (
                pqp_convex_model_num_vertices(a),
                pqp_convex_model_num_faces(a)
            ),
            (8, 6)
        );
        let mut xyz = [0.0; 3];
        assert_eq!(
            pqp_convex_model_vertex(a, 8, xyz.as_mut_ptr()),
            PQP_ERR_INVALID_ARGUMENT
        );
        let k = pqp_convex_model_face_num_vertices(a, 0);
        let mut face = vec![0; k as usize];
        assert_eq!(pqp_convex_model_face(a, 0, face.as_mut_ptr()), PQP_OK);
        let (mut tail, mut head) = (0, 0);
        assert_eq!(pqp_convex_model_edge(a, 0, &mut tail, &mut head), PQP_OK);
        let mut flat = null_mut();
        assert_eq!(
            pqp_convex_model_from_points(&mut flat, cube.as_ptr(), 4),
            PQP_ERR_DEGENERATE_POINTS
        );
        assert!(flat.is_null());

        // A tetrahedron from its triangles, and a broken one.
        let v = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let tris: [c_int; 12] = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3];
        let mut b = null_mut();
        assert_eq!(
            pqp_convex_model_from_triangles(&mut b, v.as_ptr(), 4, tris.as_ptr(), 4),
            PQP_OK
        );
        let mut broken = tris;
        broken.swap(0, 1);
        let mut no = null_mut();
        assert_eq!(
            pqp_convex_model_from_triangles(&mut no, v.as_ptr(), 4, broken.as_ptr(), 4),
            PQP_ERR_INVALID_CONVEX_MESH
        );
        broken[0] = 4;
        assert_eq!(
            pqp_convex_model_from_triangles(&mut no, v.as_ptr(), 4, broken.as_ptr(), 4),
            PQP_ERR_INVALID_ARGUMENT
        );

        let cache = pqp_convex_cache_create();
        let r = pqp_convex_result_create();
        let apart = [3.0, 0.0, 0.0];
        for c in [null_mut(), cache, cache] {
            assert_eq!(
                pqp_convex_distance(
                    r,
                    I.as_ptr(),
                    O.as_ptr(),
                    a,
                    I.as_ptr(),
                    apart.as_ptr(),
                    b,
                    c
                ),
                PQP_OK
            );
            assert_eq!(pqp_convex_result_distance(r), 2.0);
        }
        let mut hit = -1;
        assert_eq!(
            pqp_convex_intersect(
                &mut hit,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                O.as_ptr(),
                b,
                cache
            ),
            PQP_OK
        );
        assert_eq!(hit, 1);
        let inside = [0.25, 0.25, 0.25];
        assert_eq!(
            pqp_convex_penetration(
                r,
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                inside.as_ptr(),
                b,
                cache
            ),
            PQP_OK
        );
        assert!(pqp_convex_result_depth(r) > 0.0);
        let n = std::slice::from_raw_parts(pqp_convex_result_normal(r), 3);
        assert!((n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0).abs() < 1e-12);
        let _ = std::slice::from_raw_parts(pqp_convex_result_deepest_p1(r), 3);
        let _ = (
            pqp_convex_result_feature1_kind(r),
            pqp_convex_result_feature2_index(r),
        );
        let bad = [f64::INFINITY, 0.0, 0.0];
        assert_eq!(
            pqp_convex_distance(
                r,
                I.as_ptr(),
                bad.as_ptr(),
                a,
                I.as_ptr(),
                O.as_ptr(),
                b,
                cache
            ),
            PQP_ERR_NONFINITE_POSE
        );
        assert_eq!(
            pqp_convex_distance(
                null_mut(),
                I.as_ptr(),
                O.as_ptr(),
                a,
                I.as_ptr(),
                O.as_ptr(),
                b,
                cache
            ),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(pqp_convex_cache_clear(cache), PQP_OK);
        pqp_convex_result_destroy(r);
        pqp_convex_cache_destroy(cache);
        pqp_convex_model_destroy(a);
        pqp_convex_model_destroy(b);
        pqp_convex_model_destroy(null_mut());
        pqp_convex_result_destroy(null_mut());
        pqp_convex_cache_destroy(null_mut());
    }
}

/// Refit with PQP 1.3's views made before and after (the old arrays are dropped, new ones made),
/// self-collision and pairs within a distance, with their error paths.
#[test]
fn refit_self_collide_within_distance() {
    // SAFETY: every handle is live until destroyed; every pointer points to what the header asks.
    unsafe {
        let tris = [tri(0.0), tri(1.0), tri(2.0)];
        let m = model(&tris);
        let (mut t, mut n) = (null(), 0);
        assert_eq!(pqp_model_tris(m, &mut t, &mut n), PQP_OK);
        let (mut b, mut nb) = (null(), 0);
        assert_eq!(pqp_model_bvs(m, &mut b, &mut nb), PQP_OK);
        // Fold the second triangle onto the first: identical vertices, so they collide.
        let moved = [tri(0.0), tri(0.0), tri(5.0)];
        let flat = moved.as_flattened().as_flattened();
        assert_eq!(
            pqp_model_refit(null_mut(), flat.as_ptr(), 3),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(pqp_model_refit(m, null(), 3), PQP_ERR_NULL_POINTER);
        assert_eq!(
            pqp_model_refit(m, flat.as_ptr(), 2),
            PQP_ERR_INVALID_ARGUMENT
        );
        assert_eq!(pqp_model_refit(m, flat.as_ptr(), 3), PQP_OK);
        assert_eq!(pqp_model_tris(m, &mut t, &mut n), PQP_OK);
        assert_eq!((n, (*t.add(2)).p1[2]), (3, 5.0));
        assert_eq!(pqp_model_bvs(m, &mut b, &mut nb), PQP_OK);
        assert_eq!(nb, 5);
        let r = pqp_collide_result_create();
        assert_eq!(pqp_self_collide(r, m, PQP_ALL_CONTACTS), PQP_OK);
        assert_eq!(pqp_collide_result_num_pairs(r), 1);
        assert_eq!(
            (pqp_collide_result_id1(r, 0), pqp_collide_result_id2(r, 0)),
            (10, 11)
        );
        assert_eq!(pqp_self_collide(r, m, 7), PQP_ERR_INVALID_ARGUMENT);
        assert_eq!(
            pqp_self_collide(r, null(), PQP_ALL_CONTACTS),
            PQP_ERR_NULL_POINTER
        );
        let other = model(&[tri(0.5)]);
        assert_eq!(
            pqp_within_distance(
                r,
                I.as_ptr(),
                O.as_ptr(),
                m,
                I.as_ptr(),
                O.as_ptr(),
                other,
                0.6
            ),
            PQP_OK
        );
        assert_eq!(pqp_collide_result_num_pairs(r), 2);
        assert_eq!(
            pqp_within_distance(
                r,
                I.as_ptr(),
                O.as_ptr(),
                m,
                I.as_ptr(),
                O.as_ptr(),
                other,
                -1.0
            ),
            PQP_ERR_INVALID_ARGUMENT
        );
        assert_eq!(pqp_collide_result_num_pairs(r), 2);
        pqp_collide_result_destroy(r);
        pqp_model_destroy(other);
        pqp_model_destroy(m);
    }
}

#[test]
fn point_queries() {
    // SAFETY: every pointer is NULL (where an error is expected) or points to what the header
    // asks: live models, 9 and 3 doubles, a writable result or double.
    unsafe {
        let m = model(&[tri(0.0), tri(1.0), tri(2.0)]);
        let p = [0.2, 0.2, 5.0];
        let mut r = pqp_point_result {
            distance: 0.0,
            point: [0.0; 3],
            triangle: 0,
        };
        assert_eq!(
            pqp_closest_point(&mut r, I.as_ptr(), O.as_ptr(), m, p.as_ptr(), f64::INFINITY),
            PQP_OK
        );
        assert_eq!(
            (r.distance, r.point, r.triangle),
            (3.0, [0.2, 0.2, 2.0], 12)
        );
        assert_eq!(
            pqp_closest_point(&mut r, I.as_ptr(), O.as_ptr(), m, p.as_ptr(), 1.0),
            PQP_OK
        );
        assert_eq!((r.distance, r.triangle), (f64::INFINITY, -1));
        assert!(r.point.iter().all(|c| c.is_nan()));
        let mut sd = 0.0;
        assert_eq!(
            pqp_signed_distance(&mut sd, I.as_ptr(), O.as_ptr(), m, p.as_ptr()),
            PQP_OK
        );
        assert_eq!(sd, 3.0);
        // The answer may overwrite its input.
        let mut q = p;
        assert_eq!(
            pqp_signed_distance(q.as_mut_ptr(), I.as_ptr(), O.as_ptr(), m, q.as_ptr()),
            PQP_OK
        );
        assert_eq!(q[0], 3.0);
        assert_eq!(
            pqp_closest_point(null_mut(), I.as_ptr(), O.as_ptr(), m, p.as_ptr(), 1.0),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_signed_distance(&mut sd, I.as_ptr(), O.as_ptr(), null(), p.as_ptr()),
            PQP_ERR_NULL_POINTER
        );
        let empty = pqp_model_create();
        assert_eq!(
            pqp_signed_distance(&mut sd, I.as_ptr(), O.as_ptr(), empty, p.as_ptr()),
            PQP_ERR_UNPROCESSED_MODEL
        );
        assert_eq!(sd, 3.0);
        pqp_model_destroy(empty);
        pqp_model_destroy(m);
    }
}

#[test]
fn batch_queries_read_and_write_only_their_arrays() {
    // Three poses of a triangle pair: overlapping, 0.5 apart, 2 apart; pose arrays exactly n long
    // (Miri catches any read past them), answers compared with single calls.
    let (a, b) = (model(&[tri(0.0)]), model(&[tri(0.0), tri(0.1)]));
    let n = 3;
    let mut r = Vec::new();
    for _ in 0..n {
        r.extend_from_slice(&I);
    }
    let t1 = vec![0.0; 3 * n];
    let t2 = vec![0.2, 0.2, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 2.0];
    unsafe {
        for threads in [0, 1, 2] {
            let mut hit = vec![-1 as c_int; n];
            let mut gap = vec![-1.0; n];
            let mut near = vec![-1 as c_int; n];
            let (rp, t1p, t2p) = (r.as_ptr(), t1.as_ptr(), t2.as_ptr());
            let rc = pqp_collide_batch(hit.as_mut_ptr(), n, rp, t1p, a, rp, t2p, b, 1, threads);
            assert_eq!(rc, PQP_OK);
            let rc = pqp_distance_batch(gap.as_mut_ptr(), n, rp, t1p, a, rp, t2p, b, 0.0, 0.0, 2);
            assert_eq!(rc, PQP_OK);
            let rc = pqp_tolerance_batch(near.as_mut_ptr(), n, rp, t1p, a, rp, t2p, b, 0.6, 2);
            assert_eq!(rc, PQP_OK);
            assert_eq!(hit, [1, 0, 0]);
            assert_eq!(gap, [0.0, 0.5, 2.0]);
            assert_eq!(near, [1, 1, 0]);
        }
        // A NaN in the last pose: nothing written; n = 0 with NULL pointers: nothing read.
        let mut bad = t2.clone();
        bad[8] = f64::NAN;
        let mut hit = vec![-1 as c_int; n];
        let rc = pqp_collide_batch(
            hit.as_mut_ptr(),
            n,
            r.as_ptr(),
            t1.as_ptr(),
            a,
            r.as_ptr(),
            bad.as_ptr(),
            b,
            1,
            2,
        );
        assert_eq!(rc, PQP_ERR_NONFINITE_POSE);
        assert_eq!(hit, [-1; 3]);
        let rc = pqp_distance_batch(
            null_mut(),
            0,
            null(),
            null(),
            null(),
            null(),
            null(),
            null(),
            0.0,
            0.0,
            0,
        );
        assert_eq!(rc, PQP_OK);
        pqp_model_destroy(a);
        pqp_model_destroy(b);
    }
}

/// Saved models: the size query, serialize into a buffer with room to spare and into one too
/// small, deserialize into a built model (its views dropped) and, refused, from truncated and
/// unaligned bytes.
#[test]
fn saved_models() {
    let a = model(&[tri(0.0), tri(1.0), tri(2.5)]);
    let b = model(&[tri(-1.0)]);
    // SAFETY: every handle is live; every buffer is as long as the length passed with it.
    unsafe {
        let mut size = 0usize;
        assert_eq!(
            pqp_model_serialize(a, null_mut(), 0, &mut size),
            PQP_ERR_BUFFER_TOO_SMALL
        );
        let mut buf = vec![0u8; size + 5];
        let mut small = vec![7u8; size - 1];
        assert_eq!(
            pqp_model_serialize(a, small.as_mut_ptr().cast(), small.len(), &mut size),
            PQP_ERR_BUFFER_TOO_SMALL
        );
        assert!(small.iter().all(|&x| x == 7));
        // At an odd address: bytes need no alignment.
        let mut written = 0usize;
        assert_eq!(
            pqp_model_serialize(a, buf[1..].as_mut_ptr().cast(), size + 4, &mut written),
            PQP_OK
        );
        assert_eq!(written, size);
        let (mut tris, mut n) = (null(), 0);
        assert_eq!(pqp_model_tris(b, &mut tris, &mut n), PQP_OK);
        let bytes = &buf[1..1 + size];
        assert_eq!(
            pqp_model_deserialize(b, bytes.as_ptr().cast(), size - 1),
            PQP_ERR_INVALID_DATA
        );
        assert_eq!(pqp_model_num_tris(b), 1);
        assert_eq!(
            pqp_model_deserialize(b, bytes.as_ptr().cast(), size),
            PQP_OK
        );
        assert_eq!(pqp_model_num_tris(b), 3);
        assert_eq!(pqp_model_tris(b, &mut tris, &mut n), PQP_OK);
        assert_eq!((n, (*tris.add(2)).id), (3, 12));
        let r = pqp_distance_result_create();
        let up = [0.0, 0.0, 10.0];
        let rc = pqp_distance(
            r,
            I.as_ptr(),
            O.as_ptr(),
            a,
            I.as_ptr(),
            up.as_ptr(),
            b,
            0.0,
            0.0,
            2,
        );
        assert_eq!(rc, PQP_OK);
        assert_eq!(pqp_distance_result_distance(r), 7.5);
        pqp_distance_result_destroy(r);
        pqp_model_destroy(a);
        pqp_model_destroy(b);
    }
}

#[test]
fn ray_casts() {
    unsafe {
        // Two stacked triangles: a ray down through both hits the upper one.
        let m = model(&[tri(0.0), tri(1.0)]);
        let (o, d) = ([0.25, 0.25, 3.0], [0.0, 0.0, -1.0]);
        let mut hit = std::mem::MaybeUninit::<pqp_ray_hit>::uninit();
        let rc = pqp_ray_cast(
            hit.as_mut_ptr(),
            I.as_ptr(),
            O.as_ptr(),
            m,
            o.as_ptr(),
            d.as_ptr(),
            f64::INFINITY,
        );
        assert_eq!(rc, PQP_OK);
        let hit = hit.assume_init();
        assert_eq!((hit.t, hit.triangle), (2.0, 11));
        let mut h = hit;
        let zero = [0.0; 3];
        assert_eq!(
            pqp_ray_cast(
                &mut h,
                I.as_ptr(),
                O.as_ptr(),
                m,
                o.as_ptr(),
                zero.as_ptr(),
                1.0
            ),
            PQP_ERR_INVALID_ARGUMENT
        );
        assert_eq!(
            pqp_ray_cast(
                null_mut(),
                I.as_ptr(),
                O.as_ptr(),
                m,
                o.as_ptr(),
                d.as_ptr(),
                1.0
            ),
            PQP_ERR_NULL_POINTER
        );
        // A batch of 70 rays (two chunks) on two threads, one ray missing; then one bad ray.
        let n = 70;
        let mut origins = Vec::new();
        let mut dirs = Vec::new();
        for i in 0..n {
            origins.extend_from_slice(&[0.25, if i == 5 { 3.0 } else { 0.25 }, 3.0]);
            dirs.extend_from_slice(&d);
        }
        let mut hits = vec![h; n];
        let rc = pqp_ray_cast_batch(
            hits.as_mut_ptr(),
            n,
            I.as_ptr(),
            O.as_ptr(),
            m,
            origins.as_ptr(),
            dirs.as_ptr(),
            5.0,
            2,
        );
        assert_eq!(rc, PQP_OK);
        assert_eq!(hits[5].triangle, -1);
        assert!(
            hits.iter()
                .enumerate()
                .all(|(i, x)| i == 5 || x.triangle == 11)
        );
        dirs[3 * 40] = f64::NAN;
        let before = hits.clone();
        let rc = pqp_ray_cast_batch(
            hits.as_mut_ptr(),
            n,
            I.as_ptr(),
            O.as_ptr(),
            m,
            origins.as_ptr(),
            dirs.as_ptr(),
            5.0,
            2,
        );
        assert_eq!(rc, PQP_ERR_NONFINITE_COORDINATE);
        assert_eq!(hits[7], before[7]);
        assert_eq!(
            pqp_ray_cast_batch(
                null_mut(),
                0,
                I.as_ptr(),
                O.as_ptr(),
                m,
                null(),
                null(),
                1.0,
                0
            ),
            PQP_OK
        );
        pqp_model_destroy(m);
    }
}
