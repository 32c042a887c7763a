//! The swept sphere volume family in whole models: every volume choice (PSS, LSS, RSS, hybrid) and
//! both collision volumes (OBB, SSV) give the exact answers of brute force on random meshes and
//! poses, so the same answers as each other; and the choice through the Rust and C APIs.

// Edition 2024: these helpers' bodies call the C ABI under their own `unsafe fn` contract.
#![allow(unsafe_op_in_unsafe_fn)]

mod common;

use common::{Mesh, Random, RandomPqp, Rng, brute};
use pqp::capi::*;
use pqp::{
    CollisionVolume, ContactMode, DistanceOptions, Error, Model, Pose, Search, VolumeKind, collide,
    distance, tolerance,
};

const VOLUMES: [VolumeKind; 4] = [
    VolumeKind::Rss,
    VolumeKind::Pss,
    VolumeKind::Lss,
    VolumeKind::Hybrid,
];

fn model(mesh: &Mesh, volume: VolumeKind, collision: CollisionVolume) -> Model {
    let mut m = Model::new();
    m.set_volume(volume).unwrap();
    m.set_collision_volume(collision).unwrap();
    for (i, t) in mesh.tris.iter().enumerate() {
        m.add_triangle(t[0], t[1], t[2], i as i32).unwrap();
    }
    m.end().unwrap();
    assert_eq!((m.volume(), m.collision_volume()), (volume, collision));
    m
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()) + 1e-12
}

/// Every choice of volumes answers all three queries as brute force does.
fn check_all_choices(a: &Mesh, b: &Mesh, poses: &[(Pose, Pose)]) -> usize {
    let truths: Vec<_> = poses.iter().map(|(pa, pb)| brute(a, pa, b, pb)).collect();
    let mut colliding = 0;
    for volume in VOLUMES {
        for collision in [CollisionVolume::Obb, CollisionVolume::Ssv] {
            let (ma, mb) = (model(a, volume, collision), model(b, volume, collision));
            for ((pa, pb), truth) in poses.iter().zip(&truths) {
                let what = format!("{volume:?}/{collision:?}");
                let all = collide(&ma, pa, &mb, pb, ContactMode::All).unwrap();
                let mut got: Vec<(i32, i32)> = all.pairs().iter().map(|p| (p.id1, p.id2)).collect();
                got.sort();
                assert_eq!(got, truth.pairs, "{what}");
                colliding += usize::from(all.colliding());
                for search in [Search::default(), Search::pqp(2), Search::pqp(100)] {
                    let opts = DistanceOptions {
                        search,
                        ..DistanceOptions::exact()
                    };
                    let d = distance(&ma, pa, &mb, pb, &opts).unwrap();
                    assert!(
                        close(d.distance, truth.distance),
                        "{what}: distance {} vs brute {}",
                        d.distance,
                        truth.distance
                    );
                }
                for t in [0.01, 0.1, 0.5] {
                    if (truth.distance - t).abs() < 1e-9 {
                        continue;
                    }
                    let r = tolerance(&ma, pa, &mb, pb, t, &Search::default()).unwrap();
                    assert_eq!(r.closer_than_tolerance, truth.distance <= t, "{what} t {t}");
                }
            }
        }
    }
    colliding
}

#[test]
fn every_volume_choice_answers_exactly_on_random_soups() {
    let mut rng = Rng::new(61);
    let mut colliding = 0;
    for case in 0..12 {
        let a = Mesh::soup(&mut rng, 40 + 3 * case, 1.0, 0.3);
        let b = Mesh::soup(&mut rng, 30 + 2 * case, 1.0, 0.3);
        let poses: Vec<(Pose, Pose)> = (0..4)
            .map(|k| {
                let spread = [0.5, 1.5, 3.0, 20.0][k];
                (rng.pose(spread), rng.pose(spread))
            })
            .collect();
        colliding += check_all_choices(&a, &b, &poses);
    }
    // Both verdicts are exercised.
    assert!(colliding > 40 && colliding < 12 * 4 * 8, "{colliding}");
}

#[test]
fn every_volume_choice_answers_exactly_on_spheres_and_tori() {
    let mut rng = Rng::new(62);
    let sphere = Mesh::sphere(1.0, 20, 12);
    let torus = Mesh::torus(1.0, 0.3, 24, 10);
    let mut poses = Vec::new();
    for gap in [1e-4, 0.05, 0.3, 2.0] {
        let dir = rng.point(1.0);
        let len = common::norm(dir);
        let off = (2.3 + gap) / len;
        poses.push((
            rng.pose(0.0),
            Pose::new(rng.rotation(), [dir[0] * off, dir[1] * off, dir[2] * off]),
        ));
    }
    // Through each other.
    for _ in 0..3 {
        poses.push((rng.pose(0.3), rng.pose(0.3)));
    }
    let colliding = check_all_choices(&sphere, &torus, &poses);
    assert!(colliding > 0);
}

#[test]
fn the_choice_is_made_before_end_and_kept() {
    let mut m = Model::new();
    assert_eq!(m.volume(), VolumeKind::Rss);
    assert_eq!(m.collision_volume(), CollisionVolume::Obb);
    m.set_volume(VolumeKind::Lss).unwrap();
    m.begin(1).unwrap();
    m.set_collision_volume(CollisionVolume::Ssv).unwrap();
    m.add_triangle([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0)
        .unwrap();
    m.end().unwrap();
    assert_eq!(
        m.set_volume(VolumeKind::Pss),
        Err(Error::BuildOutOfSequence)
    );
    assert_eq!(
        m.set_collision_volume(CollisionVolume::Obb),
        Err(Error::BuildOutOfSequence)
    );
    assert_eq!(m.volume(), VolumeKind::Lss);
    // A rebuild keeps the choice.
    assert_eq!(m.begin(1), Err(Error::BuildOutOfSequence));
    assert_eq!(m.volume(), VolumeKind::Lss);
    assert_eq!(m.collision_volume(), CollisionVolume::Ssv);
}

/// A C model of `mesh` with the given choices, built.
unsafe fn c_model(mesh: &Mesh, volume: i32, collision: i32) -> *mut pqp_model {
    let m = pqp_model_create();
    assert_eq!(pqp_model_set_volume(m, volume), PQP_OK);
    assert_eq!(pqp_model_set_collision_volume(m, collision), PQP_OK);
    assert_eq!(pqp_model_begin(m, mesh.tris.len() as i32), PQP_OK);
    for (i, t) in mesh.tris.iter().enumerate() {
        let r = pqp_model_add_tri(m, t[0].as_ptr(), t[1].as_ptr(), t[2].as_ptr(), i as i32);
        assert_eq!(r, PQP_OK);
    }
    assert_eq!(pqp_model_end(m), PQP_OK);
    m
}

#[test]
fn c_api_chooses_volumes_with_documented_codes() {
    unsafe {
        assert_eq!(
            pqp_model_set_volume(std::ptr::null_mut(), PQP_BV_PSS),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_model_set_collision_volume(std::ptr::null_mut(), PQP_COLLIDE_SSV),
            PQP_ERR_NULL_POINTER
        );
        let m = pqp_model_create();
        for bad in [-1, 4, 99, i32::MIN, i32::MAX] {
            assert_eq!(pqp_model_set_volume(m, bad), PQP_ERR_INVALID_ARGUMENT);
        }
        for bad in [-1, 2, i32::MAX] {
            assert_eq!(
                pqp_model_set_collision_volume(m, bad),
                PQP_ERR_INVALID_ARGUMENT
            );
        }
        let (p, q, r) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(
            pqp_model_add_tri(m, p.as_ptr(), q.as_ptr(), r.as_ptr(), 0),
            PQP_OK
        );
        assert_eq!(pqp_model_end(m), PQP_OK);
        assert_eq!(
            pqp_model_set_volume(m, PQP_BV_HYBRID),
            PQP_ERR_BUILD_OUT_OF_SEQUENCE
        );
        assert_eq!(
            pqp_model_set_collision_volume(m, PQP_COLLIDE_SSV),
            PQP_ERR_BUILD_OUT_OF_SEQUENCE
        );
        pqp_model_destroy(m);
    }
}

#[test]
fn c_api_answers_are_the_same_for_every_choice() {
    let mut rng = Rng::new(63);
    let a = Mesh::soup(&mut rng, 60, 1.0, 0.3);
    let b = Mesh::soup(&mut rng, 50, 1.0, 0.3);
    let (pa, pb) = (rng.rotation(), rng.rotation());
    let (ra, rb): (Vec<f64>, Vec<f64>) = (
        pa.iter().flatten().copied().collect(),
        pb.iter().flatten().copied().collect(),
    );
    let (ta, tb) = ([0.0; 3], [0.4, 0.3, 0.2]);
    let truth = brute(&a, &Pose::new(pa, ta), &b, &Pose::new(pb, tb));
    assert!(!truth.pairs.is_empty());
    unsafe {
        for volume in [PQP_BV_RSS, PQP_BV_PSS, PQP_BV_LSS, PQP_BV_HYBRID] {
            for collision in [PQP_COLLIDE_OBB, PQP_COLLIDE_SSV] {
                let (ma, mb) = (
                    c_model(&a, volume, collision),
                    c_model(&b, volume, collision),
                );
                let cr = pqp_collide_result_create();
                let code = pqp_collide(
                    cr,
                    ra.as_ptr(),
                    ta.as_ptr(),
                    ma,
                    rb.as_ptr(),
                    tb.as_ptr(),
                    mb,
                    PQP_ALL_CONTACTS,
                );
                assert_eq!(code, PQP_OK);
                let n = pqp_collide_result_num_pairs(cr);
                let mut got: Vec<(i32, i32)> = (0..n)
                    .map(|k| (pqp_collide_result_id1(cr, k), pqp_collide_result_id2(cr, k)))
                    .collect();
                got.sort();
                assert_eq!(got, truth.pairs, "volume {volume} collision {collision}");
                let dr = pqp_distance_result_create();
                let far = [3.0, 0.0, 0.0];
                let code = pqp_distance(
                    dr,
                    ra.as_ptr(),
                    ta.as_ptr(),
                    ma,
                    rb.as_ptr(),
                    far.as_ptr(),
                    mb,
                    0.0,
                    0.0,
                    2,
                );
                assert_eq!(code, PQP_OK);
                let want = brute(&a, &Pose::new(pa, ta), &b, &Pose::new(pb, far)).distance;
                assert!(close(pqp_distance_result_distance(dr), want));
                pqp_distance_result_destroy(dr);
                pqp_collide_result_destroy(cr);
                pqp_model_destroy(ma);
                pqp_model_destroy(mb);
            }
        }
    }
}
