//! Refit: new coordinates for a built model's triangles (pqp_model_refit).

use super::{deref_mut, pqp_model, status};
use crate::error::Error;

/// Moves the triangles of a built model and refits its bounding-volume hierarchy, without
/// rebuilding it: for meshes that deform (cloth, soft bodies, animated characters) and keep their
/// triangles and ids.
///
/// Every triangle keeps its id and its place in the hierarchy; each volume keeps the frame it was
/// built with and gets new extents around its children, bottom-up, in O(n) (4 to 8 times faster
/// than pqp_model_end; see BENCHMARKS.md, Refit). Every query stays exact after a refit. The
/// volumes are looser than a rebuild's, and queries do more work: 1.2 to 2.5 times a rebuilt
/// model's when the mesh stretches (an inflating sphere), up to 8 times for distance queries when
/// its patches turn (a bending sheet; collision stayed within 1.4 times). When to rebuild instead
/// (pqp_model_begin, pqp_model_add_tri, pqp_model_end): when the queries after each deformation
/// are many (a rebuild of an 80,000-triangle bending sheet paid back after about 600 distance
/// queries), or when the queries' bound-test counts (pqp_distance_result_num_bv_tests) reach
/// about twice what they were after the last build.
///
/// Distance and tolerance results that cached m's old shape (closest pairs, search fronts) ignore
/// the cache on their next query. Arrays from pqp_model_tris and pqp_model_bvs (and their float
/// forms) are invalid after a successful refit: ask again.
///
/// @param m          the model (built).
/// @param triangles  9 * num_tris doubles: for each triangle, in the order the triangles were added,
///                   its new p1, p2 and p3 (x, y, z each).
/// @param num_tris   the number of triangles; must be the model's (pqp_model_num_tris).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m or triangles is NULL; PQP_ERR_UNPROCESSED_MODEL if m is
///         not built; PQP_ERR_INVALID_ARGUMENT if num_tris is not the model's count;
///         PQP_ERR_NOT_A_TRIANGLE_MESH if m holds a primitive (pqp_model_set_sphere, ...);
///         PQP_ERR_NONFINITE_COORDINATE if a coordinate is NaN, infinite or larger than 1e150 in
///         magnitude; PQP_ERR_MODEL_OUT_OF_MEMORY if the new arrays could not be allocated;
///         PQP_ERR_INTERNAL on an internal fault. On any error m is unchanged.
/// Thread safety: as the build calls, must not run concurrently with any other call using m
///                (queries included).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_refit(
    m: *mut pqp_model,
    triangles: *const f64,
    num_tris: usize,
) -> std::ffi::c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = deref_mut(m)?;
            if triangles.is_null() {
                return Err(Error::NullPointer);
            }
            let n = m.model.bvh()?.num_tris();
            if num_tris != n {
                return Err(Error::InvalidArgument);
            }
            // SAFETY: triangles points to 9 * num_tris doubles (the caller's contract), and
            // num_tris is the model's count, at most i32::MAX, so the length does not overflow.
            let coords = std::slice::from_raw_parts(triangles.cast::<[[f64; 3]; 3]>(), n);
            m.model.refit(coords)?;
            m.view.refitted();
            Ok(())
        })
    }
}
