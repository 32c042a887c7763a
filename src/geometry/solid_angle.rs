//! The solid angle a triangle subtends at a point, the summand of the generalized winding number.

use super::predicates::{exponent, kernel_rescale, max_abs, pow2};
use crate::math::Vec3;

/// The signed solid angle triangle `(a, b, c)` subtends at the origin (its vertices relative to
/// the point), in `[-2 pi, 2 pi]`: positive when its normal `(b - a) x (c - a)` points away from
/// the origin, that is when the origin is behind it. Zero for a degenerate triangle or one whose
/// plane holds the origin outside it.
///
/// Why the formula holds: on the unit sphere, the spherical triangle of the unit vectors
/// `u, v, w` has area `E` (the solid angle), and `tan(E / 2) = u . (v x w) / (1 + u.v + v.w +
/// w.u)` (Van Oosterom and Strackee, 1983: the area of a spherical triangle is the argument of
/// the product of the three complex numbers `1 + u.v + i |..|`, summed in pairs, which reduces to
/// this quotient). Multiplying both terms by `|a| |b| |c|` gives the quotient below without a
/// division; `atan2` takes its quadrant from both signs, so the angle is right up to `2 pi` in
/// magnitude (a point just behind a large triangle) and the sign follows the determinant.
///
/// Coordinates are brought near 1 first by a power of two when they are far from it (the terms
/// reach the cube of the magnitudes), which the angle does not depend on.
#[inline]
pub(crate) fn solid_angle(a: &Vec3, b: &Vec3, c: &Vec3) -> f64 {
    let (den, det) = half_angle_tangent(a, b, c);
    2.0 * det.atan2(den)
}

/// The denominator and numerator of `tan(E / 2)` of [`solid_angle`], scaled together by a
/// positive factor (a power of two times `|a| |b| |c|`): the half angle is their argument.
#[inline(always)]
fn half_angle_tangent(a: &Vec3, b: &Vec3, c: &Vec3) -> (f64, f64) {
    if let Some(k) = kernel_rescale(max_abs(&[a, b, c])) {
        let s = pow2(k);
        return half_angle_tangent_near_unit(&(a * s), &(b * s), &(c * s));
    }
    half_angle_tangent_near_unit(a, b, c)
}

/// [`half_angle_tangent`] for coordinates whose cubes neither overflow nor underflow to nothing.
#[inline(always)]
fn half_angle_tangent_near_unit(a: &Vec3, b: &Vec3, c: &Vec3) -> (f64, f64) {
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let det = a.dot(&b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    (den, det)
}

/// A sum of solid angles ([`solid_angle`]) that takes one `atan2` in all rather than one per
/// triangle: the half angles are the arguments of the complex numbers `den + i det`, so their sum
/// is the argument of their product, plus a multiple of `2 pi` counted as the product turns past
/// the negative real axis. That count is decidable from signs alone for factors turning it less
/// than a quarter turn (`den > 0`); the others (rare: a triangle subtending more than a
/// hemisphere's half) are added through their own `atan2`. The product is kept near unit
/// magnitude by exact powers of two.
pub(crate) struct SolidAngleSum {
    re: f64,
    im: f64,
    /// Turns of the product past the negative real axis, counterclockwise positive.
    turns: i64,
    /// The angles added one by one.
    separate: f64,
}

impl Default for SolidAngleSum {
    fn default() -> Self {
        SolidAngleSum {
            re: 1.0,
            im: 0.0,
            turns: 0,
            separate: 0.0,
        }
    }
}

impl SolidAngleSum {
    /// Adds the solid angle of triangle `(a, b, c)` (vertices relative to the point).
    #[inline]
    pub fn add(&mut self, a: &Vec3, b: &Vec3, c: &Vec3) {
        let (den, det) = half_angle_tangent(a, b, c);
        // A NaN (never expected) goes the separate way too.
        if den.is_nan() || den <= 0.0 {
            self.separate += 2.0 * det.atan2(den);
            return;
        }
        let re = self.re * den - self.im * det;
        let im = self.re * det + self.im * den;
        // Turned by less than a quarter turn: the negative real axis was crossed exactly when the
        // imaginary part changed sign on its left half (arguments in (-pi, pi], pi on the axis).
        if self.re < 0.0 {
            if self.im >= 0.0 && im < 0.0 {
                self.turns += 1;
            } else if self.im < 0.0 && im >= 0.0 {
                self.turns -= 1;
            }
        }
        let m = re.abs().max(im.abs());
        let (re, im) = if (1e-100..=1e100).contains(&m) {
            (re, im)
        } else {
            let s = pow2((-exponent(m)).clamp(-1000, 1000));
            (re * s, im * s)
        };
        self.re = re;
        self.im = im;
    }

    /// The sum.
    pub fn total(&self) -> f64 {
        2.0 * (self.im.atan2(self.re) + std::f64::consts::TAU * self.turns as f64) + self.separate
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::{Lcg, Random};
    use std::f64::consts::PI;

    /// The eight octants of a sphere, each the triangle of three unit axes: pi / 2 each, signed by
    /// the orientation, and 4 pi in all from inside an octahedron.
    #[test]
    fn octants_and_a_closed_octahedron() {
        let (x, y, z) = (Vec3::x(), Vec3::y(), Vec3::z());
        assert!((solid_angle(&x, &y, &z) - PI / 2.0).abs() < 1e-15);
        assert!((solid_angle(&x, &z, &y) + PI / 2.0).abs() < 1e-15);
        // The octahedron |x| + |y| + |z| <= 1 seen from o: every face, outwards.
        let total = |o: Vec3| {
            let v = |s: [f64; 3]| Vec3::from(s) - o;
            let mut sum = 0.0;
            for sx in [-1.0, 1.0] {
                for sy in [-1.0, 1.0] {
                    for sz in [-1.0, 1.0] {
                        let (a, b, c) = (v([sx, 0.0, 0.0]), v([0.0, sy, 0.0]), v([0.0, 0.0, sz]));
                        // Mirroring an odd number of axes turns the octant's face round.
                        sum += if sx * sy * sz > 0.0 {
                            solid_angle(&a, &b, &c)
                        } else {
                            solid_angle(&a, &c, &b)
                        };
                    }
                }
            }
            sum
        };
        let mut rng = Lcg(5);
        for _ in 0..200 {
            let o = Vec3::from(rng.point(0.3));
            assert!((total(o) - 4.0 * PI).abs() < 1e-12, "{o}");
            let out = o + Vec3::new(1.5, 0.5, 0.0);
            assert!(total(out).abs() < 1e-12, "{out}");
        }
    }

    /// The product form adds up to the sum of the angles, across many turns (a closed octahedron
    /// counted many times over, both ways round) and with factors of every size.
    #[test]
    fn product_sum_is_the_sum() {
        let mut rng = Lcg(9);
        for round in 0..200 {
            let mut sum = SolidAngleSum::default();
            let mut plain = 0.0;
            let n = 1 + round * 3;
            for _ in 0..n {
                let s = 10f64.powf(rng.range(-120.0, 120.0));
                let v = |r: &mut Lcg| Vec3::from(r.point(1.0)) * s;
                let (a, b, c) = (v(&mut rng), v(&mut rng), v(&mut rng));
                sum.add(&a, &b, &c);
                plain += solid_angle(&a, &b, &c);
            }
            assert!(
                (sum.total() - plain).abs() < 1e-12 * n as f64,
                "{} vs {plain}",
                sum.total()
            );
        }
        // Many turns: an octant's triangle, from inside, 40 times.
        let (x, y, z) = (Vec3::x(), Vec3::y(), Vec3::z());
        let mut sum = SolidAngleSum::default();
        for _ in 0..40 {
            sum.add(&x, &y, &z);
        }
        assert!((sum.total() - 20.0 * PI).abs() < 1e-12);
        let mut sum = SolidAngleSum::default();
        for _ in 0..40 {
            sum.add(&x, &z, &y);
        }
        assert!((sum.total() + 20.0 * PI).abs() < 1e-12);
    }

    /// The angle does not depend on the scale, down to subnormal and up to huge coordinates.
    #[test]
    fn scale_invariant() {
        let (a, b, c) = (
            Vec3::new(1.0, 0.2, 0.3),
            Vec3::new(-0.4, 1.0, 0.1),
            Vec3::new(0.3, -0.2, 0.9),
        );
        let w = solid_angle(&a, &b, &c);
        for s in [1e-300, 1e-160, 1e-100, 1e100, 1e150, 1e300] {
            let ws = solid_angle(&(a * s), &(b * s), &(c * s));
            assert!((ws - w).abs() < 1e-14, "{s}: {ws} vs {w}");
        }
    }
}
