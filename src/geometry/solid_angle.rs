//! The solid angle a triangle subtends at a point, the summand of the generalized winding number.

use super::predicates::{kernel_rescale, max_abs, pow2};
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
    if let Some(k) = kernel_rescale(max_abs(&[a, b, c])) {
        let s = pow2(k);
        return solid_angle_near_unit(&(a * s), &(b * s), &(c * s));
    }
    solid_angle_near_unit(a, b, c)
}

/// [`solid_angle`] for coordinates whose cubes neither overflow nor underflow to nothing.
#[inline(always)]
fn solid_angle_near_unit(a: &Vec3, b: &Vec3, c: &Vec3) -> f64 {
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let det = a.dot(&b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * det.atan2(den)
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
