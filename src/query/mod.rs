//! The three proximity queries, ray casting (`ray.rs`) and time of contact (`contact_time.rs`), one
//! file each, and what they share (`traversal.rs`).
//!
//! Every query takes two built models, each with its pose, and works in model 1's frame: model 2's
//! volumes and triangles are brought there by the relative pose. Results are plain values that the
//! caller may keep and pass again: a distance or tolerance result remembers the closest triangle
//! pair it found (the *triangle cache*), and the next query on the same two models starts from it.
//! The cache lives in the result, never in the models, so models stay immutable and shareable.

mod batch;
mod bound_heap;
mod collide;
mod contact_time;
mod distance;
mod front;
#[cfg(test)]
mod layering_tests;
mod point;
mod primitive;
mod queue;
mod ray;
mod ray_triangle;
pub(crate) mod search;
mod self_collide;
mod strategy;
mod tolerance;
mod traversal;
mod winding;
mod within_distance;

#[cfg(test)]
pub(crate) use batch::answer_all;
pub(crate) use batch::{Workers, collide_batch_with, distance_batch_with, tolerance_batch_with};
pub use batch::{collide_batch, distance_batch, tolerance_batch};
pub use collide::{CollideResult, ContactMode, ContactPair, collide, collide_into};
pub use contact_time::{ContactTime, Motion, time_of_contact};
pub use distance::{DistanceOptions, DistanceResult, distance, distance_into};
pub use point::{PointResult, closest_point, signed_distance};
pub(crate) use ray::RayCaster;
pub use ray::{RayHit, ray_cast, ray_cast_batch};
pub use self_collide::{self_collide, self_collide_into, self_contact};
pub use strategy::{Search, Strategy};
pub use tolerance::{ToleranceResult, tolerance, tolerance_into};
pub use winding::winding_number;
pub use within_distance::{within_distance, within_distance_into};

use crate::bvh::Bvh;
use crate::error::{Error, MAX_COORDINATE};
use crate::math::{Pose, RelPose, Vec3};
use crate::model::Model;

/// Work counters and time of one query.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// Bounding-volume tests (overlap tests for collision, distance bounds otherwise).
    pub bv_tests: u64,
    /// Triangle-pair tests.
    pub tri_tests: u64,
    /// Wall-clock time of the query, in seconds.
    pub query_time_secs: f64,
}

/// The closest triangle pair of a previous query, by slot in each model's leaf order, tagged with the
/// models' build ids so that it is used only on the same two models.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct TriCache {
    uid1: u64,
    uid2: u64,
    tri1: u32,
    tri2: u32,
}

impl TriCache {
    fn new(m1: &Model, m2: &Model, tri1: usize, tri2: usize) -> TriCache {
        TriCache {
            uid1: m1.uid(),
            uid2: m2.uid(),
            tri1: tri1 as u32,
            tri2: tri2 as u32,
        }
    }

    /// Where a search starts: the cached pair, if the search uses triangle caching and the pair
    /// belongs to these two models.
    fn start_pair(
        cache: &Option<TriCache>,
        m1: &Model,
        m2: &Model,
        search: &Search,
    ) -> Option<(usize, usize)> {
        cache
            .filter(|c| search.triangle_cache && c.uid1 == m1.uid() && c.uid2 == m2.uid())
            .map(|c| (c.tri1 as usize, c.tri2 as usize))
    }
}

/// Checks what every query needs and returns the two hierarchies and the relative pose.
fn prepare<'a>(
    m1: &'a Model,
    pose1: &Pose,
    m2: &'a Model,
    pose2: &Pose,
) -> Result<(&'a Bvh, &'a Bvh, RelPose), Error> {
    let b1 = m1.bvh()?;
    let b2 = m2.bvh()?;
    pose1.validate()?;
    pose2.validate()?;
    Ok((b1, b2, RelPose::between(pose1, pose2)))
}

/// Checks what every point query needs: the hierarchy of a built model, and the point carried into
/// its frame.
fn prepare_point<'a>(
    model: &'a Model,
    pose: &Pose,
    point: &Vec3,
) -> Result<(&'a Bvh, Vec3), Error> {
    let bvh = model.bvh()?;
    pose.validate()?;
    if !point
        .iter()
        .all(|c| c.is_finite() && c.abs() <= MAX_COORDINATE)
    {
        return Err(Error::NonFiniteCoordinate);
    }
    let to_world = RelPose {
        rot: pose.rotation,
        trans: pose.translation,
    };
    Ok((bvh, to_world.apply_inverse(point)))
}
