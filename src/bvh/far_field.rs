//! A node's far field for the winding number: the first term of the expansion of the solid angle
//! its triangles subtend at a distant point, with a rigorous bound on what that term leaves out.
//!
//! The solid angle of a surface S at p is the integral over S of `n . K(x)` with
//! `K(x) = (x - p) / |x - p|^3`. Replacing `K(x)` by `K(c)` for a centre c gives the dipole term
//! `A . K(c)`, A the vector area of S (the sum of its triangles' `(b - a) x (c - a) / 2`). For S
//! inside the ball of radius r about c and `D = |c - p| > r`, the Jacobian of K has norm
//! `2 / |y - p|^3` at y, at most `2 / (D - r)^3` on the ball, so `|K(x) - K(c)| <= 2 r / (D - r)^3`
//! and the term is off by at most `2 r F / (D - r)^3`, F the (unsigned) area of S. Over `4 pi`
//! (winding numbers): the stored `a = A / (4 pi)` and `f = F / (4 pi)`.
//!
//! The winding-number query (`query/winding.rs`) uses it only to decide which side of 1/2 the
//! winding number lies, and computes the number exactly whenever the bounds cannot tell.

use crate::math::Vec3;
use std::f64::consts::PI;

/// The dipole term of a node, the ball it is taken over, and its error's factors.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FarField {
    /// Centre of the ball.
    pub centre: Vec3,
    /// Radius of the ball about `centre` holding every vertex of the node (rounded up).
    pub radius: f64,
    /// Vector area over 4 pi.
    pub area: Vec3,
    /// Unsigned area over 4 pi, rounded up.
    pub spread: f64,
    /// A bound on the rounding of `area`, over 4 pi.
    pub slop: f64,
}

/// The range of lengths (a loop's extent, a point's distance) over which the far field's squares
/// neither overflow nor underflow.
const SAFE_MIN: f64 = 1e-140;
const SAFE_MAX: f64 = 1e140;

impl FarField {
    /// A far field that holds nowhere (`at` answers `None`).
    const NONE: FarField = FarField {
        centre: Vec3::new(0.0, 0.0, 0.0),
        radius: f64::INFINITY,
        area: Vec3::new(0.0, 0.0, 0.0),
        spread: 0.0,
        slop: 0.0,
    };

    /// The far field of the fan from the centroid of a closed loop's vertices over its edges
    /// `(from, to)` (at least one): the fan lies in the convex hull of the loop, and its area is
    /// that of a cap over it, small for a small hole however large the surface around it.
    pub fn of_fan(edges: impl Iterator<Item = (Vec3, Vec3)> + Clone) -> FarField {
        let (mut sum, mut count) = (Vec3::zeros(), 0.0);
        for (a, _) in edges.clone() {
            sum += a;
            count += 1.0;
        }
        let centre = sum / count;
        // Relative to the centre, brought near unit size (the squares below would underflow or
        // overflow at extreme scales): by 1 / m, whose rounding the allowance below covers.
        let m = edges
            .clone()
            .map(|(a, _)| (a - centre).amax())
            .fold(0.0, f64::max);
        if !(SAFE_MIN..=SAFE_MAX).contains(&m) {
            return FarField::NONE;
        }
        let k = 1.0 / m;
        let (mut far2, mut vector, mut unsigned) = (0.0f64, Vec3::zeros(), 0.0);
        for (a, b) in edges {
            let (a, b) = ((a - centre) * k, (b - centre) * k);
            far2 = far2.max(a.norm_squared()).max(b.norm_squared());
            let n = a.cross(&b) * 0.5;
            vector += n;
            unsigned += n.norm();
        }
        let (vector, unsigned) = (vector * (m * m), unsigned * (m * m));
        // Each edge's term is within a few ulps of its size, the centre off the centroid by a few
        // ulps of the vertices' spread, and each sum adds one rounding per term: (count + 16)
        // ulps of the unsigned area bound all of it.
        let rounding = 2.3e-16 * (count + 16.0);
        let spread = unsigned / (4.0 * PI);
        FarField {
            centre,
            radius: far2.sqrt() * m * (1.0 + 1e-12),
            area: vector / (4.0 * PI),
            spread: spread * (1.0 + rounding),
            slop: spread * rounding,
        }
    }
    /// The dipole term's winding number at `p` and a bound on its error, if `p` is outside the
    /// ball by a tenth of its radius (nearer, the bound would be useless) and its distance is
    /// within the safe range.
    #[inline]
    pub fn at(&self, p: &Vec3) -> Option<(f64, f64)> {
        let d = self.centre - p;
        let dist = d.norm();
        let gap = dist - self.radius;
        if gap.is_nan() || gap <= 0.1 * self.radius || !(SAFE_MIN..=SAFE_MAX).contains(&dist) {
            return None;
        }
        // Divisions one at a time, the direction first: no product of more than two huge or tiny
        // lengths is formed.
        let w = self.area.dot(&(d / dist)) / dist / dist;
        let per_gap2 = self.spread / gap / gap;
        let bound = 2.0 * (self.radius / gap) * per_gap2;
        // Beyond the expansion's error: the rounding of `area` (over dist^2 <= gap^2) and the
        // term's own (a few ulps of |a| / dist^2 <= spread / gap^2), generously.
        Some((
            w,
            bound * (1.0 + 1e-12) + self.slop / gap / gap + 1e-13 * per_gap2,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::solid_angle;
    use crate::test_rng::{Lcg, Random};

    /// The term is within its bound of the exact solid angle of the loop's fan, for wavy loops
    /// (not flat, not convex) at scales from tiny to huge and points from just outside the ball
    /// to far away; and the bound shrinks with the distance.
    #[test]
    fn dipole_term_is_within_its_bound() {
        let mut rng = Lcg(29);
        let mut tight = 0;
        for round in 0..400 {
            let s = [1e-130, 1e-3, 1.0, 1e4, 1e130][round % 5];
            let n = 3 + rng.below(40);
            let centre = Vec3::from(rng.point(5.0)) * s;
            let (wave, tilt) = (rng.range(0.0, 0.5), rng.range(0.0, 1.0));
            let loop_pts: Vec<Vec3> = (0..n)
                .map(|i| {
                    let t = 2.0 * PI * i as f64 / n as f64;
                    let r = 1.0 + wave * (3.0 * t).sin() + 0.2 * rng.signed();
                    centre + Vec3::new(r * t.cos(), r * t.sin(), tilt * (2.0 * t).cos()) * s
                })
                .collect();
            let edges = (0..n).map(|i| (loop_pts[i], loop_pts[(i + 1) % n]));
            let f = FarField::of_fan(edges.clone());
            for _ in 0..20 {
                let p = f.centre
                    + Vec3::from(rng.direction()) * (f.radius * rng.log_uniform(1.11, 1e3));
                let Some((w, bound)) = f.at(&p) else {
                    continue;
                };
                // The exact solid angle of the fan from the loop's first vertex.
                let o = loop_pts[0] - p;
                let exact: f64 = edges
                    .clone()
                    .map(|(a, b)| solid_angle(&o, &(a - p), &(b - p)))
                    .sum::<f64>()
                    / (4.0 * PI);
                assert!(
                    (w - exact).abs() <= bound,
                    "{w} {exact} {bound} at scale {s}"
                );
                tight += usize::from(bound < 1e-3);
            }
        }
        assert!(tight > 1000, "{tight}");
    }
}
