//! What the queries share: the descent rule of the bounding volume traversal tree (BVTT) and a
//! fixed-size stack, so that no query allocates.

use crate::bounding_volume::BoundingVolume;
use crate::bvh::{MAX_DEPTH, NodeRef};
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

/// A stack on the call stack (no heap allocation per query), left uninitialised: a priority
/// search starts one for every pair its queue overflows with (thousands per query on the nested
/// shells), and zeroing it cost more than its use.
pub(crate) struct PairStack {
    items: [MaybeUninit<NodePair>; STACK_CAPACITY],
    len: usize,
}

impl PairStack {
    pub fn new() -> Self {
        PairStack {
            items: [const { MaybeUninit::uninit() }; STACK_CAPACITY],
            len: 0,
        }
    }

    #[inline]
    pub fn push(&mut self, p: NodePair) {
        // The build bounds the depth, so this cannot overflow; checked indexing keeps it memory safe
        // even if that reasoning were wrong (a panic, caught at the C boundary).
        self.items[self.len] = MaybeUninit::new(p);
        self.len += 1;
    }

    /// Pushes `p` if `keep`: written either way, counted only if kept (no branch).
    #[inline]
    pub fn push_if(&mut self, p: NodePair, keep: bool) {
        self.items[self.len] = MaybeUninit::new(p);
        self.len += usize::from(keep);
    }

    #[inline]
    pub fn pop(&mut self) -> Option<NodePair> {
        if self.len == 0 {
            None
        } else {
            self.len -= 1;
            // SAFETY: the items below `len` were written by `push`.
            Some(unsafe { self.items[self.len].assume_init() })
        }
    }
}

/// Which side of a BVTT node to descend: `true` for model 1's node. Descend the larger volume, or
/// whichever is not a leaf (both leaves is handled by the caller).
#[inline]
pub(crate) fn descend_first<B: BoundingVolume>(a: NodeRef, b: NodeRef, va: &B, vb: &B) -> bool {
    if b.is_leaf() {
        return true;
    }
    if a.is_leaf() {
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
    /// For the first of two leaves asked for together that share a slot (see `get_two`).
    spare: MaybeUninit<V>,
}

impl<V: Copy> Default for LeafCache<V> {
    fn default() -> Self {
        LeafCache {
            keys: [NodeRef::inner(0); LEAF_SLOTS],
            volumes: [const { MaybeUninit::uninit() }; LEAF_SLOTS],
            spare: MaybeUninit::uninit(),
        }
    }
}

impl<V: Copy> LeafCache<V> {
    /// Makes the cache at `slot` empty, in place: only its keys are written (the rest may stay
    /// uninitialised). A cache built by value and moved into place is copied whole, every slot
    /// included (6.5 KB for a swept sphere volume's), which cost a distance query two copies.
    ///
    /// # Safety
    /// `slot` must be valid for writes and aligned for `Self`.
    #[inline(always)]
    pub(crate) unsafe fn init_at(slot: *mut Self) {
        // SAFETY: the caller's promise; the other fields are `MaybeUninit`, valid uninitialised.
        unsafe { (&raw mut (*slot).keys).write([NodeRef::inner(0); LEAF_SLOTS]) };
    }

    /// The slot of leaf `r`, filled with its volume (`leaf(r)`) if it holds another.
    #[inline(always)]
    fn fill(&mut self, r: NodeRef, leaf: impl Fn(NodeRef) -> V) -> usize {
        let i = r.triangle() % LEAF_SLOTS;
        if self.keys[i] != r {
            self.volumes[i] = MaybeUninit::new(leaf(r));
            self.keys[i] = r;
        }
        i
    }

    /// The volume of node `r` by reference, as [`get_two`](LeafCache::get_two) gives it.
    #[inline(always)]
    pub fn get_ref<'x>(
        &'x mut self,
        r: NodeRef,
        inner: impl Fn(NodeRef) -> &'x V,
        leaf: impl Fn(NodeRef) -> V + Copy,
    ) -> &'x V {
        if !r.is_leaf() {
            return inner(r);
        }
        self.get_leaf(r, leaf)
    }

    /// The value of leaf `r` (a leaf), made by `leaf` unless its slot holds it.
    #[inline(always)]
    pub fn get_leaf(&mut self, r: NodeRef, leaf: impl Fn(NodeRef) -> V) -> &V {
        let i = self.fill(r, leaf);
        // SAFETY: `fill` just set the slot's key to this leaf, with its value.
        unsafe { self.volumes[i].assume_init_ref() }
    }

    /// The volumes of nodes `rs`, by reference (no copy): an inner node's as `inner` gives it, a
    /// leaf's from the table (computed by `leaf` when not there).
    #[inline(always)]
    pub fn get_two<'x>(
        &'x mut self,
        rs: [NodeRef; 2],
        inner: impl Fn(NodeRef) -> &'x V,
        leaf: impl Fn(NodeRef) -> V + Copy,
    ) -> [&'x V; 2] {
        let [r0, r1] = rs;
        let i0 = if r0.is_leaf() { self.fill(r0, leaf) } else { 0 };
        let i1 = if r1.is_leaf() { self.fill(r1, leaf) } else { 0 };
        // Two leaves of one slot (never two siblings: their triangles are consecutive): the
        // second evicted the first, which goes to the spare.
        let first_spare = r0.is_leaf() && r1.is_leaf() && r0 != r1 && i0 == i1;
        if first_spare {
            self.spare = MaybeUninit::new(leaf(r0));
        }
        let this: &'x Self = self;
        let at = |r: NodeRef, i: usize| {
            // Checked (a cheap, predictable branch) rather than trusted: a wrong slot must not
            // read an uninitialised one.
            assert_eq!(this.keys[i], r);
            // SAFETY: a slot whose key is a leaf holds that leaf's volume (set together in
            // `fill`).
            unsafe { this.volumes[i].assume_init_ref() }
        };
        [
            if !r0.is_leaf() {
                inner(r0)
            } else if first_spare {
                // SAFETY: set just above.
                unsafe { this.spare.assume_init_ref() }
            } else {
                at(r0, i0)
            },
            if !r1.is_leaf() { inner(r1) } else { at(r1, i1) },
        ]
    }

    /// Node `r`'s volume, as `volume(r)` gives it; a leaf's from the table when it is there.
    #[inline(always)]
    pub fn get(&mut self, r: NodeRef, volume: impl Fn(NodeRef) -> V) -> V {
        if !r.is_leaf() {
            return volume(r);
        }
        let i = r.triangle() % LEAF_SLOTS;
        if self.keys[i] == r {
            // SAFETY: a slot's key is set to a leaf only together with its volume.
            unsafe { self.volumes[i].assume_init() }
        } else {
            let v = volume(r);
            self.volumes[i] = MaybeUninit::new(v);
            self.keys[i] = r;
            v
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// Whatever the slots, each node gets its own volume, and a leaf's is computed only when its
    /// slot holds another: two leaves of one slot asked for together, repeated lookups, inner
    /// nodes.
    #[test]
    fn leaf_cache_gives_each_node_its_volume() {
        let inner_volumes: Vec<i64> = (0..200).map(|i| 1000 + i).collect();
        let computed = Cell::new(0);
        let leaf = |r: NodeRef| {
            computed.set(computed.get() + 1);
            -(r.raw() as i64)
        };
        let mut cache = LeafCache::<i64>::default();
        let expect = |r: NodeRef| {
            if r.is_leaf() {
                -(r.raw() as i64)
            } else {
                1000 + r.raw() as i64
            }
        };
        let pairs: [[i32; 2]; 7] = [
            [-1, -2],
            [-1, -2],
            [-1, -1 - LEAF_SLOTS as i32],
            [-1 - LEAF_SLOTS as i32, -1],
            [5, -3],
            [-3, 7],
            [-3, -3],
        ];
        let mut expected_computed = 0;
        for (k, rs) in pairs.into_iter().enumerate() {
            let before = computed.get();
            let rs = rs.map(NodeRef::from_raw);
            let got = cache.get_two(rs, |r| &inner_volumes[r.raw() as usize], leaf);
            assert_eq!([*got[0], *got[1]], rs.map(expect), "pair {k}");
            expected_computed += [2, 0, 2, 2, 1, 0, 0][k];
            assert_eq!(computed.get(), expected_computed, "pair {k} from {before}");
        }
        let (leaf2, inner9) = (NodeRef::from_raw(-2), NodeRef::from_raw(9));
        assert_eq!(
            *cache.get_ref(leaf2, |r| &inner_volumes[r.raw() as usize], leaf),
            2
        );
        assert_eq!(cache.get(leaf2, leaf), 2);
        assert_eq!(
            *cache.get_ref(inner9, |r| &inner_volumes[r.raw() as usize], leaf),
            1009
        );
    }
}
