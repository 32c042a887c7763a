//! The priority queue of the priority-directed search: BVTT nodes by bound, the smallest first,
//! and among equal bounds the one pushed last first (depth-first among ties).
//!
//! The search only ever pushes a node whose bound is at least that of the last node it popped (a
//! child's bound is raised to its parent's, which bounds the child's triangles too), so the queue
//! can be a radix heap (Ahuja, Mehlhorn, Orlin and Tarjan): the keys are the bounds' bit patterns,
//! which order as the bounds do for non-negative doubles, and a node waits in the bucket of the
//! highest bit in which its key differs from the last key popped. A push is one append; a pop takes
//! from bucket 0 (keys equal to the last) or, when that is empty, spreads the lowest non-empty
//! bucket over the lower ones, which each node undergoes at most 63 times. It replaced a binary
//! heap, whose sifting comparisons were unpredictable branches.

use super::traversal::NodePair;
use crate::bvh::NodeRef;

/// A queued BVTT node.
#[derive(Clone, Copy)]
struct Entry {
    key: u64,
    a: NodeRef,
    b: NodeRef,
}

impl Entry {
    #[inline(always)]
    fn pair(self) -> NodePair {
        NodePair {
            a: self.a,
            b: self.b,
            bound: f64::from_bits(self.key),
        }
    }
}

/// Buckets: 0 for keys equal to the last popped, `i` for keys whose highest bit differing from it
/// is bit `i - 1`. The keys of non-negative doubles never set bit 63, so 64 buckets do.
const BUCKETS: usize = 64;

/// See the module documentation. Reused from query to query (its buckets keep their capacity).
pub(crate) struct RadixQueue {
    /// The last key popped (0 when none was): no key in the queue is below it.
    last: u64,
    buckets: [Vec<Entry>; BUCKETS],
    /// Bit `i` set when bucket `i` is not empty.
    occupied: u64,
    len: usize,
}

impl Default for RadixQueue {
    fn default() -> Self {
        RadixQueue {
            last: 0,
            buckets: std::array::from_fn(|_| Vec::new()),
            occupied: 0,
            len: 0,
        }
    }
}

impl RadixQueue {
    /// Empties the queue (keeping the buckets' storage) and resets the last key to 0.
    pub fn clear(&mut self) {
        let mut occupied = self.occupied;
        while occupied != 0 {
            self.buckets[occupied.trailing_zeros() as usize].clear();
            occupied &= occupied - 1;
        }
        self.occupied = 0;
        self.len = 0;
        self.last = 0;
    }

    pub fn len(&self) -> usize {
        self.len
    }

    #[inline(always)]
    fn bucket(&self, key: u64) -> usize {
        (u64::BITS - (key ^ self.last).leading_zeros()) as usize
    }

    /// Queues `p`, whose bound (not negative nor NaN) must be at least the last popped one's.
    #[inline]
    pub fn push(&mut self, p: NodePair) {
        debug_assert!(p.bound >= 0.0);
        // +0.0 makes -0 positive zero; the max keeps the queue's invariant whatever the caller
        // (a bound below the last popped would be a caller's bug: it is only delayed to there),
        // and the mask keeps a negative or NaN bound (another bug) in the buckets.
        let key = ((p.bound + 0.0).to_bits() & (u64::MAX >> 1)).max(self.last);
        debug_assert_eq!(
            key,
            (p.bound + 0.0).to_bits(),
            "pushed below the last popped"
        );
        let i = self.bucket(key);
        self.buckets[i].push(Entry {
            key,
            a: p.a,
            b: p.b,
        });
        self.occupied |= 1 << i;
        self.len += 1;
    }

    /// The node of least bound, the last pushed among equal bounds.
    #[inline]
    pub fn pop(&mut self) -> Option<NodePair> {
        if self.occupied & 1 == 0 {
            if self.occupied == 0 {
                return None;
            }
            // Spread the lowest non-empty bucket over the lower ones, in order, so that among
            // equal keys the later pushed stay later (and come out first).
            let i = self.occupied.trailing_zeros() as usize;
            let moving = std::mem::take(&mut self.buckets[i]);
            self.occupied &= !(1 << i);
            self.last = moving.iter().map(|e| e.key).min().unwrap_or(self.last);
            for &e in &moving {
                let j = self.bucket(e.key);
                self.buckets[j].push(e);
                self.occupied |= 1 << j;
            }
            // Give the storage back to the bucket, so that no query allocates once warm.
            let mut moving = moving;
            moving.clear();
            self.buckets[i] = moving;
        }
        let e = self.buckets[0].pop()?;
        if self.buckets[0].is_empty() {
            self.occupied &= !1;
        }
        self.len -= 1;
        Some(e.pair())
    }

    /// Takes every queued node out, in no particular order, and gives it to `f`.
    pub fn drain(&mut self, mut f: impl FnMut(NodePair)) {
        let mut occupied = std::mem::take(&mut self.occupied);
        while occupied != 0 {
            for e in self.buckets[occupied.trailing_zeros() as usize].drain(..) {
                f(e.pair());
            }
            occupied &= occupied - 1;
        }
        self.len = 0;
    }

    /// The last key popped, as a bound: every queued node's is at least this.
    #[inline(always)]
    pub fn floor(&self) -> f64 {
        f64::from_bits(self.last)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Lcg;
    use std::collections::BinaryHeap;

    /// Pops in the order (bound ascending, latest pushed first among equal bounds), which a binary
    /// heap keyed by (bound, push number) gives, under the search's pattern: pops interleaved with
    /// pushes of bounds at least the last popped, with many ties (0 and repeated values) and
    /// bounds of every magnitude.
    #[test]
    fn pops_as_an_ordered_heap() {
        let mut rng = Lcg(11);
        let mut next = move || rng.bits();
        let mut q = RadixQueue::default();
        for round in 0..50 {
            q.clear();
            // (bound bits reversed for a min-heap, push number; node ids carry the push number).
            let mut reference = BinaryHeap::new();
            let mut last = 0.0f64;
            let mut pushed = 0i32;
            let (mut pops, mut ties) = (0, 0);
            for _ in 0..2000 {
                if next() % 3 != 0 || reference.is_empty() {
                    let bound = match next() % 5 {
                        0 => last,
                        1 => last + 1e-300,
                        2 => last * (1.0 + (next() % 1000) as f64 * 1e-3),
                        3 => last + (next() % 7) as f64,
                        _ => last + f64::from_bits(next() % (1u64 << 62)).min(1e300),
                    };
                    q.push(NodePair {
                        a: NodeRef::from_raw(pushed),
                        b: NodeRef::from_raw(-pushed),
                        bound,
                    });
                    reference.push((std::cmp::Reverse(bound.to_bits()), pushed));
                    pushed += 1;
                } else {
                    let (std::cmp::Reverse(key), id) = reference.pop().unwrap();
                    let p = q.pop().unwrap();
                    assert_eq!(
                        (p.bound.to_bits(), p.a.raw(), p.b.raw()),
                        (key, id, -id),
                        "round {round}"
                    );
                    ties += usize::from(p.bound == last);
                    last = p.bound;
                    pops += 1;
                }
                assert_eq!(q.len(), reference.len());
            }
            while let Some((std::cmp::Reverse(key), id)) = reference.pop() {
                let p = q.pop().unwrap();
                assert_eq!((p.bound.to_bits(), p.a.raw()), (key, id));
            }
            assert!(q.pop().is_none() && q.len() == 0);
            assert!(pops > 300 && ties > 50, "{pops} {ties}");
        }
    }

    /// Draining gives back every queued node once and leaves the queue empty and reusable.
    #[test]
    fn drain_returns_everything() {
        let mut q = RadixQueue::default();
        for i in 0..100 {
            q.push(NodePair {
                a: NodeRef::from_raw(i),
                b: NodeRef::from_raw(0),
                bound: f64::from(i % 7) * 0.5,
            });
        }
        assert_eq!(q.pop().map(|p| p.bound), Some(0.0));
        let mut got = vec![];
        q.drain(|p| got.push(p.a.raw()));
        got.sort_unstable();
        assert_eq!(got.len(), 99);
        assert!(got.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(q.len(), 0);
        assert!(q.pop().is_none());
        q.clear();
        q.push(NodePair {
            a: NodeRef::from_raw(5),
            b: NodeRef::from_raw(6),
            bound: 0.25,
        });
        assert_eq!(q.pop().map(|p| (p.a.raw(), p.b.raw())), Some((5, 6)));
    }
}
