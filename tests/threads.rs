//! Many threads querying the same built models at once get the serial answers.

mod common;

use common::{Mesh, RandomPqp, Rng};
use pqp::{
    ContactMode, DistanceOptions, DistanceResult, Pose, Search, collide, distance_into, tolerance,
};
use std::sync::Arc;

#[derive(Debug, PartialEq)]
struct Answers {
    pairs: Vec<Vec<(i32, i32)>>,
    distances: Vec<f64>,
    verdicts: Vec<bool>,
}

fn run(ma: &pqp::Model, mb: &pqp::Model, poses: &[(Pose, Pose)]) -> Answers {
    // One result reused across poses: each thread has its own triangle cache.
    let mut dres = DistanceResult::new();
    let mut out = Answers {
        pairs: Vec::new(),
        distances: Vec::new(),
        verdicts: Vec::new(),
    };
    for (pa, pb) in poses {
        let c = collide(ma, pa, mb, pb, ContactMode::All).unwrap();
        let mut p: Vec<_> = c.pairs().iter().map(|p| (p.id1, p.id2)).collect();
        p.sort();
        out.pairs.push(p);
        distance_into(&mut dres, ma, pa, mb, pb, &DistanceOptions::default()).unwrap();
        out.distances.push(dres.distance);
        out.verdicts.push(
            tolerance(ma, pa, mb, pb, 0.05, &Search::default())
                .unwrap()
                .closer_than_tolerance,
        );
    }
    out
}

#[test]
fn concurrent_queries_on_shared_models_match_serial_answers() {
    let mut rng = Rng::new(7);
    let a = Mesh::torus(1.0, 0.3, 30, 16);
    let b = Mesh::sphere(0.8, 24, 16);
    let (ma, mb) = (Arc::new(a.model()), Arc::new(b.model()));
    let poses: Vec<(Pose, Pose)> = (0..80).map(|_| (rng.pose(0.2), rng.pose(1.5))).collect();
    let serial = run(&ma, &mb, &poses);
    assert!(serial.pairs.iter().any(|p| !p.is_empty()));
    assert!(serial.distances.iter().any(|&d| d > 0.0));
    let poses = Arc::new(poses);
    let handles: Vec<_> = (0..6)
        .map(|k| {
            let (ma, mb, poses) = (Arc::clone(&ma), Arc::clone(&mb), Arc::clone(&poses));
            std::thread::spawn(move || {
                // Different threads walk the poses in different orders, so their caches differ.
                let mut order: Vec<usize> = (0..poses.len()).collect();
                order.rotate_left(k * 13 % poses.len());
                let mine: Vec<(Pose, Pose)> = order.iter().map(|&i| poses[i]).collect();
                let ans = run(&ma, &mb, &mine);
                (order, ans)
            })
        })
        .collect();
    for h in handles {
        let (order, ans) = h.join().unwrap();
        for (slot, &i) in order.iter().enumerate() {
            assert_eq!(ans.pairs[slot], serial.pairs[i]);
            assert_eq!(ans.verdicts[slot], serial.verdicts[i]);
            let (x, y) = (ans.distances[slot], serial.distances[i]);
            assert!((x - y).abs() <= 1e-12 * x.max(y).max(1.0), "{x} vs {y}");
        }
    }
}

#[test]
fn models_are_send_and_sync() {
    fn check<T: Send + Sync>() {}
    check::<pqp::Model>();
    check::<pqp::DistanceResult>();
    check::<pqp::CollideResult>();
    check::<pqp::ToleranceResult>();
}
