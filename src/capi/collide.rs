//! Collision: the result handle, its getters, and pqp_collide.
//!
//! Getters never fail: given NULL they return a fallback value (stated on each).

#![allow(non_snake_case)] // R1, T1, R2, T2 keep PQP's names, which the header shows.

use super::{
    PQP_ALL_CONTACTS, PQP_ERR_INTERNAL, PQP_FIRST_CONTACT, boundary, code, count, deref, deref_mut,
    destroy_handle, getter, new_handle, pqp_model, read_pose, reset,
};
use crate::error::Error;
use crate::query::{CollideResult, ContactMode, ContactPair, collide_into};
use std::ffi::c_int;
use std::mem::{align_of, offset_of, size_of};
use std::ptr;

/// A colliding triangle pair: the id of the triangle of model 1 and of model 2, as given to
/// pqp_model_add_tri.
#[allow(non_camel_case_types)]
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct pqp_contact_pair {
    /// Id of the triangle of model 1.
    pub id1: c_int,
    /// Id of the triangle of model 2.
    pub id2: c_int,
}

// `pqp_collide_result_pairs` hands out the core's pair array as `pqp_contact_pair`s.
const _: () = {
    assert!(size_of::<ContactPair>() == size_of::<pqp_contact_pair>());
    assert!(align_of::<ContactPair>() == align_of::<pqp_contact_pair>());
    assert!(offset_of!(ContactPair, id1) == offset_of!(pqp_contact_pair, id1));
    assert!(offset_of!(ContactPair, id2) == offset_of!(pqp_contact_pair, id2));
};

/// The answer of pqp_collide (opaque). Reuse one for many queries to reuse its storage.
#[allow(non_camel_case_types)]
#[derive(Default)]
pub struct pqp_collide_result {
    pub(crate) result: CollideResult,
}

/// Creates an empty collision result.
///
/// @return a new result, to be freed with pqp_collide_result_destroy; NULL only if memory could
///         not be allocated.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub extern "C" fn pqp_collide_result_create() -> *mut pqp_collide_result {
    new_handle::<pqp_collide_result>()
}

/// Frees a collision result.
///
/// @param r  a result from pqp_collide_result_create, or NULL (then nothing happens).
/// Thread safety: must not run concurrently with any other call using r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_destroy(r: *mut pqp_collide_result) {
    // SAFETY: r is NULL or a live handle of its kind, used by no other call (the caller's contract).
    unsafe { destroy_handle(r) }
}

/// Finds the colliding triangle pairs of two posed models (PQP_Collide).
///
/// A model's pose maps its coordinates to the world: x_world = R * x_model + T, with R given as 9
/// doubles row by row (R[3*i+j] is row i, column j; the columns are the model's axes in world
/// coordinates, exactly PQP's `R[3][3]`, so C code passes `&R[0][0]`) and T as 3 doubles. Two triangles
/// collide when they share a point: crossing, touching at a vertex or an edge, and overlapping
/// coplanar all count. Each colliding pair is reported once.
///
/// @param r       the result to fill (its previous answer is replaced).
/// @param R1, T1  the pose of model 1.
/// @param m1      model 1 (built).
/// @param R2, T2  the pose of model 2.
/// @param m2      model 2 (built; may be the same model as m1).
/// @param flag    PQP_ALL_CONTACTS to find every colliding pair, PQP_FIRST_CONTACT to stop at the
///                first found.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_INVALID_ARGUMENT if flag
///         is neither PQP_ALL_CONTACTS nor PQP_FIRST_CONTACT; PQP_ERR_UNPROCESSED_MODEL if a model
///         is not built; PQP_ERR_NONFINITE_POSE if an entry of R1, T1, R2 or T2 is NaN, infinite
///         or larger than 1e150 in magnitude; PQP_ERR_INTERNAL on an internal fault (r is then
///         reset to its freshly created state). On any other error r is left unchanged.
/// Thread safety: any number of queries may use the same models at once from different threads;
///                r must not be used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide(
    r: *mut pqp_collide_result,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_model,
    flag: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        let body = || -> Result<(), Error> {
            let result = deref_mut(r)?;
            let (pose1, m1) = (read_pose(R1, T1)?, deref(m1)?);
            let (pose2, m2) = (read_pose(R2, T2)?, deref(m2)?);
            let mode = match flag {
                PQP_ALL_CONTACTS => ContactMode::All,
                PQP_FIRST_CONTACT => ContactMode::First,
                _ => return Err(Error::InvalidArgument),
            };
            collide_into(
                &mut result.result,
                &m1.model,
                &pose1,
                &m2.model,
                &pose2,
                mode,
            )
        };
        boundary(PQP_ERR_INTERNAL, || reset(r), || code(body()))
    }
}

/// Whether the last pqp_collide on r found a colliding triangle pair.
///
/// @param r  the result, or NULL.
/// @return 1 if colliding, else 0 (also before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_colliding(r: *const pqp_collide_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| c_int::from(r.result.colliding())) }
}

/// The number of colliding triangle pairs the last pqp_collide on r found (at most 1 with
/// PQP_FIRST_CONTACT).
///
/// @param r  the result, or NULL.
/// @return the count (0 before any query or after pqp_collide_result_free_pairs); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_num_pairs(r: *const pqp_collide_result) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe {
        getter(r, 0, |r| {
            c_int::try_from(r.result.num_pairs()).unwrap_or(c_int::MAX)
        })
    }
}

/// One colliding pair's id for model 1 (PQP's Id1).
///
/// @param r  the result, or NULL.
/// @param k  the pair's index, 0 <= k < pqp_collide_result_num_pairs(r).
/// @return the id of the pair's triangle of model 1; -1 if r is NULL or k is out of range.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_id1(r: *const pqp_collide_result, k: c_int) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, -1, |r| pair(r, k).map_or(-1, |p| p.id1)) }
}

/// One colliding pair's id for model 2 (PQP's Id2).
///
/// @param r  the result, or NULL.
/// @param k  the pair's index, 0 <= k < pqp_collide_result_num_pairs(r).
/// @return the id of the pair's triangle of model 2; -1 if r is NULL or k is out of range.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_id2(r: *const pqp_collide_result, k: c_int) -> c_int {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, -1, |r| pair(r, k).map_or(-1, |p| p.id2)) }
}

/// Pair `k` of a collision result, if it exists.
fn pair(r: &pqp_collide_result, k: c_int) -> Option<ContactPair> {
    let k = usize::try_from(k).ok()?;
    r.result.pairs().get(k).copied()
}

/// All colliding pairs of the last pqp_collide on r, as an array.
///
/// @param r  the result, or NULL.
/// @return pqp_collide_result_num_pairs(r) pairs, each once, in no particular order; NULL if there
///         are none or r is NULL. The array belongs to r and stays valid until the next call that
///         modifies r (pqp_collide, pqp_collide_result_free_pairs, pqp_collide_result_destroy).
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_pairs(
    r: *const pqp_collide_result,
) -> *const pqp_contact_pair {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            ptr::null(),
            || {},
            || match deref(r) {
                Ok(r) if r.result.num_pairs() > 0 => {
                    r.result.pairs().as_ptr().cast::<pqp_contact_pair>()
                }
                _ => ptr::null(),
            },
        )
    }
}

/// Frees a collision result's pair list (PQP's FreePairsList); the result then reports no pairs.
///
/// @param r  the result, or NULL (then nothing happens).
/// Thread safety: must not run concurrently with any other call using r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_free_pairs(r: *mut pqp_collide_result) {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            (),
            || {},
            || {
                if let Ok(r) = deref_mut(r) {
                    r.result.free_pairs();
                }
            },
        )
    }
}

/// The number of bounding-volume overlap tests the last pqp_collide on r performed.
///
/// @param r  the result, or NULL.
/// @return the count (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_num_bv_tests(r: *const pqp_collide_result) -> i64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| count(r.result.stats.bv_tests)) }
}

/// The number of triangle-pair overlap tests the last pqp_collide on r performed.
///
/// @param r  the result, or NULL.
/// @return the count (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_num_tri_tests(r: *const pqp_collide_result) -> i64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0, |r| count(r.result.stats.tri_tests)) }
}

/// The wall-clock time of the last pqp_collide on r.
///
/// @param r  the result, or NULL.
/// @return seconds (0 before any query); 0 if r is NULL.
/// Thread safety: may run concurrently with other getters on r, not with calls that modify r.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_result_query_time_secs(r: *const pqp_collide_result) -> f64 {
    // SAFETY: r is NULL or a live result that no other call modifies meanwhile (the caller's contract).
    unsafe { getter(r, 0.0, |r| r.result.stats.query_time_secs) }
}
