//! The search of the bounding volume test tree (BVTT) for a closest triangle pair, shared by the
//! distance and tolerance queries, and the strategies it can follow.
//!
//! Every strategy visits a BVTT node only while its lower bound could still improve the answer, so
//! all of them return the same exact distance; they differ in the order of the visits, hence in how
//! soon a good answer prunes the rest. A priority-directed search with an unbounded queue expands
//! nodes in increasing order of bound, so it expands no node whose bound is above the final distance:
//! it does the least work any search with these volumes can do (the minimal BVTT). The default
//! bounds the queue (see [`Search::DEFAULT_QSIZE`]) so that where the bounds cannot tell pairs apart
//! the overflow goes depth-first instead of growing a queue of a million pairs.
//!
//! The search is split by job: this file holds its state and its entry points ([`ClosestSearch::run`]
//! and what records the front); `strategies.rs` the three visiting orders; `visit.rs` what one
//! BVTT node costs (a leaf pair's triangle test, an inner node's expansion); `bounds.rs` the
//! bounds of a pair's children (the descent rule, the leaves' and posed volumes' caches). The
//! stop rules are the caller's: the distance and tolerance queries pass them to `run`.

mod bounds;
mod strategies;
mod visit;

pub use super::strategy::{Search, Strategy};
pub(crate) use bounds::{LeafVolumes, expand, root_pair};

use super::Stats;
use super::front::{FrontPair, Motion};
use super::traversal::NodePair;
use crate::bounding_volume::Ssv;
use crate::bvh::Bvh;
use crate::geometry::Plane;
use crate::math::{RelPose, Vec3, avx2_or_portable};

/// Two models of at least this many triangles together (hierarchies of about 1.3 MB, more than
/// a level-2 cache of 1 MB holds) have the depth-first search prefetch the volumes of the nodes
/// it stacks (see `bounds::prefetch_children`); on smaller ones the volumes stay in the caches and
/// the prefetches would only cost instructions (7% on the bunny's tolerance query).
const PREFETCH_TRIANGLES: usize = 8192;

/// The closest triangle pair found so far, with its points in model 1's frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Best {
    pub d: f64,
    pub p: Vec3,
    pub q: Vec3,
    pub ta: usize,
    pub tb: usize,
}

/// A search of the BVTT of two hierarchies for their closest triangle pair. The distance and
/// tolerance queries differ only in when they prune and when they stop.
pub(crate) struct ClosestSearch<'a> {
    b1: &'a Bvh,
    b2: &'a Bvh,
    rel: RelPose,
    /// The bounds' rounding allowance, one for every pair of the two models.
    slack: f64,
    /// The triangle whose plane last showed a pair apart, to be tried first next time.
    plane_first: Plane,
    /// No triangle pair of the two models needs rescaling (see [`Bvh::in_kernel_range`]).
    in_range: bool,
    /// The two hierarchies are large enough for the depth-first search to prefetch the volumes
    /// of the nodes it stacks (see [`PREFETCH_TRIANGLES`]).
    prefetch: bool,
    /// With `prefetch`, an expansion prefetches what its children's expansions will read rather
    /// than what a kept child's will (see [`ClosestSearch::prefetch_ahead`]).
    ahead: bool,
    pub best: Best,
    pub stats: Stats,
    /// The smallest bound among pruned BVTT nodes: with `best.d`, a lower bound on the true distance.
    pub pruned_min: f64,
    /// The caller's (a few kilobytes: made in place there rather than moved with the search).
    leaves: &'a mut LeafVolumes,
    /// With `Some`, every BVTT node the search leaves behind (pruned, tested as a leaf pair, or
    /// unvisited when it stops) is recorded here with its bound, and the axis that shows it when
    /// the search has one: a cut of the BVTT, the front from which the next query under coherent
    /// motion can start (see `front.rs`). `None` also when storage ran out.
    front: Option<Vec<FrontPair>>,
}

impl<'a> ClosestSearch<'a> {
    /// A search whose first answer is the given triangle pair (the cached one), if any; otherwise
    /// it starts with no answer (distance infinite).
    pub fn new(
        b1: &'a Bvh,
        b2: &'a Bvh,
        rel: RelPose,
        start: Option<(usize, usize)>,
        leaves: &'a mut LeafVolumes,
    ) -> Self {
        let mut s = ClosestSearch {
            b1,
            b2,
            rel,
            slack: Ssv::slack_for(b1.scale, b2.scale, &rel),
            plane_first: Plane::A,
            in_range: b1.in_kernel_range(b2, &rel),
            prefetch: b1.num_tris() + b2.num_tris() >= PREFETCH_TRIANGLES,
            ahead: false,
            best: Best {
                d: f64::INFINITY,
                p: Vec3::zeros(),
                q: Vec3::zeros(),
                ta: 0,
                tb: 0,
            },
            stats: Stats::default(),
            pruned_min: f64::INFINITY,
            leaves,
            front: None,
        };
        if let Some((ta, tb)) = start.filter(|&(a, b)| a < b1.num_tris() && b < b2.num_tris()) {
            s.test_triangles(ta, tb);
        }
        s
    }

    /// Runs the search; `Auto` runs as `auto` (the caller's query knows which is best for it).
    /// `cutoff(best)` is the least bound of a BVTT node that cannot improve the
    /// answer `best` enough to be worth visiting (nondecreasing in `best`): such nodes are pruned.
    /// `stop(best)` ends the search early. `fixed_cutoff`: the cutoff does not fall before `stop`
    /// ends the search (a tolerance query's), so that a depth-first search loses nothing by asking
    /// for loose bounds (see [`depth_first`](ClosestSearch::depth_first)).
    ///
    /// With `front`, it starts from the BVTT nodes of the front (a cut of the BVTT: every triangle
    /// pair lies below one of them) instead of the root, when the search is priority-directed;
    /// other strategies start from the root. A front node's bound held before the `motion`; less
    /// the motion of the node's points, it bounds the triangles below it now.
    ///
    /// `root`: the root pair, if the caller has it already: with its exact bound, or as
    /// [`root_pair`] gives it with the cutoff of the search's first answer (either prunes alike;
    /// it is counted here as a bound test all the same).
    #[allow(clippy::too_many_arguments)]
    pub fn run(
        &mut self,
        search: &Search,
        auto: Strategy,
        cutoff: impl Fn(f64) -> f64 + Copy,
        stop: impl Fn(f64) -> bool + Copy,
        fixed_cutoff: bool,
        front: Option<(&[FrontPair], Motion)>,
        root: Option<NodePair>,
    ) {
        // The search loops and the visits are inlined here, and this into the copy compiled for
        // AVX2 (or the portable one); the bounds' kernel is called: it has copies of its own.
        avx2_or_portable(
            #[inline(always)]
            move || {
                if stop(self.best.d) {
                    return;
                }
                let strategy = search.resolve(auto);
                if let (Strategy::Priority, Some((front, motion))) = (strategy, front) {
                    return self.priority(None, front, Some(motion), search.qsize, cutoff, stop);
                }
                self.stats.bv_tests += 1;
                let root = root
                    .unwrap_or_else(|| root_pair(self.b1, self.b2, &self.rel, cutoff(self.best.d)));
                match strategy {
                    Strategy::Auto | Strategy::DepthFirst => {
                        self.depth_first(root, cutoff, stop, fixed_cutoff);
                    }
                    Strategy::BreadthFirst => self.breadth_first(root, cutoff, stop),
                    Strategy::Priority => {
                        self.priority(Some(root), &[], None, search.qsize, cutoff, stop)
                    }
                }
            },
        )
    }

    /// Finds a first answer for a search that has none: descends from the root pair to one pair
    /// of leaves, the child pair with the smaller bound first at every level, and tests its
    /// triangles (two bound tests a level). An approximate distance query prunes with its answer
    /// from the start, as a depth-first search would after its first descent, where a
    /// priority-directed search from the root reaches its first leaf pair only after expanding
    /// every node with a smaller bound. Where the root volumes overlap (bound 0: the models touch
    /// or nearly), the descent is not taken: there many pairs share the bound 0, the one it
    /// reaches is seldom the answer, and the search finds a closest pair as soon without it.
    ///
    /// Returns the root pair with its exact bound, for [`run`] to start from (it counts it), or
    /// `None` with a front recorded (the descent's nodes would not form one; nothing is done).
    ///
    /// [`run`]: ClosestSearch::run
    pub fn probe(&mut self) -> Option<NodePair> {
        if self.front.is_some() {
            return None;
        }
        let root = root_pair(self.b1, self.b2, &self.rel, f64::INFINITY);
        if root.bound <= 0.0 {
            return Some(root);
        }
        avx2_or_portable(
            #[inline(always)]
            move || {
                let mut p = root;
                while let Some([(near, _), _]) = self.visit(&p, f64::INFINITY, true) {
                    p = near;
                }
            },
        );
        Some(root)
    }

    /// Asks the search to prefetch one level further ahead (on models large enough to prefetch at
    /// all, see [`PREFETCH_TRIANGLES`]): when it is about to expand a BVTT node, the volumes that
    /// each child's own expansion will read, before the children's bounds are known, in place of
    /// the prefetch for each kept child after them. The loads get a whole expansion's time, but
    /// are asked for children that are then pruned too: it pays where most children survive
    /// their bound (an approximate distance query on the nested shells, about 3% faster) and
    /// costs where many are pruned (3-5% on an exact one on the spheres).
    pub fn prefetch_ahead(&mut self, on: bool) {
        self.ahead = on && self.prefetch;
    }

    /// Keeps the front of this search (see the `front` field) in `buffer` (cleared first).
    pub fn record_front(&mut self, mut buffer: Vec<FrontPair>) {
        buffer.clear();
        self.front = Some(buffer);
    }

    /// The front recorded, if it was asked for and storage did not run out.
    pub fn take_front(&mut self) -> Option<Vec<FrontPair>> {
        self.front.take()
    }

    /// Notes a pruned node; its bound, like every bound, is a lower bound on what lies below it.
    /// `axis`: a unit vector along which the node's volumes are at least that far apart (zero:
    /// none known).
    #[inline]
    fn pruned(&mut self, p: &NodePair, axis: Vec3) {
        self.pruned_pair(FrontPair::new(*p, axis));
    }

    /// As [`pruned`](ClosestSearch::pruned), for a node with what the front keeps of it.
    #[inline]
    fn pruned_pair(&mut self, f: FrontPair) {
        self.pruned_min = self.pruned_min.min(f.pair.bound);
        self.left_pair(f);
    }

    /// Records a node the search leaves behind in the front, when it keeps one.
    #[inline]
    fn left(&mut self, p: &NodePair, axis: Vec3) {
        self.left_pair(FrontPair::new(*p, axis));
    }

    /// As [`left`](ClosestSearch::left), for a node with what the front keeps of it.
    #[inline]
    fn left_pair(&mut self, f: FrontPair) {
        if let Some(front) = &mut self.front {
            if front.try_reserve(1).is_ok() {
                front.push(f);
            } else {
                // Out of memory: no front this time (it only saves work).
                self.front = None;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Search;
    use crate::math::{Pose, portable_only};
    use crate::model::Model;
    use crate::query::{
        DistanceOptions, DistanceResult, ToleranceResult, distance_into, tolerance_into,
    };
    use crate::test_rng::{Random, Rng};

    /// `n` random small triangles near the sphere of radius `r` about the origin.
    fn shell(rng: &mut Rng, n: usize, r: f64) -> Model {
        let tris = (0..n).map(|i| {
            let d = crate::math::Vec3::new(rng.signed(), rng.signed(), rng.signed()).normalize();
            let mut corner = || {
                let p =
                    d * r + crate::math::Vec3::new(rng.signed(), rng.signed(), rng.signed()) * 0.15;
                [p.x, p.y, p.z]
            };
            (corner(), corner(), corner(), i as i32)
        });
        Model::from_triangles(tris.collect::<Vec<_>>()).unwrap()
    }

    /// Every answer and every count of the distance and tolerance queries, exact or not, from a
    /// fresh result or along a path that reuses it (front tracking), is bit for bit the same from
    /// the copies compiled for AVX2 and from the portable ones (the same where the processor has
    /// no AVX2: both sides run the portable copies).
    #[test]
    fn avx2_and_portable_copies_answer_alike() {
        let mut rng = Rng(41);
        let (a, b) = (shell(&mut rng, 400, 1.0), shell(&mut rng, 300, 0.7));
        let rot = |rng: &mut Rng| {
            let axis = nalgebra::Unit::new_normalize(crate::math::Vec3::new(
                rng.signed(),
                rng.signed(),
                rng.signed() + 1e-3,
            ));
            nalgebra::Rotation3::from_axis_angle(&axis, 3.0 * rng.signed()).into_inner()
        };
        let mut poses = Vec::new();
        let (r0, t0) = (rot(&mut rng), [rng.signed(), rng.signed(), rng.signed()]);
        for k in 0..60 {
            // Random poses, then a short smooth path (nested, touching, apart).
            let (r, t) = if k < 30 {
                let s = [0.0, 0.5, 2.0, 4.0][k % 4];
                (rot(&mut rng), [s * rng.signed(), s * rng.signed(), s])
            } else {
                let step = (k - 30) as f64 * 0.01;
                let turn = nalgebra::Rotation3::from_euler_angles(step, 0.5 * step, 0.0);
                (turn.into_inner() * r0, [t0[0] + step, t0[1], t0[2] + 1.8])
            };
            let m: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| r[(i, j)]));
            poses.push(Pose::new(m, t));
        }
        let options = [
            DistanceOptions::exact(),
            DistanceOptions::approximate(0.1, f64::INFINITY),
            DistanceOptions::approximate(0.0, 0.05),
        ];
        let run = || {
            let mut out = Vec::new();
            for o in &options {
                let mut r = DistanceResult::new();
                for p in &poses {
                    distance_into(&mut r, &a, &Pose::identity(), &b, p, o).unwrap();
                    out.push((r.distance.to_bits(), r.p1, r.p2, r.tri1, r.tri2));
                    let work = (r.stats.bv_tests, r.stats.tri_tests as i32);
                    out.push((work.0, r.p1, r.p2, work.1, 0));
                }
            }
            let mut t = ToleranceResult::default();
            for p in &poses {
                for tol in [0.01, 0.3] {
                    tolerance_into(
                        &mut t,
                        &a,
                        &Pose::identity(),
                        &b,
                        p,
                        tol,
                        &Search::default(),
                    )
                    .unwrap();
                    out.push((
                        t.distance.to_bits(),
                        t.p1,
                        t.p2,
                        i32::from(t.closer_than_tolerance),
                        t.stats.bv_tests as i32,
                    ));
                }
            }
            out
        };
        let fast = run();
        let portable = portable_only(run);
        assert_eq!(fast.len(), portable.len());
        for (i, (x, y)) in fast.iter().zip(&portable).enumerate() {
            assert!(
                x.0 == y.0 && x.1 == y.1 && x.2 == y.2 && x.3 == y.3 && x.4 == y.4,
                "answer {i}: {x:?} against {y:?}"
            );
        }
    }
}
