//! Swept-sphere primitives as models: pqp_model_set_sphere, pqp_model_set_capsule,
//! pqp_model_set_box.

use super::legacy::LegacyView;
use super::{deref_mut, pqp_model, status};
use crate::model::Primitive;
use std::ffi::c_int;

/// Replaces m's contents with `p`, and PQP 1.3's view of them (which was of the old contents).
unsafe fn set(m: *mut pqp_model, p: Primitive) -> c_int {
    // SAFETY: m is NULL or a valid model handle (the caller's contract, passed on).
    unsafe {
        status(|| {
            let m = deref_mut(m)?;
            m.model.set_primitive(p)?;
            m.view = LegacyView::default();
            Ok(())
        })
    }
}

/// Replaces a model's contents (triangles or a primitive, built or not) with a solid sphere of
/// `radius` centred on the model's origin, built: it can be queried at once.
///
/// A primitive model works in pqp_collide, pqp_distance (and pqp_distance_search),
/// pqp_tolerance (and pqp_tolerance_search), pqp_within_distance and the batch calls, against
/// triangle models and against other primitives, with exact answers (as exact as the triangle
/// distance: a triangle's distance from the primitive's core, less its radius). It is a solid: a
/// triangle inside it collides with it and is at distance 0. In pair lists and results the
/// primitive is one element with id 0 and triangle index 0; the triangle cache and search front
/// of a distance result are not used with it. Its volume choices are kept for a later build.
///
/// It holds no triangles: pqp_model_num_tris gives 0, pqp_model_tris 0 triangles, and the calls
/// that need triangles or a hierarchy (pqp_closest_point, pqp_signed_distance, pqp_ray_cast and
/// its batch, pqp_self_collide, pqp_time_of_contact, pqp_model_refit, pqp_model_serialize,
/// pqp_model_bvs) return PQP_ERR_NOT_A_TRIANGLE_MESH. pqp_model_add_tri and pqp_model_end return
/// PQP_ERR_BUILD_OUT_OF_SEQUENCE as on any built model; pqp_model_begin clears it into an empty
/// model being built (returning PQP_ERR_BUILD_OUT_OF_SEQUENCE, as on any built model).
///
/// @param m       the model.
/// @param radius  the sphere's radius, >= 0 (0 is a point), at most 1e150.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m is NULL; PQP_ERR_INVALID_ARGUMENT if radius is
///         negative, NaN, infinite or above 1e150; PQP_ERR_INTERNAL on an internal fault. On any
///         error m is unchanged.
/// Thread safety: as the build calls, must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_set_sphere(m: *mut pqp_model, radius: f64) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { set(m, Primitive::Sphere { radius }) }
}

/// Replaces a model's contents with a solid capsule, built: the points within `radius` of the
/// segment of `length` on the model's z axis, centred on its origin (from (0, 0, -length/2) to
/// (0, 0, length/2); FCL's Capsule(radius, lz) is the same shape). Everything else as
/// pqp_model_set_sphere.
///
/// @param m       the model.
/// @param radius  the radius, >= 0, at most 1e150.
/// @param length  the segment's length, >= 0 (0 gives a sphere), at most 1e150.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m is NULL; PQP_ERR_INVALID_ARGUMENT if radius or
///         length is negative, NaN, infinite or above 1e150; PQP_ERR_INTERNAL on an internal
///         fault. On any error m is unchanged.
/// Thread safety: as the build calls, must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_set_capsule(
    m: *mut pqp_model,
    radius: f64,
    length: f64,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { set(m, Primitive::Capsule { radius, length }) }
}

/// Replaces a model's contents with a solid box, built: side lengths x, y and z along the model's
/// axes, centred on its origin (FCL's Box(x, y, z) is the same shape). A zero side makes it flat
/// (a rectangle, a segment or a point), still a solid for every query. Everything else as
/// pqp_model_set_sphere.
///
/// @param m        the model.
/// @param x, y, z  the side lengths, each >= 0 and at most 1e150.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m is NULL; PQP_ERR_INVALID_ARGUMENT if a side is
///         negative, NaN, infinite or above 1e150; PQP_ERR_INTERNAL on an internal fault. On any
///         error m is unchanged.
/// Thread safety: as the build calls, must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_set_box(m: *mut pqp_model, x: f64, y: f64, z: f64) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { set(m, Primitive::Box { size: [x, y, z] }) }
}
