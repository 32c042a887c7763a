//! Time of first contact of two moving models, by conservative advancement on the exact distance.
//!
//! Each model moves from a start pose (t = 0) to an end pose (t = 1): its translation linearly, its
//! rotation at constant angular velocity about a fixed axis ([`RotationPath`]). A point x of model
//! i is at `p_i(t) = R_i(t) x + T_i(t)`, whose velocity is `omega_i x (R_i(t) x) + dT_i`, with
//! `|omega_i|` the relative turn's angle and `dT_i = T_i(1) - T_i(0)`. For any two points, one on
//! each model, `|d/dt (p_2 - p_1)| <= |dT_2 - dT_1| + angle_1 r_1 + angle_2 r_2 = B`, where `r_i`
//! bounds `|x|` over model i (from its root box). The distance between the models is therefore
//! B-Lipschitz in t: `d(t') >= d(t) - B |t' - t|`.
//!
//! Advancement: at t with `d(t) > tol`, every t' up to `t + (d(t) - 0.999 tol) / B` has
//! `d(t') >= 0.999 tol`, so the search jumps there and measures again; it stops at the first
//! measured `d <= tol` (the time of contact). Each jump is at least `0.001 tol / B` (and never
//! shorter than to the next double), so at most `1000 B / tol + 1` advancement steps are made (the
//! bound is reached only when the distance stays just above the tolerance for the whole motion;
//! approaching motions converge in a few steps).
//!
//! Certifying no contact: the jumps alone prove `d > 0.999 tol`, not `d > tol`. Between two
//! measurements at a and b both above tol, the two Lipschitz cones prove `d > tol` on `[a, b]`
//! when `(d(a) - tol) + (d(b) - tol) > B (b - a)`. Intervals that fail this are bisected, with a
//! measurement at each midpoint, until they pass, a midpoint is within the tolerance (the time of
//! contact: every earlier time is above 0.999 tol already), or `B (b - a) <= GRAZE tol`, where the
//! distance is proven above `(1 - GRAZE / 2) tol` and the interval is taken as clear. Only the
//! stretches where a step ended within 0.1% of the tolerance are doubtful, each at most
//! `0.001 tol / B` long in its uncertain part; a graze that stays within a relative 1e-9 above the
//! tolerance across it costs up to about `2e6` measurements there, a clear dip a few dozen.

use super::{DistanceOptions, DistanceResult, distance_into};
use crate::error::Error;
use crate::math::{Pose, RotationPath, Vec3};
use crate::model::Model;

/// The motion of a model from `start` (t = 0) to `end` (t = 1): translation linear in t, rotation
/// at constant angular velocity about a fixed axis, the shorter way (see [`RotationPath`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    /// The pose at t = 0.
    pub start: Pose,
    /// The pose at t = 1.
    pub end: Pose,
}

impl Motion {
    /// The motion from `start` to `end`.
    pub fn new(start: Pose, end: Pose) -> Motion {
        Motion { start, end }
    }
}

/// The answer of [`time_of_contact`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactTime {
    /// Whether the models come within the tolerance during the motion.
    pub contact: bool,
    /// The time of contact in `[0, 1]`; infinite without contact.
    pub toc: f64,
    /// The distance at `toc` (at most the tolerance); infinite without contact.
    pub distance: f64,
    /// Id of model 1's triangle of the closest pair at `toc`; -1 without contact.
    pub id1: i32,
    /// Id of model 2's triangle of the closest pair at `toc`; -1 without contact.
    pub id2: i32,
    /// The closest point on model 1 at `toc`, world coordinates; NaN without contact.
    pub point1: Vec3,
    /// The closest point on model 2 at `toc`, world coordinates; NaN without contact.
    pub point2: Vec3,
    /// Distance queries made (advancement steps and certifying bisections).
    pub steps: u64,
}

/// Below this width (as `B (b - a) / tol`) an interval between two measurements above the
/// tolerance is taken as clear (module documentation).
const GRAZE: f64 = 1e-9;

/// The share of the tolerance an advancement step keeps in hand.
const MARGIN: f64 = 0.999;

/// A model's motion, ready to be evaluated at any t.
struct Sweep {
    rotation: RotationPath,
    start: Vec3,
    delta: Vec3,
}

impl Sweep {
    fn new(motion: &Motion) -> Result<Sweep, Error> {
        motion.start.validate()?;
        motion.end.validate()?;
        Ok(Sweep {
            rotation: RotationPath::new(&motion.start.rotation, &motion.end.rotation)?,
            start: motion.start.translation,
            delta: motion.end.translation - motion.start.translation,
        })
    }

    fn at(&self, t: f64) -> Pose {
        Pose {
            rotation: self.rotation.at(t),
            translation: self.start + self.delta * t,
        }
    }
}

/// The first time in `[0, 1]` at which `m1` and `m2`, moving as `motion1` and `motion2`, come within
/// `tolerance` of each other (conservative advancement; the method and its guarantees are in the
/// module documentation).
///
/// Guarantees: with contact, `d(toc) <= tolerance` and `d(t) > 0.999 tolerance` for every
/// `t < toc` (so the models do not overlap before `toc`), and `toc = 0` when they are within the
/// tolerance at the start; without contact, `d(t) > tolerance` over `[0, 1]`, except where the
/// motion grazes the tolerance to within a relative 1e-9. Up to the rounding of the poses and the
/// distance at each t.
///
/// Rotations are accepted when orthonormal to within 1e-6 ([`crate::math::nearest_rotation`]) and
/// projected to the nearest rotation first. A relative turn of exactly pi (to within
/// [`crate::math::HALF_TURN_TOLERANCE`], 1e-12 radians) turns right-handed, by +pi, about the axis,
/// in the start rotation's frame, whose largest-magnitude component is positive (the first of
/// equal ones), whatever the start rotation ([`crate::math::rotation_log`]).
///
/// Errors: `InvalidArgument` for a tolerance not above 0 (or NaN), or a rotation that is not one;
/// `UnprocessedModel` for an unbuilt model; `NonFinitePose` for a pose entry NaN, infinite or
/// beyond 1e150.
///
/// ```
/// use pqp::{Model, Motion, Pose, time_of_contact};
/// let tri = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0);
/// let a = Model::from_triangles([tri]).unwrap();
/// let b = Model::from_triangles([tri]).unwrap();
/// let still = Motion::new(Pose::identity(), Pose::identity());
/// let fall = Motion::new(Pose::from_translation([0.0, 0.0, 4.0]), Pose::from_translation([0.0, 0.0, -4.0]));
/// let c = time_of_contact(&a, &still, &b, &fall, 0.01).unwrap();
/// assert!(c.contact && c.toc > 0.49 && c.toc < 0.5);
/// ```
pub fn time_of_contact(
    m1: &Model,
    motion1: &Motion,
    m2: &Model,
    motion2: &Motion,
    tolerance: f64,
) -> Result<ContactTime, Error> {
    if tolerance.is_nan() || tolerance <= 0.0 {
        return Err(Error::InvalidArgument);
    }
    let reach1 = reach(m1)?;
    let reach2 = reach(m2)?;
    let (sweep1, sweep2) = (Sweep::new(motion1)?, Sweep::new(motion2)?);
    // The speed bound B, with a relative allowance for the rounding of its terms.
    let speed = ((sweep2.delta - sweep1.delta).norm()
        + sweep1.rotation.angle * reach1
        + sweep2.rotation.angle * reach2)
        * (1.0 + 1e-9);
    let mut probe = Probe {
        m1,
        m2,
        sweep1: &sweep1,
        sweep2: &sweep2,
        result: DistanceResult::new(),
        options: DistanceOptions::exact(),
        steps: 0,
    };
    match advance(tolerance, speed, |t| probe.at(t))? {
        // The time found was the last one measured: `probe.result` holds its closest pair.
        Some(t) => Ok(probe.contact(t)),
        None => Ok(ContactTime {
            contact: false,
            toc: f64::INFINITY,
            distance: f64::INFINITY,
            id1: -1,
            id2: -1,
            point1: Vec3::repeat(f64::NAN),
            point2: Vec3::repeat(f64::NAN),
            steps: probe.steps,
        }),
    }
}

/// Conservative advancement (module documentation) on a distance `measure(t)` that is
/// `speed`-Lipschitz in t: the time of contact, which is the last time measured, or `None`.
fn advance(
    tol: f64,
    speed: f64,
    mut measure: impl FnMut(f64) -> Result<f64, Error>,
) -> Result<Option<f64>, Error> {
    let mut t = 0.0;
    let mut d = measure(t)?;
    // Intervals between measurements that the cones do not prove clear of the tolerance.
    let mut doubtful = Vec::new();
    loop {
        if d <= tol {
            return Ok(Some(t));
        }
        if (d - tol) / speed > 1.0 - t {
            // Clear of the tolerance up to t = 1 (also when B = 0).
            break;
        }
        let next = (t + (d - MARGIN * tol) / speed).max(t.next_up()).min(1.0);
        let d_next = measure(next)?;
        if d_next > tol && !clear(d, d_next, tol, speed * (next - t)) {
            doubtful.push((t, d, next, d_next));
        }
        (t, d) = (next, d_next);
        if t >= 1.0 && d > tol {
            break;
        }
    }
    for (a, da, b, db) in doubtful {
        if let Some(t) = bisect((a, da), (b, db), tol, speed, &mut measure)? {
            return Ok(Some(t));
        }
    }
    Ok(None)
}

/// Searches `[a, b]`, between measurements `da`, `db` above `tol`, by bisection (module
/// documentation): the first midpoint found within the tolerance, or `None` when the interval is
/// proven clear (to within `GRAZE`). Earlier halves are searched first.
fn bisect(
    (a, da): (f64, f64),
    (b, db): (f64, f64),
    tol: f64,
    speed: f64,
    measure: &mut impl FnMut(f64) -> Result<f64, Error>,
) -> Result<Option<f64>, Error> {
    let mut stack = vec![(a, da, b, db)];
    while let Some((a, da, b, db)) = stack.pop() {
        let width = speed * (b - a);
        let mid = 0.5 * (a + b);
        if clear(da, db, tol, width) || width <= GRAZE * tol || mid <= a || mid >= b {
            continue;
        }
        let dm = measure(mid)?;
        if dm <= tol {
            return Ok(Some(mid));
        }
        stack.push((mid, dm, b, db));
        stack.push((a, da, mid, dm));
    }
    Ok(None)
}

/// Whether the distance is proven above `tol` between two measurements `da`, `db` (both above it)
/// taken `reach` apart in the distance a point can move (B times the time between them).
fn clear(da: f64, db: f64, tol: f64, reach: f64) -> bool {
    (da - tol) + (db - tol) > reach
}

/// A bound on `|x|` over the points of a built model: its root box's centre's norm plus its half
/// diagonal (the box contains every triangle), with a relative allowance for rounding.
fn reach(m: &Model) -> Result<f64, Error> {
    let bvh = m.bvh()?;
    let obb = bvh.obb(bvh.root());
    Ok((obb.center.norm() + obb.half.norm()) * (1.0 + 1e-9))
}

/// The exact distance at a time of the motion, with one result kept across measurements (its
/// triangle cache and front follow the motion).
struct Probe<'a> {
    m1: &'a Model,
    m2: &'a Model,
    sweep1: &'a Sweep,
    sweep2: &'a Sweep,
    result: DistanceResult,
    options: DistanceOptions,
    steps: u64,
}

impl Probe<'_> {
    /// The distance at time t (the closest pair stays in `result`).
    fn at(&mut self, t: f64) -> Result<f64, Error> {
        let (pose1, pose2) = (self.sweep1.at(t), self.sweep2.at(t));
        distance_into(
            &mut self.result,
            self.m1,
            &pose1,
            self.m2,
            &pose2,
            &self.options,
        )?;
        self.steps += 1;
        Ok(self.result.distance)
    }

    /// The answer for a contact at t, the last time measured.
    fn contact(&self, t: f64) -> ContactTime {
        let r = &self.result;
        ContactTime {
            contact: true,
            toc: t,
            distance: r.distance,
            id1: r.id1,
            id2: r.id2,
            point1: self.sweep1.at(t).transform_point(&r.p1),
            point2: self.sweep2.at(t).transform_point(&r.p2),
            steps: self.steps,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs `advance` on `d` and checks the guarantees on a fine grid: the answer, and the
    /// number of measurements.
    fn run(d: impl Fn(f64) -> f64, tol: f64, speed: f64) -> (Option<f64>, usize) {
        let mut count = 0;
        let found = advance(tol, speed, |t| {
            count += 1;
            Ok(d(t))
        })
        .unwrap();
        match found {
            Some(toc) => {
                assert!(d(toc) <= tol);
                for k in 0..10_000 {
                    let t = toc * k as f64 / 10_000.0;
                    assert!(d(t) > MARGIN * tol, "{t}");
                }
            }
            None => {
                for k in 0..=10_000 {
                    assert!(d(k as f64 / 10_000.0) > tol * (1.0 - GRAZE));
                }
            }
        }
        (found, count)
    }

    #[test]
    fn a_dip_between_the_steps_is_found_by_the_bisection() {
        // V-shaped dips at the full speed bound, their bottom inside the 0.1% the steps keep in
        // hand, at many places: the steps jump over them, the bisection of the doubtful
        // intervals must find them (and certify the ones that stay just above the tolerance).
        let (tol, speed) = (0.01, 3.0);
        let mut found_by_bisection = 0;
        for k in 1..200 {
            let at = k as f64 / 200.0;
            for (bottom, expect) in [(0.9995, true), (1.0003, false)] {
                let d = |t: f64| (tol * bottom + speed * (t - at).abs()).min(2.0);
                let (found, count) = run(d, tol, speed);
                assert_eq!(found.is_some(), expect, "dip at {at}, bottom {bottom}");
                if let Some(toc) = found {
                    assert!((toc - at).abs() < 1e-3 * tol / speed, "{toc} vs {at}");
                    // Not the last advancement step: found by the bisection.
                    found_by_bisection += usize::from(count > 3);
                }
            }
        }
        assert!(found_by_bisection > 100, "{found_by_bisection}");
    }

    #[test]
    fn steps_are_bounded_and_the_end_is_checked() {
        let (tol, speed) = (0.01, 1.0);
        // Sliding just above the tolerance the whole way: about 1000 B / tol steps at most.
        let (found, count) = run(|_| tol * 1.01, tol, speed);
        assert!(
            found.is_none() && count <= (1000.0 * speed / tol) as usize + 1,
            "{count}"
        );
        // Within the tolerance only at t = 1.
        let (found, _) = run(|t| tol + speed * (1.0 - t), tol, speed);
        assert_eq!(found, Some(1.0));
        // Already within at the start; no motion.
        assert_eq!(run(|_| tol, tol, speed).0, Some(0.0));
        assert_eq!(run(|_| 2.0 * tol, tol, 0.0), (None, 1));
    }
}
