//! Ray casting: pqp_ray_cast and pqp_ray_cast_batch, over `query::ray`.

#![allow(non_snake_case)] // R and T keep PQP's names, which the header shows.

use super::batch::workers;
use super::{PQP_ERR_INTERNAL, boundary, code, deref, pqp_model, read_doubles, read_pose, status};
use crate::error::Error;
use crate::math::Vec3;
use crate::query::{RayCaster, RayHit, ray_cast};
use std::cell::Cell;
use std::ffi::{c_int, c_uint};

/// Where a ray first meets a model (pqp_ray_cast, pqp_ray_cast_batch).
///
/// Accuracy: point lies within 1e-14 * (|origin| + |T| + m) of the hit triangle, m being the
/// model's largest vertex coordinate (in its frame): it is a point of the triangle up to the
/// rounding of the coordinates.
/// Along the ray the error grows as the ray grazes the triangle (divided by the sine of the angle
/// between the ray and the triangle's plane).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(non_camel_case_types)]
pub struct pqp_ray_hit {
    /// The hit is at origin + t * direction, 0 <= t <= max_t, in units of the direction given;
    /// INFINITY if no hit in [0, max_t].
    pub t: f64,
    /// The hit point, world coordinates (NaN if no hit).
    pub point: [f64; 3],
    /// The unit normal of the hit triangle, (p2 - p1) x (p3 - p1) with its vertices in the order
    /// given to pqp_model_add_tri, world coordinates (NaN if no hit). It points to either side of
    /// the ray: triangles are hit from both sides.
    pub normal: [f64; 3],
    /// The caller's id of the hit triangle; -1 if no hit.
    pub triangle: c_int,
}

impl From<Option<RayHit>> for pqp_ray_hit {
    fn from(h: Option<RayHit>) -> pqp_ray_hit {
        match h {
            Some(h) => pqp_ray_hit {
                t: h.t,
                point: h.point.into(),
                normal: h.normal.into(),
                triangle: h.triangle,
            },
            None => NO_HIT,
        }
    }
}

/// What a ray that hits nothing gets.
const NO_HIT: pqp_ray_hit = pqp_ray_hit {
    t: f64::INFINITY,
    point: [f64::NAN; 3],
    normal: [f64::NAN; 3],
    triangle: -1,
};

/// Casts a ray at a posed model: the nearest point where origin + t * direction, 0 <= t <= max_t,
/// meets one of its triangles.
///
/// Watertight: a ray through an edge or a vertex shared by triangles of a closed mesh hits one of
/// them, never slips between. Triangles are hit from either side. A ray lying in a triangle's plane
/// does not hit that triangle (it hits its neighbours' edges) unless it starts on it; a triangle
/// without area is never hit. A ray starting on a triangle (inside it, on an edge or on a vertex,
/// exactly: the origin brought into the model's frame, R^T (origin - T), is a point of the
/// triangle) hits it at t = 0, whatever its direction, max_t = 0 included. Among hits at the same
/// t, the triangle added first is reported. See pqp_ray_hit for the accuracy.
///
/// @param hit        where the answer is written (only on PQP_OK).
/// @param R, T       the model's pose (as for pqp_collide).
/// @param m          the model (built).
/// @param origin     3 doubles, world coordinates, each finite and at most 1e150 in magnitude.
/// @param direction  3 doubles, world coordinates, finite, not all zero; need not be a unit vector
///                   (t is in its units).
/// @param max_t      the farthest t of interest, >= 0 (-0 is 0), may be INFINITY.
/// @return PQP_OK (hit->triangle is -1 and hit->t INFINITY if the ray hits nothing);
///         PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_UNPROCESSED_MODEL if m is not
///         built; PQP_ERR_NOT_A_TRIANGLE_MESH if m holds a primitive
///         (pqp_model_set_sphere, ...);
///         PQP_ERR_NONFINITE_POSE if a pose entry is NaN, infinite or larger than 1e150 in
///         magnitude; PQP_ERR_INVALID_ARGUMENT if max_t is negative or NaN or direction is zero;
///         PQP_ERR_NONFINITE_COORDINATE if an origin coordinate is NaN, infinite or larger than
///         1e150 in magnitude, or a direction coordinate is NaN or infinite;
///         PQP_ERR_OUT_OF_MEMORY if the model's tree of axis-aligned boxes and its copy of the
///         triangles in the tree's leaf order (made on its first ray cast, about 40 + 80 = 120
///         bytes per triangle, kept in the model and counted by pqp_model_memory_usage) could
///         not be allocated; PQP_ERR_INTERNAL on an internal fault. On any error nothing is
///         written.
/// Thread safety: any number of calls may use the same model at once from different threads
///                (the first ones on a model may each make its tree of boxes and copy of the
///                triangles; one of each is kept).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_ray_cast(
    hit: *mut pqp_ray_hit,
    R: *const f64,
    T: *const f64,
    m: *const pqp_model,
    origin: *const f64,
    direction: *const f64,
    max_t: f64,
) -> c_int {
    status(|| {
        // SAFETY: each pointer is NULL or valid as the header requires (the caller's contract).
        let (pose, m, o, d) = unsafe {
            (
                read_pose(R, T)?,
                deref(m)?,
                read_doubles::<3>(origin)?,
                read_doubles::<3>(direction)?,
            )
        };
        if hit.is_null() {
            return Err(Error::NullPointer);
        }
        let answer = ray_cast(&m.model, &pose, &o.into(), &d.into(), max_t)?;
        // SAFETY: `hit` is not NULL, so it points to a writable pqp_ray_hit (the caller's contract).
        unsafe { hit.write(answer.into()) };
        Ok(())
    })
}

/// Casts n rays at a posed model, on several threads: `hits[i]` is what pqp_ray_cast gives for the
/// ray origins + 3 * i, directions + 3 * i (the same answer, whatever the threads).
///
/// Every ray is checked before any is cast: one bad ray fails the whole call.
///
/// @param hits        n answers, written only on PQP_OK; must not overlap origins or directions.
/// @param n           the number of rays; 0 returns PQP_OK (hits, origins and directions may
///                    then be NULL).
/// @param R, T        the model's pose (as for pqp_collide).
/// @param m           the model (built).
/// @param origins     3 n doubles: the origins, as for pqp_ray_cast.
/// @param directions  3 n doubles: the directions, as for pqp_ray_cast.
/// @param max_t       the farthest t of interest for every ray, as for pqp_ray_cast.
/// @param threads     the threads to cast on, the calling one included; 0 for as many as the
///                    machine has (counted once per process); any value is valid and is capped
///                    to the available cores and to n.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if R, T or m is NULL, or hits, origins or directions is
///         NULL and n > 0; PQP_ERR_INVALID_ARGUMENT if n is too large for the address space (n *
///         sizeof(pqp_ray_hit) > PTRDIFF_MAX), or as pqp_ray_cast for max_t or any ray; the other
///         codes as pqp_ray_cast, for any ray; PQP_ERR_OUT_OF_MEMORY if the answers' working
///         storage could not be allocated; PQP_ERR_INTERNAL on an internal fault (every hit
///         is then reset to "no hit" if the casting had begun). On any other error nothing is
///         written.
/// Thread safety: as pqp_ray_cast.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_ray_cast_batch(
    hits: *mut pqp_ray_hit,
    n: usize,
    R: *const f64,
    T: *const f64,
    m: *const pqp_model,
    origins: *const f64,
    directions: *const f64,
    max_t: f64,
    threads: c_uint,
) -> c_int {
    // Set once the answers start being written: only then does a fault reset them.
    let writing = Cell::new(false);
    let checked = || -> Result<(), Error> {
        // SAFETY: R and T are NULL or point to 9 and 3 doubles, m is NULL or a live model.
        let (pose, m) = unsafe { (read_pose(R, T)?, deref(m)?) };
        if n > 0 && (hits.is_null() || origins.is_null() || directions.is_null()) {
            return Err(Error::NullPointer);
        }
        if n > isize::MAX as usize / std::mem::size_of::<pqp_ray_hit>() {
            return Err(Error::InvalidArgument);
        }
        let caster = RayCaster::new(&m.model, &pose, max_t)?;
        if n == 0 {
            return Ok(());
        }
        // SAFETY: not NULL, so each points to 3 n doubles (aligned, as C arrays of double are),
        // not written during the call (`hits` does not overlap them: the caller's contract); the
        // size is below isize::MAX bytes (checked above).
        let (o, d) = unsafe {
            (
                std::slice::from_raw_parts(origins.cast::<[f64; 3]>(), n),
                std::slice::from_raw_parts(directions.cast::<[f64; 3]>(), n),
            )
        };
        for (o, d) in o.iter().zip(d) {
            RayCaster::check(&Vec3::from(*o), &Vec3::from(*d))?;
        }
        // SAFETY: not NULL, so it points to n writable answers that nothing else accesses during
        // the call (the caller's contract).
        let out = unsafe { std::slice::from_raw_parts_mut(hits, n) };
        writing.set(true);
        let ray = |i: usize| (Vec3::from(o[i]), Vec3::from(d[i]));
        let answers = caster.cast_all(ray, n, workers(threads))?;
        for (slot, hit) in out.iter_mut().zip(answers) {
            *slot = pqp_ray_hit::from(hit);
        }
        Ok(())
    };
    let recover = || {
        if writing.get() {
            // SAFETY: as above: `hits` points to n writable answers (checked before `writing`).
            let out = unsafe { std::slice::from_raw_parts_mut(hits, n) };
            out.fill(NO_HIT);
        }
    };
    boundary(PQP_ERR_INTERNAL, recover, || code(checked()))
}
