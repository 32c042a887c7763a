//! Pairs within a distance: pqp_within_distance, answered in a collision result.

#![allow(non_snake_case)] // R1, T1, R2, T2 keep PQP's names, which the header shows.

use super::{
    PQP_ERR_INTERNAL, boundary, code, deref, deref_mut, pqp_collide_result, pqp_model, read_pose,
    reset,
};
use crate::error::Error;
use crate::query::within_distance_into;

/// Lists every triangle pair of two posed models whose distance is at most tolerance, overlapping
/// pairs included, each once: contact generation with a margin. Read the pairs with the collision
/// result getters (pqp_collide_result_num_pairs, pqp_collide_result_id1 for model 1's triangle,
/// pqp_collide_result_id2, pqp_collide_result_pairs).
///
/// With tolerance 0 the pairs are exactly those of pqp_collide with PQP_ALL_CONTACTS (overlap is
/// decided exactly). Above 0, a pair that does not overlap is listed when its distance, as the
/// exact triangle distance of pqp_triangle_distance computes it, is at most tolerance. Node pairs
/// are pruned by the swept sphere volumes' distance bounds, so the work grows with the number of
/// pairs near each other, not with all pairs. Poses as in pqp_collide.
///
/// @param r          the result to fill (its previous answer is replaced).
/// @param R1, T1     the pose of model 1.
/// @param m1         model 1 (built).
/// @param R2, T2     the pose of model 2.
/// @param m2         model 2 (built; may be the same model as m1).
/// @param tolerance  the distance, >= 0 (INFINITY lists every pair).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_INVALID_ARGUMENT if
///         tolerance is negative or NaN; PQP_ERR_UNPROCESSED_MODEL if a model is not built;
///         PQP_ERR_NONFINITE_POSE if an entry of R1, T1, R2 or T2 is NaN, infinite or larger than
///         1e150 in magnitude; PQP_ERR_OUT_OF_MEMORY if the pair list could not grow (r then
///         holds no pairs); PQP_ERR_INTERNAL on an internal fault (r is then reset to its freshly
///         created state). On any other error r is left unchanged.
/// Thread safety: any number of queries may use the same models at once from different threads;
///                r must not be used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_within_distance(
    r: *mut pqp_collide_result,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_model,
    tolerance: f64,
) -> std::ffi::c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        let body = || -> Result<(), Error> {
            let result = deref_mut(r)?;
            let (pose1, m1) = (read_pose(R1, T1)?, deref(m1)?);
            let (pose2, m2) = (read_pose(R2, T2)?, deref(m2)?);
            within_distance_into(
                &mut result.result,
                &m1.model,
                &pose1,
                &m2.model,
                &pose2,
                tolerance,
            )
        };
        boundary(PQP_ERR_INTERNAL, || reset(r), || code(body()))
    }
}
