//! Separation distance, exact or within a relative/absolute error, with closest points.

use super::traversal::{descend_first, NodePair, PairStack};
use super::{prepare, Stats, TriCache};
use crate::bounding_volume::DistanceVolume;
use crate::bvh::Bvh;
use crate::error::Error;
use crate::geometry::{tri_distance, Tri};
use crate::math::{Pose, RelPose, Vec3};
use crate::model::Model;
use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::time::Instant;

/// How a distance query may trade accuracy for speed, and how it searches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceOptions {
    /// Relative error allowed (>= 0).
    pub rel_err: f64,
    /// Absolute error allowed (>= 0). With 0 the query is exact whatever `rel_err` is, as in PQP;
    /// pass `f64::INFINITY` to let only the relative bound act.
    pub abs_err: f64,
    /// Priority-queue size (>= 1). 1 or 2 search depth-first, nearer pair first (PQP's default is
    /// 2); larger values keep up to `qsize` pending pairs ordered by their lower bound and expand the
    /// nearest first.
    pub qsize: usize,
}

impl Default for DistanceOptions {
    fn default() -> Self {
        DistanceOptions {
            rel_err: 0.0,
            abs_err: 0.0,
            qsize: 2,
        }
    }
}

impl DistanceOptions {
    /// Exact distance with the default search.
    pub fn exact() -> Self {
        Self::default()
    }

    fn validate(&self) -> Result<(), Error> {
        let ok = self.rel_err >= 0.0 && self.abs_err >= 0.0 && self.qsize >= 1;
        if ok {
            Ok(())
        } else {
            Err(Error::InvalidArgument)
        }
    }
}

/// The answer of a distance query.
///
/// Keep it and pass it to [`distance_into`] again for the next query on the same models: it
/// remembers the closest triangle pair (the triangle cache), which makes coherent motion cheap.
#[derive(Clone, Debug)]
pub struct DistanceResult {
    /// The separation distance (0 when the models touch or overlap). With error bounds,
    /// `true <= distance <= min(true * (1 + rel_err), true + abs_err)`.
    pub distance: f64,
    /// A closest point on model 1, in model 1's frame.
    pub p1: Vec3,
    /// A closest point on model 2, in model 2's frame.
    pub p2: Vec3,
    /// Whether the models touch or overlap. Then `distance` is 0, `id1`/`id2` name an intersecting
    /// triangle pair, and `p1`, `p2` are the same world point, common to both triangles.
    pub overlap: bool,
    /// Id of model 1's triangle of the closest pair.
    pub id1: i32,
    /// Id of model 2's triangle of the closest pair.
    pub id2: i32,
    /// Work done.
    pub stats: Stats,
    pub(crate) cache: Option<TriCache>,
}

impl Default for DistanceResult {
    fn default() -> Self {
        DistanceResult {
            distance: f64::INFINITY,
            p1: Vec3::zeros(),
            p2: Vec3::zeros(),
            overlap: false,
            id1: -1,
            id2: -1,
            stats: Stats::default(),
            cache: None,
        }
    }
}

impl DistanceResult {
    /// An empty result (distance infinite, no cached pair).
    pub fn new() -> Self {
        Self::default()
    }
}

/// The separation distance between `m1` at `pose1` and `m2` at `pose2`.
///
/// ```
/// use pqp::{distance, DistanceOptions, Model, Pose};
/// let tri = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0);
/// let a = Model::from_triangles([tri]).unwrap();
/// let b = Model::from_triangles([tri]).unwrap();
/// let r = distance(&a, &Pose::identity(), &b, &Pose::from_translation([0.0, 0.0, 3.0]),
///                  &DistanceOptions::exact()).unwrap();
/// assert!((r.distance - 3.0).abs() < 1e-12);
/// ```
pub fn distance(
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    options: &DistanceOptions,
) -> Result<DistanceResult, Error> {
    let mut r = DistanceResult::new();
    distance_into(&mut r, m1, pose1, m2, pose2, options)?;
    Ok(r)
}

/// As [`distance`], starting from the triangle pair cached in `result` by a previous query on the
/// same two models. On error `result` is left as it was.
pub fn distance_into(
    result: &mut DistanceResult,
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    options: &DistanceOptions,
) -> Result<(), Error> {
    let start = Instant::now();
    options.validate()?;
    let (b1, b2, rel) = prepare(m1, pose1, m2, pose2)?;
    let (rel_err, abs_err) = (options.rel_err, options.abs_err);
    let mut search = ClosestSearch::new(b1, b2, rel, TriCache::pair_for(&result.cache, m1, m2));
    // A pair with lower bound b is pruned only when both error bounds allow it.
    let prune = |bound: f64, d: f64| bound * (1.0 + rel_err) >= d && bound + abs_err >= d;
    search.run(options.qsize, prune, |d| d <= 0.0);
    let best = search.best;
    result.stats = search.stats;
    result.distance = best.d;
    result.overlap = best.d <= 0.0;
    result.p1 = best.p;
    result.p2 = rel.apply_inverse(&best.q);
    result.id1 = b1.ids[best.ta];
    result.id2 = b2.ids[best.tb];
    result.cache = Some(TriCache::new(m1, m2, best.ta, best.tb));
    result.stats.query_time_secs = start.elapsed().as_secs_f64();
    Ok(())
}

/// The closest triangle pair found so far, with its points in model 1's frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Best {
    pub d: f64,
    pub p: Vec3,
    pub q: Vec3,
    pub ta: usize,
    pub tb: usize,
}

/// A best-first / depth-first search of the BVTT for the closest triangle pair, shared by the
/// distance and tolerance queries, which differ only in when they prune and when they stop.
pub(crate) struct ClosestSearch<'a> {
    b1: &'a Bvh,
    b2: &'a Bvh,
    rel: RelPose,
    pub best: Best,
    pub stats: Stats,
    /// The smallest bound among pruned BVTT nodes: with `best.d`, a lower bound on the true distance.
    pub pruned_min: f64,
}

impl<'a> ClosestSearch<'a> {
    /// A search whose first answer is the cached pair, if any (triangle caching), else the first
    /// triangle of each model.
    pub fn new(b1: &'a Bvh, b2: &'a Bvh, rel: RelPose, cached: Option<(usize, usize)>) -> Self {
        let mut s = ClosestSearch {
            b1,
            b2,
            rel,
            best: Best {
                d: f64::INFINITY,
                p: Vec3::zeros(),
                q: Vec3::zeros(),
                ta: 0,
                tb: 0,
            },
            stats: Stats::default(),
            pruned_min: f64::INFINITY,
        };
        let (ta, tb) = match cached {
            Some((a, b)) if a < b1.tris.len() && b < b2.tris.len() => (a, b),
            _ => (0, 0),
        };
        s.test_triangles(ta, tb);
        s
    }

    fn test_triangles(&mut self, ta: usize, tb: usize) {
        self.stats.tri_tests += 1;
        let t2 = &self.b2.tris[tb];
        let moved: Tri = [
            self.rel.apply(&t2[0]),
            self.rel.apply(&t2[1]),
            self.rel.apply(&t2[2]),
        ];
        let c = tri_distance(&self.b1.tris[ta], &moved);
        if c.distance < self.best.d {
            self.best = Best {
                d: c.distance,
                p: c.p,
                q: c.q,
                ta,
                tb,
            };
        }
    }

    fn bound(&mut self, a: u32, b: u32) -> f64 {
        self.stats.bv_tests += 1;
        DistanceVolume::distance(
            &self.b1.nodes[a as usize].ssv,
            &self.b2.nodes[b as usize].ssv,
            &self.rel,
        )
    }

    /// The two children of a BVTT node with their bounds, nearer first; `None` for a leaf pair.
    fn children(&mut self, p: &NodePair) -> Option<[NodePair; 2]> {
        let na = &self.b1.nodes[p.a as usize];
        let nb = &self.b2.nodes[p.b as usize];
        let (c1, c2) = if descend_first(na, nb, &na.ssv, &nb.ssv) {
            if na.child < 0 {
                return None;
            }
            let c = na.first_child() as u32;
            ((c, p.b), (c + 1, p.b))
        } else {
            let c = nb.first_child() as u32;
            ((p.a, c), (p.a, c + 1))
        };
        let x = NodePair {
            a: c1.0,
            b: c1.1,
            bound: self.bound(c1.0, c1.1),
        };
        let y = NodePair {
            a: c2.0,
            b: c2.1,
            bound: self.bound(c2.0, c2.1),
        };
        Some(if y.bound < x.bound { [y, x] } else { [x, y] })
    }

    /// Visits one BVTT node: tests a leaf pair, or returns its children.
    #[inline]
    fn visit(&mut self, p: &NodePair) -> Option<[NodePair; 2]> {
        let na = &self.b1.nodes[p.a as usize];
        let nb = &self.b2.nodes[p.b as usize];
        if let (Some(ta), Some(tb)) = (na.leaf_triangle(), nb.leaf_triangle()) {
            self.test_triangles(ta, tb);
            return None;
        }
        self.children(p)
    }

    /// Runs the search. `prune(bound, best)` says a BVTT node cannot improve the answer enough to be
    /// worth visiting (it must be monotone in `bound`); `stop(best)` ends the search early.
    pub fn run(
        &mut self,
        qsize: usize,
        prune: impl Fn(f64, f64) -> bool + Copy,
        stop: impl Fn(f64) -> bool + Copy,
    ) {
        if stop(self.best.d) {
            return;
        }
        let root = NodePair {
            a: 0,
            b: 0,
            bound: self.bound(0, 0),
        };
        if qsize <= 2 {
            self.depth_first(root, prune, stop);
        } else {
            self.priority(root, qsize, prune, stop);
        }
    }

    /// Depth-first, nearer child first.
    fn depth_first(
        &mut self,
        root: NodePair,
        prune: impl Fn(f64, f64) -> bool,
        stop: impl Fn(f64) -> bool,
    ) -> bool {
        let mut stack = PairStack::new();
        stack.push(root);
        while let Some(p) = stack.pop() {
            if prune(p.bound, self.best.d) {
                self.pruned_min = self.pruned_min.min(p.bound);
                continue;
            }
            if let Some([near, far]) = self.visit(&p) {
                stack.push(far);
                stack.push(near);
            } else if stop(self.best.d) {
                return true;
            }
        }
        false
    }

    /// Priority-directed: a queue of up to `qsize` BVTT nodes ordered by bound; when it is full, the
    /// overflow is searched depth-first at once.
    fn priority(
        &mut self,
        root: NodePair,
        qsize: usize,
        prune: impl Fn(f64, f64) -> bool + Copy,
        stop: impl Fn(f64) -> bool + Copy,
    ) {
        thread_local! {
            static QUEUE: RefCell<BinaryHeap<ByBound>> = const { RefCell::new(BinaryHeap::new()) };
        }
        QUEUE.with(|q| {
            let mut taken = q.take();
            taken.clear();
            let heap = &mut taken;
            heap.push(ByBound(root));
            while let Some(ByBound(p)) = heap.pop() {
                if prune(p.bound, self.best.d) {
                    // Every queued node has a bound at least this large: all are pruned.
                    self.pruned_min = self.pruned_min.min(p.bound);
                    break;
                }
                match self.visit(&p) {
                    Some(children) => {
                        for c in children {
                            if heap.len() < qsize {
                                heap.push(ByBound(c));
                            } else if self.depth_first(c, prune, stop) {
                                heap.clear();
                                break;
                            }
                        }
                    }
                    None => {
                        if stop(self.best.d) {
                            break;
                        }
                    }
                }
            }
            taken.clear();
            q.replace(taken);
        });
    }
}

/// Orders BVTT nodes so that `BinaryHeap` pops the smallest bound first.
struct ByBound(NodePair);

impl PartialEq for ByBound {
    fn eq(&self, other: &Self) -> bool {
        self.0.bound.total_cmp(&other.0.bound) == Ordering::Equal
    }
}
impl Eq for ByBound {}
impl PartialOrd for ByBound {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for ByBound {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.bound.total_cmp(&self.0.bound)
    }
}
