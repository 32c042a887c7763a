//! Closest points between points and segments, the small kernels V-Clip needs on its features.
//! (Kept here rather than in `geometry/` so that the convex module stands on its own.)

use crate::math::Vec3;

/// The point at parameter `t` of segment `[a, b]`, returning the endpoints themselves (not a
/// rounded interpolation) at `t == 0` and `t == 1`, so that decisions taken on endpoints agree
/// with decisions taken on the vertices they are.
#[inline]
pub(crate) fn point_at(a: &Vec3, b: &Vec3, t: f64) -> Vec3 {
    if t <= 0.0 {
        *a
    } else if t >= 1.0 {
        *b
    } else {
        a + (b - a) * t
    }
}

/// Parameter in `[0, 1]` of the point of segment `[a, b]` closest to `p`.
#[inline]
pub(crate) fn point_segment_param(p: &Vec3, a: &Vec3, b: &Vec3) -> f64 {
    let d = b - a;
    let dd = d.norm_squared();
    if dd <= 0.0 {
        return 0.0;
    }
    ((p - a).dot(&d) / dd).clamp(0.0, 1.0)
}

/// Parameters `(s, t)` of a closest pair between segments `[p0, p1]` and `[q0, q1]`.
///
/// The squared distance is a convex quadratic in `(s, t)` over the unit square. Away from
/// parallel, its unconstrained minimiser in `s` (for the best `t`) is clamped, `t` is then the best
/// for that `s`, clamped, and `s` is re-optimised for the clamped `t`; that lands on the minimum
/// because the function is convex and separable along these one-dimensional slices. Parallel (or
/// nearly) segments take the middle of their overlap, a pair at the common minimal distance.
pub(crate) fn segment_segment_params(p0: &Vec3, p1: &Vec3, q0: &Vec3, q1: &Vec3) -> (f64, f64) {
    // The parameters do not change when the whole picture is scaled; scale by a power of two
    // (exact) so that the longer segment's largest coordinate is about 1. Otherwise `a * e` (the
    // fourth power of the lengths) overflows for segments longer than about 1e77. The offset `r`
    // caps the factor, so that it stays far from overflow itself.
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let len = d1.amax().max(d2.amax());
    if len == 0.0 {
        return (0.0, 0.0);
    }
    // Within these bounds nothing over- or underflows (the products stay within 2^±800) and
    // scaling, exact, would change no bit of the answer: skip it on V-Clip's usual path.
    let (lo, hi) = (2f64.powi(-200), 2f64.powi(200));
    let (d1, d2, r) = if len >= lo && len <= hi && r.amax() <= hi {
        (d1, d2, r)
    } else {
        let k = (-len.log2().floor()).min(500.0 - r.amax().log2().ceil());
        let scale = 2f64.powi((k as i32).clamp(-1000, 1000));
        (d1 * scale, d2 * scale, r * scale)
    };
    let a = d1.norm_squared();
    let e = d2.norm_squared();
    if a <= 0.0 && e <= 0.0 {
        return (0.0, 0.0);
    }
    if a <= 0.0 {
        return (0.0, point_segment_param(p0, q0, q1));
    }
    if e <= 0.0 {
        return (point_segment_param(q0, p0, p1), 0.0);
    }
    let b = d1.dot(&d2);
    let c = d1.dot(&r);
    let f = d2.dot(&r);
    let denom = a * e - b * b;
    let s = if denom > 1e-14 * a * e {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        // Parallel: middle of the overlap of q's projection with [0, 1], or the nearer end.
        let s0 = -c / a;
        let s1 = (b - c) / a;
        let (lo, hi) = (s0.min(s1).max(0.0), s0.max(s1).min(1.0));
        if lo <= hi {
            0.5 * (lo + hi)
        } else if s0.max(s1) < 0.0 {
            0.0
        } else {
            1.0
        }
    };
    let t = (b * s + f) / e;
    if t < 0.0 {
        ((-c / a).clamp(0.0, 1.0), 0.0)
    } else if t > 1.0 {
        (((b - c) / a).clamp(0.0, 1.0), 1.0)
    } else {
        (s, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute(p0: &Vec3, p1: &Vec3, q0: &Vec3, q1: &Vec3) -> f64 {
        let n = 400;
        let mut best = f64::INFINITY;
        for i in 0..=n {
            let p = point_at(p0, p1, i as f64 / n as f64);
            let t = point_segment_param(&p, q0, q1);
            best = best.min((p - point_at(q0, q1, t)).norm());
        }
        best
    }

    #[test]
    fn segment_pairs_against_sampling() {
        let v = |x: f64, y: f64, z: f64| Vec3::new(x, y, z);
        let cases = [
            (v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 1.), v(1., 1., 1.)),
            (v(0., 0., 0.), v(1., 0., 0.), v(2., 1., 0.), v(3., 1., 0.)),
            (
                v(0., 0., 0.),
                v(1., 0., 0.),
                v(0.5, -1., 1.),
                v(0.5, 1., 1.),
            ),
            (
                v(0., 0., 0.),
                v(1., 1., 0.),
                v(2., -3., 0.5),
                v(-1., 0.2, 0.7),
            ),
            (v(0., 0., 0.), v(1., 0., 0.), v(-2., 0., 0.), v(-1., 0., 0.)),
        ];
        for (p0, p1, q0, q1) in cases {
            let (s, t) = segment_segment_params(&p0, &p1, &q0, &q1);
            let d = (point_at(&p0, &p1, s) - point_at(&q0, &q1, t)).norm();
            let b = brute(&p0, &p1, &q0, &q1);
            assert!(d <= b + 1e-12 && d >= b - 1e-2, "{d} vs {b}");
        }
    }

    #[test]
    fn segment_pairs_at_every_scale() {
        // The same crossing picture scaled from 1e-150 to 1e150: (a * e) would overflow past 1e77
        // and underflow below 1e-77 without the rescaling.
        for k in -15..=15 {
            let m = 10f64.powi(10 * k);
            let v = |x: f64, y: f64, z: f64| Vec3::new(x * m, y * m, z * m);
            let (s, t) = segment_segment_params(
                &v(-1.0, 0.0, 0.0),
                &v(3.0, 0.0, 0.0),
                &v(0.0, -3.0, 1.0),
                &v(0.0, 1.0, 1.0),
            );
            assert!(
                (s - 0.25).abs() < 1e-12 && (t - 0.75).abs() < 1e-12,
                "{m}: {s} {t}"
            );
        }
        // A long needle against a short one far away: the offset caps the factor.
        let (s, t) = segment_segment_params(
            &Vec3::new(-1e150, 0.0, 0.0),
            &Vec3::new(1e150, 0.0, 0.0),
            &Vec3::new(0.0, 1e-150, 1e150),
            &Vec3::new(0.0, 2e-150, 1e150),
        );
        assert!(
            (s - 0.5).abs() < 1e-12 && (0.0..=1.0).contains(&t),
            "{s} {t}"
        );
    }
}
