//! Exact orientation predicates on `f64` points: a floating-point filter, and when it cannot decide,
//! an exact evaluation with floating-point expansions (sums of non-overlapping doubles whose exact
//! sum is the value; Dekker's and Knuth's error-free transformations).
//!
//! The exact path expands the determinant into signed products of input coordinates (no rounded
//! differences), so it is exact as long as no product underflows: callers scale their points by a
//! power of two so that the largest coordinate is about 1 (scaling by 2^k is exact), which leaves
//! exactness intact unless coordinates are below ~1e-100 times the largest one and non-zero.

/// A point as plain coordinates.
pub(crate) type P3 = [f64; 3];

/// `a + b` as `(s, e)` with `s + e == a + b` exactly (Knuth's two-sum).
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// `a * b` as `(p, e)` with `p + e == a * b` exactly (the fused multiply-add rounds once).
#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// An expansion on the stack: components of increasing magnitude, non-overlapping.
struct Expansion {
    c: [f64; 128],
    len: usize,
}

impl Expansion {
    fn new() -> Expansion {
        Expansion {
            c: [0.0; 128],
            len: 0,
        }
    }

    /// Adds one double exactly (grow-expansion with zero elimination).
    fn add(&mut self, mut q: f64) {
        if q == 0.0 {
            return;
        }
        let mut out = 0;
        for i in 0..self.len {
            let (s, e) = two_sum(q, self.c[i]);
            q = s;
            if e != 0.0 {
                self.c[out] = e;
                out += 1;
            }
        }
        // Cannot overflow: at most one component per power-of-two range of f64 survives
        // non-overlapping, far fewer than 128 for our short sums; guard anyway by folding.
        if out == self.c.len() {
            out -= 1;
            let (s, _) = two_sum(self.c[out], q);
            q = s;
        }
        self.c[out] = q;
        self.len = out + 1;
    }

    /// Adds `sign * x * y * z` exactly.
    fn add_triple(&mut self, sign: f64, x: f64, y: f64, z: f64) {
        let (p, e) = two_prod(x, y);
        let (p1, e1) = two_prod(p, z);
        let (p2, e2) = two_prod(e, z);
        self.add(sign * e2);
        self.add(sign * e1);
        self.add(sign * p2);
        self.add(sign * p1);
    }

    /// Adds `sign * x * y` exactly.
    fn add_pair(&mut self, sign: f64, x: f64, y: f64) {
        let (p, e) = two_prod(x, y);
        self.add(sign * e);
        self.add(sign * p);
    }

    /// The sum rounded (to within a couple of ulps): the components added from the smallest.
    fn estimate(&self) -> f64 {
        self.c[..self.len].iter().sum()
    }

    /// The sign of the exact sum: that of its largest (last non-zero) component.
    fn sign(&self) -> i32 {
        for i in (0..self.len).rev() {
            if self.c[i] > 0.0 {
                return 1;
            }
            if self.c[i] < 0.0 {
                return -1;
            }
        }
        0
    }
}

/// Adds `sign * det[p; q; r]` (rows) exactly.
fn add_det3(x: &mut Expansion, sign: f64, p: &P3, q: &P3, r: &P3) {
    x.add_triple(sign, p[0], q[1], r[2]);
    x.add_triple(-sign, p[0], q[2], r[1]);
    x.add_triple(sign, p[1], q[2], r[0]);
    x.add_triple(-sign, p[1], q[0], r[2]);
    x.add_triple(sign, p[2], q[0], r[1]);
    x.add_triple(-sign, p[2], q[1], r[0]);
}

/// Sign of `(b - a) . ((c - a) x (d - a))`: positive when `d` lies on the side of the plane `abc`
/// that `(b - a) x (c - a)` points to, zero when the four points are coplanar. Exact.
pub(crate) fn orient3d(a: &P3, b: &P3, c: &P3, d: &P3) -> i32 {
    let (bx, by, bz) = (b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    let (cx, cy, cz) = (c[0] - a[0], c[1] - a[1], c[2] - a[2]);
    let (dx, dy, dz) = (d[0] - a[0], d[1] - a[1], d[2] - a[2]);
    let (m1, m2) = (cy * dz, cz * dy);
    let (m3, m4) = (cz * dx, cx * dz);
    let (m5, m6) = (cx * dy, cy * dx);
    let det = bx * (m1 - m2) + by * (m3 - m4) + bz * (m5 - m6);
    let permanent = bx.abs() * (m1.abs() + m2.abs())
        + by.abs() * (m3.abs() + m4.abs())
        + bz.abs() * (m5.abs() + m6.abs());
    // About 8 machine epsilons of the permanent bound the rounding of the expression above; the
    // margin is generous since the exact path only costs time. Tiny permanents may hide underflow.
    let bound = 1e-14 * permanent;
    if permanent > 1e-280 && det.is_finite() {
        if det > bound {
            return 1;
        }
        if det < -bound {
            return -1;
        }
    }
    orient3d_exact(a, b, c, d)
}

/// det[b-a; c-a; d-a] = det[b;c;d] - det[b;c;a] - det[b;a;d] - det[a;c;d] (multilinearity; terms
/// with `a` twice vanish), each 3x3 determinant a sum of six products of input coordinates.
fn orient3d_exact(a: &P3, b: &P3, c: &P3, d: &P3) -> i32 {
    let mut x = Expansion::new();
    add_det3(&mut x, 1.0, b, c, d);
    add_det3(&mut x, -1.0, b, c, a);
    add_det3(&mut x, -1.0, b, a, d);
    add_det3(&mut x, -1.0, a, c, d);
    x.sign()
}

/// Sign of `(b - a) x (c - a)` in the plane of coordinates `(i, j)`: positive for a
/// counter-clockwise turn `a, b, c`. Exact.
pub(crate) fn orient2d(a: &P3, b: &P3, c: &P3, i: usize, j: usize) -> i32 {
    let (bx, by) = (b[i] - a[i], b[j] - a[j]);
    let (cx, cy) = (c[i] - a[i], c[j] - a[j]);
    let (l, r) = (bx * cy, by * cx);
    let det = l - r;
    let bound = 1e-15 * (l.abs() + r.abs());
    if l.abs() + r.abs() > 1e-290 && det.is_finite() {
        if det > bound {
            return 1;
        }
        if det < -bound {
            return -1;
        }
    }
    // D(b-a, c-a) = D(b,c) - D(b,a) - D(a,c) with D(p,q) = p_i q_j - p_j q_i.
    let mut x = Expansion::new();
    x.add_pair(1.0, b[i], c[j]);
    x.add_pair(-1.0, b[j], c[i]);
    x.add_pair(-1.0, b[i], a[j]);
    x.add_pair(1.0, b[j], a[i]);
    x.add_pair(-1.0, a[i], c[j]);
    x.add_pair(1.0, a[j], c[i]);
    x.sign()
}

/// Twice the vector area of a polygon, `sum_k p_k x p_(k+1)` (its direction is the normal of a
/// planar polygon, counter-clockwise seen from its tip), computed exactly and rounded at the end,
/// so that it is accurate to a few ulps even for slivers whose float cross products cancel.
pub(crate) fn area_vector(pts: &[P3], cycle: &[u32]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (c, o) in out.iter_mut().enumerate() {
        let (i, j) = ((c + 1) % 3, (c + 2) % 3);
        let mut x = Expansion::new();
        for k in 0..cycle.len() {
            let a = &pts[cycle[k] as usize];
            let b = &pts[cycle[(k + 1) % cycle.len()] as usize];
            x.add_pair(1.0, a[i], b[j]);
            x.add_pair(-1.0, a[j], b[i]);
        }
        *o = x.estimate();
    }
    out
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
    fn exact_on_near_degenerate() {
        // Points on the plane x + y + z = 1 built so that float evaluation is unreliable.
        let e = f64::EPSILON;
        let a = [0.1, 0.2, 0.7];
        let b = [0.7, 0.1, 0.2];
        let c = [0.2, 0.7, 0.1];
        for k in -3i32..=3 {
            let d = [1.0 / 3.0 + k as f64 * e, 1.0 / 3.0, 1.0 / 3.0];
            let fast = orient3d(&a, &b, &c, &d);
            let exact = orient3d_exact(&a, &b, &c, &d);
            assert_eq!(fast, exact);
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
