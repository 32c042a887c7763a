//! What the swept sphere fits (`pss.rs`, `lss.rs`, `rss.rs`) share: how far a point may lie
//! beside a core and stay within the radius, and a small ball around a point set.

use crate::math::Vec3;

/// How far a point at height `dz` above the rectangle's plane may lie beside the rectangle, in the
/// plane, and stay within `r` of it: `sqrt(r^2 - dz^2)`, factored to keep precision near the caps.
#[inline(always)]
pub(super) fn allowance(r: f64, dz: f64) -> f64 {
    ((r - dz) * (r + dz)).max(0.0).sqrt()
}

/// The radius `r` less point `i`'s pad (`pads` empty: no pads): how far from the core the centre
/// of a ball of that pad may be for the ball to be within `r`.
#[inline(always)]
pub(super) fn padded_reach(r: f64, pads: &[f64], i: usize) -> f64 {
    match pads.get(i) {
        Some(p) => r - p,
        None => r,
    }
}

/// The centre of a small ball around `n` points given by `at(i)`, in whatever coordinates `at`
/// returns: the centre of their bounding box, then a few steps of Badoiu and Clarkson's iteration
/// (move towards the farthest point by a shrinking fraction), keeping the centre whose farthest
/// point is nearest. The box centre is within sqrt(3)/2 of optimal; the steps usually shave a few
/// per cent off round and irregular sets. Returns the centre and the squared radius it needs.
pub(super) fn ball_centre(n: usize, at: impl Fn(usize) -> Vec3) -> (Vec3, f64) {
    let first = at(0);
    let (mut lo, mut hi) = (first, first);
    for i in 1..n {
        let q = at(i);
        lo = lo.inf(&q);
        hi = hi.sup(&q);
    }
    // Halve before adding: no overflow whatever the magnitudes.
    let mut c = lo * 0.5 + hi * 0.5;
    let farthest = |c: &Vec3| {
        let mut best = (0usize, -1.0f64);
        for i in 0..n {
            let d = (at(i) - c).norm_squared();
            if d > best.1 {
                best = (i, d);
            }
        }
        best
    };
    let (mut far, mut r2) = farthest(&c);
    let mut best = (c, r2);
    // The box centre is already close, so start with small steps (1/4, 1/5, ...) rather than the
    // iteration's 1/2: the point is to settle between the few farthest points.
    for k in 4..12 {
        c += (at(far) - c) / k as f64;
        (far, r2) = farthest(&c);
        if r2 < best.1 {
            best = (c, r2);
        }
    }
    best
}
