//! What visiting one BVTT node costs the search: a pair of leaves is a triangle test (the closest
//! pair yet kept, the pair left in the front), an inner pair is expanded into its children with
//! their bounds (`bounds.rs`).

use super::bounds::{Child, LeafChildren, expand, leaf_children};
use super::{Best, ClosestSearch};
use crate::bounding_volume::Want;
use crate::bvh::NodeRef;
use crate::geometry::{Near, Plane, PlanedTri, Tri, tri_distance_below};
use crate::math::Vec3;
use crate::query::traversal::NodePair;

impl ClosestSearch<'_> {
    /// Tests a triangle pair, keeps it if it is the closest yet, and returns its distance with the
    /// vector between its closest points (from `ta` to `tb`, in model 1's frame); or, for a pair at
    /// least as far apart as the closest yet when no front is recorded, possibly that distance with
    /// a zero vector.
    ///
    /// The common case inline: a pair that model 2's triangle's plane shows at least the cutoff
    /// apart, when that plane is tried first (it settles nearly every pair where it does); the
    /// rest of [`tri_distance_below`] is called.
    #[inline(always)]
    pub(super) fn test_triangles(&mut self, ta: usize, tb: usize) -> (f64, Vec3) {
        self.stats.tri_tests += 1;
        let (b2, rel) = (self.b2, &self.rel);
        let moved = self.leaves.triangles.get_leaf(
            NodeRef::leaf(tb),
            #[inline(always)]
            |r| PlanedTri::new(b2.tri(r.triangle()).map(|v| rel.apply(&v))),
        );
        // A front keeps the pair's bound for the next query: the exact distance prunes more of
        // the next query than its cost here.
        let cutoff = if self.front.is_some() {
            f64::INFINITY
        } else {
            self.best.d
        };
        // `tri_distance_below`'s first test, with the plane from the cache: the plane it would
        // make, as `in_range` rules out its rescaling. A pair not shown apart here goes the whole
        // way (which tries this plane again: rare, about 135 pairs of 255,000 on nested shells).
        if self.in_range
            && cutoff < f64::INFINITY
            && self.plane_first == Plane::B
            && moved.apart(&self.b1.tri(ta), cutoff)
        {
            return (cutoff, Vec3::zeros());
        }
        let moved = moved.tri;
        self.test_rest(&moved, ta, tb, cutoff)
    }

    /// [`test_triangles`](ClosestSearch::test_triangles) beyond its common case.
    #[inline(never)]
    fn test_rest(&mut self, b: &Tri, ta: usize, tb: usize, cutoff: f64) -> (f64, Vec3) {
        let a = self.b1.tri(ta);
        let c = match tri_distance_below(&a, b, cutoff, self.plane_first, self.in_range) {
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
    pub(super) fn visit(&mut self, p: &NodePair, cutoff: f64, exact: bool) -> Option<[Child; 2]> {
        self.visit_unordered(p, cutoff, exact, |_| false)
            .map(|[x, y]| {
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
    /// infinite bound for the second (see [`depth_first`](ClosestSearch::depth_first)). There,
    /// a first leaf pair after which `stop` ends the search leaves the rest of the node unvisited
    /// (in the front, if one is kept, at the node's bound): a tolerance query's pair within the
    /// tolerance.
    #[inline(always)]
    pub(super) fn visit_unordered(
        &mut self,
        p: &NodePair,
        cutoff: f64,
        exact: bool,
        stop: impl Fn(f64) -> bool,
    ) -> Option<[Child; 2]> {
        if !exact {
            match leaf_children(self.b1, self.b2, p) {
                LeafChildren::Both([x, y]) => {
                    self.leaf_pair(&x);
                    if stop(self.best.d) {
                        self.left(&y, Vec3::zeros());
                    } else {
                        self.leaf_pair(&y);
                    }
                    return None;
                }
                LeafChildren::One(x, y) if self.front.is_none() => {
                    // The leaf pair straight to its triangles, the other bounded alone; the
                    // second child is a placeholder a depth-first search prunes (no front
                    // records it).
                    self.leaf_pair(&x);
                    if stop(self.best.d) {
                        return None;
                    }
                    self.stats.bv_tests += 1;
                    let want = Want { axes: false, exact };
                    let c = self.bound_one(&y, cutoff, want);
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
    #[inline(always)]
    pub(super) fn leaf_pair(&mut self, p: &NodePair) {
        let (d, gap) = self.test_triangles(p.a.triangle(), p.b.triangle());
        // The pair's own distance, which the closest points' axis shows: the tightest bound the
        // front can keep for it (the axis made a unit vector only for a front).
        if self.front.is_some() {
            let axis = if d > 0.0 { gap / d } else { Vec3::zeros() };
            self.left(&NodePair { bound: d, ..*p }, axis);
        }
    }
}
