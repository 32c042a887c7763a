//! Building convex models (from points, triangles or polygons) and freeing them.

use super::super::{PQP_ERR_INTERNAL, boundary, code, destroy_handle, into_handle, read_doubles};
use super::*;
use crate::convex::MAX_POINTS;
use crate::error::Error;
use std::ptr;

/// A count from C: >= 0.
fn length(n: c_int) -> Result<usize, Error> {
    usize::try_from(n).map_err(|_| Error::InvalidArgument)
}

/// A count from C, `0..=limit`, else `Err(InvalidArgument)`: checked before anything is allocated
/// or read, so that a count past the documented limit never reads past the caller's array.
fn length_at_most(n: c_int, limit: usize) -> Result<usize, Error> {
    length(n).and_then(|n| {
        if n > limit {
            Err(Error::InvalidArgument)
        } else {
            Ok(n)
        }
    })
}

/// Copies `n` points (3 doubles each) from C: `Err(InvalidArgument)` for `n < 0` or
/// `n > MAX_POINTS` (2^30), before anything is allocated or read.
///
/// # Safety
/// `xyz` is NULL or points to `3 n` readable doubles.
unsafe fn read_points(xyz: *const f64, n: c_int) -> Result<Vec<[f64; 3]>, Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if xyz.is_null() {
            return Err(Error::NullPointer);
        }
        let n = length_at_most(n, MAX_POINTS)?;
        let mut out = Vec::new();
        out.try_reserve_exact(n)
            .map_err(|_| Error::ModelOutOfMemory)?;
        for i in 0..n {
            out.push(read_doubles::<3>(xyz.add(3 * i))?);
        }
        Ok(out)
    }
}

/// Copies `n` non-negative ints from C as indices or counts.
///
/// # Safety
/// `p` is NULL or points to `n` readable ints.
unsafe fn read_indices(p: *const c_int, n: usize) -> Result<Vec<u32>, Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if p.is_null() {
            return Err(Error::NullPointer);
        }
        let mut out = Vec::new();
        out.try_reserve_exact(n)
            .map_err(|_| Error::ModelOutOfMemory)?;
        for i in 0..n {
            let v = p.add(i).read_unaligned();
            out.push(u32::try_from(v).map_err(|_| Error::InvalidArgument)?);
        }
        Ok(out)
    }
}

/// The body of the pqp_convex_model_from_ functions, inside the boundary (a fault leaves NULL in
/// `out`): builds a model with `make` and hands it to C through `out` (NULL there on any error).
///
/// # Safety
/// `out` is NULL or points to a writable `pqp_convex_model *`.
unsafe fn create(
    out: *mut *mut pqp_convex_model,
    make: impl FnOnce() -> Result<ConvexModel, Error>,
) -> c_int {
    let body = || -> Result<(), Error> {
        if out.is_null() {
            return Err(Error::NullPointer);
        }
        // SAFETY: `out` is not NULL, so it is writable (this function's contract).
        unsafe { out.write(ptr::null_mut()) };
        let h = into_handle(pqp_convex_model { model: make()? });
        if h.is_null() {
            return Err(Error::ModelOutOfMemory);
        }
        // SAFETY: as above.
        unsafe { out.write(h) };
        Ok(())
    };
    // SAFETY: `out` is NULL or writable (this function's contract).
    boundary(
        PQP_ERR_INTERNAL,
        || unsafe { clear_out(out) },
        || code(body()),
    )
}

/// After an internal fault in a create function: C sees NULL. (A handle is written only as the
/// last step, so none can have been made and lost.)
///
/// # Safety
/// As [`create`].
unsafe fn clear_out(out: *mut *mut pqp_convex_model) {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if !out.is_null() {
            out.write(ptr::null_mut());
        }
    }
}

/// Creates a convex model: the convex hull of a point set.
///
/// The hull is exact: duplicate, coplanar and nearly coplanar points are fine (every decision is
/// an exact orientation sign on the input doubles). Coplanar faces are merged into convex polygons
/// and only the hull's corners become vertices (pqp_convex_model_vertex_source maps them back to
/// the input).
///
/// @param out  receives the new model (free it with pqp_convex_model_destroy), or NULL on any
///             error.
/// @param xyz  the points, 3 doubles each (x, y, z in the model's frame), n * 3 doubles in all.
/// @param n    the number of points, >= 0.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if out or xyz is NULL (even when n is 0);
///         PQP_ERR_INVALID_ARGUMENT if n < 0 or n > 2^30 (checked before xyz is read);
///         PQP_ERR_NONFINITE_COORDINATE if a coordinate is NaN, infinite or larger than 1e150 in
///         magnitude; PQP_ERR_DEGENERATE_POINTS if the points do not span a volume (n = 0, fewer
///         than four distinct points, all collinear or all coplanar); PQP_ERR_MODEL_OUT_OF_MEMORY
///         if the model could not be allocated; PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_from_points(
    out: *mut *mut pqp_convex_model,
    xyz: *const f64,
    n: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { create(out, || ConvexModel::from_points(&read_points(xyz, n)?)) }
}

/// Creates a convex model from a closed convex triangle mesh, verified exactly.
///
/// The mesh must be closed and consistently oriented (each edge used once in each direction, faces
/// counter-clockwise seen from outside), use every vertex, be a topological sphere and be convex
/// (no vertex above the plane of any triangle). Coplanar neighbouring triangles are merged into
/// polygons. A mesh convex only up to rounding is refused: build it with
/// pqp_convex_model_from_points instead.
///
/// @param out            receives the new model, or NULL on any error.
/// @param xyz            the vertices, 3 doubles each, num_vertices * 3 doubles in all.
/// @param num_vertices   the number of vertices, >= 0.
/// @param triangles      vertex indices, 3 per triangle, num_triangles * 3 ints in all.
/// @param num_triangles  the number of triangles, >= 0.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if out, xyz or triangles is NULL;
///         PQP_ERR_INVALID_ARGUMENT if a count is negative or too large (num_vertices > 2^30 or
///         num_triangles > 2 num_vertices: a closed mesh has 2 num_vertices - 4; both checked
///         before any array is read), or an index is negative or >= num_vertices;
///         PQP_ERR_NONFINITE_COORDINATE for a NaN, infinite or huge coordinate;
///         PQP_ERR_INVALID_CONVEX_MESH if the mesh is not a closed convex polyhedron (open,
///         inconsistently oriented, inside out, not convex, flat, an unused vertex, fewer than 4
///         vertices or faces); PQP_ERR_MODEL_OUT_OF_MEMORY; PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_from_triangles(
    out: *mut *mut pqp_convex_model,
    xyz: *const f64,
    num_vertices: c_int,
    triangles: *const c_int,
    num_triangles: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        let make = || {
            let v = read_points(xyz, num_vertices)?;
            // A closed triangle mesh on V vertices has 2 V - 4 triangles: more than 2 V is too
            // many, refused before the triangles are read.
            let nt = length_at_most(num_triangles, 2 * v.len())?;
            let n = nt.checked_mul(3).ok_or(Error::InvalidArgument)?;
            let idx = read_indices(triangles, n)?;
            let counts = vec![3u32; nt];
            ConvexModel::from_polygons(&v, &counts, &idx)
        };
        create(out, make)
    }
}

/// Creates a convex model from a closed convex polyhedral mesh (polygon faces), verified exactly.
///
/// Each face has as many vertices as its entry in counts, listed counter-clockwise seen from
/// outside; the faces' index lists are concatenated in indices. Each face must be exactly planar
/// and strictly convex; the rest is as for pqp_convex_model_from_triangles.
///
/// @param out           receives the new model, or NULL on any error.
/// @param xyz           the vertices, 3 doubles each, num_vertices * 3 doubles in all.
/// @param num_vertices  the number of vertices, >= 0.
/// @param counts        the number of vertices of each face (each >= 3), num_faces ints.
/// @param num_faces     the number of faces, >= 0.
/// @param indices       the faces' vertex indices, concatenated, num_indices ints.
/// @param num_indices   the number of indices: must equal the sum of counts.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if out, xyz, counts or indices is NULL;
///         PQP_ERR_INVALID_ARGUMENT if a count is negative or too large (num_vertices > 2^30,
///         num_faces > 2 num_vertices or num_indices > 6 num_vertices: a closed polyhedron has at
///         most 2 num_vertices - 4 faces and 6 num_vertices - 12 indices; checked before the
///         arrays they count are read), a face count is below 3, the counts do not sum to
///         num_indices, or an index is negative or >= num_vertices;
///         PQP_ERR_NONFINITE_COORDINATE for a NaN, infinite or huge coordinate;
///         PQP_ERR_INVALID_CONVEX_MESH if the mesh is not a closed convex polyhedron (as for
///         pqp_convex_model_from_triangles, or a face not planar or not strictly convex);
///         PQP_ERR_MODEL_OUT_OF_MEMORY; PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_from_polygons(
    out: *mut *mut pqp_convex_model,
    xyz: *const f64,
    num_vertices: c_int,
    counts: *const c_int,
    num_faces: c_int,
    indices: *const c_int,
    num_indices: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        let make = || {
            let v = read_points(xyz, num_vertices)?;
            // A closed polyhedron on V vertices has at most 2 V - 4 faces and 6 V - 12 indices
            // (twice its edges): more than 2 V faces or 6 V indices are too many, refused before
            // they are read.
            let counts = read_indices(counts, length_at_most(num_faces, 2 * v.len())?)?;
            if indices.is_null() {
                return Err(Error::NullPointer);
            }
            let ni = length_at_most(num_indices, 6 * v.len())?;
            let total: u64 = counts.iter().map(|&c| u64::from(c)).sum();
            if total != ni as u64 {
                return Err(Error::InvalidArgument);
            }
            let idx = read_indices(indices, ni)?;
            ConvexModel::from_polygons(&v, &counts, &idx)
        };
        create(out, make)
    }
}

/// Frees a convex model.
///
/// @param m  a model from a pqp_convex_model_from_ function, or NULL (then nothing happens). It
///           must not be used afterwards. Caches that saw it may be kept: they ignore it.
/// Thread safety: must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_destroy(m: *mut pqp_convex_model) {
    // SAFETY: m is NULL or a live handle of its kind, used by no other call (the caller's contract).
    unsafe { destroy_handle(m) }
}
