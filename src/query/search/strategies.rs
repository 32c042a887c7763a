//! The three visiting orders of the search (see [`Strategy`](super::Strategy)): depth-first,
//! breadth-first and priority-directed (with its depth-first overflow and its start from a front).
//! Each visits a BVTT node only while its bound is below the caller's cutoff, and ends when the
//! caller's stop rule says so.

use super::ClosestSearch;
use super::bounds::{prefetch_children, prefetch_grandchildren};
use crate::math::{Vec3, least};
use crate::query::front::{FrontPair, Motion};
use crate::query::queue::RadixQueue;
use crate::query::traversal::{NodePair, PairStack};
use std::cell::RefCell;
use std::collections::VecDeque;

impl ClosestSearch<'_> {
    /// Depth-first, nearer child first. Returns whether `stop` ended the search.
    ///
    /// With `loose`, it asks for loose bounds (see [`Want`](crate::bounding_volume::Want)): a pair
    /// below the cutoff is expanded whatever its bound, and only the order of two siblings suffers
    /// a little, as long as the cutoff does not fall much before the pair's turn (a lower bound
    /// that is not the exact one then prunes less). So the overflow of a priority-directed search, whose cutoff is nearly
    /// final by then, and a tolerance query, whose cutoff is fixed, ask for them; a distance
    /// query's depth-first search from the root does not: its cutoff falls as it goes, and
    /// siblings in the wrong order then cost many more bound tests. Loose bounds pay where most
    /// pairs are below the cutoff (the nested shells). With them, a leaf pair under a leaf and an
    /// inner node goes straight to its triangles (see [`visit_unordered`]): bounding it would cost
    /// about as much as a triangle test that the planes settle, and would seldom prune where the
    /// cutoff stays put.
    ///
    /// [`visit_unordered`]: ClosestSearch::visit_unordered
    // Each strategy is inlined into both copies of `run` (see `math::avx2_or_portable`).
    #[inline(always)]
    pub(super) fn depth_first(
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
            // The volumes its children's expansions will read, while it bounds them (an
            // approximate query's: see `ClosestSearch::prefetch_ahead`).
            if self.ahead {
                prefetch_grandchildren(self.b1, self.b2, &p);
            }
            if let Some([(x, _), (y, _)]) = self.visit_unordered(&p, cut, !loose, &stop) {
                // Nearer child on top; a child at or beyond the cutoff is pruned now (the cutoff
                // only falls). Both without branches where no front is kept: either decision is
                // a coin toss on most models, which a branch mispredicts.
                let pair = [x, y];
                let k = usize::from(y.bound < x.bound);
                let (near, far) = (pair[k], pair[1 - k]);
                if self.front.is_none() {
                    for c in [far, near] {
                        let keep = c.bound < cut;
                        // Its volumes on their way into the cache while the search goes on (the
                        // far child's subtree comes first only after the near child's); already
                        // asked for when its parent was, with `ahead`.
                        if keep && self.prefetch && !self.ahead {
                            prefetch_children(self.b1, self.b2, &c);
                        }
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
    #[inline(always)]
    pub(super) fn breadth_first(
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
    /// bounds were computed before `motion`: a seed whose volumes' gap along its separating axis
    /// now (or without one, whose bound less the motion of its points) is still beyond the cutoff
    /// is pruned at once, the others are tested first.
    #[inline(always)]
    pub(super) fn priority(
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
            for (i, f) in seeds.iter().enumerate() {
                let FrontPair {
                    pair: seed, axis, ..
                } = *f;
                let cut = cutoff(self.best.d);
                let (a, b) = (seed.a, seed.b);
                if let Some(m) = &motion {
                    // The old bound less the whole model's motion first (free), then the volumes'
                    // gap along the node's axis now (a few dot products; it may have grown since),
                    // or without one, the old bound less the node's own motion. Model 1's side of
                    // the gap is kept with the node once measured (its volume does not move).
                    let (mut now, mut side1) = (seed.bound - m.whole(), f.side1);
                    if now < cut {
                        (now, side1) = m.renewed(self.b1, self.b2, f, cut);
                    }
                    if now >= cut {
                        let pair = NodePair { bound: now, ..seed };
                        self.pruned_pair(FrontPair { pair, axis, side1 });
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
                // As in the depth-first search.
                if self.ahead {
                    prefetch_grandchildren(self.b1, self.b2, &p);
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
                        continue;
                    }
                    // Its volumes on their way into the cache while it waits (as in the
                    // depth-first search; with `ahead`, asked for already).
                    if self.prefetch && !self.ahead {
                        prefetch_children(self.b1, self.b2, &c);
                    }
                    if go_on {
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
