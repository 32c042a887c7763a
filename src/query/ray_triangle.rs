//! The ray/triangle kernel's exact parts: the edge functions about the ray with their signs, the
//! barycentric weights of a hit, whether a triangle has area, its normal, and whether the ray's
//! origin lies exactly on a triangle (see `ray.rs` for the method).

use crate::geometry::Tri;
use crate::geometry::predicates::{
    cross_accurate, exponent, max_abs, orient2d, orient3d, pow2, two_prod,
};
use crate::math::Vec3;

/// Relative error bound of an edge function `l - r` computed from rounded products `l`, `r`:
/// comfortably above its three roundings.
const EDGE_ERR: f64 = 4.0 * f64::EPSILON;

/// Absolute part of the edge functions' error bound: covers products that underflow.
const EDGE_UNDERFLOW: f64 = 1e-300;

/// The edge function of `p`, `q` about the ray (`p x q` in the plane across it), with a bound on
/// its rounding error.
#[inline(always)]
pub(super) fn edge(p: &[f64; 3], q: &[f64; 3]) -> (f64, f64) {
    let (l, r) = (p[0] * q[1], p[1] * q[0]);
    (l - r, EDGE_ERR * (l.abs() + r.abs()) + EDGE_UNDERFLOW)
}

/// The exact sign of an edge function (-1, 0, 1), from its filtered value or exactly.
#[inline]
pub(super) fn edge_sign((v, err): (f64, f64), p: &[f64; 3], q: &[f64; 3]) -> i8 {
    let v = if v.abs() > err {
        v
    } else {
        // (q - p) x (0 - p) = p x q, with an exact sign.
        orient2d([p[0], p[1]], [q[0], q[1]], [0.0, 0.0])
    };
    (v > 0.0) as i8 - (v < 0.0) as i8
}

/// The barycentric weights of the ray's point in the projected triangle `v` (summing to 1), each
/// to a few ulps: the edge functions recomputed on coordinates scaled by a power of two (no under-
/// or overflow) with exact products, their signs `s` being the exact ones.
pub(super) fn weights(v: &[[f64; 3]; 3], s: [i8; 3]) -> [f64; 3] {
    let m = v
        .iter()
        .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let k = pow2((-exponent(m)).clamp(-1022, 1023));
    let p = v.map(|p| [p[0] * k, p[1] * k]);
    let f = |a: [f64; 2], b: [f64; 2], s: i8| {
        let (x, ex) = two_prod(a[0], b[1]);
        let (y, ey) = two_prod(a[1], b[0]);
        let w = (x - y) + (ex - ey);
        // Keep the exact sign (products that underflow can disagree with it).
        if (w > 0.0) as i8 - (w < 0.0) as i8 == s {
            w
        } else {
            0.0
        }
    };
    let mut w = [
        f(p[1], p[2], s[0]),
        f(p[2], p[0], s[1]),
        f(p[0], p[1], s[2]),
    ];
    let mut sum = w[0] + w[1] + w[2];
    if sum == 0.0 {
        // Every weight lost to underflow (coordinates spanning hundreds of orders of magnitude):
        // some point of the triangle.
        w = s.map(|s| f64::from(s.abs()));
        sum = w[0] + w[1] + w[2];
    }
    w.map(|w| w / sum)
}

/// Whether triangle `t` has no area (its vertices are collinear), exactly: its normal's three
/// components, the orientations of its projections on the coordinate planes, are all zero.
pub(super) fn zero_area(t: &Tri) -> bool {
    [(0, 1), (1, 2), (2, 0)]
        .iter()
        .all(|&(i, j)| orient2d([t[0][i], t[0][j]], [t[1][i], t[1][j]], [t[2][i], t[2][j]]) == 0.0)
}

/// `(b - a) x (c - a)` of a triangle with area, to a few ulps, in some positive scale.
pub(super) fn triangle_normal(a: &Vec3, b: &Vec3, c: &Vec3) -> Vec3 {
    let (e1, e2) = (b - a, c - a);
    let k = pow2((-exponent(max_abs(&[&e1, &e2]))).clamp(-1022, 1023));
    let n = cross_accurate(&(e1 * k), &(e2 * k));
    if n != Vec3::zeros() {
        return n;
    }
    // The edges' rounding made them parallel: the exact components' signs, approximate values.
    let o = |i: usize, j: usize| orient2d([a[i], a[j]], [b[i], b[j]], [c[i], c[j]]);
    Vec3::new(o(1, 2), o(2, 0), o(0, 1))
}

/// Whether `o` lies on triangle `t` (its interior, an edge or a vertex), exactly; never for a
/// triangle without area.
///
/// `o` must lie in the triangle's plane (the exact sign of [`orient3d`] is zero). Then the
/// triangle and `o` are projected along a coordinate axis on which the triangle's projection has
/// area: an affine bijection of the plane onto the coordinate plane, which keeps whether `o` is on
/// the closed triangle; there `o` is on it when none of the three orientations it makes with the
/// edges is opposite to the triangle's own (exact [`orient2d`] signs).
#[cold]
#[inline(never)]
pub(super) fn origin_on_triangle(t: [&Vec3; 3], o: &Vec3) -> bool {
    let [a, b, c] = t;
    // The coordinate plane on which the projected triangle is largest (any with area is exact).
    let mut plane = None;
    let mut largest = 0.0f64;
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let area = orient2d([a[i], a[j]], [b[i], b[j]], [c[i], c[j]]);
        if area.abs() > largest {
            largest = area.abs();
            plane = Some((i, j, area));
        }
    }
    let Some((i, j, area)) = plane else {
        return false;
    };
    if orient3d(a, b, c, o) != 0.0 {
        return false;
    }
    let p = |v: &Vec3| [v[i], v[j]];
    let q = p(o);
    [(a, b), (b, c), (c, a)]
        .iter()
        .all(|(u, v)| orient2d(p(u), p(v), q) * area.signum() >= 0.0)
}
