//! Separation distance, exact or within a relative/absolute error, with closest points.

use super::front::{Front, FrontQuery};
use super::primitive::{Goal, Nearest};
use super::search::{ClosestSearch, LeafVolumes, Search, Strategy};
use super::{Stats, TriCache, prepare};
use crate::error::Error;
use crate::math::{Pose, Vec3};
use crate::model::Model;
use std::mem::MaybeUninit;
use std::time::Instant;

/// How a distance query may trade accuracy for speed, and how it searches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceOptions {
    /// Relative error allowed (>= 0).
    pub rel_err: f64,
    /// Absolute error allowed (>= 0). With 0 the query is exact whatever `rel_err` is, as in PQP;
    /// pass `f64::INFINITY` to let only the relative bound act.
    pub abs_err: f64,
    /// How the bounding volume test tree is searched (the default is the fastest measured;
    /// [`Search::pqp`] gives PQP 1.3's search for a queue size).
    pub search: Search,
}

impl Default for DistanceOptions {
    fn default() -> Self {
        DistanceOptions {
            rel_err: 0.0,
            abs_err: 0.0,
            search: Search::default(),
        }
    }
}

impl DistanceOptions {
    /// Exact distance with the default search.
    pub fn exact() -> Self {
        Self::default()
    }

    /// Within the error bounds `rel_err` and `abs_err`, with the default search.
    pub fn approximate(rel_err: f64, abs_err: f64) -> Self {
        DistanceOptions {
            rel_err,
            abs_err,
            search: Search::default(),
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Error> {
        if self.rel_err >= 0.0 && self.abs_err >= 0.0 {
            self.search.validate()
        } else {
            Err(Error::InvalidArgument)
        }
    }
}

/// The answer of a distance query.
///
/// Keep it and pass it to [`distance_into`] again for the next query on the same models: it
/// remembers the closest triangle pair (the triangle cache), which makes coherent motion cheap.
#[derive(Clone, Debug)]
pub struct DistanceResult {
    /// The separation distance (0 when the models touch or overlap). With error bounds,
    /// `true <= distance <= min(true * (1 + rel_err), true + abs_err)`.
    pub distance: f64,
    /// A closest point on model 1, in model 1's frame.
    pub p1: Vec3,
    /// A closest point on model 2, in model 2's frame.
    pub p2: Vec3,
    /// Whether the models touch or overlap. Then `distance` is 0, `id1`/`id2` name an intersecting
    /// triangle pair, and `p1`, `p2` are the same world point, common to both triangles.
    pub overlap: bool,
    /// Id of model 1's triangle of the closest pair.
    pub id1: i32,
    /// Id of model 2's triangle of the closest pair.
    pub id2: i32,
    /// Model 1's triangle of the closest pair by its position in the order added (0 for the
    /// first triangle given to the model, as PQP 1.3's `tris` lists them); -1 before any query.
    pub tri1: i32,
    /// As `tri1`, for model 2.
    pub tri2: i32,
    /// Work done.
    pub stats: Stats,
    pub(crate) cache: Option<TriCache>,
    pub(crate) front: Front,
}

impl Default for DistanceResult {
    fn default() -> Self {
        DistanceResult {
            distance: f64::INFINITY,
            p1: Vec3::zeros(),
            p2: Vec3::zeros(),
            overlap: false,
            id1: -1,
            id2: -1,
            tri1: -1,
            tri2: -1,
            stats: Stats::default(),
            cache: None,
            front: Front::default(),
        }
    }
}

impl DistanceResult {
    /// An empty result (distance infinite, no cached pair).
    pub fn new() -> Self {
        Self::default()
    }

    /// Drops the BVTT front kept for the next query (the triangle cache stays).
    #[cfg(test)]
    pub(crate) fn forget_front(&mut self) {
        self.front = Front::default();
    }
}

/// The separation distance between `m1` at `pose1` and `m2` at `pose2`.
///
/// ```
/// use pqp::{distance, DistanceOptions, Model, Pose};
/// let tri = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0);
/// let a = Model::from_triangles([tri]).unwrap();
/// let b = Model::from_triangles([tri]).unwrap();
/// let r = distance(&a, &Pose::identity(), &b, &Pose::from_translation([0.0, 0.0, 3.0]),
///                  &DistanceOptions::exact()).unwrap();
/// assert!((r.distance - 3.0).abs() < 1e-12);
/// ```
pub fn distance(
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    options: &DistanceOptions,
) -> Result<DistanceResult, Error> {
    let mut r = DistanceResult::new();
    distance_into(&mut r, m1, pose1, m2, pose2, options)?;
    Ok(r)
}

/// The largest factor the relative error bound prunes with (see `distance_into`).
const TWO_TO_50: f64 = (1u64 << 50) as f64;

/// As [`distance`], starting from the triangle pair cached in `result` by a previous query on the
/// same two models. On error `result` is left as it was.
pub fn distance_into(
    result: &mut DistanceResult,
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    options: &DistanceOptions,
) -> Result<(), Error> {
    let start = Instant::now();
    options.validate()?;
    // A primitive: its own search, without the triangle cache or the front.
    let goal = Goal::Distance {
        rel_err: options.rel_err,
        abs_err: options.abs_err,
    };
    if let Some(found) = super::primitive::nearest(m1, pose1, m2, pose2, goal) {
        let Nearest { best, stats, .. } = found?;
        let best = best.ok_or(Error::Internal)?;
        (result.distance, result.p1, result.p2) = (best.distance, best.p1, best.p2);
        result.overlap = best.distance <= 0.0;
        ((result.id1, result.id2), (result.tri1, result.tri2)) = (best.ids, best.tris);
        (result.cache, result.front, result.stats) = (None, Front::default(), stats);
        return Ok(());
    }
    let (b1, b2, rel) = prepare(m1, pose1, m2, pose2)?;
    let (rel_err, abs_err) = (options.rel_err, options.abs_err);
    let start_pair = TriCache::start_pair(&result.cache, m1, m2, &options.search);
    let mut leaves = MaybeUninit::uninit();
    let leaves = LeafVolumes::init(&mut leaves);
    let fresh = start_pair.is_none();
    let mut search = ClosestSearch::new(b1, b2, rel, start_pair, leaves);
    let asked = FrontQuery {
        m1,
        m2,
        b1,
        b2,
        rel: &rel,
        search: &options.search,
    };
    if result.front.worth_recording(&asked) {
        search.record_front(result.front.take_spare());
    }
    // An approximate query (both errors nonzero: see `cutoff` below) keeps most of the children
    // it bounds: prefetching for them before their bounds pays there, and costs an exact query,
    // which prunes many.
    search.prefetch_ahead(rel_err > 0.0 && abs_err > 0.0);
    // An approximate query without a first answer (a new result) finds one by a probe, so that
    // its error bound prunes from the start (see `ClosestSearch::probe`): it then stops as early
    // as a depth-first search would. An exact query gains little from it (its priority-directed
    // search expands nearly only what any search must), so it goes without.
    let root = if fresh && abs_err > 0.0 && rel_err > 0.0 {
        search.probe()
    } else {
        None
    };
    let front = result.front.start(&asked);
    let from_front = front.is_some();
    // A pair with lower bound b is pruned only when both error bounds allow it: b (1 + rel_err) >= d
    // and b + abs_err >= d. With abs_err = 0 that is b >= d, exactly. A pair with bound 0 must not
    // be pruned while d > 0 (touching models answer 0): the factor is kept at most 2^50 (pruning
    // less is always allowed), so that `d / scale` does not underflow to 0 for any d of at least
    // 2^-1024, and stays infinite for an infinite d (an infinite rel_err would make it NaN). With
    // an infinite abs_err, `d - abs_err` is NaN or -infinity, which `max` passes over.
    let scale = (1.0 + rel_err).min(TWO_TO_50);
    let cutoff = |d: f64| {
        if abs_err == 0.0 {
            d
        } else {
            (d / scale).max(d - abs_err)
        }
    };
    search.run(
        &options.search,
        Strategy::Priority,
        cutoff,
        |d| d <= 0.0,
        false,
        front,
        root,
    );
    let new_front = search.take_front();
    result.front.finish(m1, m2, rel, new_front, from_front);
    let best = search.best;
    result.stats = search.stats;
    result.distance = best.d;
    result.overlap = best.d <= 0.0;
    result.p1 = best.p;
    result.p2 = rel.apply_inverse(&best.q);
    result.id1 = b1.ids[best.ta];
    result.id2 = b2.ids[best.tb];
    result.tri1 = b1.added[best.ta] as i32;
    result.tri2 = b2.added[best.tb] as i32;
    result.cache = Some(TriCache::new(m1, m2, best.ta, best.tb));
    result.stats.query_time_secs = start.elapsed().as_secs_f64();
    Ok(())
}
