//! [`Ssv::fit`]: the tightest swept sphere volume of a kind around a point set, by the kind's own
//! fit (`pss.rs`, `lss.rs`, `rss.rs`). Above both the type (`ssv.rs`) and the fits.

use super::ssv::{Ssv, SsvKind};
use super::{lss, pss, rss};
use crate::math::{Mat3, UNDERFLOW_SLACK, Vec3};

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
        Ssv::fit_uncovered(kind, axes, points.len(), local, &[], zmin, zmax).cover(points)
    }

    /// [`fit`](Ssv::fit) before [`cover`](Ssv::cover), from the `count` (> 0) points in the frame:
    /// `local(i) == axes.tr_mul(&points[i])`, the same bits. For a rectangle, `zmin` and `zmax`
    /// are the least and greatest `local(i).z`. The builder computes the points in the frame once
    /// for all the volumes it fits on it. `pads`: empty, or one radius per point, making the
    /// points balls (see [`fit_balls`](Ssv::fit_balls)); `zmin` and `zmax` then bound the balls.
    #[inline]
    pub(crate) fn fit_uncovered(
        kind: SsvKind,
        axes: &Mat3,
        count: usize,
        local: impl Fn(usize) -> Vec3 + Copy,
        pads: &[f64],
        zmin: f64,
        zmax: f64,
    ) -> Ssv {
        debug_assert!(count > 0);
        match kind {
            SsvKind::Point => pss::fit(axes, count, local),
            SsvKind::Line => lss::fit(axes, count, local, pads),
            SsvKind::Rect => rss::fit(axes, count, local, pads, zmin, zmax),
        }
    }

    /// A volume of `kind` on `axes` (orthonormal right-handed columns) containing every ball
    /// (centre `centres[i]`, model frame; radius `pads[i] >= 0`; not empty), fitted as
    /// [`fit`](Ssv::fit) fits points. What a refit puts around a node's children: their cores'
    /// corners padded with their radii, and a triangle's vertices with 0.
    ///
    /// The radius reaches every ball's far side as `contains` measures distances, plus an
    /// allowance for rounding (about 1e-13 of the volume's magnitudes): every point that a ball's
    /// volume contains, as its `contains` measures it (with the same allowance), this one
    /// contains as its own measures it. So containment holds down a refitted hierarchy as
    /// strictly as after a build, whatever the rounding of the cores' corners.
    pub(crate) fn fit_balls(kind: SsvKind, axes: &Mat3, centres: &[Vec3], pads: &[f64]) -> Ssv {
        debug_assert!(!centres.is_empty() && centres.len() == pads.len());
        let local = |i: usize| axes.tr_mul(&centres[i]);
        let (mut zmin, mut zmax) = (f64::INFINITY, f64::NEG_INFINITY);
        for (i, p) in pads.iter().enumerate() {
            let z = local(i).z;
            zmin = zmin.min(z - p);
            zmax = zmax.max(z + p);
        }
        let mut v = Ssv::fit_uncovered(kind, axes, centres.len(), local, pads, zmin, zmax);
        let mut far = 0.0f64;
        for (c, p) in centres.iter().zip(pads) {
            far = far.max(v.core_distance(c) + p);
        }
        let r = v.radius.max(far);
        v.radius = r + REFIT_SLACK * (v.scale() + r) + UNDERFLOW_SLACK;
        v
    }

    /// The points of the core whose hull it is: its corners (one for a point, two for a segment,
    /// four for a rectangle), into `out`; returns how many.
    pub(crate) fn core_corners(&self, out: &mut [Vec3; 4]) -> usize {
        let u = self.axes.column(0) * self.lengths[0];
        let v = self.axes.column(1) * self.lengths[1];
        out[0] = self.origin;
        match self.kind() {
            SsvKind::Point => 1,
            SsvKind::Line => {
                out[1] = self.origin + u;
                2
            }
            SsvKind::Rect => {
                out[1] = self.origin + u;
                out[2] = self.origin + v;
                out[3] = self.origin + u + v;
                4
            }
        }
    }
}

/// The rounding allowance of a refitted volume, relative to its magnitudes: the corners of a
/// child's core and the distances to them are a few roundings off, each at most `EPSILON` of
/// those magnitudes; this is many times that and still negligible for pruning.
pub(crate) const REFIT_SLACK: f64 = 256.0 * f64::EPSILON;
