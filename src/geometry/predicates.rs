//! Orientation predicates with exact signs, and the error-free transformations behind them.
//!
//! `orient3d` and `orient2d` first evaluate the determinant in floating point together with a
//! bound on its rounding error; only when the value does not clear the bound is it recomputed
//! exactly, as a sum of exactly represented products accumulated into a non-overlapping expansion
//! (the idea of Priest and Shewchuk's adaptive predicates). The returned `f64` always has the exact
//! sign of the determinant and approximates its value, so callers may also use it as a magnitude.
//!
//! The expansions are exact as long as no intermediate product underflows: the exact path rescales
//! its input by a power of two so that the largest coordinate is near 2^100, which is enough unless
//! the nonzero coordinates span more than 2^330 in magnitude (1e6 and 1e128 together, say). Such
//! input is evaluated with exact integers instead (`big_int.rs`): slower, and as rare as it sounds.

use super::big_int::BigInt;
use crate::math::Vec3;

/// Unit roundoff multiple used by the filters: comfortably above the worst accumulated relative
/// error of the float evaluation of a 3x3 determinant (8 roundings per term, 8.9e-16).
const ERR3: f64 = 1.0e-15;
/// Same for the 2x2 determinant of `orient2d` (3 roundings per term, 3.3e-16).
const ERR2: f64 = 4.0e-16;
/// Absolute slack covering products that underflow (each loses at most 2^-1075) and the errors they
/// carry into later products: far above what underflow can cost, far below any value met in
/// ordinary input. Both filters stay rigorous for any finite input; a value within the bound (or a
/// NaN or infinite evaluation after overflow) goes to the exact path.
const UNDERFLOW: f64 = 9.332636185032189e-302; // 2^-1000

/// `a + b` as a rounded sum and its exact error (Knuth's TwoSum).
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// `a * b` as a rounded product and its exact error.
#[inline]
pub(crate) fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    #[cfg(target_feature = "fma")]
    {
        (p, a.mul_add(b, -p))
    }
    #[cfg(not(target_feature = "fma"))]
    {
        // Dekker's product: without a hardware FMA, `mul_add` would be a library call.
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    }
}

/// Veltkamp's split of `a` into two halves of 26 significant bits each.
#[cfg(not(target_feature = "fma"))]
#[inline]
fn split(a: f64) -> (f64, f64) {
    const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
    let c = SPLITTER * a;
    let h = c - (c - a);
    (h, a - h)
}

/// `a*b - c*d` to within a few ulps of the result even under cancellation.
#[inline]
fn diff_of_products(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let (p, ep) = two_prod(a, b);
    let (q, eq) = two_prod(c, d);
    (p - q) + (ep - eq)
}

/// Cross product accurate to a few ulps per component, for nearly parallel operands whose plain
/// float cross product is dominated by cancellation.
pub(crate) fn cross_accurate(u: &Vec3, v: &Vec3) -> Vec3 {
    Vec3::new(
        diff_of_products(u.y, v.z, u.z, v.y),
        diff_of_products(u.z, v.x, u.x, v.z),
        diff_of_products(u.x, v.y, u.y, v.x),
    )
}

/// `2^k` for `-1022 <= k <= 1023`.
#[inline]
pub(crate) fn pow2(k: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&k));
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// The binary exponent of a positive normal `m` (so that `2^e <= m < 2^(e+1)`); -1023 for
/// subnormals.
#[inline]
pub(crate) fn exponent(m: f64) -> i32 {
    ((m.to_bits() >> 52) & 0x7ff) as i32 - 1023
}

/// `x * 2^k` for any `k`, keeping the sign of a nonzero `x` even where the value would over- or
/// underflow (it saturates at the largest finite or the smallest normal magnitude).
fn scale_keep_sign(x: f64, mut k: i32) -> f64 {
    if x == 0.0 || k == 0 {
        return x;
    }
    let mut y = x;
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        y *= pow2(step);
        k -= step;
    }
    if y == 0.0 {
        f64::MIN_POSITIVE.copysign(x)
    } else if y.is_infinite() {
        f64::MAX.copysign(x)
    } else {
        y
    }
}

/// The range of coordinate magnitudes the floating-point distance kernels take as they are:
/// 2^200 and 2^-200 (see [`kernel_rescale`]).
pub(crate) const RESCALE_HI: f64 = 1.606_938_044_258_990_3e60;
pub(crate) const RESCALE_LO: f64 = 6.223_015_277_861_142e-61;

/// For the floating-point distance kernels, whose intermediate values reach the fourth power of
/// the coordinates: when the largest magnitude `m` is outside `[2^-200, 2^200]`, the exponent `k`
/// such that `m * 2^k` is near 1 (scaling by a power of two is exact and is undone on the result).
#[inline]
pub(crate) fn kernel_rescale(m: f64) -> Option<i32> {
    if m > RESCALE_HI && m.is_finite() || m < RESCALE_LO && m > 0.0 {
        Some((-exponent(m)).clamp(-1000, 1000))
    } else {
        None
    }
}

/// Largest coordinate magnitude of some points.
#[inline]
pub(crate) fn max_abs(points: &[&Vec3]) -> f64 {
    // Plain comparisons (one instruction each), not `f64::max` with its NaN rules: a NaN
    // coordinate is refused when models are built.
    let mut m = 0.0f64;
    for p in points {
        for v in [p.x.abs(), p.y.abs(), p.z.abs()] {
            m = if v > m { v } else { m };
        }
    }
    m
}

/// A sum of floats held exactly as a non-overlapping expansion, smallest component first.
pub(crate) struct Expansion<const N: usize> {
    c: [f64; N],
    len: usize,
}

impl<const N: usize> Expansion<N> {
    pub(crate) fn new() -> Self {
        Expansion {
            c: [0.0; N],
            len: 0,
        }
    }

    /// Adds `x` exactly (Shewchuk's Grow-Expansion with zero elimination). The length grows by at
    /// most one per call, so `N` terms always fit.
    pub(crate) fn add(&mut self, x: f64) {
        if x == 0.0 {
            return;
        }
        let mut q = x;
        let mut k = 0;
        for i in 0..self.len {
            let (s, e) = two_sum(q, self.c[i]);
            if e != 0.0 {
                self.c[k] = e;
                k += 1;
            }
            q = s;
        }
        if q != 0.0 && k < N {
            self.c[k] = q;
            k += 1;
        }
        self.len = k;
    }

    /// Adds `sign * x * y` exactly.
    pub(crate) fn add_product(&mut self, sign: f64, x: f64, y: f64) {
        let (p, e) = two_prod(x, y);
        self.add(sign * p);
        self.add(sign * e);
    }

    /// Adds `sign * x * y * z` exactly.
    pub(crate) fn add_triple(&mut self, sign: f64, x: f64, y: f64, z: f64) {
        let (p, e) = two_prod(x, y);
        let (p1, e1) = two_prod(p, z);
        let (p2, e2) = two_prod(e, z);
        self.add(sign * e2);
        self.add(sign * e1);
        self.add(sign * p2);
        self.add(sign * p1);
    }

    /// The largest component: it has the sign of the sum and is within an ulp or so of it.
    pub(crate) fn leading(&self) -> f64 {
        if self.len == 0 {
            0.0
        } else {
            self.c[self.len - 1]
        }
    }

    /// The sum rounded (within a couple of ulps): the components added from the smallest.
    pub(crate) fn estimate(&self) -> f64 {
        self.c[..self.len].iter().sum()
    }
}

/// How the exact predicates evaluate their input (see the module docs).
enum Exact {
    /// Every value is 0 (or one is not finite).
    Zero,
    /// With expansions, after scaling by 2^k, which brings the largest magnitude near 2^100.
    Scaled(i32),
    /// With exact integers: the nonzero magnitudes span more than 2^330, so that products of
    /// three could underflow after any scaling.
    Integers,
}

/// How to evaluate exactly a determinant of degree at most 3 in `vals`. With the largest magnitude
/// at 2^100 and the least nonzero one at least 2^(100 - 330 - 52) (a subnormal's exponent reads
/// up to 52 too high), each value is a multiple of 2^-334 and every partial product of three a
/// multiple of 2^-1002, which no expansion rounds.
fn exact_method(vals: &[f64]) -> Exact {
    let (mut hi, mut lo) = (0.0f64, f64::INFINITY);
    for v in vals {
        let a = v.abs();
        hi = hi.max(a);
        if a != 0.0 {
            lo = lo.min(a);
        }
    }
    if hi == 0.0 || !hi.is_finite() {
        Exact::Zero
    } else if exponent(hi) - exponent(lo) > 330 {
        Exact::Integers
    } else {
        Exact::Scaled((100 - exponent(hi)).clamp(-1000, 1000))
    }
}

/// Orientation of `d` relative to the plane through `a`, `b`, `c`: the determinant
/// `((b - a) x (c - a)) . (d - a)`, positive when `d` lies on the side the normal of the
/// counter-clockwise triangle `a b c` points to. The sign is exact.
#[inline]
pub(crate) fn orient3d(a: &Vec3, b: &Vec3, c: &Vec3, d: &Vec3) -> f64 {
    let plane = PlaneFilter::new(a, b, c);
    let (v, certain) = plane.eval(d);
    if certain {
        v
    } else {
        orient3d_exact(a, b, c, d)
    }
}

/// The plane of a triangle prepared for many `orient3d` evaluations against it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlaneFilter {
    base: Vec3,
    /// `(b - a) x (c - a)` in floating point.
    pub n: Vec3,
    /// The same cross product with every product taken in absolute value (the permanent), which
    /// bounds the rounding error.
    nabs: Vec3,
}

impl PlaneFilter {
    #[inline]
    pub(crate) fn new(a: &Vec3, b: &Vec3, c: &Vec3) -> Self {
        let u = b - a;
        let v = c - a;
        PlaneFilter {
            base: *a,
            n: Vec3::new(
                u.y * v.z - u.z * v.y,
                u.z * v.x - u.x * v.z,
                u.x * v.y - u.y * v.x,
            ),
            // The UNDERFLOW added to each component makes `ERR3 * perm` cover, for any `d`, the
            // absolute error of products that underflow: 2^-1074 |d_k| for each component that
            // can underflow (whose permanent is then below 2^-1021, so the addition counts).
            nabs: Vec3::new(
                (u.y * v.z).abs() + (u.z * v.y).abs() + UNDERFLOW,
                (u.z * v.x).abs() + (u.x * v.z).abs() + UNDERFLOW,
                (u.x * v.y).abs() + (u.y * v.x).abs() + UNDERFLOW,
            ),
        }
    }

    /// The plane through `base` with normal `n`, taken as given (exact): the sign of
    /// `n . (d - base)` for a point `d`, certified by [`eval`](Self::eval) as for a plane through
    /// three points (whose bound also covers the rounding of their cross product, here none).
    #[inline]
    pub(crate) fn with_normal(base: &Vec3, n: Vec3) -> Self {
        PlaneFilter {
            base: *base,
            n,
            // The UNDERFLOW added to each component plays the same part as in `new`.
            nabs: n.abs().add_scalar(UNDERFLOW),
        }
    }

    /// The float value of `orient3d(a, b, c, d)`, without its error bound.
    #[inline]
    pub(crate) fn value(&self, d: &Vec3) -> f64 {
        let w = d - self.base;
        self.n.x * w.x + self.n.y * w.y + self.n.z * w.z
    }

    /// The float value of `orient3d(a, b, c, d)` and whether its sign is certain. A NaN or
    /// infinite evaluation (overflow) is never certain.
    #[inline]
    pub(crate) fn eval(&self, d: &Vec3) -> (f64, bool) {
        let (v, err) = self.eval_with_error(d);
        (v, v.abs() > err)
    }

    /// The float value of `orient3d(a, b, c, d)` and a bound on its error (a NaN or infinite
    /// value: the bound is not finite, or the comparison with it fails).
    #[inline]
    pub(crate) fn eval_with_error(&self, d: &Vec3) -> (f64, f64) {
        let w = d - self.base;
        let v = self.n.x * w.x + self.n.y * w.y + self.n.z * w.z;
        let perm = self.nabs.x * w.x.abs() + self.nabs.y * w.y.abs() + self.nabs.z * w.z.abs();
        // The constant covers the final products' own underflow (3 x 2^-1075).
        (v, ERR3 * perm + UNDERFLOW)
    }

    /// A bound on how far the exact `(b - a) x (c - a)` lies from its float value `n` (each
    /// component is within a few roundings of its permanent).
    #[inline]
    pub(crate) fn normal_error_bound(&self) -> f64 {
        8.0 * f64::EPSILON * (self.nabs.x + self.nabs.y + self.nabs.z)
    }
}

/// `orient3d` computed exactly (its value rounded, its sign exact).
pub(crate) fn orient3d_exact(a: &Vec3, b: &Vec3, c: &Vec3, d: &Vec3) -> f64 {
    let k = match exact_method(&[a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z]) {
        Exact::Zero => return 0.0,
        Exact::Integers => return orient3d_integers(a, b, c, d),
        Exact::Scaled(k) => k,
    };
    let s = pow2(k);
    let (a, b, c, d) = (a * s, b * s, c * s, d * s);
    let (u, v, w) = (b - a, c - a, d - a);
    // Differences of nearby coordinates are usually exact (Sterbenz); then the 3x3 determinant of
    // the differences is the cheap exact form.
    let exact = |x: f64, y: f64| two_sum(x, -y).1 == 0.0;
    let diffs_exact = exact(b.x, a.x)
        && exact(b.y, a.y)
        && exact(b.z, a.z)
        && exact(c.x, a.x)
        && exact(c.y, a.y)
        && exact(c.z, a.z)
        && exact(d.x, a.x)
        && exact(d.y, a.y)
        && exact(d.z, a.z);
    let value = if diffs_exact {
        let mut e = Expansion::<24>::new();
        det3_terms(&mut e, 1.0, &u, &v, &w);
        e.leading()
    } else {
        // det[b-a; c-a; d-a] = M_a - M_b + M_c - M_d, where M_x is the 3x3 determinant of the
        // three points other than x (expansion of the 4x4 determinant with a column of ones).
        let mut e = Expansion::<96>::new();
        det3_terms(&mut e, 1.0, &b, &c, &d);
        det3_terms(&mut e, -1.0, &a, &c, &d);
        det3_terms(&mut e, 1.0, &a, &b, &d);
        det3_terms(&mut e, -1.0, &a, &b, &c);
        e.leading()
    };
    scale_keep_sign(value, -3 * k)
}

/// `orient3d` with exact integers (every double is an integer multiple of 2^-1074).
#[cold]
#[inline(never)]
fn orient3d_integers(a: &Vec3, b: &Vec3, c: &Vec3, d: &Vec3) -> f64 {
    let big = |p: &Vec3| [p.x, p.y, p.z].map(BigInt::from_f64);
    let [a, b, c, d] = [a, b, c, d].map(big);
    let diff = |p: &[BigInt; 3]| [0, 1, 2].map(|i| p[i].sub(&a[i]));
    let (u, v, w) = (diff(&b), diff(&c), diff(&d));
    let minor = |i: usize, j: usize| v[i].mul(&w[j]).sub(&v[j].mul(&w[i]));
    let det = u[0]
        .mul(&minor(1, 2))
        .sub(&u[1].mul(&minor(0, 2)))
        .add(&u[2].mul(&minor(0, 1)));
    det.to_f64_scaled(3 * super::big_int::LSB)
}

/// Adds `sign * det[u; v; w]` to `e` as 6 exact triple products.
fn det3_terms<const N: usize>(e: &mut Expansion<N>, sign: f64, u: &Vec3, v: &Vec3, w: &Vec3) {
    e.add_triple(sign, u.x, v.y, w.z);
    e.add_triple(-sign, u.x, v.z, w.y);
    e.add_triple(-sign, u.y, v.x, w.z);
    e.add_triple(sign, u.y, v.z, w.x);
    e.add_triple(sign, u.z, v.x, w.y);
    e.add_triple(-sign, u.z, v.y, w.x);
}

/// A point of a coordinate plane.
pub(crate) type P2 = [f64; 2];

/// Orientation of `c` relative to the line through `a` and `b`: `(b - a) x (c - a)`, positive
/// when `a b c` turn counter-clockwise. The sign is exact.
pub(crate) fn orient2d(a: P2, b: P2, c: P2) -> f64 {
    let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
    let (vx, vy) = (c[0] - a[0], c[1] - a[1]);
    let (l, r) = (ux * vy, uy * vx);
    let v = l - r;
    let bound = ERR2 * (l.abs() + r.abs()) + UNDERFLOW;
    if v.abs() > bound {
        return v;
    }
    orient2d_exact(a, b, c)
}

/// `orient2d` computed exactly.
fn orient2d_exact(a: P2, b: P2, c: P2) -> f64 {
    let k = match exact_method(&[a[0], a[1], b[0], b[1], c[0], c[1]]) {
        Exact::Zero => return 0.0,
        Exact::Integers => return orient2d_integers(a, b, c),
        Exact::Scaled(k) => k,
    };
    let s = pow2(k);
    let (a, b, c) = (
        [a[0] * s, a[1] * s],
        [b[0] * s, b[1] * s],
        [c[0] * s, c[1] * s],
    );
    // det[[ax, ay, 1], [bx, by, 1], [cx, cy, 1]]
    let mut e = Expansion::<12>::new();
    e.add_product(1.0, a[0], b[1]);
    e.add_product(-1.0, a[0], c[1]);
    e.add_product(-1.0, a[1], b[0]);
    e.add_product(1.0, a[1], c[0]);
    e.add_product(1.0, b[0], c[1]);
    e.add_product(-1.0, b[1], c[0]);
    scale_keep_sign(e.leading(), -2 * k)
}

/// `orient2d` with exact integers.
#[cold]
#[inline(never)]
fn orient2d_integers(a: P2, b: P2, c: P2) -> f64 {
    let [a, b, c] = [a, b, c].map(|p| p.map(BigInt::from_f64));
    let (ux, uy) = (b[0].sub(&a[0]), b[1].sub(&a[1]));
    let (vx, vy) = (c[0].sub(&a[0]), c[1].sub(&a[1]));
    ux.mul(&vy)
        .sub(&uy.mul(&vx))
        .to_f64_scaled(2 * super::big_int::LSB)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::{Random, Rng};

    fn det_i128(p: [[i64; 3]; 4]) -> i128 {
        let d = |i: usize, k: usize| (p[i][k] - p[0][k]) as i128;
        d(1, 0) * (d(2, 1) * d(3, 2) - d(2, 2) * d(3, 1))
            - d(1, 1) * (d(2, 0) * d(3, 2) - d(2, 2) * d(3, 0))
            + d(1, 2) * (d(2, 0) * d(3, 1) - d(2, 1) * d(3, 0))
    }

    fn sign(x: f64) -> i32 {
        (x > 0.0) as i32 - (x < 0.0) as i32
    }

    #[test]
    fn two_prod_and_two_sum_are_exact() {
        let mut r = Rng(1);
        for _ in 0..2000 {
            // 26-bit integers times powers of two: products fit in i128 exactly.
            let a = r.int(-(1 << 40), 1 << 40);
            let b = r.int(-(1 << 40), 1 << 40);
            let (p, e) = two_prod(a as f64, b as f64);
            assert_eq!(p as i128 + e as i128, a as i128 * b as i128);
            let (s, t) = two_sum(a as f64 * 1e10, b as f64);
            assert_eq!(s as i128 + t as i128, (a as f64 * 1e10) as i128 + b as i128);
        }
    }

    /// Random near-degenerate integer configurations (a fourth point on the plane of three, moved
    /// by at most one unit), with large offsets and power-of-two scales so that the float filter
    /// fails and the exact path decides; compared with 128-bit integer arithmetic.
    #[test]
    fn orient3d_sign_is_exact_on_near_degenerate_input() {
        let mut r = Rng(7);
        for iter in 0..3000 {
            let off = [
                r.int(-(1 << 40), 1 << 40),
                r.int(-(1 << 40), 1 << 40),
                r.int(0, 1 << 40),
            ];
            let mut p = [[0i64; 3]; 4];
            for q in p.iter_mut().take(3) {
                for (c, o) in q.iter_mut().zip(off) {
                    *c = o + r.int(-(1 << 20), 1 << 20);
                }
            }
            let (i, j) = (r.int(-3, 3), r.int(-3, 3));
            p[3] = std::array::from_fn(|k| {
                p[0][k] + i * (p[1][k] - p[0][k]) + j * (p[2][k] - p[0][k]) + r.int(-1, 1)
            });
            let want = det_i128(p).signum() as i32;
            let scale = [1.0, 2f64.powi(-60), 2f64.powi(300), 2f64.powi(-400)][iter % 4];
            let v: Vec<Vec3> = p
                .iter()
                .map(|q| {
                    Vec3::new(
                        q[0] as f64 * scale,
                        q[1] as f64 * scale,
                        q[2] as f64 * scale,
                    )
                })
                .collect();
            assert_eq!(sign(orient3d(&v[0], &v[1], &v[2], &v[3])), want, "{p:?}");
            assert_eq!(
                sign(orient3d_exact(&v[0], &v[1], &v[2], &v[3])),
                want,
                "{p:?}"
            );
            // Orientation is antisymmetric under swapping two points.
            assert_eq!(sign(orient3d(&v[1], &v[0], &v[2], &v[3])), -want);
        }
    }

    #[test]
    fn orient3d_exact_value_approximates_float_value() {
        let mut r = Rng(3);
        for _ in 0..500 {
            let v: Vec<Vec3> = (0..4)
                .map(|_| {
                    Vec3::new(
                        r.int(-1000, 1000) as f64,
                        r.int(-1000, 1000) as f64,
                        r.int(-1000, 1000) as f64,
                    ) * 0.37
                })
                .collect();
            let f = PlaneFilter::new(&v[0], &v[1], &v[2]).eval(&v[3]).0;
            let e = orient3d_exact(&v[0], &v[1], &v[2], &v[3]);
            assert!((f - e).abs() <= 1e-12 * f.abs().max(1.0), "{f} {e}");
        }
    }

    #[test]
    fn orient2d_sign_is_exact_on_near_degenerate_input() {
        let mut r = Rng(11);
        for iter in 0..3000 {
            let off = [r.int(-(1 << 45), 1 << 45), r.int(-(1 << 45), 1 << 45)];
            let a = [
                off[0] + r.int(-(1 << 24), 1 << 24),
                off[1] + r.int(-(1 << 24), 1 << 24),
            ];
            let b = [
                off[0] + r.int(-(1 << 24), 1 << 24),
                off[1] + r.int(-(1 << 24), 1 << 24),
            ];
            let t = r.int(-5, 5);
            let c = [
                a[0] + t * (b[0] - a[0]) + r.int(-1, 1),
                a[1] + t * (b[1] - a[1]) + r.int(-1, 1),
            ];
            let want = ((b[0] - a[0]) as i128 * (c[1] - a[1]) as i128
                - (b[1] - a[1]) as i128 * (c[0] - a[0]) as i128)
                .signum() as i32;
            let s = [1.0, 2f64.powi(-70), 2f64.powi(400)][iter % 3];
            let f = |p: [i64; 2]| [p[0] as f64 * s, p[1] as f64 * s];
            assert_eq!(sign(orient2d(f(a), f(b), f(c))), want);
            assert_eq!(sign(orient2d(f(b), f(a), f(c))), -want);
        }
    }

    #[test]
    fn accurate_cross_product_of_nearly_parallel_vectors() {
        // u and v differ by one unit in the last place of one component: the true cross product is
        // tiny but nonzero, and must come out with a small relative error.
        let u = Vec3::new(0.1, 0.7, 0.3);
        let v = Vec3::new(0.1, 0.7, f64::from_bits(0.3f64.to_bits() + 1));
        let n = cross_accurate(&u, &v);
        let dz = v.z - u.z; // exact
        // u x v = u x (u + dz e_z) = dz (u x e_z) = dz (u.y, -u.x, 0)
        let want = Vec3::new(dz * u.y, -dz * u.x, 0.0);
        assert!((n - want).norm() <= 1e-15 * want.norm(), "{n:?} {want:?}");
    }
}
