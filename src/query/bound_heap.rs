//! A binary min-heap of nodes keyed by a distance bound, for the closest-point search: the node
//! of least bound first and, of equal bounds, the last pushed (the order of the radix queue of
//! `queue.rs`, which a point query outgrew: its queue stays short, a few dozen entries, and
//! moving entries between the radix buckets cost more than sifting a short heap).

use crate::bvh::NodeRef;

#[derive(Clone, Copy)]
struct Entry {
    bound: f64,
    /// Push count: of equal bounds, the larger (later) comes out first.
    seq: u32,
    node: NodeRef,
}

impl Entry {
    /// Whether `self` comes out before `other`.
    #[inline(always)]
    fn before(&self, other: &Entry) -> bool {
        self.bound < other.bound || (self.bound == other.bound && self.seq > other.seq)
    }
}

/// The heap; cleared and reused from query to query so that its storage is allocated once.
#[derive(Default)]
pub(crate) struct BoundHeap {
    entries: Vec<Entry>,
    seq: u32,
}

impl BoundHeap {
    /// Empties the heap (keeping its storage).
    #[inline]
    pub fn clear(&mut self) {
        self.entries.clear();
        self.seq = 0;
    }

    /// Queues `node` with `bound` (not NaN).
    #[inline]
    pub fn push(&mut self, node: NodeRef, bound: f64) {
        let e = Entry {
            bound,
            seq: self.seq,
            node,
        };
        self.seq = self.seq.wrapping_add(1);
        let mut i = self.entries.len();
        self.entries.push(e);
        while i > 0 {
            let parent = (i - 1) / 2;
            if !e.before(&self.entries[parent]) {
                break;
            }
            self.entries[i] = self.entries[parent];
            i = parent;
        }
        self.entries[i] = e;
    }

    /// The bound of the first node, if any.
    #[inline(always)]
    pub fn peek_bound(&self) -> Option<f64> {
        self.entries.first().map(|e| e.bound)
    }

    /// The first node and its bound, if any.
    #[inline]
    pub fn pop(&mut self) -> Option<(NodeRef, f64)> {
        let last = self.entries.pop()?;
        let n = self.entries.len();
        if n == 0 {
            return Some((last.node, last.bound));
        }
        let top = self.entries[0];
        // Sift the last entry down from the root.
        let mut i = 0;
        loop {
            let l = 2 * i + 1;
            if l >= n {
                break;
            }
            let r = l + 1;
            let c = if r < n && self.entries[r].before(&self.entries[l]) {
                r
            } else {
                l
            };
            if !self.entries[c].before(&last) {
                break;
            }
            self.entries[i] = self.entries[c];
            i = c;
        }
        self.entries[i] = last;
        Some((top.node, top.bound))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Lcg;

    /// Pops in the order of a sort by bound, the later pushed first among equal bounds, with
    /// pushes and pops interleaved.
    #[test]
    fn pops_least_bound_last_pushed_first() {
        let mut rng = Lcg(3);
        let mut h = BoundHeap::default();
        for _ in 0..100 {
            h.clear();
            // (bound, push number) of what is queued.
            let mut reference: Vec<(f64, u32)> = Vec::new();
            let mut pushed = 0u32;
            for _ in 0..300 {
                if !rng.bits().is_multiple_of(3) || reference.is_empty() {
                    // Few distinct bounds, so that ties are common.
                    let bound = (rng.bits() % 8) as f64 * 0.5;
                    h.push(NodeRef::inner(pushed as usize), bound);
                    reference.push((bound, pushed));
                    pushed += 1;
                } else {
                    let best = (0..reference.len())
                        .min_by(|&i, &j| {
                            let (a, b) = (reference[i], reference[j]);
                            a.0.total_cmp(&b.0).then(b.1.cmp(&a.1))
                        })
                        .unwrap();
                    let (bound, n) = reference.swap_remove(best);
                    assert_eq!(h.pop(), Some((NodeRef::inner(n as usize), bound)));
                }
            }
        }
    }
}
