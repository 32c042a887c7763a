//! Tolerance: are two posed models within distance `t` of each other?

use super::primitive::{Goal, Nearest};
use super::search::{ClosestSearch, LeafVolumes, Search, Strategy, root_pair};
use super::{Stats, TriCache, prepare};
use crate::error::Error;
use crate::math::{Pose, Vec3};
use crate::model::Model;
use std::mem::MaybeUninit;
use std::time::Instant;

/// The answer of a tolerance query.
///
/// Keep it and pass it to [`tolerance_into`] again for the next query on the same models: the
/// triangle pair that decided the last answer is tried first.
#[derive(Clone, Debug)]
pub struct ToleranceResult {
    /// Whether the models' distance is at most `tolerance`.
    pub closer_than_tolerance: bool,
    /// The tolerance asked for.
    pub tolerance: f64,
    /// When closer: the distance of a triangle pair within the tolerance (not necessarily the
    /// closest pair). Otherwise: a lower bound on the distance, greater than `tolerance`.
    pub distance: f64,
    /// When closer: the point on model 1 of that pair, in model 1's frame.
    pub p1: Vec3,
    /// When closer: the point on model 2 of that pair, in model 2's frame.
    pub p2: Vec3,
    /// When closer: the ids of that triangle pair; otherwise -1.
    pub id1: i32,
    /// See `id1`.
    pub id2: i32,
    /// When closer: model 1's triangle of that pair by its position in the order added (0 for
    /// the first triangle given to the model, as PQP 1.3's `tris` lists them); otherwise -1.
    pub tri1: i32,
    /// As `tri1`, for model 2.
    pub tri2: i32,
    /// Work done.
    pub stats: Stats,
    pub(crate) cache: Option<TriCache>,
}

impl Default for ToleranceResult {
    fn default() -> Self {
        ToleranceResult {
            closer_than_tolerance: false,
            tolerance: 0.0,
            distance: f64::INFINITY,
            p1: Vec3::zeros(),
            p2: Vec3::zeros(),
            id1: -1,
            id2: -1,
            tri1: -1,
            tri2: -1,
            stats: Stats::default(),
            cache: None,
        }
    }
}

impl ToleranceResult {
    /// An empty result.
    pub fn new() -> Self {
        Self::default()
    }
}

/// Whether `m1` at `pose1` and `m2` at `pose2` are within `tolerance` (>= 0) of each other.
///
/// It stops at the first triangle pair within the tolerance and prunes every pair of volumes farther
/// apart than it, so it is cheaper than a distance query. `search` is as for a distance query
/// (`&Search::default()` unless comparing strategies).
///
/// ```
/// use pqp::{tolerance, Model, Pose, Search};
/// let tri = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0);
/// let a = Model::from_triangles([tri]).unwrap();
/// let b = Model::from_triangles([tri]).unwrap();
/// let near = Pose::from_translation([0.0, 0.0, 0.5]);
/// let search = Search::default();
/// assert!(tolerance(&a, &Pose::identity(), &b, &near, 0.6, &search).unwrap().closer_than_tolerance);
/// assert!(!tolerance(&a, &Pose::identity(), &b, &near, 0.4, &search).unwrap().closer_than_tolerance);
/// ```
pub fn tolerance(
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    tolerance: f64,
    search: &Search,
) -> Result<ToleranceResult, Error> {
    let mut r = ToleranceResult::new();
    tolerance_into(&mut r, m1, pose1, m2, pose2, tolerance, search)?;
    Ok(r)
}

/// As [`tolerance`], trying first the pair cached in `result` by a previous query on the same two
/// models. On error `result` is left as it was.
pub fn tolerance_into(
    result: &mut ToleranceResult,
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    tolerance: f64,
    search: &Search,
) -> Result<(), Error> {
    let start = Instant::now();
    if tolerance.is_nan() || tolerance < 0.0 {
        return Err(Error::InvalidArgument);
    }
    search.validate()?;
    // A primitive: its own search, without the triangle cache.
    let goal = Goal::Tolerance(tolerance);
    if let Some(found) = super::primitive::nearest(m1, pose1, m2, pose2, goal) {
        let Nearest {
            best,
            pruned,
            stats,
        } = found?;
        let within = best.filter(|b| b.distance <= tolerance);
        result.closer_than_tolerance = within.is_some();
        result.distance = match within {
            Some(b) => b.distance,
            None => best.map_or(pruned, |b| b.distance.min(pruned)),
        };
        let zero = Vec3::zeros();
        (result.p1, result.p2) = within.map_or((zero, zero), |b| (b.p1, b.p2));
        let (ids, tris) = within.map_or(((-1, -1), (-1, -1)), |b| (b.ids, b.tris));
        ((result.id1, result.id2), (result.tri1, result.tri2)) = (ids, tris);
        (result.tolerance, result.cache, result.stats) = (tolerance, None, stats);
        return Ok(());
    }
    let (b1, b2, rel) = prepare(m1, pose1, m2, pose2)?;
    let start_pair = TriCache::start_pair(&result.cache, m1, m2, search);
    // -0 is 0 (its bits would make the cutoff below negative). An infinite tolerance takes in
    // every pair: the search still goes down to one triangle pair, whose distance it reports.
    let limit = if tolerance == 0.0 {
        0.0
    } else {
        tolerance.min(f64::MAX)
    };
    // Nothing farther than the tolerance matters, nor anything that cannot beat the best pair:
    // the cutoff is the least bound above the tolerance, or the best distance if smaller.
    let above = f64::from_bits(limit.to_bits() + 1);
    // Without a cached pair the search starts at the root pair, with the cutoff `above`: bound it
    // first, before the search is set up (its caches cost as much as this test). Beyond the
    // tolerance, it is the answer the search would give: the root pruned, nothing tested.
    let root = match start_pair {
        Some(_) => None,
        None => {
            let root = root_pair(b1, b2, &rel, above);
            if root.bound >= above {
                result.closer_than_tolerance = false;
                result.distance = root.bound;
                result.tolerance = tolerance;
                (result.p1, result.p2) = (Vec3::zeros(), Vec3::zeros());
                ((result.id1, result.id2), (result.tri1, result.tri2)) = ((-1, -1), (-1, -1));
                result.stats = Stats {
                    bv_tests: 1,
                    tri_tests: 0,
                    query_time_secs: start.elapsed().as_secs_f64(),
                };
                return Ok(());
            }
            Some(root)
        }
    };
    let options = search;
    let mut leaves = MaybeUninit::uninit();
    let leaves = LeafVolumes::init(&mut leaves);
    let mut search = ClosestSearch::new(b1, b2, rel, start_pair, leaves);
    search.run(
        options,
        Strategy::DepthFirst,
        |d| d.min(above),
        |d| d <= limit,
        // The cutoff falls only with a pair within the tolerance, which stops the search.
        true,
        None,
        root,
    );
    let best = search.best;
    result.stats = search.stats;
    result.tolerance = tolerance;
    result.closer_than_tolerance = best.d <= limit;
    if result.closer_than_tolerance {
        result.distance = best.d;
        result.p1 = best.p;
        result.p2 = rel.apply_inverse(&best.q);
        result.id1 = b1.ids[best.ta];
        result.id2 = b2.ids[best.tb];
        result.tri1 = b1.added[best.ta] as i32;
        result.tri2 = b2.added[best.tb] as i32;
        result.cache = Some(TriCache::new(m1, m2, best.ta, best.tb));
    } else {
        result.distance = best.d.min(search.pruned_min);
        result.p1 = Vec3::zeros();
        result.p2 = Vec3::zeros();
        result.id1 = -1;
        result.id2 = -1;
        result.tri1 = -1;
        result.tri2 = -1;
        // The nearest pair seen, if any was tested, is the best start for the next query.
        if best.d.is_finite() {
            result.cache = Some(TriCache::new(m1, m2, best.ta, best.tb));
        }
    }
    result.stats.query_time_secs = start.elapsed().as_secs_f64();
    Ok(())
}
