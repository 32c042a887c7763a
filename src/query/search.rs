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

use super::front::{FrontPair, Motion};
use super::queue::RadixQueue;
use super::traversal::{LeafCache, NodePair, PairStack};
use super::Stats;
use crate::bounding_volume::{CompactSsv, DistanceVolume, Ssv, Want};
use crate::bvh::{leaf_triangle, Bvh, NodeRef};
use crate::error::Error;
use crate::geometry::{tri_distance_below, Near, Plane, Tri};
use crate::math::{RelPose, Vec3};
use std::cell::RefCell;
use std::collections::VecDeque;
use std::mem::MaybeUninit;

/// The order in which a search visits the BVTT.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// The fastest measured for the query (BENCHMARKS.md): [`Priority`](Strategy::Priority) for
    /// distance, which then expands no more nodes than any search can; [`DepthFirst`](Strategy::DepthFirst)
    /// for tolerance, which stops at the first pair within the tolerance and so wants to reach
    /// triangle pairs soon.
    Auto,
    /// Depth-first, nearer child first: PQP 1.3's search for a queue size of 1 or 2.
    DepthFirst,
    /// Level by level (first in, first out).
    BreadthFirst,
    /// Priority-directed: pending pairs in a queue ordered by bound, the nearest expanded first. The
    /// queue holds at most [`Search::qsize`] pairs; a pair that does not fit is searched depth-first
    /// at once (PQP 1.3's search for a queue size above 2).
    Priority,
}

/// How a distance or tolerance query searches.
///
/// The default, [`Strategy::Auto`] with a queue of [`Search::DEFAULT_QSIZE`] pairs and triangle
/// caching, was chosen from the measurements in BENCHMARKS.md: it does the least bounding-volume
/// work for distance (or close to it), reaches an answer soonest for tolerance, and caching makes
/// coherent motion cheap.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Search {
    /// The visiting order.
    pub strategy: Strategy,
    /// [`Strategy::Priority`] (and `Auto` when it chooses it) only: the most pairs the queue holds
    /// (>= 1; `usize::MAX`: unbounded).
    pub qsize: usize,
    /// Start from the closest triangle pair of the last query on the same two models (kept in the
    /// result), so that under coherent motion the first answer is already nearly the final one.
    /// A priority-directed distance query also starts from the last query's BVTT front (kept in
    /// the result too) when the models moved little since, which skips most of its bound tests
    /// (nearly two thirds on the tumbling tori of BENCHMARKS.md).
    pub triangle_cache: bool,
}

impl Default for Search {
    fn default() -> Self {
        Search {
            strategy: Strategy::Auto,
            qsize: Search::DEFAULT_QSIZE,
            triangle_cache: true,
        }
    }
}

impl Search {
    /// The default queue size. Large enough that on every benchmark workload but the nested shells
    /// the queue never fills, so the search does the minimal work; small enough that where the
    /// bounds cannot tell pairs apart (nested shells: about a million pairs with bound 0) the queue
    /// stays in cache and the overflow, searched depth-first, finds a good answer soon. Measured in
    /// BENCHMARKS.md: unbounded, the shells took 3.7 times as long (28 times with rel_err 0.1).
    pub const DEFAULT_QSIZE: usize = 1024;

    /// PQP 1.3's own search for its queue size `qsize`: depth-first for 1 or 2, else a priority
    /// queue of `qsize` pairs; with triangle caching.
    pub fn pqp(qsize: usize) -> Search {
        Search {
            strategy: if qsize <= 2 {
                Strategy::DepthFirst
            } else {
                Strategy::Priority
            },
            qsize: qsize.max(1),
            triangle_cache: true,
        }
    }

    /// The strategy it runs, `auto` standing for the query's choice.
    pub(crate) fn resolve(&self, auto: Strategy) -> Strategy {
        match self.strategy {
            Strategy::Auto => auto,
            s => s,
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Error> {
        if self.qsize >= 1 {
            Ok(())
        } else {
            Err(Error::InvalidArgument)
        }
    }
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
    /// The model 2 triangle last tested, posed in model 1's frame, and its index (`usize::MAX`:
    /// none yet): consecutive tests often share it (a leaf against a node of two leaves).
    posed: (usize, Tri),
    /// No triangle pair of the two models needs rescaling (see [`Bvh::in_kernel_range`]).
    in_range: bool,
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

/// Recently met leaves' volumes of each model (see [`LeafCache`]).
#[derive(Default)]
pub(crate) struct LeafVolumes {
    first: LeafCache<CompactSsv>,
    second: LeafCache<CompactSsv>,
    /// Volumes recently posed by [`expand`]: a node stays the fixed side of several expansions
    /// close together (a fifth of the nested shells' expansions fix the node fixed by the one
    /// before, a third one fixed in the last few).
    posed: PosedVolumes,
}

/// Slots of [`PosedVolumes`].
const POSED_SLOTS: usize = 64;

/// Nodes' volumes posed in the other model's frame, in a small direct-mapped table (as
/// [`LeafCache`]: only the keys are initialised).
struct PosedVolumes {
    /// The node each slot holds, as `key` gives it; 0: none.
    keys: [u64; POSED_SLOTS],
    volumes: [MaybeUninit<Ssv>; POSED_SLOTS],
}

impl Default for PosedVolumes {
    fn default() -> Self {
        PosedVolumes {
            keys: [0; POSED_SLOTS],
            volumes: [const { MaybeUninit::uninit() }; POSED_SLOTS],
        }
    }
}

impl PosedVolumes {
    /// `v`, the volume of node `r` of model 2 (`second`) or 1, posed by `rel` (by its inverse for
    /// model 1), unless its slot holds it. (The volume is looked up whether or not it is needed:
    /// measured cheaper than looking it up only when it is.)
    #[inline(always)]
    fn get(&mut self, r: NodeRef, second: bool, v: &CompactSsv, rel: &RelPose) -> &Ssv {
        // Nonzero, and distinct for every node of either model.
        let key = ((r as u32 as u64) << 1 | u64::from(second)) + 1;
        let i =
            (r as u32 as usize).wrapping_add(usize::from(second) * (POSED_SLOTS / 2)) % POSED_SLOTS;
        if self.keys[i] != key {
            self.volumes[i] = MaybeUninit::new(v.posed(rel, !second));
            self.keys[i] = key;
        }
        // SAFETY: a slot's key is set nonzero only together with its volume.
        unsafe { self.volumes[i].assume_init_ref() }
    }
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
            posed: (usize::MAX, [Vec3::zeros(); 3]),
            in_range: b1.in_kernel_range(b2, &rel),
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

    /// Tests a triangle pair, keeps it if it is the closest yet, and returns its distance with the
    /// vector between its closest points (from `ta` to `tb`, in model 1's frame); or, for a pair at
    /// least as far apart as the closest yet when no front is recorded, possibly that distance with
    /// a zero vector.
    fn test_triangles(&mut self, ta: usize, tb: usize) -> (f64, Vec3) {
        self.stats.tri_tests += 1;
        if self.posed.0 != tb {
            let t2 = self.b2.tri(tb);
            self.posed = (
                tb,
                [
                    self.rel.apply(&t2[0]),
                    self.rel.apply(&t2[1]),
                    self.rel.apply(&t2[2]),
                ],
            );
        }
        let moved = &self.posed.1;
        // A front keeps the pair's bound for the next query: the exact distance is worth its cost
        // there (measured on the tumbling tori).
        let cutoff = if self.front.is_some() {
            f64::INFINITY
        } else {
            self.best.d
        };
        let c = match tri_distance_below(
            &self.b1.tri(ta),
            moved,
            cutoff,
            self.plane_first,
            self.in_range,
        ) {
            Near::Closest(c) => c,
            Near::Apart(plane) => {
                self.plane_first = plane;
                return (cutoff, Vec3::zeros());
            }
        };
        if c.distance < self.best.d {
            self.best = Best {
                d: c.distance,
                p: c.p,
                q: c.q,
                ta,
                tb,
            };
        }
        (c.distance, c.q - c.p)
    }

    /// As [`visit_unordered`](ClosestSearch::visit_unordered), the nearer child first.
    #[inline]
    fn visit(&mut self, p: &NodePair, cutoff: f64, exact: bool) -> Option<[Child; 2]> {
        self.visit_unordered(p, cutoff, exact).map(|[x, y]| {
            if y.0.bound < x.0.bound {
                [y, x]
            } else {
                [x, y]
            }
        })
    }

    /// Visits one BVTT node: tests a leaf pair (`None`), or returns the node's two children with
    /// their bounds (below `cutoff`, exact if `exact`) and separating axes (see [`expand`]).
    ///
    /// Without `exact`, a leaf against a node of two leaves goes straight to its two triangle
    /// pairs, as if a leaf pair; against a node of a leaf and an inner node (when no front is
    /// kept), the leaf pair does, and the other child comes back with a placeholder at an
    /// infinite bound for the second (see [`depth_first`](ClosestSearch::depth_first)).
    #[inline]
    fn visit_unordered(&mut self, p: &NodePair, cutoff: f64, exact: bool) -> Option<[Child; 2]> {
        if !exact {
            match leaf_children(self.b1, self.b2, p) {
                LeafChildren::Both([x, y]) => {
                    self.leaf_pair(&x);
                    self.leaf_pair(&y);
                    return None;
                }
                LeafChildren::One(x, y) if self.front.is_none() => {
                    // The leaf pair straight to its triangles, the other bounded alone; the
                    // second child is a placeholder a depth-first search prunes (no front
                    // records it).
                    self.leaf_pair(&x);
                    self.stats.bv_tests += 1;
                    let want = Want { axes: false, exact };
                    let (rel, slack) = (&self.rel, self.slack);
                    let c = bound_one(self.b1, self.b2, rel, slack, &y, cutoff, want, self.leaves);
                    let none = NodePair {
                        bound: f64::INFINITY,
                        ..y
                    };
                    return Some([c, (none, Vec3::zeros())]);
                }
                _ => {}
            }
        }
        let want = Want {
            axes: self.front.is_some(),
            exact,
        };
        let (rel, slack) = (&self.rel, self.slack);
        match expand(self.b1, self.b2, rel, slack, p, cutoff, want, self.leaves) {
            Some(children) => {
                self.stats.bv_tests += 2;
                Some(children)
            }
            None => {
                self.leaf_pair(p);
                None
            }
        }
    }

    /// Tests the triangles of a pair of leaves, and leaves the pair in the front.
    #[inline]
    fn leaf_pair(&mut self, p: &NodePair) {
        let (d, gap) = self.test_triangles(leaf_triangle(p.a), leaf_triangle(p.b));
        // The pair's own distance, which the closest points' axis shows: the tightest bound the
        // front can keep for it (the axis made a unit vector only for a front).
        if self.front.is_some() {
            let axis = if d > 0.0 { gap / d } else { Vec3::zeros() };
            self.left(&NodePair { bound: d, ..*p }, axis);
        }
    }

    /// Runs the search; `Auto` runs as `auto` (the caller's query knows which is best for it).
    /// `cutoff(best)` is the least bound of a BVTT node that cannot improve the
    /// answer `best` enough to be worth visiting (nondecreasing in `best`): such nodes are pruned.
    /// `stop(best)` ends the search early. `fixed_cutoff`: the cutoff does not fall before `stop`
    /// ends the search (a tolerance query's), so that a depth-first search loses nothing by asking
    /// for loose bounds (see [`depth_first`](ClosestSearch::depth_first)).
    pub fn run(
        &mut self,
        search: &Search,
        auto: Strategy,
        cutoff: impl Fn(f64) -> f64 + Copy,
        stop: impl Fn(f64) -> bool + Copy,
        fixed_cutoff: bool,
    ) {
        self.run_from(search, auto, cutoff, stop, fixed_cutoff, None)
    }

    /// As [`run`](ClosestSearch::run), starting from the BVTT nodes of `front` (a cut of the BVTT:
    /// every triangle pair lies below one of them) instead of the root, when given and the search
    /// is priority-directed; other strategies start from the root. A front node's bound held before
    /// the `motion`; less the motion of the node's points, it bounds the triangles below it now.
    pub fn run_from(
        &mut self,
        search: &Search,
        auto: Strategy,
        cutoff: impl Fn(f64) -> f64 + Copy,
        stop: impl Fn(f64) -> bool + Copy,
        fixed_cutoff: bool,
        front: Option<(&[FrontPair], Motion)>,
    ) {
        if stop(self.best.d) {
            return;
        }
        let strategy = search.resolve(auto);
        if let (Strategy::Priority, Some((front, motion))) = (strategy, front) {
            return self.priority(None, front, Some(motion), search.qsize, cutoff, stop);
        }
        self.stats.bv_tests += 1;
        let root = root_pair(self.b1, self.b2, &self.rel, cutoff(self.best.d));
        match strategy {
            Strategy::Auto | Strategy::DepthFirst => {
                self.depth_first(root, cutoff, stop, fixed_cutoff);
            }
            Strategy::BreadthFirst => self.breadth_first(root, cutoff, stop),
            Strategy::Priority => self.priority(Some(root), &[], None, search.qsize, cutoff, stop),
        }
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

    /// The bound of the BVTT node `(a, b)` (exact below `cutoff`, at least `cutoff` otherwise),
    /// with a separating axis when it reaches `cutoff` (see [`expand`]).
    fn pair_bound(&mut self, a: NodeRef, b: NodeRef, cutoff: f64) -> Child {
        let (b1, b2) = (self.b1, self.b2);
        let va = volume(b1, &mut self.leaves.first, a);
        let vb = volume(b2, &mut self.leaves.second, b);
        let want = Want {
            axes: self.front.is_some(),
            exact: true,
        };
        let [(bound, axis)] =
            Ssv::bounds_against([va], vb, &self.rel, false, want, cutoff, self.slack);
        (NodePair { a, b, bound }, axis)
    }

    /// Notes a pruned node; its bound, like every bound, is a lower bound on what lies below it.
    /// `axis`: a unit vector along which the node's volumes are at least that far apart (zero:
    /// none known).
    #[inline]
    fn pruned(&mut self, p: &NodePair, axis: Vec3) {
        self.pruned_min = self.pruned_min.min(p.bound);
        self.left(p, axis);
    }

    /// Records a node the search leaves behind in the front, when it keeps one.
    #[inline]
    fn left(&mut self, p: &NodePair, axis: Vec3) {
        if let Some(front) = &mut self.front {
            if front.try_reserve(1).is_ok() {
                front.push(FrontPair { pair: *p, axis });
            } else {
                // Out of memory: no front this time (it only saves work).
                self.front = None;
            }
        }
    }

    /// Depth-first, nearer child first. Returns whether `stop` ended the search.
    ///
    /// With `loose`, it asks for loose bounds (see [`Want`]): a pair below the cutoff is expanded
    /// whatever its bound, and only the order of two siblings suffers a little, as long as the
    /// cutoff does not fall much before the pair's turn (a lower bound that is not the exact one
    /// then prunes less). So the overflow of a priority-directed search, whose cutoff is nearly
    /// final by then, and a tolerance query, whose cutoff is fixed, ask for them; a distance
    /// query's depth-first search from the root does not (on the spheres of BENCHMARKS.md, loose
    /// bounds there took 1.6 times the bound tests). On the nested shells, where most pairs are
    /// below the cutoff, they take about a quarter off a query's time. With them, a leaf pair
    /// under a leaf and an inner node goes straight to its triangles (see [`visit_unordered`]):
    /// bounding it would cost about as much as a triangle test that the planes settle, and would
    /// seldom prune where the cutoff stays put (shells 7% fewer instructions for nodes of two
    /// leaves, 2% more for nodes of a leaf and an inner node).
    ///
    /// [`visit_unordered`]: ClosestSearch::visit_unordered
    fn depth_first(
        &mut self,
        root: NodePair,
        cutoff: impl Fn(f64) -> f64,
        stop: impl Fn(f64) -> bool,
        loose: bool,
    ) -> bool {
        let mut stack = PairStack::new();
        stack.push(root);
        while let Some(p) = stack.pop() {
            let cut = cutoff(self.best.d);
            if p.bound >= cut {
                self.pruned(&p, Vec3::zeros());
                continue;
            }
            if let Some([(x, _), (y, _)]) = self.visit_unordered(&p, cut, !loose) {
                // Nearer child on top; a child at or beyond the cutoff is pruned now (the cutoff
                // only falls). Both without branches where no front is kept: either decision is
                // a coin toss on most models, which a branch mispredicts.
                let pair = [x, y];
                let k = usize::from(y.bound < x.bound);
                let (near, far) = (pair[k], pair[1 - k]);
                if self.front.is_none() {
                    for c in [far, near] {
                        let keep = c.bound < cut;
                        stack.push_if(c, keep);
                        self.pruned_min =
                            least(self.pruned_min, if keep { f64::INFINITY } else { c.bound });
                    }
                } else {
                    stack.push(far);
                    stack.push(near);
                }
            }
            // After a leaf pair (alone, or beside a child as above).
            if stop(self.best.d) {
                // Left unvisited: the front still covers them.
                while let Some(p) = stack.pop() {
                    self.left(&p, Vec3::zeros());
                }
                return true;
            }
        }
        false
    }

    /// Level by level, through a first-in first-out queue.
    fn breadth_first(
        &mut self,
        root: NodePair,
        cutoff: impl Fn(f64) -> f64,
        stop: impl Fn(f64) -> bool,
    ) {
        thread_local! {
            static QUEUE: RefCell<VecDeque<NodePair>> = const { RefCell::new(VecDeque::new()) };
        }
        QUEUE.with(|q| {
            let mut queue = q.take();
            queue.clear();
            queue.push_back(root);
            while let Some(p) = queue.pop_front() {
                let cut = cutoff(self.best.d);
                if p.bound >= cut {
                    self.pruned(&p, Vec3::zeros());
                    continue;
                }
                match self.visit(&p, cut, true) {
                    Some(children) => queue.extend(children.map(|c| c.0)),
                    None if stop(self.best.d) => break,
                    None => {}
                }
            }
            // Pairs left behind by a stop are unvisited: their bounds still bound what they hold.
            for p in queue.drain(..) {
                self.pruned(&p, Vec3::zeros());
            }
            q.replace(queue);
        });
    }

    /// Priority-directed: a queue of up to `qsize` BVTT nodes ordered by bound; a node that does not
    /// fit is searched depth-first at once.
    ///
    /// The queue is a radix heap (`queue.rs`), which wants no node pushed below the last popped:
    /// a child's bound is raised to its parent's (a bound on the child's triangles too). After
    /// expanding a node, its nearer child goes on at once without passing through the queue when
    /// no queued node can have a smaller bound (the queue is empty, or the child is at the last
    /// popped bound): it is the one the queue would give next anyway, so the order is the same.
    ///
    /// It starts from `root` if given, else from the nodes of `seeds` (a cut of the BVTT), whose
    /// bounds were computed before `motion`: a seed whose bound less the motion of its points (along
    /// its separating axis when it has one) is still beyond the cutoff is pruned at once, the
    /// others are tested first.
    fn priority(
        &mut self,
        root: Option<NodePair>,
        seeds: &[FrontPair],
        motion: Option<Motion>,
        qsize: usize,
        cutoff: impl Fn(f64) -> f64 + Copy,
        stop: impl Fn(f64) -> bool + Copy,
    ) {
        thread_local! {
            static QUEUE: RefCell<RadixQueue> = RefCell::new(RadixQueue::default());
        }
        QUEUE.with(|q| {
            // Borrowed rather than taken: a fresh queue is 64 buckets to set up.
            let mut queue = q.borrow_mut();
            queue.clear();
            let mut next = root;
            for (i, &FrontPair { pair: seed, axis }) in seeds.iter().enumerate() {
                let cut = cutoff(self.best.d);
                let (a, b) = (seed.a, seed.b);
                if let Some(m) = &motion {
                    // The whole model's motion first (free), then the node's own. The axis that
                    // showed the old bound still shows the decayed one.
                    let mut old = seed.bound - m.whole();
                    if old < cut && seed.bound >= cut {
                        old = seed.bound - m.of_node(self.b2, b, seed.bound, &axis);
                    }
                    if old >= cut {
                        self.pruned(&NodePair { bound: old, ..seed }, axis);
                        continue;
                    }
                }
                self.stats.bv_tests += 1;
                let (p, axis) = self.pair_bound(a, b, cut);
                if p.bound >= cut {
                    self.pruned(&p, unit(axis));
                } else if queue.len() < qsize {
                    queue.push(p);
                } else if self.depth_first(p, cutoff, stop, true) {
                    // Stopped: the other seeds are left unvisited, with 0 as their bound.
                    for s in &seeds[i + 1..] {
                        self.pruned(
                            &NodePair {
                                bound: 0.0,
                                ..s.pair
                            },
                            Vec3::zeros(),
                        );
                    }
                    queue.drain(|c| self.pruned(&c, Vec3::zeros()));
                    break;
                }
            }
            'search: while let Some(p) = next.take().or_else(|| queue.pop()) {
                let cut = cutoff(self.best.d);
                if p.bound >= cut {
                    // Every queued node has a bound at least this large: all are pruned.
                    self.pruned(&p, Vec3::zeros());
                    break;
                }
                let Some([(near, near_axis), (far, far_axis)]) = self.visit(&p, cut, true) else {
                    if stop(self.best.d) {
                        break;
                    }
                    continue;
                };
                // A child's bound is raised to its parent's, which bounds its triangles too: the
                // queue wants every node pushed at least as far as the last one popped.
                let [near, far] = [near, far].map(|c| NodePair {
                    bound: c.bound.max(p.bound),
                    ..c
                });
                // The farther child waits in the queue; the nearer goes on at once if no queued
                // node can be nearer (none is below the last popped), else waits too.
                let near_next = queue.len() == 0 || near.bound <= queue.floor();
                for (c, axis, go_on) in [(far, far_axis, false), (near, near_axis, near_next)] {
                    if c.bound >= cutoff(self.best.d) {
                        // Pruned now, pruned later: the answer only improves.
                        self.pruned(&c, unit(axis));
                    } else if go_on {
                        next = Some(c);
                    } else if queue.len() < qsize {
                        queue.push(c);
                    } else if self.depth_first(c, cutoff, stop, true) {
                        if c.a == far.a && c.b == far.b {
                            // The nearer child is left unvisited too.
                            self.pruned(&near, Vec3::zeros());
                        }
                        break 'search;
                    }
                }
            }
            // Left behind by a stop, or by the prune that ends the search: each is pruned.
            if let Some(p) = next {
                self.pruned(&p, Vec3::zeros());
            }
            queue.drain(|c| self.pruned(&c, Vec3::zeros()));
        });
    }
}

/// The root of the BVTT with its bound (exact below `cutoff`, at least `cutoff` otherwise).
pub(crate) fn root_pair(b1: &Bvh, b2: &Bvh, rel: &RelPose, cutoff: f64) -> NodePair {
    let (a, b) = (b1.root(), b2.root());
    NodePair {
        a,
        b,
        bound: DistanceVolume::distance_below(&b1.ssv(a), &b2.ssv(b), rel, cutoff),
    }
}

/// A BVTT node with its bound, and an axis along which its volumes are at least that far apart
/// (in model 1's frame, from model 1's volume towards model 2's; not normalized), or zero.
pub(crate) type Child = (NodePair, Vec3);

/// The two children of the BVTT node `p` with their bounds (exact below `cutoff`, at least
/// `cutoff` otherwise) and, with `axes`, their separating axes (see [`Child`]; zero without), or
/// `None` for a pair of leaves. The descent rule: split model 1's node when model 2's is a leaf,
/// model 2's when model 1's is, else the one with the larger volume (model 1's on a tie). Leaves'
/// volumes (computed from their triangles) go through `leaves`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn expand(
    b1: &Bvh,
    b2: &Bvh,
    rel: &RelPose,
    slack: f64,
    p: &NodePair,
    cutoff: f64,
    want: Want,
    leaves: &mut LeafVolumes,
) -> Option<[Child; 2]> {
    let (a, b) = (p.a, p.b);
    let split_first = if b < 0 {
        if a < 0 {
            return None;
        }
        true
    } else if a < 0 {
        false
    } else {
        b1.nodes[a as usize].ssv_size() >= b2.nodes[b as usize].ssv_size()
    };
    // The fixed side is posed once, in the frame of the side being split; the children are read
    // where they lie (no copies).
    let pair = |a, b, (bound, axis)| (NodePair { a, b, bound }, axis);
    Some(if split_first {
        let fixed = leaves
            .posed
            .get(b, true, volume(b2, &mut leaves.second, b), rel);
        let [c0, c1] = b1.nodes[a as usize].children;
        let children = volumes(b1, &mut leaves.first, [c0, c1]);
        let [d0, d1] = Ssv::bounds_against_posed(children, fixed, rel, false, want, cutoff, slack);
        [pair(c0, b, d0), pair(c1, b, d1)]
    } else {
        let fixed = leaves
            .posed
            .get(a, false, volume(b1, &mut leaves.first, a), rel);
        let [c0, c1] = b2.nodes[b as usize].children;
        let children = volumes(b2, &mut leaves.second, [c0, c1]);
        let [d0, d1] = Ssv::bounds_against_posed(children, fixed, rel, true, want, cutoff, slack);
        [pair(a, c0, d0), pair(a, c1, d1)]
    })
}

/// The volume of node `r` of `b`, by reference: an inner node's where it lies, a leaf's through
/// `cache`.
#[inline(always)]
fn volume<'x>(b: &'x Bvh, cache: &'x mut LeafCache<CompactSsv>, r: NodeRef) -> &'x CompactSsv {
    cache.get_ref(r, |r| &b.nodes[r as usize].ssv, |r| b.leaf_compact_ssv(r))
}

/// As [`volume`], for two nodes at once.
#[inline(always)]
fn volumes<'x>(
    b: &'x Bvh,
    cache: &'x mut LeafCache<CompactSsv>,
    rs: [NodeRef; 2],
) -> [&'x CompactSsv; 2] {
    cache.get_two(rs, |r| &b.nodes[r as usize].ssv, |r| b.leaf_compact_ssv(r))
}

/// The children of a BVTT node that pairs a leaf with an inner node, by how many of them are leaf
/// pairs (with `p`'s bound, which bounds them too).
enum LeafChildren {
    /// Not such a node, or neither child is a leaf pair.
    None,
    /// The inner node's children are both leaves.
    Both([NodePair; 2]),
    /// One is: the leaf pair, then the other.
    One(NodePair, NodePair),
}

/// See [`LeafChildren`].
#[inline]
fn leaf_children(b1: &Bvh, b2: &Bvh, p: &NodePair) -> LeafChildren {
    let (leaf_first, node) = if p.a < 0 && p.b >= 0 {
        (true, b2.nodes[p.b as usize].children)
    } else if p.b < 0 && p.a >= 0 {
        (false, b1.nodes[p.a as usize].children)
    } else {
        return LeafChildren::None;
    };
    let pair = |c: NodeRef| {
        let (a, b) = if leaf_first { (p.a, c) } else { (c, p.b) };
        NodePair { a, b, ..*p }
    };
    match node {
        [c0, c1] if c0 < 0 && c1 < 0 => LeafChildren::Both([pair(c0), pair(c1)]),
        [c0, c1] if c0 < 0 => LeafChildren::One(pair(c0), pair(c1)),
        [c0, c1] if c1 < 0 => LeafChildren::One(pair(c1), pair(c0)),
        _ => LeafChildren::None,
    }
}

/// The bound of the BVTT node `p`, a leaf against an inner node, as [`expand`] gives its
/// children's (the leaf posed, through the same table).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn bound_one(
    b1: &Bvh,
    b2: &Bvh,
    rel: &RelPose,
    slack: f64,
    p: &NodePair,
    cutoff: f64,
    want: Want,
    leaves: &mut LeafVolumes,
) -> Child {
    let [(bound, axis)] = if p.a < 0 {
        let fixed = leaves
            .posed
            .get(p.a, false, volume(b1, &mut leaves.first, p.a), rel);
        let node = &b2.nodes[p.b as usize].ssv;
        Ssv::bounds_against_posed([node], fixed, rel, true, want, cutoff, slack)
    } else {
        let fixed = leaves
            .posed
            .get(p.b, true, volume(b2, &mut leaves.second, p.b), rel);
        let node = &b1.nodes[p.a as usize].ssv;
        Ssv::bounds_against_posed([node], fixed, rel, false, want, cutoff, slack)
    };
    (NodePair { bound, ..*p }, axis)
}

/// The smaller of two numbers (no NaN reaches here), as a select.
#[inline(always)]
fn least(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

/// `v` scaled to length 1, or zero when it is zero (or too small or large to scale exactly).
#[inline]
fn unit(v: Vec3) -> Vec3 {
    let len2 = v.norm_squared();
    if len2 >= f64::MIN_POSITIVE && len2.is_finite() {
        v * (1.0 / len2.sqrt())
    } else {
        Vec3::zeros()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whatever the slots, each node of either model gets its own volume posed the right way:
    /// the same index in both models, nodes that share a slot, a node met again after its slot
    /// was taken.
    #[test]
    fn posed_volumes_are_each_nodes_own() {
        let rel = RelPose {
            rot: nalgebra::Rotation3::from_euler_angles(0.3, -0.5, 1.1).into_inner(),
            trans: Vec3::new(0.5, -2.0, 3.0),
        };
        let volume = |r: NodeRef| CompactSsv {
            axes: [Vec3::x(), Vec3::y()],
            origin: Vec3::new(f64::from(r), 1.0, -2.0),
            lengths: [1.0, 2.0],
            radius: 0.25,
        };
        let mut posed = PosedVolumes::default();
        let s = POSED_SLOTS as NodeRef;
        let asks = [
            (0, true),
            (0, false),
            (0, true),
            (s, true),
            (0, true),
            (-1, false),
            (-1, true),
            (-1 - s, false),
            (-1, false),
            (s / 2, true),
            (s / 2, false),
            (0, false),
        ];
        for (r, second) in asks {
            let v = volume(r);
            let got = *posed.get(r, second, &v, &rel);
            assert_eq!(got, v.posed(&rel, !second), "node {r}, second {second}");
        }
    }
}
