//! Convex polyhedra: model handles (built from a point set or from a closed convex mesh), the
//! per-pair warm-start cache, the result handle and its getters, and the three queries
//! (pqp_convex_distance, pqp_convex_intersect, pqp_convex_penetration) over [`crate::convex`].
//!
//! Getters never fail: given NULL (or an index out of range) they return a fallback value (stated
//! on each).

#![allow(non_snake_case)] // R1, T1, R2, T2 keep the names the rest of the header uses.

use super::{
    boundary, code, count, deref, deref_mut, destroy_handle, getter, into_handle, new_handle,
    read_doubles, read_pose, reset, status, PQP_ERR_INTERNAL,
};
use crate::convex::{
    convex_distance, convex_penetration, ConvexDistance, ConvexModel, ConvexPairCache,
    ConvexPenetration, ConvexStats, Feature,
};
use crate::error::Error;
use crate::math::{Pose, Vec3};
use std::ffi::c_int;
use std::ptr;

/// Feature kind: a vertex (see pqp_convex_result_feature1_kind).
pub const PQP_CONVEX_VERTEX: c_int = 0;
/// Feature kind: an edge.
pub const PQP_CONVEX_EDGE: c_int = 1;
/// Feature kind: a face.
pub const PQP_CONVEX_FACE: c_int = 2;

/// A convex polyhedron (opaque), immutable once created. Create with pqp_convex_model_from_points,
/// pqp_convex_model_from_triangles or pqp_convex_model_from_polygons; free with
/// pqp_convex_model_destroy.
#[allow(non_camel_case_types)]
pub struct pqp_convex_model {
    pub(crate) model: ConvexModel,
}

/// The warm-start state of one ordered pair of convex models (opaque): the feature pair the last
/// query on them ended on. Owned by the caller, one per pair; used only with the two models (in
/// the same order) that filled it, and ignored with any others.
#[allow(non_camel_case_types)]
#[derive(Default)]
pub struct pqp_convex_cache {
    pub(crate) cache: ConvexPairCache,
}

/// The answer of pqp_convex_distance or pqp_convex_penetration (opaque).
#[allow(non_camel_case_types)]
pub struct pqp_convex_result {
    distance: f64,
    p1: [f64; 3],
    p2: [f64; 3],
    intersecting: bool,
    features: Option<(Feature, Feature)>,
    stats: ConvexStats,
    depth: f64,
    normal: [f64; 3],
    deepest: [[f64; 3]; 2],
}

impl Default for pqp_convex_result {
    fn default() -> Self {
        pqp_convex_result {
            distance: f64::INFINITY,
            p1: [0.0; 3],
            p2: [0.0; 3],
            intersecting: false,
            features: None,
            stats: ConvexStats::default(),
            depth: f64::NAN,
            normal: [0.0; 3],
            deepest: [[0.0; 3]; 2],
        }
    }
}

// Queries take `const pqp_convex_model *` from any number of threads at once.
const _: () = {
    const fn shareable<T: Send + Sync>() {}
    shareable::<pqp_convex_model>();
};

fn arr(v: &Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

impl pqp_convex_result {
    fn from_distance(d: &ConvexDistance) -> Self {
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

    fn from_penetration(p: &ConvexPenetration) -> Self {
        pqp_convex_result {
            depth: p.depth,
            normal: arr(&p.normal),
            deepest: [arr(&p.p1), arr(&p.p2)],
            ..Self::from_distance(&p.closest)
        }
    }
}

/// A count from C: >= 0.
fn length(n: c_int) -> Result<usize, Error> {
    usize::try_from(n).map_err(|_| Error::InvalidArgument)
}

/// Copies `n` points (3 doubles each) from C.
///
/// # Safety
/// `xyz` is NULL or points to `3 n` readable doubles.
unsafe fn read_points(xyz: *const f64, n: c_int) -> Result<Vec<[f64; 3]>, Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if xyz.is_null() {
            return Err(Error::NullPointer);
        }
        let n = length(n)?;
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

/// Builds a model with `make` and hands it to C through `out` (NULL there on any error).
///
/// # Safety
/// `out` is NULL or points to a writable `pqp_convex_model *`.
unsafe fn create(
    out: *mut *mut pqp_convex_model,
    make: impl FnOnce() -> Result<ConvexModel, Error>,
) -> Result<(), Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if out.is_null() {
            return Err(Error::NullPointer);
        }
        out.write(ptr::null_mut());
        let h = into_handle(pqp_convex_model { model: make()? });
        if h.is_null() {
            return Err(Error::ModelOutOfMemory);
        }
        out.write(h);
        Ok(())
    }
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
///         PQP_ERR_INVALID_ARGUMENT if n < 0 or n > 2^30; PQP_ERR_NONFINITE_COORDINATE if a
///         coordinate is NaN, infinite or larger than 1e150 in magnitude;
///         PQP_ERR_DEGENERATE_POINTS if the points do not span a volume (n = 0, fewer than four
///         distinct points, all collinear or all coplanar); PQP_ERR_MODEL_OUT_OF_MEMORY if the
///         model could not be allocated; PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_convex_model_from_points(
    out: *mut *mut pqp_convex_model,
    xyz: *const f64,
    n: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            PQP_ERR_INTERNAL,
            || clear_out(out),
            || {
                code(create(out, || {
                    ConvexModel::from_points(&read_points(xyz, n)?)
                }))
            },
        )
    }
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
///         PQP_ERR_INVALID_ARGUMENT if a count is negative or too large, or an index is negative or
///         >= num_vertices; PQP_ERR_NONFINITE_COORDINATE for a NaN, infinite or huge coordinate;
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
            let nt = length(num_triangles)?;
            let n = nt.checked_mul(3).ok_or(Error::InvalidArgument)?;
            let idx = read_indices(triangles, n)?;
            let counts = vec![3u32; nt];
            ConvexModel::from_polygons(&v, &counts, &idx)
        };
        boundary(
            PQP_ERR_INTERNAL,
            || clear_out(out),
            || code(create(out, make)),
        )
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
///         PQP_ERR_INVALID_ARGUMENT if a count is negative, a face count is below 3, the counts do
///         not sum to num_indices, or an index is negative or >= num_vertices;
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
            let counts = read_indices(counts, length(num_faces)?)?;
            if indices.is_null() {
                return Err(Error::NullPointer);
            }
            let ni = length(num_indices)?;
            let total: u64 = counts.iter().map(|&c| u64::from(c)).sum();
            if total != ni as u64 {
                return Err(Error::InvalidArgument);
            }
            let idx = read_indices(indices, ni)?;
            ConvexModel::from_polygons(&v, &counts, &idx)
        };
        boundary(
            PQP_ERR_INTERNAL,
            || clear_out(out),
            || code(create(out, make)),
        )
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
        let body = || -> Result<(), Error> {
            let result = deref_mut(r)?;
            let q = query(R1, T1, m1, R2, T2, m2, cache)?;
            let d = convex_distance(q.m1, &q.pose1, q.m2, &q.pose2, q.cache)?;
            *result = pqp_convex_result::from_distance(&d);
            Ok(())
        };
        boundary(PQP_ERR_INTERNAL, || reset(r), || code(body()))
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
        let body = || -> Result<(), Error> {
            let result = deref_mut(r)?;
            let q = query(R1, T1, m1, R2, T2, m2, cache)?;
            let p = convex_penetration(q.m1, &q.pose1, q.m2, &q.pose2, q.cache)?;
            *result = pqp_convex_result::from_penetration(&p);
            Ok(())
        };
        boundary(PQP_ERR_INTERNAL, || reset(r), || code(body()))
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
