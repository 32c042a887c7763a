//! Point swept sphere fit: one sphere around all the points.

use super::ssv::{ball_centre, Ssv};
use crate::math::{Mat3, Vec3};

/// A sphere containing every point (not empty). Its centre is found in the principal frame, where
/// the points' bounding box is tightest, so the box-centre start is already good.
pub(super) fn fit(axes: &Mat3, points: &[Vec3]) -> Ssv {
    let (c, _) = ball_centre(points.len(), |i| axes.tr_mul(&points[i]));
    Ssv {
        axes: *axes,
        origin: axes * c,
        lengths: [0.0; 2],
        radius: 0.0,
    }
    .cover(points)
}
