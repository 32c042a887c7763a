//! The three queries against brute force over all triangle pairs (independent routines in
//! `common`), on random soups, spheres and tori in random poses.

mod common;

use common::{Mesh, Random, RandomPqp, Rng, apply, brute, norm, point_tri, sub};
use pqp::{
    ContactMode, DistanceOptions, DistanceResult, Model, Pose, Search, Strategy, collide, distance,
    distance_into, tolerance,
};

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()) + 1e-12
}

/// Every search strategy, with and without triangle caching, and PQP's searches for several queue
/// sizes: all must give the same exact answers.
fn all_searches() -> Vec<Search> {
    let mut v = vec![
        Search::pqp(1),
        Search::pqp(2),
        Search::pqp(8),
        Search::pqp(1000),
    ];
    for strategy in [
        Strategy::Auto,
        Strategy::DepthFirst,
        Strategy::BreadthFirst,
        Strategy::Priority,
    ] {
        for triangle_cache in [false, true] {
            v.push(Search {
                strategy,
                qsize: usize::MAX,
                triangle_cache,
            });
        }
    }
    v
}

/// Checks the distance answer of the library against brute force, with its points.
fn check_distance(
    a: &Mesh,
    ma: &Model,
    pa: &Pose,
    b: &Mesh,
    mb: &Model,
    pb: &Pose,
    search: Search,
) {
    let truth = brute(a, pa, b, pb);
    let opts = DistanceOptions {
        search,
        ..DistanceOptions::default()
    };
    let r = distance(ma, pa, mb, pb, &opts).unwrap();
    assert!(
        close(r.distance, truth.distance),
        "distance {} vs brute {} ({search:?})",
        r.distance,
        truth.distance
    );
    assert_eq!(r.overlap, truth.distance == 0.0);
    // The points lie on the named triangles and are `distance` apart in the world.
    let p1 = [r.p1.x, r.p1.y, r.p1.z];
    let p2 = [r.p2.x, r.p2.y, r.p2.z];
    assert!(point_tri(p1, &a.tris[r.id1 as usize]) < 1e-9);
    assert!(point_tri(p2, &b.tris[r.id2 as usize]) < 1e-9);
    let gap = norm(sub(apply(pa, p1), apply(pb, p2)));
    assert!(close(gap, r.distance) || (gap - r.distance).abs() < 1e-9);
}

#[test]
fn collide_matches_brute_force_on_random_soups() {
    let mut rng = Rng::new(1);
    let mut colliding_poses = 0;
    for case in 0..60 {
        let a = Mesh::soup(&mut rng, 40 + case, 1.0, 0.4);
        let b = Mesh::soup(&mut rng, 30 + case, 1.0, 0.4);
        let (ma, mb) = (a.model(), b.model());
        for _ in 0..5 {
            let (pa, pb) = (rng.pose(0.5), rng.pose(2.5));
            let truth = brute(&a, &pa, &b, &pb);
            let all = collide(&ma, &pa, &mb, &pb, ContactMode::All).unwrap();
            let mut got: Vec<(i32, i32)> = all.pairs().iter().map(|p| (p.id1, p.id2)).collect();
            got.sort();
            assert_eq!(got, truth.pairs, "case {case}");
            let first = collide(&ma, &pa, &mb, &pb, ContactMode::First).unwrap();
            assert_eq!(first.colliding(), !truth.pairs.is_empty());
            assert!(first.num_pairs() <= 1);
            if let Some(p) = first.pairs().first() {
                assert!(truth.pairs.contains(&(p.id1, p.id2)));
            }
            colliding_poses += usize::from(all.colliding());
        }
    }
    // The workload must exercise both answers.
    assert!(
        colliding_poses > 50 && colliding_poses < 250,
        "{colliding_poses}"
    );
}

#[test]
fn distance_matches_brute_force_on_random_soups() {
    let mut rng = Rng::new(2);
    for case in 0..40 {
        let a = Mesh::soup(&mut rng, 30 + case, 1.0, 0.3);
        let b = Mesh::soup(&mut rng, 20 + case, 1.0, 0.3);
        let (ma, mb) = (a.model(), b.model());
        for k in 0..4 {
            let spread = [0.5, 2.0, 5.0, 50.0][k];
            let (pa, pb) = (rng.pose(spread), rng.pose(spread));
            for search in all_searches() {
                check_distance(&a, &ma, &pa, &b, &mb, &pb, search);
            }
        }
    }
}

#[test]
fn distance_matches_brute_force_on_spheres_and_tori() {
    let mut rng = Rng::new(3);
    let sphere = Mesh::sphere(1.0, 16, 10);
    let torus = Mesh::torus(1.0, 0.3, 18, 10);
    let (ms, mt) = (sphere.model(), torus.model());
    for gap in [1e-6, 1e-3, 0.1, 1.0, 3.0] {
        for _ in 0..6 {
            let pa = rng.pose(0.0);
            // Place the torus so the bounding spheres are `gap` apart along a random direction.
            let dir = rng.point(1.0);
            let len = norm(dir);
            let off = (2.3 + gap) / len;
            let pb = Pose::new(rng.rotation(), [dir[0] * off, dir[1] * off, dir[2] * off]);
            for search in all_searches() {
                check_distance(&sphere, &ms, &pa, &torus, &mt, &pb, search);
            }
        }
    }
    // Overlapping poses: sphere through the torus.
    for _ in 0..10 {
        let (pa, pb) = (rng.pose(0.3), rng.pose(0.3));
        for search in all_searches() {
            check_distance(&sphere, &ms, &pa, &torus, &mt, &pb, search);
        }
    }
}

#[test]
fn approximate_distance_honours_both_bounds() {
    let mut rng = Rng::new(4);
    let a = Mesh::sphere(1.0, 24, 14);
    let b = Mesh::sphere(1.05, 20, 12);
    let (ma, mb) = (a.model(), b.model());
    for _ in 0..20 {
        let (pa, pb) = (rng.pose(0.02), rng.pose(0.02));
        let truth = brute(&a, &pa, &b, &pb).distance;
        for (rel, abs) in [
            (0.1, f64::INFINITY),
            (0.5, 1e-3),
            (1.0, 0.0),
            (0.0, 0.01),
            (0.2, 0.02),
        ] {
            for search in all_searches() {
                let opts = DistanceOptions {
                    rel_err: rel,
                    abs_err: abs,
                    search,
                };
                let r = distance(&ma, &pa, &mb, &pb, &opts).unwrap();
                let slack = 1e-12;
                assert!(r.distance >= truth - slack, "{} < {truth}", r.distance);
                assert!(
                    r.distance <= (truth * (1.0 + rel)).min(truth + abs) + slack,
                    "rel {rel} abs {abs} {search:?}: {} vs {truth}",
                    r.distance
                );
            }
        }
    }
}

#[test]
fn relative_error_prunes_work() {
    // Nested shells: the exact query must visit many volume pairs, a 10% bound far fewer.
    let a = Mesh::sphere(1.0, 60, 40);
    let b = Mesh::sphere(1.05, 60, 40);
    let (ma, mb) = (a.model(), b.model());
    let here = Pose::identity();
    let exact = distance(&ma, &here, &mb, &here, &DistanceOptions::default()).unwrap();
    let opts = DistanceOptions::approximate(0.1, f64::INFINITY);
    let approx = distance(&ma, &here, &mb, &here, &opts).unwrap();
    assert!(approx.distance <= exact.distance * 1.1 + 1e-12);
    assert!(
        approx.stats.bv_tests * 2 < exact.stats.bv_tests,
        "{:?} vs {:?}",
        approx.stats,
        exact.stats
    );
}

#[test]
fn tolerance_verdict_matches_brute_force() {
    let mut rng = Rng::new(5);
    for case in 0..30 {
        let a = Mesh::soup(&mut rng, 30 + case, 1.0, 0.3);
        let b = Mesh::soup(&mut rng, 25, 1.0, 0.3);
        let (ma, mb) = (a.model(), b.model());
        for _ in 0..4 {
            let (pa, pb) = (rng.pose(1.5), rng.pose(1.5));
            let truth = brute(&a, &pa, &b, &pb).distance;
            for t in [0.0, 0.01, 0.1, 0.3, 1.0] {
                if (truth - t).abs() < 1e-9 {
                    continue;
                }
                for search in all_searches() {
                    let r = tolerance(&ma, &pa, &mb, &pb, t, &search).unwrap();
                    assert_eq!(
                        r.closer_than_tolerance,
                        truth <= t,
                        "t {t} truth {truth} {search:?}"
                    );
                    if r.closer_than_tolerance {
                        assert!(r.distance <= t && r.distance >= truth - 1e-12);
                        let p1 = [r.p1.x, r.p1.y, r.p1.z];
                        let p2 = [r.p2.x, r.p2.y, r.p2.z];
                        assert!(point_tri(p1, &a.tris[r.id1 as usize]) < 1e-9);
                        assert!(point_tri(p2, &b.tris[r.id2 as usize]) < 1e-9);
                        let gap = norm(sub(apply(&pa, p1), apply(&pb, p2)));
                        assert!((gap - r.distance).abs() < 1e-9);
                    } else {
                        assert!(r.distance > t && r.distance <= truth + 1e-12);
                    }
                }
            }
        }
    }
}

#[test]
fn tolerance_is_cheaper_than_distance() {
    let a = Mesh::sphere(1.0, 40, 30);
    let b = Mesh::sphere(1.0, 40, 30);
    let (ma, mb) = (a.model(), b.model());
    let (pa, pb) = (Pose::identity(), Pose::from_translation([2.05, 0.1, 0.0]));
    let d = distance(&ma, &pa, &mb, &pb, &DistanceOptions::default()).unwrap();
    let far = tolerance(&ma, &pa, &mb, &pb, 0.01, &Search::default()).unwrap();
    let near = tolerance(&ma, &pa, &mb, &pb, 0.2, &Search::default()).unwrap();
    assert!(!far.closer_than_tolerance && near.closer_than_tolerance);
    assert!(far.stats.bv_tests < d.stats.bv_tests);
    assert!(near.stats.bv_tests < d.stats.bv_tests);
}

#[test]
fn triangle_cache_gives_same_answers_with_less_work() {
    let mut rng = Rng::new(6);
    let a = Mesh::torus(1.0, 0.3, 40, 20);
    let b = Mesh::torus(1.0, 0.3, 40, 20);
    let (ma, mb) = (a.model(), b.model());
    let mut warm = DistanceResult::new();
    let (mut warm_tests, mut cold_tests) = (0, 0);
    let r0 = rng.rotation();
    for k in 0..30 {
        let s = k as f64 * 0.01;
        let (c, sn) = (s.cos(), s.sin());
        let rot = [[c, -sn, 0.0], [sn, c, 0.0], [0.0, 0.0, 1.0]];
        let pb = Pose::new(rot, [2.2 + s * 0.1, 0.3, 0.1]);
        let pa = Pose::new(r0, [0.0; 3]);
        let cold = distance(&ma, &pa, &mb, &pb, &DistanceOptions::default()).unwrap();
        distance_into(&mut warm, &ma, &pa, &mb, &pb, &DistanceOptions::default()).unwrap();
        assert!(close(cold.distance, warm.distance));
        warm_tests += warm.stats.bv_tests;
        cold_tests += cold.stats.bv_tests;
    }
    assert!(warm_tests < cold_tests, "{warm_tests} vs {cold_tests}");
    // A cached pair from other models is ignored, not misused.
    let c = Mesh::sphere(0.5, 8, 6);
    let mc = c.model();
    let far = Pose::from_translation([5.0, 0.0, 0.0]);
    distance_into(
        &mut warm,
        &ma,
        &Pose::identity(),
        &mc,
        &far,
        &DistanceOptions::default(),
    )
    .unwrap();
    let truth = brute(&a, &Pose::identity(), &c, &far).distance;
    assert!(close(warm.distance, truth));
}

/// A result reused along a coherent motion starts each query from the BVTT front of the last one:
/// the answers must be those of a fresh query (and of brute force), touching and overlapping
/// frames included, for every search that keeps a front, and the work must drop (most of the
/// front's pairs pruned by their separating axes).
#[test]
fn front_tracking_gives_same_answers_along_coherent_motion() {
    let a = Mesh::torus(1.0, 0.3, 24, 12);
    let b = Mesh::torus(0.8, 0.25, 20, 10);
    let (ma, mb) = (a.model(), b.model());
    let searches = [
        Search::default(),
        Search {
            strategy: Strategy::Priority,
            qsize: 4,
            triangle_cache: true,
        },
        Search::pqp(8),
    ];
    for search in searches {
        let opts = DistanceOptions {
            search,
            ..DistanceOptions::default()
        };
        let mut warm = DistanceResult::new();
        let (mut warm_tests, mut cold_tests, mut touching) = (0, 0, 0);
        for k in 0..120 {
            // Model 2 tumbles slowly and passes through model 1's hole and rim, then away.
            let s = k as f64 * 0.02;
            let (c, sn) = (s.cos(), s.sin());
            let (c2, s2) = ((0.7 * s).cos(), (0.7 * s).sin());
            let rot = [[c, -sn * c2, sn * s2], [sn, c * c2, -c * s2], [0.0, s2, c2]];
            let pa = Pose::identity();
            let pb = Pose::new(rot, [3.4 - 1.0 * s, 0.2 * s, 0.3 - 0.1 * s]);
            let cold = distance(&ma, &pa, &mb, &pb, &opts).unwrap();
            distance_into(&mut warm, &ma, &pa, &mb, &pb, &opts).unwrap();
            assert!(
                close(cold.distance, warm.distance),
                "frame {k}: {} vs {} ({search:?})",
                warm.distance,
                cold.distance
            );
            assert_eq!(cold.overlap, warm.overlap);
            if k % 10 == 0 {
                let truth = brute(&a, &pa, &b, &pb).distance;
                assert!(close(warm.distance, truth), "frame {k}: {truth}");
            }
            touching += warm.overlap as usize;
            warm_tests += warm.stats.bv_tests;
            cold_tests += cold.stats.bv_tests;
        }
        assert!(touching > 5 && touching < 100, "{touching}");
        // Measured: 0.26, 0.14 and 0.17 of the cold work; 0.36 for the default search when front
        // pairs are decayed by their points' whole displacement rather than along their axes.
        assert!(
            (warm_tests as f64) < 0.3 * cold_tests as f64,
            "{warm_tests} vs {cold_tests} ({search:?})"
        );
    }
}

#[test]
fn overlap_is_flagged_with_an_intersecting_pair() {
    let a = Mesh::sphere(1.0, 12, 8);
    let b = Mesh::sphere(1.0, 12, 8);
    let (ma, mb) = (a.model(), b.model());
    let (pa, pb) = (Pose::identity(), Pose::from_translation([1.0, 0.2, 0.1]));
    let r = distance(&ma, &pa, &mb, &pb, &DistanceOptions::default()).unwrap();
    assert!(r.overlap);
    assert_eq!(r.distance, 0.0);
    let ta = common::apply_tri(&pa, &a.tris[r.id1 as usize]);
    let tb = common::apply_tri(&pb, &b.tris[r.id2 as usize]);
    assert_eq!(common::tri_tri(&ta, &tb), 0.0);
    // The points are one world point common to both triangles.
    let w1 = apply(&pa, [r.p1.x, r.p1.y, r.p1.z]);
    let w2 = apply(&pb, [r.p2.x, r.p2.y, r.p2.z]);
    assert!(norm(sub(w1, w2)) < 1e-12);
    assert!(point_tri(w1, &ta) < 1e-12 && point_tri(w1, &tb) < 1e-12);
}

#[test]
fn degenerate_triangles_answer_point_and_segment_queries() {
    // A mesh of one point, and one of one segment, against a sphere.
    let sphere = Mesh::sphere(1.0, 20, 12);
    let ms = sphere.model();
    let point =
        Model::from_triangles([([0.0, 0.0, 3.0], [0.0, 0.0, 3.0], [0.0, 0.0, 3.0], 5)]).unwrap();
    let seg =
        Model::from_triangles([([-5.0, 0.0, 2.0], [5.0, 0.0, 2.0], [0.0, 0.0, 2.0], 6)]).unwrap();
    let here = Pose::identity();
    let truth_p = sphere
        .tris
        .iter()
        .map(|t| point_tri([0.0, 0.0, 3.0], t))
        .fold(f64::INFINITY, f64::min);
    let r = distance(&ms, &here, &point, &here, &DistanceOptions::default()).unwrap();
    assert!(close(r.distance, truth_p));
    assert_eq!(r.id2, 5);
    let seg_mesh = Mesh {
        tris: vec![[[-5.0, 0.0, 2.0], [5.0, 0.0, 2.0], [0.0, 0.0, 2.0]]],
    };
    let truth_s = brute(&sphere, &here, &seg_mesh, &here).distance;
    let r = distance(&ms, &here, &seg, &here, &DistanceOptions::default()).unwrap();
    assert!(close(r.distance, truth_s));
    assert!(truth_s > 0.9 && truth_s <= 1.0);
}

#[test]
fn large_offsets_and_tiny_gaps() {
    // Two parallel squares 1e-9 apart, a million units from the origin.
    let off = 1e6;
    let sq = |z: f64| {
        Model::from_triangles([
            (
                [off, off, z],
                [off + 1.0, off, z],
                [off + 1.0, off + 1.0, z],
                0,
            ),
            (
                [off, off, z],
                [off + 1.0, off + 1.0, z],
                [off, off + 1.0, z],
                1,
            ),
        ])
        .unwrap()
    };
    let (a, b) = (sq(off), sq(off + 1e-6));
    let here = Pose::identity();
    let r = distance(&a, &here, &b, &here, &DistanceOptions::default()).unwrap();
    // The exact answer of the stored doubles.
    let gap = (off + 1e-6) - off;
    assert!((r.distance - gap).abs() < 1e-12, "{}", r.distance);
    assert!(
        !collide(&a, &here, &b, &here, ContactMode::All)
            .unwrap()
            .colliding()
    );
}

#[test]
fn queries_validate_their_arguments() {
    let m = Mesh::sphere(1.0, 6, 4).model();
    let here = Pose::identity();
    let unbuilt = Model::new();
    assert_eq!(
        collide(&m, &here, &unbuilt, &here, ContactMode::All).unwrap_err(),
        pqp::Error::UnprocessedModel
    );
    let mut bad = Pose::identity();
    bad.translation.x = f64::NAN;
    assert_eq!(
        distance(&m, &bad, &m, &here, &DistanceOptions::default()).unwrap_err(),
        pqp::Error::NonFinitePose
    );
    bad = Pose::identity();
    bad.rotation[(1, 2)] = f64::INFINITY;
    assert_eq!(
        tolerance(&m, &here, &m, &bad, 0.1, &Search::default()).unwrap_err(),
        pqp::Error::NonFinitePose
    );
    for opts in [
        DistanceOptions {
            rel_err: -0.1,
            ..Default::default()
        },
        DistanceOptions {
            abs_err: f64::NAN,
            ..Default::default()
        },
        DistanceOptions {
            search: Search {
                qsize: 0,
                ..Search::default()
            },
            ..Default::default()
        },
    ] {
        assert_eq!(
            distance(&m, &here, &m, &here, &opts).unwrap_err(),
            pqp::Error::InvalidArgument
        );
    }
    assert_eq!(
        tolerance(&m, &here, &m, &here, -1.0, &Search::default()).unwrap_err(),
        pqp::Error::InvalidArgument
    );
    assert_eq!(
        tolerance(&m, &here, &m, &here, f64::NAN, &Search::default()).unwrap_err(),
        pqp::Error::InvalidArgument
    );
    // A model against itself is a valid query: it touches everywhere.
    assert_eq!(
        distance(&m, &here, &m, &here, &DistanceOptions::default())
            .unwrap()
            .distance,
        0.0
    );
}

#[test]
fn tiny_and_huge_models_answer_as_rescaled() {
    // Rescaling by a power of two is exact, so the distance scales with the models; at the extremes
    // the triangle tests must rescale themselves (their intermediate values reach fourth powers).
    let mut rng = Rng::new(91);
    let mut apart = 0;
    let (a, b) = (
        Mesh::soup(&mut rng, 60, 1.0, 0.3),
        Mesh::soup(&mut rng, 60, 1.0, 0.3),
    );
    for k in 0..20 {
        let (rot, t) = (rng.rotation(), rng.point(1.5));
        let pose = |s: f64| Pose::new(rot, [(t[0] + 2.5) * s, t[1] * s, t[2] * s]);
        let here = Pose::identity();
        let exact = DistanceOptions::exact();
        let unit = distance(&a.model(), &here, &b.model(), &pose(1.0), &exact).unwrap();
        apart += usize::from(unit.distance > 0.0);
        for e in [-300, -230, -150, 100, 300] {
            let s = 2f64.powi(e);
            let scaled = |m: &Mesh| Mesh {
                tris: m.tris.iter().map(|t| t.map(|p| p.map(|x| x * s))).collect(),
            };
            let (sa, sb) = (scaled(&a).model(), scaled(&b).model());
            let r = distance(&sa, &here, &sb, &pose(s), &exact).unwrap();
            assert!(
                (r.distance / s - unit.distance).abs() <= 1e-12 * unit.distance,
                "pose {k}, scale 2^{e}: {} vs {}",
                r.distance / s,
                unit.distance
            );
        }
    }
    assert!(apart >= 10, "{apart}");
}

/// Extreme but valid arguments keep the queries' promises: a tolerance of -0 is 0, an infinite
/// tolerance still reports a triangle pair within it, and error bounds so large that the cutoff
/// would underflow (or become NaN) still make touching models answer 0.
#[test]
fn extreme_tolerances_and_error_bounds() {
    let model = |tris: &[[[f64; 3]; 3]]| {
        Model::from_triangles(
            tris.iter()
                .enumerate()
                .map(|(i, t)| (t[0], t[1], t[2], i as i32)),
        )
        .unwrap()
    };
    let base = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let far = [[5.0, 5.0, 5.0], [6.0, 5.0, 5.0], [5.0, 6.0, 5.0]];
    let crossing = [[0.25, 0.25, -1.0], [0.25, 0.25, 1.0], [0.5, 0.25, 1.0]];
    let above = [[0.25, 0.25, 0.5], [0.75, 0.25, 0.5], [0.25, 0.75, 0.5]];
    let a = model(&[base, far]);
    let touching = model(&[crossing, above]);
    let other_far = [[-5.0, -5.0, -5.0], [-6.0, -5.0, -5.0], [-5.0, -6.0, -5.0]];
    let apart = model(&[above, other_far]);
    let id = Pose::identity();
    for search in all_searches() {
        for t in [0.0, -0.0] {
            let r = tolerance(&a, &id, &touching, &id, t, &search).unwrap();
            assert!(
                r.closer_than_tolerance && r.distance == 0.0,
                "{t:?} {search:?}"
            );
            let r = tolerance(&a, &id, &apart, &id, t, &search).unwrap();
            assert!(
                !r.closer_than_tolerance && r.distance > 0.0,
                "{t:?} {search:?} {r:?}"
            );
        }
        for m in [&touching, &apart] {
            let r = tolerance(&a, &id, m, &id, f64::INFINITY, &search).unwrap();
            assert!(
                r.closer_than_tolerance && r.distance.is_finite(),
                "{search:?}"
            );
            // The reported points lie on the reported triangles, that distance apart.
            assert!(r.id1 >= 0 && r.id2 >= 0);
            assert!(((r.p1 - r.p2).norm() - r.distance).abs() <= 1e-12);
        }
        for (rel_err, abs_err) in [
            (f64::INFINITY, f64::INFINITY),
            (f64::INFINITY, 1.0),
            (1e300, f64::INFINITY),
            (1e300, 1e300),
        ] {
            let opts = DistanceOptions {
                rel_err,
                abs_err,
                search,
            };
            let r = distance(&a, &id, &touching, &id, &opts).unwrap();
            assert!(
                r.distance == 0.0 && r.overlap,
                "{rel_err} {abs_err} {search:?}"
            );
            let r = distance(&a, &id, &apart, &id, &opts).unwrap();
            // Any answer at least the true distance (0.5) is within such bounds; it is a pair's.
            assert!(r.distance >= 0.5 - 1e-12 && r.distance.is_finite());
            assert!(((r.p1 - r.p2).norm() - r.distance).abs() <= 1e-12);
        }
    }
}

/// A degenerate triangle (a repeated vertex) touching coplanar triangles, with every volume
/// family and both collision volumes: every touching pair is found, as brute force finds them.
/// (A repeated vertex once gave the triangle's swept sphere volume two equal axes, and
/// collision on swept sphere volumes missed half the pairs.)
#[test]
fn degenerate_triangle_collides_with_every_volume() {
    use pqp::geometry::tri_overlap;
    let segment = [[0.25, 0.75, 0.0], [0.0, 0.5, 0.0], [0.0, 0.5, 0.0]];
    let others = [
        [[-0.5, 0.5, 0.0], [0.0, -1.0, 0.0], [0.25, 0.5, 0.0]],
        [[0.25, 1.0, 0.0], [-0.25, -1.0, 0.0], [0.25, 0.25, 0.0]],
        [[0.5, -1.0, 0.0], [-1.0, 0.5, 0.0], [0.0, 0.5, 0.0]],
        [[0.25, 0.75, 0.0], [0.0, 0.25, 0.0], [0.0, -0.75, 0.0]],
    ];
    let v = |p: [f64; 3]| pqp::Vec3::new(p[0], p[1], p[2]);
    let tri = |t: [[f64; 3]; 3]| [v(t[0]), v(t[1]), v(t[2])];
    let truth: Vec<(i32, i32)> = (0..others.len())
        .filter(|&j| tri_overlap(&tri(segment), &tri(others[j])))
        .map(|j| (0, j as i32))
        .collect();
    assert_eq!(truth.len(), 4, "the reference: all four touch the segment");
    for (kind, collision) in all_volumes() {
        let (a, b) = (
            model_with(&[segment], kind, collision),
            model_with(&others, kind, collision),
        );
        let id = Pose::identity();
        let r = collide(&a, &id, &b, &id, ContactMode::All).unwrap();
        assert_eq!(pair_ids(r.pairs()), truth, "{kind:?} {collision:?}");
    }
}

/// Builds a model of `tris` (ids = indices) with the given volumes.
fn model_with(
    tris: &[[[f64; 3]; 3]],
    kind: pqp::VolumeKind,
    collision: pqp::CollisionVolume,
) -> Model {
    let mut m = Model::new();
    m.set_volume(kind).unwrap();
    m.set_collision_volume(collision).unwrap();
    for (i, t) in tris.iter().enumerate() {
        m.add_triangle(t[0], t[1], t[2], i as i32).unwrap();
    }
    m.end().unwrap();
    m
}

/// Contact pairs as sorted ids.
fn pair_ids(pairs: &[pqp::ContactPair]) -> Vec<(i32, i32)> {
    let mut v: Vec<(i32, i32)> = pairs.iter().map(|p| (p.id1, p.id2)).collect();
    v.sort_unstable();
    v
}

/// Every volume family with each collision volume.
fn all_volumes() -> Vec<(pqp::VolumeKind, pqp::CollisionVolume)> {
    use pqp::{CollisionVolume, VolumeKind};
    let kinds = [
        VolumeKind::Rss,
        VolumeKind::Pss,
        VolumeKind::Lss,
        VolumeKind::Hybrid,
    ];
    let mut v = Vec::new();
    for k in kinds {
        for c in [CollisionVolume::Obb, CollisionVolume::Ssv] {
            v.push((k, c));
        }
    }
    v
}

/// Scenes so small that squared lengths underflow (below about 1e-154) answer as the same scenes
/// at unit scale, scaled by the same power of two (exact): every volume family and collision
/// volume, the three queries, and a coherent motion through one reused result (its front). Volumes
/// fitted there miss their points by up to about 1e-161, and lengths computed as roots of sums of
/// squares err as much, whatever the scene's size: once, a capsule fitted to 1e-300 triangles had
/// radius 0 and collision missed every contact, 1e-161 scenes answered distances 3.5% high, and a
/// front at 1e-302 pruned the closest pair.
#[test]
fn subnormal_scale_scenes_answer_as_at_unit_scale() {
    let mut rng = Rng::new(97);
    for case in 0..8 {
        // Small soups, every third triangle a segment (a repeated vertex).
        let soup = |rng: &mut Rng| {
            let mut m = Mesh::soup(rng, 10, 0.6, 0.5);
            for t in m.tris.iter_mut().step_by(3) {
                t[2] = t[1];
            }
            m
        };
        let (a, b) = (soup(&mut rng), soup(&mut rng));
        let rot = rng.rotation();
        let t0 = rng.point(0.8);
        // A small tumble: the poses of B along the motion.
        let motion: Vec<([[f64; 3]; 3], [f64; 3])> = (0..4)
            .map(|i| {
                let c = 0.01 * f64::from(i);
                let (cs, sn) = (c.cos(), c.sin());
                let turn = [[cs, -sn, 0.0], [sn, cs, 0.0], [0.0, 0.0, 1.0]];
                let mut r = [[0.0; 3]; 3];
                for (i, row) in r.iter_mut().enumerate() {
                    for (j, x) in row.iter_mut().enumerate() {
                        *x = (0..3).map(|k| turn[i][k] * rot[k][j]).sum();
                    }
                }
                (r, [t0[0] + 0.02 * c, t0[1], t0[2] - 0.01 * c])
            })
            .collect();
        let id = Pose::identity();
        let unit_pose = |k: usize| Pose::new(motion[k].0, motion[k].1);
        let truth = brute(&a, &id, &b, &unit_pose(0));
        for (kind, collision) in all_volumes() {
            let (ua, ub) = (
                model_with(&a.tris, kind, collision),
                model_with(&b.tris, kind, collision),
            );
            let exact = DistanceOptions::exact();
            let unit = distance(&ua, &id, &ub, &unit_pose(0), &exact).unwrap();
            assert!(close(unit.distance, truth.distance));
            let unit_pairs = collide(&ua, &id, &ub, &unit_pose(0), ContactMode::All).unwrap();
            for e in [-520, -535, -1000] {
                let s = 2f64.powi(e);
                let scaled = |m: &Mesh| -> Vec<[[f64; 3]; 3]> {
                    m.tris.iter().map(|t| t.map(|p| p.map(|x| x * s))).collect()
                };
                let (sa, sb) = (
                    model_with(&scaled(&a), kind, collision),
                    model_with(&scaled(&b), kind, collision),
                );
                let pose = |k: usize| Pose::new(motion[k].0, motion[k].1.map(|x| x * s));
                let what = format!("case {case}, {kind:?}/{collision:?}, scale 2^{e}");
                let r = distance(&sa, &id, &sb, &pose(0), &exact).unwrap();
                assert!(
                    (r.distance / s - unit.distance).abs() <= 1e-12 * unit.distance,
                    "{what}: {:e} vs {:e}",
                    r.distance / s,
                    unit.distance
                );
                let c = collide(&sa, &id, &sb, &pose(0), ContactMode::All).unwrap();
                assert_eq!(pair_ids(c.pairs()), pair_ids(unit_pairs.pairs()), "{what}");
                if unit.distance > 0.0 {
                    for (f, closer) in [(1.0 + 1e-9, true), (1.0 - 1e-9, false)] {
                        let t = unit.distance * f * s;
                        let r = tolerance(&sa, &id, &sb, &pose(0), t, &Search::default()).unwrap();
                        assert_eq!(r.closer_than_tolerance, closer, "{what}, {f}");
                    }
                }
                // Along the motion, one result reused (triangle cache and front).
                let mut reused = DistanceResult::new();
                for k in 0..motion.len() {
                    distance_into(&mut reused, &sa, &id, &sb, &pose(k), &exact).unwrap();
                    let fresh = distance(&ua, &id, &ub, &unit_pose(k), &exact).unwrap();
                    assert!(
                        (reused.distance / s - fresh.distance).abs() <= 1e-12 * fresh.distance,
                        "{what}, step {k}: {:e} vs {:e}",
                        reused.distance / s,
                        fresh.distance
                    );
                }
            }
        }
    }
}

/// A triangle tiny beside the other's coordinates (3e4 beside 8.7e127): its normal's square
/// underflows once the triangle test works at the pair's scale, and the test that shows a pair at
/// least the cutoff apart must then not decide (it once called this pair apart below the cutoff,
/// so that tolerance said no and cached searches answered 1.3% high).
#[test]
fn tiny_triangle_beside_huge_coordinates() {
    let a = [[[0.0, 0.0, 0.0], [0.0, 0.0, -32768.0], [0.0, 16384.0, 0.0]]];
    let b = [
        [[0.0, 0.0, 0.0]; 3],
        [
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 8.664592794127546e127],
        ],
    ];
    let (ma, mb) = (Mesh { tris: a.to_vec() }, Mesh { tris: b.to_vec() });
    let id = Pose::identity();
    let moved = Pose::from_translation([
        -1.943864225315713e121,
        -1.0855337746980732e121,
        -3.587745898334106e120,
    ]);
    let truth = brute(&ma, &id, &mb, &moved).distance;
    assert!((truth - 2.226430259961561e121).abs() <= 1e-9 * truth);
    let (a, b) = (ma.model(), mb.model());
    for search in all_searches() {
        let r = tolerance(&a, &id, &b, &moved, truth * (1.0 + 1e-6), &search).unwrap();
        assert!(r.closer_than_tolerance, "{search:?}");
        let opts = DistanceOptions {
            search,
            ..DistanceOptions::exact()
        };
        let mut reused = DistanceResult::new();
        distance_into(&mut reused, &a, &id, &b, &id, &opts).unwrap();
        distance_into(&mut reused, &a, &id, &b, &moved, &opts).unwrap();
        assert!(
            close(reused.distance, truth),
            "{search:?}: {:e}",
            reused.distance
        );
    }
}

/// Poses far apart end at the root pair (one bound test): collision (every mode) finds nothing
/// and tolerance answers "farther", with a lower bound on the distance, with a fresh result and
/// with one reused (which starts from its cached pair); near poses go on past the root as before,
/// with the answers of brute force.
#[test]
fn calls_decided_at_the_root_answer_as_the_whole_search() {
    let mut rng = Rng::new(42);
    let a = Mesh::torus(1.0, 0.3, 24, 12);
    let b = Mesh::sphere(0.6, 16, 10);
    let (ma, mb) = (a.model(), b.model());
    let mut reused = pqp::ToleranceResult::new();
    for k in 0..60 {
        let pa = Pose::new(rng.rotation(), rng.point(0.3));
        let d = rng.direction();
        // Far (beyond any root volume) or near (through the root test).
        let s = if k % 2 == 0 {
            rng.range(8.0, 20.0)
        } else {
            rng.range(0.5, 2.0)
        };
        let pb = Pose::new(rng.rotation(), d.map(|x| x * s));
        let truth = brute(&a, &pa, &b, &pb).distance;
        let t = rng.range(0.001, 0.3);
        if (truth - t).abs() < 1e-9 {
            continue;
        }
        for mode in [ContactMode::First, ContactMode::All] {
            let c = collide(&ma, &pa, &mb, &pb, mode).unwrap();
            assert_eq!(c.pairs().is_empty(), truth > 0.0);
            if k % 2 == 0 {
                assert_eq!((c.stats.bv_tests, c.stats.tri_tests), (1, 0));
            }
        }
        let fresh = tolerance(&ma, &pa, &mb, &pb, t, &Search::default()).unwrap();
        pqp::tolerance_into(&mut reused, &ma, &pa, &mb, &pb, t, &Search::default()).unwrap();
        for r in [&fresh, &reused] {
            assert_eq!(r.closer_than_tolerance, truth <= t);
            if !r.closer_than_tolerance {
                assert!(r.distance > t && r.distance <= truth + 1e-12);
                assert_eq!((r.id1, r.id2), (-1, -1));
            }
        }
        if k % 2 == 0 {
            assert_eq!((fresh.stats.bv_tests, fresh.stats.tri_tests), (1, 0));
        }
    }
}

/// An approximate distance with a new result starts from a probe's pair (one descent to a pair
/// of leaves), so its error bound prunes from the start: on poses from overlapping to far, it
/// never does more bound tests than the exact query and in all a small fraction of them, and its
/// answer depends on the pose alone (the same bits from a new result, whatever was asked before).
#[test]
fn approximate_distance_stops_early_from_a_new_result() {
    let mut rng = Rng::new(77);
    let a = Mesh::torus(1.0, 0.3, 40, 20);
    let b = Mesh::sphere(0.7, 24, 16);
    let (ma, mb) = (a.model(), b.model());
    let (mut exact_tests, mut approx_tests) = (0, 0);
    let opts = DistanceOptions::approximate(0.1, f64::INFINITY);
    for _ in 0..40 {
        let pa = Pose::new(rng.rotation(), [0.0; 3]);
        let d = rng.direction();
        let s = rng.range(0.5, 6.0);
        let pb = Pose::new(rng.rotation(), d.map(|x| x * s));
        let exact = distance(&ma, &pa, &mb, &pb, &DistanceOptions::exact()).unwrap();
        let approx = distance(&ma, &pa, &mb, &pb, &opts).unwrap();
        assert!(approx.distance >= exact.distance - 1e-12);
        assert!(approx.distance <= exact.distance * 1.1 + 1e-12);
        let again = distance(&ma, &pa, &mb, &pb, &opts).unwrap();
        assert_eq!(again.distance.to_bits(), approx.distance.to_bits());
        assert_eq!(again.stats.bv_tests, approx.stats.bv_tests);
        assert!(approx.stats.bv_tests <= exact.stats.bv_tests, "{s}");
        exact_tests += exact.stats.bv_tests;
        approx_tests += approx.stats.bv_tests;
    }
    assert!(
        approx_tests * 4 < exact_tests,
        "{approx_tests} vs {exact_tests}"
    );
}
