use super::rect_distance::rect_distance;
use super::{BoundingVolume, DistanceVolume};
use crate::math::{Mat3, RelPose, Vec3};

/// Rectangle swept sphere: the Minkowski sum of a rectangle and a sphere.
///
/// The rectangle spans `origin + s * axes.column(0) + t * axes.column(1)` for `s` in
/// `[0, lengths[0]]`, `t` in `[0, lengths[1]]`; `axes.column(2)` is its normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rss {
    /// Orthonormal axes (columns) in the model frame.
    pub axes: Mat3,
    /// The rectangle's corner, in the model frame.
    pub origin: Vec3,
    /// Side lengths along the first two axes.
    pub lengths: [f64; 2],
    /// Radius of the swept sphere.
    pub radius: f64,
}

/// Rounding allowance of a distance bound, relative to the magnitudes that enter it: composing the
/// pose and the frames costs a few tens of roundings, each at most `EPSILON` of those magnitudes.
const BOUND_SLACK: f64 = 64.0 * f64::EPSILON;

impl Rss {
    /// Distance from `p` (model frame) to the rectangle.
    #[inline]
    fn rectangle_distance(&self, p: &Vec3) -> f64 {
        let q = self.axes.tr_mul(&(p - self.origin));
        let dx = outside(q.x, 0.0, self.lengths[0]);
        let dy = outside(q.y, 0.0, self.lengths[1]);
        (dx * dx + dy * dy + q.z * q.z).sqrt()
    }
}

/// How far `x` is outside `[lo, hi]`.
#[inline(always)]
fn outside(x: f64, lo: f64, hi: f64) -> f64 {
    if x < lo {
        lo - x
    } else if x > hi {
        x - hi
    } else {
        0.0
    }
}

/// How far a point at height `dz` above the rectangle's plane may lie beside the rectangle, in the
/// plane, and stay within `r` of it: `sqrt(r^2 - dz^2)`, factored to keep precision near the caps.
#[inline(always)]
fn allowance(r: f64, dz: f64) -> f64 {
    ((r - dz) * (r + dz)).max(0.0).sqrt()
}

impl BoundingVolume for Rss {
    fn fit(axes: &Mat3, points: &[Vec3]) -> Self {
        let Some(first) = points.first() else {
            // The builder never asks for this; an empty volume at the origin rather than NaNs.
            return Rss {
                axes: *axes,
                origin: Vec3::zeros(),
                lengths: [0.0; 2],
                radius: 0.0,
            };
        };
        let n: Vec3 = axes.column(2).into();

        // The plane halves the spread along the normal; the radius is half that spread.
        let (mut zmin, mut zmax) = (n.dot(first), n.dot(first));
        for p in points {
            let z = n.dot(p);
            zmin = zmin.min(z);
            zmax = zmax.max(z);
        }
        // Halve before adding: no overflow whatever the magnitudes.
        let zc = 0.5 * zmin + 0.5 * zmax;
        let r = (0.5 * zmax - 0.5 * zmin).max(0.0);

        // Each point may stick out beside the rectangle by its allowance, so a side needs to reach
        // only to the point's projection minus (or plus) it. These are the least extents for which
        // every point is within reach along each axis alone.
        let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in points {
            let q = axes.tr_mul(p);
            let h = allowance(r, q.z - zc);
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
        for p in points {
            let q = axes.tr_mul(p);
            let h = allowance(r, q.z - zc);
            let (dx, grow_hi_x) = if q.x > x1 {
                (q.x - x1, true)
            } else {
                (x0 - q.x, false)
            };
            let (dy, grow_hi_y) = if q.y > y1 {
                (q.y - y1, true)
            } else {
                (y0 - q.y, false)
            };
            if dx <= 0.0 || dy <= 0.0 || dx * dx + dy * dy <= h * h {
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

        let mut rss = Rss {
            axes: *axes,
            origin: axes * Vec3::new(x0, y0, zc),
            lengths: [(x1 - x0).max(0.0), (y1 - y0).max(0.0)],
            radius: r,
        };
        // Rounding (of the corner, the sides, the allowances) may leave a point a few ulps out: take
        // the radius up to the distances exactly as `contains` measures them.
        for p in points {
            rss.radius = rss.radius.max(rss.rectangle_distance(p));
        }
        rss
    }

    fn contains(&self, p: &Vec3, eps: f64) -> bool {
        self.rectangle_distance(p) <= self.radius + eps
    }

    fn size(&self) -> f64 {
        (self.lengths[0] * self.lengths[0] + self.lengths[1] * self.lengths[1]).sqrt()
            + 2.0 * self.radius
    }
}

impl DistanceVolume for Rss {
    #[inline]
    fn distance(a: &Self, b: &Self, rel: &RelPose) -> f64 {
        Rss::distance_below(a, b, rel, f64::INFINITY)
    }

    #[inline]
    fn distance_below(a: &Self, b: &Self, rel: &RelPose, cutoff: f64) -> f64 {
        // b's rectangle in the frame of a's rectangle: axes A^T rot B, corner A^T (rot ob + trans - oa).
        let m = a.axes.tr_mul(&rel.rot);
        let r = m * b.axes;
        let t = m * b.origin + a.axes.tr_mul(&(rel.trans - a.origin));
        // Err low by the rounding of the composition, so the bound never exceeds the true distance.
        let scale = a.origin.abs().sum()
            + b.origin.abs().sum()
            + rel.trans.abs().sum()
            + a.lengths[0]
            + a.lengths[1]
            + b.lengths[0]
            + b.lengths[1];
        let slack = BOUND_SLACK * scale;
        // The rectangles' distance that makes the bound reach the cutoff, with a second slack so
        // that a rectangle distance at or above it proves the bound's true value is at least cutoff.
        let core_cutoff = cutoff + a.radius + b.radius + 2.0 * slack;
        let d = rect_distance(&r, &t, a.lengths, b.lengths, core_cutoff);
        let bound = (d - a.radius - b.radius - slack).max(0.0);
        if d >= core_cutoff {
            bound.max(cutoff)
        } else {
            bound
        }
    }
}
