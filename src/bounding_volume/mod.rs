//! Bounding volumes: oriented boxes (`obb.rs`) and the swept sphere volume family (`ssv.rs`, the
//! type and its distance, over the exact core distance of `rect_distance.rs`; one fit per kind,
//! `pss.rs`, `lss.rs`, `rss.rs`, over `fit_support.rs`; and `ssv_fit.rs`, which dispatches to
//! them). Dependencies point one way: `ssv_fit` -> fits -> `ssv`, `fit_support` -> geometry, math.
//!
//! A volume is fitted in its model's frame on principal axes chosen by the hierarchy builder, and
//! tested against a volume of another model through the relative pose of the second model's frame in
//! the first's. Distance volumes give a lower bound on the distance between anything they contain;
//! overlap volumes answer whether they may intersect.

mod fit_support;
mod lss;
mod obb;
mod pss;
mod rect_distance;
mod rss;
mod ssv;
mod ssv_fit;

pub use obb::{Obb, PosedObb};
pub(crate) use rect_distance::rect_distance;
pub(crate) use ssv::CompactSsv;
pub(crate) use ssv::Want;
pub use ssv::{Ssv, SsvKind};

use crate::geometry::Tri;
use crate::math::{RelPose, Vec3};

/// What every bounding volume offers the hierarchy builder.
pub trait BoundingVolume: Copy + Send + Sync + std::fmt::Debug + 'static {
    /// Whether `p` lies in the volume, allowing `eps` of slack (for tests and debug checks).
    fn contains(&self, p: &Vec3, eps: f64) -> bool;

    /// A size used to decide which volume of a pair to descend (the larger one).
    fn size(&self) -> f64;
}

/// Volumes that bound distance: the separation-distance and tolerance queries use these.
pub trait DistanceVolume: BoundingVolume {
    /// A lower bound (>= 0) on the distance between any point of `a` and any point of `b`, where `b`
    /// is in a frame whose pose in `a`'s frame is `rel`. Returns 0 when they overlap.
    fn distance(a: &Self, b: &Self, rel: &RelPose) -> f64;

    /// As [`distance`](Self::distance) when that is below `cutoff` (not NaN); otherwise any lower
    /// bound no less than `cutoff`, which may be cheaper. A search that prunes every pair whose bound
    /// reaches `cutoff` loses nothing by it.
    fn distance_below(a: &Self, b: &Self, rel: &RelPose, cutoff: f64) -> f64 {
        let _ = cutoff;
        Self::distance(a, b, rel)
    }
}

/// Volumes that bound overlap: the collision query uses these.
pub trait OverlapVolume: BoundingVolume {
    /// Whether `a` and `b` (with `b` posed by `rel` in `a`'s frame) may share a point. Never false
    /// when they do.
    #[inline]
    fn overlap(a: &Self, b: &Self, rel: &RelPose) -> bool {
        Self::overlap_posed(a, &Self::pose(b, rel), rel)
    }

    /// `b` (of the second model) as [`overlap_posed`](OverlapVolume::overlap_posed) takes it.
    type Posed: Copy;

    /// `b` posed by `rel`, once for all the volumes of the first model it is tested against.
    fn pose(b: &Self, rel: &RelPose) -> Self::Posed;

    /// [`overlap`](OverlapVolume::overlap) with `b` given as [`pose`](OverlapVolume::pose) made it
    /// (with the same `rel`).
    fn overlap_posed(a: &Self, b: &Self::Posed, rel: &RelPose) -> bool;

    /// Whether `a` may share a point with the triangle `t` (given in `a`'s model frame), for
    /// volumes with a direct test; `None` makes the caller test against the triangle's own volume.
    /// Never `Some(false)` when they share a point.
    fn overlap_triangle(a: &Self, t: &Tri) -> Option<bool> {
        let _ = (a, t);
        None
    }
}
