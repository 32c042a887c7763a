//! Rectangle swept sphere fit: a rectangle on the two axes of largest spread, swept by a sphere
//! whose radius is half the spread along the third.

use super::fit_support::{allowance, padded_reach};
use super::ssv::Ssv;
use crate::math::{Mat3, Vec3};

/// The rectangle swept sphere containing every point (not empty), its rectangle on the first two
/// axes: the plane halves the points' spread along the normal, and the rectangle is the smallest
/// that keeps every point within the radius, growing where a point beside a corner needs it.
/// `local(i)` is the `i`th of the `count` points in the frame `axes`; `zmin` and `zmax` are the
/// least and greatest `local(i).z`. Before [`Ssv::cover`].
///
/// `pads`, empty or one per point: the points are then balls of these radii (a refit fits a node
/// around its children's volumes), `zmin` and `zmax` bound the balls, and each ball's centre is
/// kept within the radius less its pad.
pub(super) fn fit(
    axes: &Mat3,
    count: usize,
    local: impl Fn(usize) -> Vec3,
    pads: &[f64],
    zmin: f64,
    zmax: f64,
) -> Ssv {
    let reach = |i: usize| padded_reach(r_of(zmin, zmax), pads, i);
    // The plane halves the spread along the normal; the radius is half that spread.
    // Halve before adding: no overflow whatever the magnitudes.
    let zc = 0.5 * zmin + 0.5 * zmax;
    let r = r_of(zmin, zmax);

    // Each point may stick out beside the rectangle by its allowance, so a side needs to reach
    // only to the point's projection minus (or plus) it. These are the least extents for which
    // every point is within reach along each axis alone.
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..count {
        let q = local(i);
        // As the allowance is not negative, a point within the extents so far cannot move them:
        // only one outside needs its allowance (and its square root).
        // (Non-short-circuit `&`: one well-predicted branch rather than four.)
        if (q.x >= x0) & (q.x <= x1) & (q.y >= y0) & (q.y <= y1) {
            continue;
        }
        let h = allowance(reach(i), q.z - zc);
        x0 = x0.min(q.x + h);
        x1 = x1.max(q.x - h);
        y0 = y0.min(q.y + h);
        y1 = y1.max(q.y - h);
    }
    // Crossed extents mean every point's reach overlaps there: a zero side in the middle serves.
    if x0 > x1 {
        let m = 0.5 * x0 + 0.5 * x1;
        (x0, x1) = (m, m);
    }
    if y0 > y1 {
        let m = 0.5 * y0 + 0.5 * y1;
        (y0, y1) = (m, m);
    }

    // A point beside a corner may still be out of reach (its allowance is a disc, not a square):
    // grow the side that costs the least volume to bring it in. Growing never loses a point.
    for i in 0..count {
        let q = local(i);
        // How far outside each extent (not positive: inside it). As `x0 <= x1`, at most one of
        // the two differences is positive, so the larger is it when the point is outside.
        let (above_x, below_x) = (q.x - x1, x0 - q.x);
        let (above_y, below_y) = (q.y - y1, y0 - q.y);
        let dx = if above_x > below_x { above_x } else { below_x };
        let dy = if above_y > below_y { above_y } else { below_y };
        if (dx <= 0.0) | (dy <= 0.0) {
            continue;
        }
        let (grow_hi_x, grow_hi_y) = (q.x > x1, q.y > y1);
        let h = allowance(reach(i), q.z - zc);
        if dx * dx + dy * dy <= h * h {
            continue;
        }
        // Growth along one axis that brings the corner line of the other within reach. Should
        // rounding have left the point out of reach along an axis alone, that axis must grow.
        let (lx, ly) = (x1 - x0, y1 - y0);
        let (ex, ey) = match (dx >= h, dy >= h) {
            (true, true) => (dx, dy),
            (false, true) => (0.0, dy - allowance(h, dx)),
            (true, false) => (dx - allowance(h, dy), 0.0),
            (false, false) => {
                let ex = dx - allowance(h, dy);
                let ey = dy - allowance(h, dx);
                // Volume added by a growth e along x: e (2 r ly + pi r^2); likewise along y.
                let pr = std::f64::consts::PI * r;
                if ex * (2.0 * ly + pr) <= ey * (2.0 * lx + pr) {
                    (ex, 0.0)
                } else {
                    (0.0, ey)
                }
            }
        };
        if grow_hi_x {
            x1 += ex;
        } else {
            x0 -= ex;
        }
        if grow_hi_y {
            y1 += ey;
        } else {
            y0 -= ey;
        }
    }

    Ssv {
        axes: *axes,
        origin: axes * Vec3::new(x0, y0, zc),
        lengths: [(x1 - x0).max(0.0), (y1 - y0).max(0.0)],
        radius: r,
    }
}

/// Half the spread `zmin..zmax`: the radius.
#[inline(always)]
fn r_of(zmin: f64, zmax: f64) -> f64 {
    (0.5 * zmax - 0.5 * zmin).max(0.0)
}
