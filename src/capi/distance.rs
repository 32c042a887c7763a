//! Separation distance: the result handle, its getters, and pqp_distance.
//!
//! Getters never fail: given NULL they return a fallback value (stated on each).

#![allow(non_snake_case)] // R1, T1, R2, T2 keep PQP's names, which the header shows.

use super::{
    DEFAULT_SEARCH_OPTIONS, PosedModel, SearchArg, boundary, count, destroy_handle, getter,
    new_handle, pair_query, pqp_model, pqp_search_options, write_triangles,
};
use crate::query::{DistanceOptions, DistanceResult, distance_into};
use std::ffi::c_int;
use std::ptr;

/// The answer of pqp_distance (opaque). Reusing one for the next query on the same two models starts
/// from the last closest triangle pair (triangle caching).
#[allow(non_camel_case_types)]
#[derive(Default)]
pub struct pqp_distance_result {
    pub(crate) result: DistanceResult,
}

/// Creates an empty distance result (distance +infinity, no cached triangle pair).
///
/// @return a new result, to be freed with pqp_distance_result_destroy; NULL only if memory could
///         not be allocated.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub extern "C" fn pqp_distance_result_create() -> *mut pqp_distance_result {
    new_handle::<pqp_distance_result>()
}

/// Frees a distance result.
///
/// @param r  a result from pqp_distance_result_create, or NULL (then nothing happens).
/// Thread safety: must not run concurrently with any other call using r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_destroy(r: *mut pqp_distance_result) {
    // SAFETY: r is NULL or a live handle of its kind, used by no other call (the caller's contract).
    unsafe { destroy_handle(r) }
}

/// Computes the separation distance of two posed models and a closest pair of points
/// (PQP_Distance).
///
/// Poses are as for pqp_collide. The answer is within the error bounds asked for:
/// true <= distance <= min(true * (1 + rel_err), true + abs_err); abs_err = 0 asks for the exact
/// distance whatever rel_err is (as in PQP), abs_err = +infinity lets only rel_err act. When the
/// models touch or overlap the distance is 0 and pqp_distance_result_overlap reports 1, whatever
/// the bounds (infinite ones too). Reusing r for the next query on the same two models starts
/// from the last closest triangle pair and, after a small motion, from the last query's BVTT
/// front (both live in r, so models stay shareable).
///
/// @param r        the result to fill (its previous answer is replaced).
/// @param R1, T1   the pose of model 1.
/// @param m1       model 1 (built).
/// @param R2, T2   the pose of model 2.
/// @param m2       model 2 (built; may be the same model as m1).
/// @param rel_err  relative error allowed, >= 0.
/// @param abs_err  absolute error allowed, >= 0 (0: exact).
/// @param qsize    PQP's search queue size, >= 1, only checked: the search is the default one (for
///                 distance, priority-directed with a queue of 1024 pairs, and triangle caching),
///                 which does less work than PQP's search with any queue size on the benchmark
///                 workloads. pqp_distance_search chooses the search.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_INVALID_ARGUMENT if
///         rel_err or abs_err is negative or NaN, or qsize < 1; PQP_ERR_UNPROCESSED_MODEL if a
///         model is not built; PQP_ERR_NONFINITE_POSE if a pose entry is NaN, infinite or larger
///         than 1e150 in magnitude; PQP_ERR_INTERNAL on an internal fault (r is then reset to its
///         freshly created state). On any other error r is left unchanged.
/// Thread safety: any number of queries may use the same models at once from different threads;
///                r must not be used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance(
    r: *mut pqp_distance_result,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_model,
    rel_err: f64,
    abs_err: f64,
    qsize: c_int,
) -> c_int {
    let search = SearchArg::QueueSize(qsize);
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { distance_query(r, (R1, T1, m1), (R2, T2, m2), rel_err, abs_err, search) }
}

/// As pqp_distance, with the search chosen by options (NULL: the default search).
///
/// @param r        the result to fill (its previous answer is replaced).
/// @param R1, T1   the pose of model 1.
/// @param m1       model 1 (built).
/// @param R2, T2   the pose of model 2.
/// @param m2       model 2 (built; may be the same model as m1).
/// @param rel_err  relative error allowed, >= 0.
/// @param abs_err  absolute error allowed, >= 0 (0: exact).
/// @param options  the strategy, queue size and triangle caching (see pqp_search_options), or
///                 NULL for the default (as pqp_search_options_default gives).
/// @return PQP_OK, or as pqp_distance (PQP_ERR_NULL_POINTER, ...); PQP_ERR_INVALID_ARGUMENT also
///         for an unknown strategy, a negative queue size, or a triangle_cache other than 0 or 1.
/// Thread safety: as pqp_distance.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_search(
    r: *mut pqp_distance_result,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_model,
    rel_err: f64,
    abs_err: f64,
    options: *const pqp_search_options,
) -> c_int {
    let search = SearchArg::Options(options);
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { distance_query(r, (R1, T1, m1), (R2, T2, m2), rel_err, abs_err, search) }
}

/// The body of pqp_distance and pqp_distance_search, which differ in how they give the search.
///
/// # Safety
/// As the entry points': every pointer NULL or valid as the header requires.
unsafe fn distance_query(
    r: *mut pqp_distance_result,
    one: PosedModel,
    two: PosedModel,
    rel_err: f64,
    abs_err: f64,
    search: SearchArg,
) -> c_int {
    // SAFETY: the pointers are as pair_query requires (this function's contract).
    unsafe {
        pair_query(r, one, two, search, |r, q| {
            let options = DistanceOptions {
                rel_err,
                abs_err,
                search: q.search,
            };
            distance_into(&mut r.result, q.m1, &q.pose1, q.m2, &q.pose2, &options)
        })
    }
}

/// The default search options: PQP_SEARCH_AUTO (priority-directed for distance, depth-first for
/// tolerance), a queue of 1024 pairs, triangle caching (what pqp_distance and pqp_tolerance use).
///
/// @return the options, to adjust and pass to pqp_distance_search or pqp_tolerance_search.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub extern "C" fn pqp_search_options_default() -> pqp_search_options {
    boundary(DEFAULT_SEARCH_OPTIONS, || {}, || DEFAULT_SEARCH_OPTIONS)
}

/// The distance the last pqp_distance on r found.
///
/// With error bounds rel_err and abs_err (abs_err > 0): true <= distance <=
/// min(true * (1 + rel_err), true + abs_err); exact when abs_err is 0. 0 when the models touch or
/// overlap.
///
/// @param r  the result, or NULL.
/// @return the distance; +infinity before any query; NaN if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_distance(r: *const pqp_distance_result) -> f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, f64::NAN, |r| r.result.distance) }
}

/// The closest point on model 1 found by the last pqp_distance on r, in model 1's frame.
///
/// When the models overlap it is a point common to both models (p1 and p2 are then the same point
/// in world coordinates).
///
/// @param r  the result, or NULL.
/// @return 3 doubles (x, y, z), owned by r and valid until r is modified or destroyed; (0, 0, 0)
///         before any query; NULL if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_p1(r: *const pqp_distance_result) -> *const f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, ptr::null(), |r| r.result.p1.as_ptr()) }
}

/// The closest point on model 2 found by the last pqp_distance on r, in model 2's frame.
///
/// @param r  the result, or NULL.
/// @return 3 doubles (x, y, z), owned by r and valid until r is modified or destroyed; (0, 0, 0)
///         before any query; NULL if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_p2(r: *const pqp_distance_result) -> *const f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, ptr::null(), |r| r.result.p2.as_ptr()) }
}

/// Whether the last pqp_distance on r found the models touching or overlapping (distance 0).
///
/// @param r  the result, or NULL.
/// @return 1 if they touch or overlap, else 0 (also before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_overlap(r: *const pqp_distance_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| c_int::from(r.result.overlap)) }
}

/// The id of model 1's triangle of the closest (or, when overlapping, an intersecting) triangle
/// pair found by the last pqp_distance on r.
///
/// @param r  the result, or NULL.
/// @return the id given to pqp_model_add_tri; -1 before any query or if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_id1(r: *const pqp_distance_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, -1, |r| r.result.id1) }
}

/// The id of model 2's triangle of the closest (or, when overlapping, an intersecting) triangle
/// pair found by the last pqp_distance on r.
///
/// @param r  the result, or NULL.
/// @return the id given to pqp_model_add_tri; -1 before any query or if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_id2(r: *const pqp_distance_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, -1, |r| r.result.id2) }
}

/// The triangles of the closest (or, when overlapping, an intersecting) triangle pair found by the
/// last pqp_distance on r, by their positions in the order added: indices into pqp_model_tris of
/// each model (what PQP 1.3's last_tri pointed at). They name the same triangles as
/// pqp_distance_result_id1 and pqp_distance_result_id2.
///
/// @param r   the result.
/// @param t1  receives model 1's triangle: 0 for the first triangle added to it, and so on; -1
///            before any query (r holds no pair then).
/// @param t2  receives model 2's triangle, likewise.
/// @return PQP_OK (also before any query, with -1 in both); PQP_ERR_NULL_POINTER if r, t1 or t2 is
///         NULL (nothing is written); PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_triangles(
    r: *const pqp_distance_result,
    t1: *mut c_int,
    t2: *mut c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { write_triangles(r, t1, t2, |r| (r.result.tri1, r.result.tri2)) }
}

/// The number of bounding-volume distance tests the last pqp_distance on r performed.
///
/// @param r  the result, or NULL.
/// @return the count (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_num_bv_tests(r: *const pqp_distance_result) -> i64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| count(r.result.stats.bv_tests)) }
}

/// The number of triangle-pair distance tests the last pqp_distance on r performed.
///
/// @param r  the result, or NULL.
/// @return the count (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_num_tri_tests(r: *const pqp_distance_result) -> i64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| count(r.result.stats.tri_tests)) }
}

/// The wall-clock time of the last pqp_distance on r.
///
/// @param r  the result, or NULL.
/// @return seconds (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_result_query_time_secs(r: *const pqp_distance_result) -> f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0.0, |r| r.result.stats.query_time_secs) }
}
