//! Line swept sphere fit: a segment along the axis of largest spread, swept by the smallest sphere
//! that reaches every point.

use super::fit_support::{allowance, ball_centre, padded_reach};
use super::ssv::Ssv;
use crate::math::{Mat3, Vec3};

/// A capsule containing every point (not empty), its segment along `axes.column(0)`, before
/// [`Ssv::cover`].
/// `local(i)` is the `i`th of the `count` points in the frame `axes`. `pads`, empty or one per
/// point: the points are then balls of these radii (see `rss::fit`).
pub(super) fn fit(axes: &Mat3, count: usize, local: impl Fn(usize) -> Vec3, pads: &[f64]) -> Ssv {
    // The segment's line: through the centre of a small disc around the points' projections on the
    // plane of the other two axes; the radius must reach the farthest of them.
    let (c, r2) = ball_centre(count, |i| {
        let q = local(i);
        Vec3::new(0.0, q.y, q.z)
    });
    let mut r = r2.sqrt();
    // Balls: the radius reaches the far side of each.
    for (i, p) in pads.iter().enumerate() {
        let q = local(i);
        let (dy, dz) = (q.y - c.y, q.z - c.z);
        r = r.max((dy * dy + dz * dz).sqrt() + p);
    }
    // Each point may lie beyond an end by its allowance sqrt(r^2 - rho^2) (rho its distance from
    // the line) and still be in the end cap: the segment need only reach each projection minus (or
    // plus) it. These extents are the least that keep every point in.
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..count {
        let q = local(i);
        let (dy, dz) = (q.y - c.y, q.z - c.z);
        let h = allowance(padded_reach(r, pads, i), (dy * dy + dz * dz).sqrt());
        x0 = x0.min(q.x + h);
        x1 = x1.max(q.x - h);
    }
    // Crossed extents mean every point's reach overlaps there: a zero-length segment in the middle.
    if x0 > x1 {
        let m = 0.5 * x0 + 0.5 * x1;
        (x0, x1) = (m, m);
    }
    Ssv {
        axes: *axes,
        origin: axes * Vec3::new(x0, c.y, c.z),
        lengths: [(x1 - x0).max(0.0), 0.0],
        radius: r,
    }
}
