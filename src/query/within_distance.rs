//! Pairs within a distance: every triangle pair of two posed models at most a tolerance apart
//! (contact generation with a margin).

use super::collide::{CollideResult, ContactPair};
use super::prepare;
use super::traversal::{LeafCache, NodePair, PairStack, descend_first};
use crate::bounding_volume::{DistanceVolume, Ssv};
use crate::error::Error;
use crate::geometry::{Tri, tri_distance, tri_overlap};
use crate::math::Pose;
use crate::model::Model;
use std::time::Instant;

/// Every triangle pair of `m1` at `pose1` and `m2` at `pose2` whose distance is at most
/// `tolerance`, overlapping pairs included, each once (`id1` the triangle of `m1`). With
/// `tolerance` 0 these are exactly the pairs [`collide`](super::collide) reports with
/// [`ContactMode::All`](super::ContactMode::All): overlap is decided exactly. Above 0 a pair that
/// does not overlap is in when its distance, as [`tri_distance`] computes it, is at most
/// `tolerance`. The search prunes node pairs by the swept sphere volumes' distance bounds.
///
/// `Err(InvalidArgument)` if `tolerance` is negative or NaN; `Err(OutOfMemory)` if the pair list
/// cannot grow (an infinite tolerance asks for every pair).
///
/// ```
/// use pqp::{Model, Pose, within_distance};
/// let tri = |id| ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], id);
/// let a = Model::from_triangles([tri(1)]).unwrap();
/// let b = Model::from_triangles([tri(2)]).unwrap();
/// let up = Pose::from_translation([0.0, 0.0, 0.5]);
/// assert_eq!(within_distance(&a, &Pose::identity(), &b, &up, 0.6).unwrap().num_pairs(), 1);
/// assert_eq!(within_distance(&a, &Pose::identity(), &b, &up, 0.4).unwrap().num_pairs(), 0);
/// ```
pub fn within_distance(
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    tolerance: f64,
) -> Result<CollideResult, Error> {
    let mut r = CollideResult::new();
    within_distance_into(&mut r, m1, pose1, m2, pose2, tolerance)?;
    Ok(r)
}

/// As [`within_distance`], reusing `result`'s storage. On error `result` is left as it was,
/// except `Err(OutOfMemory)`, after which it holds no pairs.
pub fn within_distance_into(
    result: &mut CollideResult,
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    tolerance: f64,
) -> Result<(), Error> {
    let start = Instant::now();
    if tolerance.is_nan() || tolerance < 0.0 {
        return Err(Error::InvalidArgument);
    }
    if let Some(found) = super::primitive::pairs(m1, pose1, m2, pose2, tolerance, false) {
        return result.set_pairs(found?);
    }
    let (b1, b2, rel) = prepare(m1, pose1, m2, pose2)?;
    // Bounds from `distance_below` are exact below the cutoff and at least it otherwise: with a
    // cutoff just above the tolerance, a node pair is pruned exactly when its bound exceeds it.
    let cutoff = tolerance.next_up();
    result.stats = Default::default();
    let pairs = result.pairs_mut();
    pairs.clear();
    let mut stats = super::Stats::default();
    let mut stack = PairStack::new();
    let (mut leaf1, mut leaf2) = (LeafCache::default(), LeafCache::default());
    stack.push(NodePair {
        a: b1.root(),
        b: b2.root(),
        bound: 0.0,
    });
    while let Some(p) = stack.pop() {
        if p.a.is_leaf() && p.b.is_leaf() {
            let (ta, tb) = (p.a.triangle(), p.b.triangle());
            stats.tri_tests += 1;
            let t2 = b2.tri(tb);
            let moved: Tri = [rel.apply(&t2[0]), rel.apply(&t2[1]), rel.apply(&t2[2])];
            let t1 = b1.tri(ta);
            let near = tri_overlap(&t1, &moved)
                || (tolerance > 0.0 && tri_distance(&t1, &moved).distance <= tolerance);
            if near {
                if pairs.try_reserve(1).is_err() {
                    pairs.clear();
                    return Err(Error::OutOfMemory);
                }
                pairs.push(ContactPair {
                    id1: b1.ids[ta],
                    id2: b2.ids[tb],
                });
            }
            continue;
        }
        let va: Ssv = leaf1.get(p.a, |r| b1.ssv(r));
        let vb: Ssv = leaf2.get(p.b, |r| b2.ssv(r));
        stats.bv_tests += 1;
        if Ssv::distance_below(&va, &vb, &rel, cutoff) > tolerance {
            continue;
        }
        if descend_first(p.a, p.b, &va, &vb) {
            let [c0, c1] = b1.children(p.a);
            stack.push(NodePair { a: c1, ..p });
            stack.push(NodePair { a: c0, ..p });
        } else {
            let [c0, c1] = b2.children(p.b);
            stack.push(NodePair { b: c1, ..p });
            stack.push(NodePair { b: c0, ..p });
        }
    }
    stats.query_time_secs = start.elapsed().as_secs_f64();
    result.stats = stats;
    Ok(())
}
