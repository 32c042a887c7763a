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
//! The crate is published as the package `pqp-rs`; its library is named `pqp`:
//!
//! ```toml
//! [dependencies]
//! pqp-rs = { git = "https://github.com/pqp-rs/pqp-rs" }   # or { path = "../pqp-rs" }
//! ```
//!
//! ## Every query family, in a few lines
//!
//! The examples below share two unit squares (two triangles each), `b` 0.5 above `a`:
//!
//! ```
//! # use pqp::{Model, Pose};
//! let square = |z: f64| {
//!     Model::from_triangles([
//!         ([0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], 0),
//!         ([0.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z], 1),
//!     ])
//! };
//! let (a, b) = (square(0.0)?, square(0.5)?);
//! let here = Pose::identity();
//! # let _ = (a, b, here);
//! # Ok::<(), pqp::Error>(())
//! ```
//!
//! | Family | Functions |
//! |---|---|
//! | Pair queries | [`collide`], [`distance`], [`tolerance`], [`within_distance`], [`self_collide`] (and `_into` forms reusing a result) |
//! | Point queries | [`closest_point`], [`signed_distance`], [`winding_number`] |
//! | Rays | [`ray_cast`], [`ray_cast_batch`] |
//! | Primitives as models | [`Model::set_sphere`], [`Model::set_capsule`], [`Model::set_box`] |
//! | Motion | [`time_of_contact`] between two [`Motion`]s |
//! | Batches (many poses, several threads) | [`collide_batch`], [`distance_batch`], [`tolerance_batch`] |
//! | Saved models | [`Model::to_bytes`], [`Model::from_bytes`] |
//! | Convex polytopes | [`convex::ConvexModel`], [`convex::convex_distance`], [`convex::convex_penetration`] |
//!
//! **Collision, distance, tolerance**:
//!
//! ```
//! # use pqp::{Model, Pose};
//! # let square = |z: f64| Model::from_triangles([
//! #     ([0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], 0),
//! #     ([0.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z], 1)]);
//! # let (a, b) = (square(0.0)?, square(0.5)?);
//! # let here = Pose::identity();
//! use pqp::{collide, distance, tolerance, ContactMode, DistanceOptions, Search};
//! let c = collide(&a, &here, &b, &here, ContactMode::All)?;
//! assert!(!c.colliding());
//! let d = distance(&a, &here, &b, &here, &DistanceOptions::exact())?;
//! assert!((d.distance - 0.5).abs() < 1e-12);
//! let t = tolerance(&a, &here, &b, &here, 0.6, &Search::default())?;
//! assert!(t.closer_than_tolerance);
//! # Ok::<(), pqp::Error>(())
//! ```
//!
//! **Points and rays**: the closest point of a model to a point, and the first hit of a ray.
//!
//! ```
//! # use pqp::{Model, Pose};
//! # let square = |z: f64| Model::from_triangles([
//! #     ([0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], 0),
//! #     ([0.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z], 1)]);
//! # let a = square(0.0)?;
//! # let here = Pose::identity();
//! use pqp::{closest_point, ray_cast, Vec3};
//! let p = closest_point(&a, &here, &Vec3::new(0.5, 0.5, 2.0), f64::INFINITY)?;
//! assert!((p.distance - 2.0).abs() < 1e-12);
//! let down = Vec3::new(0.0, 0.0, -1.0);
//! let hit = ray_cast(&a, &here, &Vec3::new(0.25, 0.5, 3.0), &down, f64::INFINITY)?.unwrap();
//! assert!((hit.t - 3.0).abs() < 1e-12);
//! # Ok::<(), pqp::Error>(())
//! ```
//!
//! **Primitives, motion and batches**: a sphere as a model and its distances for many poses on
//! two threads, and the time a falling square first touches another.
//!
//! ```
//! # use pqp::{Model, Pose};
//! # let square = |z: f64| Model::from_triangles([
//! #     ([0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], 0),
//! #     ([0.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z], 1)]);
//! # let a = square(0.0)?;
//! # let here = Pose::identity();
//! use pqp::{distance_batch, time_of_contact, DistanceOptions, Motion};
//! let mut ball = Model::new();
//! ball.set_sphere(0.25)?;
//! let poses: Vec<(Pose, Pose)> = (1..=4)
//!     .map(|k| (Pose::from_translation([0.5, 0.5, k as f64]), here))
//!     .collect();
//! let d = distance_batch(&ball, &a, &poses, &DistanceOptions::exact(), 2)?;
//! assert!((d[3] - 3.75).abs() < 1e-12);
//! // A copy of the square falls from z = 2 to z = -2: it touches the first half way.
//! let fall = Motion::new(Pose::from_translation([0.0, 0.0, 2.0]), Pose::from_translation([0.0, 0.0, -2.0]));
//! let toc = time_of_contact(&a, &fall, &a, &Motion::new(here, here), 1e-9)?;
//! assert!(toc.contact && (toc.toc - 0.5).abs() < 1e-6);
//! # Ok::<(), pqp::Error>(())
//! ```
//!
//! **Saved models and convex polytopes**: a built model to bytes and back (no rebuild), and the
//! distance between two convex hulls.
//!
//! ```
//! # use pqp::{Model, Pose};
//! # let square = |z: f64| Model::from_triangles([
//! #     ([0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], 0),
//! #     ([0.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z], 1)]);
//! # let a = square(0.0)?;
//! use pqp::convex::{ConvexModel, convex_distance};
//! let bytes = a.to_bytes()?;
//! let again = Model::from_bytes(&bytes)?;
//! assert_eq!(again.num_triangles(), 2);
//!
//! let corners: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
//!     .collect();
//! let cube = ConvexModel::from_points(&corners)?;
//! let (p1, p2) = (Pose::identity(), Pose::from_translation([3.0, 0.0, 0.0]));
//! let d = convex_distance(&cube, &p1, &cube, &p2, None)?;
//! assert!((d.distance - 2.0).abs() < 1e-12);
//! # Ok::<(), pqp::Error>(())
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

/// The README's Rust examples, run as doc tests (tests/readme.rs runs its C and C++ ones).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
