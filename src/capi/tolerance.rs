//! Tolerance: the result handle, its getters, and pqp_tolerance.
//!
//! Getters never fail: given NULL they return a fallback value (stated on each).

#![allow(non_snake_case)] // R1, T1, R2, T2 keep PQP's names, which the header shows.

use super::{
    PosedModel, SearchArg, count, destroy_handle, getter, new_handle, pair_query, pqp_model,
    pqp_search_options, write_triangles,
};
use crate::query::{ToleranceResult, tolerance_into};
use std::ffi::c_int;
use std::ptr;

/// The answer of pqp_tolerance (opaque). Reusing one for the next query on the same two models starts
/// from the triangle pair that decided the last answer.
#[allow(non_camel_case_types)]
#[derive(Default)]
pub struct pqp_tolerance_result {
    pub(crate) result: ToleranceResult,
}

/// Creates an empty tolerance result (not closer, distance +infinity, no cached triangle pair).
///
/// @return a new result, to be freed with pqp_tolerance_result_destroy; NULL only if memory could
///         not be allocated.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub extern "C" fn pqp_tolerance_result_create() -> *mut pqp_tolerance_result {
    new_handle::<pqp_tolerance_result>()
}

/// Frees a tolerance result.
///
/// @param r  a result from pqp_tolerance_result_create, or NULL (then nothing happens).
/// Thread safety: must not run concurrently with any other call using r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_destroy(r: *mut pqp_tolerance_result) {
    // SAFETY: r is NULL or a live handle of its kind, used by no other call (the caller's contract).
    unsafe { destroy_handle(r) }
}

/// Decides whether two posed models are within a distance of each other (PQP_Tolerance).
///
/// Poses are as for pqp_collide. Cheaper than pqp_distance: it stops at the first triangle pair
/// within the tolerance and skips everything farther than it. Reusing r for the next query on the
/// same two models first tries the triangle pair that decided the last answer.
///
/// @param r          the result to fill (its previous answer is replaced).
/// @param R1, T1     the pose of model 1.
/// @param m1         model 1 (built).
/// @param R2, T2     the pose of model 2.
/// @param m2         model 2 (built; may be the same model as m1).
/// @param tolerance  the distance asked about, >= 0 (-0 is 0; with +infinity every pair is
///                   within it, and the query still reports one triangle pair and its distance).
/// @param qsize      PQP's search queue size, >= 1, only checked (as for pqp_distance);
///                   pqp_tolerance_search chooses the search.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_INVALID_ARGUMENT if
///         tolerance is negative or NaN, or qsize < 1; PQP_ERR_UNPROCESSED_MODEL if a model is
///         not built; PQP_ERR_NONFINITE_POSE if a pose entry is NaN, infinite or larger than 1e150
///         in magnitude; PQP_ERR_INTERNAL on an internal fault (r is then reset to its freshly
///         created state). On any other error r is left unchanged.
/// Thread safety: any number of queries may use the same models at once from different threads;
///                r must not be used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance(
    r: *mut pqp_tolerance_result,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_model,
    tolerance: f64,
    qsize: c_int,
) -> c_int {
    let search = SearchArg::QueueSize(qsize);
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { tolerance_query(r, (R1, T1, m1), (R2, T2, m2), tolerance, search) }
}

/// As pqp_tolerance, with the search chosen by options (NULL: the default search).
///
/// @param r          the result to fill (its previous answer is replaced).
/// @param R1, T1     the pose of model 1.
/// @param m1         model 1 (built).
/// @param R2, T2     the pose of model 2.
/// @param m2         model 2 (built; may be the same model as m1).
/// @param tolerance  the distance asked about, >= 0 (-0 is 0; with +infinity every pair is
///                   within it, and the query still reports one triangle pair and its distance).
/// @param options  the strategy, queue size and triangle caching (see pqp_search_options), or
///                 NULL for the default (as pqp_search_options_default gives).
/// @return PQP_OK, or as pqp_tolerance (PQP_ERR_NULL_POINTER, ...); PQP_ERR_INVALID_ARGUMENT also
///         for an unknown strategy, a negative queue size, or a triangle_cache other than 0 or 1.
/// Thread safety: as pqp_tolerance.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_search(
    r: *mut pqp_tolerance_result,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_model,
    tolerance: f64,
    options: *const pqp_search_options,
) -> c_int {
    let search = SearchArg::Options(options);
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { tolerance_query(r, (R1, T1, m1), (R2, T2, m2), tolerance, search) }
}

/// The body of pqp_tolerance and pqp_tolerance_search, which differ in how they give the search.
///
/// # Safety
/// As the entry points': every pointer NULL or valid as the header requires.
unsafe fn tolerance_query(
    r: *mut pqp_tolerance_result,
    one: PosedModel,
    two: PosedModel,
    tolerance: f64,
    search: SearchArg,
) -> c_int {
    // SAFETY: the pointers are as pair_query requires (this function's contract).
    unsafe {
        pair_query(r, one, two, search, |r, q| {
            tolerance_into(
                &mut r.result,
                q.m1,
                &q.pose1,
                q.m2,
                &q.pose2,
                tolerance,
                &q.search,
            )
        })
    }
}

/// Whether the last pqp_tolerance on r found the models within the tolerance (distance <=
/// tolerance).
///
/// @param r  the result, or NULL.
/// @return 1 if closer than (or at) the tolerance, else 0 (also before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_closer_than_tolerance(
    r: *const pqp_tolerance_result,
) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| c_int::from(r.result.closer_than_tolerance)) }
}

/// A distance found by the last pqp_tolerance on r.
///
/// When closer than the tolerance: the distance of a triangle pair within the tolerance (not
/// necessarily the closest pair). Otherwise: a lower bound on the models' distance, greater than the
/// tolerance.
///
/// @param r  the result, or NULL.
/// @return the distance; +infinity before any query; NaN if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_distance(r: *const pqp_tolerance_result) -> f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, f64::NAN, |r| r.result.distance) }
}

/// The tolerance the last pqp_tolerance on r was asked about.
///
/// @param r  the result, or NULL.
/// @return the tolerance; 0 before any query; NaN if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_tolerance(r: *const pqp_tolerance_result) -> f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, f64::NAN, |r| r.result.tolerance) }
}

/// When the last pqp_tolerance on r found the models closer than the tolerance: the point on
/// model 1 of the triangle pair within the tolerance, in model 1's frame. Otherwise (0, 0, 0).
///
/// @param r  the result, or NULL.
/// @return 3 doubles (x, y, z), owned by r and valid until r is modified or destroyed; NULL if r
///         is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_p1(r: *const pqp_tolerance_result) -> *const f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, ptr::null(), |r| r.result.p1.as_ptr()) }
}

/// When the last pqp_tolerance on r found the models closer than the tolerance: the point on
/// model 2 of the triangle pair within the tolerance, in model 2's frame. Otherwise (0, 0, 0).
///
/// @param r  the result, or NULL.
/// @return 3 doubles (x, y, z), owned by r and valid until r is modified or destroyed; NULL if r
///         is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_p2(r: *const pqp_tolerance_result) -> *const f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, ptr::null(), |r| r.result.p2.as_ptr()) }
}

/// When the last pqp_tolerance on r found the models closer than the tolerance: the triangles of
/// the pair within the tolerance, by their positions in the order added (indices into
/// pqp_model_tris of each model, what PQP 1.3's last_tri pointed at). Otherwise -1 and -1.
///
/// @param r   the result.
/// @param t1  receives model 1's triangle: 0 for the first triangle added to it, and so on; -1
///            before any query, or when the models were not within the tolerance (no pair then).
/// @param t2  receives model 2's triangle, likewise.
/// @return PQP_OK (also when there is no pair, with -1 in both); PQP_ERR_NULL_POINTER if r, t1 or
///         t2 is NULL (nothing is written); PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_triangles(
    r: *const pqp_tolerance_result,
    t1: *mut c_int,
    t2: *mut c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { write_triangles(r, t1, t2, |r| (r.result.tri1, r.result.tri2)) }
}

/// The number of bounding-volume distance tests the last pqp_tolerance on r performed.
///
/// @param r  the result, or NULL.
/// @return the count (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_num_bv_tests(r: *const pqp_tolerance_result) -> i64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| count(r.result.stats.bv_tests)) }
}

/// The number of triangle-pair distance tests the last pqp_tolerance on r performed.
///
/// @param r  the result, or NULL.
/// @return the count (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_num_tri_tests(r: *const pqp_tolerance_result) -> i64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| count(r.result.stats.tri_tests)) }
}

/// The wall-clock time of the last pqp_tolerance on r.
///
/// @param r  the result, or NULL.
/// @return seconds (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_result_query_time_secs(
    r: *const pqp_tolerance_result,
) -> f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0.0, |r| r.result.stats.query_time_secs) }
}
