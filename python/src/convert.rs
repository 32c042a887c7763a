//! Python values in: arrays of any numeric dtype (converted to float64), poses, and the library's
//! errors out as Python exceptions naming the argument at fault.

use numpy::ndarray::ArrayViewD;
use numpy::{AllowTypeChange, PyArrayLikeDyn};
use pqp::Pose;
use pqp::error::MAX_COORDINATE;
use pyo3::exceptions::{PyMemoryError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// Largest deviation of `R^T R` from the identity (per entry) accepted for a rotation.
const ROTATION_TOL: f64 = 1e-6;

/// `ValueError("{name}: {msg}")`.
pub fn bad(name: &str, msg: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{name}: {msg}"))
}

/// The library's error as a Python exception: out of memory as `MemoryError`, an internal fault
/// as `RuntimeError`, every other (bad input) as `ValueError`, prefixed with `what`.
pub fn lib_err(what: &str, e: pqp::Error) -> PyErr {
    match e {
        pqp::Error::OutOfMemory | pqp::Error::ModelOutOfMemory => {
            PyMemoryError::new_err(format!("{what}: {e}"))
        }
        pqp::Error::Internal => PyRuntimeError::new_err(format!("{what}: {e}")),
        _ => PyValueError::new_err(format!("{what}: {e}")),
    }
}

/// `obj` as a float64 array (any numeric dtype, nested sequences too), or `ValueError` naming it.
pub fn float_array<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
) -> PyResult<PyArrayLikeDyn<'py, f64, AllowTypeChange>> {
    obj.extract::<PyArrayLikeDyn<'py, f64, AllowTypeChange>>()
        .map_err(|e| bad(name, format!("not convertible to a float64 array ({e})")))
}

/// Shape check: `shape` must match `want`, where `None` is any length.
fn check_shape(name: &str, shape: &[usize], want: &[Option<usize>]) -> PyResult<()> {
    let ok = shape.len() == want.len()
        && shape
            .iter()
            .zip(want)
            .all(|(s, w)| w.is_none_or(|w| *s == w));
    if ok {
        return Ok(());
    }
    let want: Vec<String> = want
        .iter()
        .zip(["n", "m", "k"])
        .map(|(w, n)| w.map_or(n.to_string(), |w| w.to_string()))
        .collect();
    Err(bad(
        name,
        format!(
            "expected an array of shape ({}), got shape {:?}",
            want.join(", "),
            shape
        ),
    ))
}

/// Rows of an `(n, 3)` array of finite coordinates within the library's range (|x| <= 1e150).
pub fn points(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<[f64; 3]>> {
    let arr = float_array(obj, name)?;
    let view = arr.as_array();
    rows3(&view, name)
}

/// Rows of an `(n, 3)` float view, each coordinate finite and within range.
pub fn rows3(view: &ArrayViewD<'_, f64>, name: &str) -> PyResult<Vec<[f64; 3]>> {
    check_shape(name, view.shape(), &[None, Some(3)])?;
    let mut out = Vec::new();
    out.try_reserve_exact(view.shape()[0])
        .map_err(|_| PyMemoryError::new_err(format!("{name}: too large")))?;
    for (i, row) in view.outer_iter().enumerate() {
        let r = [row[0], row[1], row[2]];
        if !r.iter().all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE) {
            return Err(bad(
                name,
                format!("row {i} has a coordinate that is NaN, infinite or beyond 1e150"),
            ));
        }
        out.push(r);
    }
    Ok(out)
}

/// Rows of a `(k, 3)` array of vertex indices in `0..n_vertices` (any integer dtype, or floats
/// holding whole numbers).
pub fn faces(obj: &Bound<'_, PyAny>, name: &str, n_vertices: usize) -> PyResult<Vec<[u32; 3]>> {
    let arr = float_array(obj, name)?;
    let view = arr.as_array();
    check_shape(name, view.shape(), &[None, Some(3)])?;
    if view.shape()[0] == 0 {
        return Err(bad(name, "no faces (a model needs at least one triangle)"));
    }
    if view.shape()[0] > i32::MAX as usize {
        return Err(bad(name, "more than 2^31 - 1 faces"));
    }
    let mut out = Vec::new();
    out.try_reserve_exact(view.shape()[0])
        .map_err(|_| PyMemoryError::new_err(format!("{name}: too large")))?;
    for (i, row) in view.outer_iter().enumerate() {
        let mut f = [0u32; 3];
        for (k, &v) in row.iter().enumerate() {
            if v.fract() != 0.0 || !(v >= 0.0 && v < n_vertices as f64) {
                return Err(bad(
                    name,
                    format!(
                        "face {i} has vertex index {v}, not an integer in 0..{n_vertices} (the vertex count)"
                    ),
                ));
            }
            f[k] = v as u32;
        }
        out.push(f);
    }
    Ok(out)
}

/// Whether `obj` is an `(R, T)` pair: a tuple or list of two whose first is 3x3 (a list of two
/// 4x4 matrices is a batch of poses, not a pair).
fn is_pair(obj: &Bound<'_, PyAny>) -> PyResult<bool> {
    if !(obj.is_instance_of::<PyTuple>() || obj.is_instance_of::<PyList>()) || obj.len()? != 2 {
        return Ok(false);
    }
    let first = obj.get_item(0)?;
    Ok(
        match first.extract::<PyArrayLikeDyn<'_, f64, AllowTypeChange>>() {
            Ok(r) => r.as_array().shape() == [3, 3],
            Err(_) => false,
        },
    )
}

/// A pose from Python: `None` (identity), a 4x4 homogeneous matrix, or a pair `(R, T)` of a 3x3
/// rotation and a 3-vector. The rotation must be one (orthonormal, determinant +1, to 1e-6), every
/// entry finite and within 1e150, and a 4x4 matrix's last row `[0, 0, 0, 1]`.
pub fn pose(obj: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Pose> {
    let obj = match obj {
        None => return Ok(Pose::identity()),
        Some(o) if o.is_none() => return Ok(Pose::identity()),
        Some(o) => o,
    };
    if is_pair(obj)? {
        let r = float_array(&obj.get_item(0)?, name)?;
        let t = float_array(&obj.get_item(1)?, name)?;
        let (r, t) = (r.as_array(), t.as_array());
        if r.shape() != [3, 3] {
            return Err(bad(
                name,
                format!(
                    "rotation of an (R, T) pair must be 3x3, got shape {:?}",
                    r.shape()
                ),
            ));
        }
        if t.len() != 3 || t.ndim() > 2 {
            return Err(bad(
                name,
                format!(
                    "translation of an (R, T) pair must have 3 entries, got shape {:?}",
                    t.shape()
                ),
            ));
        }
        let rv: Vec<f64> = r.iter().copied().collect();
        let tv: Vec<f64> = t.iter().copied().collect();
        return make_pose(&rv, &tv, name);
    }
    let m = float_array(obj, name)?;
    let m = m.as_array();
    if m.shape() != [4, 4] {
        return Err(bad(
            name,
            format!(
                "expected a 4x4 matrix or an (R, T) pair, got shape {:?}",
                m.shape()
            ),
        ));
    }
    let v: Vec<f64> = m.iter().copied().collect();
    pose_from_matrix(&v, name)
}

/// A pose from a row-major 4x4 homogeneous matrix (16 entries).
pub fn pose_from_matrix(m: &[f64], name: &str) -> PyResult<Pose> {
    if m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0 {
        return Err(bad(name, "last row of a 4x4 pose must be [0, 0, 0, 1]"));
    }
    let r = [m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]];
    let t = [m[3], m[7], m[11]];
    make_pose(&r, &t, name)
}

/// A checked pose from a row-major rotation (9 entries) and a translation (3).
fn make_pose(r: &[f64], t: &[f64], name: &str) -> PyResult<Pose> {
    if !r
        .iter()
        .chain(t)
        .all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE)
    {
        return Err(bad(name, "an entry is NaN, infinite or beyond 1e150"));
    }
    // R^T R = I: columns orthonormal.
    let mut worst: f64 = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..3).map(|k| r[3 * k + i] * r[3 * k + j]).sum();
            let want = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((dot - want).abs());
        }
    }
    let det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6])
        + r[2] * (r[3] * r[7] - r[4] * r[6]);
    if worst > ROTATION_TOL || det <= 0.0 {
        return Err(bad(
            name,
            format!("not a rotation (R^T R differs from I by {worst:.3e}, det(R) = {det:.6})"),
        ));
    }
    Ok(Pose::new(
        [[r[0], r[1], r[2]], [r[3], r[4], r[5]], [r[6], r[7], r[8]]],
        [t[0], t[1], t[2]],
    ))
}

/// Poses of a batch: an `(N, 4, 4)` array (or a single pose, or `None`, repeated `n` times when the
/// other side gives the count). Returns the poses, or one pose to repeat.
pub enum BatchPoses {
    /// One pose per query.
    Many(Vec<Pose>),
    /// The same pose for every query.
    One(Pose),
}

/// Reads a batch's poses (see [`BatchPoses`]).
pub fn batch_poses(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<BatchPoses> {
    if obj.is_none() {
        return Ok(BatchPoses::One(Pose::identity()));
    }
    if is_pair(obj)? {
        return Ok(BatchPoses::One(pose(Some(obj), name)?));
    }
    let arr = float_array(obj, name)?;
    let view = arr.as_array();
    match view.shape() {
        [4, 4] => {
            let v: Vec<f64> = view.iter().copied().collect();
            Ok(BatchPoses::One(pose_from_matrix(&v, name)?))
        }
        [n, 4, 4] => {
            let mut out = Vec::new();
            out.try_reserve_exact(*n)
                .map_err(|_| PyMemoryError::new_err(format!("{name}: too large")))?;
            let mut buf = [0.0; 16];
            for (i, m) in view.outer_iter().enumerate() {
                for (b, v) in buf.iter_mut().zip(m.iter()) {
                    *b = *v;
                }
                out.push(pose_from_matrix(&buf, &format!("{name}[{i}]"))?);
            }
            Ok(BatchPoses::Many(out))
        }
        s => Err(bad(
            name,
            format!("expected an (N, 4, 4) array of poses, got shape {s:?}"),
        )),
    }
}

/// The pose pairs of a batch from its two sides.
pub fn pose_pairs(
    a: BatchPoses,
    b: BatchPoses,
    names: (&str, &str),
) -> PyResult<Vec<(Pose, Pose)>> {
    Ok(match (a, b) {
        (BatchPoses::Many(a), BatchPoses::Many(b)) => {
            if a.len() != b.len() {
                return Err(bad(
                    names.1,
                    format!("{} poses, but {} has {}", b.len(), names.0, a.len()),
                ));
            }
            a.into_iter().zip(b).collect()
        }
        (BatchPoses::Many(a), BatchPoses::One(b)) => a.into_iter().map(|p| (p, b)).collect(),
        (BatchPoses::One(a), BatchPoses::Many(b)) => b.into_iter().map(|p| (a, p)).collect(),
        (BatchPoses::One(a), BatchPoses::One(b)) => vec![(a, b)],
    })
}
