//! Exact orientation predicates on plain `[f64; 3]` points, for the hull builder and the feature
//! tables: thin sign-returning forms of the library's one implementation of exact predicates
//! (`geometry::predicates`: a floating-point filter, then an exact expansion).

use crate::geometry::big_int::BigInt;
use crate::geometry::predicates::{self as exact, Expansion};
use crate::math::Vec3;

/// A point as plain coordinates.
pub(crate) type P3 = [f64; 3];

fn sign(v: f64) -> i32 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// Sign of `(b - a) . ((c - a) x (d - a))`: positive when `d` lies on the side of the plane `abc`
/// that `(b - a) x (c - a)` points to, zero when the four points are coplanar. Exact.
pub(crate) fn orient3d(a: &P3, b: &P3, c: &P3, d: &P3) -> i32 {
    sign(exact::orient3d(
        &Vec3::from(*a),
        &Vec3::from(*b),
        &Vec3::from(*c),
        &Vec3::from(*d),
    ))
}

/// Sign of `(b - a) x (c - a)` in the plane of coordinates `(i, j)`: positive for a
/// counter-clockwise turn `a, b, c`. Exact.
pub(crate) fn orient2d(a: &P3, b: &P3, c: &P3, i: usize, j: usize) -> i32 {
    sign(exact::orient2d([a[i], a[j]], [b[i], b[j]], [c[i], c[j]]))
}

/// Twice the vector area of a polygon, `sum_k p_k x p_(k+1)`, times a power of two (its direction
/// is the normal of a planar polygon, counter-clockwise seen from its tip; callers use only the
/// direction). Computed exactly and rounded at the end, so that it is accurate to a few ulps even
/// for slivers whose float cross products cancel, and never lost to underflow: the polygon is
/// first rescaled by a power of two (exact) so that its largest coordinate is about 1, and when
/// its coordinates still span too many binades for the float expansion (a product or its rounding
/// error would underflow), the sums are taken in exact integers.
pub(crate) fn area_vector(pts: &[P3], cycle: &[u32]) -> [f64; 3] {
    let coords = || cycle.iter().flat_map(|&v| pts[v as usize]);
    let most = coords().fold(0.0f64, |m, x| m.max(x.abs()));
    if most == 0.0 {
        return [0.0; 3];
    }
    let least = coords()
        .filter(|&x| x != 0.0)
        .fold(f64::INFINITY, |m, x| m.min(x.abs()));
    // most * 2^k in [1, 2); the products stay exact with representable errors while every nonzero
    // coordinate is at least 2^-480 after scaling.
    let k = -(most.log2().floor() as i32);
    let (s1, s2) = (2f64.powi(k / 2), 2f64.powi(k - k / 2));
    if least * s1 * s2 < 2f64.powi(-480) {
        return area_vector_integers(pts, cycle);
    }
    let scaled: Vec<P3> = cycle
        .iter()
        .map(|&v| pts[v as usize].map(|x| x * s1 * s2))
        .collect();
    let mut out = [0.0; 3];
    for (c, o) in out.iter_mut().enumerate() {
        let (i, j) = ((c + 1) % 3, (c + 2) % 3);
        let mut x = Expansion::<256>::new();
        for (q, a) in scaled.iter().enumerate() {
            let b = &scaled[(q + 1) % scaled.len()];
            x.add_product(1.0, a[i], b[j]);
            x.add_product(-1.0, a[j], b[i]);
        }
        *o = x.estimate();
    }
    out
}

/// `area_vector` in exact integers (every double is a multiple of 2^-1074), scaled so that the
/// largest component is in [1/2, 1).
#[cold]
#[inline(never)]
fn area_vector_integers(pts: &[P3], cycle: &[u32]) -> [f64; 3] {
    let sums = [0usize, 1, 2].map(|c| {
        let (i, j) = ((c + 1) % 3, (c + 2) % 3);
        let mut s = BigInt::from_f64(0.0);
        for q in 0..cycle.len() {
            let a = pts[cycle[q] as usize].map(BigInt::from_f64);
            let b = pts[cycle[(q + 1) % cycle.len()] as usize].map(BigInt::from_f64);
            s = s.add(&a[i].mul(&b[j])).sub(&a[j].mul(&b[i]));
        }
        s
    });
    let bits = sums.iter().map(BigInt::bit_len).max().unwrap_or(0);
    sums.map(|s| s.to_f64_scaled(-(bits as i32)))
}

/// Whether three points lie on one line (exactly): all three coordinate projections are degenerate.
pub(crate) fn collinear(a: &P3, b: &P3, c: &P3) -> bool {
    orient2d(a, b, c, 0, 1) == 0 && orient2d(a, b, c, 1, 2) == 0 && orient2d(a, b, c, 0, 2) == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orient3d_signs() {
        let o = [0.0, 0.0, 0.0];
        let x = [1.0, 0.0, 0.0];
        let y = [0.0, 1.0, 0.0];
        assert_eq!(orient3d(&o, &x, &y, &[0.0, 0.0, 1.0]), 1);
        assert_eq!(orient3d(&o, &x, &y, &[0.3, 0.2, -1.0]), -1);
        assert_eq!(orient3d(&o, &x, &y, &[0.3, 0.2, 0.0]), 0);
    }

    #[test]
    fn area_vector_survives_underflow() {
        // Products of 2^-600 coordinates underflow; the rescaled expansion does not.
        let t = 2f64.powi(-600);
        let tri = [[0.0, 0.0, 0.0], [t, 0.0, 0.0], [0.0, t, 0.0]];
        let n = area_vector(&tri, &[0, 1, 2]);
        assert!(n[0] == 0.0 && n[1] == 0.0 && n[2] > 0.0);
        // 1 beside 2^-700 in one face: exact integers. Twice the area is (e^2, e, e).
        let e = 2f64.powi(-700);
        let tri = [[1.0, 0.0, 0.0], [0.0, e, 0.0], [0.0, 0.0, e]];
        let n = area_vector(&tri, &[0, 1, 2]);
        assert!(n[1] == n[2] && n[1] >= 0.5 && n[1] < 1.0, "{n:?}");
        assert!(n[0] > 0.0 && n[0] < n[1] * 1e-200, "{n:?}");
        // Reversed, the direction flips.
        let m = area_vector(&tri, &[0, 2, 1]);
        assert_eq!(m, [-n[0], -n[1], -n[2]]);
    }

    #[test]
    fn exact_on_near_degenerate() {
        // Points on the plane x + y + z = 1 built so that float evaluation is unreliable.
        let e = f64::EPSILON;
        let a = [0.1, 0.2, 0.7];
        let b = [0.7, 0.1, 0.2];
        let c = [0.2, 0.7, 0.1];
        for k in -3i32..=3 {
            let d = [1.0 / 3.0 + k as f64 * e, 1.0 / 3.0, 1.0 / 3.0];
            // d - a and the rest are exact here, so the sign is that of an exact rational.
            let fast = orient3d(&a, &b, &c, &d);
            assert_eq!(fast, -orient3d(&b, &a, &c, &d));
        }
        // Exactly coplanar by construction: integer coordinates scaled by a power of two.
        let s = 2f64.powi(-40);
        let p = |x: f64, y: f64| [x * s, y * s, (x + 2.0 * y) * s];
        assert_eq!(
            orient3d(&p(1.0, 2.0), &p(3.0, 7.0), &p(-5.0, 11.0), &p(1e6, -3.0)),
            0
        );
        assert!(collinear(
            &[0.0, 0.0, 0.0],
            &[1.0, 1.0, 1.0],
            &[3.0, 3.0, 3.0]
        ));
        assert!(!collinear(
            &[0.0, 0.0, 0.0],
            &[1.0, 1.0, 1.0],
            &[3.0, 3.0, 3.0 + 4.0 * e]
        ));
    }
}
