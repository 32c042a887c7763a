//! The result's getters, and how a query's answer fills the result.

use super::super::{count, getter};
use super::*;
use crate::convex::{ConvexDistance, ConvexPenetration};
use std::ptr;

impl pqp_convex_result {
    pub(super) fn from_distance(d: &ConvexDistance) -> Self {
        pqp_convex_result {
            distance: d.distance,
            p1: arr(&d.p1),
            p2: arr(&d.p2),
            intersecting: d.intersecting,
            features: Some((d.feature1, d.feature2)),
            stats: d.stats,
            ..Default::default()
        }
    }

    pub(super) fn from_penetration(p: &ConvexPenetration) -> Self {
        pqp_convex_result {
            depth: p.depth,
            normal: arr(&p.normal),
            deepest: [arr(&p.p1), arr(&p.p2)],
            ..Self::from_distance(&p.closest)
        }
    }
}

/// The distance the last query on r found (0 when the models touch or overlap).
///
/// @param r  the result, or NULL.
/// @return the distance; +infinity before any query; NaN if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_distance(r: *const pqp_convex_result) -> f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, f64::NAN, |r| r.distance) }
}

/// The closest point on model 1 found by the last query on r, in model 1's frame. When the models
/// intersect, a point common to both (p1 and p2 are then the same world point).
///
/// @param r  the result, or NULL.
/// @return 3 doubles, owned by r and valid until r is modified or destroyed; (0, 0, 0) before any
///         query; NULL if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_p1(r: *const pqp_convex_result) -> *const f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, ptr::null(), |r| r.p1.as_ptr()) }
}

/// The closest point on model 2 found by the last query on r, in model 2's frame.
///
/// @param r  the result, or NULL.
/// @return 3 doubles, owned by r and valid until r is modified or destroyed; (0, 0, 0) before any
///         query; NULL if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_p2(r: *const pqp_convex_result) -> *const f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, ptr::null(), |r| r.p2.as_ptr()) }
}

/// Whether the last query on r found the models touching or overlapping.
///
/// @param r  the result, or NULL.
/// @return 1 if they touch or overlap, else 0 (also before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_intersecting(r: *const pqp_convex_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| c_int::from(r.intersecting)) }
}

/// The kind of model 1's feature in the final feature pair of the last query on r (the closest
/// feature when the models are apart; it contains p1).
///
/// @param r  the result, or NULL.
/// @return PQP_CONVEX_VERTEX, PQP_CONVEX_EDGE or PQP_CONVEX_FACE; -1 before any query or if r is
///         NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_feature1_kind(r: *const pqp_convex_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, -1, |r| r.features.map_or(-1, |f| f.0.kind as c_int)) }
}

/// The index of model 1's feature in the final feature pair of the last query on r, among model
/// 1's features of its kind (see pqp_convex_model_vertex, _edge, _face).
///
/// @param r  the result, or NULL.
/// @return the index; -1 before any query or if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_feature1_index(r: *const pqp_convex_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, -1, |r| r.features.map_or(-1, |f| f.0.index as c_int)) }
}

/// The kind of model 2's feature in the final feature pair of the last query on r (it contains p2
/// when the models are apart).
///
/// @param r  the result, or NULL.
/// @return PQP_CONVEX_VERTEX, PQP_CONVEX_EDGE or PQP_CONVEX_FACE; -1 before any query or if r is
///         NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_feature2_kind(r: *const pqp_convex_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, -1, |r| r.features.map_or(-1, |f| f.1.kind as c_int)) }
}

/// The index of model 2's feature in the final feature pair of the last query on r.
///
/// @param r  the result, or NULL.
/// @return the index; -1 before any query or if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_feature2_index(r: *const pqp_convex_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, -1, |r| r.features.map_or(-1, |f| f.1.index as c_int)) }
}

/// The penetration depth found by the last pqp_convex_penetration on r: the length of the smallest
/// translation of model 2 that separates the models (0 when they are apart or only touch).
///
/// @param r  the result, or NULL.
/// @return the depth; NaN before any query, after pqp_convex_distance (which does not compute it),
///         or if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_depth(r: *const pqp_convex_result) -> f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, f64::NAN, |r| r.depth) }
}

/// The penetration direction found by the last pqp_convex_penetration on r: the unit vector, in
/// world coordinates, along which to move model 2 by the depth to separate it from model 1. When
/// the models are apart, the direction from model 1's closest point to model 2's.
///
/// @param r  the result, or NULL.
/// @return 3 doubles, owned by r and valid until r is modified or destroyed; (0, 0, 0) before any
///         query, after pqp_convex_distance, or when the models are apart at distance 0; NULL if r
///         is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_normal(r: *const pqp_convex_result) -> *const f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, ptr::null(), |r| r.normal.as_ptr()) }
}

/// The deepest point of model 1 found by the last pqp_convex_penetration on r, in model 1's
/// frame: where model 2, moved out by the depth along the normal, touches model 1. In world
/// coordinates deepest_p1 = deepest_p2 + depth * normal. When apart, model 1's closest point.
///
/// @param r  the result, or NULL.
/// @return 3 doubles, owned by r and valid until r is modified or destroyed; (0, 0, 0) before any
///         query or after pqp_convex_distance; NULL if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_deepest_p1(r: *const pqp_convex_result) -> *const f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, ptr::null(), |r| r.deepest[0].as_ptr()) }
}

/// The deepest point of model 2 found by the last pqp_convex_penetration on r, in model 2's frame
/// (see pqp_convex_result_deepest_p1). When apart, model 2's closest point.
///
/// @param r  the result, or NULL.
/// @return 3 doubles, owned by r and valid until r is modified or destroyed; (0, 0, 0) before any
///         query or after pqp_convex_distance; NULL if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_deepest_p2(r: *const pqp_convex_result) -> *const f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, ptr::null(), |r| r.deepest[1].as_ptr()) }
}

/// The number of V-Clip iterations (feature-pair steps) the last query on r took: small and nearly
/// constant under coherent motion with a warm cache.
///
/// @param r  the result, or NULL.
/// @return the count (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_num_iterations(r: *const pqp_convex_result) -> i64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| count(u64::from(r.stats.iterations))) }
}

/// The number of local-minimum escapes (a vertex below a face's plane, resolved by a scan of the
/// polyhedron) the last query on r performed.
///
/// @param r  the result, or NULL.
/// @return the count (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_num_local_minima(r: *const pqp_convex_result) -> i64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| count(u64::from(r.stats.local_minima))) }
}
