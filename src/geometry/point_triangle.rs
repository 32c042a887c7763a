use super::predicates::{cross_accurate, kernel_rescale, max_abs, pow2};
use super::segment_segment::{length, point_on};
use super::{ClosestPoints, Tri};
use crate::math::Vec3;

/// Closest point of triangle `t` to point `p`: `ClosestPoints { p: *p, q: on the triangle, .. }`.
///
/// A triangle with collinear vertices is treated as the segment they span, one with equal vertices
/// as that point. A point equal to a vertex is at distance 0 exactly (the plane's distance,
/// computed from a rounded normal, could leave a few ulps of the triangle's size).
pub fn point_triangle(p: &Vec3, t: &Tri) -> ClosestPoints {
    if t.contains(p) {
        return ClosestPoints {
            distance: 0.0,
            p: *p,
            q: *p,
        };
    }
    if let Some(k) = kernel_rescale(max_abs(&[p, &t[0], &t[1], &t[2]])) {
        let (s, inv) = (pow2(k), pow2(-k));
        let r = point_triangle(&(p * s), &[t[0] * s, t[1] * s, t[2] * s]);
        return ClosestPoints {
            distance: r.distance * inv,
            p: *p,
            q: r.q * inv,
        };
    }
    let e1 = t[1] - t[0];
    let e2 = t[2] - t[0];
    let n = face_normal(&e1, &e2);
    let nn = n.norm_squared();
    if nn > 0.0 {
        let w = p - t[0];
        if let Some(h) = face_projection(&e1, &e2, &n, nn, &w) {
            return ClosestPoints {
                distance: h.abs() / nn.sqrt(),
                p: *p,
                q: p - n * (h / nn),
            };
        }
    }
    // The projection falls outside (or the triangle is degenerate): the closest point is on an edge.
    let mut best = (f64::INFINITY, *p, Vec3::zeros());
    for i in 0..3 {
        let (a, b) = (&t[i], &t[(i + 1) % 3]);
        let c = point_segment(p, a, b);
        if c.0 < best.0 {
            best = c;
        }
    }
    ClosestPoints {
        distance: length(&best.2, best.0),
        p: *p,
        q: best.1,
    }
}

/// Squared distance from `p` to the segment `[a, b]`, the closest point and the gap vector.
#[inline]
fn point_segment(p: &Vec3, a: &Vec3, b: &Vec3) -> (f64, Vec3, Vec3) {
    let d = b - a;
    let w = p - a;
    let dd = d.norm_squared();
    let s = if dd > 0.0 {
        (w.dot(&d) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let gap = w - d * s;
    (gap.norm_squared(), point_on(a, b, &d, s), gap)
}

/// The normal `e1 x e2` of a triangle with edge vectors `e1`, `e2` from one vertex, recomputed
/// with compensated products when the triangle is a sliver (sine of its angle below 1e-3), where
/// the plain cross product would tilt the plane by rounding.
#[inline]
pub(crate) fn face_normal(e1: &Vec3, e2: &Vec3) -> Vec3 {
    let n = e1.cross(e2);
    if n.norm_squared() <= 1e-6 * e1.norm_squared() * e2.norm_squared() {
        cross_accurate(e1, e2)
    } else {
        n
    }
}

/// If the orthogonal projection of `v0 + w` onto the plane of the triangle `(v0, v0 + e1, v0 + e2)`
/// with normal `n` (`nn = |n|^2 > 0`) falls inside the triangle, `Some(n . w)`: the signed
/// distance to the plane times `|n|`.
#[inline]
pub(crate) fn face_projection(e1: &Vec3, e2: &Vec3, n: &Vec3, nn: f64, w: &Vec3) -> Option<f64> {
    FaceFrame::new(e1, e2, n, nn).projection(w)
}

/// What deciding whether a point projects inside a triangle needs, computed once per triangle.
pub(crate) struct FaceFrame {
    n: Vec3,
    nn: f64,
    /// `e2 x n` and `n x e1`: their products with `w` are the barycentric coordinates of the
    /// projection of `v0 + w`, times `|n|^2`.
    m1: Vec3,
    m2: Vec3,
}

impl FaceFrame {
    #[inline]
    pub(crate) fn new(e1: &Vec3, e2: &Vec3, n: &Vec3, nn: f64) -> Self {
        FaceFrame {
            n: *n,
            nn,
            m1: e2.cross(n),
            m2: n.cross(e1),
        }
    }

    /// As [`face_projection`].
    #[inline]
    pub(crate) fn projection(&self, w: &Vec3) -> Option<f64> {
        let l1 = w.dot(&self.m1);
        let l2 = w.dot(&self.m2);
        if l1 >= 0.0 && l2 >= 0.0 && l1 + l2 <= self.nn {
            Some(self.n.dot(w))
        } else {
            None
        }
    }
}
