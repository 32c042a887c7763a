//! What PQP 1.3 programs read of a model, through the C ABI: the build protocol's codes and
//! states, deep copies of models.

// Edition 2024: these helpers' bodies call the C ABI under their own `unsafe fn` contract.
#![allow(unsafe_op_in_unsafe_fn)]

mod common;

use common::{Mesh, Random, RandomPqp, Rng};
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
        let mut out = std::ptr::dangling_mut::<pqp_model>();
        assert_eq!(pqp_model_clone(&mut out, ptr::null()), PQP_ERR_NULL_POINTER);
        assert!(out.is_null());
        pqp_model_destroy(m);
    }
}

/// The triangle view of `m` (PQP_OK asserted).
unsafe fn tris_of<'a>(m: *const pqp_model) -> &'a [pqp_tri] {
    let (mut p, mut n) = (ptr::null(), -1);
    assert_eq!(pqp_model_tris(m, &mut p, &mut n), PQP_OK);
    assert!(n >= 0);
    if n == 0 {
        assert!(p.is_null());
        return &[];
    }
    std::slice::from_raw_parts(p, n as usize)
}

/// The volume view of a built `m` (PQP_OK asserted).
unsafe fn bvs_of<'a>(m: *const pqp_model) -> &'a [pqp_bv] {
    let (mut p, mut n) = (ptr::null(), -1);
    assert_eq!(pqp_model_bvs(m, &mut p, &mut n), PQP_OK);
    assert!(n > 0 && !p.is_null());
    std::slice::from_raw_parts(p, n as usize)
}

type M3 = [[f64; 3]; 3];

fn mat_mul(a: &M3, b: &M3) -> M3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn mat_vec(a: &M3, v: &[f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

/// `a^T v`.
fn mat_tr_vec(a: &M3, v: &[f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| (0..3).map(|k| a[k][i] * v[k]).sum())
}

fn add3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// A volume in model coordinates: frame, rectangle corner, box centre, and the sizes.
#[derive(Clone, Copy, Debug)]
struct Placed {
    rot: M3,
    corner: [f64; 3],
    center: [f64; 3],
    l: [f64; 2],
    r: f64,
    d: [f64; 3],
}

impl Placed {
    /// How far `p` is outside the rectangle swept sphere (negative inside).
    fn rss_excess(&self, p: [f64; 3]) -> f64 {
        let q = mat_tr_vec(&self.rot, &sub3(p, self.corner));
        let out = |x: f64, len: f64| (-x).max(x - len).max(0.0);
        let (dx, dy) = (out(q[0], self.l[0]), out(q[1], self.l[1]));
        (dx * dx + dy * dy + q[2] * q[2]).sqrt() - self.r
    }

    /// How far `p` is outside the box (along the worst axis; negative inside).
    fn box_excess(&self, p: [f64; 3]) -> f64 {
        let q = mat_tr_vec(&self.rot, &sub3(p, self.center));
        (0..3)
            .map(|i| q[i].abs() - self.d[i])
            .fold(f64::MIN, f64::max)
    }
}

/// Checks PQP's view of a built model of `tris` (ids `ids`): the triangles in the order added;
/// 2n - 1 volumes laid out depth first as PQP did, every slot but the root a child exactly once,
/// every triangle in exactly one leaf; composed from the root, every volume orthonormal and
/// containing (within `1e-9` of the model's size) the vertices of every triangle below it. Returns
/// the volumes in model coordinates, by slot.
unsafe fn check_view(m: *const pqp_model, tris: &[[[f64; 3]; 3]], ids: &[i32]) -> Vec<Placed> {
    let n = tris.len();
    let view = tris_of(m);
    assert_eq!(view.len(), n);
    for (k, (t, v)) in tris.iter().zip(view).enumerate() {
        // Bit for bit (NaN-free input: == on doubles is bitwise here but for -0).
        let bits = |p: &[f64; 3]| p.map(f64::to_bits);
        assert_eq!(
            [bits(&v.p1), bits(&v.p2), bits(&v.p3)],
            [bits(&t[0]), bits(&t[1]), bits(&t[2])],
            "triangle {k}"
        );
        assert_eq!(v.id, ids[k]);
    }
    let bvs = bvs_of(m);
    assert_eq!(bvs.len(), 2 * n - 1);
    let size = tris
        .iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |a, &x| a.max(x.abs()));
    let tol = 1e-9 * size.max(f64::MIN_POSITIVE);

    // Referenced once each; children after their parent, given out depth first.
    let mut referenced = vec![0; bvs.len()];
    let mut leaf_of = vec![usize::MAX; n];
    let mut placed = vec![None; bvs.len()];
    let mut next = 1usize;
    // (slot, parent's placement, ancestors' slots)
    let mut stack: Vec<(usize, Option<Placed>, Vec<usize>)> = vec![(0, None, Vec::new())];
    while let Some((k, parent, mut ancestors)) = stack.pop() {
        let b = &bvs[k];
        let mut here = Placed {
            rot: b.R,
            corner: b.Tr,
            center: b.To,
            l: b.l,
            r: b.r,
            d: b.d,
        };
        if let Some(p) = parent {
            here.rot = mat_mul(&p.rot, &b.R);
            here.corner = add3(mat_vec(&p.rot, &b.Tr), p.corner);
            here.center = add3(mat_vec(&p.rot, &b.To), p.center);
        }
        // Orthonormal, relative and composed.
        for rot in [&b.R, &here.rot] {
            let g = mat_mul(&transpose(rot), rot);
            for (i, row) in g.iter().enumerate() {
                for (j, &x) in row.iter().enumerate() {
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((x - want).abs() < 1e-9, "slot {k}: {rot:?}");
                }
            }
        }
        assert!(b.l[0] >= 0.0 && b.l[1] >= 0.0 && b.r >= 0.0, "slot {k}");
        assert!(b.d.iter().all(|&x| x >= 0.0), "slot {k}");
        placed[k] = Some(here);
        ancestors.push(k);
        if b.first_child >= 0 {
            let c = b.first_child as usize;
            assert_eq!(c, next, "slot {k}: children not given out depth first");
            next += 2;
            assert!(c > k && c + 1 < bvs.len(), "slot {k}: child {c}");
            referenced[c] += 1;
            referenced[c + 1] += 1;
            stack.push((c + 1, Some(here), ancestors.clone()));
            stack.push((c, Some(here), ancestors));
        } else {
            let t = (-(b.first_child as i64) - 1) as usize;
            assert!(t < n, "slot {k}: triangle {t}");
            assert_eq!(leaf_of[t], usize::MAX, "triangle {t} in two leaves");
            leaf_of[t] = k;
            for &a in &ancestors {
                let v: Placed = placed[a].unwrap();
                for &p in &tris[t] {
                    let (e1, e2) = (v.rss_excess(p), v.box_excess(p));
                    assert!(e1 <= tol, "slot {a}: vertex of {t} {e1} outside its RSS");
                    assert!(e2 <= tol, "slot {a}: vertex of {t} {e2} outside its box");
                }
            }
        }
    }
    assert_eq!(next, bvs.len());
    assert_eq!(referenced[0], 0);
    assert!(referenced[1..].iter().all(|&r| r == 1));
    assert!(leaf_of.iter().all(|&k| k != usize::MAX));
    placed.into_iter().map(Option::unwrap).collect()
}

fn transpose(a: &M3) -> M3 {
    [0, 1, 2].map(|i| [a[0][i], a[1][i], a[2][i]])
}

/// Random triangles, with every kind of degenerate one mixed in: points, repeated vertices,
/// collinear vertices, slivers, exact repeats.
fn mixed_soup(rng: &mut Rng, n: usize, offset: f64) -> Vec<[[f64; 3]; 3]> {
    let mut tris: Vec<[[f64; 3]; 3]> = Vec::new();
    while tris.len() < n {
        let c = add3(rng.point(1.0), [offset; 3]);
        let mut v = || add3(c, rng.point(0.1));
        let (a, b) = (v(), v());
        let t = match tris.len() % 9 {
            0 => [a, a, a],
            1 => [a, b, a],
            2 => [
                a,
                b,
                add3(
                    a,
                    [
                        (b[0] - a[0]) * 0.5,
                        (b[1] - a[1]) * 0.5,
                        (b[2] - a[2]) * 0.5,
                    ],
                ),
            ],
            3 => [a, b, add3(a, [1e-13, 0.0, 0.0])],
            4 if !tris.is_empty() => tris[tris.len() - 1],
            _ => [a, b, v()],
        };
        tris.push(t);
    }
    tris
}

#[test]
fn the_view_is_pqp_layout_and_contains_every_triangle() {
    let mut rng = Rng::new(77);
    for &(n, offset) in &[
        (1, 0.0),
        (2, 0.0),
        (3, 0.0),
        (4, 5.0),
        (17, 0.0),
        (1000, 0.0),
        (1000, 1e3),
    ] {
        let tris = mixed_soup(&mut rng, n, offset);
        let ids: Vec<i32> = (0..n as i32).map(|i| 7 * i - 50).collect();
        for volume in [PQP_BV_RSS, PQP_BV_PSS, PQP_BV_LSS, PQP_BV_HYBRID] {
            unsafe {
                let m = pqp_model_create();
                assert_eq!(pqp_model_set_volume(m, volume), PQP_OK);
                for (t, &id) in tris.iter().zip(&ids) {
                    assert_eq!(
                        pqp_model_add_tri(m, t[0].as_ptr(), t[1].as_ptr(), t[2].as_ptr(), id),
                        PQP_OK
                    );
                }
                assert_eq!(pqp_model_end(m), PQP_OK);
                let placed = check_view(m, &tris, &ids);
                // The root is in model coordinates, and holds everything.
                let b0 = &bvs_of(m)[0];
                assert_eq!((placed[0].rot, placed[0].corner), (b0.R, b0.Tr));
                if n == 1 {
                    assert_eq!(b0.first_child, -1);
                }
                // Asked again: the same arrays.
                assert_eq!(tris_of(m).as_ptr(), tris_of(m).as_ptr());
                assert_eq!(bvs_of(m).as_ptr(), bvs_of(m).as_ptr());
                pqp_model_destroy(m);
            }
        }
    }
}

/// The view of a real mesh (shared vertices, a closed surface), as a PQP program would walk it.
#[test]
fn the_view_of_a_closed_mesh() {
    let mesh = Mesh::torus(2.0, 0.5, 40, 20);
    let ids: Vec<i32> = (0..mesh.tris.len() as i32).collect();
    unsafe {
        let m = c_model(&mesh.tris, PQP_BV_RSS);
        check_view(m, &mesh.tris, &ids);
        pqp_model_destroy(m);
    }
}

#[test]
fn the_float_view_is_the_double_view_rounded() {
    let mut rng = Rng::new(3);
    let tris = mixed_soup(&mut rng, 300, 2.0);
    unsafe {
        let m = c_model(&tris, PQP_BV_HYBRID);
        let (mut tp, mut tn) = (ptr::null(), 0);
        assert_eq!(pqp_model_tris_float(m, &mut tp, &mut tn), PQP_OK);
        let (mut bp, mut bn) = (ptr::null(), 0);
        assert_eq!(pqp_model_bvs_float(m, &mut bp, &mut bn), PQP_OK);
        let tf = std::slice::from_raw_parts(tp, tn as usize);
        let bf = std::slice::from_raw_parts(bp, bn as usize);
        let (td, bd) = (tris_of(m), bvs_of(m));
        assert_eq!((tf.len(), bf.len()), (td.len(), bd.len()));
        let f = |a: &[f64]| a.iter().map(|&x| x as f32).collect::<Vec<f32>>();
        for (a, b) in tf.iter().zip(td) {
            assert_eq!(a.p1.to_vec(), f(&b.p1));
            assert_eq!(a.p2.to_vec(), f(&b.p2));
            assert_eq!(a.p3.to_vec(), f(&b.p3));
            assert_eq!(a.id, b.id);
        }
        for (a, b) in bf.iter().zip(bd) {
            assert_eq!(a.R.as_flattened().to_vec(), f(b.R.as_flattened()));
            assert_eq!(a.Tr.to_vec(), f(&b.Tr));
            assert_eq!(a.l.to_vec(), f(&b.l));
            assert_eq!(a.r, b.r as f32);
            assert_eq!(a.To.to_vec(), f(&b.To));
            assert_eq!(a.d.to_vec(), f(&b.d));
            assert_eq!(a.first_child, b.first_child);
        }
        // The float arrays are kept apart from the double ones, and kept.
        assert_ne!(tp as usize, td.as_ptr() as usize);
        let (mut again, mut n2) = (ptr::null(), 0);
        assert_eq!(pqp_model_bvs_float(m, &mut again, &mut n2), PQP_OK);
        assert_eq!((again, n2), (bp, bn));
        pqp_model_destroy(m);
    }
}

#[test]
fn the_view_follows_the_build() {
    let mut rng = Rng::new(11);
    let first = mixed_soup(&mut rng, 50, 0.0);
    let second = mixed_soup(&mut rng, 20, 3.0);
    unsafe {
        let m = pqp_model_create();
        // Fresh: no triangles, no volumes.
        assert!(tris_of(m).is_empty());
        let (mut bp, mut bn) = (std::ptr::dangling::<pqp_bv>(), 5);
        assert_eq!(
            pqp_model_bvs(m, &mut bp, &mut bn),
            PQP_ERR_UNPROCESSED_MODEL
        );
        assert!(bp.is_null() && bn == 0);
        let (mut fp, mut fn_) = (std::ptr::dangling::<pqp_bv_float>(), 5);
        assert_eq!(
            pqp_model_bvs_float(m, &mut fp, &mut fn_),
            PQP_ERR_UNPROCESSED_MODEL
        );
        assert!(fp.is_null() && fn_ == 0);
        // Being built: the triangles added so far, read after every add (refused ones left out).
        assert_eq!(pqp_model_begin(m, 0), PQP_OK);
        for (k, t) in first.iter().enumerate() {
            add_all(m, std::slice::from_ref(t), k as i32);
            let bad = [f64::INFINITY, 0.0, 0.0];
            assert_eq!(
                pqp_model_add_tri(m, t[0].as_ptr(), bad.as_ptr(), t[2].as_ptr(), -1),
                PQP_ERR_NONFINITE_COORDINATE
            );
            let view = tris_of(m);
            assert_eq!(view.len(), k + 1);
            assert_eq!(
                (view[k].p1, view[k].p2, view[k].p3, view[k].id),
                (t[0], t[1], t[2], k as i32)
            );
            assert_eq!(
                pqp_model_bvs(m, &mut bp, &mut bn),
                PQP_ERR_UNPROCESSED_MODEL
            );
        }
        let (mut tf, mut tfn) = (ptr::null(), 0);
        assert_eq!(pqp_model_tris_float(m, &mut tf, &mut tfn), PQP_OK);
        add_all(m, &first[..1], 50);
        assert_eq!(pqp_model_tris_float(m, &mut tf, &mut tfn), PQP_OK);
        assert_eq!(tfn, 51);
        assert_eq!((*tf.add(50)).p2, first[0][1].map(|x| x as f32));
        // Built: the same triangles, and the volumes.
        assert_eq!(pqp_model_end(m), PQP_OK);
        let mut all = first.clone();
        all.push(first[0]);
        let ids: Vec<i32> = (0..51).collect();
        check_view(m, &all, &ids);
        let before = bvs_of(m).to_vec();
        // Add after end is ignored: the view is unchanged.
        assert_eq!(
            pqp_model_add_tri(
                m,
                first[1][0].as_ptr(),
                first[1][1].as_ptr(),
                first[1][2].as_ptr(),
                9
            ),
            PQP_ERR_BUILD_OUT_OF_SEQUENCE
        );
        assert_eq!(bvs_of(m), &before[..]);
        // Rebuilt with other triangles: the view is of them.
        assert_eq!(pqp_model_begin(m, 0), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        assert!(tris_of(m).is_empty());
        assert_eq!(
            pqp_model_bvs(m, &mut bp, &mut bn),
            PQP_ERR_UNPROCESSED_MODEL
        );
        add_all(m, &second, 100);
        assert_eq!(pqp_model_end(m), PQP_OK);
        let ids: Vec<i32> = (100..120).collect();
        check_view(m, &second, &ids);
        assert_eq!(bvs_of(m).len(), 39);
        pqp_model_destroy(m);
    }
}

#[test]
fn view_getters_refuse_null_and_clear_their_outputs() {
    unsafe {
        let m = c_model(&[[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]], PQP_BV_RSS);
        let (mut tp, mut tn) = (std::ptr::dangling::<pqp_tri>(), 7);
        assert_eq!(
            pqp_model_tris(ptr::null(), &mut tp, &mut tn),
            PQP_ERR_NULL_POINTER
        );
        assert!(tp.is_null() && tn == 0);
        assert_eq!(
            pqp_model_tris(m, ptr::null_mut(), &mut tn),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_model_tris(m, &mut tp, ptr::null_mut()),
            PQP_ERR_NULL_POINTER
        );
        assert!(tp.is_null());
        let (mut bp, mut bn) = (std::ptr::dangling::<pqp_bv>(), 7);
        assert_eq!(
            pqp_model_bvs(ptr::null(), &mut bp, &mut bn),
            PQP_ERR_NULL_POINTER
        );
        assert!(bp.is_null() && bn == 0);
        assert_eq!(
            pqp_model_bvs(m, ptr::null_mut(), &mut bn),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_model_bvs(m, &mut bp, ptr::null_mut()),
            PQP_ERR_NULL_POINTER
        );
        let (mut fp, mut fn_) = (std::ptr::dangling::<pqp_tri_float>(), 7);
        assert_eq!(
            pqp_model_tris_float(ptr::null(), &mut fp, &mut fn_),
            PQP_ERR_NULL_POINTER
        );
        assert!(fp.is_null() && fn_ == 0);
        let (mut gp, mut gn) = (std::ptr::dangling::<pqp_bv_float>(), 7);
        assert_eq!(
            pqp_model_bvs_float(ptr::null(), &mut gp, &mut gn),
            PQP_ERR_NULL_POINTER
        );
        assert!(gp.is_null() && gn == 0);
        assert_eq!(
            pqp_model_bvs_float(m, &mut gp, ptr::null_mut()),
            PQP_ERR_NULL_POINTER
        );
        pqp_model_destroy(m);
    }
}

/// Four threads asking a built model for its views at once all get the same arrays.
#[test]
fn concurrent_getters_share_one_view() {
    let mut rng = Rng::new(8);
    let tris = mixed_soup(&mut rng, 2000, 0.0);
    for round in 0..20 {
        let m = unsafe { c_model(&tris, PQP_BV_RSS) } as usize;
        let start = std::sync::Arc::new(std::sync::Barrier::new(4));
        let threads: Vec<_> = (0..4)
            .map(|k| {
                let start = start.clone();
                std::thread::spawn(move || unsafe {
                    let m = m as *const pqp_model;
                    start.wait();
                    // Different threads ask in different orders.
                    let mut got = [0usize; 4];
                    for j in 0..4 {
                        let which = (j + k + round) % 4;
                        got[which] = match which {
                            0 => tris_of(m).as_ptr() as usize,
                            1 => bvs_of(m).as_ptr() as usize,
                            2 => {
                                let (mut p, mut n) = (ptr::null(), 0);
                                assert_eq!(pqp_model_tris_float(m, &mut p, &mut n), PQP_OK);
                                p as usize
                            }
                            _ => {
                                let (mut p, mut n) = (ptr::null(), 0);
                                assert_eq!(pqp_model_bvs_float(m, &mut p, &mut n), PQP_OK);
                                p as usize
                            }
                        };
                    }
                    got
                })
            })
            .collect();
        let got: Vec<[usize; 4]> = threads.into_iter().map(|t| t.join().unwrap()).collect();
        assert!(got.iter().all(|g| *g == got[0]), "{got:?}");
        unsafe {
            let m = m as *mut pqp_model;
            assert_eq!(got[0][0], tris_of(m).as_ptr() as usize);
            if round == 0 {
                let ids: Vec<i32> = (0..tris.len() as i32).collect();
                check_view(m, &tris, &ids);
            }
            pqp_model_destroy(m);
        }
    }
}

/// A model never asked for its view costs nothing for it; once asked, memory usage counts it.
#[test]
fn memory_usage_counts_the_view_once_made() {
    let mut rng = Rng::new(4);
    let tris = mixed_soup(&mut rng, 1000, 0.0);
    unsafe {
        let m = c_model(&tris, PQP_BV_RSS);
        let bare = pqp_model_memory_usage(m);
        let mut copy = ptr::null_mut();
        assert_eq!(pqp_model_clone(&mut copy, m), PQP_OK);
        tris_of(m);
        let with_tris = pqp_model_memory_usage(m);
        assert!(with_tris >= bare + 1000 * std::mem::size_of::<pqp_tri>() as u64);
        bvs_of(m);
        let with_both = pqp_model_memory_usage(m);
        assert!(with_both >= with_tris + 1999 * std::mem::size_of::<pqp_bv>() as u64);
        // A copy does not take the views along, but makes the same ones.
        assert_eq!(pqp_model_memory_usage(copy), bare);
        assert_eq!(tris_of(copy), tris_of(m));
        assert_eq!(bvs_of(copy), bvs_of(m));
        // Rebuilding drops them.
        assert_eq!(pqp_model_begin(m, 0), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        add_all(m, &tris, 0);
        assert_eq!(pqp_model_end(m), PQP_OK);
        assert_eq!(pqp_model_memory_usage(m), bare);
        pqp_model_destroy(m);
        pqp_model_destroy(copy);
    }
}

/// The triangles a distance or tolerance result names are the closest (or a close enough) pair,
/// by their positions in the order added, whatever the ids (here repeated, so that only the
/// positions tell triangles apart).
#[test]
fn results_name_their_triangles_in_the_order_added() {
    use common::{apply_tri, point_tri, tri_tri};
    let mut rng = Rng::new(31);
    let a = Mesh::soup(&mut rng, 200, 1.0, 0.3);
    let b = Mesh::torus(0.7, 0.2, 16, 8);
    unsafe {
        let build = |mesh: &Mesh| {
            let m = pqp_model_create();
            for (i, t) in mesh.tris.iter().enumerate() {
                let id = (i % 7) as i32;
                assert_eq!(
                    pqp_model_add_tri(m, t[0].as_ptr(), t[1].as_ptr(), t[2].as_ptr(), id),
                    PQP_OK
                );
            }
            assert_eq!(pqp_model_end(m), PQP_OK);
            m
        };
        let (ma, mb) = (build(&a), build(&b));
        let (dr, tr) = (pqp_distance_result_create(), pqp_tolerance_result_create());
        let (mut t1, mut t2) = (5, 5);
        assert_eq!(pqp_distance_result_triangles(dr, &mut t1, &mut t2), PQP_OK);
        assert_eq!((t1, t2), (-1, -1));
        (t1, t2) = (5, 5);
        assert_eq!(pqp_tolerance_result_triangles(tr, &mut t1, &mut t2), PQP_OK);
        assert_eq!((t1, t2), (-1, -1));
        let (mut overlapping, mut apart, mut closer, mut farther) = (0, 0, 0, 0);
        for k in 0..200 {
            let pose = rng.pose(if k % 2 == 0 { 1.0 } else { 2.5 });
            let (r, t) = c_pose(&pose);
            let (rp, tp) = (r.as_ptr(), t.as_ptr());
            let (ip, zp) = (I3.as_ptr(), [0.0; 3].as_ptr());
            assert_eq!(
                pqp_distance(dr, ip, zp, ma, rp, tp, mb, 0.0, 0.0, 2),
                PQP_OK
            );
            assert_eq!(pqp_distance_result_triangles(dr, &mut t1, &mut t2), PQP_OK);
            let (ta, tb) = (a.tris[t1 as usize], apply_tri(&pose, &b.tris[t2 as usize]));
            let d = pqp_distance_result_distance(dr);
            assert!((tri_tri(&ta, &tb) - d).abs() <= 1e-9, "pose {k}");
            let p1 = *(pqp_distance_result_p1(dr) as *const [f64; 3]);
            assert!(point_tri(p1, &ta) <= 1e-9, "pose {k}");
            assert_eq!(pqp_distance_result_id1(dr), t1 % 7);
            assert_eq!(pqp_distance_result_id2(dr), t2 % 7);
            if pqp_distance_result_overlap(dr) == 1 {
                overlapping += 1;
            } else {
                apart += 1;
            }
            let tol = 0.1;
            assert_eq!(pqp_tolerance(tr, ip, zp, ma, rp, tp, mb, tol, 2), PQP_OK);
            assert_eq!(pqp_tolerance_result_triangles(tr, &mut t1, &mut t2), PQP_OK);
            if pqp_tolerance_result_closer_than_tolerance(tr) == 1 {
                let (ta, tb) = (a.tris[t1 as usize], apply_tri(&pose, &b.tris[t2 as usize]));
                assert!(tri_tri(&ta, &tb) <= tol + 1e-9, "pose {k}");
                closer += 1;
            } else {
                assert_eq!((t1, t2), (-1, -1));
                farther += 1;
            }
        }
        assert!(overlapping > 10 && apart > 10 && closer > 10 && farther > 10);
        // NULL: nothing written.
        (t1, t2) = (5, 5);
        assert_eq!(
            pqp_distance_result_triangles(ptr::null(), &mut t1, &mut t2),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_distance_result_triangles(dr, ptr::null_mut(), &mut t2),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_tolerance_result_triangles(tr, &mut t1, ptr::null_mut()),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_tolerance_result_triangles(ptr::null(), &mut t1, &mut t2),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!((t1, t2), (5, 5));
        pqp_distance_result_destroy(dr);
        pqp_tolerance_result_destroy(tr);
        pqp_model_destroy(ma);
        pqp_model_destroy(mb);
    }
}
