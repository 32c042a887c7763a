//! # pqp-rs
//!
//! Proximity queries between triangle meshes: **collision** (which triangle pairs overlap),
//! **separation distance** (exact or within an error bound, with closest points) and **tolerance**
//! (are two models within a distance `t`?). A replacement for UNC's PQP 1.3, with the same queries and
//! semantics, exact triangle routines, shareable immutable models, and a C ABI (`pqp_*`, see
//! `include/pqp/pqp.h`) under a drop-in C++ `PQP.h`.
//!
//! Models carry a bounding-volume hierarchy of rectangle swept spheres (RSS, for distance and
//! tolerance) and oriented bounding boxes (OBB, for collision), built top-down from the principal
//! axes of each node's vertices, as in Larsen, Gottschalk, Lin and Manocha, *Fast Proximity Queries
//! with Swept Sphere Volumes* (1999). Before building, a model may choose other members of the swept
//! sphere family ([`VolumeKind`]: point or line swept spheres, or a hybrid taking per node the
//! smallest of the three) and collision on its swept spheres ([`CollisionVolume`]); answers are the
//! same whatever the choice, only the work differs.
//!
//! ```
//! use pqp::{collide, distance, ContactMode, DistanceOptions, Model, Pose};
//!
//! // Two unit squares (two triangles each), one 0.5 above the other.
//! let square = |z: f64| {
//!     Model::from_triangles([
//!         ([0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], 0),
//!         ([0.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z], 1),
//!     ])
//!     .unwrap()
//! };
//! let (a, b) = (square(0.0), square(0.5));
//! let here = Pose::identity();
//! let d = distance(&a, &here, &b, &here, &DistanceOptions::exact()).unwrap();
//! assert!((d.distance - 0.5).abs() < 1e-12);
//! let c = collide(&a, &here, &b, &here, ContactMode::All).unwrap();
//! assert!(!c.colliding());
//! ```
//!
//! Threads: a built [`Model`] is immutable and `Sync`; any number of threads may query the same
//! models at once. Results belong to their caller.

#![deny(missing_docs)]
#![deny(unsafe_op_in_unsafe_fn)]
#![deny(clippy::undocumented_unsafe_blocks)]

pub mod bounding_volume;
pub(crate) mod bvh;
pub mod capi;
pub mod convex;
#[doc(hidden)]
pub mod diagnostics;
pub mod error;
pub mod geometry;
pub mod math;
pub mod model;
pub mod query;
#[cfg(test)]
mod test_rng;

pub use error::Error;
pub use math::{Pose, RelPose, Vec3};
pub use model::{BuildState, CollisionVolume, Model, Primitive, VolumeKind};
pub use query::{
    CollideResult, ContactMode, ContactPair, DistanceOptions, DistanceResult, PointResult, Search,
    Stats, Strategy, ToleranceResult, closest_point, collide, collide_batch, collide_into,
    distance, distance_batch, distance_into, self_collide, self_collide_into, signed_distance,
    tolerance, tolerance_batch, tolerance_into, winding_number, within_distance,
    within_distance_into,
};
pub use query::{ContactTime, Motion, time_of_contact};
pub use query::{RayHit, ray_cast, ray_cast_batch};
