//! Self-collision: pqp_self_collide, answered in a collision result.

use super::{
    PQP_ALL_CONTACTS, PQP_ERR_INTERNAL, PQP_FIRST_CONTACT, boundary, code, deref, deref_mut,
    pqp_collide_result, pqp_model, reset,
};
use crate::error::Error;
use crate::query::{ContactMode, self_collide_into};
use std::ffi::c_int;

/// Finds the pairs of distinct triangles of one model that intersect (share a point): crossing,
/// touching and overlapping coplanar all count, as in pqp_collide, each pair once; except that
/// two triangles sharing a vertex or an edge (coordinates exactly equal) are not reported when
/// they meet only in what they share, so a mesh's neighbours are not reported. Identical triangles
/// (the same three vertices) are reported.
///
/// Exactly: two triangles sharing one vertex are reported when the edge of either opposite it
/// meets the other; sharing one edge, when they are coplanar and on the same side of it (one folded
/// onto the other). For triangles with area that is exactly whether they meet beyond what they
/// share. For degenerate triangles (collinear vertices) sharing vertices, and the remaining
/// cases, a pair is reported when the part of either spanned by its vertices not shared meets the
/// other (and does not lie in the shared edge).
///
/// Read the answer with the collision result getters: pqp_collide_result_id1 is the id of the
/// triangle added first, pqp_collide_result_id2 the other's. The model's hierarchy is searched
/// against itself, on axis-aligned boxes of its nodes computed for the call, so a mesh without
/// self-intersections costs about as much as its neighbour pairs (see BENCHMARKS.md,
/// Self-collision).
///
/// @param r     the result to fill (its previous answer is replaced).
/// @param m     the model (built).
/// @param flag  PQP_ALL_CONTACTS to find every pair, PQP_FIRST_CONTACT to stop at the first found.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if r or m is NULL; PQP_ERR_INVALID_ARGUMENT if flag is
///         neither PQP_ALL_CONTACTS nor PQP_FIRST_CONTACT; PQP_ERR_UNPROCESSED_MODEL if m is not
///         built; PQP_ERR_NOT_A_TRIANGLE_MESH if m holds a primitive (pqp_model_set_sphere,
///         ...); PQP_ERR_OUT_OF_MEMORY if the search's boxes (24 bytes per triangle and per
///         inner node, for the duration of the call) cannot be allocated; PQP_ERR_INTERNAL on an
///         internal fault (r is then reset to its freshly created state). On any other error r is
///         left unchanged.
/// Thread safety: any number of queries may use the same model at once from different threads;
///                r must not be used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_self_collide(
    r: *mut pqp_collide_result,
    m: *const pqp_model,
    flag: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        let body = || -> Result<(), Error> {
            let result = deref_mut(r)?;
            let m = deref(m)?;
            let mode = match flag {
                PQP_ALL_CONTACTS => ContactMode::All,
                PQP_FIRST_CONTACT => ContactMode::First,
                _ => return Err(Error::InvalidArgument),
            };
            self_collide_into(&mut result.result, &m.model, mode)
        };
        boundary(PQP_ERR_INTERNAL, || reset(r), || code(body()))
    }
}
