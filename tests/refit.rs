//! Refit (`Model::refit`): after deformations (a sheet bending, a sphere inflating into an
//! ellipsoid, random vertex noise) every query on the refitted model equals brute force over all
//! triangle pairs and the same query on a model rebuilt from the new triangles; every volume
//! contains its triangles; bad input leaves the model unchanged.

mod common;

use common::{Mesh, Random, RandomPqp, Rng, T};
use pqp::diagnostics::check_containment;
use pqp::geometry::{tri_distance, tri_overlap};
use pqp::{
    CollisionVolume, ContactMode, DistanceOptions, Error, Model, Pose, Search, Vec3, VolumeKind,
    collide, distance, tolerance,
};

/// A model of `mesh` (ids are indices) with the given volumes.
fn build(mesh: &[T], volume: VolumeKind, collision: CollisionVolume) -> Model {
    let mut m = Model::new();
    m.set_volume(volume).unwrap();
    m.set_collision_volume(collision).unwrap();
    m.begin(mesh.len()).unwrap();
    for (i, t) in mesh.iter().enumerate() {
        m.add_triangle(t[0], t[1], t[2], i as i32).unwrap();
    }
    m.end().unwrap();
    m
}

fn world(mesh: &[T], pose: &Pose) -> Vec<pqp::geometry::Tri> {
    mesh.iter()
        .map(|t| t.map(|p| pose.transform_point(&Vec3::from(p))))
        .collect()
}

/// Exact brute force: the overlapping pairs (sorted) and the distance.
fn brute(a: &[T], pa: &Pose, b: &[T], pb: &Pose) -> (Vec<(i32, i32)>, f64) {
    let (wa, wb) = (world(a, pa), world(b, pb));
    let mut pairs = Vec::new();
    let mut d = f64::INFINITY;
    for (i, ta) in wa.iter().enumerate() {
        for (j, tb) in wb.iter().enumerate() {
            if tri_overlap(ta, tb) {
                pairs.push((i as i32, j as i32));
                d = 0.0;
            } else {
                d = d.min(tri_distance(ta, tb).distance);
            }
        }
    }
    pairs.sort();
    (pairs, d)
}

fn pairs(m1: &Model, p1: &Pose, m2: &Model, p2: &Pose) -> Vec<(i32, i32)> {
    let r = collide(m1, p1, m2, p2, ContactMode::All).unwrap();
    let mut v: Vec<_> = r.pairs().iter().map(|p| (p.id1, p.id2)).collect();
    v.sort();
    v
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
}

/// Every query of `refit` (refitted to `now`) against `other` at random poses equals brute force
/// and the same query on `rebuilt` (built from `now`).
fn check_queries(
    rng: &mut Rng,
    refit: &Model,
    rebuilt: &Model,
    now: &[T],
    other: &[T],
    poses: usize,
) {
    let om = build(other, VolumeKind::Rss, CollisionVolume::Obb);
    let p1 = Pose::identity();
    for _ in 0..poses {
        let p2 = rng.pose(1.0);
        let (want, d) = brute(now, &p1, other, &p2);
        assert_eq!(pairs(refit, &p1, &om, &p2), want);
        assert_eq!(pairs(rebuilt, &p1, &om, &p2), want);
        let first = collide(refit, &p1, &om, &p2, ContactMode::First).unwrap();
        assert_eq!(first.colliding(), !want.is_empty());
        let exact = distance(refit, &p1, &om, &p2, &DistanceOptions::exact()).unwrap();
        let again = distance(rebuilt, &p1, &om, &p2, &DistanceOptions::exact()).unwrap();
        assert!(close(exact.distance, d), "{} vs brute {d}", exact.distance);
        assert!(close(again.distance, d));
        let approx = distance(
            refit,
            &p1,
            &om,
            &p2,
            &DistanceOptions::approximate(0.2, 0.0),
        )
        .unwrap();
        assert!(approx.distance >= d * (1.0 - 1e-12) && approx.distance <= d * 1.2 + 1e-12);
        for tol in [0.5 * d, 0.9 * d, 1.1 * d, 2.0 * d + 0.01] {
            if (tol - d).abs() < 1e-9 {
                continue;
            }
            let t = tolerance(refit, &p1, &om, &p2, tol, &Search::default()).unwrap();
            assert_eq!(t.closer_than_tolerance, d <= tol, "tol {tol} d {d}");
        }
    }
}

/// A flat `n x n` grid sheet of side 2 in the xy plane.
fn sheet(n: usize) -> Vec<T> {
    let p = |i: usize, j: usize| {
        [
            2.0 * i as f64 / n as f64 - 1.0,
            2.0 * j as f64 / n as f64 - 1.0,
            0.0,
        ]
    };
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    tris
}

fn deform(mesh: &[T], f: impl Fn([f64; 3]) -> [f64; 3]) -> Vec<T> {
    mesh.iter().map(|t| t.map(&f)).collect()
}

/// The sheet rolled by angle `a` (radians) around a cylinder whose axis is along y.
fn bend(p: [f64; 3], a: f64) -> [f64; 3] {
    if a == 0.0 {
        return p;
    }
    let r = 2.0 / a;
    let th = (p[0] + 1.0) / r;
    [r * th.sin() - 1.0, p[1], r * (1.0 - th.cos()) + p[2]]
}

const KINDS: [(VolumeKind, CollisionVolume); 4] = [
    (VolumeKind::Rss, CollisionVolume::Obb),
    (VolumeKind::Pss, CollisionVolume::Ssv),
    (VolumeKind::Lss, CollisionVolume::Obb),
    (VolumeKind::Hybrid, CollisionVolume::Ssv),
];

#[test]
fn bending_sheet_queries_equal_brute_force_and_rebuild() {
    let mut rng = Rng::new(20);
    let base = sheet(12);
    let other = Mesh::soup(&mut rng, 40, 1.2, 0.3).tris;
    for (volume, collision) in KINDS {
        let mut m = build(&base, volume, collision);
        for step in 1..=4 {
            let now = deform(&base, |p| bend(p, 1.5 * step as f64));
            m.refit(&now).unwrap();
            check_containment(&m).unwrap();
            let rebuilt = build(&now, volume, collision);
            check_queries(&mut rng, &m, &rebuilt, &now, &other, 6);
        }
    }
}

#[test]
fn inflating_sphere_queries_equal_brute_force_and_rebuild() {
    let mut rng = Rng::new(21);
    let base = Mesh::sphere(0.6, 16, 8).tris;
    let other = Mesh::torus(0.9, 0.2, 12, 6).tris;
    for (volume, collision) in KINDS {
        let mut m = build(&base, volume, collision);
        for step in 1..=4 {
            let s = 0.4 * step as f64;
            let now = deform(&base, |p| [p[0] * (1.0 + s), p[1] * (1.0 + 0.5 * s), p[2]]);
            m.refit(&now).unwrap();
            check_containment(&m).unwrap();
            let rebuilt = build(&now, volume, collision);
            check_queries(&mut rng, &m, &rebuilt, &now, &other, 6);
        }
    }
}

#[test]
fn noisy_vertices_queries_equal_brute_force_and_rebuild() {
    let mut rng = Rng::new(22);
    for (volume, collision) in KINDS {
        let base = Mesh::soup(&mut rng, 150, 1.0, 0.25).tris;
        let other = Mesh::soup(&mut rng, 60, 1.0, 0.25).tris;
        let mut m = build(&base, volume, collision);
        let mut now = base.clone();
        for step in 0..4 {
            // Noise per vertex, growing; every other step collapses some triangles to segments
            // and points (degenerate input refits too).
            let amp = 0.05 * (step + 1) as f64;
            for t in now.iter_mut() {
                for p in t.iter_mut() {
                    let d = rng.point(amp);
                    *p = [p[0] + d[0], p[1] + d[1], p[2] + d[2]];
                }
            }
            if step % 2 == 1 {
                for t in now.iter_mut().step_by(7) {
                    t[2] = t[1];
                }
            }
            m.refit(&now).unwrap();
            check_containment(&m).unwrap();
            let rebuilt = build(&now, volume, collision);
            check_queries(&mut rng, &m, &rebuilt, &now, &other, 5);
        }
    }
}

/// Shared models: the bunny and the torus, refitted through a twist, far from the origin and at
/// huge and tiny scales: containment holds as after a build, and collision equals brute force.
#[test]
fn shared_models_refit_at_every_scale() {
    let mut rng = Rng::new(23);
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models");
    let dir = if dir.exists() {
        dir
    } else {
        std::path::PathBuf::from("/work/shared/models")
    };
    for name in ["bunny.tris", "torus.tris"] {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        let nums: Vec<f64> = text
            .split_whitespace()
            .map(|w| w.parse().unwrap())
            .collect();
        let n = nums[0] as usize;
        let base: Vec<T> = (0..n)
            .map(|k| {
                let v = |i: usize| {
                    let o = 1 + 9 * k + 3 * i;
                    [nums[o], nums[o + 1], nums[o + 2]]
                };
                [v(0), v(1), v(2)]
            })
            .collect();
        let mut m = build(&base, VolumeKind::Rss, CollisionVolume::Obb);
        for (scale, offset) in [(1.0, 0.0), (1e100, 3e100), (1e-100, 0.0), (1.0, 1e6)] {
            let now = deform(&base, |p| {
                let a = 0.8 * p[2];
                let (s, c) = a.sin_cos();
                [
                    (c * p[0] - s * p[1]) * scale + offset,
                    (s * p[0] + c * p[1]) * scale,
                    p[2] * scale,
                ]
            });
            m.refit(&now).unwrap();
            check_containment(&m).unwrap_or_else(|e| panic!("{name} at {scale}: {e}"));
        }
        // Back at unit scale, a few collision queries against brute force.
        let now = deform(&base, |p| [p[0] * 1.3, p[1], p[2] * 0.8]);
        m.refit(&now).unwrap();
        let probe: Vec<T> = base.iter().step_by(base.len() / 80).copied().collect();
        let pm = build(&probe, VolumeKind::Rss, CollisionVolume::Obb);
        for _ in 0..4 {
            let p2 = rng.pose(0.05);
            let (want, _) = brute(&now, &Pose::identity(), &probe, &p2);
            assert_eq!(pairs(&m, &Pose::identity(), &pm, &p2), want, "{name}");
        }
    }
}

/// A refit back to the original coordinates, then a clone: both answer as the original build.
#[test]
fn refit_round_trip_and_clone() {
    let mut rng = Rng::new(24);
    let base = Mesh::sphere(0.7, 12, 6).tris;
    let other = Mesh::soup(&mut rng, 30, 0.8, 0.3).tris;
    let mut m = build(&base, VolumeKind::Rss, CollisionVolume::Obb);
    let moved = deform(&base, |p| [p[0] + 0.3 * p[1], p[1], p[2] * 2.0]);
    m.refit(&moved).unwrap();
    m.refit(&base).unwrap();
    let c = m.try_clone().unwrap();
    let rebuilt = build(&base, VolumeKind::Rss, CollisionVolume::Obb);
    check_queries(&mut rng, &c, &rebuilt, &base, &other, 5);
}

/// A distance result reused across a refit does not trust what it cached for the old shape.
#[test]
fn reused_results_see_the_refit() {
    let base = sheet(8);
    let probe = vec![[[0.0, 0.0, 0.5], [0.1, 0.0, 0.5], [0.0, 0.1, 0.5]]];
    let mut m = build(&base, VolumeKind::Rss, CollisionVolume::Obb);
    let pm = build(&probe, VolumeKind::Rss, CollisionVolume::Obb);
    let id = Pose::identity();
    let mut r = pqp::DistanceResult::new();
    for step in 0..6 {
        let lift = 0.08 * step as f64;
        let now = deform(&base, |p| [p[0], p[1], lift * (1.0 - p[0] * p[0])]);
        m.refit(&now).unwrap();
        pqp::distance_into(&mut r, &m, &id, &pm, &id, &DistanceOptions::exact()).unwrap();
        let (_, d) = brute(&now, &id, &probe, &id);
        assert!(close(r.distance, d), "step {step}: {} vs {d}", r.distance);
    }
}

#[test]
fn bad_input_leaves_the_model_unchanged() {
    let mut rng = Rng::new(25);
    let base = Mesh::soup(&mut rng, 50, 1.0, 0.3).tris;
    let other = build(
        &Mesh::soup(&mut rng, 50, 1.0, 0.3).tris,
        VolumeKind::Rss,
        CollisionVolume::Obb,
    );
    let mut m = build(&base, VolumeKind::Rss, CollisionVolume::Obb);
    let p2 = rng.pose(0.3);
    let before = (pairs(&m, &Pose::identity(), &other, &p2), m.memory_usage());
    let moved = deform(&base, |p| [p[0] * 3.0, p[1], p[2]]);
    assert_eq!(m.refit(&moved[..49]), Err(Error::InvalidArgument));
    let mut longer = moved.clone();
    longer.push(moved[0]);
    assert_eq!(m.refit(&longer), Err(Error::InvalidArgument));
    for bad in [
        f64::NAN,
        f64::INFINITY,
        -f64::INFINITY,
        1.0000001e150,
        -2e150,
    ] {
        let mut t = moved.clone();
        t[49][2][1] = bad;
        assert_eq!(m.refit(&t), Err(Error::NonFiniteCoordinate));
    }
    let after = (pairs(&m, &Pose::identity(), &other, &p2), m.memory_usage());
    assert_eq!(before, after);
    check_containment(&m).unwrap();
    // The largest accepted magnitude is accepted.
    let mut edge = base.clone();
    edge[0][0] = [1e150, -1e150, 0.0];
    m.refit(&edge).unwrap();
    check_containment(&m).unwrap();
    // Unbuilt models: fresh, begun, and cleared.
    let mut fresh = Model::new();
    assert_eq!(fresh.refit(&[]), Err(Error::UnprocessedModel));
    assert_eq!(fresh.refit(&base[..1]), Err(Error::UnprocessedModel));
    fresh
        .add_triangle(base[0][0], base[0][1], base[0][2], 0)
        .unwrap();
    assert_eq!(fresh.refit(&base[..1]), Err(Error::UnprocessedModel));
    assert_eq!(fresh.num_triangles(), 1);
}
