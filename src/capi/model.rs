//! Model handles and PQP's build protocol (begin, add triangles, end).

use super::legacy::LegacyView;
use super::{
    PQP_ERR_INTERNAL, boundary, code, deref, deref_mut, destroy_handle, into_handle, read_doubles,
    status,
};
use crate::error::Error;
use crate::model::{BuildState, CollisionVolume, Model, VolumeKind};
use std::ffi::{c_int, c_uint};

/// Volume choice (pqp_model_set_volume): rectangle swept spheres, PQP's choice and the default.
pub const PQP_BV_RSS: c_int = 0;
/// Volume choice (pqp_model_set_volume): point swept spheres (spheres).
pub const PQP_BV_PSS: c_int = 1;
/// Volume choice (pqp_model_set_volume): line swept spheres (capsules).
pub const PQP_BV_LSS: c_int = 2;
/// Volume choice (pqp_model_set_volume): each node takes the swept sphere volume kind whose fitted
/// volume is smallest.
pub const PQP_BV_HYBRID: c_int = 3;
/// Collision volume choice (pqp_model_set_collision_volume): oriented boxes, PQP's choice and the
/// default.
pub const PQP_COLLIDE_OBB: c_int = 0;
/// Collision volume choice (pqp_model_set_collision_volume): the model's swept sphere volumes.
pub const PQP_COLLIDE_SSV: c_int = 1;
/// Build state (pqp_model_build_state): fresh or cleared, no build begun (PQP 1.3's name and
/// value).
pub const PQP_BUILD_STATE_EMPTY: c_int = 0;
/// Build state (pqp_model_build_state): begun (by pqp_model_begin, or by pqp_model_add_tri on an
/// empty model) and not built since (PQP 1.3's name and value).
pub const PQP_BUILD_STATE_BEGUN: c_int = 1;
/// Build state (pqp_model_build_state): built by a successful pqp_model_end (PQP 1.3's name and
/// value).
pub const PQP_BUILD_STATE_PROCESSED: c_int = 2;

/// A triangle model (opaque). Create with pqp_model_create, fill with pqp_model_begin,
/// pqp_model_add_tri and pqp_model_end, free with pqp_model_destroy.
#[allow(non_camel_case_types)]
pub struct pqp_model {
    pub(crate) model: Model,
    /// PQP 1.3's view of the model, made on request (pqp_model_tris, pqp_model_bvs).
    pub(crate) view: LegacyView,
}

// Queries take `const pqp_model *` from any number of threads at once: the model must be shareable.
const _: () = {
    const fn shareable<T: Send + Sync>() {}
    shareable::<pqp_model>();
};

/// Creates an empty model.
///
/// @return a new model, to be freed with pqp_model_destroy; NULL only if memory could not be
///         allocated.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub extern "C" fn pqp_model_create() -> *mut pqp_model {
    boundary(
        std::ptr::null_mut(),
        || {},
        || {
            into_handle(pqp_model {
                model: Model::new(),
                view: LegacyView::default(),
            })
        },
    )
}

/// Frees a model and everything it holds.
///
/// @param m  a model from pqp_model_create, or NULL (then nothing happens). It must not be used
///           afterwards.
/// Thread safety: must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_destroy(m: *mut pqp_model) {
    // SAFETY: m is NULL or a live handle of its kind, used by no other call (the caller's contract).
    unsafe { destroy_handle(m) }
}

/// Makes a deep, independent copy of a model, in whatever state it is: empty, being built (the
/// triangles added so far; the copy can go on being built), or built (the copy is built, with the
/// same hierarchy bit for bit, and answers every query exactly as m does). The volume choices are
/// copied too. Building, rebuilding or destroying either model never affects the other.
///
/// @param out  receives the copy (free it with pqp_model_destroy), or NULL on any error.
/// @param m    the model to copy.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if out or m is NULL; PQP_ERR_MODEL_OUT_OF_MEMORY if the
///         copy could not be allocated; PQP_ERR_INTERNAL on an internal fault (*out is then NULL).
/// Thread safety: may run concurrently with queries and getters on m (a built model may be copied
///                while other threads query it), not with build calls on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_clone(out: *mut *mut pqp_model, m: *const pqp_model) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            PQP_ERR_INTERNAL,
            || {
                if !out.is_null() {
                    out.write(std::ptr::null_mut());
                }
            },
            || code(clone_into(out, m)),
        )
    }
}

/// The body of pqp_model_clone: NULL in `out` until the copy is made, so that no error leaves a
/// handle there.
///
/// # Safety
/// `out` is NULL or points to a writable `pqp_model *`; `m` is NULL or a live handle.
unsafe fn clone_into(out: *mut *mut pqp_model, m: *const pqp_model) -> Result<(), Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if out.is_null() {
            return Err(Error::NullPointer);
        }
        out.write(std::ptr::null_mut());
        // The views are not copied: the copy makes its own on request.
        let copy = pqp_model {
            model: deref(m)?.model.try_clone()?,
            view: LegacyView::default(),
        };
        let h = into_handle(copy);
        if h.is_null() {
            return Err(Error::ModelOutOfMemory);
        }
        out.write(h);
        Ok(())
    }
}

/// Where a model is in PQP's build protocol (PQP 1.3's build_state).
///
/// @param m  the model, or NULL.
/// @return PQP_BUILD_STATE_EMPTY (0) for a fresh model (pqp_model_end leaves it so; as
///         pqp_model_begin clears a model and begins it, no other model is empty);
///         PQP_BUILD_STATE_BEGUN (1) after pqp_model_begin or pqp_model_add_tri (even one that
///         refused its triangle) until a successful pqp_model_end; PQP_BUILD_STATE_PROCESSED (2)
///         once built; 0 if m is NULL.
/// Thread safety: may run concurrently with queries and other getters on m, not with build calls.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_build_state(m: *const pqp_model) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            PQP_BUILD_STATE_EMPTY,
            || {},
            || {
                deref(m).map_or(PQP_BUILD_STATE_EMPTY, |m| match m.model.build_state() {
                    BuildState::Empty => PQP_BUILD_STATE_EMPTY,
                    BuildState::Begun => PQP_BUILD_STATE_BEGUN,
                    BuildState::Built => PQP_BUILD_STATE_PROCESSED,
                })
            },
        )
    }
}

/// Starts building a model (PQP's BeginModel).
///
/// On a model that is not fresh (already begun, or built) the model is cleared, the call returns
/// PQP_ERR_BUILD_OUT_OF_SEQUENCE, and the model is begun anyway: it accepts pqp_model_add_tri.
///
/// @param m              the model.
/// @param num_tris_hint  how many triangles will be added (a capacity hint only; < 0 is taken as 0).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m is NULL; PQP_ERR_BUILD_OUT_OF_SEQUENCE as above;
///         PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_begin(m: *mut pqp_model, num_tris_hint: c_int) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = deref_mut(m)?;
            m.view.begun();
            m.model.begin(usize::try_from(num_tris_hint).unwrap_or(0))
        })
    }
}

/// Adds a triangle to a model being built (PQP's AddTri).
///
/// Before pqp_model_begin, the model is begun implicitly (as PQP does). Degenerate triangles (a
/// segment, a point) are accepted, and so are coordinates of any magnitude up to 1e150, however
/// small: answers stay exact, but in a scene whose coordinates are all below about 1e-135 the
/// bounding volumes prune less (below 1e-150, not at all: a query may test every triangle pair).
///
/// @param m           the model.
/// @param p1, p2, p3  the vertices, 3 doubles each (x, y, z in the model's frame).
/// @param id          the caller's id for this triangle, reported by queries (any value).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m, p1, p2 or p3 is NULL;
///         PQP_ERR_BUILD_OUT_OF_SEQUENCE after a successful pqp_model_end (the triangle is ignored);
///         PQP_ERR_NONFINITE_COORDINATE if a coordinate is NaN, infinite or larger than 1e150 in
///         magnitude (the triangle is not stored; the model keeps the triangles it had and stays
///         usable; an empty model is begun all the same, as the implicit begin comes first:
///         pqp_model_build_state then gives PQP_BUILD_STATE_BEGUN);
///         PQP_ERR_MODEL_OUT_OF_MEMORY if the triangle could not be stored;
///         PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_add_tri(
    m: *mut pqp_model,
    p1: *const f64,
    p2: *const f64,
    p3: *const f64,
    id: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = deref_mut(m)?;
            let (a, b, c) = (read_doubles(p1)?, read_doubles(p2)?, read_doubles(p3)?);
            let before = m.model.num_triangles();
            let result = m.model.add_triangle(a, b, c, id);
            let stored = m.model.num_triangles() > before;
            m.view
                .added(stored.then(|| ([a.into(), b.into(), c.into()], id)));
            result
        })
    }
}

/// Finishes a model: builds its bounding-volume hierarchy (PQP's EndModel). After it the model is
/// immutable and can be queried.
///
/// @param m  the model.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m is NULL; PQP_ERR_BUILD_OUT_OF_SEQUENCE if the model
///         is already built (it stays built); PQP_ERR_BUILD_EMPTY_MODEL if the model holds no
///         triangle, whether begun or not (a fresh model included; as PQP 1.3): the model stays
///         unbuilt, in its state (queries return PQP_ERR_UNPROCESSED_MODEL);
///         PQP_ERR_MODEL_OUT_OF_MEMORY if the hierarchy could not be allocated; PQP_ERR_INTERNAL
///         on an internal fault.
/// Thread safety: must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_end(m: *mut pqp_model) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            // PQP 1.3's views stay (see LegacyView).
            deref_mut(m)?.model.end()
        })
    }
}

/// Chooses the swept sphere volume a model's hierarchy is built with, for distance and tolerance
/// queries (and for collision with PQP_COLLIDE_SSV). Call it before pqp_model_end; the choice stays
/// for later builds of the model (pqp_model_begin does not reset it). Without it a model uses
/// PQP_BV_RSS, as PQP does. Answers are the same whatever the choice; only the work differs.
///
/// @param m     the model.
/// @param kind  PQP_BV_RSS, PQP_BV_PSS, PQP_BV_LSS or PQP_BV_HYBRID.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m is NULL; PQP_ERR_INVALID_ARGUMENT if kind is none of
///         those (the choice is not changed); PQP_ERR_BUILD_OUT_OF_SEQUENCE if the model is built
///         (the choice is not changed); PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_set_volume(m: *mut pqp_model, kind: c_int) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = deref_mut(m)?;
            let kind = match kind {
                PQP_BV_RSS => VolumeKind::Rss,
                PQP_BV_PSS => VolumeKind::Pss,
                PQP_BV_LSS => VolumeKind::Lss,
                PQP_BV_HYBRID => VolumeKind::Hybrid,
                _ => return Err(Error::InvalidArgument),
            };
            m.model.set_volume(kind)
        })
    }
}

/// Chooses the volume collision queries test a model's nodes with. Call it before pqp_model_end;
/// the choice stays for later builds of the model. Without it a model uses PQP_COLLIDE_OBB, as PQP
/// does. A collision query runs on swept sphere volumes only when both of its models chose
/// PQP_COLLIDE_SSV; the pairs reported are the same either way.
///
/// @param m       the model.
/// @param volume  PQP_COLLIDE_OBB or PQP_COLLIDE_SSV.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m is NULL; PQP_ERR_INVALID_ARGUMENT if volume is neither
///         (the choice is not changed); PQP_ERR_BUILD_OUT_OF_SEQUENCE if the model is built (the
///         choice is not changed); PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_set_collision_volume(m: *mut pqp_model, volume: c_int) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = deref_mut(m)?;
            let volume = match volume {
                PQP_COLLIDE_OBB => CollisionVolume::Obb,
                PQP_COLLIDE_SSV => CollisionVolume::Ssv,
                _ => return Err(Error::InvalidArgument),
            };
            m.model.set_collision_volume(volume)
        })
    }
}

/// The number of triangles a model holds (added so far, or in the built model).
///
/// @param m  the model, or NULL.
/// @return the count; 0 if m is NULL.
/// Thread safety: may run concurrently with queries and other getters on m, not with build calls.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_num_tris(m: *const pqp_model) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            0,
            || {},
            || match deref(m) {
                // The build protocol refuses a triangle beyond i32::MAX, so this never clamps.
                Ok(m) => c_int::try_from(m.model.num_triangles()).unwrap_or(c_int::MAX),
                Err(_) => 0,
            },
        )
    }
}

/// The memory a model holds, in bytes (triangles, hierarchy and bookkeeping), including PQP
/// 1.3's view of it once asked for (pqp_model_tris, pqp_model_bvs and their float forms make it on
/// their first call and keep it; a model never asked costs nothing for it).
///
/// @param m  the model, or NULL.
/// @return the byte count; 0 if m is NULL.
/// Thread safety: may run concurrently with queries and other getters on m, not with build calls.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_memory_usage(m: *const pqp_model) -> u64 {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            0,
            || {},
            || {
                deref(m).map_or(0, |m| {
                    // The handle beyond the model, and the views' arrays.
                    let extra = std::mem::size_of::<pqp_model>() - std::mem::size_of::<Model>();
                    m.model.memory_usage() + (extra + m.view.memory_usage()) as u64
                })
            },
        )
    }
}

/// Whether a model is built (its last pqp_model_end succeeded) and can be queried.
///
/// @param m  the model, or NULL.
/// @return 1 if built, else 0; 0 if m is NULL.
/// Thread safety: may run concurrently with queries and other getters on m, not with build calls.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_is_built(m: *const pqp_model) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            0,
            || {},
            || deref(m).map_or(0, |m| c_int::from(m.model.is_built())),
        )
    }
}

/// pqp_model_end on up to `threads` threads: builds the same hierarchy, bit for bit, whatever the
/// number (so every query answers the same), in less time on a machine with several cores.
/// pqp_model_end (and PQP 1.3's EndModel through the C++ header) builds on the calling thread
/// only; this is the opt-in.
///
/// @param m        the model.
/// @param threads  how many threads may build (the calling thread among them): 0 for as many as
///                 the machine has cores; 1 as pqp_model_end. Any value is valid: more than the
///                 cores is allowed, and a small model (a few thousand triangles) is built on the
///                 calling thread whatever the value.
/// @return as pqp_model_end.
/// Thread safety: must not run concurrently with any other call using m. The threads it starts
/// have ended when it returns.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_end_threads(m: *mut pqp_model, threads: c_uint) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { status(|| deref_mut(m)?.model.end_threads(threads as usize)) }
}
