//! `pqp.Model`: a built model with the vertices and faces it was built from (for refit and for the
//! distances of `within_distance`), and its pickling through the saved-model format.

use crate::convert::{bad, faces, float_array, lib_err, rows3};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pqp::Primitive;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyTuple};

/// A triangle mesh or a solid primitive (sphere, capsule, box), built and ready for queries.
///
/// ``Model(vertices, faces)`` builds the bounding-volume hierarchy of a mesh: ``vertices`` an
/// ``(n, 3)`` array, ``faces`` a ``(k, 3)`` array of vertex indices; any float or integer dtype
/// is accepted and converted (to float64, and to integers: float faces must hold whole numbers).
/// Triangle ``i`` of the model is row ``i`` of ``faces``: queries report faces by that row.
/// ``Model(mesh)`` takes any object with ``vertices`` and ``faces`` attributes, such as a
/// ``trimesh.Trimesh``. Bad input (wrong shape, NaN or infinite coordinates, an index out of
/// range, no faces) raises ``ValueError`` naming the argument. Building releases the GIL, and
/// uses up to ``threads`` threads (0: all cores).
///
/// A model is immutable except through :meth:`refit`, and may be queried from many threads at
/// once. It pickles through the library's saved-model format: unpickling (in another process,
/// say) copies and checks the hierarchy instead of rebuilding it.
#[pyclass(module = "pqp", name = "Model")]
pub struct PyModel {
    pub inner: pqp::Model,
    /// The mesh's vertices and faces (empty for a primitive).
    pub vertices: Vec<[f64; 3]>,
    pub faces: Vec<[u32; 3]>,
}

/// Triangles of `faces` over `vertices`.
fn triangles(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> Vec<[[f64; 3]; 3]> {
    faces
        .iter()
        .map(|f| f.map(|i| vertices[i as usize]))
        .collect()
}

impl PyModel {
    /// Builds a model of a mesh from checked vertices and faces (the GIL released).
    pub fn build(
        py: Python<'_>,
        vertices: Vec<[f64; 3]>,
        faces: Vec<[u32; 3]>,
        threads: usize,
    ) -> PyResult<PyModel> {
        let inner = py
            .detach(|| {
                let mut m = pqp::Model::new();
                m.begin(faces.len())?;
                for (i, f) in faces.iter().enumerate() {
                    let [a, b, c] = f.map(|k| vertices[k as usize]);
                    m.add_triangle(a, b, c, i as i32)?;
                }
                m.end_threads(threads)?;
                Ok(m)
            })
            .map_err(|e| lib_err("Model", e))?;
        Ok(PyModel {
            inner,
            vertices,
            faces,
        })
    }

    /// A model of a mesh given as Python objects: `(vertices, faces)`.
    pub fn from_arrays(
        py: Python<'_>,
        vertices: &Bound<'_, PyAny>,
        faces_obj: &Bound<'_, PyAny>,
        threads: usize,
    ) -> PyResult<PyModel> {
        let v = float_array(vertices, "vertices")?;
        let v = rows3(&v.as_array(), "vertices")?;
        let f = faces(faces_obj, "faces", v.len())?;
        PyModel::build(py, v, f, threads)
    }

    /// A model of a mesh given as an object with `vertices` and `faces` attributes (a
    /// `trimesh.Trimesh`), or `None` if it has none.
    pub fn from_mesh_like(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<Option<PyModel>> {
        if obj.hasattr("vertices")? && obj.hasattr("faces")? {
            let v = obj.getattr("vertices")?;
            let f = obj.getattr("faces")?;
            return PyModel::from_arrays(py, &v, &f, 0).map(Some);
        }
        Ok(None)
    }

    fn primitive(p: Primitive) -> PyResult<PyModel> {
        let mut inner = pqp::Model::new();
        inner.set_primitive(p).map_err(|e| lib_err("Model", e))?;
        Ok(PyModel {
            inner,
            vertices: Vec::new(),
            faces: Vec::new(),
        })
    }
}

#[pymethods]
impl PyModel {
    #[new]
    #[pyo3(signature = (vertices, faces=None, *, threads=0))]
    fn new(
        py: Python<'_>,
        vertices: &Bound<'_, PyAny>,
        faces: Option<&Bound<'_, PyAny>>,
        threads: i64,
    ) -> PyResult<PyModel> {
        let threads = crate::queries::threads_arg(threads)?;
        match faces {
            Some(f) => PyModel::from_arrays(py, vertices, f, threads),
            None => match PyModel::from_mesh_like(py, vertices)? {
                Some(m) => Ok(m),
                None => Err(PyTypeError::new_err(
                    "Model(vertices, faces) or Model(mesh) with a mesh having vertices and faces",
                )),
            },
        }
    }

    /// A solid sphere of ``radius`` centred on the model's origin.
    #[staticmethod]
    fn sphere(radius: f64) -> PyResult<PyModel> {
        check_size(radius, "radius")?;
        PyModel::primitive(Primitive::Sphere { radius })
    }

    /// A solid capsule: the points within ``radius`` of the segment of ``length`` on the model's
    /// z axis, centred on the origin (trimesh's ``capsule(height=length, radius=radius)``, whose
    /// height is the segment's too).
    #[staticmethod]
    fn capsule(radius: f64, length: f64) -> PyResult<PyModel> {
        check_size(radius, "radius")?;
        check_size(length, "length")?;
        PyModel::primitive(Primitive::Capsule { radius, length })
    }

    /// A solid box with side lengths ``x``, ``y``, ``z`` along the model's axes, centred on the
    /// origin.
    #[staticmethod]
    #[pyo3(name = "box")]
    fn box_(x: f64, y: f64, z: f64) -> PyResult<PyModel> {
        check_size(x, "x")?;
        check_size(y, "y")?;
        check_size(z, "z")?;
        PyModel::primitive(Primitive::Box { size: [x, y, z] })
    }

    /// Moves the mesh's vertices to ``vertices`` (same shape as the model's), keeping its faces
    /// and hierarchy and refitting every bounding volume (no rebuild). Queries stay exact; they
    /// slow as the shape drifts far from the one built. ``ValueError`` for a primitive or bad
    /// vertices; the GIL is released while refitting.
    fn refit(&mut self, py: Python<'_>, vertices: &Bound<'_, PyAny>) -> PyResult<()> {
        if self.inner.primitive().is_some() {
            return Err(bad(
                "refit",
                "the model is a primitive, not a triangle mesh",
            ));
        }
        let v = float_array(vertices, "vertices")?;
        let v = rows3(&v.as_array(), "vertices")?;
        if v.len() != self.vertices.len() {
            return Err(bad(
                "vertices",
                format!(
                    "{} rows, but the model has {} vertices",
                    v.len(),
                    self.vertices.len()
                ),
            ));
        }
        let faces = &self.faces;
        let inner = &mut self.inner;
        py.detach(|| inner.refit(&triangles(&v, faces)))
            .map_err(|e| lib_err("refit", e))?;
        self.vertices = v;
        Ok(())
    }

    /// The mesh's vertices, an ``(n, 3)`` float64 array (a copy; empty for a primitive).
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let flat: Vec<f64> = self.vertices.as_flattened().to_vec();
        Array2::from_shape_vec((self.vertices.len(), 3), flat)
            .expect("n x 3")
            .into_pyarray(py)
    }

    /// The mesh's faces, a ``(k, 3)`` int64 array (a copy; empty for a primitive).
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        let flat: Vec<i64> = self
            .faces
            .as_flattened()
            .iter()
            .map(|&i| i as i64)
            .collect();
        Array2::from_shape_vec((self.faces.len(), 3), flat)
            .expect("k x 3")
            .into_pyarray(py)
    }

    /// Number of triangles (0 for a primitive).
    #[getter]
    fn num_triangles(&self) -> usize {
        self.inner.num_triangles()
    }

    /// ``"mesh"``, or the primitive's kind: ``"sphere"``, ``"capsule"`` or ``"box"``.
    #[getter]
    fn kind(&self) -> &'static str {
        match self.inner.primitive() {
            None => "mesh",
            Some(Primitive::Sphere { .. }) => "sphere",
            Some(Primitive::Capsule { .. }) => "capsule",
            Some(Primitive::Box { .. }) => "box",
        }
    }

    fn __repr__(&self) -> String {
        match self.inner.primitive() {
            None => format!(
                "pqp.Model({} vertices, {} triangles)",
                self.vertices.len(),
                self.faces.len()
            ),
            Some(Primitive::Sphere { radius }) => format!("pqp.Model.sphere({radius:?})"),
            Some(Primitive::Capsule { radius, length }) => {
                format!("pqp.Model.capsule({radius:?}, {length:?})")
            }
            Some(Primitive::Box { size: [x, y, z] }) => {
                format!("pqp.Model.box({x:?}, {y:?}, {z:?})")
            }
        }
    }

    /// Pickling: a mesh as its saved-model bytes (with its vertices and faces), a primitive as
    /// its sizes.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let this = slf.borrow();
        match this.inner.primitive() {
            Some(p) => {
                let (kind, a) = match p {
                    Primitive::Sphere { radius } => ("sphere", [radius, 0.0, 0.0]),
                    Primitive::Capsule { radius, length } => ("capsule", [radius, length, 0.0]),
                    Primitive::Box { size } => ("box", size),
                };
                let f = slf.getattr("_from_primitive")?;
                PyTuple::new(
                    py,
                    [
                        f.into_any(),
                        (kind, a[0], a[1], a[2]).into_pyobject(py)?.into_any(),
                    ],
                )
            }
            None => {
                let saved = this.inner.to_bytes().map_err(|e| lib_err("pickle", e))?;
                let f = slf.getattr("_from_saved")?;
                let args = (PyBytes::new(py, &saved), this.vertices(py), this.faces(py));
                PyTuple::new(py, [f.into_any(), args.into_pyobject(py)?.into_any()])
            }
        }
    }

    /// Unpickles a mesh model: its saved bytes (checked, not rebuilt) and its vertices and faces.
    #[staticmethod]
    fn _from_saved(
        py: Python<'_>,
        saved: &[u8],
        vertices: &Bound<'_, PyAny>,
        faces_obj: &Bound<'_, PyAny>,
    ) -> PyResult<PyModel> {
        let inner = py
            .detach(|| pqp::Model::from_bytes(saved))
            .map_err(|e| lib_err("saved model", e))?;
        let v = float_array(vertices, "vertices")?;
        let v = rows3(&v.as_array(), "vertices")?;
        let f = faces(faces_obj, "faces", v.len())?;
        if f.len() != inner.num_triangles() {
            return Err(bad(
                "faces",
                "count differs from the saved model's triangles",
            ));
        }
        Ok(PyModel {
            inner,
            vertices: v,
            faces: f,
        })
    }

    /// Unpickles a primitive model.
    #[staticmethod]
    fn _from_primitive(kind: &str, a: f64, b: f64, c: f64) -> PyResult<PyModel> {
        match kind {
            "sphere" => PyModel::sphere(a),
            "capsule" => PyModel::capsule(a, b),
            "box" => PyModel::box_(a, b, c),
            _ => Err(bad("kind", format!("unknown primitive {kind:?}"))),
        }
    }
}

fn check_size(v: f64, name: &str) -> PyResult<()> {
    if (0.0..=pqp::error::MAX_COORDINATE).contains(&v) {
        Ok(())
    } else {
        Err(bad(name, format!("must be finite and >= 0, got {v}")))
    }
}
