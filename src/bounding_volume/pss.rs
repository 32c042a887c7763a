//! Point swept sphere fit: one sphere around all the points.

use super::fit_support::ball_centre;
use super::ssv::Ssv;
use crate::math::{Mat3, Vec3};

/// A sphere containing every point (not empty), before [`Ssv::cover`]. Its centre is found in the principal frame, where
/// the points' bounding box is tightest, so the box-centre start is already good.
/// `local(i)` is the `i`th of the `count` points in the frame `axes`.
pub(super) fn fit(axes: &Mat3, count: usize, local: impl Fn(usize) -> Vec3) -> Ssv {
    let (c, _) = ball_centre(count, local);
    Ssv {
        axes: *axes,
        origin: axes * c,
        lengths: [0.0; 2],
        radius: 0.0,
    }
}
