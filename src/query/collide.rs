//! Collision: which triangle pairs of two posed models overlap.

use super::traversal::{NodePair, PairStack};
use super::{Stats, prepare};
use crate::bounding_volume::OverlapVolume;
use crate::bvh::{Bvh, NodeRef};
use crate::error::Error;
use crate::geometry::{Tri, tri_overlap};
use crate::math::{Pose, RelPose, Vec3};
use crate::model::{CollisionVolume, Model};
use std::mem::MaybeUninit;
use std::time::Instant;

/// Report every overlapping pair, or stop at the first (PQP's `PQP_ALL_CONTACTS` = 1 and
/// `PQP_FIRST_CONTACT` = 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(i32)]
pub enum ContactMode {
    /// Find all overlapping triangle pairs.
    All = 1,
    /// Stop at the first overlapping pair found.
    First = 2,
}

/// An overlapping triangle pair, by the ids the caller gave the triangles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(C)]
pub struct ContactPair {
    /// Id of the triangle of model 1.
    pub id1: i32,
    /// Id of the triangle of model 2.
    pub id2: i32,
}

/// The answer of a collision query.
#[derive(Clone, Debug, Default)]
pub struct CollideResult {
    /// Work done.
    pub stats: Stats,
    pairs: Vec<ContactPair>,
}

impl CollideResult {
    /// An empty result.
    pub fn new() -> Self {
        Self::default()
    }
    /// Whether any triangle pair overlaps.
    pub fn colliding(&self) -> bool {
        !self.pairs.is_empty()
    }
    /// The overlapping pairs found (one, at most, in `ContactMode::First`), each once.
    pub fn pairs(&self) -> &[ContactPair] {
        &self.pairs
    }
    /// Number of overlapping pairs found.
    pub fn num_pairs(&self) -> usize {
        self.pairs.len()
    }
    /// The pair list, for the queries that fill it.
    pub(super) fn pairs_mut(&mut self) -> &mut Vec<ContactPair> {
        &mut self.pairs
    }
    /// Sets the pairs (ids) and the work of a query on a primitive (`query/primitive.rs`).
    pub(super) fn set_pairs(
        &mut self,
        (pairs, stats): super::primitive::Pairs,
    ) -> Result<(), Error> {
        self.pairs.clear();
        self.pairs
            .extend(pairs.into_iter().map(|(id1, id2)| ContactPair { id1, id2 }));
        self.stats = stats;
        Ok(())
    }
    /// Releases the pair list's memory (PQP's `FreePairsList`).
    pub fn free_pairs(&mut self) {
        self.pairs = Vec::new();
    }
}

/// Finds the overlapping triangle pairs of `m1` at `pose1` and `m2` at `pose2`.
///
/// Two triangles overlap when they share a point: crossing, touching at a vertex or edge, and
/// coplanar overlap all count. The test is exact for triangles in general position.
///
/// ```
/// use pqp::{collide, ContactMode, Model, Pose};
/// let tri = |id| ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], id);
/// let a = Model::from_triangles([tri(1)]).unwrap();
/// let b = Model::from_triangles([tri(2)]).unwrap();
/// let r = collide(&a, &Pose::identity(), &b, &Pose::from_translation([0.2, 0.2, 0.0]), ContactMode::All).unwrap();
/// assert_eq!(r.num_pairs(), 1);
/// assert_eq!((r.pairs()[0].id1, r.pairs()[0].id2), (1, 2));
/// ```
pub fn collide(
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    mode: ContactMode,
) -> Result<CollideResult, Error> {
    let mut r = CollideResult::new();
    collide_into(&mut r, m1, pose1, m2, pose2, mode)?;
    Ok(r)
}

/// As [`collide`], reusing `result`'s storage. On error `result` is left as it was.
pub fn collide_into(
    result: &mut CollideResult,
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    mode: ContactMode,
) -> Result<(), Error> {
    let start = Instant::now();
    let first = mode == ContactMode::First;
    if let Some(found) = super::primitive::pairs(m1, pose1, m2, pose2, 0.0, first) {
        return result.set_pairs(found?);
    }
    let (b1, b2, rel) = prepare(m1, pose1, m2, pose2)?;
    result.pairs.clear();
    // Two triangles: test them at once (their volumes, computed from them, would cost about as
    // much as the test).
    let leaf_pair = |ta: usize, tb: usize, moved: &Tri| {
        tri_overlap(&b1.tri(ta), moved).then(|| ContactPair {
            id1: b1.ids[ta],
            id2: b2.ids[tb],
        })
    };
    let mut stats = search_pairs(&mut result.pairs, b1, b2, &rel, mode, leaf_pair);
    stats.query_time_secs = start.elapsed().as_secs_f64();
    result.stats = stats;
    Ok(())
}

/// The search of [`collide_into`] on the models' collision volume (the swept sphere volumes if
/// both models ask for them, else the boxes): see [`search`]. `leaf_pair` gets the triangles' leaf
/// slots and model 2's triangle posed by `rel` in model 1's frame.
fn search_pairs(
    pairs: &mut Vec<ContactPair>,
    b1: &Bvh,
    b2: &Bvh,
    rel: &RelPose,
    mode: ContactMode,
    leaf_pair: impl FnMut(usize, usize, &Tri) -> Option<ContactPair>,
) -> Stats {
    let ssv = b1.collision == CollisionVolume::Ssv && b2.collision == CollisionVolume::Ssv;
    // The mode as a constant: the all-contacts search compiles without the first-contact order.
    // The volumes through closures, which are inlined into the search (a method passed by name
    // was called through a shim that was not, and cost 7% of collide all).
    let (ssv_of, obb_of) = (|b: &Bvh, r| b.ssv(r), |b: &Bvh, r| b.obb(r));
    match (ssv, mode) {
        (true, ContactMode::All) => search::<_, false>(pairs, b1, b2, rel, leaf_pair, ssv_of),
        (true, ContactMode::First) => search::<_, true>(pairs, b1, b2, rel, leaf_pair, ssv_of),
        (false, ContactMode::All) => search::<_, false>(pairs, b1, b2, rel, leaf_pair, obb_of),
        (false, ContactMode::First) => search::<_, true>(pairs, b1, b2, rel, leaf_pair, obb_of),
    }
}

/// The search on the overlap volume `volume` picks from each node: depth first, descending the
/// larger volume; `leaf_pair` tests the triangles (by leaf slot) of overlapping leaf pairs and
/// gives the pair to report, if any. `FIRST`: stop at the first pair, visiting the nearer child
/// first (see [`near_first`]); else report every pair, visiting the children as stored (an
/// all-contacts search visits every overlapping pair whatever the order).
fn search<V: OverlapVolume, const FIRST: bool>(
    pairs: &mut Vec<ContactPair>,
    b1: &Bvh,
    b2: &Bvh,
    rel: &RelPose,
    mut leaf_pair: impl FnMut(usize, usize, &Tri) -> Option<ContactPair>,
    volume: impl Fn(&Bvh, NodeRef) -> V,
) -> Stats {
    // The root pair first, before the search's tables are set up: a planner's free-space checks
    // mostly end there, and the tables (a kilobyte of keys to clear) would cost as much as the
    // test. Its volumes go into the tables if the search goes on (it tests the pair again, from
    // them, as its first node).
    let (root_a, root_b) = (b1.root(), b2.root());
    let roots = if root_a.is_leaf() || root_b.is_leaf() {
        None
    } else {
        let va = volume(b1, root_a);
        let vb = volume(b2, root_b);
        let posed = V::pose(&vb, rel);
        if !V::overlap_posed(&va, &posed, rel) {
            return Stats {
                bv_tests: 1,
                ..Stats::default()
            };
        }
        Some(((va, va.size()), (posed, vb.size())))
    };
    let mut stats = Stats::default();
    let mut stack = PairStack::new();
    let (mut nodes1, mut posed2) = (NodeCache::new(), NodeCache::new());
    if let Some((a, b)) = roots {
        nodes1.get(root_a, || a);
        posed2.get(root_b, || b);
    }
    // Model 1's triangles posed in model 2's frame, and model 2's in model 1's.
    let (mut tris1, mut tris2) = (NodeCache::<Tri>::new(), NodeCache::<Tri>::new());
    let to_1 = |t: Tri| t.map(|p| rel.apply(&p));
    let to_2 = |t: Tri| t.map(|p| rel.apply_inverse(&p));
    // The children of `a` (model 1) or of `b` (model 2), in the order to visit them.
    let split1 = |a: NodeRef, b: NodeRef| {
        if FIRST {
            near_first(b1, a, &rel.apply(&centre(b2, b)))
        } else {
            b1.children(a)
        }
    };
    let split2 = |a: NodeRef, b: NodeRef| {
        if FIRST {
            near_first(b2, b, &rel.apply_inverse(&centre(b1, a)))
        } else {
            b2.children(b)
        }
    };
    stack.push(NodePair {
        a: b1.root(),
        b: b2.root(),
        bound: 0.0,
    });
    while let Some(p) = stack.pop() {
        if p.a.is_leaf() && p.b.is_leaf() {
            stats.tri_tests += 1;
            let tb = p.b.triangle();
            let moved = *tris2.get(p.b, || to_1(b2.tri(tb)));
            if let Some(pair) = leaf_pair(p.a.triangle(), tb, &moved) {
                pairs.push(pair);
                if FIRST {
                    break;
                }
            }
            continue;
        }
        // A node against a triangle: volumes with a direct test skip the triangle's own volume.
        if p.a.is_leaf() || p.b.is_leaf() {
            let direct = if p.b.is_leaf() {
                let moved = tris2.get(p.b, || to_1(b2.tri(p.b.triangle())));
                let (va, _) = nodes1.get(p.a, || {
                    let v = volume(b1, p.a);
                    (v, v.size())
                });
                V::overlap_triangle(va, moved)
            } else {
                let moved = tris1.get(p.a, || to_2(b1.tri(p.a.triangle())));
                V::overlap_triangle(&volume(b2, p.b), moved)
            };
            if let Some(hit) = direct {
                stats.bv_tests += 1;
                if hit {
                    // Descend the node; the triangle stays.
                    if p.b.is_leaf() {
                        let [c0, c1] = split1(p.a, p.b);
                        stack.push(NodePair { a: c1, ..p });
                        stack.push(NodePair { a: c0, ..p });
                    } else {
                        let [c0, c1] = split2(p.a, p.b);
                        stack.push(NodePair { b: c1, ..p });
                        stack.push(NodePair { b: c0, ..p });
                    }
                }
                continue;
            }
        }
        let (va, size_a) = nodes1.get(p.a, || {
            let v = volume(b1, p.a);
            (v, v.size())
        });
        let (vb, size_b) = posed2.get(p.b, || {
            let v = volume(b2, p.b);
            (V::pose(&v, rel), v.size())
        });
        stats.bv_tests += 1;
        if !V::overlap_posed(va, vb, rel) {
            continue;
        }
        // Descend the larger volume, or whichever is not a leaf (as `descend_first`).
        if p.b.is_leaf() || (!p.a.is_leaf() && *size_a >= *size_b) {
            let [c0, c1] = split1(p.a, p.b);
            stack.push(NodePair { a: c1, ..p });
            stack.push(NodePair { a: c0, ..p });
        } else {
            let [c0, c1] = split2(p.a, p.b);
            stack.push(NodePair { b: c1, ..p });
            stack.push(NodePair { b: c0, ..p });
        }
    }
    stats
}

/// A point central to node `r` of `b`: its box's centre, or a leaf's centroid.
#[inline(always)]
fn centre(b: &Bvh, r: NodeRef) -> Vec3 {
    if r.is_leaf() {
        let [x, y, z] = b.tri(r.triangle());
        (x + y + z) / 3.0
    } else {
        b.obb(r).center
    }
}

/// The children of inner node `r` of `b`, the one whose centre is nearer `other` (a point in
/// `b`'s frame: the centre of the node `r` is tested against) first.
///
/// A first-contact search ends at the first overlapping triangle pair, so the order in which it
/// visits overlapping node pairs decides its work. Surfaces that cross do so in the region the two
/// volumes share, and the child nearer the other node's centre is the one more likely to reach
/// into it: visited first, it finds a contact after fewer tests (on the bunny-torus poses, a median over poses of 35 bound tests per query instead of 126).
/// The answer stays a pair the all-contacts search reports; which one may change. A search
/// without a contact visits every overlapping pair whatever the order, and pays for the ordering
/// (about 12% more time on the bunny poses without contact).
#[inline(always)]
fn near_first(b: &Bvh, r: NodeRef, other: &Vec3) -> [NodeRef; 2] {
    let [c0, c1] = b.children(r);
    let d0 = (centre(b, c0) - other).norm_squared();
    let d1 = (centre(b, c1) - other).norm_squared();
    if d1 < d0 { [c1, c0] } else { [c0, c1] }
}

/// Slots of a [`NodeCache`].
const NODE_SLOTS: usize = 64;

/// Values computed for the nodes of one hierarchy met recently (inner nodes and leaves), in a
/// small direct-mapped table: the depth-first search tests one node against a run of the other
/// model's nodes while it descends the other model, so a node's volume (posed, for model 2) and
/// size are computed once for the run rather than at every test. Lives in the query, on the
/// stack; only its keys are initialised.
struct NodeCache<T> {
    /// The raw value of the node whose value each slot holds; `i32::MIN` (no node's: a model has
    /// fewer than `i32::MAX` triangles): none.
    keys: [i32; NODE_SLOTS],
    values: [MaybeUninit<T>; NODE_SLOTS],
}

impl<T: Copy> NodeCache<T> {
    fn new() -> Self {
        NodeCache {
            keys: [i32::MIN; NODE_SLOTS],
            values: [const { MaybeUninit::uninit() }; NODE_SLOTS],
        }
    }

    /// Node `r`'s value, computed by `make` when its slot holds another node's.
    #[inline(always)]
    fn get(&mut self, r: NodeRef, make: impl FnOnce() -> T) -> &T {
        let i = (r.raw() as u32 as usize) % NODE_SLOTS;
        if self.keys[i] != r.raw() {
            self.values[i] = MaybeUninit::new(make());
            self.keys[i] = r.raw();
        }
        // SAFETY: a slot's key is set only together with its value (just above, or before).
        unsafe { self.values[i].assume_init_ref() }
    }
}
