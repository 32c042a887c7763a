//! Convex polyhedra: model handles (built from a point set or from a closed convex mesh), the
//! per-pair warm-start cache, the result handle and its getters, and the three queries
//! (pqp_convex_distance, pqp_convex_intersect, pqp_convex_penetration) over [`crate::convex`].
//!
//! Getters never fail: given NULL (or an index out of range) they return a fallback value (stated
//! on each).

use crate::convex::{ConvexModel, ConvexPairCache, ConvexStats, Feature};
use crate::math::Vec3;
use std::ffi::c_int;

/// Feature kind: a vertex (see pqp_convex_result_feature1_kind).
pub const PQP_CONVEX_VERTEX: c_int = 0;
/// Feature kind: an edge.
pub const PQP_CONVEX_EDGE: c_int = 1;
/// Feature kind: a face.
pub const PQP_CONVEX_FACE: c_int = 2;

/// A convex polyhedron (opaque), immutable once created. Create with pqp_convex_model_from_points,
/// pqp_convex_model_from_triangles or pqp_convex_model_from_polygons; free with
/// pqp_convex_model_destroy.
#[allow(non_camel_case_types)]
pub struct pqp_convex_model {
    pub(crate) model: ConvexModel,
}

/// The warm-start state of one ordered pair of convex models (opaque): the feature pair the last
/// query on them ended on. Owned by the caller, one per pair; used only with the two models (in
/// the same order) that filled it, and ignored with any others.
#[allow(non_camel_case_types)]
#[derive(Default)]
pub struct pqp_convex_cache {
    pub(crate) cache: ConvexPairCache,
}

/// The answer of pqp_convex_distance or pqp_convex_penetration (opaque).
#[allow(non_camel_case_types)]
pub struct pqp_convex_result {
    distance: f64,
    p1: [f64; 3],
    p2: [f64; 3],
    intersecting: bool,
    features: Option<(Feature, Feature)>,
    stats: ConvexStats,
    depth: f64,
    normal: [f64; 3],
    deepest: [[f64; 3]; 2],
}

impl Default for pqp_convex_result {
    fn default() -> Self {
        pqp_convex_result {
            distance: f64::INFINITY,
            p1: [0.0; 3],
            p2: [0.0; 3],
            intersecting: false,
            features: None,
            stats: ConvexStats::default(),
            depth: f64::NAN,
            normal: [0.0; 3],
            deepest: [[0.0; 3]; 2],
        }
    }
}

// Queries take `const pqp_convex_model *` from any number of threads at once.
const _: () = {
    const fn shareable<T: Send + Sync>() {}
    shareable::<pqp_convex_model>();
};

/// A vector as C's 3 doubles.
fn arr(v: &Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

// In the order the header lists them (cbindgen follows the module order).
// Building models and freeing them.
mod build;
// A model's features.
mod features;
// The per-pair cache.
mod cache;
// The result handle and the queries.
mod query;
// The result's getters.
mod result;

pub use build::*;
pub use cache::*;
pub use features::*;
pub use query::*;
pub use result::*;
