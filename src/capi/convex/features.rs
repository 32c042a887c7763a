//! A convex model's features: counts, vertices, edges and faces.

use super::super::{boundary, deref, status};
use super::*;
use crate::error::Error;

/// A model's count of one feature kind as a C int (models have at most 2^30 vertices, so the
/// counts fit).
unsafe fn feature_count(
    m: *const pqp_convex_model,
    f: impl FnOnce(&ConvexModel) -> usize,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { deref(m).map_or(0, |m| c_int::try_from(f(&m.model)).unwrap_or(c_int::MAX)) }
}

/// The number of vertices of a convex model (the hull's corners).
///
/// @param m  the model, or NULL.
/// @return the count; 0 if m is NULL.
/// Thread safety: may run concurrently with queries and other getters on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_num_vertices(m: *const pqp_convex_model) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { boundary(0, || {}, || feature_count(m, ConvexModel::num_vertices)) }
}

/// The number of edges of a convex model.
///
/// @param m  the model, or NULL.
/// @return the count; 0 if m is NULL.
/// Thread safety: may run concurrently with queries and other getters on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_num_edges(m: *const pqp_convex_model) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { boundary(0, || {}, || feature_count(m, ConvexModel::num_edges)) }
}

/// The number of faces of a convex model (coplanar triangles merged: each face is a strictly
/// convex polygon, and vertices - edges + faces = 2).
///
/// @param m  the model, or NULL.
/// @return the count; 0 if m is NULL.
/// Thread safety: may run concurrently with queries and other getters on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_num_faces(m: *const pqp_convex_model) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { boundary(0, || {}, || feature_count(m, ConvexModel::num_faces)) }
}

/// An index from C checked against a count.
fn index(i: c_int, n: usize) -> Result<usize, Error> {
    usize::try_from(i)
        .ok()
        .filter(|&i| i < n)
        .ok_or(Error::InvalidArgument)
}

/// Copies a vertex of a convex model.
///
/// @param m    the model.
/// @param i    the vertex index, 0 <= i < pqp_convex_model_num_vertices(m).
/// @param xyz  receives 3 doubles: the vertex in the model's frame (an input point, bit for bit).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m or xyz is NULL; PQP_ERR_INVALID_ARGUMENT if i is out
///         of range (xyz is then not written); PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may run concurrently with queries and other getters on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_vertex(
    m: *const pqp_convex_model,
    i: c_int,
    xyz: *mut f64,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = &deref(m)?.model;
            if xyz.is_null() {
                return Err(Error::NullPointer);
            }
            let v = m.vertex(index(i, m.num_vertices())?);
            xyz.cast::<[f64; 3]>().write_unaligned(arr(&v));
            Ok(())
        })
    }
}

/// The input point a vertex of a convex model came from.
///
/// @param m  the model, or NULL.
/// @param i  the vertex index.
/// @return the index of the point (for pqp_convex_model_from_points, the first of equal points)
///         or mesh vertex it is; -1 if m is NULL or i is out of range.
/// Thread safety: may run concurrently with queries and other getters on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_vertex_source(
    m: *const pqp_convex_model,
    i: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            -1,
            || {},
            || {
                let Ok(m) = deref(m) else { return -1 };
                index(i, m.model.num_vertices())
                    .ok()
                    .and_then(|i| c_int::try_from(m.model.vertex_source(i)).ok())
                    .unwrap_or(-1)
            },
        )
    }
}

/// The end vertices of an edge of a convex model.
///
/// @param m     the model.
/// @param i     the edge index, 0 <= i < pqp_convex_model_num_edges(m).
/// @param tail  receives one end's vertex index.
/// @param head  receives the other end's vertex index.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m, tail or head is NULL; PQP_ERR_INVALID_ARGUMENT if i
///         is out of range (nothing is written); PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may run concurrently with queries and other getters on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_edge(
    m: *const pqp_convex_model,
    i: c_int,
    tail: *mut c_int,
    head: *mut c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = &deref(m)?.model;
            if tail.is_null() || head.is_null() {
                return Err(Error::NullPointer);
            }
            let (t, h) = m.edge(index(i, m.num_edges())?);
            // Vertex indices are below 2^30.
            tail.write_unaligned(t as c_int);
            head.write_unaligned(h as c_int);
            Ok(())
        })
    }
}

/// The number of vertices (= edges) of a face of a convex model.
///
/// @param m  the model, or NULL.
/// @param i  the face index.
/// @return the count (>= 3); 0 if m is NULL or i is out of range.
/// Thread safety: may run concurrently with queries and other getters on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_face_num_vertices(
    m: *const pqp_convex_model,
    i: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            0,
            || {},
            || {
                let Ok(m) = deref(m) else { return 0 };
                index(i, m.model.num_faces()).map_or(0, |i| m.model.face(i).len() as c_int)
            },
        )
    }
}

/// The vertices of a face of a convex model, counter-clockwise seen from outside.
///
/// @param m         the model.
/// @param i         the face index, 0 <= i < pqp_convex_model_num_faces(m).
/// @param vertices  receives pqp_convex_model_face_num_vertices(m, i) vertex indices.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m or vertices is NULL; PQP_ERR_INVALID_ARGUMENT if i is
///         out of range (nothing is written); PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may run concurrently with queries and other getters on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_face(
    m: *const pqp_convex_model,
    i: c_int,
    vertices: *mut c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = &deref(m)?.model;
            if vertices.is_null() {
                return Err(Error::NullPointer);
            }
            for (k, &v) in m.face(index(i, m.num_faces())?).iter().enumerate() {
                vertices.add(k).write_unaligned(v as c_int);
            }
            Ok(())
        })
    }
}
