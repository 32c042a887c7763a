//! The result handle and the three queries: pqp_convex_distance, pqp_convex_intersect,
//! pqp_convex_penetration.

#![allow(non_snake_case)] // R1, T1, R2, T2 keep the names the rest of the header uses.

use super::super::{
    PQP_ERR_INTERNAL, boundary, code, deref, deref_mut, destroy_handle, new_handle, read_pose,
    reset, status,
};
use super::*;
use crate::convex::{convex_distance, convex_penetration};
use crate::error::Error;
use crate::math::Pose;

/// Creates an empty convex result (distance +infinity, no feature pair, depth NaN).
///
/// @return a new result, to be freed with pqp_convex_result_destroy; NULL only if memory could not
///         be allocated.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub extern "C" fn pqp_convex_result_create() -> *mut pqp_convex_result {
    new_handle::<pqp_convex_result>()
}

/// Frees a convex result.
///
/// @param r  a result from pqp_convex_result_create, or NULL (then nothing happens).
/// Thread safety: must not run concurrently with any other call using r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_result_destroy(r: *mut pqp_convex_result) {
    // SAFETY: r is NULL or a live handle of its kind, used by no other call (the caller's contract).
    unsafe { destroy_handle(r) }
}

/// The two posed models and the cache of a query, read from C.
struct Query<'a> {
    pose1: Pose,
    m1: &'a ConvexModel,
    pose2: Pose,
    m2: &'a ConvexModel,
    cache: Option<&'a mut ConvexPairCache>,
}

/// # Safety
/// Each pointer is NULL or valid as the header states; `cache` may be NULL (cold start).
unsafe fn query<'a>(
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_convex_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_convex_model,
    cache: *mut pqp_convex_cache,
) -> Result<Query<'a>, Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        Ok(Query {
            pose1: read_pose(R1, T1)?,
            m1: &deref(m1)?.model,
            pose2: read_pose(R2, T2)?,
            m2: &deref(m2)?.model,
            cache: cache.as_mut().map(|c| &mut c.cache),
        })
    }
}

/// The body of pqp_convex_distance and pqp_convex_penetration, inside the boundary (a fault resets
/// `r`): reads the query, and stores what `answer` gives in `r` (left unchanged on an error).
///
/// # Safety
/// As [`query`], and `r` is NULL or a live result no other call uses.
unsafe fn answer_into(
    r: *mut pqp_convex_result,
    (R1, T1, m1): (*const f64, *const f64, *const pqp_convex_model),
    (R2, T2, m2): (*const f64, *const f64, *const pqp_convex_model),
    cache: *mut pqp_convex_cache,
    answer: impl FnOnce(Query<'_>) -> Result<pqp_convex_result, Error>,
) -> c_int {
    let body = || -> Result<(), Error> {
        // SAFETY: every pointer is NULL or valid (this function's contract).
        let (result, q) = unsafe { (deref_mut(r)?, query(R1, T1, m1, R2, T2, m2, cache)?) };
        *result = answer(q)?;
        Ok(())
    };
    // SAFETY: `r` is NULL or a live result (this function's contract).
    boundary(PQP_ERR_INTERNAL, || unsafe { reset(r) }, || code(body()))
}

/// Computes the separation distance of two posed convex models, their closest points and closest
/// feature pair, and whether they intersect (V-Clip).
///
/// Poses are as for pqp_collide (x_world = R x + T, R row by row). The distance is exact up to
/// rounding; when the models touch or overlap it is 0, pqp_convex_result_intersecting reports 1,
/// and p1, p2 are a point common to both. Models closer than the rounding of posing them (64 ulps
/// of the scene's size) count as touching. The search is warm-started from cache (the feature pair
/// the last query on the same two models ended on; near-constant time under coherent motion) and
/// the cache is updated; with cache NULL it starts cold. The search's iterations are bounded; the
/// bound is never reached on valid input (PQP_ERR_INTERNAL if it were).
///
/// @param r       the result to fill (its previous answer is replaced; depth becomes NaN).
/// @param R1, T1  the pose of model 1.
/// @param m1      model 1.
/// @param R2, T2  the pose of model 2.
/// @param m2      model 2 (may be the same model as m1).
/// @param cache   the pair's cache, or NULL for a cold start. A cache last used with other models
///                (or the same models in the other order) is ignored and then refilled.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if r, a pose pointer, m1 or m2 is NULL;
///         PQP_ERR_NONFINITE_POSE if a pose entry is NaN, infinite or larger than 1e150 in
///         magnitude; PQP_ERR_INTERNAL on an internal fault (r is then reset to its freshly created
///         state and the cache is left as it was). On any other error r and cache are unchanged.
/// Thread safety: any number of queries may use the same models at once from different threads;
///                r and cache must not be used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_distance(
    r: *mut pqp_convex_result,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_convex_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_convex_model,
    cache: *mut pqp_convex_cache,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        answer_into(r, (R1, T1, m1), (R2, T2, m2), cache, |q| {
            let d = convex_distance(q.m1, &q.pose1, q.m2, &q.pose2, q.cache)?;
            Ok(pqp_convex_result::from_distance(&d))
        })
    }
}

/// Whether two posed convex models touch or overlap (V-Clip, as pqp_convex_distance).
///
/// @param intersecting  receives 1 if they touch or overlap, else 0 (not written on error).
/// @param R1, T1        the pose of model 1.
/// @param m1            model 1.
/// @param R2, T2        the pose of model 2.
/// @param m2            model 2.
/// @param cache         the pair's cache, or NULL for a cold start (as for pqp_convex_distance).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if intersecting, a pose pointer, m1 or m2 is NULL;
///         PQP_ERR_NONFINITE_POSE for a NaN, infinite or huge pose entry; PQP_ERR_INTERNAL on an
///         internal fault (the cache is then left as it was).
/// Thread safety: any number of queries may use the same models at once from different threads;
///                cache must not be used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_intersect(
    intersecting: *mut c_int,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_convex_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_convex_model,
    cache: *mut pqp_convex_cache,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            if intersecting.is_null() {
                return Err(Error::NullPointer);
            }
            let q = query(R1, T1, m1, R2, T2, m2, cache)?;
            let d = convex_distance(q.m1, &q.pose1, q.m2, &q.pose2, q.cache)?;
            intersecting.write_unaligned(c_int::from(d.intersecting));
            Ok(())
        })
    }
}

/// Computes the penetration depth and direction of two posed convex models: the length and
/// direction of the smallest translation of model 2 that separates it from model 1.
///
/// The depth is exact up to rounding (the minimum over every candidate direction of the Minkowski
/// difference: face normals and edge-edge pairs; cost grows with edges1 * edges2). r also receives
/// everything pqp_convex_distance gives (distance, closest points, features, work), computed at the
/// given poses; when the models are apart the depth is 0 and the normal points from model 1's
/// closest point to model 2's.
///
/// @param r       the result to fill (its previous answer is replaced).
/// @param R1, T1  the pose of model 1.
/// @param m1      model 1.
/// @param R2, T2  the pose of model 2.
/// @param m2      model 2.
/// @param cache   the pair's cache, or NULL for a cold start (as for pqp_convex_distance).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if r, a pose pointer, m1 or m2 is NULL;
///         PQP_ERR_NONFINITE_POSE for a NaN, infinite or huge pose entry; PQP_ERR_INTERNAL on an
///         internal fault (r is then reset to its freshly created state). On any other error r and
///         cache are unchanged.
/// Thread safety: any number of queries may use the same models at once from different threads;
///                r and cache must not be used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_penetration(
    r: *mut pqp_convex_result,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_convex_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_convex_model,
    cache: *mut pqp_convex_cache,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        answer_into(r, (R1, T1, m1), (R2, T2, m2), cache, |q| {
            let p = convex_penetration(q.m1, &q.pose1, q.m2, &q.pose2, q.cache)?;
            Ok(pqp_convex_result::from_penetration(&p))
        })
    }
}
