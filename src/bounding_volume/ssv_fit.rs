//! [`Ssv::fit`]: the tightest swept sphere volume of a kind around a point set, by the kind's own
//! fit (`pss.rs`, `lss.rs`, `rss.rs`). Above both the type (`ssv.rs`) and the fits.

use super::ssv::{Ssv, SsvKind};
use super::{lss, pss, rss};
use crate::math::{Mat3, Vec3};

impl Ssv {
    /// The tightest volume of `kind` on the given axes (orthonormal right-handed columns, in
    /// decreasing order of spread) that contains every point of `points` (not empty): a sphere, a
    /// segment along the first axis, or a rectangle on the first two, each with the smallest radius
    /// its fit finds that reaches every point, as [`contains`](super::BoundingVolume::contains) measures.
    pub fn fit(kind: SsvKind, axes: &Mat3, points: &[Vec3]) -> Ssv {
        if points.is_empty() {
            // The builder never asks for this; an empty volume at the origin rather than NaNs.
            return Ssv {
                axes: *axes,
                origin: Vec3::zeros(),
                lengths: [0.0; 2],
                radius: 0.0,
            };
        }
        let local = |i: usize| axes.tr_mul(&points[i]);
        let z = |i: usize| local(i).z;
        let (mut zmin, mut zmax) = (z(0), z(0));
        if kind == SsvKind::Rect {
            for i in 0..points.len() {
                zmin = zmin.min(z(i));
                zmax = zmax.max(z(i));
            }
        }
        Ssv::fit_uncovered(kind, axes, points.len(), local, zmin, zmax).cover(points)
    }

    /// [`fit`](Ssv::fit) before [`cover`](Ssv::cover), from the `count` (> 0) points in the frame:
    /// `local(i) == axes.tr_mul(&points[i])`, the same bits. For a rectangle, `zmin` and `zmax`
    /// are the least and greatest `local(i).z`. The builder computes the points in the frame once
    /// for all the volumes it fits on it.
    #[inline]
    pub(crate) fn fit_uncovered(
        kind: SsvKind,
        axes: &Mat3,
        count: usize,
        local: impl Fn(usize) -> Vec3 + Copy,
        zmin: f64,
        zmax: f64,
    ) -> Ssv {
        debug_assert!(count > 0);
        match kind {
            SsvKind::Point => pss::fit(axes, count, local),
            SsvKind::Line => lss::fit(axes, count, local),
            SsvKind::Rect => rss::fit(axes, count, local, zmin, zmax),
        }
    }
}
