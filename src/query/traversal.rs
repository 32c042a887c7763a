//! What the queries share: the descent rule of the bounding volume traversal tree (BVTT) and a
//! fixed-size stack, so that no query allocates.

use crate::bounding_volume::BoundingVolume;
use crate::bvh::{leaf_triangle, NodeRef, MAX_DEPTH};
use std::mem::MaybeUninit;

/// A node of the BVTT: a node of each hierarchy, and (for distance) the lower bound of the pair.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct NodePair {
    pub a: NodeRef,
    pub b: NodeRef,
    pub bound: f64,
}

/// Each step of a depth-first descent leaves at most one sibling pair behind, and the descent is at
/// most as long as both trees are deep.
const STACK_CAPACITY: usize = 2 * MAX_DEPTH + 4;

/// A stack on the call stack (no heap allocation per query).
pub(crate) struct PairStack {
    items: [NodePair; STACK_CAPACITY],
    len: usize,
}

impl PairStack {
    pub fn new() -> Self {
        PairStack {
            items: [NodePair::default(); STACK_CAPACITY],
            len: 0,
        }
    }

    #[inline]
    pub fn push(&mut self, p: NodePair) {
        // The build bounds the depth, so this cannot overflow; checked indexing keeps it memory safe
        // even if that reasoning were wrong (a panic, caught at the C boundary).
        self.items[self.len] = p;
        self.len += 1;
    }

    #[inline]
    pub fn pop(&mut self) -> Option<NodePair> {
        if self.len == 0 {
            None
        } else {
            self.len -= 1;
            Some(self.items[self.len])
        }
    }
}

/// Which side of a BVTT node to descend: `true` for model 1's node. Descend the larger volume, or
/// whichever is not a leaf (both leaves is handled by the caller).
#[inline]
pub(crate) fn descend_first<B: BoundingVolume>(a: NodeRef, b: NodeRef, va: &B, vb: &B) -> bool {
    if b < 0 {
        return true;
    }
    if a < 0 {
        return false;
    }
    va.size() >= vb.size()
}

/// Slots of a [`LeafCache`].
const LEAF_SLOTS: usize = 64;

/// The volumes of leaves met recently in one model, in a small direct-mapped table: a leaf stores
/// no volume (it is computed from the triangle), and a search meets the same leaf against many
/// nodes of the other model. Lives in the query (models stay immutable), on the stack; only its
/// keys are initialised, so it costs next to nothing to set up.
pub(crate) struct LeafCache<V> {
    /// The leaf whose volume each slot holds; 0 (an inner node, never looked up): none.
    keys: [NodeRef; LEAF_SLOTS],
    volumes: [MaybeUninit<V>; LEAF_SLOTS],
}

impl<V: Copy> Default for LeafCache<V> {
    fn default() -> Self {
        LeafCache {
            keys: [0; LEAF_SLOTS],
            volumes: [const { MaybeUninit::uninit() }; LEAF_SLOTS],
        }
    }
}

impl<V: Copy> LeafCache<V> {
    /// Node `r`'s volume, as `volume(r)` gives it; a leaf's from the table when it is there.
    #[inline(always)]
    pub fn get(&mut self, r: NodeRef, volume: impl Fn(NodeRef) -> V) -> V {
        if r >= 0 {
            return volume(r);
        }
        let i = leaf_triangle(r) % LEAF_SLOTS;
        if self.keys[i] == r {
            // SAFETY: a slot's key is set to a leaf (< 0) only together with its volume.
            unsafe { self.volumes[i].assume_init() }
        } else {
            let v = volume(r);
            self.volumes[i] = MaybeUninit::new(v);
            self.keys[i] = r;
            v
        }
    }
}
