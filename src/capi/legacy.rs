//! PQP 1.3's view of a model, for programs that read its internals (`PQP_Model::tris`, `b`,
//! `num_bvs`, `child(n)`), and the functions of PQP's `BV.h` (fit, overlap, distance of volumes).
//!
//! The view is made on first request and kept in the model handle (one per kind and precision),
//! so a model that is never looked at this way costs nothing more. Build calls drop or update it.

#![allow(non_snake_case)] // R, Tr, To, l, r, d: PQP's names, which the header shows.

use super::{PQP_ERR_INTERNAL, boundary, code, deref, pqp_model, read_doubles};
use crate::bounding_volume::{Obb, OverlapVolume, Ssv, SsvKind, rect_distance};
use crate::bvh::PqpBv;
use crate::error::{Error, MAX_COORDINATE};
use crate::geometry::Tri;
use crate::math::{Mat3, Pose, RelPose, Vec3};
use crate::model::Model;
use std::cell::UnsafeCell;
use std::ffi::c_int;
use std::ptr;
use std::sync::OnceLock;

/// A triangle as PQP 1.3's `Tri` holds it (pqp_model_tris): its vertices and the id given to
/// pqp_model_add_tri.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct pqp_tri {
    /// First vertex (x, y, z in the model's frame).
    pub p1: [f64; 3],
    /// Second vertex.
    pub p2: [f64; 3],
    /// Third vertex.
    pub p3: [f64; 3],
    /// The caller's id.
    pub id: c_int,
}

/// pqp_tri with float coordinates (pqp_model_tris_float), for code compiled with PQP_REAL float:
/// the same values rounded to float (beyond float's range: +-infinity).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct pqp_tri_float {
    /// First vertex.
    pub p1: [f32; 3],
    /// Second vertex.
    pub p2: [f32; 3],
    /// Third vertex.
    pub p3: [f32; 3],
    /// The caller's id.
    pub id: c_int,
}

/// A bounding volume as PQP 1.3's `BV` holds it (pqp_model_bvs): a frame, a rectangle swept
/// sphere and an oriented box on it, and where its children are.
///
/// With R, Tr and To in model coordinates, the rectangle swept sphere is the set of points within
/// r of `{ Tr + x * axis0 + y * axis1 : 0 <= x <= l[0], 0 <= y <= l[1] }` and the box is
/// `{ To + c0 * axis0 + c1 * axis1 + c2 * axis2 : |ci| <= d[i] }`, axis i being column i of R. In
/// pqp_model_bvs's array (as in PQP's) only the root's R, Tr and To are in model coordinates;
/// every other volume's are relative to its parent's: with Ra, Tra, Toa a volume's values in
/// model coordinates and Rp, Trp, Top its parent's, the array holds R = Rp^T Ra,
/// Tr = Rp^T (Tra - Trp) and To = Rp^T (Toa - Top) (so Ra = Rp R, Tra = Rp Tr + Trp,
/// Toa = Rp To + Top, composed from the root down). A model built with PQP_BV_PSS, PQP_BV_LSS or
/// PQP_BV_HYBRID has point or segment cores in some volumes: rectangles with zero sides.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct pqp_bv {
    /// Orientation, row by row (`R[row][col]`): its columns are the volume's axes.
    pub R: [[f64; 3]; 3],
    /// Rectangle swept sphere: the rectangle's corner.
    pub Tr: [f64; 3],
    /// Rectangle swept sphere: the rectangle's sides along the first two axes (>= 0).
    pub l: [f64; 2],
    /// Rectangle swept sphere: the radius (>= 0).
    pub r: f64,
    /// Oriented box: its centre.
    pub To: [f64; 3],
    /// Oriented box: its half extents along the axes (>= 0).
    pub d: [f64; 3],
    /// Where the children are: when first_child >= 0 they are at first_child and first_child + 1
    /// (both after this volume in the array); when first_child < 0 this is a leaf, holding
    /// triangle -first_child - 1 of pqp_model_tris (PQP's encoding).
    pub first_child: c_int,
}

/// pqp_bv with float values (pqp_model_bvs_float), for code compiled with PQP_REAL float: the
/// same values rounded to float (beyond float's range: +-infinity).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct pqp_bv_float {
    /// Orientation, row by row (`R[row][col]`): its columns are the volume's axes.
    pub R: [[f32; 3]; 3],
    /// Rectangle swept sphere: the rectangle's corner.
    pub Tr: [f32; 3],
    /// Rectangle swept sphere: the rectangle's sides.
    pub l: [f32; 2],
    /// Rectangle swept sphere: the radius.
    pub r: f32,
    /// Oriented box: its centre.
    pub To: [f32; 3],
    /// Oriented box: its half extents.
    pub d: [f32; 3],
    /// As in pqp_bv.
    pub first_child: c_int,
}

/// An entry of the triangle view, made from a triangle and its id.
trait ViewTri: Copy + Default {
    fn new(t: &Tri, id: i32) -> Self;
}

impl ViewTri for pqp_tri {
    fn new(t: &Tri, id: i32) -> Self {
        pqp_tri {
            p1: t[0].into(),
            p2: t[1].into(),
            p3: t[2].into(),
            id,
        }
    }
}

impl ViewTri for pqp_tri_float {
    fn new(t: &Tri, id: i32) -> Self {
        let f = |v: &Vec3| [v.x as f32, v.y as f32, v.z as f32];
        pqp_tri_float {
            p1: f(&t[0]),
            p2: f(&t[1]),
            p3: f(&t[2]),
            id,
        }
    }
}

/// An entry of the volume view, made from the core's record of it.
trait ViewBv: Copy + Default {
    fn new(bv: &PqpBv) -> Self;
}

impl ViewBv for pqp_bv {
    fn new(bv: &PqpBv) -> Self {
        let m = &bv.rot;
        pqp_bv {
            R: [0, 1, 2].map(|i| [m[(i, 0)], m[(i, 1)], m[(i, 2)]]),
            Tr: bv.corner.into(),
            l: bv.lengths,
            r: bv.radius,
            To: bv.center.into(),
            d: bv.half.into(),
            first_child: bv.first_child,
        }
    }
}

impl ViewBv for pqp_bv_float {
    fn new(bv: &PqpBv) -> Self {
        // Rounded from the double view's values, so that the two agree.
        let b = pqp_bv::new(bv);
        let f = |v: f64| v as f32;
        pqp_bv_float {
            R: b.R.map(|row| row.map(f)),
            Tr: b.Tr.map(f),
            l: b.l.map(f),
            r: f(b.r),
            To: b.To.map(f),
            d: b.d.map(f),
            first_child: b.first_child,
        }
    }
}

/// The views a model handle keeps, each made on first request (see the module's doc). Build calls
/// update or drop them (see [`LegacyView::begun`] and [`LegacyView::added`]; `end` leaves them: the
/// triangles in the order added are the same before and after it, and a model that was not built
/// had no volume view while one that was is left unchanged).
#[derive(Debug, Default)]
pub(crate) struct LegacyView {
    tris: OnceLock<Vec<Entry<pqp_tri>>>,
    tris_float: OnceLock<Vec<Entry<pqp_tri_float>>>,
    bvs: OnceLock<Vec<Entry<pqp_bv>>>,
    bvs_float: OnceLock<Vec<Entry<pqp_bv_float>>>,
}

/// An entry of a view. C reads it through the `const` pointer the getters give, but PQP 1.3's
/// members were plain pointers, and PQP.h hands C++ programs non-`const` ones, through which a
/// program may write: the cell makes such writes legitimate, as writes through a shared reference
/// are not. Laid out as `T` (the getters hand out the array as one of `T`).
#[repr(transparent)]
#[derive(Debug)]
struct Entry<T>(UnsafeCell<T>);

impl<T> Entry<T> {
    fn new(value: T) -> Self {
        Entry(UnsafeCell::new(value))
    }
}

// SAFETY: Rust code never reads an entry after storing it (appending moves entries, under the
// `&mut` of a build call, which excludes every other call on the model); the entries' values are
// plain data (`Send`), and ordering C's reads and writes of them is the C program's part, as for
// any array it writes to.
unsafe impl<T: Send> Sync for Entry<T> {}

impl LegacyView {
    /// After `begin`: the model is cleared, so is every view.
    pub(crate) fn begun(&mut self) {
        *self = LegacyView::default();
    }

    /// After a refit: every triangle and volume moved, so every view is dropped (the next request
    /// makes it afresh).
    pub(crate) fn refitted(&mut self) {
        *self = LegacyView::default();
    }

    /// After `add_tri`: a stored triangle `t` (in `Some`) is appended to the triangle views that
    /// exist (dropping one that cannot grow), so that a caller reading the triangles after every
    /// add does linear work in all, not quadratic. A model being built has no volume view.
    pub(crate) fn added(&mut self, stored: Option<(Tri, i32)>) {
        let Some((t, id)) = stored else { return };
        fn append<T: ViewTri>(cell: &mut OnceLock<Vec<Entry<T>>>, t: &Tri, id: i32) {
            if let Some(v) = cell.get_mut() {
                if v.try_reserve(1).is_ok() {
                    v.push(Entry::new(T::new(t, id)));
                } else {
                    cell.take();
                }
            }
        }
        append(&mut self.tris, &t, id);
        append(&mut self.tris_float, &t, id);
        self.bvs.take();
        self.bvs_float.take();
    }

    /// Bytes the views hold.
    pub(crate) fn memory_usage(&self) -> usize {
        fn bytes<T>(cell: &OnceLock<Vec<Entry<T>>>) -> usize {
            cell.get()
                .map_or(0, |v| v.capacity() * std::mem::size_of::<T>())
        }
        bytes(&self.tris) + bytes(&self.tris_float) + bytes(&self.bvs) + bytes(&self.bvs_float)
    }
}

/// The view in `cell`, made by `make` if there is none yet. Threads asking at once may each make
/// one; the first stored is kept and every caller gets it. A failed `make` stores nothing.
fn view<T>(
    cell: &OnceLock<Vec<Entry<T>>>,
    make: impl FnOnce() -> Result<Vec<Entry<T>>, Error>,
) -> Result<&[Entry<T>], Error> {
    if let Some(v) = cell.get() {
        return Ok(v);
    }
    let made = make()?;
    // Another thread may have stored its view first: then `made` is dropped, theirs is the same.
    let _ = cell.set(made);
    cell.get().map(Vec::as_slice).ok_or(Error::Internal)
}

/// `n` default entries, or `Err(ModelOutOfMemory)`.
fn filled<T: Copy + Default>(n: usize) -> Result<Vec<Entry<T>>, Error> {
    let mut v = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|_| Error::ModelOutOfMemory)?;
    v.extend((0..n).map(|_| Entry::new(T::default())));
    Ok(v)
}

/// Every triangle of `model` in the order added.
fn make_tris<T: ViewTri>(model: &Model) -> Result<Vec<Entry<T>>, Error> {
    let mut v = filled::<T>(model.num_triangles())?;
    model.for_each_added(|k, t, id| v[k] = Entry::new(T::new(&t, id)));
    Ok(v)
}

/// The volumes of a built `model` in PQP's layout.
fn make_bvs<T: ViewBv>(model: &Model) -> Result<Vec<Entry<T>>, Error> {
    let bvh = model.bvh()?;
    let n = 2 * bvh.num_tris() - 1;
    // The count and the child indices are C ints.
    if n > c_int::MAX as usize {
        return Err(Error::ModelOutOfMemory);
    }
    let mut v = filled::<T>(n)?;
    bvh.pqp_view(|k, bv| v[k] = Entry::new(T::new(&bv)))?;
    Ok(v)
}

/// Writes NULL and 0 to whichever of the two out pointers is not NULL.
///
/// # Safety
/// Each pointer is NULL or writable.
unsafe fn clear<T>(out: *mut *const T, count: *mut c_int) {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if !out.is_null() {
            out.write(ptr::null());
        }
        if !count.is_null() {
            count.write(0);
        }
    }
}

/// The body of the view getters, inside the boundary: hands the view `get` gives to C (NULL and
/// 0 on any error, and NULL for an empty view), and returns the code.
///
/// # Safety
/// `m` is NULL or a live handle; `out` and `count` are NULL or writable.
unsafe fn hand_out<T>(
    m: *const pqp_model,
    out: *mut *const T,
    count: *mut c_int,
    get: impl FnOnce(&pqp_model) -> Result<&[Entry<T>], Error>,
) -> c_int {
    let body = || -> Result<(), Error> {
        // SAFETY: `m` is NULL or a live handle, `out` and `count` NULL or writable (this
        // function's contract); neither is written through unless checked non-NULL.
        unsafe {
            clear(out, count);
            let m = deref(m)?;
            if out.is_null() || count.is_null() {
                return Err(Error::NullPointer);
            }
            let v = get(m)?;
            // Views hold at most a C int's count of entries (see make_bvs; num_tris is one already).
            let n = c_int::try_from(v.len()).map_err(|_| Error::ModelOutOfMemory)?;
            out.write(if v.is_empty() {
                ptr::null()
            } else {
                // `Entry<T>` is laid out as `T`.
                v.as_ptr().cast::<T>()
            });
            count.write(n);
            Ok(())
        }
    };
    // SAFETY: as above.
    boundary(
        PQP_ERR_INTERNAL,
        || unsafe { clear(out, count) },
        || code(body()),
    )
}

/// PQP 1.3's PQP_Model::tris and num_tris: every triangle of a model, in the order added, with its
/// id, as double.
///
/// Made on the first call and kept in the model (pqp_model_memory_usage counts it from then on);
/// later calls return the same array. While a model is being built it holds the triangles added so
/// far; a triangle refused by pqp_model_add_tri is not in it.
///
/// @param m         the model, in any state.
/// @param tris      receives the array (owned by m; NULL when the model holds no triangle, and on
///                  any error). It stays valid, and its contents unchanged, until the next
///                  pqp_model_begin, pqp_model_add_tri, pqp_model_end or
///                  pqp_model_refit on m, or pqp_model_destroy(m).
/// @param num_tris  receives the number of triangles (0 on any error).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m, tris or num_tris is NULL;
///         PQP_ERR_MODEL_OUT_OF_MEMORY if the array could not be allocated; PQP_ERR_INTERNAL on an
///         internal fault.
/// Thread safety: may run concurrently with queries and other getters on m (threads asking at once
///                all get the same array), not with build calls on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_tris(
    m: *const pqp_model,
    tris: *mut *const pqp_tri,
    num_tris: *mut c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        hand_out(m, tris, num_tris, |m| {
            view(&m.view.tris, || make_tris(&m.model))
        })
    }
}

/// PQP 1.3's PQP_Model::b and num_bvs: the bounding-volume hierarchy of a built model, in PQP's
/// layout and frames (see pqp_bv).
///
/// There are exactly 2 n - 1 volumes for n triangles. `b[0]` is the root. The children of a volume
/// are at first_child and first_child + 1, both after it; they were given out depth first, as PQP
/// did (when a volume is expanded its two children take the next two free slots, then the first
/// child's subtree is laid out before the second's). A leaf's first_child is -(t + 1), t being its
/// triangle's index in pqp_model_tris (the order added); a one-triangle model has one volume, a
/// leaf with first_child -1. Each volume contains its triangles. Inner volumes are those the
/// queries use; a leaf's are the rectangle around its triangle and the box on that rectangle's
/// axes.
///
/// Made on the first call and kept in the model (pqp_model_memory_usage counts it from then on);
/// later calls return the same array.
///
/// @param m        the model.
/// @param bvs      receives the array (owned by m; NULL on any error). It stays valid, and its
///                 contents unchanged, until the next pqp_model_begin, pqp_model_add_tri,
///                 pqp_model_end or pqp_model_refit on m, or pqp_model_destroy(m).
/// @param num_bvs  receives the number of volumes (0 on any error).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m, bvs or num_bvs is NULL; PQP_ERR_UNPROCESSED_MODEL if
///         m is not built; PQP_ERR_MODEL_OUT_OF_MEMORY if the array could not be allocated;
///         PQP_ERR_NOT_A_TRIANGLE_MESH if m holds a primitive (pqp_model_set_sphere, ...);
///         PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may run concurrently with queries and other getters on m (threads asking at once
///                all get the same array), not with build calls on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_bvs(
    m: *const pqp_model,
    bvs: *mut *const pqp_bv,
    num_bvs: *mut c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        hand_out(m, bvs, num_bvs, |m| {
            view(&m.view.bvs, || make_bvs(&m.model))
        })
    }
}

/// As pqp_model_tris, with float coordinates (pqp_tri_float): for code compiled with PQP_REAL
/// float. The values are pqp_model_tris's rounded to float. Kept apart from the double array.
///
/// @param m         the model, in any state.
/// @param tris      receives the array (owned by m; NULL when the model holds no triangle, and on
///                  any error), valid as pqp_model_tris's.
/// @param num_tris  receives the number of triangles (0 on any error).
/// @return PQP_OK, or as pqp_model_tris (PQP_ERR_NULL_POINTER, PQP_ERR_MODEL_OUT_OF_MEMORY,
///         PQP_ERR_INTERNAL).
/// Thread safety: as pqp_model_tris.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_tris_float(
    m: *const pqp_model,
    tris: *mut *const pqp_tri_float,
    num_tris: *mut c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        hand_out(m, tris, num_tris, |m| {
            view(&m.view.tris_float, || make_tris(&m.model))
        })
    }
}

/// As pqp_model_bvs, with float values (pqp_bv_float): for code compiled with PQP_REAL float. The
/// values are pqp_model_bvs's rounded to float. Kept apart from the double array.
///
/// @param m        the model.
/// @param bvs      receives the array (owned by m; NULL on any error), valid as pqp_model_bvs's.
/// @param num_bvs  receives the number of volumes (0 on any error).
/// @return PQP_OK, or as pqp_model_bvs (PQP_ERR_NULL_POINTER, PQP_ERR_UNPROCESSED_MODEL,
///         PQP_ERR_MODEL_OUT_OF_MEMORY, PQP_ERR_INTERNAL).
/// Thread safety: as pqp_model_bvs.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_bvs_float(
    m: *const pqp_model,
    bvs: *mut *const pqp_bv_float,
    num_bvs: *mut c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        hand_out(m, bvs, num_bvs, |m| {
            view(&m.view.bvs_float, || make_bvs(&m.model))
        })
    }
}

/// The rotation and translation of PQP's BV functions, checked as a pose.
///
/// # Safety
/// Each pointer is NULL or points to that many doubles.
unsafe fn read_placement(R: *const f64, T: *const f64) -> Result<RelPose, Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        let pose: Pose = super::read_pose(R, T)?;
        pose.validate()?;
        Ok(RelPose {
            rot: pose.rotation,
            trans: pose.translation,
        })
    }
}

/// `v` if it is a size a volume can have: `Err(NonFiniteCoordinate)` for NaN, infinity or a
/// magnitude beyond 1e150, `Err(InvalidArgument)` below 0.
fn size(v: f64) -> Result<f64, Error> {
    if !(v.is_finite() && v.abs() <= MAX_COORDINATE) {
        Err(Error::NonFiniteCoordinate)
    } else if v < 0.0 {
        Err(Error::InvalidArgument)
    } else {
        Ok(v)
    }
}

/// PQP 1.3's BV::FitToTris: fits a volume's rectangle swept sphere and box, on the axes given, to
/// every vertex of some triangles.
///
/// bv->R becomes O; Tr, l and r become the smallest rectangle swept sphere the library's fit finds
/// on those axes (the rectangle on the first two) and To, d the tightest box on them, both
/// containing every vertex of the triangles and given in the triangles' coordinates (as PQP's:
/// pqp_model_bvs then makes them relative to the parent). bv->first_child is left as it was.
///
/// @param bv        the volume to fill.
/// @param O         the axes, 9 doubles row by row: its columns are the axes, which must be
///                  orthonormal (not checked: otherwise the volumes need not contain the vertices).
///                  PQP used the principal axes of the vertices, the first of largest spread.
/// @param tris      the triangles, num_tris of them (their ids are not read).
/// @param num_tris  how many, >= 1.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if bv, O or tris is NULL; PQP_ERR_INVALID_ARGUMENT if
///         num_tris < 1; PQP_ERR_NONFINITE_POSE if an entry of O is NaN, infinite or larger than
///         1e150 in magnitude; PQP_ERR_NONFINITE_COORDINATE if a vertex coordinate is;
///         PQP_ERR_OUT_OF_MEMORY if working storage could not be allocated; PQP_ERR_INTERNAL on an
///         internal fault. On any error *bv is left unchanged.
/// Thread safety: may be called from any thread at any time; bv must not be used by another
///                thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_bv_fit(
    bv: *mut pqp_bv,
    O: *const f64,
    tris: *const pqp_tri,
    num_tris: c_int,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe { boundary(PQP_ERR_INTERNAL, || {}, || code(fit(bv, O, tris, num_tris))) }
}

/// The body of pqp_bv_fit.
///
/// # Safety
/// As pqp_bv_fit's pointers.
unsafe fn fit(
    bv: *mut pqp_bv,
    O: *const f64,
    tris: *const pqp_tri,
    num_tris: c_int,
) -> Result<(), Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if bv.is_null() || tris.is_null() {
            return Err(Error::NullPointer);
        }
        let o: [f64; 9] = read_doubles(O)?;
        let n = usize::try_from(num_tris)
            .ok()
            .filter(|&n| n > 0)
            .ok_or(Error::InvalidArgument)?;
        if !o.iter().all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE) {
            return Err(Error::NonFinitePose);
        }
        let axes = Mat3::new(o[0], o[1], o[2], o[3], o[4], o[5], o[6], o[7], o[8]);
        let mut points: Vec<Vec3> = Vec::new();
        points
            .try_reserve_exact(3 * n)
            .map_err(|_| Error::OutOfMemory)?;
        for i in 0..n {
            let t = tris.add(i).read_unaligned();
            for p in [t.p1, t.p2, t.p3] {
                if !p.iter().all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE) {
                    return Err(Error::NonFiniteCoordinate);
                }
                points.push(p.into());
            }
        }
        let ssv = Ssv::fit(SsvKind::Rect, &axes, &points);
        let obb = Obb::fit(&axes, &points);
        let out = &mut *bv;
        out.R = [[o[0], o[1], o[2]], [o[3], o[4], o[5]], [o[6], o[7], o[8]]];
        out.Tr = ssv.origin.into();
        out.l = ssv.lengths;
        out.r = ssv.radius;
        out.To = obb.center.into();
        out.d = obb.half.into();
        Ok(())
    }
}

/// PQP 1.3's BV_Overlap: whether the boxes of two volumes overlap, the second placed in the
/// first's frame by (R, T).
///
/// Each box is taken in its volume's own frame, about that frame's origin: box 1 is
/// `{ x : |x_i| <= b1->d[i] }`, box 2 is `{ y : |y_i| <= b2->d[i] }`, and a point y of box 2's
/// frame is R y + T in box 1's. The volumes' R, Tr, To, l and r are not read (PQP's callers fold
/// the volumes' frames and centres into R and T). The test is conservative: it never answers 0
/// for boxes that share a point (touching counts as overlapping); for boxes apart by less than a
/// rounding allowance (a few ulps of the magnitudes involved) it may answer 1.
///
/// @param overlap  receives 1 if the boxes overlap, else 0 (unchanged on any error).
/// @param R        the rotation of box 2's frame in box 1's, 9 doubles row by row (a rotation; not
///                 checked).
/// @param T        the translation, 3 doubles.
/// @param b1, b2   the volumes (only d is read).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_NONFINITE_POSE if an entry
///         of R or T is NaN, infinite or larger than 1e150 in magnitude;
///         PQP_ERR_NONFINITE_COORDINATE if a half extent is, PQP_ERR_INVALID_ARGUMENT if one is
///         negative; PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_bv_overlap(
    overlap: *mut c_int,
    R: *const f64,
    T: *const f64,
    b1: *const pqp_bv,
    b2: *const pqp_bv,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            PQP_ERR_INTERNAL,
            || {},
            || code(boxes_overlap(overlap, R, T, b1, b2)),
        )
    }
}

/// The body of pqp_bv_overlap.
///
/// # Safety
/// As pqp_bv_overlap's pointers.
unsafe fn boxes_overlap(
    overlap: *mut c_int,
    R: *const f64,
    T: *const f64,
    b1: *const pqp_bv,
    b2: *const pqp_bv,
) -> Result<(), Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if overlap.is_null() {
            return Err(Error::NullPointer);
        }
        let rel = read_placement(R, T)?;
        let (b1, b2) = (deref(b1)?, deref(b2)?);
        let about_origin = |d: &[f64; 3]| -> Result<Obb, Error> {
            Ok(Obb {
                axes: Mat3::identity(),
                center: Vec3::zeros(),
                half: Vec3::new(size(d[0])?, size(d[1])?, size(d[2])?),
            })
        };
        let (a, b) = (about_origin(&b1.d)?, about_origin(&b2.d)?);
        overlap.write(c_int::from(Obb::overlap(&a, &b, &rel)));
        Ok(())
    }
}

/// PQP 1.3's BV_Distance: the distance between the rectangle swept spheres of two volumes, the
/// second placed in the first's frame by (R, T).
///
/// Each rectangle is taken in its volume's own frame, with its corner at that frame's origin:
/// rectangle 1 is `[0, b1->l[0]] x [0, b1->l[1]]` in the xy-plane of frame 1, rectangle 2 likewise
/// in frame 2, and a point y of frame 2 is R y + T in frame 1. The answer is the distance between
/// the two rectangles (exact up to rounding, by the library's rectangle kernel) less both radii:
/// the distance between the swept sphere volumes when they are apart, negative when they overlap
/// deeper than touching (as PQP's). The volumes' R, Tr, To and d are not read (PQP's callers fold
/// the volumes' frames and corners into R and T).
///
/// @param distance  receives the distance (unchanged on any error).
/// @param R         the rotation of frame 2 in frame 1, 9 doubles row by row (a rotation; not
///                  checked).
/// @param T         the translation, 3 doubles.
/// @param b1, b2    the volumes (only l and r are read).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_NONFINITE_POSE if an entry
///         of R or T is NaN, infinite or larger than 1e150 in magnitude;
///         PQP_ERR_NONFINITE_COORDINATE if a side or radius is, PQP_ERR_INVALID_ARGUMENT if one is
///         negative; PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_bv_distance(
    distance: *mut f64,
    R: *const f64,
    T: *const f64,
    b1: *const pqp_bv,
    b2: *const pqp_bv,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        boundary(
            PQP_ERR_INTERNAL,
            || {},
            || code(volumes_distance(distance, R, T, b1, b2)),
        )
    }
}

/// The body of pqp_bv_distance.
///
/// # Safety
/// As pqp_bv_distance's pointers.
unsafe fn volumes_distance(
    distance: *mut f64,
    R: *const f64,
    T: *const f64,
    b1: *const pqp_bv,
    b2: *const pqp_bv,
) -> Result<(), Error> {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        if distance.is_null() {
            return Err(Error::NullPointer);
        }
        let rel = read_placement(R, T)?;
        let (b1, b2) = (deref(b1)?, deref(b2)?);
        let l1 = [size(b1.l[0])?, size(b1.l[1])?];
        let l2 = [size(b2.l[0])?, size(b2.l[1])?];
        let radii = size(b1.r)? + size(b2.r)?;
        // Exact: no early stop (enough 0), no cutoff.
        let (d, _) = rect_distance(&rel.rot, &rel.trans, l1, l2, 0.0, f64::INFINITY, true);
        distance.write(d - radii);
        Ok(())
    }
}
