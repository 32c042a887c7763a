//! The query functions: model pairs, points, rays and batches. Each checks its arguments (naming
//! the one at fault), then runs with the GIL released.

use crate::convert::{bad, batch_poses, lib_err, pose, pose_pairs, rows3};
use crate::model::PyModel;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pqp::geometry::tri_distance;
use pqp::{ContactMode, DistanceOptions, Pose, Search, Vec3};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::ops::Deref;

/// A model argument: a `pqp.Model`, or a mesh built for this call from a `(vertices, faces)`
/// pair or an object with `vertices` and `faces` (a `trimesh.Trimesh`).
pub enum ModelArg<'py> {
    Ref(PyRef<'py, PyModel>),
    Own(Box<PyModel>),
}

impl Deref for ModelArg<'_> {
    type Target = PyModel;
    fn deref(&self) -> &PyModel {
        match self {
            ModelArg::Ref(r) => r,
            ModelArg::Own(m) => m,
        }
    }
}

/// Reads a model argument (see [`ModelArg`]).
pub fn model_arg<'py>(obj: &Bound<'py, PyAny>, name: &str) -> PyResult<ModelArg<'py>> {
    let py = obj.py();
    if let Ok(m) = obj.cast::<PyModel>() {
        return m
            .try_borrow()
            .map(ModelArg::Ref)
            .map_err(|_| bad(name, "the model is being refitted by another thread"));
    }
    let named = |e: PyErr| bad(name, e.value(py).to_string());
    if obj.is_instance_of::<PyTuple>() && obj.len()? == 2 {
        let (v, f) = (obj.get_item(0)?, obj.get_item(1)?);
        return PyModel::from_arrays(py, &v, &f, 0)
            .map(|m| ModelArg::Own(Box::new(m)))
            .map_err(named);
    }
    match PyModel::from_mesh_like(py, obj).map_err(named)? {
        Some(m) => Ok(ModelArg::Own(Box::new(m))),
        None => Err(bad(
            name,
            "expected a pqp.Model, a (vertices, faces) pair or a mesh with vertices and faces",
        )),
    }
}

/// `(p, 2)` int64 array of face pairs.
fn pairs_array<'py>(py: Python<'py>, pairs: &[(i32, i32)]) -> Bound<'py, PyArray2<i64>> {
    let flat: Vec<i64> = pairs
        .iter()
        .flat_map(|&(a, b)| [a as i64, b as i64])
        .collect();
    Array2::from_shape_vec((pairs.len(), 2), flat)
        .expect("p x 2")
        .into_pyarray(py)
}

/// `(q, 3)` float64 array.
fn rows_array<'py>(py: Python<'py>, rows: Vec<[f64; 3]>) -> Bound<'py, PyArray2<f64>> {
    let n = rows.len();
    Array2::from_shape_vec((n, 3), rows.into_flattened())
        .expect("q x 3")
        .into_pyarray(py)
}

fn vec3(v: &Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

fn check_nonneg(v: f64, name: &str) -> PyResult<()> {
    if v.is_nan() || v < 0.0 {
        Err(bad(name, format!("must be >= 0, got {v}")))
    } else {
        Ok(())
    }
}

fn mesh_only(m: &PyModel, name: &str) -> PyResult<()> {
    if m.inner.primitive().is_some() {
        Err(bad(name, "a primitive; this query needs a triangle mesh"))
    } else {
        Ok(())
    }
}

/// A `threads` argument: 0 (all cores) or a positive count.
pub fn threads_arg(threads: i64) -> PyResult<usize> {
    usize::try_from(threads).map_err(|_| bad("threads", format!("must be >= 0, got {threads}")))
}

/// Runs `f(i)` for `i` in `0..n` on up to `threads` threads (0: all cores), in order.
fn par_map<T: Send + Default + Clone>(
    n: usize,
    threads: usize,
    f: impl Fn(usize) -> Result<T, pqp::Error> + Sync,
) -> Result<Vec<T>, pqp::Error> {
    let mut out = Vec::new();
    out.try_reserve_exact(n)
        .map_err(|_| pqp::Error::OutOfMemory)?;
    out.resize(n, T::default());
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    let threads = if threads == 0 {
        cores
    } else {
        threads.min(cores)
    };
    // Small jobs stay on this thread: starting threads costs more than they save.
    let threads = threads.min(n / 256).max(1);
    let chunk = n.div_ceil(threads).max(1);
    let f = &f;
    let results: Vec<Result<(), pqp::Error>> = std::thread::scope(|s| {
        let handles: Vec<_> = out
            .chunks_mut(chunk)
            .enumerate()
            .map(|(c, part)| {
                s.spawn(move || {
                    for (k, slot) in part.iter_mut().enumerate() {
                        *slot = f(c * chunk + k)?;
                    }
                    Ok(())
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or(Err(pqp::Error::Internal)))
            .collect()
    });
    for r in results {
        r?;
    }
    Ok(out)
}

/// The overlapping face pairs of ``m1`` at ``pose1`` and ``m2`` at ``pose2``: an ``(p, 2)`` int64
/// array, column 0 a face (row of ``faces``) of ``m1``, column 1 of ``m2`` (0 for a primitive).
/// With ``first=True``, stops at the first pair found (at most one row). A pose is ``None``
/// (identity), a 4x4 matrix or an ``(R, T)`` pair.
#[pyfunction]
#[pyo3(signature = (m1, pose1, m2, pose2, first=false))]
pub fn collide<'py>(
    py: Python<'py>,
    m1: &Bound<'py, PyAny>,
    pose1: Option<&Bound<'py, PyAny>>,
    m2: &Bound<'py, PyAny>,
    pose2: Option<&Bound<'py, PyAny>>,
    first: bool,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let (a, b) = (model_arg(m1, "m1")?, model_arg(m2, "m2")?);
    let (p1, p2) = (pose(pose1, "pose1")?, pose(pose2, "pose2")?);
    let mode = if first {
        ContactMode::First
    } else {
        ContactMode::All
    };
    let (ma, mb) = (&a.inner, &b.inner);
    let pairs = py
        .detach(|| {
            pqp::collide(ma, &p1, mb, &p2, mode)
                .map(|r| r.pairs().iter().map(|c| (c.id1, c.id2)).collect::<Vec<_>>())
        })
        .map_err(|e| lib_err("collide", e))?;
    Ok(pairs_array(py, &pairs))
}

/// The separation distance of ``m1`` at ``pose1`` and ``m2`` at ``pose2`` (0 when they touch or
/// overlap), with a closest point on each, in world coordinates: ``(distance, point1, point2)``.
/// With ``rel_err`` or ``abs_err`` above 0 the distance may exceed the true one by at most
/// ``min(true * rel_err, abs_err)`` (faster).
#[pyfunction]
#[pyo3(signature = (m1, pose1, m2, pose2, rel_err=0.0, abs_err=0.0))]
#[allow(clippy::type_complexity)]
pub fn distance<'py>(
    py: Python<'py>,
    m1: &Bound<'py, PyAny>,
    pose1: Option<&Bound<'py, PyAny>>,
    m2: &Bound<'py, PyAny>,
    pose2: Option<&Bound<'py, PyAny>>,
    rel_err: f64,
    abs_err: f64,
) -> PyResult<(f64, Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>)> {
    let (a, b) = (model_arg(m1, "m1")?, model_arg(m2, "m2")?);
    let (p1, p2) = (pose(pose1, "pose1")?, pose(pose2, "pose2")?);
    check_nonneg(rel_err, "rel_err")?;
    check_nonneg(abs_err, "abs_err")?;
    let opts = DistanceOptions::approximate(rel_err, abs_err);
    let (ma, mb) = (&a.inner, &b.inner);
    let r = py
        .detach(|| pqp::distance(ma, &p1, mb, &p2, &opts))
        .map_err(|e| lib_err("distance", e))?;
    let w1 = vec3(&p1.transform_point(&r.p1));
    let w2 = vec3(&p2.transform_point(&r.p2));
    Ok((
        r.distance,
        PyArray1::from_slice(py, &w1),
        PyArray1::from_slice(py, &w2),
    ))
}

/// Whether ``m1`` at ``pose1`` and ``m2`` at ``pose2`` are within ``tolerance`` (>= 0) of each
/// other (overlap included).
#[pyfunction]
#[pyo3(signature = (m1, pose1, m2, pose2, tolerance))]
pub fn tolerance<'py>(
    py: Python<'py>,
    m1: &Bound<'py, PyAny>,
    pose1: Option<&Bound<'py, PyAny>>,
    m2: &Bound<'py, PyAny>,
    pose2: Option<&Bound<'py, PyAny>>,
    tolerance: f64,
) -> PyResult<bool> {
    let (a, b) = (model_arg(m1, "m1")?, model_arg(m2, "m2")?);
    let (p1, p2) = (pose(pose1, "pose1")?, pose(pose2, "pose2")?);
    check_nonneg(tolerance, "tolerance")?;
    let (ma, mb) = (&a.inner, &b.inner);
    py.detach(|| pqp::tolerance(ma, &p1, mb, &p2, tolerance, &Search::default()))
        .map(|r| r.closer_than_tolerance)
        .map_err(|e| lib_err("tolerance", e))
}

/// A one-triangle model of face `f` of a mesh (for distances from a primitive).
fn one_triangle(m: &PyModel, f: i32) -> Result<pqp::Model, pqp::Error> {
    let [a, b, c] = m.faces[f as usize].map(|k| m.vertices[k as usize]);
    pqp::Model::from_triangles([(a, b, c, f)])
}

/// The distance of face pair `(f1, f2)` (a primitive's "face" is 0, itself).
fn pair_distance(
    a: &PyModel,
    p1: &Pose,
    b: &PyModel,
    p2: &Pose,
    (f1, f2): (i32, i32),
) -> Result<f64, pqp::Error> {
    let posed = |m: &PyModel, p: &Pose, f: i32| {
        m.faces[f as usize].map(|k| p.transform_point(&Vec3::from(m.vertices[k as usize])))
    };
    match (a.inner.primitive(), b.inner.primitive()) {
        (None, None) => Ok(tri_distance(&posed(a, p1, f1), &posed(b, p2, f2)).distance),
        (Some(_), None) => {
            let t = one_triangle(b, f2)?;
            pqp::distance(&a.inner, p1, &t, p2, &DistanceOptions::exact()).map(|r| r.distance)
        }
        (None, Some(_)) => {
            let t = one_triangle(a, f1)?;
            pqp::distance(&t, p1, &b.inner, p2, &DistanceOptions::exact()).map(|r| r.distance)
        }
        (Some(_), Some(_)) => {
            pqp::distance(&a.inner, p1, &b.inner, p2, &DistanceOptions::exact()).map(|r| r.distance)
        }
    }
}

/// Every face pair of ``m1`` at ``pose1`` and ``m2`` at ``pose2`` at most ``d`` (>= 0) apart,
/// overlapping pairs included: ``(pairs, distances)``, an ``(p, 2)`` int64 array as
/// :func:`collide` gives and the ``(p,)`` distances of those pairs (0 where they overlap).
#[pyfunction]
#[pyo3(signature = (m1, pose1, m2, pose2, d))]
#[allow(clippy::type_complexity)]
pub fn within_distance<'py>(
    py: Python<'py>,
    m1: &Bound<'py, PyAny>,
    pose1: Option<&Bound<'py, PyAny>>,
    m2: &Bound<'py, PyAny>,
    pose2: Option<&Bound<'py, PyAny>>,
    d: f64,
) -> PyResult<(Bound<'py, PyArray2<i64>>, Bound<'py, PyArray1<f64>>)> {
    let (a, b) = (model_arg(m1, "m1")?, model_arg(m2, "m2")?);
    let (p1, p2) = (pose(pose1, "pose1")?, pose(pose2, "pose2")?);
    check_nonneg(d, "d")?;
    let (ma, mb) = (&*a, &*b);
    let (pairs, dists) = py
        .detach(|| {
            let r = pqp::within_distance(&ma.inner, &p1, &mb.inner, &p2, d)?;
            let pairs: Vec<(i32, i32)> = r.pairs().iter().map(|c| (c.id1, c.id2)).collect();
            let dists = pairs
                .iter()
                .map(|&fp| pair_distance(ma, &p1, mb, &p2, fp))
                .collect::<Result<Vec<f64>, _>>()?;
            Ok((pairs, dists))
        })
        .map_err(|e| lib_err("within_distance", e))?;
    Ok((pairs_array(py, &pairs), dists.into_pyarray(py)))
}

/// For each of the ``(q, 3)`` ``points`` (world coordinates), the closest point of the mesh
/// ``model`` at ``pose``: ``(distances (q,), closest (q, 3), faces (q,))``. Points farther than
/// ``max_distance`` get distance ``inf``, closest ``nan`` and face -1. Runs on up to ``threads``
/// threads (0: all cores) with the GIL released.
#[pyfunction]
#[pyo3(signature = (model, pose, points, max_distance=f64::INFINITY, threads=0))]
#[allow(clippy::type_complexity)]
pub fn closest_point<'py>(
    py: Python<'py>,
    model: &Bound<'py, PyAny>,
    pose: Option<&Bound<'py, PyAny>>,
    points: &Bound<'py, PyAny>,
    max_distance: f64,
    threads: i64,
) -> PyResult<(
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<i64>>,
)> {
    let m = model_arg(model, "model")?;
    mesh_only(&m, "model")?;
    let threads = threads_arg(threads)?;
    let p = crate::convert::pose(pose, "pose")?;
    let pts = crate::convert::points(points, "points")?;
    check_nonneg(max_distance, "max_distance")?;
    let inner = &m.inner;
    let res = py
        .detach(|| {
            par_map(pts.len(), threads, |i| {
                let r = pqp::closest_point(inner, &p, &Vec3::from(pts[i]), max_distance)?;
                Ok((r.distance, vec3(&r.point), r.triangle.map_or(-1, i64::from)))
            })
        })
        .map_err(|e| lib_err("closest_point", e))?;
    let d: Vec<f64> = res.iter().map(|r| r.0).collect();
    let c: Vec<[f64; 3]> = res.iter().map(|r| r.1).collect();
    let f: Vec<i64> = res.iter().map(|r| r.2).collect();
    Ok((d.into_pyarray(py), rows_array(py, c), f.into_pyarray(py)))
}

/// Signed distances ``(q,)`` from the ``(q, 3)`` ``points`` to the mesh ``model`` at ``pose``:
/// negative inside (where the mesh's winding number is at least 1/2), 0 on the surface. Runs on
/// up to ``threads`` threads (0: all cores) with the GIL released.
#[pyfunction]
#[pyo3(signature = (model, pose, points, threads=0))]
pub fn signed_distance<'py>(
    py: Python<'py>,
    model: &Bound<'py, PyAny>,
    pose: Option<&Bound<'py, PyAny>>,
    points: &Bound<'py, PyAny>,
    threads: i64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let m = model_arg(model, "model")?;
    mesh_only(&m, "model")?;
    let threads = threads_arg(threads)?;
    let p = crate::convert::pose(pose, "pose")?;
    let pts = crate::convert::points(points, "points")?;
    let inner = &m.inner;
    let d = py
        .detach(|| {
            par_map(pts.len(), threads, |i| {
                pqp::signed_distance(inner, &p, &Vec3::from(pts[i]))
            })
        })
        .map_err(|e| lib_err("signed_distance", e))?;
    Ok(d.into_pyarray(py))
}

/// The first hit of each ray ``origins[i] + t * directions[i]``, ``0 <= t <= max_t``, on the mesh
/// ``model`` at ``pose``: ``(t (q,), faces (q,))``, ``t`` in units of the direction given (not
/// necessarily unit), ``inf`` and face -1 for a miss. Directions must be finite and nonzero.
#[pyfunction]
#[pyo3(signature = (model, pose, origins, directions, max_t=f64::INFINITY, threads=0))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn ray_cast<'py>(
    py: Python<'py>,
    model: &Bound<'py, PyAny>,
    pose: Option<&Bound<'py, PyAny>>,
    origins: &Bound<'py, PyAny>,
    directions: &Bound<'py, PyAny>,
    max_t: f64,
    threads: i64,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<i64>>)> {
    let m = model_arg(model, "model")?;
    mesh_only(&m, "model")?;
    let threads = threads_arg(threads)?;
    let p = crate::convert::pose(pose, "pose")?;
    let o = crate::convert::points(origins, "origins")?;
    let d = crate::convert::float_array(directions, "directions")?;
    let d = rows3(&d.as_array(), "directions")?;
    if d.len() != o.len() {
        return Err(bad(
            "directions",
            format!("{} rows, but origins has {}", d.len(), o.len()),
        ));
    }
    if let Some(i) = d.iter().position(|v| *v == [0.0; 3]) {
        return Err(bad("directions", format!("row {i} is zero")));
    }
    check_nonneg(max_t, "max_t")?;
    let o: Vec<Vec3> = o.into_iter().map(Vec3::from).collect();
    let d: Vec<Vec3> = d.into_iter().map(Vec3::from).collect();
    let inner = &m.inner;
    let hits = py
        .detach(|| pqp::ray_cast_batch(inner, &p, &o, &d, max_t, threads))
        .map_err(|e| lib_err("ray_cast", e))?;
    let t: Vec<f64> = hits
        .iter()
        .map(|h| h.map_or(f64::INFINITY, |h| h.t))
        .collect();
    let f: Vec<i64> = hits
        .iter()
        .map(|h| h.map_or(-1, |h| h.triangle as i64))
        .collect();
    Ok((t.into_pyarray(py), f.into_pyarray(py)))
}

/// Reads a batch's models and pose pairs.
#[allow(clippy::type_complexity)]
fn batch_args<'py>(
    m1: &Bound<'py, PyAny>,
    poses1: &Bound<'py, PyAny>,
    m2: &Bound<'py, PyAny>,
    poses2: &Bound<'py, PyAny>,
) -> PyResult<(ModelArg<'py>, ModelArg<'py>, Vec<(Pose, Pose)>)> {
    let (a, b) = (model_arg(m1, "m1")?, model_arg(m2, "m2")?);
    let pairs = pose_pairs(
        batch_poses(poses1, "poses1")?,
        batch_poses(poses2, "poses2")?,
        ("poses1", "poses2"),
    )?;
    Ok((a, b, pairs))
}

/// Whether ``m1`` at ``poses1[i]`` and ``m2`` at ``poses2[i]`` collide, for each ``i``: an
/// ``(N,)`` bool array. ``poses1`` and ``poses2`` are ``(N, 4, 4)`` arrays; either may be a single
/// pose (or ``None``) used for every ``i``. Runs on up to ``threads`` threads (0: all cores) with
/// the GIL released.
#[pyfunction]
#[pyo3(signature = (m1, poses1, m2, poses2, threads=0))]
pub fn collide_batch<'py>(
    py: Python<'py>,
    m1: &Bound<'py, PyAny>,
    poses1: &Bound<'py, PyAny>,
    m2: &Bound<'py, PyAny>,
    poses2: &Bound<'py, PyAny>,
    threads: i64,
) -> PyResult<Bound<'py, PyArray1<bool>>> {
    let (a, b, pairs) = batch_args(m1, poses1, m2, poses2)?;
    let threads = threads_arg(threads)?;
    let (ma, mb) = (&a.inner, &b.inner);
    let r = py
        .detach(|| pqp::collide_batch(ma, mb, &pairs, threads))
        .map_err(|e| lib_err("collide_batch", e))?;
    Ok(r.into_pyarray(py))
}

/// The separation distance of ``m1`` at ``poses1[i]`` and ``m2`` at ``poses2[i]``, for each ``i``:
/// an ``(N,)`` float64 array (exact unless ``rel_err`` or ``abs_err`` is above 0, as in
/// :func:`distance`). Poses and threads as in :func:`collide_batch`.
#[pyfunction]
#[pyo3(signature = (m1, poses1, m2, poses2, threads=0, rel_err=0.0, abs_err=0.0))]
#[allow(clippy::too_many_arguments)]
pub fn distance_batch<'py>(
    py: Python<'py>,
    m1: &Bound<'py, PyAny>,
    poses1: &Bound<'py, PyAny>,
    m2: &Bound<'py, PyAny>,
    poses2: &Bound<'py, PyAny>,
    threads: i64,
    rel_err: f64,
    abs_err: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let (a, b, pairs) = batch_args(m1, poses1, m2, poses2)?;
    let threads = threads_arg(threads)?;
    check_nonneg(rel_err, "rel_err")?;
    check_nonneg(abs_err, "abs_err")?;
    let opts = DistanceOptions::approximate(rel_err, abs_err);
    let (ma, mb) = (&a.inner, &b.inner);
    let r = py
        .detach(|| pqp::distance_batch(ma, mb, &pairs, &opts, threads))
        .map_err(|e| lib_err("distance_batch", e))?;
    Ok(r.into_pyarray(py))
}
