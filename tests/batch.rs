//! Batch queries (Rust API and C ABI) against single queries and brute force: the same answers on
//! the example models (random poses, and a coherent path that exercises each thread's triangle
//! cache and front) and on random meshes, on every thread count; every bad argument returns its code
//! and writes nothing.

mod common;

#[path = "../examples/workloads/mod.rs"]
mod workloads;

use common::{Mesh, Random, RandomPqp, Rng, borderline, brute};
use pqp::capi::*;
use pqp::{
    ContactMode, DistanceOptions, DistanceResult, Error, Model, Pose, Search, Strategy, collide,
    collide_batch, distance, distance_batch, distance_into, tolerance, tolerance_batch,
    tolerance_into,
};
use std::ffi::{c_int, c_uint};
use std::ptr::{null, null_mut};

/// Thread counts every batch is run with: all cores, one, two, and far more than cores or queries.
const THREADS: [usize; 4] = [0, 1, 2, 1000];

fn example_tris(name: &str) -> Vec<workloads::Tri> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/models")
        .join(name);
    workloads::read_tris(&path).expect("example model")
}

fn example_model(name: &str) -> Model {
    Model::from_triangles(example_tris(name)).unwrap()
}

/// The bunny (about 0.15 across) and the torus, as the demos pair them.
fn bunny_and_torus() -> (Model, Model) {
    (example_model("bunny.tris"), example_model("torus.tris"))
}

/// Random poses around the origin: about half of them overlap for models of size `size`.
fn random_poses(rng: &mut Rng, n: usize, size: f64) -> Vec<(Pose, Pose)> {
    (0..n)
        .map(|_| (rng.pose(0.3 * size), rng.pose(1.2 * size)))
        .collect()
}

/// A coherent motion: model 2 sweeps through model 1, turning a little at each step.
fn sweep(n: usize, size: f64) -> Vec<(Pose, Pose)> {
    (0..n)
        .map(|k| {
            let s = k as f64 / n as f64;
            let (c, si) = ((3.0 * s).cos(), (3.0 * s).sin());
            let r = [[c, -si, 0.0], [si, c, 0.0], [0.0, 0.0, 1.0]];
            let t = [
                size * (3.0 * s - 1.5),
                0.1 * size,
                0.2 * size * (9.0 * s).sin(),
            ];
            (Pose::identity(), Pose::new(r, t))
        })
        .collect()
}

/// Single queries with fresh results, as references.
fn single_collide(m1: &Model, m2: &Model, poses: &[(Pose, Pose)]) -> Vec<bool> {
    poses
        .iter()
        .map(|(p1, p2)| {
            collide(m1, p1, m2, p2, ContactMode::All)
                .unwrap()
                .colliding()
        })
        .collect()
}

fn single_distance(
    m1: &Model,
    m2: &Model,
    poses: &[(Pose, Pose)],
    o: &DistanceOptions,
) -> Vec<f64> {
    poses
        .iter()
        .map(|(p1, p2)| distance(m1, p1, m2, p2, o).unwrap().distance)
        .collect()
}

fn single_tolerance(m1: &Model, m2: &Model, poses: &[(Pose, Pose)], t: f64) -> Vec<bool> {
    poses
        .iter()
        .map(|(p1, p2)| {
            tolerance(m1, p1, m2, p2, t, &Search::default())
                .unwrap()
                .closer_than_tolerance
        })
        .collect()
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|d| d.to_bits()).collect()
}

/// Every batch, on every thread count, against single queries with fresh results.
fn check_against_single(m1: &Model, m2: &Model, poses: &[(Pose, Pose)], tol: f64) {
    let colliding = single_collide(m1, m2, poses);
    let exact = DistanceOptions::exact();
    let approx = DistanceOptions::approximate(0.1, 0.05);
    let d_exact = single_distance(m1, m2, poses, &exact);
    let d_approx = single_distance(m1, m2, poses, &approx);
    let closer = single_tolerance(m1, m2, poses, tol);
    // The poses exercise both answers of each query.
    assert!(colliding.contains(&true) && colliding.contains(&false));
    assert!(closer.contains(&true) && closer.contains(&false));
    assert!(d_exact.iter().any(|&d| d > 0.0) && d_exact.contains(&0.0));
    // The error bounds matter here: some approximate answers are not the exact ones.
    assert!(d_exact.iter().zip(&d_approx).any(|(e, a)| e != a));
    for threads in THREADS {
        assert_eq!(collide_batch(m1, m2, poses, threads).unwrap(), colliding);
        let d = distance_batch(m1, m2, poses, &exact, threads).unwrap();
        assert_eq!(bits(&d), bits(&d_exact), "threads {threads}");
        let d = distance_batch(m1, m2, poses, &approx, threads).unwrap();
        assert_eq!(bits(&d), bits(&d_approx), "threads {threads}");
        let t = tolerance_batch(m1, m2, poses, tol, &Search::default(), threads).unwrap();
        assert_eq!(t, closer);
    }
}

#[test]
fn batches_match_single_queries_on_the_example_models() {
    let (bunny, torus) = bunny_and_torus();
    let mut rng = Rng::new(2101);
    let poses = random_poses(&mut rng, 300, 1.0);
    check_against_single(&bunny, &torus, &poses, 0.05);
    // The same model on both sides.
    check_against_single(&torus, &torus, &poses, 0.05);
}

#[test]
fn batches_match_single_queries_along_a_coherent_path() {
    // Consecutive poses are close: each thread's result keeps its triangle cache and, for exact
    // distance, its BVTT front from one pose to the next; the answers must not change.
    let (bunny, torus) = bunny_and_torus();
    let poses = sweep(600, 1.0);
    check_against_single(&bunny, &torus, &poses, 0.03);
    // A caller reusing one result along the path gets the same exact distances too.
    let mut r = DistanceResult::new();
    let reused: Vec<f64> = poses
        .iter()
        .map(|(p1, p2)| {
            distance_into(&mut r, &bunny, p1, &torus, p2, &DistanceOptions::exact()).unwrap();
            r.distance
        })
        .collect();
    let batch = distance_batch(&bunny, &torus, &poses, &DistanceOptions::exact(), 2).unwrap();
    assert_eq!(bits(&batch), bits(&reused));
}

#[test]
fn exact_distance_with_every_search_matches_single_queries() {
    let (bunny, torus) = bunny_and_torus();
    let poses = sweep(200, 1.0);
    for strategy in [Strategy::Auto, Strategy::DepthFirst, Strategy::Priority] {
        for triangle_cache in [false, true] {
            let o = DistanceOptions {
                search: Search {
                    strategy,
                    qsize: 16,
                    triangle_cache,
                },
                ..DistanceOptions::exact()
            };
            let single = single_distance(&bunny, &torus, &poses, &o);
            let batch = distance_batch(&bunny, &torus, &poses, &o, 2).unwrap();
            assert_eq!(bits(&batch), bits(&single));
        }
    }
}

#[test]
fn batches_match_brute_force_on_random_meshes() {
    let mut rng = Rng::new(2102);
    for round in 0..6 {
        let a = match round % 3 {
            0 => Mesh::soup(&mut rng, 40, 1.0, 0.4),
            1 => Mesh::sphere(0.8, 10, 6),
            _ => Mesh::torus(1.0, 0.3, 12, 6),
        };
        let b = Mesh::soup(&mut rng, 30, 0.8, 0.5);
        let (ma, mb) = (a.model(), b.model());
        let poses: Vec<(Pose, Pose)> = (0..40)
            .map(|_| (rng.pose(0.5), rng.pose(2.0)))
            .filter(|(pa, pb)| !borderline(&a, pa, &b, pb, 1e-9))
            .collect();
        let tol = 0.2;
        let refs: Vec<_> = poses.iter().map(|(pa, pb)| brute(&a, pa, &b, pb)).collect();
        for threads in THREADS {
            let c = collide_batch(&ma, &mb, &poses, threads).unwrap();
            let d = distance_batch(&ma, &mb, &poses, &DistanceOptions::exact(), threads).unwrap();
            let t = tolerance_batch(&ma, &mb, &poses, tol, &Search::default(), threads).unwrap();
            for (i, r) in refs.iter().enumerate() {
                assert_eq!(c[i], !r.pairs.is_empty(), "round {round} pose {i}");
                let e = (d[i] - r.distance).abs();
                assert!(
                    e <= 1e-9 * r.distance.max(1.0),
                    "{} vs {}",
                    d[i],
                    r.distance
                );
                if (r.distance - tol).abs() > 1e-9 {
                    assert_eq!(t[i], r.distance <= tol, "round {round} pose {i}");
                }
            }
        }
    }
}

#[test]
fn tolerance_batch_with_reused_results_matches_fresh_ones() {
    // Each thread reuses its tolerance result; a caller doing the same, serially, agrees.
    let (bunny, torus) = bunny_and_torus();
    let poses = sweep(400, 1.0);
    for tol in [0.0, 0.01, 0.1] {
        let mut r = pqp::ToleranceResult::new();
        let reused: Vec<bool> = poses
            .iter()
            .map(|(p1, p2)| {
                tolerance_into(&mut r, &bunny, p1, &torus, p2, tol, &Search::default()).unwrap();
                r.closer_than_tolerance
            })
            .collect();
        assert_eq!(reused, single_tolerance(&bunny, &torus, &poses, tol));
        let batch = tolerance_batch(&bunny, &torus, &poses, tol, &Search::default(), 0).unwrap();
        assert_eq!(batch, reused);
    }
}

#[test]
fn rust_batches_check_their_arguments_first() {
    let (bunny, torus) = bunny_and_torus();
    let unbuilt = Model::new();
    let mut rng = Rng::new(2103);
    let good = random_poses(&mut rng, 20, 1.0);
    let mut bad = good.clone();
    bad[13].1.translation.y = f64::NAN;
    let exact = DistanceOptions::exact();
    let s = Search::default();
    for threads in THREADS {
        assert_eq!(
            collide_batch(&unbuilt, &torus, &good, threads),
            Err(Error::UnprocessedModel)
        );
        assert_eq!(
            collide_batch(&bunny, &unbuilt, &good, threads),
            Err(Error::UnprocessedModel)
        );
        assert_eq!(
            collide_batch(&bunny, &torus, &bad, threads),
            Err(Error::NonFinitePose)
        );
        // The model is checked before the poses, as a single query checks them.
        assert_eq!(
            collide_batch(&unbuilt, &torus, &bad, threads),
            Err(Error::UnprocessedModel)
        );
        assert_eq!(
            distance_batch(&bunny, &torus, &bad, &exact, threads),
            Err(Error::NonFinitePose)
        );
        let neg = DistanceOptions::approximate(-1.0, 0.0);
        assert_eq!(
            distance_batch(&unbuilt, &torus, &bad, &neg, threads),
            Err(Error::InvalidArgument)
        );
        assert_eq!(
            distance_batch(&bunny, &unbuilt, &good, &exact, threads),
            Err(Error::UnprocessedModel)
        );
        assert_eq!(
            tolerance_batch(&bunny, &torus, &bad, 0.1, &s, threads),
            Err(Error::NonFinitePose)
        );
        for t in [-1.0, f64::NAN] {
            assert_eq!(
                tolerance_batch(&unbuilt, &torus, &bad, t, &s, threads),
                Err(Error::InvalidArgument)
            );
        }
        let no_queue = Search { qsize: 0, ..s };
        assert_eq!(
            tolerance_batch(&bunny, &torus, &good, 0.1, &no_queue, threads),
            Err(Error::InvalidArgument)
        );
        // No poses: the arguments are still checked.
        assert_eq!(collide_batch(&bunny, &torus, &[], threads), Ok(vec![]));
        assert_eq!(
            distance_batch(&bunny, &torus, &[], &exact, threads),
            Ok(vec![])
        );
        assert_eq!(
            tolerance_batch(&unbuilt, &torus, &[], 0.1, &s, threads),
            Err(Error::UnprocessedModel)
        );
    }
    // A pose at the limit is accepted, beyond it refused.
    let mut edge = good.clone();
    edge[5].0.translation.x = 1e150;
    assert!(collide_batch(&bunny, &torus, &edge, 2).is_ok());
    edge[5].0.rotation[(1, 2)] = -1.1e150;
    assert_eq!(
        collide_batch(&bunny, &torus, &edge, 2),
        Err(Error::NonFinitePose)
    );
}

// ---- The C ABI ----

/// A C model of an example model (ids are indices); free with pqp_model_destroy.
fn c_model(name: &str) -> *mut pqp_model {
    let h = pqp_model_create();
    let mut copy: *mut pqp_model = null_mut();
    // SAFETY: h is a live handle; each vertex pointer points to 3 doubles.
    unsafe {
        let tris = example_tris(name);
        assert_eq!(pqp_model_begin(h, tris.len() as c_int), PQP_OK);
        for (p, q, r, id) in &tris {
            let rc = pqp_model_add_tri(h, p.as_ptr(), q.as_ptr(), r.as_ptr(), *id);
            assert_eq!(rc, PQP_OK);
        }
        assert_eq!(pqp_model_end(h), PQP_OK);
        // A clone is a built model too: use it, so that the batch meets a model made that way.
        assert_eq!(pqp_model_clone(&mut copy, h), PQP_OK);
        pqp_model_destroy(h);
    }
    copy
}

/// Pose pairs as the C batch takes them: four flat arrays.
struct Flat {
    r1: Vec<f64>,
    t1: Vec<f64>,
    r2: Vec<f64>,
    t2: Vec<f64>,
}

fn flat(poses: &[(Pose, Pose)]) -> Flat {
    let mut f = Flat {
        r1: Vec::new(),
        t1: Vec::new(),
        r2: Vec::new(),
        t2: Vec::new(),
    };
    for (p1, p2) in poses {
        for (p, r, t) in [(p1, &mut f.r1, &mut f.t1), (p2, &mut f.r2, &mut f.t2)] {
            for i in 0..3 {
                for j in 0..3 {
                    r.push(p.rotation[(i, j)]);
                }
            }
            t.extend(p.translation.iter());
        }
    }
    f
}

/// The single C queries, each with a fresh result, as references.
fn c_single(
    a: *const pqp_model,
    b: *const pqp_model,
    f: &Flat,
    n: usize,
) -> (Vec<c_int>, Vec<f64>, Vec<c_int>) {
    let (mut c, mut d, mut t) = (Vec::new(), Vec::new(), Vec::new());
    // SAFETY: the handles are live; the arrays hold n poses.
    unsafe {
        for i in 0..n {
            let (r1, t1) = (f.r1[9 * i..].as_ptr(), f.t1[3 * i..].as_ptr());
            let (r2, t2) = (f.r2[9 * i..].as_ptr(), f.t2[3 * i..].as_ptr());
            let cr = pqp_collide_result_create();
            assert_eq!(
                pqp_collide(cr, r1, t1, a, r2, t2, b, PQP_ALL_CONTACTS),
                PQP_OK
            );
            c.push(pqp_collide_result_colliding(cr));
            pqp_collide_result_destroy(cr);
            let dr = pqp_distance_result_create();
            assert_eq!(pqp_distance(dr, r1, t1, a, r2, t2, b, 0.0, 0.0, 2), PQP_OK);
            d.push(pqp_distance_result_distance(dr));
            pqp_distance_result_destroy(dr);
            let tr = pqp_tolerance_result_create();
            assert_eq!(pqp_tolerance(tr, r1, t1, a, r2, t2, b, 0.05, 2), PQP_OK);
            t.push(pqp_tolerance_result_closer_than_tolerance(tr));
            pqp_tolerance_result_destroy(tr);
        }
    }
    (c, d, t)
}

#[test]
fn c_batches_match_single_c_calls() {
    let (bunny, torus) = bunny_and_torus();
    let (a, b) = (c_model("bunny.tris"), c_model("torus.tris"));
    let mut rng = Rng::new(2104);
    let mut poses = random_poses(&mut rng, 150, 1.0);
    poses.extend(sweep(150, 1.0));
    let f = flat(&poses);
    let n = poses.len();
    let (c, d, t) = c_single(a, b, &f, n);
    for threads in [0, 1, 2, 3, 1000, c_uint::MAX] {
        for flag in [PQP_ALL_CONTACTS, PQP_FIRST_CONTACT] {
            let mut out = vec![-1 as c_int; n];
            // SAFETY: the arrays hold n poses and n answers; the handles are live.
            let rc = unsafe {
                pqp_collide_batch(
                    out.as_mut_ptr(),
                    n,
                    f.r1.as_ptr(),
                    f.t1.as_ptr(),
                    a,
                    f.r2.as_ptr(),
                    f.t2.as_ptr(),
                    b,
                    flag,
                    threads,
                )
            };
            assert_eq!(rc, PQP_OK);
            assert_eq!(out, c);
        }
        let mut out = vec![-1.0; n];
        // SAFETY: as above.
        let rc = unsafe {
            pqp_distance_batch(
                out.as_mut_ptr(),
                n,
                f.r1.as_ptr(),
                f.t1.as_ptr(),
                a,
                f.r2.as_ptr(),
                f.t2.as_ptr(),
                b,
                0.0,
                0.0,
                threads,
            )
        };
        assert_eq!(rc, PQP_OK);
        assert_eq!(bits(&out), bits(&d));
        let mut out = vec![-1 as c_int; n];
        // SAFETY: as above.
        let rc = unsafe {
            pqp_tolerance_batch(
                out.as_mut_ptr(),
                n,
                f.r1.as_ptr(),
                f.t1.as_ptr(),
                a,
                f.r2.as_ptr(),
                f.t2.as_ptr(),
                b,
                0.05,
                threads,
            )
        };
        assert_eq!(rc, PQP_OK);
        assert_eq!(out, t);
    }
    // Approximate distance: what single calls with fresh results return, bit for bit.
    let mut out = vec![-1.0; n];
    // SAFETY: as above.
    let rc = unsafe {
        pqp_distance_batch(
            out.as_mut_ptr(),
            n,
            f.r1.as_ptr(),
            f.t1.as_ptr(),
            a,
            f.r2.as_ptr(),
            f.t2.as_ptr(),
            b,
            0.2,
            0.05,
            2,
        )
    };
    assert_eq!(rc, PQP_OK);
    let approx = single_distance(
        &bunny,
        &torus,
        &poses,
        &DistanceOptions::approximate(0.2, 0.05),
    );
    assert_eq!(bits(&out), bits(&approx));
    // SAFETY: live handles, destroyed once.
    unsafe {
        pqp_model_destroy(a);
        pqp_model_destroy(b);
    }
}

/// The three C batches on the same arguments (colliding, distance, closer): their codes, with
/// answers left as they were on any error.
#[allow(clippy::too_many_arguments)]
fn c_codes(
    n: usize,
    r1: *const f64,
    t1: *const f64,
    a: *const pqp_model,
    r2: *const f64,
    t2: *const f64,
    b: *const pqp_model,
    out_int: *mut c_int,
    out_double: *mut f64,
    flag: c_int,
    err: (f64, f64),
    tol: f64,
) -> [c_int; 3] {
    // SAFETY: the caller passes NULL or arrays of n poses and n answers, and live handles.
    unsafe {
        [
            pqp_collide_batch(out_int, n, r1, t1, a, r2, t2, b, flag, 2),
            pqp_distance_batch(out_double, n, r1, t1, a, r2, t2, b, err.0, err.1, 2),
            pqp_tolerance_batch(out_int, n, r1, t1, a, r2, t2, b, tol, 2),
        ]
    }
}

#[test]
fn c_batches_refuse_bad_arguments_and_write_nothing() {
    let (a, b) = (c_model("bunny.tris"), c_model("torus.tris"));
    let unbuilt = pqp_model_create();
    let mut rng = Rng::new(2105);
    let n = 12;
    let f = flat(&random_poses(&mut rng, n, 1.0));
    let mut ints = vec![7 as c_int; n];
    let mut doubles = vec![7.0; n];
    let (pi, pd) = (ints.as_mut_ptr(), doubles.as_mut_ptr());
    let (r1, t1, r2, t2) = (f.r1.as_ptr(), f.t1.as_ptr(), f.r2.as_ptr(), f.t2.as_ptr());
    let ok = (0.0, 0.0);
    let all = |code| [code; 3];
    let codes =
        |n, r1, t1, a, r2, t2, b, pi, pd| c_codes(n, r1, t1, a, r2, t2, b, pi, pd, 1, ok, 0.1);

    // NULL pointers, each in turn.
    let null_int: *mut c_int = null_mut();
    let null_double: *mut f64 = null_mut();
    let nul: *const f64 = null();
    let nm: *const pqp_model = null();
    let e = all(PQP_ERR_NULL_POINTER);
    assert_eq!(codes(n, nul, t1, a, r2, t2, b, pi, pd), e);
    assert_eq!(codes(n, r1, nul, a, r2, t2, b, pi, pd), e);
    assert_eq!(codes(n, r1, t1, nm, r2, t2, b, pi, pd), e);
    assert_eq!(codes(n, r1, t1, a, nul, t2, b, pi, pd), e);
    assert_eq!(codes(n, r1, t1, a, r2, nul, b, pi, pd), e);
    assert_eq!(codes(n, r1, t1, a, r2, t2, nm, pi, pd), e);
    assert_eq!(codes(n, r1, t1, a, r2, t2, b, null_int, null_double), e);

    // Bad scalar arguments, before the models and poses are looked at.
    for flag in [0, 3, -1] {
        let rc = c_codes(n, r1, t1, unbuilt, r2, t2, b, pi, pd, flag, ok, 0.1)[0];
        assert_eq!(rc, PQP_ERR_INVALID_ARGUMENT);
    }
    for err in [(-1.0, 0.0), (0.0, -1.0), (f64::NAN, 0.0), (0.0, f64::NAN)] {
        let rc = c_codes(n, r1, t1, unbuilt, r2, t2, b, pi, pd, 1, err, 0.1)[1];
        assert_eq!(rc, PQP_ERR_INVALID_ARGUMENT);
    }
    for tol in [-0.5, f64::NAN, f64::NEG_INFINITY] {
        let rc = c_codes(n, r1, t1, unbuilt, r2, t2, b, pi, pd, 1, ok, tol)[2];
        assert_eq!(rc, PQP_ERR_INVALID_ARGUMENT);
    }

    // Unbuilt models (checked before the poses).
    let e = all(PQP_ERR_UNPROCESSED_MODEL);
    assert_eq!(codes(n, r1, t1, unbuilt, r2, t2, b, pi, pd), e);
    assert_eq!(codes(n, r1, t1, a, r2, t2, unbuilt, pi, pd), e);

    // A bad entry in any pose but the first, in each array: nothing is written.
    for (array, len) in [(0, 9), (1, 3), (2, 9), (3, 3)] {
        for bad in [f64::NAN, f64::INFINITY, -2e150] {
            let mut g = [f.r1.clone(), f.t1.clone(), f.r2.clone(), f.t2.clone()];
            let k = 1 + rng.below(n - 1);
            g[array][len * k + rng.below(len)] = bad;
            let p: Vec<*const f64> = g.iter().map(|v| v.as_ptr()).collect();
            assert_eq!(
                codes(n, p[0], p[1], a, p[2], p[3], b, pi, pd),
                all(PQP_ERR_NONFINITE_POSE)
            );
        }
    }
    assert!(ints.iter().all(|&v| v == 7) && doubles.iter().all(|&v| v == 7.0));

    // n = 0: PQP_OK, nothing read (every pointer NULL, the flag and bounds not even looked at).
    let rc = c_codes(
        0,
        nul,
        nul,
        nm,
        nul,
        nul,
        nm,
        null_int,
        null_double,
        1,
        ok,
        0.1,
    );
    assert_eq!(rc, all(PQP_OK));
    // SAFETY: n = 0: nothing is read or written.
    unsafe {
        assert_eq!(
            pqp_collide_batch(null_mut(), 0, nul, nul, nm, nul, nul, nm, 99, 0),
            PQP_OK
        );
    }

    // A count no array can hold: refused before anything is read (the arrays are short).
    for huge in [usize::MAX, usize::MAX / 9 + 1, isize::MAX as usize / 72 + 1] {
        assert_eq!(
            codes(huge, r1, t1, a, r2, t2, b, pi, pd),
            all(PQP_ERR_INVALID_ARGUMENT)
        );
    }
    assert!(ints.iter().all(|&v| v == 7) && doubles.iter().all(|&v| v == 7.0));

    // The same arrays answer once the bad arguments are gone.
    assert_eq!(codes(n, r1, t1, a, r2, t2, b, pi, pd), all(PQP_OK));
    assert!(ints.iter().all(|&v| v == 0 || v == 1));
    assert!(doubles.iter().all(|&v| v >= 0.0 && v != 7.0));
    // SAFETY: live handles, destroyed once.
    unsafe {
        pqp_model_destroy(a);
        pqp_model_destroy(b);
        pqp_model_destroy(unbuilt);
    }
}
