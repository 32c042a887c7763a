//! Internal measurements for the benchmark suite (`examples/bvtt_efficiency.rs`, `BENCHMARKS.md`).
//! Not part of the supported API: hidden from the docs and free to change.
//!
//! A distance query walks the bounding-volume traversal tree (BVTT): its nodes are pairs of
//! hierarchy nodes, its root the pair of roots, and a node's children are the pairs obtained by
//! splitting one side by the query's descent rule. A search that knew the final distance `d` from
//! the start would still have to expand every BVTT node whose lower bound is below `d` (any of them
//! might hide a closer pair) and could skip every other. Those nodes form the *minimal BVTT*; how far
//! a real query's work exceeds it measures how well its search order and initial guess work.

use crate::bounding_volume::{Ssv, Want};
use crate::bvh::Bvh;
use crate::error::Error;
use crate::math::{Pose, RelPose};
use crate::model::Model;
use crate::query::search::{LeafVolumes, expand, root_pair};

/// Sizes of the minimal BVTT of a distance query (see the module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MinimalBvtt {
    /// BVTT nodes whose bound is below the distance and whose ancestors' bounds all are too.
    pub nodes_below: u64,
    /// Bounds that any search using the query's descent rule must compute: the root's, and both
    /// children's of every inner node counted in `nodes_below`. Comparable with `Stats::bv_tests`.
    pub bound_tests: u64,
    /// Leaf pairs (triangle pairs) counted in `nodes_below`: triangle tests any such search makes.
    pub leaf_pairs_below: u64,
    /// Inner nodes counted in `nodes_below` exactly one of whose children is below the distance
    /// too: each costs two bound tests for one node of the minimal BVTT.
    pub single_child_below: u64,
    /// Inner nodes counted in `nodes_below` neither of whose children is below the distance: two
    /// bound tests for no node of the minimal BVTT.
    pub no_child_below: u64,
}

/// The minimal BVTT of the distance query between `m1` at `pose1` and `m2` at `pose2`, given their
/// final distance `distance` (take it from an exact query). Walks the BVTT from the root with the
/// query's descent rule and bounds, descending a node only when its bound is below `distance`.
pub fn minimal_bvtt(
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    distance: f64,
) -> Result<MinimalBvtt, Error> {
    let b1 = m1.bvh()?;
    let b2 = m2.bvh()?;
    pose1.validate()?;
    pose2.validate()?;
    let rel = RelPose::between(pose1, pose2);
    Ok(walk(b1, b2, &rel, distance))
}

/// `minimal_bvtt(..).nodes_below`: the number of BVTT nodes whose bound is below the final
/// distance and whose parent's bound is too.
pub fn minimal_bvtt_size(
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    distance: f64,
) -> Result<u64, Error> {
    Ok(minimal_bvtt(m1, pose1, m2, pose2, distance)?.nodes_below)
}

/// Checks that every volume of a built model's hierarchy contains its triangles as strictly as a
/// build leaves them: each node's swept sphere volume and box contain every vertex of every
/// triangle below it as their `contains` measures it with no allowance, and the model-wide bound
/// on the volumes' scales (the queries' rounding allowances are relative to it) holds. `Err`
/// describes the first failure (for tests of refits and builds).
pub fn check_containment(m: &Model) -> Result<(), String> {
    use crate::bounding_volume::BoundingVolume;
    use crate::bvh::{NodeKind, NodeRef};
    let b = m.bvh().map_err(|e| format!("{e:?}"))?;
    // Each node with the triangles below it, found by one descent per node from the root: the
    // nodes' triangle lists, collected bottom-up.
    fn below(b: &Bvh, r: NodeRef, out: &mut Vec<(NodeRef, Vec<usize>)>) -> Vec<usize> {
        let tris = match r.kind() {
            NodeKind::Leaf(t) => vec![t],
            NodeKind::Inner(_) => {
                let [c0, c1] = b.children(r);
                let mut v = below(b, c0, out);
                v.extend(below(b, c1, out));
                v
            }
        };
        out.push((r, tris.clone()));
        tris
    }
    let mut nodes = Vec::new();
    below(b, b.root(), &mut nodes);
    for (r, tris) in nodes {
        let (ssv, obb) = (b.ssv(r), b.obb(r));
        if ssv.scale() > b.scale {
            return Err(format!("node {r}: scale {} above {}", ssv.scale(), b.scale));
        }
        for t in tris {
            for v in &b.tri(t) {
                if !ssv.contains(v, 0.0) {
                    return Err(format!("node {r}: swept sphere {ssv:?} misses {v:?}"));
                }
                if !obb.contains(v, 0.0) {
                    return Err(format!("node {r}: box {obb:?} misses {v:?}"));
                }
            }
        }
    }
    Ok(())
}

/// Walks the BVTT with the query's own expansion (`query::search::expand`: the same descent rule
/// and the same bounds), descending a node only when its bound is below `d`.
fn walk(b1: &Bvh, b2: &Bvh, rel: &RelPose, d: f64) -> MinimalBvtt {
    let mut out = MinimalBvtt {
        bound_tests: 1,
        ..MinimalBvtt::default()
    };
    let root = root_pair(b1, b2, rel, f64::INFINITY);
    let mut stack = vec![root];
    let mut leaves = LeafVolumes::default();
    let slack = Ssv::slack_for(b1.scale, b2.scale, rel);
    // Written so that a NaN bound is not descended.
    let below = |bound: f64| bound < d;
    while let Some(p) = stack.pop() {
        if !below(p.bound) {
            continue;
        }
        out.nodes_below += 1;
        match expand(
            b1,
            b2,
            rel,
            slack,
            &p,
            f64::INFINITY,
            Want::EXACT,
            &mut leaves,
        ) {
            None => out.leaf_pairs_below += 1,
            Some(children) => {
                out.bound_tests += 2;
                match children.map(|c| below(c.0.bound)) {
                    [false, false] => out.no_child_below += 1,
                    [true, true] => {}
                    _ => out.single_child_below += 1,
                }
                stack.extend(children.map(|c| c.0));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::{DistanceOptions, DistanceResult, Search, distance, distance_into};
    use crate::test_rng::{Lcg, Random};

    /// A closed-ish bumpy blob: a UV sphere with a random radius per vertex ring.
    fn blob(rng: &mut Lcg, nlat: usize, nlon: usize) -> Model {
        let radii: Vec<f64> = (0..=nlat).map(|_| 0.8 + 0.4 * rng.unit()).collect();
        let v = |i: usize, j: usize| {
            let th = std::f64::consts::PI * i as f64 / nlat as f64;
            let ph = 2.0 * std::f64::consts::PI * j as f64 / nlon as f64;
            let r = radii[i];
            [
                r * th.sin() * ph.cos(),
                r * th.sin() * ph.sin(),
                r * th.cos(),
            ]
        };
        let mut tris = Vec::new();
        for i in 0..nlat {
            for j in 0..nlon {
                let j1 = (j + 1) % nlon;
                let id = tris.len() as i32;
                tris.push((v(i, j), v(i + 1, j), v(i + 1, j1), id));
                tris.push((v(i, j), v(i + 1, j1), v(i, j1), id + 1));
            }
        }
        Model::from_triangles(tris).unwrap()
    }

    /// Separated poses: centres 2.5 to 4 apart (the blobs have radius at most 1.2).
    fn poses(rng: &mut Lcg, n: usize) -> Vec<(Pose, Pose)> {
        (0..n)
            .map(|_| {
                let dir = [rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5];
                let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
                let c = 2.5 + 1.5 * rng.unit();
                let t = [dir[0] / len * c, dir[1] / len * c, dir[2] / len * c];
                (
                    Pose::new(rng.rotation(), [0.0; 3]),
                    Pose::new(rng.rotation(), t),
                )
            })
            .collect()
    }

    /// A query started from the closest pair itself (the triangle cache, filled by the same query
    /// just before) already holds the final distance, so it expands exactly the minimal BVTT: its
    /// counts must equal the walk's, for the depth-first and the priority-queue searches. This also
    /// checks that the walk's descent rule is the query's. One difference: the depth-first
    /// overflow of a small queue sends a leaf pair straight to its triangles when it is a child of
    /// a leaf and an inner node, so there each such node takes one bound test fewer per leaf child,
    /// and a triangle test for each leaf pair whether or not it is below the distance.
    #[test]
    fn query_started_at_the_answer_does_exactly_the_minimal_work() {
        let mut rng = Lcg(7);
        let a = blob(&mut rng, 12, 16);
        let b = blob(&mut rng, 9, 20);
        let (mut saved_total, mut odd) = (0, false);
        for (p1, p2) in poses(&mut rng, 25) {
            for qsize in [2, 8] {
                let opts = DistanceOptions {
                    search: Search::pqp(qsize),
                    ..DistanceOptions::exact()
                };
                let mut r = DistanceResult::new();
                distance_into(&mut r, &a, &p1, &b, &p2, &opts).unwrap();
                let d = r.distance;
                assert!(d > 0.0);
                // From its front (the same answer; the work is compared in tests/queries.rs).
                let mut from_front = r.clone();
                distance_into(&mut from_front, &a, &p1, &b, &p2, &opts).unwrap();
                assert_eq!(from_front.distance, d);
                // From the root, with the cached pair only.
                r.forget_front();
                distance_into(&mut r, &a, &p1, &b, &p2, &opts).unwrap();
                assert_eq!(r.distance, d);
                let m = minimal_bvtt(&a, &p1, &b, &p2, d).unwrap();
                assert!(m.nodes_below >= 1);
                // The cached pair is tested once before the search starts.
                let (walk_bv, walk_tri) = (m.bound_tests, m.leaf_pairs_below + 1);
                let (bv, tri) = (r.stats.bv_tests, r.stats.tri_tests);
                if qsize == 2 {
                    assert_eq!((bv, tri), (walk_bv, walk_tri), "qsize {qsize}");
                } else {
                    // A bound test saved per leaf pair sent to its triangles, for a triangle
                    // test that the walk makes too when the pair is below the distance.
                    assert!(bv <= walk_bv, "{bv} {walk_bv}");
                    let saved = walk_bv - bv;
                    assert!(
                        tri >= walk_tri && tri - walk_tri <= saved,
                        "{tri} {walk_tri}"
                    );
                    saved_total += saved;
                    // A node of a leaf and an inner node saves one, a node of two leaves two.
                    odd |= saved % 2 == 1;
                }
            }
        }
        // The overflow did meet such nodes, of both kinds (the checks above are not vacuous).
        assert!(saved_total > 0 && odd);
    }

    /// The default search (priority-directed, unbounded queue) expands nodes in increasing order of
    /// bound, so even from a cold start it does exactly the minimal work.
    #[test]
    fn default_search_does_exactly_the_minimal_work() {
        let mut rng = Lcg(5);
        let a = blob(&mut rng, 12, 16);
        let b = blob(&mut rng, 9, 20);
        for (p1, p2) in poses(&mut rng, 25) {
            let r = distance(&a, &p1, &b, &p2, &DistanceOptions::exact()).unwrap();
            let m = minimal_bvtt(&a, &p1, &b, &p2, r.distance).unwrap();
            assert_eq!(r.stats.bv_tests, m.bound_tests);
            assert_eq!(r.stats.tri_tests, m.leaf_pairs_below);
        }
    }

    /// From a cold start a query can only do more: every minimal node's parent has a bound below
    /// the final distance, hence below every distance the search holds.
    #[test]
    fn cold_query_does_at_least_the_minimal_work() {
        let mut rng = Lcg(11);
        let a = blob(&mut rng, 10, 14);
        let b = blob(&mut rng, 11, 13);
        for (p1, p2) in poses(&mut rng, 25) {
            let mut r = DistanceResult::new();
            distance_into(&mut r, &a, &p1, &b, &p2, &DistanceOptions::exact()).unwrap();
            let m = minimal_bvtt(&a, &p1, &b, &p2, r.distance).unwrap();
            assert!(r.stats.bv_tests >= m.bound_tests);
            assert!(r.stats.tri_tests >= m.leaf_pairs_below);
            assert!(m.bound_tests >= m.nodes_below);
            // Every node below but the root is a child of an expanded one, which has one or two
            // children below; the minimal BVTT's leaves (its leaf pairs among them) number one
            // more than its nodes with two.
            let inner = m.nodes_below - m.leaf_pairs_below;
            let rest = m.nodes_below - 1 - m.single_child_below;
            assert!(rest.is_multiple_of(2));
            let two_below = rest / 2;
            assert_eq!(m.no_child_below + m.single_child_below + two_below, inner);
            assert_eq!(two_below + 1, m.leaf_pairs_below + m.no_child_below);
            assert_eq!(
                minimal_bvtt_size(&a, &p1, &b, &p2, r.distance).unwrap(),
                m.nodes_below
            );
        }
    }

    /// Nothing is below a distance of zero; everything is below infinity (the whole BVTT, whose
    /// leaf pairs are all triangle pairs).
    #[test]
    fn extreme_distances() {
        let mut rng = Lcg(3);
        let a = blob(&mut rng, 3, 4);
        let b = blob(&mut rng, 2, 5);
        let (p1, p2) = poses(&mut rng, 1)[0];
        let zero = minimal_bvtt(&a, &p1, &b, &p2, 0.0).unwrap();
        assert_eq!(
            zero,
            MinimalBvtt {
                nodes_below: 0,
                bound_tests: 1,
                leaf_pairs_below: 0,
                single_child_below: 0,
                no_child_below: 0,
            }
        );
        let all = minimal_bvtt(&a, &p1, &b, &p2, f64::INFINITY).unwrap();
        let (n1, n2) = (a.num_triangles() as u64, b.num_triangles() as u64);
        assert_eq!(all.leaf_pairs_below, n1 * n2);
        // A full binary tree with L leaves has 2L - 1 nodes, and so does the BVTT.
        assert_eq!(all.nodes_below, 2 * n1 * n2 - 1);
        assert_eq!(all.bound_tests, all.nodes_below);
        assert_eq!((all.single_child_below, all.no_child_below), (0, 0));
    }

    #[test]
    fn unbuilt_model_is_refused() {
        let a = Model::new();
        let id = Pose::identity();
        assert_eq!(
            minimal_bvtt_size(&a, &id, &a, &id, 1.0),
            Err(Error::UnprocessedModel)
        );
    }
}
