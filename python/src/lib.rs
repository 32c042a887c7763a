//! The Python module `pqp`: proximity queries between triangle meshes (pqp-rs) with NumPy arrays in
//! and out. See docs/python.md for the API and `pqp.pyi` for its types.
//!
//! Every argument is checked and converted while the GIL is held (bad input raises `ValueError`
//! naming the argument); the queries then run with the GIL released, on the crate's safe API.

mod convert;
mod model;
mod queries;

use pyo3::prelude::*;

/// Proximity queries between triangle meshes: collision, separation distance, tolerance, pairs
/// within a distance, closest points, signed distance, rays, and batches of poses.
#[pymodule(name = "pqp")]
fn pqp_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<model::PyModel>()?;
    m.add_function(wrap_pyfunction!(queries::collide, m)?)?;
    m.add_function(wrap_pyfunction!(queries::distance, m)?)?;
    m.add_function(wrap_pyfunction!(queries::tolerance, m)?)?;
    m.add_function(wrap_pyfunction!(queries::within_distance, m)?)?;
    m.add_function(wrap_pyfunction!(queries::closest_point, m)?)?;
    m.add_function(wrap_pyfunction!(queries::signed_distance, m)?)?;
    m.add_function(wrap_pyfunction!(queries::ray_cast, m)?)?;
    m.add_function(wrap_pyfunction!(queries::collide_batch, m)?)?;
    m.add_function(wrap_pyfunction!(queries::distance_batch, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
