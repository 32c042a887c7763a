//! Time of first contact: pqp_time_of_contact.

#![allow(non_snake_case)] // R1a, T1a, ... keep the poses' names the header shows.

use super::{PQP_ERR_INTERNAL, PosedModel, boundary, code, deref, pqp_model, read_pose};
use crate::error::Error;
use crate::query::{Motion, time_of_contact};
use std::ffi::c_int;

/// The answer of pqp_time_of_contact.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct pqp_contact_time {
    /// 1 if the models come within tolerance during the motion.
    pub contact: c_int,
    /// The first such time in [0, 1]; INFINITY if none.
    pub toc: f64,
    /// Model 1's triangle (its id) of the closest pair at toc, within tolerance; -1 if none.
    pub id1: c_int,
    /// Model 2's triangle (its id) of the closest pair at toc; -1 if none.
    pub id2: c_int,
    /// The closest point on model 1 at toc, world coordinates; NaN (all three) if none.
    pub point1: [f64; 3],
    /// The closest point on model 2 at toc, world coordinates; NaN (all three) if none.
    pub point2: [f64; 3],
}

/// The time of first contact of two moving models: the first time in [0, 1] at which they come
/// within tolerance of each other (continuous collision detection by conservative advancement).
///
/// Each model moves from pose a (t = 0) to pose b (t = 1): its translation linearly, its rotation
/// at constant angular velocity about a fixed axis, R(t) = Ra exp(t log(Ra^T Rb)), the shorter
/// way; a relative turn of exactly pi (to within 1e-12 radians, which the rounding of the
/// rotations cannot tell from it) turns right-handed, by +pi, about the axis, in Ra's frame, whose
/// largest-magnitude component is positive (when components are equal in magnitude, the first of
/// them: x before y before z), whatever Ra. Rotations orthonormal to within 1e-6 (every singular
/// value within 1e-6 of 1, determinant positive) are accepted and projected to the nearest
/// rotation first.
///
/// Guarantees (up to the rounding of poses and distances): with contact, the distance at toc is
/// at most tolerance and above 0.999 tolerance at every earlier time, so the models never overlap
/// before toc; toc is 0 when they are within tolerance at the start. contact is 0 only when the
/// distance stays above tolerance over all of [0, 1] (to within a relative 1e-9 where the motion
/// only grazes the tolerance). No thin obstacle is missed, however fast the motion: the search
/// steps by the exact distance over a bound on the speed of every point, and makes at most
/// 1000 B / tolerance + 1 advancement steps, B being that bound (a distance query each); motions
/// that approach converge in a few.
///
/// @param out        the answer (written only on success).
/// @param R1a, T1a   the pose of model 1 at t = 0.
/// @param R1b, T1b   the pose of model 1 at t = 1.
/// @param m1         model 1 (built).
/// @param R2a, T2a   the pose of model 2 at t = 0.
/// @param R2b, T2b   the pose of model 2 at t = 1.
/// @param m2         model 2 (built; may be the same model as m1).
/// @param tolerance  the distance that counts as contact, > 0 (INFINITY: contact at 0).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_INVALID_ARGUMENT if
///         tolerance is not above 0 (or NaN), or a rotation is not one to within 1e-6 (a
///         reflection included); PQP_ERR_UNPROCESSED_MODEL if a model is not built;
///         PQP_ERR_NOT_A_TRIANGLE_MESH if a model holds a primitive (pqp_model_set_sphere, ...);
///         PQP_ERR_NONFINITE_POSE if a pose entry is NaN, infinite or larger than 1e150 in
///         magnitude; PQP_ERR_INTERNAL on an internal fault. On any error out is left unchanged.
/// Thread safety: any number of queries may use the same models at once from different threads.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_time_of_contact(
    out: *mut pqp_contact_time,
    R1a: *const f64,
    T1a: *const f64,
    R1b: *const f64,
    T1b: *const f64,
    m1: *const pqp_model,
    R2a: *const f64,
    T2a: *const f64,
    R2b: *const f64,
    T2b: *const f64,
    m2: *const pqp_model,
    tolerance: f64,
) -> c_int {
    let body = || -> Result<(), Error> {
        if out.is_null() {
            return Err(Error::NullPointer);
        }
        // SAFETY: every pointer is NULL or valid as the header requires of the caller.
        let (motion1, m1) = unsafe { read_motion((R1a, T1a, m1), R1b, T1b)? };
        // SAFETY: as above.
        let (motion2, m2) = unsafe { read_motion((R2a, T2a, m2), R2b, T2b)? };
        let c = time_of_contact(&m1.model, &motion1, &m2.model, &motion2, tolerance)?;
        let answer = pqp_contact_time {
            contact: c_int::from(c.contact),
            toc: c.toc,
            id1: c.id1,
            id2: c.id2,
            point1: c.point1.into(),
            point2: c.point2.into(),
        };
        // SAFETY: `out` is not NULL, so it points to a writable pqp_contact_time (the header's
        // contract).
        unsafe { out.write_unaligned(answer) };
        Ok(())
    };
    boundary(PQP_ERR_INTERNAL, || {}, || code(body()))
}

/// A model and its motion from C: the start pose and model, and the end pose.
///
/// # Safety
/// Each pointer is NULL or valid as the header requires (9 or 3 doubles, a live model).
unsafe fn read_motion<'a>(
    (ra, ta, m): PosedModel,
    rb: *const f64,
    tb: *const f64,
) -> Result<(Motion, &'a super::pqp_model), Error> {
    // SAFETY: each pointer is NULL or valid (this function's contract).
    unsafe {
        let start = read_pose(ra, ta)?;
        let end = read_pose(rb, tb)?;
        Ok((Motion::new(start, end), deref(m)?))
    }
}
