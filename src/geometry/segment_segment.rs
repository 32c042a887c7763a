use super::ClosestPoints;
use super::predicates::{cross_accurate, kernel_rescale, max_abs, pow2};
use crate::math::Vec3;

/// Closest points between segments `[p0, p1]` and `[q0, q1]` (either may have zero length).
///
/// Parallel and collinear segments get one of their closest pairs. The distance is correct to a
/// few roundings of the segments' size, also for nearly parallel segments.
pub fn segment_segment(p0: &Vec3, p1: &Vec3, q0: &Vec3, q1: &Vec3) -> ClosestPoints {
    if let Some(k) = kernel_rescale(max_abs(&[p0, p1, q0, q1])) {
        // Huge or tiny coordinates: work at unit scale (exactly, by a power of two).
        let (s, inv) = (pow2(k), pow2(-k));
        let r = segment_segment(&(p0 * s), &(p1 * s), &(q0 * s), &(q1 * s));
        return ClosestPoints {
            distance: r.distance * inv,
            p: r.p * inv,
            q: r.q * inv,
        };
    }
    let (d1, d2) = (p1 - p0, q1 - q0);
    let (a, e) = (d1.norm_squared(), d2.norm_squared());
    let c = seg_seg(p0, &d1, a, recip(a), q0, &d2, e, recip(e));
    ClosestPoints {
        distance: length(&c.gap, c.dist2),
        p: point_on(p0, p1, &d1, c.s),
        q: point_on(q0, q1, &d2, c.t),
    }
}

/// Closest points between the segments `p + s a` and `q + t b`, `s, t` in `[0, 1]`: each segment
/// given by a start point and a direction vector (PQP 1.3's `SegPoints` takes them so). As
/// [`segment_segment`], on the segments exactly as given: the far endpoints `p + a` and `q + b`,
/// which would round, are never formed (except as the closest point when it is the far end).
pub fn segment_segment_dir(p: &Vec3, a: &Vec3, q: &Vec3, b: &Vec3) -> ClosestPoints {
    if let Some(k) = kernel_rescale(max_abs(&[p, a, q, b])) {
        // Huge or tiny coordinates: work at unit scale (exactly, by a power of two).
        let (s, inv) = (pow2(k), pow2(-k));
        let r = segment_segment_dir(&(p * s), &(a * s), &(q * s), &(b * s));
        return ClosestPoints {
            distance: r.distance * inv,
            p: r.p * inv,
            q: r.q * inv,
        };
    }
    let (aa, bb) = (a.norm_squared(), b.norm_squared());
    let c = seg_seg(p, a, aa, recip(aa), q, b, bb, recip(bb));
    ClosestPoints {
        distance: length(&c.gap, c.dist2),
        p: if c.s == 0.0 { *p } else { p + a * c.s },
        q: if c.t == 0.0 { *q } else { q + b * c.t },
    }
}

/// `p0 + s (p1 - p0)`, exactly an endpoint when `s` is 0 or 1.
#[inline]
pub(crate) fn point_on(p0: &Vec3, p1: &Vec3, d: &Vec3, s: f64) -> Vec3 {
    if s == 0.0 {
        *p0
    } else if s == 1.0 {
        *p1
    } else {
        p0 + d * s
    }
}

/// Result of [`seg_seg`]: squared distance, the parameters of the closest points and the gap
/// vector between them (first minus second).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SegSeg {
    pub dist2: f64,
    pub s: f64,
    pub t: f64,
    pub gap: Vec3,
}

/// Clamps to `[0, 1]` with plain comparisons, which compile to branch-free min/max (a NaN, which
/// only non-finite input could produce, maps to 0).
#[inline]
fn clamp01(x: f64) -> f64 {
    let x = if x > 0.0 { x } else { 0.0 };
    if x < 1.0 { x } else { 1.0 }
}

/// Closest points of `p0 + s d1` and `q0 + t d2`, `s, t` in `[0, 1]`, given `a = |d1|^2`,
/// `e = |d2|^2` and their reciprocals (0 for a zero length).
///
/// The squared distance is a convex quadratic over the unit square. Take `s` as its unconstrained
/// minimiser clamped to `[0, 1]`, then `t` optimal for that `s` (clamped), then `s` optimal for
/// that `t` (clamped): this reaches the minimum in every case. If the unconstrained minimiser is
/// inside, the last step changes nothing; if the first `t` needed clamping, the minimum lies on
/// that side of the square. For parallel segments any starting `s` works, as every `s` minimises
/// over the line. Written without branches on the data: the clamps are min/max.
///
/// The unconstrained `s` is `(b f - c e) / (a e - b^2)`, whose rounding error grows as 1/sin^2 of
/// the angle between the segments; it moves the answer along the segments, which matters to the
/// distance only in proportion to the sine. Below sin = 1/4 the same `s` is recomputed from the
/// cross product `n = d1 x d2`, formed accurately, as `n . (d2 x r) / |n|^2`: its error then stays
/// a few roundings of the segments' size.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn seg_seg(
    p0: &Vec3,
    d1: &Vec3,
    a: f64,
    inv_a: f64,
    q0: &Vec3,
    d2: &Vec3,
    e: f64,
    inv_e: f64,
) -> SegSeg {
    let r = p0 - q0;
    let f = d2.dot(&r);
    let c = d1.dot(&r);
    let b = d1.dot(d2);
    let ae = a * e;
    let denom = ae - b * b;
    let s = if denom > 0.0625 * ae {
        clamp01((b * f - c * e) / denom)
    } else if ae == 0.0 {
        0.0
    } else {
        let n = cross_accurate(d1, d2);
        let nn = n.norm_squared();
        if nn > 0.0 {
            clamp01(n.dot(&d2.cross(&r)) / nn)
        } else {
            0.0
        }
    };
    let t = clamp01((b * s + f) * inv_e);
    let s = clamp01((b * t - c) * inv_a);
    // The gap vector from r, not from the two points: r is exact for nearby segments far from the
    // origin, so the distance keeps its accuracy there.
    let gap = r + d1 * s - d2 * t;
    SegSeg {
        dist2: gap.norm_squared(),
        s,
        t,
        gap,
    }
}

/// `1 / x`, or 0 for `x == 0`.
#[inline]
pub(crate) fn recip(x: f64) -> f64 {
    if x > 0.0 { 1.0 / x } else { 0.0 }
}

/// `|v|`, also where `|v|^2` would underflow (below about 1e-154): a separation that small is
/// still reported as nonzero, as the exact contact test sees it.
#[inline]
pub(crate) fn length(v: &Vec3, squared: f64) -> f64 {
    if squared >= 1e-290 {
        return squared.sqrt();
    }
    let m = v.amax();
    if m == 0.0 {
        return 0.0;
    }
    m * (v / m).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_at_a_tiny_angle_is_zero_to_rounding() {
        // Both segments pass through (0.5, 0.25, 0.125) exactly; the angle between them is ~1e-9.
        let x = Vec3::new(0.5, 0.25, 0.125);
        let u = Vec3::new(1.0, 0.5, 0.25);
        let v = Vec3::new(1.0, 0.5, 0.25 + 2f64.powi(-30));
        let r = segment_segment(
            &(x - u * 0.375),
            &(x + u * 0.625),
            &(x - v * 0.5),
            &(x + v * 0.5),
        );
        assert!(r.distance < 1e-15, "{}", r.distance);
    }

    #[test]
    fn start_and_direction_agree_with_endpoints() {
        // Integer coordinates: the far endpoints p0 + d are exact, so both forms see the same
        // segments and must give the same distance (to a rounding).
        let mut rng = crate::test_rng::Lcg(7);
        let mut int = || (rng.signed() * 8.0).round();
        for _ in 0..2000 {
            let mut v = || Vec3::new(int(), int(), int());
            let (p, a, q, b) = (v(), v(), v(), v());
            let e = segment_segment(&p, &(p + a), &q, &(q + b));
            let d = segment_segment_dir(&p, &a, &q, &b);
            assert!((d.distance - e.distance).abs() <= 1e-14 * (1.0 + e.distance));
            assert!(((d.p - d.q).norm() - d.distance).abs() <= 1e-13);
        }
    }

    #[test]
    fn parallel_and_degenerate() {
        let z = Vec3::zeros();
        let ex = Vec3::new(1.0, 0.0, 0.0);
        let up = Vec3::new(0.0, 0.0, 2.0);
        // Parallel overlapping: distance 2, points anywhere over the overlap.
        let r = segment_segment(&z, &(ex * 3.0), &(up + ex), &(up + ex * 5.0));
        assert_eq!(r.distance, 2.0);
        assert!((r.p - r.q).norm() == 2.0 && r.p.x >= 1.0 && r.p.x <= 3.0);
        // Collinear disjoint.
        let r = segment_segment(&z, &ex, &(ex * 3.0), &(ex * 2.0));
        assert_eq!((r.distance, r.p, r.q), (1.0, ex, ex * 2.0));
        // Point to segment, point to point.
        let r = segment_segment(&up, &up, &z, &(ex * 4.0));
        assert_eq!((r.distance, r.q), (2.0, z));
        let r = segment_segment(&up, &up, &ex, &ex);
        assert_eq!(r.distance, 5f64.sqrt());
    }
}
