//! The bounds of a BVTT node's children: the descent rule (which side to split), the leaves'
//! volumes (computed from their triangles, kept in a small cache) and the fixed side's volume
//! posed once in the other model's frame.

use super::ClosestSearch;
use crate::bounding_volume::{CompactSsv, DistanceVolume, Ssv, Want};
use crate::bvh::{Bvh, NodeRef};
use crate::geometry::PlanedTri;
use crate::math::{RelPose, Vec3};
use crate::query::traversal::{LeafCache, NodePair};
use std::mem::MaybeUninit;

/// Recently met leaves' volumes of each model (see [`LeafCache`]). Made in place by
/// [`LeafVolumes::init`], on the query's stack.
#[derive(Default)]
pub(crate) struct LeafVolumes {
    first: LeafCache<CompactSsv>,
    second: LeafCache<CompactSsv>,
    /// Volumes recently posed by [`expand`]: a node stays the fixed side of several expansions
    /// close together, so a posed volume is often asked for again soon.
    posed: PosedVolumes,
    /// Model 2's triangles recently tested, posed in model 1's frame: a leaf of one model is
    /// tested against a few neighbouring leaves of the other in turn, so the same few of model 2
    /// come back alternately (a leaf against a node of two leaves, then the next leaf). With
    /// their planes, by which most pairs are shown apart (see `test_triangles`).
    pub(super) triangles: LeafCache<PlanedTri>,
}

impl LeafVolumes {
    /// Empty caches in `slot`, made in place (only their keys are written: moving a value made
    /// elsewhere would copy every slot, about 26 KB).
    #[inline(always)]
    pub(crate) fn init(slot: &mut MaybeUninit<LeafVolumes>) -> &mut LeafVolumes {
        let p = slot.as_mut_ptr();
        // SAFETY: `p` is valid and aligned (from `slot`); each field's keys are written and every
        // other field is `MaybeUninit`, so the whole value is then initialised.
        unsafe {
            LeafCache::init_at(&raw mut (*p).first);
            LeafCache::init_at(&raw mut (*p).second);
            LeafCache::init_at(&raw mut (*p).triangles);
            (&raw mut (*p).posed.keys).write([0; POSED_SLOTS]);
            slot.assume_init_mut()
        }
    }
}

/// Slots of [`PosedVolumes`].
const POSED_SLOTS: usize = 64;

/// Nodes' volumes posed in the other model's frame, in a small direct-mapped table (as
/// [`LeafCache`]: only the keys are initialised).
struct PosedVolumes {
    /// The node each slot holds, as `key` gives it; 0: none.
    keys: [u64; POSED_SLOTS],
    volumes: [MaybeUninit<Ssv>; POSED_SLOTS],
}

impl Default for PosedVolumes {
    fn default() -> Self {
        PosedVolumes {
            keys: [0; POSED_SLOTS],
            volumes: [const { MaybeUninit::uninit() }; POSED_SLOTS],
        }
    }
}

impl PosedVolumes {
    /// `v`, the volume of node `r` of model 2 (`second`) or 1, posed by `rel` (by its inverse for
    /// model 1), unless its slot holds it. (The volume is looked up whether or not it is needed:
    /// a branch on the need costs more than the lookup.)
    #[inline(always)]
    fn get(&mut self, r: NodeRef, second: bool, v: &CompactSsv, rel: &RelPose) -> &Ssv {
        // Nonzero, and distinct for every node of either model.
        let key = ((r.raw() as u32 as u64) << 1 | u64::from(second)) + 1;
        let i = (r.raw() as u32 as usize).wrapping_add(usize::from(second) * (POSED_SLOTS / 2))
            % POSED_SLOTS;
        if self.keys[i] != key {
            self.volumes[i] = MaybeUninit::new(v.posed(rel, !second));
            self.keys[i] = key;
        }
        // SAFETY: a slot's key is set nonzero only together with its volume.
        unsafe { self.volumes[i].assume_init_ref() }
    }
}

impl ClosestSearch<'_> {
    /// The bound of the BVTT node `(a, b)` (exact below `cutoff`, at least `cutoff` otherwise),
    /// with a separating axis when it reaches `cutoff` (see [`expand`]).
    pub(super) fn pair_bound(&mut self, a: NodeRef, b: NodeRef, cutoff: f64) -> Child {
        let (b1, b2) = (self.b1, self.b2);
        let va = volume(b1, &mut self.leaves.first, a);
        let vb = volume(b2, &mut self.leaves.second, b);
        let want = Want {
            axes: self.front.is_some(),
            exact: true,
        };
        // Through the table of posed volumes: the nodes of a front come in the order the last
        // search left them, so that consecutive ones often share model 2's node.
        let moved = self.leaves.posed.get(b, true, vb, &self.rel);
        let [(bound, axis)] =
            Ssv::bounds_against([va], moved, &self.rel, false, want, cutoff, self.slack);
        (NodePair { a, b, bound }, axis)
    }
}

/// The root of the BVTT with its bound (exact below `cutoff`, at least `cutoff` otherwise).
pub(crate) fn root_pair(b1: &Bvh, b2: &Bvh, rel: &RelPose, cutoff: f64) -> NodePair {
    let (a, b) = (b1.root(), b2.root());
    NodePair {
        a,
        b,
        bound: DistanceVolume::distance_below(&b1.ssv(a), &b2.ssv(b), rel, cutoff),
    }
}

/// A BVTT node with its bound, and an axis along which its volumes are at least that far apart
/// (in model 1's frame, from model 1's volume towards model 2's; not normalized), or zero.
pub(crate) type Child = (NodePair, Vec3);

/// The two children of the BVTT node `p` with their bounds (exact below `cutoff`, at least
/// `cutoff` otherwise) and, with `axes`, their separating axes (see [`Child`]; zero without), or
/// `None` for a pair of leaves. The side split is [`splits_first`]'s. Leaves' volumes (computed
/// from their triangles) go through `leaves`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn expand(
    b1: &Bvh,
    b2: &Bvh,
    rel: &RelPose,
    slack: f64,
    p: &NodePair,
    cutoff: f64,
    want: Want,
    leaves: &mut LeafVolumes,
) -> Option<[Child; 2]> {
    let (a, b) = (p.a, p.b);
    let split_first = splits_first(b1, b2, a, b)?;
    // The fixed side is posed once, in the frame of the side being split; the children are read
    // where they lie (no copies).
    let pair = |a, b, (bound, axis)| (NodePair { a, b, bound }, axis);
    Some(if split_first {
        let fixed = leaves
            .posed
            .get(b, true, volume(b2, &mut leaves.second, b), rel);
        let [c0, c1] = b1.children(a);
        let children = volumes(b1, &mut leaves.first, [c0, c1]);
        let [d0, d1] = Ssv::bounds_against(children, fixed, rel, false, want, cutoff, slack);
        [pair(c0, b, d0), pair(c1, b, d1)]
    } else {
        let fixed = leaves
            .posed
            .get(a, false, volume(b1, &mut leaves.first, a), rel);
        let [c0, c1] = b2.children(b);
        let children = volumes(b2, &mut leaves.second, [c0, c1]);
        let [d0, d1] = Ssv::bounds_against(children, fixed, rel, true, want, cutoff, slack);
        [pair(a, c0, d0), pair(a, c1, d1)]
    })
}

/// The descent rule: which node of the BVTT node (`a`, `b`) its expansion splits. `Some(true)`
/// model 1's (when model 2's is a leaf, or when both are inner nodes and model 1's volume is at
/// least as large as model 2's), `Some(false)` model 2's, `None` for a pair of leaves: the rule of
/// `traversal::descend_first`, with the sizes the hierarchy stores. Written once for the search:
/// [`expand`] follows it, and the prefetches ask for what it will read.
#[inline(always)]
pub(super) fn splits_first(b1: &Bvh, b2: &Bvh, a: NodeRef, b: NodeRef) -> Option<bool> {
    match (a.is_leaf(), b.is_leaf()) {
        (true, true) => None,
        (false, true) => Some(true),
        (true, false) => Some(false),
        (false, false) => Some(b1.inner_ssv_size(a) >= b2.inner_ssv_size(b)),
    }
}

/// Asks the processor to bring into the cache the volumes that expanding the BVTT node `p` will
/// read: the children of the side the descent rule splits (a hint; nothing on other
/// architectures, nor for a leaf child, whose volume comes from its triangle). For a node stacked
/// now and expanded later: on models larger than the caches (the nested shells' hierarchies take
/// 4.5 MB each) the loads then overlap other work.
#[inline(always)]
pub(super) fn prefetch_children(b1: &Bvh, b2: &Bvh, p: &NodePair) {
    #[cfg(target_arch = "x86_64")]
    {
        // Both leaves: nothing to read.
        let (model, node) = match splits_first(b1, b2, p.a, p.b) {
            None => return,
            Some(true) => (b1, p.a),
            Some(false) => (b2, p.b),
        };
        for c in model.children(node) {
            if !c.is_leaf() {
                model.prefetch(c);
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (b1, b2, p);
}

/// For each child of the BVTT node `p` (by the descent rule, [`splits_first`]), asks for the
/// volumes its own expansion will read (see [`prefetch_children`]): one level further ahead than
/// the prefetch of a kept child, before the children's bounds are known.
#[inline(always)]
pub(super) fn prefetch_grandchildren(b1: &Bvh, b2: &Bvh, p: &NodePair) {
    match splits_first(b1, b2, p.a, p.b) {
        None => {}
        Some(true) => {
            for c in b1.children(p.a) {
                prefetch_children(b1, b2, &NodePair { a: c, ..*p });
            }
        }
        Some(false) => {
            for c in b2.children(p.b) {
                prefetch_children(b1, b2, &NodePair { b: c, ..*p });
            }
        }
    }
}

/// The volume of node `r` of `b`, by reference: an inner node's where it lies, a leaf's through
/// `cache`.
#[inline(always)]
fn volume<'x>(b: &'x Bvh, cache: &'x mut LeafCache<CompactSsv>, r: NodeRef) -> &'x CompactSsv {
    cache.get_ref(r, |r| b.inner_ssv(r), |r| b.leaf_compact_ssv(r))
}

/// As [`volume`], for two nodes at once.
#[inline(always)]
fn volumes<'x>(
    b: &'x Bvh,
    cache: &'x mut LeafCache<CompactSsv>,
    rs: [NodeRef; 2],
) -> [&'x CompactSsv; 2] {
    cache.get_two(rs, |r| b.inner_ssv(r), |r| b.leaf_compact_ssv(r))
}

/// The children of a BVTT node that pairs a leaf with an inner node, by how many of them are leaf
/// pairs (with `p`'s bound, which bounds them too).
pub(super) enum LeafChildren {
    /// Not such a node, or neither child is a leaf pair.
    None,
    /// The inner node's children are both leaves.
    Both([NodePair; 2]),
    /// One is: the leaf pair, then the other.
    One(NodePair, NodePair),
}

/// See [`LeafChildren`].
#[inline]
pub(super) fn leaf_children(b1: &Bvh, b2: &Bvh, p: &NodePair) -> LeafChildren {
    let (leaf_first, node) = if p.a.is_leaf() && !p.b.is_leaf() {
        (true, b2.children(p.b))
    } else if p.b.is_leaf() && !p.a.is_leaf() {
        (false, b1.children(p.a))
    } else {
        return LeafChildren::None;
    };
    let pair = |c: NodeRef| {
        let (a, b) = if leaf_first { (p.a, c) } else { (c, p.b) };
        NodePair { a, b, ..*p }
    };
    match node {
        [c0, c1] if c0.is_leaf() && c1.is_leaf() => LeafChildren::Both([pair(c0), pair(c1)]),
        [c0, c1] if c0.is_leaf() => LeafChildren::One(pair(c0), pair(c1)),
        [c0, c1] if c1.is_leaf() => LeafChildren::One(pair(c1), pair(c0)),
        _ => LeafChildren::None,
    }
}

impl ClosestSearch<'_> {
    /// The bound of the BVTT node `p`, a leaf against an inner node, as [`expand`] gives its
    /// children's (the leaf posed, through the same table).
    #[inline(always)]
    pub(super) fn bound_one(&mut self, p: &NodePair, cutoff: f64, want: Want) -> Child {
        let (b1, b2, rel, slack) = (self.b1, self.b2, &self.rel, self.slack);
        let leaves = &mut *self.leaves;
        let [(bound, axis)] = if p.a.is_leaf() {
            let fixed = leaves
                .posed
                .get(p.a, false, volume(b1, &mut leaves.first, p.a), rel);
            let node = b2.inner_ssv(p.b);
            Ssv::bounds_against([node], fixed, rel, true, want, cutoff, slack)
        } else {
            let fixed = leaves
                .posed
                .get(p.b, true, volume(b2, &mut leaves.second, p.b), rel);
            let node = b1.inner_ssv(p.a);
            Ssv::bounds_against([node], fixed, rel, false, want, cutoff, slack)
        };
        (NodePair { bound, ..*p }, axis)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whatever the slots, each node of either model gets its own volume posed the right way:
    /// the same index in both models, nodes that share a slot, a node met again after its slot
    /// was taken.
    #[test]
    fn posed_volumes_are_each_nodes_own() {
        let rel = RelPose {
            rot: nalgebra::Rotation3::from_euler_angles(0.3, -0.5, 1.1).into_inner(),
            trans: Vec3::new(0.5, -2.0, 3.0),
        };
        let volume = |r: NodeRef| CompactSsv {
            axes: [Vec3::x(), Vec3::y()],
            origin: Vec3::new(f64::from(r.raw()), 1.0, -2.0),
            lengths: [1.0, 2.0],
            radius: 0.25,
        };
        let mut posed = PosedVolumes::default();
        let s = POSED_SLOTS as i32;
        let asks = [
            (0, true),
            (0, false),
            (0, true),
            (s, true),
            (0, true),
            (-1, false),
            (-1, true),
            (-1 - s, false),
            (-1, false),
            (s / 2, true),
            (s / 2, false),
            (0, false),
        ];
        for (r, second) in asks {
            let r = NodeRef::from_raw(r);
            let v = volume(r);
            let got = *posed.get(r, second, &v, &rel);
            assert_eq!(got, v.posed(&rel, !second), "node {r}, second {second}");
        }
    }
}
