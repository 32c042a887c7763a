//! The three proximity queries, one file each, and what they share (`traversal.rs`).
//!
//! Every query takes two built models, each with its pose, and works in model 1's frame: model 2's
//! volumes and triangles are brought there by the relative pose. Results are plain values that the
//! caller may keep and pass again: a distance or tolerance result remembers the closest triangle
//! pair it found (the *triangle cache*), and the next query on the same two models starts from it.
//! The cache lives in the result, never in the models, so models stay immutable and shareable.

mod collide;
mod distance;
pub(crate) mod search;
mod tolerance;
mod traversal;

pub use collide::{collide, collide_into, CollideResult, ContactMode, ContactPair};
pub use distance::{distance, distance_into, DistanceOptions, DistanceResult};
pub use search::{Search, Strategy};
pub use tolerance::{tolerance, tolerance_into, ToleranceResult};

use crate::bvh::{Bvh, NodeRef};
use crate::error::Error;
use crate::math::{Pose, RelPose};
use crate::model::Model;

/// Work counters and time of one query.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// Bounding-volume tests (overlap tests for collision, distance bounds otherwise).
    pub bv_tests: u64,
    /// Triangle-pair tests.
    pub tri_tests: u64,
    /// Wall-clock time of the query, in seconds.
    pub query_time_secs: f64,
}

/// The closest triangle pair of a previous query, by slot in each model's leaf order, tagged with the
/// models' build ids so that it is used only on the same two models.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct TriCache {
    uid1: u64,
    uid2: u64,
    tri1: u32,
    tri2: u32,
}

impl TriCache {
    fn new(m1: &Model, m2: &Model, tri1: usize, tri2: usize) -> TriCache {
        TriCache {
            uid1: m1.uid(),
            uid2: m2.uid(),
            tri1: tri1 as u32,
            tri2: tri2 as u32,
        }
    }

    /// Where a search starts: the cached pair, if the search uses triangle caching and the pair
    /// belongs to these two models.
    fn start_pair(
        cache: &Option<TriCache>,
        m1: &Model,
        m2: &Model,
        search: &Search,
    ) -> Option<(usize, usize)> {
        cache
            .filter(|c| search.triangle_cache && c.uid1 == m1.uid() && c.uid2 == m2.uid())
            .map(|c| (c.tri1 as usize, c.tri2 as usize))
    }
}

/// The BVTT front of the last distance query on two models: the nodes its search left behind (a
/// cut of the BVTT, see `search.rs`), kept in the result like the triangle cache. Under coherent
/// motion the next query starts from it rather than from the root, so it skips re-testing the
/// nodes above it (generalized front tracking): about half the bound tests of a search from the
/// root. It is used only on the same two models, with the triangle cache on, for a priority-directed
/// search, and when the relative pose moved little since (else a deep front where the models were
/// close would cost more than it saves); a front that has grown to twice its size after the last
/// search from the root (the models moved on, leaving fine nodes where nothing is near) is dropped.
#[derive(Clone, Debug, Default)]
pub(crate) struct Front {
    uid1: u64,
    uid2: u64,
    /// The relative pose of the query that left the front.
    rel: Option<RelPose>,
    pairs: Vec<[NodeRef; 2]>,
    /// Storage for the next front (no allocation per query once warm).
    spare: Vec<[NodeRef; 2]>,
    /// The front's size after the last search from the root.
    base: usize,
}

impl Front {
    /// A front of more than `GROWTH` times its size after the last search from the root is dropped.
    const GROWTH: f64 = 1.1;
    /// The relative pose may have moved by at most this much (each rotation entry, and each
    /// translation coordinate in units of the models' root volume sizes) for the front to be used.
    const MOTION: f64 = 0.1;

    /// The front to start from, if it suits this query.
    fn start<'a>(
        &'a self,
        m1: &Model,
        m2: &Model,
        rel: &RelPose,
        search: &Search,
        scale: f64,
    ) -> Option<&'a [[NodeRef; 2]]> {
        let prev = self.rel.as_ref()?;
        let near = (rel.rot - prev.rot).amax() <= Self::MOTION
            && (rel.trans - prev.trans).amax() <= Self::MOTION * scale;
        let usable = search.triangle_cache
            && search.resolve(Strategy::Priority) == Strategy::Priority
            && self.uid1 == m1.uid()
            && self.uid2 == m2.uid()
            && !self.pairs.is_empty()
            && near;
        usable.then_some(&self.pairs[..])
    }

    /// Whether the front `v` of a query that started from this front has grown too large to keep.
    fn outgrown(&self, v: &[[NodeRef; 2]], from_front: bool) -> bool {
        from_front && v.len() as f64 > Self::GROWTH * self.base as f64
    }

    /// Keeps the front `new` of a query at `rel` (`None`: none was recorded); `from_front`: whether
    /// that query started from this front.
    fn finish(
        &mut self,
        m1: &Model,
        m2: &Model,
        rel: RelPose,
        new: Option<Vec<[NodeRef; 2]>>,
        from_front: bool,
    ) {
        let same = self.uid1 == m1.uid() && self.uid2 == m2.uid();
        match new {
            // The search stopped before visiting anything (the cached pair touches): the old front
            // still covers every pair.
            Some(v) if v.is_empty() && same && !self.pairs.is_empty() => {
                self.spare = v;
                self.rel = Some(rel);
            }
            Some(v) if !v.is_empty() && !self.outgrown(&v, from_front) => {
                if !from_front {
                    self.base = v.len();
                }
                self.spare = std::mem::replace(&mut self.pairs, v);
                (self.uid1, self.uid2, self.rel) = (m1.uid(), m2.uid(), Some(rel));
            }
            other => {
                // Dropped: the next query searches from the root.
                self.spare = other.unwrap_or_default();
                self.pairs.clear();
                self.rel = None;
            }
        }
    }
}

/// Checks what every query needs and returns the two hierarchies and the relative pose.
fn prepare<'a>(
    m1: &'a Model,
    pose1: &Pose,
    m2: &'a Model,
    pose2: &Pose,
) -> Result<(&'a Bvh, &'a Bvh, RelPose), Error> {
    let b1 = m1.bvh()?;
    let b2 = m2.bvh()?;
    pose1.validate()?;
    pose2.validate()?;
    Ok((b1, b2, RelPose::between(pose1, pose2)))
}
