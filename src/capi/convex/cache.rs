//! The per-pair warm-start cache.

use super::super::{deref_mut, destroy_handle, new_handle, status};
use super::*;

/// Creates an empty pair cache (the first query with it starts cold).
///
/// @return a new cache, to be freed with pqp_convex_cache_destroy; NULL only if memory could not
///         be allocated.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub extern "C" fn pqp_convex_cache_create() -> *mut pqp_convex_cache {
    new_handle::<pqp_convex_cache>()
}

/// Frees a pair cache.
///
/// @param c  a cache from pqp_convex_cache_create, or NULL (then nothing happens).
/// Thread safety: must not run concurrently with any other call using c.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_cache_destroy(c: *mut pqp_convex_cache) {
    // SAFETY: c is NULL or a live handle of its kind, used by no other call (the caller's contract).
    unsafe { destroy_handle(c) }
}

/// Empties a pair cache: the next query with it starts cold.
///
/// @param c  the cache.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if c is NULL; PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: must not run concurrently with any other call using c.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_cache_clear(c: *mut pqp_convex_cache) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            deref_mut(c)?.cache.clear();
            Ok(())
        })
    }
}
