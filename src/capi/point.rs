//! Point queries: pqp_closest_point and pqp_signed_distance.

#![allow(non_snake_case)] // R, T: PQP's names for a pose, which the header shows.

use super::{deref, read_doubles, read_pose, status};
use crate::error::Error;
use crate::math::{Pose, Vec3};
use crate::model::Model;
use crate::query::{closest_point, signed_distance};
use std::ffi::c_int;

/// The answer of pqp_closest_point.
#[repr(C)]
#[allow(non_camel_case_types)]
#[derive(Clone, Copy, Debug)]
pub struct pqp_point_result {
    /// Distance from the point to the posed model; INFINITY if beyond max_distance.
    pub distance: f64,
    /// Closest point of the model, world coordinates; NaN (all three) if beyond max_distance.
    pub point: [f64; 3],
    /// Caller's id of the triangle holding it; -1 if beyond max_distance.
    pub triangle: c_int,
}

/// The checked inputs of a point query: the model, its pose and the point.
///
/// # Safety
/// Each pointer is NULL or valid as the header requires: `R` 9 doubles, `T` and `point` 3, `m` a
/// live model.
unsafe fn point_args<'a>(
    R: *const f64,
    T: *const f64,
    m: *const super::pqp_model,
    point: *const f64,
) -> Result<(&'a Model, Pose, Vec3), Error> {
    // SAFETY: every pointer is NULL or valid (this function's contract).
    unsafe {
        let pose = read_pose(R, T)?;
        let m = deref(m)?;
        let p: [f64; 3] = read_doubles(point)?;
        Ok((&m.model, pose, Vec3::from(p)))
    }
}

/// Finds the closest point of a posed model to a point, if within max_distance.
///
/// The point is carried into the model's frame by the inverse pose (R taken as a rotation), the
/// closest point of the model's triangles found there exactly (the exact point-triangle distance,
/// degenerate triangles counting as the segment or point they span) by a search of the model's
/// bounding-volume hierarchy that max_distance prunes, and carried back to world coordinates.
/// When several triangles are equally close, one of them is reported, always the same for the
/// same model, pose and point.
///
/// Models of at most 8,192 triangles are searched in a tree of axis-aligned boxes with, per
/// triangle, its plane and edges' frames (a cheap bound that spares most exact tests). The first
/// pqp_closest_point or pqp_signed_distance on such a model builds them (a few milliseconds for
/// a few thousand triangles) and keeps them in the model: about 290 bytes per triangle more,
/// counted by pqp_model_memory_usage (a pqp_ray_cast on the model builds the box tree, about 40
/// of them, and shares it). If they cannot be allocated the query still answers, by the
/// bounding-volume hierarchy's search. pqp_model_refit discards them (the next query rebuilds
/// them). Larger models use the hierarchy's search alone and keep nothing more.
///
/// @param out           where the answer is written. Beyond max_distance (the model is farther
///                      than it from the point): distance INFINITY, point NaN, triangle -1. A
///                      model exactly at max_distance is within it.
/// @param R, T          the model's pose (as for pqp_distance).
/// @param m             the model (built).
/// @param point         the point, 3 doubles, world coordinates.
/// @param max_distance  the largest distance of interest, >= 0; INFINITY for no limit. Smaller
///                      values make the search faster.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_UNPROCESSED_MODEL if m is
///         not built; PQP_ERR_NOT_A_TRIANGLE_MESH if m holds a primitive
///         (pqp_model_set_sphere, ...);
///         PQP_ERR_NONFINITE_POSE if a pose entry is NaN, infinite or larger than
///         1e150 in magnitude; PQP_ERR_NONFINITE_COORDINATE if a coordinate of point is;
///         PQP_ERR_INVALID_ARGUMENT if max_distance is negative or NaN; PQP_ERR_INTERNAL on an
///         internal fault. On an error nothing is written. out may overlap the inputs.
/// Thread safety: any number of queries may use the same model at once from different threads,
///                the first ones included: concurrent first queries on a small model may each
///                build its box tree and frames; one of each is kept (the others are freed) and
///                every query gets the same answers either way.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_closest_point(
    out: *mut pqp_point_result,
    R: *const f64,
    T: *const f64,
    m: *const super::pqp_model,
    point: *const f64,
    max_distance: f64,
) -> c_int {
    status(|| {
        // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
        let (model, pose, p) = unsafe { point_args(R, T, m, point)? };
        if out.is_null() {
            return Err(Error::NullPointer);
        }
        let r = closest_point(model, &pose, &p, max_distance)?;
        let answer = pqp_point_result {
            distance: r.distance,
            point: r.point.into(),
            triangle: r.triangle.unwrap_or(-1),
        };
        // SAFETY: `out` is not NULL, so it points to a writable pqp_point_result (the caller's
        // contract); every input has been read.
        unsafe { out.write_unaligned(answer) };
        Ok(())
    })
}

/// Computes the signed distance from a point to a posed model: its distance, negative when the
/// point is inside the model.
///
/// Inside is decided by the generalized winding number w of the model about the point: the signed
/// solid angle its triangles subtend there over 4 pi, a triangle counting positively when the
/// point is behind it (its normal (p2 - p1) x (p3 - p1) pointing away). The point is inside when
/// |w| >= 1/2. For a closed mesh w is 0 outside and 1 or -1 inside (triangles facing out or in),
/// so either orientation gives the expected sign; for an open or self-intersecting mesh w varies
/// smoothly and inside is where the surface wraps the point at least half way round (for an open
/// hemisphere, the points near its centre). A point on the surface has distance 0. w is computed
/// hierarchically (near the point from triangles, away from it from each bounding-volume node's
/// boundary edges), in about logarithmic time per query; the first signed distance on a model
/// computes those edges and keeps them in the model (pqp_model_memory_usage counts them). The
/// distance is pqp_closest_point's, with what that keeps in a small model (see there).
///
/// @param out    where the signed distance is written (1 double).
/// @param R, T   the model's pose (as for pqp_distance).
/// @param m      the model (built).
/// @param point  the point, 3 doubles, world coordinates.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_UNPROCESSED_MODEL if m is
///         not built; PQP_ERR_NOT_A_TRIANGLE_MESH if m holds a primitive
///         (pqp_model_set_sphere, ...);
///         PQP_ERR_NONFINITE_POSE if a pose entry is NaN, infinite or larger than
///         1e150 in magnitude; PQP_ERR_NONFINITE_COORDINATE if a coordinate of point is;
///         PQP_ERR_OUT_OF_MEMORY if the model's boundary edges could not be allocated;
///         PQP_ERR_INTERNAL on an internal fault. On an error nothing is written. out may overlap
///         the inputs.
/// Thread safety: any number of queries may use the same model at once from different threads
///                (the first ones on a model may each compute its boundary edges, and on a small
///                model its box tree and frames; one of each is kept).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_signed_distance(
    out: *mut f64,
    R: *const f64,
    T: *const f64,
    m: *const super::pqp_model,
    point: *const f64,
) -> c_int {
    status(|| {
        // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
        let (model, pose, p) = unsafe { point_args(R, T, m, point)? };
        if out.is_null() {
            return Err(Error::NullPointer);
        }
        let d = signed_distance(model, &pose, &p)?;
        // SAFETY: `out` is not NULL, so it points to a writable double (the caller's contract);
        // every input has been read.
        unsafe { out.write_unaligned(d) };
        Ok(())
    })
}
