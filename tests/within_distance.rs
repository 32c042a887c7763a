//! Pairs within a distance (`within_distance`): equal to brute force over all triangle pairs
//! (exact overlap, else the exact triangle distance against the tolerance) on random soups and
//! the shared models at random poses; at tolerance 0 equal to the collision query's pairs; bad
//! input refused with the result unchanged.

mod common;

use common::{Mesh, RandomPqp, Rng, T};
use pqp::geometry::{tri_distance, tri_overlap};
use pqp::{
    CollideResult, ContactMode, Error, Model, Pose, Vec3, collide, within_distance,
    within_distance_into,
};

fn world(mesh: &[T], pose: &Pose) -> Vec<pqp::geometry::Tri> {
    mesh.iter()
        .map(|t| t.map(|p| pose.transform_point(&Vec3::from(p))))
        .collect()
}

/// All pairs within `tol`, and the distances of the pairs nearest the boundary (to skip cases
/// that rounding decides).
fn brute(a: &[T], pa: &Pose, b: &[T], pb: &Pose, tol: f64) -> (Vec<(i32, i32)>, bool) {
    let (wa, wb) = (world(a, pa), world(b, pb));
    let mut out = Vec::new();
    let mut borderline = false;
    for (i, ta) in wa.iter().enumerate() {
        for (j, tb) in wb.iter().enumerate() {
            let hit = tri_overlap(ta, tb) || {
                let d = tri_distance(ta, tb).distance;
                borderline |= tol > 0.0 && (d - tol).abs() <= 1e-12 * (1.0 + tol);
                tol > 0.0 && d <= tol
            };
            if hit {
                out.push((i as i32, j as i32));
            }
        }
    }
    (out, borderline)
}

fn sorted(r: &CollideResult) -> Vec<(i32, i32)> {
    let mut v: Vec<_> = r.pairs().iter().map(|p| (p.id1, p.id2)).collect();
    let n = v.len();
    v.sort();
    v.dedup();
    assert_eq!(n, v.len(), "a pair listed twice");
    v
}

fn check(rng: &mut Rng, a: &[T], b: &[T], poses: usize, tols: &[f64]) {
    let (ma, mb) = (
        Mesh { tris: a.to_vec() }.model(),
        Mesh { tris: b.to_vec() }.model(),
    );
    for _ in 0..poses {
        let (pa, pb) = (rng.pose(0.5), rng.pose(0.5));
        for &tol in tols {
            let (want, borderline) = brute(a, &pa, b, &pb, tol);
            if borderline {
                continue;
            }
            let got = within_distance(&ma, &pa, &mb, &pb, tol).unwrap();
            assert_eq!(sorted(&got), want, "tolerance {tol}");
            if tol == 0.0 {
                let c = collide(&ma, &pa, &mb, &pb, ContactMode::All).unwrap();
                assert_eq!(sorted(&c), want);
            }
        }
    }
}

#[test]
fn random_soups_equal_brute_force() {
    let mut rng = Rng::new(50);
    for k in 0..4 {
        let a = Mesh::soup(&mut rng, 80 + 20 * k, 1.0, 0.3).tris;
        let b = Mesh::soup(&mut rng, 60, 1.0, 0.3).tris;
        check(&mut rng, &a, &b, 4, &[0.0, 0.01, 0.1, 0.4]);
    }
}

#[test]
fn closed_meshes_equal_brute_force() {
    let mut rng = Rng::new(51);
    let a = Mesh::torus(0.8, 0.25, 16, 8).tris;
    let b = Mesh::sphere(0.5, 12, 6).tris;
    check(&mut rng, &a, &b, 6, &[0.0, 0.05, 0.2]);
}

#[test]
fn shared_models_equal_brute_force() {
    let mut rng = Rng::new(52);
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models");
    let dir = if dir.exists() {
        dir
    } else {
        std::path::PathBuf::from("/work/shared/models")
    };
    let text = std::fs::read_to_string(dir.join("torus.tris")).unwrap();
    let nums: Vec<f64> = text
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    let torus: Vec<T> = (0..nums[0] as usize)
        .map(|k| {
            let v = |i: usize| {
                let o = 1 + 9 * k + 3 * i;
                [nums[o], nums[o + 1], nums[o + 2]]
            };
            [v(0), v(1), v(2)]
        })
        .collect();
    // The torus against a patch of itself (a sixth of its triangles), rescaled to unit size.
    let scale = 1.0
        / torus
            .iter()
            .flatten()
            .map(|p| p[0].abs())
            .fold(0.0, f64::max);
    let torus: Vec<T> = torus
        .iter()
        .map(|t| t.map(|p| p.map(|x| x * scale)))
        .collect();
    let patch: Vec<T> = torus.iter().step_by(6).copied().collect();
    check(&mut rng, &torus, &patch, 3, &[0.0, 0.02, 0.1]);
}

#[test]
fn bad_input_is_refused_and_leaves_the_result() {
    let mut rng = Rng::new(53);
    let a = Mesh::soup(&mut rng, 40, 0.5, 0.3).model();
    let id = Pose::identity();
    let mut r = within_distance(&a, &id, &a, &id, 0.1).unwrap();
    let before = sorted(&r);
    assert!(!before.is_empty());
    for tol in [-1e-300, -1.0, f64::NAN, f64::NEG_INFINITY] {
        assert_eq!(
            within_distance_into(&mut r, &a, &id, &a, &id, tol),
            Err(Error::InvalidArgument)
        );
        assert_eq!(sorted(&r), before);
    }
    let fresh = Model::new();
    assert_eq!(
        within_distance_into(&mut r, &a, &id, &fresh, &id, 0.1),
        Err(Error::UnprocessedModel)
    );
    let bad = Pose::new(
        [[f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        [0.0; 3],
    );
    assert_eq!(
        within_distance_into(&mut r, &a, &bad, &a, &id, 0.1),
        Err(Error::NonFinitePose)
    );
    assert_eq!(sorted(&r), before);
    // An infinite tolerance lists every pair.
    let all = within_distance(&a, &id, &a, &id, f64::INFINITY).unwrap();
    assert_eq!(all.num_pairs(), 40 * 40);
}
