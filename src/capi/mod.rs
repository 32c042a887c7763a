//! The C ABI: `extern "C"` functions over the safe Rust API, declared in `include/pqp/pqp.h`
//! (generated from this module by cbindgen in `build.rs`; the doc comments here become the header's).
//!
//! This layer is thin: it checks pointers and arguments, calls [`crate::Model`],
//! [`crate::collide_into`], [`crate::distance_into`] and [`crate::tolerance_into`], and converts the
//! answers. Everything that decides an answer lives in the Rust core.
//!
//! Rules every exported function follows:
//! - Its whole body runs inside `boundary`, the one place where panics are caught: a panic becomes
//!   `PQP_ERR_INTERNAL` (or a documented fallback value for getters) and never unwinds into C.
//! - A NULL required pointer returns `PQP_ERR_NULL_POINTER` (getters return their fallback value).
//! - Handles are `Box` pointers: `into_handle` makes one and `free_handle` ends one; nothing else
//!   creates or frees them. The C types are opaque (cbindgen declares a Rust struct without
//!   `#[repr(C)]` as an incomplete struct).
//! - Nothing prints: a panic's message is swallowed by a panic hook that stays silent while a C ABI
//!   call is running on the thread (see `install_quiet_panic_hook`).
//!
//! Pointer requirements are the C convention and are stated once in the header's preamble: a
//! non-NULL pointer must point to what the documentation says (a live handle from the matching
//! `create`, or the stated number of doubles). Passing anything else is undefined behaviour the
//! library cannot detect.

// The exported functions take raw pointers from C; their safety contract is documented for C
// readers in the header preamble rather than in a `# Safety` section per function.
#![allow(clippy::missing_safety_doc)]

// In the order the header lists its functions, by topic (cbindgen follows the module order; the
// header's table of contents, in cbindgen.toml, names the same topics in the same order).
// Lifecycle and build.
mod model;
// Error texts and version.
mod misc;
// Pair queries: collision.
mod collide;
// Self-collision.
mod self_collide;
// Separation distance.
mod distance;
// Tolerance.
mod tolerance;
// Pairs within a distance.
mod within_distance;
// Point queries: closest point, signed distance.
mod point;
// Ray casting.
mod ray;
// Swept-sphere primitives as models: sphere, capsule, box.
mod primitive;
// Motion: refit of moving triangles.
mod refit;
// Time of first contact of moving models.
mod contact_time;
// Batches of collision, distance and tolerance queries on several threads.
mod batch;
// Saved models: serialize and deserialize.
mod saved;
// Convex polyhedra.
mod convex;
// PQP 1.3's view: single triangles and segments (TriDist.h).
mod geometry;
// A model's triangles and volumes in PQP 1.3's layout.
mod legacy;

pub use batch::*;
pub use collide::*;
pub use contact_time::*;
pub use convex::*;
pub use distance::*;
pub use geometry::*;
pub use legacy::*;
pub use misc::*;
pub use model::*;
pub use point::*;
pub use primitive::*;
pub use ray::*;
pub use refit::*;
pub use saved::*;
pub use self_collide::*;
pub use tolerance::*;
pub use within_distance::*;

use crate::error::Error;
use crate::math::Pose;
use crate::model::Model;
use crate::query::{Search, Strategy};
use std::cell::Cell;
use std::ffi::c_int;
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;

/// Success.
pub const PQP_OK: c_int = 0;
/// A model's storage could not be allocated.
pub const PQP_ERR_MODEL_OUT_OF_MEMORY: c_int = -1;
/// A query's working storage could not be allocated.
pub const PQP_ERR_OUT_OF_MEMORY: c_int = -2;
/// A query was given a model that is not built (pqp_model_end not called, or it failed).
pub const PQP_ERR_UNPROCESSED_MODEL: c_int = -3;
/// Model build calls out of order (see pqp_model_begin, pqp_model_add_tri, pqp_model_end).
pub const PQP_ERR_BUILD_OUT_OF_SEQUENCE: c_int = -4;
/// pqp_model_end on a model with no triangles.
pub const PQP_ERR_BUILD_EMPTY_MODEL: c_int = -5;
/// A vertex coordinate is NaN, infinite or larger in magnitude than 1e150; the triangle is refused
/// and the model stays usable. Also a ray's origin (NaN, infinite or beyond 1e150) or direction
/// (NaN or infinite) given to pqp_ray_cast or pqp_ray_cast_batch.
pub const PQP_ERR_NONFINITE_COORDINATE: c_int = -6;
/// A rotation or translation entry is NaN, infinite or larger in magnitude than 1e150.
pub const PQP_ERR_NONFINITE_POSE: c_int = -7;
/// An argument is out of its domain: unknown contact flag or volume choice, negative or NaN rel_err,
/// abs_err or tolerance, qsize < 1, a zero ray direction or a negative or NaN max_t.
pub const PQP_ERR_INVALID_ARGUMENT: c_int = -8;
/// A required pointer was NULL.
pub const PQP_ERR_NULL_POINTER: c_int = -9;
/// The library hit an internal fault (a bug); the call had no effect except that a query's result
/// object is reset to its freshly created state.
pub const PQP_ERR_INTERNAL: c_int = -10;
/// A point set given for a convex hull does not span a volume: no points, fewer than four distinct
/// points, or all of them collinear or coplanar.
pub const PQP_ERR_DEGENERATE_POINTS: c_int = -11;
/// A mesh given as a convex polyhedron is not a closed convex one: open, inconsistently oriented,
/// not a topological sphere, a face not planar or not strictly convex, an unused vertex, a vertex
/// above a face (not convex, or inside out), or flat.
pub const PQP_ERR_INVALID_CONVEX_MESH: c_int = -12;
/// A buffer for a saved model is NULL or smaller than the model needs (pqp_model_serialize): the
/// size it needs was written to *size and nothing else was written.
pub const PQP_ERR_BUFFER_TOO_SMALL: c_int = -13;
/// Bytes given as a saved model are not one (pqp_model_deserialize): wrong magic or version,
/// truncated, checksum mismatch, or contents that do not make a valid model.
pub const PQP_ERR_INVALID_DATA: c_int = -14;
/// The model holds a primitive (pqp_model_set_sphere, pqp_model_set_capsule, pqp_model_set_box)
/// and the call needs triangles or a hierarchy: closest point, signed distance, rays,
/// self-collision, time of contact, refit, serialize, PQP 1.3's volume view (pqp_model_bvs).
pub const PQP_ERR_NOT_A_TRIANGLE_MESH: c_int = -15;
/// Collision flag: report every colliding triangle pair.
pub const PQP_ALL_CONTACTS: c_int = 1;
/// Collision flag: stop at the first colliding triangle pair found.
pub const PQP_FIRST_CONTACT: c_int = 2;
/// Search strategy: the fastest measured for the query (priority-directed for distance, depth-first
/// for tolerance; the default).
pub const PQP_SEARCH_AUTO: c_int = 0;
/// Search strategy: depth-first, nearer pair first (PQP 1.3's search for qsize 1 or 2).
pub const PQP_SEARCH_DEPTH_FIRST: c_int = 1;
/// Search strategy: level by level.
pub const PQP_SEARCH_BREADTH_FIRST: c_int = 2;
/// Search strategy: priority-directed, nearest pending pair first.
pub const PQP_SEARCH_PRIORITY: c_int = 3;

/// How pqp_distance_search and pqp_tolerance_search search the bounding-volume test tree. Every
/// strategy gives the same exact distance; they differ in speed (see BENCHMARKS.md).
/// pqp_search_options_default fills one with the default, which pqp_distance and pqp_tolerance use.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct pqp_search_options {
    /// PQP_SEARCH_AUTO, PQP_SEARCH_DEPTH_FIRST, PQP_SEARCH_BREADTH_FIRST or PQP_SEARCH_PRIORITY.
    pub strategy: c_int,
    /// PQP_SEARCH_PRIORITY (and PQP_SEARCH_AUTO when it chooses it) only: the most pending pairs
    /// the queue holds (pairs that do not fit are searched depth-first at once, as PQP 1.3 did);
    /// 0 for unbounded. Must not be negative.
    pub qsize: c_int,
    /// 1: start from the closest triangle pair of the last query on the same two models, kept in
    /// the result object (triangle caching), and for a priority-directed distance query after a
    /// small motion from that query's BVTT front (front tracking); 0: start afresh.
    pub triangle_cache: c_int,
}

/// The code the C ABI returns for `r`.
pub(crate) fn code(r: Result<(), Error>) -> c_int {
    match r {
        Ok(()) => PQP_OK,
        Err(e) => e.code(),
    }
}

thread_local! {
    /// Whether this thread is inside a C ABI call (the quiet panic hook stays silent then).
    static IN_C_CALL: Cell<bool> = const { Cell::new(false) };
}

/// Makes panics raised inside C ABI calls silent, once per process: the library must never print.
///
/// The hook installed wraps the one in place before, which still reports panics raised outside C
/// ABI calls (for instance in a Rust program that links this crate).
fn install_quiet_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // Replacing the hook is refused while this thread panics; then stay with the old one.
        if std::thread::panicking() {
            return;
        }
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !IN_C_CALL.with(Cell::get) {
                previous(info);
            }
        }));
    });
}

/// Runs the body of an exported function: the one boundary every `extern "C"` function goes through.
///
/// Returns what `body` returns. If `body` panics, the panic is caught (it must not unwind into C),
/// `recover` is run to put any state the caller can see back into a defined shape, and `fallback` is
/// returned: `PQP_ERR_INTERNAL` for functions returning a status code, the documented NULL-input
/// value for getters.
pub(crate) fn boundary<T>(fallback: T, recover: impl FnOnce(), body: impl FnOnce() -> T) -> T {
    install_quiet_panic_hook();
    let outer = IN_C_CALL.with(|f| f.replace(true));
    let answer = match panic::catch_unwind(AssertUnwindSafe(body)) {
        Ok(v) => v,
        Err(payload) => {
            drop_payload(payload);
            if let Err(again) = panic::catch_unwind(AssertUnwindSafe(recover)) {
                drop_payload(again);
            }
            fallback
        }
    };
    IN_C_CALL.with(|f| f.set(outer));
    answer
}

/// Frees a caught panic's payload. Dropping it may itself panic (a payload with a panicking `Drop`);
/// that second payload is leaked rather than risk unwinding into C.
fn drop_payload(payload: Box<dyn std::any::Any + Send>) {
    if let Err(again) = panic::catch_unwind(AssertUnwindSafe(move || drop(payload))) {
        std::mem::forget(again);
    }
}

/// [`boundary`] for functions returning a status code.
pub(crate) fn status(body: impl FnOnce() -> Result<(), Error>) -> c_int {
    boundary(PQP_ERR_INTERNAL, || {}, || code(body()))
}

/// Moves `value` to the heap and returns the handle C holds: the only place handles are made.
/// Handles are `Box` allocations (freed by [`free_handle`] through `Box::from_raw`); they are
/// allocated by hand so that an allocation failure returns NULL instead of aborting the process.
pub(crate) fn into_handle<T>(value: T) -> *mut T {
    let layout = std::alloc::Layout::new::<T>();
    // Handles are never zero-sized, for which `alloc` would be undefined.
    const { assert!(std::mem::size_of::<T>() > 0) };
    // SAFETY: the layout has a non-zero size.
    let p = unsafe { std::alloc::alloc(layout) }.cast::<T>();
    if !p.is_null() {
        // SAFETY: `p` is fresh, writable and aligned for `T`.
        unsafe { p.write(value) };
    }
    p
}

/// The body of every `pqp_*_create` of a result or cache: a fresh object's handle, NULL if
/// memory could not be allocated.
pub(crate) fn new_handle<T: Default>() -> *mut T {
    boundary(std::ptr::null_mut(), || {}, || into_handle(T::default()))
}

/// The body of every `pqp_*_destroy`: frees the handle; NULL is accepted and ignored.
///
/// # Safety
/// As [`free_handle`].
pub(crate) unsafe fn destroy_handle<T>(h: *mut T) {
    // SAFETY: `h` is NULL or a handle of `T` not freed before (this function's contract).
    boundary((), || {}, || unsafe { free_handle(h) })
}

/// Frees a handle made by [`into_handle`]; NULL is accepted and ignored.
///
/// # Safety
/// `h` is NULL or a pointer returned by `into_handle::<T>` not freed before.
pub(crate) unsafe fn free_handle<T>(h: *mut T) {
    if !h.is_null() {
        // SAFETY: `h` came from `into_handle::<T>` (a `Box<T>` allocation) and is freed once.
        drop(unsafe { Box::from_raw(h) });
    }
}

/// The object behind a handle, or `Err(NullPointer)`.
///
/// # Safety
/// `h` is NULL or a live handle (the caller's contract, see the header).
pub(crate) unsafe fn deref<'a, T>(h: *const T) -> Result<&'a T, Error> {
    // SAFETY: `h` is NULL (then `as_ref` gives `None`) or a live handle.
    unsafe { h.as_ref() }.ok_or(Error::NullPointer)
}

/// The object behind a handle for modification, or `Err(NullPointer)`.
///
/// # Safety
/// As [`deref`], and no other reference to the object is alive (the caller's contract).
pub(crate) unsafe fn deref_mut<'a, T>(h: *mut T) -> Result<&'a mut T, Error> {
    // SAFETY: `h` is NULL or a live handle with no other reference to its object.
    unsafe { h.as_mut() }.ok_or(Error::NullPointer)
}

/// Copies `N` doubles from C, or `Err(NullPointer)`.
///
/// # Safety
/// `p` is NULL or points to `N` readable doubles.
pub(crate) unsafe fn read_doubles<const N: usize>(p: *const f64) -> Result<[f64; N], Error> {
    if p.is_null() {
        return Err(Error::NullPointer);
    }
    // C arrays of double are aligned, but nothing is lost by not relying on it.
    // SAFETY: `p` is not NULL, so it points to `N` readable doubles.
    Ok(unsafe { p.cast::<[f64; N]>().read_unaligned() })
}

/// A pose from C: `r` 9 doubles row by row, `t` 3 doubles.
///
/// # Safety
/// Each pointer is NULL or points to that many doubles.
pub(crate) unsafe fn read_pose(r: *const f64, t: *const f64) -> Result<Pose, Error> {
    // SAFETY: `r` is NULL or points to 9 doubles, `t` NULL or to 3.
    let (r, t): ([f64; 9], [f64; 3]) = unsafe { (read_doubles(r)?, read_doubles(t)?) };
    Ok(Pose::new(
        [[r[0], r[1], r[2]], [r[3], r[4], r[5]], [r[6], r[7], r[8]]],
        t,
    ))
}

/// What pqp_search_options_default gives.
pub(crate) const DEFAULT_SEARCH_OPTIONS: pqp_search_options = pqp_search_options {
    strategy: PQP_SEARCH_AUTO,
    qsize: Search::DEFAULT_QSIZE as c_int,
    triangle_cache: 1,
};

/// A search from C's options; NULL means the default search.
///
/// # Safety
/// `o` is NULL or points to a `pqp_search_options`.
pub(crate) unsafe fn read_search(o: *const pqp_search_options) -> Result<Search, Error> {
    // SAFETY: `o` is NULL or points to a `pqp_search_options`.
    let Some(o) = (unsafe { o.as_ref() }) else {
        return Ok(Search::default());
    };
    let strategy = match o.strategy {
        PQP_SEARCH_AUTO => Strategy::Auto,
        PQP_SEARCH_DEPTH_FIRST => Strategy::DepthFirst,
        PQP_SEARCH_BREADTH_FIRST => Strategy::BreadthFirst,
        PQP_SEARCH_PRIORITY => Strategy::Priority,
        _ => return Err(Error::InvalidArgument),
    };
    let qsize = match o.qsize {
        0 => usize::MAX,
        q => usize::try_from(q).map_err(|_| Error::InvalidArgument)?,
    };
    let triangle_cache = match o.triangle_cache {
        0 => false,
        1 => true,
        _ => return Err(Error::InvalidArgument),
    };
    Ok(Search {
        strategy,
        qsize,
        triangle_cache,
    })
}

/// A posed model as C passes it: rotation (9 doubles), translation (3 doubles), model.
pub(crate) type PosedModel = (*const f64, *const f64, *const pqp_model);

/// How a distance or tolerance entry point takes its search from C.
#[derive(Clone, Copy)]
pub(crate) enum SearchArg {
    /// PQP's queue size (pqp_distance, pqp_tolerance): at least 1, only checked; the default search.
    QueueSize(c_int),
    /// A `pqp_search_options` (pqp_distance_search, pqp_tolerance_search); NULL: the default.
    Options(*const pqp_search_options),
}

impl SearchArg {
    /// The search asked for, or `Err(InvalidArgument)`.
    ///
    /// # Safety
    /// An `Options` pointer is NULL or points to a `pqp_search_options`.
    unsafe fn read(self) -> Result<Search, Error> {
        match self {
            SearchArg::QueueSize(q) if q >= 1 => Ok(Search::default()),
            SearchArg::QueueSize(_) => Err(Error::InvalidArgument),
            // SAFETY: NULL or a `pqp_search_options` (this function's contract).
            SearchArg::Options(o) => unsafe { read_search(o) },
        }
    }
}

/// The checked arguments of a distance or tolerance query, as [`pair_query`] hands them on.
pub(crate) struct PairArgs<'a> {
    pub(crate) m1: &'a Model,
    pub(crate) pose1: Pose,
    pub(crate) m2: &'a Model,
    pub(crate) pose2: Pose,
    pub(crate) search: Search,
}

/// Runs a distance or tolerance entry point: inside [`boundary`] (an internal fault resets `r`),
/// checks the result, each posed model (pointers, then pose entries) and the search, in that order,
/// and hands them to `run`, whose code it returns. The query's own arguments (error bounds,
/// tolerance) are checked by the core query `run` calls.
///
/// # Safety
/// Every pointer is NULL or valid as the header requires: `r` a live result no other call uses,
/// poses 9 and 3 doubles, models live handles, search options as [`SearchArg::read`] needs.
pub(crate) unsafe fn pair_query<R: Default>(
    r: *mut R,
    (r1, t1, m1): PosedModel,
    (r2, t2, m2): PosedModel,
    search: SearchArg,
    run: impl FnOnce(&mut R, PairArgs<'_>) -> Result<(), Error>,
) -> c_int {
    let checked = || -> Result<(), Error> {
        // SAFETY: every pointer is NULL or valid (this function's contract).
        let (result, args) = unsafe {
            let result = deref_mut(r)?;
            let (pose1, m1) = (read_pose(r1, t1)?, deref(m1)?);
            let (pose2, m2) = (read_pose(r2, t2)?, deref(m2)?);
            let search = search.read()?;
            let (m1, m2) = (&m1.model, &m2.model);
            (
                result,
                PairArgs {
                    m1,
                    pose1,
                    m2,
                    pose2,
                    search,
                },
            )
        };
        run(result, args)
    };
    // SAFETY: `r` is NULL or a live result (this function's contract).
    boundary(PQP_ERR_INTERNAL, || unsafe { reset(r) }, || code(checked()))
}

/// Resets a result to its freshly created state after an internal fault, so that C never sees a
/// half-written answer.
///
/// # Safety
/// `r` is NULL or a live handle.
pub(crate) unsafe fn reset<T: Default>(r: *mut T) {
    // SAFETY: `r` is NULL or a live handle (this function's contract).
    if let Ok(r) = unsafe { deref_mut(r) } {
        *r = T::default();
    }
}

/// The body of pqp_distance_result_triangles and pqp_tolerance_result_triangles: writes the
/// triangle pair `pair` reads from the result `r` to `t1` and `t2` (nothing when either is NULL).
///
/// # Safety
/// `r` is NULL or a live handle no other call modifies meanwhile; `t1` and `t2` are NULL or
/// writable.
pub(crate) unsafe fn write_triangles<R>(
    r: *const R,
    t1: *mut c_int,
    t2: *mut c_int,
    pair: impl FnOnce(&R) -> (i32, i32),
) -> c_int {
    status(|| {
        // SAFETY: `r` is NULL or a live handle (this function's contract).
        let (a, b) = pair(unsafe { deref(r) }?);
        if t1.is_null() || t2.is_null() {
            return Err(Error::NullPointer);
        }
        // SAFETY: neither pointer is NULL, so both are writable (this function's contract).
        unsafe {
            t1.write(a);
            t2.write(b);
        }
        Ok(())
    })
}

/// Runs a result getter: inside [`boundary`], `get` of the object behind `r`, or `fallback` when
/// `r` is NULL (or `get` panics). Every `pqp_*_result_*` getter is one call of this.
///
/// # Safety
/// `r` is NULL or a live handle of its kind, not modified during the call.
pub(crate) unsafe fn getter<T, V: Copy>(r: *const T, fallback: V, get: impl FnOnce(&T) -> V) -> V {
    boundary(
        fallback,
        || {},
        // SAFETY: `r` is NULL or a live handle (this function's contract).
        || unsafe { deref(r) }.map_or(fallback, get),
    )
}

/// A counter for C's `int64_t` (saturating; no query performs 2^63 tests).
pub(crate) fn count(n: u64) -> i64 {
    i64::try_from(n).unwrap_or(i64::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_the_fallback_and_recover_runs() {
        let mut recovered = false;
        let v = boundary(
            PQP_ERR_INTERNAL,
            || recovered = true,
            || -> c_int { panic!("bug") },
        );
        assert_eq!(v, PQP_ERR_INTERNAL);
        assert!(recovered);
        // The thread is usable afterwards and the flag is restored.
        assert_eq!(boundary(-1, || {}, || 5), 5);
        assert!(!IN_C_CALL.with(Cell::get));
    }

    #[test]
    fn a_panicking_recover_is_contained() {
        let v = boundary(7, || panic!("recover bug"), || -> i32 { panic!("bug") });
        assert_eq!(v, 7);
    }

    #[test]
    fn status_maps_results() {
        assert_eq!(status(|| Ok(())), PQP_OK);
        assert_eq!(status(|| Err(Error::NullPointer)), PQP_ERR_NULL_POINTER);
        assert_eq!(status(|| panic!("bug")), PQP_ERR_INTERNAL);
    }
}
