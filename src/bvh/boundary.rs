//! Each inner node's boundary: the directed edges of its triangles that no opposite edge of the
//! same node cancels. The winding-number query evaluates a node whose volume lies away from the
//! point as a fan over these edges (any surface with the node's boundary inside a convex region
//! around it subtends the same solid angle from a point outside that region), so it costs as many
//! solid angles as the node has boundary edges, not triangles.
//!
//! Built on first use (see [`Bvh::boundaries`]): a model that never asks for a winding number pays
//! nothing for it.

use super::far_field::FarField;
use super::{Bvh, NodeKind, NodeRef};
use crate::error::Error;
use std::ops::Range;

/// What a winding-number query sums for one inner node seen from afar.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum NodeSurface<'a> {
    /// The node's boundary edges, as pairs of vertex indices ([`Bvh::vertex`]), with multiplicity
    /// (an edge left twice is listed twice). Empty for a closed node, which subtends no solid
    /// angle from outside its volume.
    Fan(&'a [[u32; 2]]),
    /// Its triangles, by slot in leaf order ([`Bvh::tri`]): for nodes with at least as many
    /// boundary edges as triangles, for which the fan would be no cheaper and is not stored.
    Triangles(Range<usize>),
}

/// The flag of a [`Span`] length that marks a triangle range rather than edges.
const TRIANGLES: u32 = 1 << 31;

/// One inner node's entry: `len` edges from `start`, or (with [`TRIANGLES`] in `len`) the
/// triangles of slots `start..start + (len & !TRIANGLES)`; and its boundary's loops: their count
/// in the low [`LOOP_COUNT_BITS`] of `loops`, the index of the first above (none if it has no far
/// fields).
#[derive(Clone, Copy, Debug, Default)]
struct Span {
    start: u32,
    len: u32,
    loops: u32,
}

/// Bits of [`Span::loops`] that count a node's loops: a node with more, or whose first loop's
/// index does not fit in the rest, keeps none (and is summed exactly).
const LOOP_COUNT_BITS: u32 = 6;

/// Nodes of at least this many triangles get far fields: below, a node's fan has a few edges and
/// costs little more than the far fields' terms, which would only add memory.
const FAR_FIELD_TRIANGLES: usize = 32;

/// One closed loop of a node's boundary: its edges `start..start + len` (of [`Boundaries`]'
/// edges, in the node's run) and the far field of the fan over them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BoundaryLoop {
    pub far: FarField,
    start: u32,
    len: u32,
}

/// The boundaries of every inner node of a hierarchy.
#[derive(Clone, Debug, Default)]
pub(crate) struct Boundaries {
    /// Per inner node, by index.
    spans: Vec<Span>,
    /// The stored nodes' edges, one run per node.
    edges: Vec<[u32; 2]>,
    /// The loops of the boundaries of the nodes of at least [`FAR_FIELD_TRIANGLES`] triangles,
    /// one run per node.
    loops: Vec<BoundaryLoop>,
}

/// An undirected edge as a sorting key (smaller index in the high half) with its multiplicity
/// in the direction from the smaller to the larger index (negative: the other way).
type Chain = Vec<(u64, i32)>;

impl Boundaries {
    /// What inner node `r` (not a leaf) sums.
    #[inline]
    pub fn node(&self, r: NodeRef) -> NodeSurface<'_> {
        let s = self.spans[r.index()];
        let (start, len) = (s.start as usize, (s.len & !TRIANGLES) as usize);
        if s.len & TRIANGLES != 0 {
            NodeSurface::Triangles(start..start + len)
        } else {
            NodeSurface::Fan(&self.edges[start..start + len])
        }
    }

    /// Inner node `r`'s boundary as closed loops with their far fields: empty if it has none
    /// (a node of few triangles, or closed), else their edges make up its [`NodeSurface::Fan`].
    #[inline]
    pub fn loops(&self, r: NodeRef) -> &[BoundaryLoop] {
        let s = self.spans[r.index()];
        let (first, count) = (
            s.loops >> LOOP_COUNT_BITS,
            s.loops & ((1 << LOOP_COUNT_BITS) - 1),
        );
        &self.loops[first as usize..(first + count) as usize]
    }

    /// The edges of loop `l`.
    #[inline]
    pub fn loop_edges(&self, l: &BoundaryLoop) -> &[[u32; 2]] {
        &self.edges[l.start as usize..(l.start + l.len) as usize]
    }

    /// Bytes held.
    pub fn memory_usage(&self) -> usize {
        self.spans.capacity() * std::mem::size_of::<Span>()
            + self.edges.capacity() * std::mem::size_of::<[u32; 2]>()
            + self.loops.capacity() * std::mem::size_of::<BoundaryLoop>()
            + std::mem::size_of::<Boundaries>()
    }

    /// Computes every inner node's boundary bottom-up, merging its children's (sorted by edge,
    /// so a merge is linear), or `Err(OutOfMemory)`.
    pub fn build(bvh: &Bvh) -> Result<Boundaries, Error> {
        let oom = |_| Error::OutOfMemory;
        let mut b = Boundaries::default();
        let inner = bvh.nodes.len();
        b.spans.try_reserve_exact(inner).map_err(oom)?;
        b.spans.resize(inner, Span::default());
        if inner > 0 {
            b.collect(bvh, bvh.root())?;
        }
        b.edges.shrink_to_fit();
        b.loops.shrink_to_fit();
        Ok(b)
    }

    /// The chain of node `r`'s boundary and the range of its triangles' slots; records inner
    /// nodes' entries on the way.
    fn collect(&mut self, bvh: &Bvh, r: NodeRef) -> Result<(Chain, Range<usize>), Error> {
        let oom = |_| Error::OutOfMemory;
        let i = match r.kind() {
            NodeKind::Leaf(t) => return Ok((triangle_chain(bvh.faces[t])?, t..t + 1)),
            NodeKind::Inner(i) => i,
        };
        let [c0, c1] = bvh.children(r);
        let (a, ra) = self.collect(bvh, c0)?;
        let (b, rb) = self.collect(bvh, c1)?;
        let chain = merge(&a, &b)?;
        drop((a, b));
        // The build keeps a subtree's triangles contiguous; a range is only used if so.
        let tris = ra.start.min(rb.start)..ra.end.max(rb.end);
        let contiguous = tris.len() == ra.len() + rb.len();
        let edges: usize = chain.iter().map(|&(_, m)| m.unsigned_abs() as usize).sum();
        self.spans[i] = if edges >= tris.len() && contiguous {
            Span {
                start: tris.start as u32,
                len: tris.len() as u32 | TRIANGLES,
                ..Span::default()
            }
        } else {
            if self.edges.len() + edges >= TRIANGLES as usize {
                return Err(Error::OutOfMemory);
            }
            self.edges.try_reserve(edges).map_err(oom)?;
            let start = self.edges.len() as u32;
            for &(key, m) in &chain {
                let (lo, hi) = ((key >> 32) as u32, key as u32);
                let e = if m > 0 { [lo, hi] } else { [hi, lo] };
                for _ in 0..m.unsigned_abs() {
                    self.edges.push(e);
                }
            }
            let first = self.loops.len();
            if tris.len() >= FAR_FIELD_TRIANGLES && edges > 0 {
                self.add_loops(bvh, start as usize, edges)?;
            }
            let count = self.loops.len() - first;
            let loops = if count < 1 << LOOP_COUNT_BITS && first < 1 << (32 - LOOP_COUNT_BITS) {
                ((first as u32) << LOOP_COUNT_BITS) | count as u32
            } else {
                self.loops.truncate(first);
                0
            };
            Span {
                start,
                len: edges as u32,
                loops,
            }
        };
        Ok((chain, tris))
    }

    /// Orders the `n` edges from `start` (a node's boundary, a sum of cycles) loop by loop, and
    /// records each loop with its far field. Records nothing if some walk does not close (never
    /// expected: every vertex of a boundary is entered as often as it is left).
    fn add_loops(&mut self, bvh: &Bvh, start: usize, n: usize) -> Result<(), Error> {
        let oom = |_| Error::OutOfMemory;
        // The edges by first vertex, each with a flag once walked.
        let mut by_from: Vec<([u32; 2], bool)> = Vec::new();
        by_from.try_reserve_exact(n).map_err(oom)?;
        by_from.extend(self.edges[start..start + n].iter().map(|&e| (e, false)));
        by_from.sort_unstable_by_key(|&(e, _)| e);
        let mut ordered: Vec<[u32; 2]> = Vec::new();
        ordered.try_reserve_exact(n).map_err(oom)?;
        let mut cuts = Vec::new();
        for first in 0..n {
            if by_from[first].1 {
                continue;
            }
            by_from[first].1 = true;
            let begin = ordered.len();
            let origin = by_from[first].0[0];
            let mut e = by_from[first].0;
            ordered.push(e);
            while e[1] != origin {
                let from = by_from.partition_point(|&(f, _)| f[0] < e[1]);
                let Some(k) = (from..n)
                    .take_while(|&k| by_from[k].0[0] == e[1])
                    .find(|&k| !by_from[k].1)
                else {
                    return Ok(());
                };
                by_from[k].1 = true;
                e = by_from[k].0;
                ordered.push(e);
            }
            cuts.try_reserve(1).map_err(oom)?;
            cuts.push(begin..ordered.len());
        }
        self.edges[start..start + n].copy_from_slice(&ordered);
        self.loops.try_reserve(cuts.len()).map_err(oom)?;
        for c in cuts {
            let edges = &self.edges[start + c.start..start + c.end];
            let far = FarField::of_fan(edges.iter().map(|e| (bvh.vertex(e[0]), bvh.vertex(e[1]))));
            self.loops.push(BoundaryLoop {
                far,
                start: (start + c.start) as u32,
                len: c.len() as u32,
            });
        }
        Ok(())
    }
}

/// A triangle's three directed edges as a sorted chain (edges between equal indices, which bound
/// nothing, left out; opposite ones cancelled).
fn triangle_chain(f: [u32; 3]) -> Result<Chain, Error> {
    let mut c: Chain = Vec::new();
    c.try_reserve_exact(3).map_err(|_| Error::OutOfMemory)?;
    for k in 0..3 {
        let (a, b) = (f[k], f[(k + 1) % 3]);
        if a != b {
            let (lo, hi, m) = if a < b { (a, b, 1) } else { (b, a, -1) };
            c.push(((u64::from(lo) << 32) | u64::from(hi), m));
        }
    }
    c.sort_unstable_by_key(|&(k, _)| k);
    merge(&c, &[])
}

/// The sum of two sorted chains (and runs of one key within either), without zero multiplicities.
fn merge(a: &[(u64, i32)], b: &[(u64, i32)]) -> Result<Chain, Error> {
    let mut out: Chain = Vec::new();
    out.try_reserve_exact(a.len() + b.len())
        .map_err(|_| Error::OutOfMemory)?;
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        let take_a = j == b.len() || (i < a.len() && a[i].0 <= b[j].0);
        let e = if take_a {
            i += 1;
            a[i - 1]
        } else {
            j += 1;
            b[j - 1]
        };
        match out.last_mut() {
            Some(last) if last.0 == e.0 => last.1 += e.1,
            _ => out.push(e),
        }
        if out.last().is_some_and(|l| l.1 == 0) {
            out.pop();
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::{CollisionVolume, VolumeKind};
    use crate::math::Vec3;

    /// The sum of every stored node's fan edges is a cycle (each vertex entered as often as
    /// left), and on a closed octahedron the root is closed.
    #[test]
    fn boundaries_are_cycles_and_a_closed_mesh_has_none() {
        let v = [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, -1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.0, 0.0, -1.0),
        ];
        let faces = [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        let tris = faces
            .iter()
            .enumerate()
            .map(|(i, f)| ([v[f[0]], v[f[1]], v[f[2]]], i as i32))
            .collect();
        let bvh = Bvh::build(tris, VolumeKind::Rss, CollisionVolume::Obb).unwrap();
        let b = Boundaries::build(&bvh).unwrap();
        assert_eq!(b.node(bvh.root()), NodeSurface::Fan(&[]));
        for i in 0..bvh.num_inner() {
            if let NodeSurface::Fan(edges) = b.node(NodeRef::inner(i)) {
                let mut degree = [0i32; 6];
                for e in edges {
                    degree[e[0] as usize] += 1;
                    degree[e[1] as usize] -= 1;
                }
                assert_eq!(degree, [0; 6], "node {i}");
            }
        }
    }

    #[test]
    fn merge_cancels_opposite_edges_and_keeps_multiplicity() {
        let a = [(1u64, 1), (5, -1), (7, 2)];
        let b = [(1u64, -1), (5, -1), (9, 1)];
        assert_eq!(merge(&a, &b).unwrap(), vec![(5, -2), (7, 2), (9, 1)]);
        assert_eq!(triangle_chain([3, 3, 4]).unwrap(), vec![]);
    }
}
