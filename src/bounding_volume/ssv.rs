//! Swept sphere volumes: the Minkowski sum of a core primitive (a point, a segment or a rectangle)
//! and a sphere, after Larsen, Gottschalk, Lin and Manocha. The three kinds are one family: a point
//! is a rectangle with both sides 0, a segment one with its second side 0. So one type holds them
//! all, a hierarchy node keeps one distance-volume field whatever kind its builder chose, and the
//! distance between any two is the distance between their cores minus both radii.
//!
//! This file holds the type, the containment test the fits are measured by, and the distance. The
//! fits live one per kind (`pss.rs`, `lss.rs`, `rss.rs`, over the helpers of `fit_support.rs`),
//! and [`Ssv::fit`], which chooses among them, in `ssv_fit.rs`: they build on this file, never
//! the other way round.

use super::rect_distance::rect_distance;
use super::{BoundingVolume, DistanceVolume, OverlapVolume};
use crate::geometry::segment_segment;
use crate::math::{Mat3, RelPose, UNDERFLOW_SLACK, Vec3, frame_from, use_avx2};

/// The core primitive of a swept sphere volume: what its side lengths make it (see [`Ssv::kind`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SsvKind {
    /// Point swept sphere (PSS): a sphere. Both sides are 0.
    Point,
    /// Line swept sphere (LSS): a segment along the first axis swept by a sphere (a capsule).
    /// The second side is 0.
    Line,
    /// Rectangle swept sphere (RSS): a rectangle on the first two axes swept by a sphere.
    Rect,
}

/// Swept sphere volume: the set of points within `radius` of its core.
///
/// The core spans `origin + s * axes.column(0) + t * axes.column(1)` for `s` in `[0, lengths[0]]`,
/// `t` in `[0, lengths[1]]`; `axes.column(2)` is the rectangle's normal. With both sides 0 it is a
/// point swept sphere (the core is `origin`), with the second side 0 a line swept sphere. The kind
/// is read from the sides rather than stored: it only chooses the fastest exact distance routine,
/// and a stored one would cost 8 bytes per volume and an invariant to keep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ssv {
    /// Orthonormal axes (columns) in the model frame.
    pub axes: Mat3,
    /// The core's corner (the centre of a PSS, an end of an LSS's segment), in the model frame.
    pub origin: Vec3,
    /// Side lengths along the first two axes (`>= 0`).
    pub lengths: [f64; 2],
    /// Radius of the swept sphere.
    pub radius: f64,
}

/// A swept sphere volume as a hierarchy stores it: without the third axis (the normal), which is
/// the cross product of the first two ([`Ssv::compact`], [`CompactSsv::full`]). The bounds read
/// it where it lies, and get the normal's part from the other volume's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub(crate) struct CompactSsv {
    /// The first two axes (orthonormal), in the model frame.
    pub axes: [Vec3; 2],
    /// As in [`Ssv`].
    pub origin: Vec3,
    pub lengths: [f64; 2],
    pub radius: f64,
}

impl CompactSsv {
    /// The volume with its normal.
    #[inline(always)]
    pub fn full(&self) -> Ssv {
        Ssv {
            axes: frame_from(&self.axes[0], &self.axes[1]),
            origin: self.origin,
            lengths: self.lengths,
            radius: self.radius,
        }
    }

    /// This volume carried by `rel` (by its inverse if `inverse`, the rotation taken as
    /// orthonormal), with its normal: the cross product of the carried axes.
    #[inline(always)]
    pub(crate) fn posed(&self, rel: &RelPose, inverse: bool) -> Ssv {
        let (u, v, origin) = if inverse {
            (
                rel.rot.tr_mul(&self.axes[0]),
                rel.rot.tr_mul(&self.axes[1]),
                rel.apply_inverse(&self.origin),
            )
        } else {
            (
                rel.rot * self.axes[0],
                rel.rot * self.axes[1],
                rel.apply(&self.origin),
            )
        };
        Ssv {
            axes: frame_from(&u, &v),
            origin,
            lengths: self.lengths,
            radius: self.radius,
        }
    }

    /// As [`Ssv::scale`].
    #[inline(always)]
    pub(crate) fn scale(&self) -> f64 {
        scale_of(&self.origin, self.lengths)
    }
}

/// What a search wants of the bounds it asks for, besides their being lower bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Want {
    /// A separating axis with each bound (see [`Ssv::bounds_against`]).
    pub axes: bool,
    /// The exact distance of a pair whose bound is below the cutoff. A search that expands such a
    /// pair whatever its bound is, and orders or prunes pairs by their bounds only loosely
    /// (depth-first), can do without: then once the cores are seen to be nearer than the cutoff
    /// (a corner of one within it of the other), a cheaper lower bound comes back.
    pub exact: bool,
}

impl Want {
    /// Exact bounds below the cutoff, no axes.
    pub const EXACT: Want = Want {
        axes: false,
        exact: true,
    };
    /// Exact bounds below the cutoff, with their axes.
    #[cfg(test)]
    pub const AXES: Want = Want {
        axes: true,
        exact: true,
    };
}

/// Rounding allowance of a distance bound, relative to the magnitudes that enter it: composing the
/// pose and the frames costs a few tens of roundings, each at most `EPSILON` of those magnitudes.
const BOUND_SLACK: f64 = 64.0 * f64::EPSILON;

impl Ssv {
    /// What the core is: a point (both sides 0), a segment along the first axis (second side 0),
    /// or a rectangle.
    #[inline(always)]
    pub fn kind(&self) -> SsvKind {
        kind_of(self.lengths)
    }

    /// This volume without its normal.
    #[inline(always)]
    pub(crate) fn compact(&self) -> CompactSsv {
        CompactSsv {
            axes: [self.axes.column(0).into(), self.axes.column(1).into()],
            origin: self.origin,
            lengths: self.lengths,
            radius: self.radius,
        }
    }

    /// Distance from `p` (model frame) to the core. A point and a segment are rectangles with zero
    /// sides, for which the clamps below pin the coordinates to 0.
    #[inline]
    pub(crate) fn core_distance(&self, p: &Vec3) -> f64 {
        self.core_distance_squared(p).sqrt()
    }

    /// The square of [`core_distance`](Ssv::core_distance), as it computes it before the root.
    #[inline(always)]
    pub(crate) fn core_distance_squared(&self, p: &Vec3) -> f64 {
        let q = self.axes.tr_mul(&(p - self.origin));
        let dx = outside(q.x, 0.0, self.lengths[0]);
        let dy = outside(q.y, 0.0, self.lengths[1]);
        dx * dx + dy * dy + q.z * q.z
    }

    /// Takes the radius up to every point's distance from the core, exactly as `contains` measures
    /// it: the fits' rounding may otherwise leave a point a few ulps out.
    pub(crate) fn cover(mut self, points: &[Vec3]) -> Ssv {
        // The largest squared distance, then one square root: as the square root is correctly
        // rounded it is monotonic, so this is the largest of the points' distances, bit for bit.
        let mut far2 = 0.0f64;
        for p in points {
            far2 = far2.max(self.core_distance_squared(p));
        }
        self.radius = self.radius.max(far2.sqrt());
        self
    }

    /// Volume of the solid in cubes of side `unit` (> 0; chosen near the volume's size so that
    /// cubing huge coordinates does not overflow). Steiner's formula for a flat convex core: twice
    /// its area times r, plus pi times half its perimeter times r^2, plus the ball.
    pub fn volume(&self, unit: f64) -> f64 {
        let (a, b, r) = (
            self.lengths[0] / unit,
            self.lengths[1] / unit,
            self.radius / unit,
        );
        let pi = std::f64::consts::PI;
        r * (2.0 * a * b + r * (pi * (a + b) + r * (4.0 / 3.0 * pi)))
    }

    /// The distance between the two cores, `b` posed by `rel` in `a`'s frame, by the cheapest
    /// routine for the pair of kinds; all are exact up to rounding. With `enough > 0`, any value
    /// between the distance and `enough` may be returned once one is found (see `rect_distance`).
    #[inline]
    fn cores_distance(a: &Ssv, b: &Ssv, rel: &RelPose, enough: f64, cutoff: f64) -> f64 {
        Ssv::cores_distance_here(a, &b.posed(rel).compact(), enough, cutoff, true).0
    }

    /// As [`cores_distance`](Ssv::cores_distance) for two volumes in the same frame, with an axis
    /// along which the cores are at least the returned value apart (see `rect_distance`), in the
    /// frame of `a`'s axes; zero when there is none (and for pairs with a point or two segments,
    /// which the default volumes never meet). The copy compiled for AVX2 where the processor has
    /// it (see `math::use_avx2`), else the portable one; neither is inlined: one copy of the kernel
    /// serves every caller and stays in the instruction cache.
    #[inline(always)]
    fn cores_distance_here(
        a: &Ssv,
        b: &CompactSsv,
        enough: f64,
        cutoff: f64,
        exact: bool,
    ) -> (f64, Vec3) {
        #[cfg(target_arch = "x86_64")]
        if use_avx2() {
            // SAFETY: the processor has AVX2.
            return unsafe { Ssv::cores_distance_avx2(a, b, enough, cutoff, exact) };
        }
        Ssv::cores_distance_portable(a, b, enough, cutoff, exact)
    }

    /// The kernel compiled for AVX2 (see `math::use_avx2`), its arguments in registers.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[inline(never)]
    fn cores_distance_avx2(
        a: &Ssv,
        b: &CompactSsv,
        enough: f64,
        cutoff: f64,
        exact: bool,
    ) -> (f64, Vec3) {
        Ssv::cores_distance_body(a, b, enough, cutoff, exact)
    }

    /// The kernel's portable copy.
    #[inline(never)]
    fn cores_distance_portable(
        a: &Ssv,
        b: &CompactSsv,
        enough: f64,
        cutoff: f64,
        exact: bool,
    ) -> (f64, Vec3) {
        Ssv::cores_distance_body(a, b, enough, cutoff, exact)
    }

    /// The kernel of [`cores_distance_here`](Ssv::cores_distance_here).
    #[inline(always)]
    fn cores_distance_body(
        a: &Ssv,
        b: &CompactSsv,
        enough: f64,
        cutoff: f64,
        exact: bool,
    ) -> (f64, Vec3) {
        use SsvKind::{Line, Point, Rect};
        let none = Vec3::zeros();
        match (a.kind(), kind_of(b.lengths)) {
            (Point, Point) => ((a.origin - b.origin).norm(), none),
            (Point, _) => (b.full().core_distance(&a.origin), none),
            (_, Point) => (a.core_distance(&b.origin), none),
            (Line, Line) => {
                let p1 = a.origin + a.axes.column(0) * a.lengths[0];
                let q1 = b.origin + b.axes[0] * b.lengths[0];
                let d = segment_segment(&a.origin, &p1, &b.origin, &q1).distance;
                (d, none)
            }
            (Line | Rect, Line | Rect) => {
                // b's core in the frame of a's core: axes A^T B, corner A^T (ob - oa). B's normal
                // there is the cross product of its first two axes there (a rotation keeps cross
                // products).
                // Through the transpose: products by columns, which the compiler vectorizes,
                // rather than dot products.
                let at = a.axes.transpose();
                let (u, v) = (at * b.axes[0], at * b.axes[1]);
                let r = frame_from(&u, &v);
                let t = at * (b.origin - a.origin);
                rect_distance(&r, &t, a.lengths, b.lengths, enough, cutoff, exact)
            }
        }
    }

    /// This volume carried by `rel` into the frame `rel` maps to.
    #[inline(always)]
    pub(crate) fn posed(&self, rel: &RelPose) -> Ssv {
        Ssv {
            axes: rel.rot * self.axes,
            origin: rel.apply(&self.origin),
            ..*self
        }
    }

    /// This volume's part of the magnitudes a bound's rounding is relative to (see `slack`).
    #[inline(always)]
    pub(crate) fn scale(&self) -> f64 {
        scale_of(&self.origin, self.lengths)
    }

    /// The bounds of several volumes `a` against one volume `b` posed by `rel` in their frame, as
    /// [`distance_below`](DistanceVolume::distance_below) gives them, sharing the work of posing
    /// `b`. `inverse`: `rel` poses the `a`s in `b`'s frame instead.
    ///
    /// With `want.axes`, each bound comes with a separating axis (zero without): a direction, in
    /// the frame `rel` maps into, from the volume that lives there towards the one `rel` poses
    /// (from `a` to `b`, or from `b` to `a` when `inverse`), along which the two are at least the
    /// bound apart; not normalized, and zero when there is none to give. Front tracking bounds how
    /// much the bound can shrink from how far the points move along it. Without `want.exact`, a
    /// bound below `cutoff` may be any lower bound of the distance (see [`Want`]).
    ///
    /// `slack`: the rounding allowance, at least [`Ssv::slack_for`] of the volumes' scales (a
    /// search takes one for all the pairs of its two models).
    ///
    /// `b` comes already posed: `moved` is `b.posed(rel, inverse)` (a search keeps recently posed
    /// volumes and poses each once).
    #[inline(always)]
    pub(crate) fn bounds_against<const N: usize>(
        a: [&CompactSsv; N],
        moved: &Ssv,
        rel: &RelPose,
        inverse: bool,
        want: Want,
        cutoff: f64,
        slack: f64,
    ) -> [(f64, Vec3); N] {
        // A plain loop: `array::map` with this body is not inlined.
        let mut out = [(0.0, Vec3::zeros()); N];
        for (out, a) in out.iter_mut().zip(a) {
            // Cores within both radii make the bound 0 however close they are: the first pair of
            // points found that near settles it.
            let radii = a.radius + moved.radius;
            let (bound, axis) = Ssv::bound_from(radii, slack, cutoff, |core_cutoff| {
                // In the fixed volume's frame, so that the kernel looks first at the corners of
                // `a` (a child of the node split, the smaller as a rule), whose box in that frame
                // is the tighter, so that it stops sooner.
                Ssv::cores_distance_here(moved, a, radii + slack, core_cutoff, want.exact)
            });
            // From the frame of b's axes into a's model frame (from a to b), then (inverse) into
            // b's, turned to point from b to a. (For every bound: a branch on the cutoff costs
            // more.)
            *out = if want.axes {
                let axis = -(moved.axes * axis);
                (bound, if inverse { -(rel.rot * axis) } else { axis })
            } else {
                (bound, Vec3::zeros())
            };
        }
        out
    }
}

/// What a core with these sides is (see [`Ssv::kind`]).
#[inline(always)]
fn kind_of(lengths: [f64; 2]) -> SsvKind {
    if lengths[1] != 0.0 {
        SsvKind::Rect
    } else if lengths[0] != 0.0 {
        SsvKind::Line
    } else {
        SsvKind::Point
    }
}

/// The scale (see [`Ssv::scale`]) of a core with this corner and these sides.
#[inline(always)]
fn scale_of(origin: &Vec3, lengths: [f64; 2]) -> f64 {
    origin.x.abs() + origin.y.abs() + origin.z.abs() + lengths[0] + lengths[1]
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

impl BoundingVolume for Ssv {
    fn contains(&self, p: &Vec3, eps: f64) -> bool {
        self.core_distance(p) <= self.radius + eps
    }

    fn size(&self) -> f64 {
        (self.lengths[0] * self.lengths[0] + self.lengths[1] * self.lengths[1]).sqrt()
            + 2.0 * self.radius
    }
}

impl Ssv {
    /// Rounding allowance of a bound on `a` and `b` posed by `rel`.
    #[inline(always)]
    fn slack(a: &Ssv, b: &Ssv, rel: &RelPose) -> f64 {
        Ssv::slack_for(a.scale(), b.scale(), rel)
    }

    /// Rounding allowance of a bound on volumes of scales (see `scale`) at most `scale_a` and
    /// `scale_b`, the second posed by `rel` (or the first by its inverse).
    #[inline(always)]
    pub(crate) fn slack_for(scale_a: f64, scale_b: f64, rel: &RelPose) -> f64 {
        let t = rel.trans;
        BOUND_SLACK * (scale_a + scale_b + t.x.abs() + t.y.abs() + t.z.abs()) + UNDERFLOW_SLACK
    }

    /// The centre of the core and the radius of a ball around the whole volume.
    #[inline(always)]
    fn ball(&self) -> (Vec3, f64) {
        let (a, b) = (0.5 * self.lengths[0], 0.5 * self.lengths[1]);
        let c = self.origin + self.axes.column(0) * a + self.axes.column(1) * b;
        (c, (a * a + b * b).sqrt() + self.radius)
    }
}

impl DistanceVolume for Ssv {
    #[inline]
    fn distance(a: &Self, b: &Self, rel: &RelPose) -> f64 {
        Ssv::distance_below(a, b, rel, f64::INFINITY)
    }

    #[inline]
    fn distance_below(a: &Self, b: &Self, rel: &RelPose, cutoff: f64) -> f64 {
        let (ca, cb, slack) = (a.compact(), b.compact(), Ssv::slack(a, b, rel));
        let moved = cb.posed(rel, false);
        Ssv::bounds_against([&ca], &moved, rel, false, Want::EXACT, cutoff, slack)[0].0
    }
}

impl Ssv {
    /// The bound from the core distance that `core(core_cutoff)` computes (exact below
    /// `core_cutoff`, at least it otherwise), for volumes whose radii sum to `radii`, with the
    /// cores' separating axis when the volumes are apart along it (zero otherwise).
    #[inline(always)]
    fn bound_from(
        radii: f64,
        slack: f64,
        cutoff: f64,
        core: impl FnOnce(f64) -> (f64, Vec3),
    ) -> (f64, Vec3) {
        // Err low by the rounding of the composition, so the bound never exceeds the true distance.
        // The core distance that makes the bound reach the cutoff, with a second slack so that a
        // core distance at or above it proves the bound's true value is at least the cutoff.
        let core_cutoff = cutoff + radii + 2.0 * slack;
        let (d, axis) = core(core_cutoff);
        let raw = d - radii - slack;
        // At or above the core cutoff the bound is at least the cutoff (up to rounding): a select
        // of the floor rather than a branch.
        let bound = raw.max(if d >= core_cutoff { cutoff } else { 0.0 });
        // A bound raised to 0 is not a separation: the volumes may overlap along the axis (a
        // product, not a branch: this is taken about half the time, unpredictably).
        (bound, axis * f64::from(u8::from(raw > 0.0)))
    }

    /// The rectangle swept sphere around one triangle, radius 0 up to rounding: the rectangle on its
    /// longest edge whose other side reaches the opposite vertex (whose foot lies on that edge, as
    /// it is the longest). A leaf's volume, computed on use rather than stored.
    #[inline]
    pub fn triangle(t: &[Vec3; 3]) -> Ssv {
        let e = [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
        let n2 = [
            e[0].norm_squared(),
            e[1].norm_squared(),
            e[2].norm_squared(),
        ];
        let i = if n2[0] >= n2[1] && n2[0] >= n2[2] {
            0
        } else if n2[1] >= n2[2] {
            1
        } else {
            2
        };
        let (p, q, r) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
        let len = n2[i].sqrt();
        let x = if len > 0.0 { e[i] / len } else { Vec3::x() };
        let w = r - p;
        // The second axis: the part of `w` across the edge, as `(x x w) x x`. A vector crossed
        // with `x` is orthogonal to `x` up to rounding however inexact it is, so the frame is
        // orthonormal to rounding whatever the triangle's shape (the distance and overlap tests
        // rely on it), with one root and one division after `x`'s (this runs for every leaf a
        // distance search meets: a short chain of latencies counts).
        // A triangle whose height across that edge is below 1e-12 of its length is taken as a
        // segment (the part across is then rounding, which may point anywhere, even along `x`,
        // and would make no frame); the radius then covers the third vertex.
        let up = x.cross(&w).cross(&x);
        let height = up.norm();
        let y = if height > len * 1e-12 && height.is_finite() {
            up / height
        } else {
            axis_across(&x)
        };
        let z = x.cross(&y);
        Ssv {
            axes: Mat3::from_columns(&[x, y, z]),
            origin: p,
            lengths: [len, y.dot(&w).max(0.0)],
            radius: 0.0,
        }
        .cover(&[q, r])
    }
}

/// A unit vector across the unit vector `x` (the second axis of a segment's or a point's volume).
#[cold]
#[inline(never)]
fn axis_across(x: &Vec3) -> Vec3 {
    let k = x.iamin();
    let mut u = Vec3::zeros();
    u[k] = 1.0;
    x.cross(&u).normalize()
}

impl OverlapVolume for Ssv {
    type Posed = Ssv;

    /// The volume itself: the test composes the poses as it goes.
    #[inline]
    fn pose(b: &Self, _rel: &RelPose) -> Ssv {
        *b
    }

    /// Swept sphere volumes may meet exactly when their cores are within both radii (and the
    /// rounding slack of the distance bound): never false when they share a point. Pairs whose
    /// enclosing balls are apart are rejected first, and the core distance stops at the first pair
    /// of points close enough.
    #[inline]
    fn overlap_posed(a: &Self, b: &Self, rel: &RelPose) -> bool {
        let (ca, ra) = a.ball();
        let (cb, rb) = b.ball();
        let slack = Ssv::slack(a, b, rel);
        if (ca - rel.apply(&cb)).norm() > ra + rb + slack {
            return false;
        }
        let reach = a.radius + b.radius + slack;
        // Stop as soon as a pair of points within reach is found, or the distance is seen to be
        // at least the reach (then a value at least the reach comes back: equality errs towards
        // overlap, which costs only work).
        Ssv::cores_distance(a, b, rel, reach, reach) <= reach
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::portable_only;
    use crate::test_rng::Lcg;
    use nalgebra::{Rotation3, Unit};

    /// How far `b` lies beyond `a` along the unit axis `n`: the gap between their projections (a
    /// rectangle's spans its corners', widened by the radius), negative if they overlap or `b`
    /// lies behind.
    fn gap_along(a: &Ssv, b: &Ssv, n: &Vec3) -> f64 {
        let span = |v: &Ssv| {
            let p =
                |x: f64, y: f64| n.dot(&(v.origin + v.axes.column(0) * x + v.axes.column(1) * y));
            let c = [p(0.0, 0.0), p(v.lengths[0], 0.0), p(0.0, v.lengths[1])];
            let c3 = p(v.lengths[0], v.lengths[1]);
            let lo = c.iter().fold(c3, |m, &x| m.min(x));
            let hi = c.iter().fold(c3, |m, &x| m.max(x));
            (lo - v.radius, hi + v.radius)
        };
        let ((_, ahi), (blo, _)) = (span(a), span(b));
        blo - ahi
    }

    /// The axes that come with bounds point from the volume in the frame `rel` maps into towards
    /// the posed one, in that frame, and show the bound, whichever side is posed.
    #[test]
    fn bound_axes_separate_by_the_bound() {
        let mut rng = Lcg(5);
        let mut f = move || rng.signed();
        let (mut given, mut cases) = (0, 0);
        for k in 0..4000 {
            let mut rot = || -> Mat3 {
                let axis = Unit::new_normalize(Vec3::new(f(), f(), f() + 1e-3));
                Rotation3::from_axis_angle(&axis, 3.0 * f()).into_inner()
            };
            let (ra, rb, rr) = (rot(), rot(), rot());
            let mut ssv = |axes: Mat3| Ssv {
                axes,
                origin: Vec3::new(f(), f(), f()),
                lengths: [f().abs(), f().abs()],
                radius: 0.1 * f().abs(),
            };
            let (a, b) = (ssv(ra), ssv(rb));
            let rel = RelPose {
                rot: rr,
                trans: Vec3::new(f(), f(), f()) * 3.0,
            };
            let cutoff = [f64::INFINITY, 0.3, 1.0][k % 3];
            // b posed by rel against a, then a posed by rel's inverse against b.
            let (ca, cb) = (a.compact(), b.compact());
            let slack = Ssv::slack(&a, &b, &rel);
            let (b_moved, a_moved) = (cb.posed(&rel, false), ca.posed(&rel, true));
            let [(bound, axis)] =
                Ssv::bounds_against([&ca], &b_moved, &rel, false, Want::AXES, cutoff, slack);
            let [(bound_inv, axis_inv)] =
                Ssv::bounds_against([&cb], &a_moved, &rel, true, Want::AXES, cutoff, slack);
            for (bound, axis) in [(bound, axis), (bound_inv, axis_inv)] {
                cases += 1;
                if axis == Vec3::zeros() {
                    continue;
                }
                given += 1;
                // In the frame rel maps into (a's), from a towards b posed by rel.
                let gap = gap_along(&a, &b.posed(&rel), &axis.normalize());
                assert!(gap >= bound - 1e-12, "case {k}: gap {gap} < bound {bound}");
            }
        }
        assert!(given > cases / 2, "{given} of {cases}");
    }

    /// The kernel's copy compiled for AVX2 gives the same bits as the portable one (value and
    /// axis), for every kind of core, with and without a cutoff, `enough` or exact answers (where
    /// the processor has no AVX2, both are the portable one).
    #[test]
    fn kernel_copies_agree() {
        let mut rng = Lcg(11);
        let mut f = move || rng.signed();
        for k in 0..20000 {
            let axes = |f: &mut dyn FnMut() -> f64| -> Mat3 {
                let axis = Unit::new_normalize(Vec3::new(f(), f(), f() + 1e-3));
                Rotation3::from_axis_angle(&axis, 3.0 * f()).into_inner()
            };
            let side = |f: &mut dyn FnMut() -> f64, zero: bool| if zero { 0.0 } else { f().abs() };
            let a = Ssv {
                axes: axes(&mut f),
                origin: Vec3::new(f(), f(), f()) * 0.5,
                lengths: [side(&mut f, k % 9 == 0), side(&mut f, k % 5 == 0)],
                radius: 0.05 * f().abs(),
            };
            let b = Ssv {
                axes: axes(&mut f),
                origin: Vec3::new(f(), f(), f()) * [0.2, 1.0, 3.0][k % 3],
                lengths: [side(&mut f, k % 11 == 0), side(&mut f, k % 4 == 0)],
                radius: 0.0,
            }
            .compact();
            let cutoff = [f64::INFINITY, 0.1, 0.5, 1.0][k % 4];
            let enough = [0.0, 0.2][k % 2];
            let exact = k % 3 != 0;
            let kernel = || Ssv::cores_distance_here(&a, &b, enough, cutoff, exact);
            let (x, y) = (portable_only(kernel), kernel());
            assert_eq!(x.0.to_bits(), y.0.to_bits(), "case {k}");
            assert_eq!(x.1.map(f64::to_bits), y.1.map(f64::to_bits), "case {k}");
        }
    }

    /// A triangle's volume has an orthonormal frame and contains the triangle whatever its
    /// shape: a repeated vertex, collinear vertices, a sliver, a point (a repeated vertex once
    /// made both axes the same, and the volume missed the triangle's other points).
    #[test]
    fn triangle_volume_of_degenerate_triangles() {
        let v = |x: f64, y: f64, z: f64| Vec3::new(x, y, z);
        let cases = [
            [v(0.25, 0.75, 0.0), v(0.0, 0.5, 0.0), v(0.0, 0.5, 0.0)],
            [v(0.0, 0.5, 0.0), v(0.25, 0.75, 0.0), v(0.0, 0.5, 0.0)],
            [v(0.1, 0.2, 0.3), v(0.4, 0.5, 0.6), v(0.7, 0.8, 0.9)],
            [v(0.0, 0.0, 0.0), v(1.0, 1e-14, 0.0), v(0.5, 0.0, 1e-15)],
            [v(1.0, 2.0, 3.0), v(1.0, 2.0, 3.0), v(1.0, 2.0, 3.0)],
            [
                v(-3.0, 1e-9, 7.0),
                v(1.0 / 3.0, 1e-9, 7.0),
                v(-3.0, 1e-9, 7.0),
            ],
        ];
        for t in cases {
            let s = Ssv::triangle(&t);
            let gram = s.axes.transpose() * s.axes;
            assert!(
                (gram - Mat3::identity()).abs().max() <= 1e-12,
                "{t:?}: {s:?}"
            );
            // Every point of the triangle (vertices and a grid of barycentric points).
            for i in 0..=4 {
                for j in 0..=4 - i {
                    let (a, b) = (f64::from(i) / 4.0, f64::from(j) / 4.0);
                    let p = t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b;
                    assert!(s.contains(&p, 1e-12), "{t:?}: {p:?} outside {s:?}");
                }
            }
        }
    }
}
