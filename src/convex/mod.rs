//! Convex polyhedra: hull construction, closest features by V-Clip, and penetration depth.
//!
//! A [`ConvexModel`] is built once, from a point set (our own exact convex hull) or from a closed
//! convex mesh, and is immutable afterwards (`Send + Sync`). Queries take two models, each with its
//! [`Pose`], and answer with plain values:
//!
//! * [`convex_distance`]: separation distance, closest points (each in its model's frame, like the
//!   mesh queries), the closest feature pair, and whether the models intersect. It runs V-Clip
//!   (Mirtich 1998), warm-started from a [`ConvexPairCache`] that the caller owns (one per model
//!   pair, so models stay shareable), or from a cold start when none is given.
//! * [`convex_intersect`]: just the verdict.
//! * [`convex_penetration`]: when the models overlap, the penetration depth and direction (the
//!   smallest translation that separates them), computed exactly over the candidate directions of
//!   the Minkowski difference (face normals and Gauss-map edge pairs, see `penetration.rs`).
//!
//! ```
//! use pqp::convex::{convex_distance, ConvexModel, ConvexPairCache};
//! use pqp::Pose;
//!
//! let mut cube = vec![];
//! for &x in &[0.0, 1.0] { for &y in &[0.0, 1.0] { for &z in &[0.0, 1.0] { cube.push([x, y, z]); } } }
//! let a = ConvexModel::from_points(&cube).unwrap();
//! let mut cache = ConvexPairCache::new();
//! let here = Pose::identity();
//! let there = Pose::from_translation([3.0, 0.0, 0.0]);
//! let d = convex_distance(&a, &here, &a, &there, Some(&mut cache)).unwrap();
//! assert!((d.distance - 2.0).abs() < 1e-12);
//! assert!(!d.intersecting);
//! ```
//!
//! Errors are [`Error`] codes: `NonFinitePose` for a bad pose, `Internal` if a search ever
//! exceeded its proven iteration bound (it cannot on valid input; see `vclip.rs`).

mod closest;
mod hull;
mod model;
mod penetration;
mod predicates;
mod vclip;

pub use model::ConvexModel;
pub(crate) use model::MAX_POINTS;

use crate::error::Error;
use crate::math::{Pose, RelPose, Vec3};

/// The kind of a feature of a convex polyhedron.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(i32)]
pub enum FeatureKind {
    /// A vertex (dimension 0).
    Vertex = 0,
    /// An edge (dimension 1).
    Edge = 1,
    /// A face (dimension 2).
    Face = 2,
}

/// A feature of a [`ConvexModel`]: its kind and its index among the features of that kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(C)]
pub struct Feature {
    /// Vertex, edge or face.
    pub kind: FeatureKind,
    /// Index in [`ConvexModel::vertex`], [`ConvexModel::edge`] or [`ConvexModel::face`].
    pub index: u32,
}

impl Feature {
    /// Vertex `i`.
    pub fn vertex(i: u32) -> Feature {
        Feature {
            kind: FeatureKind::Vertex,
            index: i,
        }
    }
    /// Edge `i`.
    pub fn edge(i: u32) -> Feature {
        Feature {
            kind: FeatureKind::Edge,
            index: i,
        }
    }
    /// Face `i`.
    pub fn face(i: u32) -> Feature {
        Feature {
            kind: FeatureKind::Face,
            index: i,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct CacheEntry {
    uid1: u64,
    uid2: u64,
    f1: Feature,
    f2: Feature,
}

/// The feature pair a query ended on, kept by the caller for the next query on the same two models
/// (V-Clip's warm start: under coherent motion the next answer is a few steps away).
///
/// One cache per ordered model pair; it is used only with the two models (in the same order) that
/// filled it, and ignored otherwise. Plain data: copy it, reset it, keep it anywhere.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ConvexPairCache {
    entry: Option<CacheEntry>,
}

impl ConvexPairCache {
    /// An empty cache (the next query starts cold).
    pub fn new() -> ConvexPairCache {
        ConvexPairCache::default()
    }

    /// Forgets the cached pair.
    pub fn clear(&mut self) {
        self.entry = None;
    }

    /// The cached feature pair (model 1's, model 2's), if any.
    pub fn features(&self) -> Option<(Feature, Feature)> {
        self.entry.map(|e| (e.f1, e.f2))
    }

    fn start_for(&self, m1: &ConvexModel, m2: &ConvexModel) -> Option<[Feature; 2]> {
        self.entry
            .filter(|e| {
                e.uid1 == m1.uid()
                    && e.uid2 == m2.uid()
                    && m1.has_feature(e.f1)
                    && m2.has_feature(e.f2)
            })
            .map(|e| [e.f1, e.f2])
    }
}

/// Work done by one query.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ConvexStats {
    /// V-Clip iterations (feature-pair examinations).
    pub iterations: u32,
    /// Local-minimum escapes (a vertex under a face's plane, resolved by a scan of the polyhedron).
    pub local_minima: u32,
    /// Rounding cycles broken (see `vclip.rs`); 0 in every test we run.
    pub cycles_broken: u32,
}

/// The answer of [`convex_distance`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConvexDistance {
    /// Separation distance; 0 when the models touch or overlap.
    pub distance: f64,
    /// Closest point on model 1, in model 1's frame. When the models intersect, a point common to
    /// both (`p1` and `p2` are then the same world point, not necessarily on the features).
    pub p1: Vec3,
    /// Closest point on model 2, in model 2's frame.
    pub p2: Vec3,
    /// Model 1's feature of the final pair (the closest feature when the models are apart).
    pub feature1: Feature,
    /// Model 2's feature of the final pair.
    pub feature2: Feature,
    /// Whether the models touch or overlap. Models closer than the rounding of posing them (64
    /// ulps of the scene's size: the models' radii about their origins plus the distance between
    /// the origins) count as touching.
    pub intersecting: bool,
    /// Work done.
    pub stats: ConvexStats,
}

/// The answer of [`convex_penetration`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConvexPenetration {
    /// Whether the models touch or overlap.
    pub intersecting: bool,
    /// Penetration depth: the length of the smallest translation separating the models (0 when
    /// they are apart or only touch).
    pub depth: f64,
    /// Unit direction, in world coordinates, in which to translate model 2 (by `depth`) to separate
    /// it from model 1. When the models are apart: the direction from model 1's closest point to
    /// model 2's (zero if that distance is 0).
    pub normal: Vec3,
    /// Deepest point of model 1 (model 1's frame): where model 2, moved out by `depth` along
    /// `normal`, touches it (found by V-Clip on that pose); when apart, its closest point.
    pub p1: Vec3,
    /// Deepest point of model 2 (model 2's frame), with `world(p1) = world(p2) + depth * normal`;
    /// when apart, its closest point.
    pub p2: Vec3,
    /// The V-Clip answer at the given poses, as [`convex_distance`] returns it (distance, closest
    /// points, final feature pair, work done).
    pub closest: ConvexDistance,
}

/// A start pair from the cache, or a cold start: on each model the vertex furthest towards the
/// other model's centroid.
fn start_pair(
    m1: &ConvexModel,
    m2: &ConvexModel,
    rel: &RelPose,
    cache: Option<&ConvexPairCache>,
) -> [Feature; 2] {
    if let Some(s) = cache.and_then(|c| c.start_for(m1, m2)) {
        return s;
    }
    let toward = |m: &ConvexModel, dir: Vec3| {
        let best = (0..m.num_vertices())
            .max_by(|&i, &j| dir.dot(&m.vertex(i)).total_cmp(&dir.dot(&m.vertex(j))));
        Feature::vertex(best.unwrap_or(0) as u32)
    };
    let c2_in_1 = rel.apply(&m2.centroid());
    let c1_in_2 = rel.apply_inverse(&m1.centroid());
    [
        toward(m1, c2_in_1 - m1.centroid()),
        toward(m2, c1_in_2 - m2.centroid()),
    ]
}

/// Distance, closest points and closest features of two posed convex models (V-Clip).
///
/// `cache`: `Some` to warm-start from, and update, the caller's per-pair cache; `None` for a cold
/// start. Errors: `NonFinitePose`; `Internal` if the search exceeded its iteration bound (never on
/// valid input).
pub fn convex_distance(
    m1: &ConvexModel,
    pose1: &Pose,
    m2: &ConvexModel,
    pose2: &Pose,
    cache: Option<&mut ConvexPairCache>,
) -> Result<ConvexDistance, Error> {
    pose1.validate()?;
    pose2.validate()?;
    let rel = RelPose::between(pose1, pose2);
    let start = start_pair(m1, m2, &rel, cache.as_deref());
    let ans = vclip::vclip(m1, m2, &rel, start)?;
    if let Some(c) = cache {
        c.entry = Some(CacheEntry {
            uid1: m1.uid(),
            uid2: m2.uid(),
            f1: ans.state[0],
            f2: ans.state[1],
        });
    }
    Ok(ConvexDistance {
        distance: ans.distance,
        p1: ans.points[0],
        p2: ans.points[1],
        feature1: ans.state[0],
        feature2: ans.state[1],
        intersecting: ans.intersecting,
        stats: ConvexStats {
            iterations: ans.counters.iterations,
            local_minima: ans.counters.local_minima,
            cycles_broken: ans.counters.cycles,
        },
    })
}

/// Whether two posed convex models touch or overlap (V-Clip; see [`convex_distance`]).
pub fn convex_intersect(
    m1: &ConvexModel,
    pose1: &Pose,
    m2: &ConvexModel,
    pose2: &Pose,
    cache: Option<&mut ConvexPairCache>,
) -> Result<bool, Error> {
    Ok(convex_distance(m1, pose1, m2, pose2, cache)?.intersecting)
}

/// Penetration depth and direction of two posed convex models (or their closest points when apart).
///
/// The overlap verdict comes from V-Clip (warm-started from `cache` as in [`convex_distance`]). The
/// depth is exact up to rounding: the minimum of the Minkowski difference's support function over
/// all its facet normals (see `penetration.rs`); cost `O(E1 E2)` plus hill climbs.
pub fn convex_penetration(
    m1: &ConvexModel,
    pose1: &Pose,
    m2: &ConvexModel,
    pose2: &Pose,
    cache: Option<&mut ConvexPairCache>,
) -> Result<ConvexPenetration, Error> {
    let d = convex_distance(m1, pose1, m2, pose2, cache)?;
    if !d.intersecting {
        // The direction is taken in model 1's frame, as V-Clip measured the distance: world
        // coordinates can round two closest points far nearer than the models' size together.
        let v = pose1.rotation * (RelPose::between(pose1, pose2).apply(&d.p2) - d.p1);
        let normal = if d.distance > 0.0 {
            model::unit(&v)
        } else {
            Vec3::zeros()
        };
        return Ok(ConvexPenetration {
            intersecting: false,
            depth: 0.0,
            normal,
            p1: d.p1,
            p2: d.p2,
            closest: d,
        });
    }
    let rel = RelPose::between(pose1, pose2);
    let pd = penetration::penetration_depth(m1, m2, &rel);
    let depth = pd.depth.max(0.0);
    let normal = pose1.rotation * pd.normal;
    // Witnesses: model 2 moved out by the depth touches model 1 (to rounding); V-Clip finds where.
    let mut out = *pose2;
    out.translation += normal * depth;
    let start = [d.feature1, d.feature2];
    let touch = vclip::vclip(m1, m2, &RelPose::between(pose1, &out), start)?;
    Ok(ConvexPenetration {
        intersecting: true,
        depth,
        normal,
        p1: touch.points[0],
        p2: touch.points[1],
        closest: d,
    })
}
