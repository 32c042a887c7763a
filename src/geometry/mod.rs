//! Exact geometric kernels on points, segments and triangles.
//!
//! Every routine here accepts degenerate input: a zero-length segment is a point, a triangle with
//! collinear vertices is a segment, one with three equal vertices is a point. Users build
//! point-to-mesh and segment-to-mesh queries that way.

pub(crate) mod big_int;
mod point_triangle;
pub(crate) mod predicates;
mod segment_segment;
mod solid_angle;
mod tri_distance;
mod tri_overlap;

pub use point_triangle::point_triangle;
pub(crate) use predicates::{RESCALE_HI, RESCALE_LO};
pub use segment_segment::{segment_segment, segment_segment_dir};
pub(crate) use solid_angle::{SolidAngleSum, solid_angle};
pub use tri_distance::tri_distance;
pub(crate) use tri_distance::{Near, Plane, PlanedTri, tri_distance_below};
pub use tri_overlap::tri_overlap;

use crate::math::Vec3;

/// A triangle as three vertices.
pub type Tri = [Vec3; 3];

/// The closest points of two primitives and the distance between them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPoints {
    /// Euclidean distance between `p` and `q` (0 when the primitives intersect).
    pub distance: f64,
    /// Closest point on the first primitive.
    pub p: Vec3,
    /// Closest point on the second primitive (equal to `p` when they intersect).
    pub q: Vec3,
}
