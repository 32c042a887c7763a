//! What PQP 1.3 programs read of a model, through the C ABI: the build protocol's codes and
//! states, deep copies of models.

mod common;

use common::{Mesh, Rng};
use pqp::capi::*;
use std::ptr;

const I3: [f64; 9] = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];

/// Adds `tris` to `m` with ids `first_id`, `first_id + 1`, ...
unsafe fn add_all(m: *mut pqp_model, tris: &[[[f64; 3]; 3]], first_id: i32) {
    for (i, t) in tris.iter().enumerate() {
        let rc = pqp_model_add_tri(
            m,
            t[0].as_ptr(),
            t[1].as_ptr(),
            t[2].as_ptr(),
            first_id + i as i32,
        );
        assert_eq!(rc, PQP_OK);
    }
}

/// A built C model of `tris` (ids 0, 1, ...) with swept sphere volumes of `volume`.
unsafe fn c_model(tris: &[[[f64; 3]; 3]], volume: i32) -> *mut pqp_model {
    let m = pqp_model_create();
    assert!(!m.is_null());
    assert_eq!(pqp_model_set_volume(m, volume), PQP_OK);
    assert_eq!(pqp_model_begin(m, tris.len() as i32), PQP_OK);
    add_all(m, tris, 0);
    assert_eq!(pqp_model_end(m), PQP_OK);
    m
}

/// Row-major rotation and translation of a pose, as C passes them.
fn c_pose(p: &pqp::Pose) -> ([f64; 9], [f64; 3]) {
    let r = &p.rotation;
    (
        [
            r[(0, 0)],
            r[(0, 1)],
            r[(0, 2)],
            r[(1, 0)],
            r[(1, 1)],
            r[(1, 2)],
            r[(2, 0)],
            r[(2, 1)],
            r[(2, 2)],
        ],
        [p.translation.x, p.translation.y, p.translation.z],
    )
}

/// Everything the three queries answer for `a` against `b` at each pose of `b`, bit for bit.
unsafe fn answers(a: *const pqp_model, b: *const pqp_model, poses: &[pqp::Pose]) -> Vec<Vec<u64>> {
    let (cr, dr, tr) = (
        pqp_collide_result_create(),
        pqp_distance_result_create(),
        pqp_tolerance_result_create(),
    );
    let mut out = Vec::new();
    for p in poses {
        let (r, t) = c_pose(p);
        let (rp, tp) = (r.as_ptr(), t.as_ptr());
        let (ip, zp) = (I3.as_ptr(), [0.0; 3].as_ptr());
        assert_eq!(
            pqp_collide(cr, ip, zp, a, rp, tp, b, PQP_ALL_CONTACTS),
            PQP_OK
        );
        assert_eq!(pqp_distance(dr, ip, zp, a, rp, tp, b, 0.0, 0.0, 2), PQP_OK);
        assert_eq!(pqp_tolerance(tr, ip, zp, a, rp, tp, b, 0.05, 2), PQP_OK);
        let mut v = Vec::new();
        for k in 0..pqp_collide_result_num_pairs(cr) {
            v.push(pqp_collide_result_id1(cr, k) as u64);
            v.push(pqp_collide_result_id2(cr, k) as u64);
        }
        v.push(pqp_distance_result_distance(dr).to_bits());
        for k in 0..3 {
            v.push((*pqp_distance_result_p1(dr).add(k)).to_bits());
            v.push((*pqp_distance_result_p2(dr).add(k)).to_bits());
        }
        v.push(pqp_distance_result_id1(dr) as u64);
        v.push(pqp_distance_result_id2(dr) as u64);
        v.push(pqp_tolerance_result_closer_than_tolerance(tr) as u64);
        v.push(pqp_tolerance_result_distance(tr).to_bits());
        // The work done shows the hierarchies are the same too.
        v.push(pqp_collide_result_num_bv_tests(cr) as u64);
        v.push(pqp_distance_result_num_bv_tests(dr) as u64);
        v.push(pqp_tolerance_result_num_bv_tests(tr) as u64);
        out.push(v);
    }
    pqp_collide_result_destroy(cr);
    pqp_distance_result_destroy(dr);
    pqp_tolerance_result_destroy(tr);
    out
}

/// PQP 1.3's build table through the C ABI, with pqp_model_build_state after every call.
#[test]
fn build_codes_and_states_follow_pqp_1_3() {
    let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let bad = [f64::NAN, 0.0, 0.0];
    unsafe {
        assert_eq!(
            (
                PQP_BUILD_STATE_EMPTY,
                PQP_BUILD_STATE_BEGUN,
                PQP_BUILD_STATE_PROCESSED
            ),
            (0, 1, 2)
        );
        assert_eq!(pqp_model_build_state(ptr::null()), PQP_BUILD_STATE_EMPTY);
        let m = pqp_model_create();
        let state = || pqp_model_build_state(m);
        let add = |p: &[f64; 3]| pqp_model_add_tri(m, t[0].as_ptr(), p.as_ptr(), t[2].as_ptr(), 0);
        assert_eq!(state(), PQP_BUILD_STATE_EMPTY);
        // End on a fresh model: empty model, nothing changes.
        assert_eq!(pqp_model_end(m), PQP_ERR_BUILD_EMPTY_MODEL);
        assert_eq!(state(), PQP_BUILD_STATE_EMPTY);
        // A refused triangle begins the model all the same, and is not stored.
        assert_eq!(add(&bad), PQP_ERR_NONFINITE_COORDINATE);
        assert_eq!((state(), pqp_model_num_tris(m)), (PQP_BUILD_STATE_BEGUN, 0));
        assert_eq!(pqp_model_end(m), PQP_ERR_BUILD_EMPTY_MODEL);
        assert_eq!(state(), PQP_BUILD_STATE_BEGUN);
        // Begin on a begun model: cleared, -4, begun.
        assert_eq!(pqp_model_begin(m, 1), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        assert_eq!(state(), PQP_BUILD_STATE_BEGUN);
        assert_eq!(add(&t[1]), PQP_OK);
        assert_eq!(add(&bad), PQP_ERR_NONFINITE_COORDINATE);
        assert_eq!((state(), pqp_model_num_tris(m)), (PQP_BUILD_STATE_BEGUN, 1));
        assert_eq!(pqp_model_end(m), PQP_OK);
        assert_eq!(state(), PQP_BUILD_STATE_PROCESSED);
        // End twice, add after end: -4, ignored, still built.
        assert_eq!(pqp_model_end(m), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        assert_eq!(add(&t[1]), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        assert_eq!(add(&bad), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        assert_eq!(
            (state(), pqp_model_num_tris(m)),
            (PQP_BUILD_STATE_PROCESSED, 1)
        );
        // Begin on a built model: cleared, -4, begun; end with nothing added: -5, still begun.
        assert_eq!(pqp_model_begin(m, 1), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        assert_eq!((state(), pqp_model_num_tris(m)), (PQP_BUILD_STATE_BEGUN, 0));
        assert_eq!(pqp_model_end(m), PQP_ERR_BUILD_EMPTY_MODEL);
        assert_eq!(state(), PQP_BUILD_STATE_BEGUN);
        pqp_model_destroy(m);
        // Add before begin begins implicitly.
        let m = pqp_model_create();
        assert_eq!(
            pqp_model_add_tri(m, t[0].as_ptr(), t[1].as_ptr(), t[2].as_ptr(), 0),
            PQP_OK
        );
        assert_eq!(pqp_model_build_state(m), PQP_BUILD_STATE_BEGUN);
        // A NULL vertex changes nothing.
        assert_eq!(
            pqp_model_add_tri(m, t[0].as_ptr(), ptr::null(), t[2].as_ptr(), 0),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(pqp_model_num_tris(m), 1);
        pqp_model_destroy(m);
    }
}

#[test]
fn a_copy_is_deep_and_answers_identically() {
    let mut rng = Rng::new(21);
    let mesh = Mesh::soup(&mut rng, 300, 1.0, 0.2);
    let other = Mesh::torus(0.8, 0.25, 20, 10);
    let poses: Vec<pqp::Pose> = (0..30).map(|_| rng.pose(1.2)).collect();
    unsafe {
        let b = c_model(&other.tris, PQP_BV_RSS);
        for volume in [PQP_BV_RSS, PQP_BV_PSS, PQP_BV_LSS, PQP_BV_HYBRID] {
            let a = c_model(&mesh.tris, volume);
            let want = answers(a, b, &poses);
            assert!(want.iter().any(|v| v.len() > 12), "some pose collides");
            let mut copy = ptr::null_mut();
            assert_eq!(pqp_model_clone(&mut copy, a), PQP_OK);
            assert!(!copy.is_null() && copy != a);
            assert_eq!(pqp_model_build_state(copy), PQP_BUILD_STATE_PROCESSED);
            assert_eq!(pqp_model_num_tris(copy), 300);
            assert_eq!(answers(copy, b, &poses), want);
            // The copy as model 2, and against the original.
            assert_eq!(answers(b, copy, &poses), answers(b, a, &poses));
            assert_eq!(answers(a, copy, &poses), answers(a, a, &poses));
            // Destroying the original leaves the copy whole.
            pqp_model_destroy(a);
            assert_eq!(answers(copy, b, &poses), want);
            // Rebuilding a copy leaves the model it was copied from as it was.
            let mut second = ptr::null_mut();
            assert_eq!(pqp_model_clone(&mut second, copy), PQP_OK);
            assert_eq!(pqp_model_begin(second, 1), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
            add_all(second, &other.tris[..5], 0);
            assert_eq!(pqp_model_end(second), PQP_OK);
            assert_eq!(pqp_model_num_tris(second), 5);
            assert_eq!(pqp_model_num_tris(copy), 300);
            assert_eq!(answers(copy, b, &poses), want);
            // A built copy is built: its volume choice is fixed.
            assert_eq!(
                pqp_model_set_volume(copy, PQP_BV_RSS),
                PQP_ERR_BUILD_OUT_OF_SEQUENCE
            );
            pqp_model_destroy(second);
            pqp_model_destroy(copy);
        }
        pqp_model_destroy(b);
    }
}

#[test]
fn copies_of_empty_and_unfinished_models_go_their_own_ways() {
    let mut rng = Rng::new(5);
    let mesh = Mesh::soup(&mut rng, 40, 1.0, 0.3);
    let poses: Vec<pqp::Pose> = (0..10).map(|_| rng.pose(1.0)).collect();
    unsafe {
        let reference = c_model(&mesh.tris, PQP_BV_LSS);
        // A fresh model: the copy is fresh too.
        let fresh = pqp_model_create();
        let mut copy = ptr::null_mut();
        assert_eq!(pqp_model_clone(&mut copy, fresh), PQP_OK);
        assert_eq!(pqp_model_build_state(copy), PQP_BUILD_STATE_EMPTY);
        assert_eq!(pqp_model_end(copy), PQP_ERR_BUILD_EMPTY_MODEL);
        assert_eq!(pqp_model_begin(copy, 0), PQP_OK);
        pqp_model_destroy(copy);
        pqp_model_destroy(fresh);
        // A model being built: both go on with different triangles; the copy keeps the volume
        // choice (its answers and work are those of a model built with it).
        let half = pqp_model_create();
        assert_eq!(pqp_model_set_volume(half, PQP_BV_LSS), PQP_OK);
        add_all(half, &mesh.tris[..20], 0);
        let mut copy = ptr::null_mut();
        assert_eq!(pqp_model_clone(&mut copy, half), PQP_OK);
        assert_eq!(pqp_model_build_state(copy), PQP_BUILD_STATE_BEGUN);
        assert_eq!(pqp_model_num_tris(copy), 20);
        add_all(copy, &mesh.tris[20..], 20);
        assert_eq!(pqp_model_num_tris(half), 20);
        assert_eq!(pqp_model_end(copy), PQP_OK);
        assert_eq!(pqp_model_build_state(half), PQP_BUILD_STATE_BEGUN);
        assert_eq!(
            answers(copy, reference, &poses),
            answers(reference, reference, &poses)
        );
        assert_eq!(pqp_model_end(half), PQP_OK);
        assert_eq!(pqp_model_num_tris(half), 20);
        assert_eq!(pqp_model_num_tris(copy), 40);
        pqp_model_destroy(half);
        pqp_model_destroy(copy);
        pqp_model_destroy(reference);
    }
}

#[test]
fn clone_refuses_null() {
    unsafe {
        let m = pqp_model_create();
        assert_eq!(pqp_model_clone(ptr::null_mut(), m), PQP_ERR_NULL_POINTER);
        let mut out = 1usize as *mut pqp_model;
        assert_eq!(pqp_model_clone(&mut out, ptr::null()), PQP_ERR_NULL_POINTER);
        assert!(out.is_null());
        pqp_model_destroy(m);
    }
}
