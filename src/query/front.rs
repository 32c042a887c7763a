//! The BVTT front a distance result keeps for the next query (generalized front tracking).
//!
//! A search of the bounding volume test tree (BVTT) expands some of its nodes and leaves the rest
//! behind: pruned, tested as triangle pairs, or unvisited when it stops. The nodes left behind form
//! a cut of the BVTT (every triangle pair lies below one of them): the *front*. Under coherent
//! motion the next query starts from the front rather than from the root, and so skips the nodes
//! above it, which it would expand again anyway.
//!
//! Each front node keeps the lower bound it had (on the distance between the triangles below it).
//! When model 2 moves relative to model 1, no point of it moves by more than the motion's reach
//! `‖ΔR‖ |p|max + |Δt|`, so no distance shrinks by more than that: the old bound minus the reach
//! is still a lower bound, and a node it puts beyond the search's cutoff is pruned without a test.
//! Under coherent motion most of the front is settled that way.
//!
//! The front is used only on the same two models, with the triangle cache on, for a
//! priority-directed search, and when the relative pose moved little since the query that left it
//! (else a front that is fine where the models were close would cost more than it saves); it is
//! dropped once it has grown past [`Front::GROWTH`] times its size after the last search from the
//! root (the models moved on, leaving fine nodes where nothing is near).

use super::search::{Search, Strategy};
use super::traversal::NodePair;
use crate::bvh::Bvh;
use crate::math::RelPose;
use crate::model::Model;

/// What a distance result keeps of its last query's search, for the next (see the module docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct Front {
    uid1: u64,
    uid2: u64,
    /// The relative pose at which the front's bounds hold; `None`: no front.
    rel: Option<RelPose>,
    /// The front nodes, each with a lower bound on the distance of the triangles below it.
    nodes: Vec<NodePair>,
    /// Storage for the next front (no allocation per query once warm).
    spare: Vec<NodePair>,
    /// The front's size after the last search from the root.
    base: usize,
}

impl Front {
    /// A front of more than this many times its size after the last search from the root is
    /// dropped (measured on the tumbling tori of BENCHMARKS.md).
    const GROWTH: f64 = 1.1;
    /// The relative pose may have moved by at most this much (each rotation entry, and each
    /// translation coordinate in units of the models' root volume sizes) for the front to be used.
    const MOTION: f64 = 0.1;

    /// Storage for the front of the next query.
    pub fn take_spare(&mut self) -> Vec<NodePair> {
        let mut v = std::mem::take(&mut self.spare);
        v.clear();
        v
    }

    /// The front to start the query at `rel` from, if it suits it, with how much its bounds may
    /// have shrunk since they were computed.
    pub fn start(
        &self,
        m1: &Model,
        m2: &Model,
        b1: &Bvh,
        b2: &Bvh,
        rel: &RelPose,
        search: &Search,
    ) -> Option<(&[NodePair], f64)> {
        let prev = self.rel.as_ref()?;
        let scale = b1.root_size() + b2.root_size();
        let dr = rel.rot - prev.rot;
        let dt = rel.trans - prev.trans;
        let usable = search.triangle_cache
            && search.resolve(Strategy::Priority) == Strategy::Priority
            && self.uid1 == m1.uid()
            && self.uid2 == m2.uid()
            && !self.nodes.is_empty()
            && dr.amax() <= Self::MOTION
            && dt.amax() <= Self::MOTION * scale;
        // A point p of model 2 moves by (ΔR) p + Δt in model 1's frame: by at most
        // ‖ΔR‖_F |p| + |Δt|, with |p| at most model 2's reach. Rounded up generously.
        let reach = dr.norm() * b2.reach() + dt.norm();
        usable.then(|| (&self.nodes[..], reach * (1.0 + 1e-6) + 1e-300))
    }

    /// Keeps the front `new` of a query at `rel` (`None`: none was recorded); `from_front`: whether
    /// that query started from this front.
    pub fn finish(
        &mut self,
        m1: &Model,
        m2: &Model,
        rel: RelPose,
        new: Option<Vec<NodePair>>,
        from_front: bool,
    ) {
        let same = self.uid1 == m1.uid() && self.uid2 == m2.uid();
        match new {
            // The search stopped before visiting anything (the cached pair touches): the old front
            // still covers every pair, but its bounds hold at its own pose only, which is kept.
            Some(v) if v.is_empty() && same && self.rel.is_some() => self.spare = v,
            Some(v) if !v.is_empty() && !self.outgrown(&v, from_front) => {
                if !from_front {
                    self.base = v.len();
                }
                self.spare = std::mem::replace(&mut self.nodes, v);
                (self.uid1, self.uid2, self.rel) = (m1.uid(), m2.uid(), Some(rel));
            }
            other => {
                // Dropped: the next query searches from the root.
                self.spare = other.unwrap_or_default();
                self.nodes.clear();
                self.rel = None;
            }
        }
    }

    /// Whether the front `v` of a query that started from this front has grown too large to keep.
    fn outgrown(&self, v: &[NodePair], from_front: bool) -> bool {
        from_front && v.len() as f64 > Self::GROWTH * self.base as f64
    }
}
