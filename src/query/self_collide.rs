//! Self-collision: which pairs of distinct triangles of one model intersect, neighbours that meet
//! only in what they share excepted.
//!
//! The hierarchy is searched against itself: a node against itself is its two children against
//! themselves and against each other, so each pair of triangles is met once, at the node where
//! their paths part, and pairs in volumes that do not overlap are never looked at. The volumes
//! are axis-aligned boxes of the nodes, computed for the query (`Aabb`): one model needs no
//! relative pose, and their test is a few comparisons; the model's own volumes (oriented boxes
//! or swept sphere volumes, for queries between posed models) are not used. Neighbours in a mesh always have overlapping volumes, so every pair sharing a
//! vertex or an edge reaches the triangle test: [`self_contact`] settles most of them with one
//! filtered orientation test.

use super::Stats;
use super::collide::{CollideResult, ContactMode, ContactPair};
use crate::bvh::{Bvh, MAX_DEPTH, NodeKind, NodeRef};
use crate::error::Error;
use crate::geometry::predicates::{P2, PlaneFilter, orient2d, orient3d, orient3d_exact};
use crate::geometry::{Tri, tri_overlap};
use crate::math::Vec3;
use crate::model::Model;
use std::time::Instant;

/// Finds every pair of distinct triangles of `m` that intersect (share a point), each pair once,
/// `id1` being the id of the triangle added first; except that two triangles sharing a vertex or
/// an edge (coordinates exactly equal) are not reported when they meet only in what they share.
/// Identical triangles (the same three vertices) are reported. See [`self_contact`] for the exact
/// rule.
///
/// ```
/// use pqp::{ContactMode, Model, self_collide};
/// // Two triangles sharing an edge (not reported) and a third crossing the first.
/// let m = Model::from_triangles([
///     ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 10),
///     ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.5], 11),
///     ([0.2, 0.2, -1.0], [0.3, 0.2, 1.0], [0.2, 0.3, 1.0], 12),
/// ]).unwrap();
/// let r = self_collide(&m, ContactMode::All).unwrap();
/// assert_eq!(r.num_pairs(), 1);
/// assert_eq!((r.pairs()[0].id1, r.pairs()[0].id2), (10, 12));
/// ```
pub fn self_collide(m: &Model, mode: ContactMode) -> Result<CollideResult, Error> {
    let mut r = CollideResult::new();
    self_collide_into(&mut r, m, mode)?;
    Ok(r)
}

/// As [`self_collide`], reusing `result`'s storage. On error `result` is left as it was.
pub fn self_collide_into(
    result: &mut CollideResult,
    m: &Model,
    mode: ContactMode,
) -> Result<(), Error> {
    let start = Instant::now();
    let mut stats = search(m.bvh()?, result.pairs_mut(), mode)?;
    stats.query_time_secs = start.elapsed().as_secs_f64();
    result.stats = stats;
    Ok(())
}

/// The search of [`self_collide_into`]: fills `pairs` (cleared first, unless the boxes cannot
/// be allocated: `OutOfMemory`, `pairs` untouched).
fn search(b: &Bvh, pairs: &mut Vec<ContactPair>, mode: ContactMode) -> Result<Stats, Error> {
    let (boxes, kids) = search_tree(b)?;
    pairs.clear();
    let mut s = Search {
        b,
        boxes: &boxes,
        n_inner: kids.len(),
        by_index: b.distinct_vertices(),
        first: mode == ContactMode::First,
        pairs,
        stats: Stats::default(),
        stack: [(0, 0); STACK],
        len: 0,
    };
    if s.n_inner == 0 {
        // One triangle.
        return Ok(s.stats);
    }
    s.push(0, 0);
    while s.len > 0 {
        s.len -= 1;
        let (p, q) = s.stack[s.len];
        let stop = if p == q {
            // An inner node against itself: its children against each other and themselves (if
            // inner).
            let [c0, c1] = kids[p as usize];
            let stop = s.meet(c0, c1);
            for c in [c1, c0] {
                if !s.is_leaf(c) {
                    s.push(c, c);
                }
            }
            stop
        } else if !s.is_leaf(p) && !s.is_leaf(q) {
            // Both inner: descend both at once (the four pairs of children).
            let ([p0, p1], [q0, q1]) = (kids[p as usize], kids[q as usize]);
            s.meet(p1, q1) || s.meet(p1, q0) || s.meet(p0, q1) || s.meet(p0, q0)
        } else if s.is_leaf(q) {
            let [c0, c1] = kids[p as usize];
            s.meet(c1, q) || s.meet(c0, q)
        } else {
            let [c0, c1] = kids[q as usize];
            s.meet(p, c1) || s.meet(p, c0)
        };
        if stop {
            break;
        }
    }
    Ok(s.stats)
}

/// Each step of the search pops one pair and pushes at most four, and a pair is at most
/// 2 `MAX_DEPTH` steps below the root (each step descends at least one of its nodes).
const STACK: usize = 8 * MAX_DEPTH + 4;

/// The state of [`search`]. Nodes are designated by their slot in the arrays of
/// [`search_tree`] (inner nodes first, then leaves). A pair of children is tested when met and
/// pushed only if it overlaps and is not two leaves, whose triangles are tested at once: the
/// stack holds only pairs to descend.
struct Search<'a> {
    b: &'a Bvh,
    boxes: &'a [Aabb],
    n_inner: usize,
    by_index: bool,
    first: bool,
    pairs: &'a mut Vec<ContactPair>,
    stats: Stats,
    stack: [(u32, u32); STACK],
    len: usize,
}

impl Search<'_> {
    #[inline(always)]
    fn is_leaf(&self, x: u32) -> bool {
        x as usize >= self.n_inner
    }

    #[inline(always)]
    fn push(&mut self, x: u32, y: u32) {
        // Checked: a panic (caught at the C boundary) if the bound above were wrong.
        self.stack[self.len] = (x, y);
        self.len += 1;
    }

    /// Meets the pair (x, y) of distinct nodes: two leaves' triangles are tested, other pairs
    /// pushed if their boxes overlap. Whether the search is to stop (a first contact found).
    #[inline(always)]
    fn meet(&mut self, x: u32, y: u32) -> bool {
        self.stats.bv_tests += 1;
        if !self.boxes[x as usize].overlaps(&self.boxes[y as usize]) {
            // Apart (so sharing no vertex either).
            return false;
        }
        if !(self.is_leaf(x) && self.is_leaf(y)) {
            self.push(x, y);
            return false;
        }
        let b = self.b;
        let (s, t) = (x as usize - self.n_inner, y as usize - self.n_inner);
        self.stats.tri_tests += 1;
        if !leaf_contact(b, s, t, self.by_index) {
            return false;
        }
        let (first, second) = if b.added[s] < b.added[t] {
            (s, t)
        } else {
            (t, s)
        };
        self.pairs.push(ContactPair {
            id1: b.ids[first],
            id2: b.ids[second],
        });
        self.first
    }
}

/// An axis-aligned box in single precision, rounded outward: it holds the box of doubles it was
/// made from, so boxes apart are apart exactly. Against itself a model needs no relative pose,
/// and in a mesh most pairs the search meets are neighbours whose volumes overlap: a box test
/// (six comparisons) costs much less than the oriented boxes' separating axis test, and
/// single precision halves the memory the search walks through.
#[derive(Clone, Copy, Debug)]
struct Aabb {
    lo: [f32; 3],
    hi: [f32; 3],
}

/// The largest float not above `x`.
fn f32_down(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) > x { y.next_down() } else { y }
}

/// The smallest float not below `x`.
fn f32_up(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) < x { y.next_up() } else { y }
}

impl Aabb {
    fn of_tri(t: &Tri) -> Aabb {
        let (mut lo, mut hi) = ([0.0; 3], [0.0; 3]);
        for k in 0..3 {
            lo[k] = f32_down(t[0][k].min(t[1][k]).min(t[2][k]));
            hi[k] = f32_up(t[0][k].max(t[1][k]).max(t[2][k]));
        }
        Aabb { lo, hi }
    }

    fn union(&self, o: &Aabb) -> Aabb {
        Aabb {
            lo: std::array::from_fn(|k| self.lo[k].min(o.lo[k])),
            hi: std::array::from_fn(|k| self.hi[k].max(o.hi[k])),
        }
    }

    /// Whether they share a point (touching counts).
    #[inline(always)]
    fn overlaps(&self, o: &Aabb) -> bool {
        (self.lo[0] <= o.hi[0] && o.lo[0] <= self.hi[0])
            && (self.lo[1] <= o.hi[1] && o.lo[1] <= self.hi[1])
            && (self.lo[2] <= o.hi[2] && o.lo[2] <= self.hi[2])
    }
}

/// The boxes of every node (the inner nodes' by index, then the leaves' in leaf order: a node's
/// slot) and the inner nodes' children's slots: the search reads only these two arrays, a few
/// bytes per node, not the model's nodes. `OutOfMemory` if they cannot be allocated.
fn search_tree(b: &Bvh) -> Result<(Vec<Aabb>, Vec<[u32; 2]>), Error> {
    let n = b.num_tris();
    let n_inner = n - 1;
    let (mut boxes, mut kids) = (Vec::new(), Vec::new());
    boxes
        .try_reserve_exact(n_inner + n)
        .map_err(|_| Error::OutOfMemory)?;
    kids.try_reserve_exact(n_inner)
        .map_err(|_| Error::OutOfMemory)?;
    let empty = Aabb {
        lo: [f32::INFINITY; 3],
        hi: [f32::NEG_INFINITY; 3],
    };
    boxes.resize(n_inner, empty);
    boxes.extend((0..n).map(|t| Aabb::of_tri(&b.tri(t))));
    let slot = |r: NodeRef| match r.kind() {
        NodeKind::Inner(i) => i as u32,
        NodeKind::Leaf(t) => (n_inner + t) as u32,
    };
    kids.extend((0..n_inner).map(|i| b.children(NodeRef::inner(i)).map(slot)));
    if n_inner == 0 {
        return Ok((boxes, kids));
    }
    // Inner nodes after their children: a depth-first walk that visits each node twice (a
    // build numbers children after their parent, but a loaded model's tree is only checked to
    // be a tree).
    let mut stack = vec![(0u32, false)];
    while let Some((r, children_done)) = stack.pop() {
        let [c0, c1] = kids[r as usize];
        if children_done {
            boxes[r as usize] = boxes[c0 as usize].union(&boxes[c1 as usize]);
            continue;
        }
        stack.push((r, true));
        for c in [c0, c1] {
            if (c as usize) < n_inner {
                stack.push((c, false));
            }
        }
    }
    Ok((boxes, kids))
}

/// Whether two triangles of one model count as self-intersecting: they share a point, and unless
/// they have the same vertices, a point beyond the vertices they share (coordinates exactly
/// equal). Exact, by orientation signs:
///
/// - No shared vertex: whether they intersect ([`tri_overlap`]).
/// - The same vertex sets (identical triangles, however ordered): yes.
/// - One shared vertex `v`: whether the part of either spanned by its other vertices (the edge
///   opposite `v`) meets the other triangle. For triangles with area this is exactly whether
///   they meet beyond `v`: a point they share beyond `v` puts the whole segment from `v` to it in
///   both, and following that segment on, the triangle it leaves first is left through its
///   opposite edge, inside the other.
/// - One shared edge: two triangles with area meet beyond it only when they are coplanar and on
///   the same side of it (one folded onto the other); otherwise their planes meet in the edge's
///   line, or they lie on either side of it.
/// - Degenerate triangles (collinear vertices) sharing an edge, and every other case of shared
///   vertices: whether the part of either spanned by its vertices not shared meets the other.
pub fn self_contact(a: &Tri, b: &Tri) -> bool {
    let (in_b, in_a) = shared(a, b);
    contact(a, in_b, b, in_a)
}

/// Which vertices of `a` are among `b`'s (bit `i` for `a[i]`), and which of `b` among `a`'s:
/// of two triangles by their coordinates, or by their vertex indices, which gives the same answer
/// when equal vertices have equal indices and distinct ones distinct indices
/// ([`Bvh::distinct_vertices`]).
#[inline]
fn shared<T: PartialEq>(a: &[T; 3], b: &[T; 3]) -> (u8, u8) {
    let (mut in_b, mut in_a) = (0u8, 0u8);
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            let e = u8::from(x == y);
            in_b |= e << i;
            in_a |= e << j;
        }
    }
    (in_b, in_a)
}

/// [`self_contact`] of the triangles in leaf slots `s` and `t` of `b`, their shared vertices
/// found by index when `by_index` ([`Bvh::distinct_vertices`]), else by coordinates.
#[inline]
fn leaf_contact(b: &Bvh, s: usize, t: usize, by_index: bool) -> bool {
    let (ta, tb) = (b.tri(s), b.tri(t));
    let (in_b, in_a) = if by_index {
        shared(&b.faces[s], &b.faces[t])
    } else {
        shared(&ta, &tb)
    };
    contact(&ta, in_b, &tb, in_a)
}

/// [`self_contact`] of `a` and `b` given which of their vertices are shared (`in_b`: bit `i` when
/// `a[i]` is a vertex of `b`; `in_a` the same for `b`).
fn contact(a: &Tri, in_b: u8, b: &Tri, in_a: u8) -> bool {
    // Bits set in a 3-bit mask; the vertex after and before vertex i.
    const ONES: [u8; 8] = [0, 1, 1, 2, 1, 2, 2, 3];
    const NEXT: [usize; 3] = [1, 2, 0];
    const PREV: [usize; 3] = [2, 0, 1];
    let (na, nb) = (ONES[usize::from(in_b & 7)], ONES[usize::from(in_a & 7)]);
    if na == 0 {
        // Most such pairs met by a search are apart along a coordinate axis.
        return !boxes_apart(a, b) && tri_overlap(a, b);
    }
    if na == 3 && nb == 3 {
        // The same vertex sets.
        return true;
    }
    if na == 1 && nb == 1 {
        // One shared vertex v. If the other two vertices of one are strictly on one side of the
        // other's plane (float signs, certain), they meet only in v, and the rule says so: the
        // signs being nonzero, the plane's triangle has area, so v is not on its edge opposite
        // v, which lies in the plane, where the first triangle has only v; and the first's edge
        // opposite v is off the plane. Settles most neighbours around a vertex of a mesh; the
        // rest (in saddles, they cross each other's planes) mostly by a plane through v between
        // them.
        let (i, j) = (
            in_b.trailing_zeros() as usize,
            in_a.trailing_zeros() as usize,
        );
        let (v, a1, a2, b1, b2) = (&a[i], &a[NEXT[i]], &a[PREV[i]], &b[NEXT[j]], &b[PREV[j]]);
        if strictly_one_side(b, a1, a2)
            || strictly_one_side(a, b1, b2)
            || apart_around(v, a1, a2, b1, b2)
        {
            return false;
        }
    }
    let mut edge = None;
    if na == 2 && nb == 2 {
        // Each has two shared vertices and one other, x and y. If a's two are one point (a
        // repeats a vertex), b's are that point too and the other shared one is missing: so
        // a's two are distinct, the shared edge p q.
        let i = (!in_b & 7).trailing_zeros() as usize;
        let j = (!in_a & 7).trailing_zeros() as usize;
        let (p, q, x, y) = (&a[NEXT[i]], &a[PREV[i]], &a[i], &b[j]);
        if p != q {
            // Sides of the edge first, in a coordinate plane where both project with area (two
            // orientations in 2D, certain in float but for nearly degenerate triangles): on
            // opposite sides they meet only in the edge, coplanar or not. Only pairs folded
            // onto the same side (rare in a mesh) need the coplanarity test, whose float filter
            // fails on the exactly planar quads of many meshes.
            let side = same_side(p, q, x, y);
            if side == Some(false) {
                return false;
            }
            if orient3d(p, q, x, y) != 0.0 {
                // Not coplanar (so both have area): their planes meet in the edge's line.
                return false;
            }
            if let Some(folded) = side {
                return folded;
            }
            edge = Some((*p, *q));
        }
    }
    unshared_part_meets(a, in_b, b, edge) || unshared_part_meets(b, in_a, a, edge)
}

/// For triangles `v a1 a2` and `v b1 b2` sharing the vertex `v`: whether a plane through `v`
/// certainly has `a1` and `a2` strictly on one side and `b1` and `b2` strictly on the other (float
/// signs whose filter certifies them; `false` when unsure). Then each triangle but `v` is
/// strictly on its side: they meet only in `v`, and neither's edge opposite `v` meets the other,
/// as the rule asks. The plane tried is normal to the difference of their vertices' sums, which
/// separates the blades of a fan around `v` (any normal is valid: it is taken as given, and the
/// filter bounds the rounding of the evaluations).
#[inline]
fn apart_around(v: &Vec3, a1: &Vec3, a2: &Vec3, b1: &Vec3, b2: &Vec3) -> bool {
    let plane = PlaneFilter::with_normal(v, (a1 + a2) - (b1 + b2));
    let above = |x: &Vec3| {
        let (f, certain) = plane.eval(x);
        certain && f > 0.0
    };
    let below = |x: &Vec3| {
        let (f, certain) = plane.eval(x);
        certain && f < 0.0
    };
    above(a1) && above(a2) && below(b1) && below(b2)
}

/// Whether `x` and `y` are certainly strictly on the same side of the plane of `t` (float
/// signs whose filter certifies them; `false` when unsure).
#[inline]
fn strictly_one_side(t: &Tri, x: &Vec3, y: &Vec3) -> bool {
    let plane = PlaneFilter::new(&t[0], &t[1], &t[2]);
    let ((fx, cx), (fy, cy)) = (plane.eval(x), plane.eval(y));
    cx && cy && ((fx > 0.0) == (fy > 0.0))
}

/// Whether the triangles' axis-aligned boxes are apart (exact: comparisons only).
fn boxes_apart(a: &Tri, b: &Tri) -> bool {
    (0..3).any(|k| {
        let (alo, ahi) = (
            a[0][k].min(a[1][k]).min(a[2][k]),
            a[0][k].max(a[1][k]).max(a[2][k]),
        );
        let (blo, bhi) = (
            b[0][k].min(b[1][k]).min(b[2][k]),
            b[0][k].max(b[1][k]).max(b[2][k]),
        );
        ahi < blo || bhi < alo
    })
}

/// Whether the hull of the vertices of `t` not flagged in `shared` (bit `i` for `t[i]`: a point,
/// a segment or the triangle) meets `other`; false when every vertex is flagged, or when `edge`
/// (the shared edge, if any) holds the one vertex not flagged: `t` then lies in the edge.
fn unshared_part_meets(t: &Tri, shared: u8, other: &Tri, edge: Option<(Vec3, Vec3)>) -> bool {
    let mut rest = [Vec3::zeros(); 3];
    let mut n = 0;
    for (i, v) in t.iter().enumerate() {
        if shared & (1 << i) == 0 {
            rest[n] = *v;
            n += 1;
        }
    }
    match n {
        0 => false,
        1 => {
            if let Some((p, q)) = edge
                && on_segment(&rest[0], &p, &q)
            {
                return false;
            }
            tri_overlap(other, &[rest[0]; 3])
        }
        2 => segment_meets(&rest[0], &rest[1], other),
        _ => tri_overlap(other, t),
    }
}

/// Whether the segment `s0 s1` meets the triangle `t` (exactly, as [`tri_overlap`] of the
/// segment taken as a triangle, which this settles with orientation signs only: a segment across
/// the plane of `t` meets `t` when the line turns the same way around each of its edges). Faster
/// than [`tri_overlap`] on a segment, whose own plane it cannot use; neighbours in a fine mesh
/// are nearly coplanar, and the segments opposite a shared vertex are the common case.
fn segment_meets(s0: &Vec3, s1: &Vec3, t: &Tri) -> bool {
    // One plane for both ends; the exact sign only where the float one is not certain.
    let plane = PlaneFilter::new(&t[0], &t[1], &t[2]);
    let ((f0, certain0), (f1, certain1)) = (plane.eval(s0), plane.eval(s1));
    // Whether the line turns both ways around t's edges: it passes beside t (or, for a
    // degenerate t, is not coplanar with it), so the segment cannot meet t.
    let beside = || {
        let e = [
            orient3d(s0, s1, &t[0], &t[1]),
            orient3d(s0, s1, &t[1], &t[2]),
            orient3d(s0, s1, &t[2], &t[0]),
        ];
        e.iter().any(|&x| x > 0.0) && e.iter().any(|&x| x < 0.0)
    };
    // An end nearly in t's plane (in a mesh of planar quads, the far corner of a quad is in the
    // plane of the quad's other triangle): the line's turns, well conditioned there, settle most
    // such pairs before the exact sides are computed.
    if !(certain0 && certain1) && beside() {
        return false;
    }
    let side = |s: &Vec3, f: f64, certain: bool| {
        if certain {
            f
        } else {
            orient3d_exact(&t[0], &t[1], &t[2], s)
        }
    };
    let (o0, o1) = (side(s0, f0, certain0), side(s1, f1, certain1));
    if (o0 > 0.0 && o1 > 0.0) || (o0 < 0.0 && o1 < 0.0) {
        return false;
    }
    if o0 == 0.0 && o1 == 0.0 {
        // In the plane of t, or t has none (degenerate).
        return tri_overlap(t, &[*s0, *s1, *s1]);
    }
    !beside()
}

/// Whether `x` lies on the segment `p q` (exactly: collinear, and between in every coordinate).
fn on_segment(x: &Vec3, p: &Vec3, q: &Vec3) -> bool {
    let between = (0..3).all(|k| x[k] >= p[k].min(q[k]) && x[k] <= p[k].max(q[k]));
    between
        && (0..3).all(|drop| {
            let (u, v) = ((drop + 1) % 3, (drop + 2) % 3);
            orient2d([p[u], p[v]], [q[u], q[v]], [x[u], x[v]]) == 0.0
        })
}

/// For `x` and `y` coplanar with the line `p q`: whether they lie strictly on the same side of it
/// (`Some(true)`), or not (`Some(false)`), decided exactly in a coordinate plane on which the
/// triangle `p q x` projects with area; `None` if it has none there (`p`, `q`, `x` collinear) or
/// `y` is on the line (`p q y` has no area).
fn same_side(p: &Vec3, q: &Vec3, x: &Vec3, y: &Vec3) -> Option<bool> {
    // Try the coordinate plane the normal is most nearly along first: there the projection is
    // largest (any plane with a nonzero orientation decides, the sign being exact).
    let n = (q - p).cross(&(x - p));
    let first = n.iamax();
    for drop in [first, (first + 1) % 3, (first + 2) % 3] {
        let (u, v) = ((drop + 1) % 3, (drop + 2) % 3);
        let pr = |w: &Vec3| -> P2 { [w[u], w[v]] };
        let ox = orient2d(pr(p), pr(q), pr(x));
        if ox != 0.0 {
            let oy = orient2d(pr(p), pr(q), pr(y));
            if oy == 0.0 {
                return None;
            }
            return Some((ox > 0.0) == (oy > 0.0));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::{CollisionVolume, VolumeKind};
    use crate::test_rng::{Random, Rng};

    type I3 = [i64; 3];

    fn sub(a: I3, b: I3) -> I3 {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    fn cross(a: I3, b: I3) -> I3 {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    fn dot(a: I3, b: I3) -> i64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    fn v(a: I3) -> Vec3 {
        Vec3::new(a[0] as f64, a[1] as f64, a[2] as f64)
    }

    /// Small integer points: exact arithmetic decides coplanarity and sides independently, and
    /// coplanar and collinear configurations are frequent.
    fn point(rng: &mut Rng, r: i64) -> I3 {
        [rng.int(-r, r), rng.int(-r, r), rng.int(-r, r)]
    }

    #[test]
    fn shared_edge_pairs_meet_only_folded() {
        // Two triangles with area sharing edge p q meet beyond it exactly when they are
        // coplanar and on the same side of it (integer arithmetic, independently of the
        // predicates).
        let mut rng = Rng::new(20);
        let (mut folded, mut flat, mut bent) = (0, 0, 0);
        for _ in 0..200_000 {
            let r = if rng.below(2) == 0 { 2 } else { 6 };
            let (p, q, x, y) = (
                point(&mut rng, r),
                point(&mut rng, r),
                point(&mut rng, r),
                point(&mut rng, r),
            );
            let (n, m) = (cross(sub(q, p), sub(x, p)), cross(sub(q, p), sub(y, p)));
            if n == [0; 3] || m == [0; 3] {
                continue;
            }
            let coplanar = dot(sub(y, p), n) == 0;
            let want = coplanar && dot(n, m) > 0;
            folded += usize::from(want);
            flat += usize::from(coplanar && !want);
            bent += usize::from(!coplanar);
            let (a, b) = ([v(p), v(q), v(x)], [v(q), v(p), v(y)]);
            assert_eq!(self_contact(&a, &b), want, "{p:?} {q:?} {x:?} {y:?}");
            assert_eq!(self_contact(&b, &a), want, "{p:?} {q:?} {x:?} {y:?}");
        }
        assert!(
            folded > 1000 && flat > 1000 && bent > 1000,
            "{folded} {flat} {bent}"
        );
    }

    #[test]
    fn segment_test_equals_the_triangle_test_on_the_segment() {
        // segment_meets is tri_overlap of the segment taken as a triangle; small integer
        // coordinates make ends in the triangle's plane (the case settled first by the line's
        // turns) and coplanar segments frequent. Also at a scale where coordinates round.
        let mut rng = Rng::new(21);
        let (mut met, mut in_plane) = (0, 0);
        for k in 0..300_000 {
            let r = if k % 2 == 0 { 2 } else { 5 };
            let t = [point(&mut rng, r), point(&mut rng, r), point(&mut rng, r)];
            let (s0, s1) = (point(&mut rng, r), point(&mut rng, r));
            let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
            in_plane += usize::from(dot(sub(s0, t[0]), n) == 0 || dot(sub(s1, t[0]), n) == 0);
            let scale = if k % 3 == 0 { 0.1 } else { 1.0 };
            let f = |a: I3| v(a) * scale;
            let tri = [f(t[0]), f(t[1]), f(t[2])];
            let (a, b) = (f(s0), f(s1));
            let want = tri_overlap(&tri, &[a, b, b]);
            met += usize::from(want);
            assert_eq!(
                segment_meets(&a, &b, &tri),
                want,
                "{t:?} {s0:?} {s1:?} x {scale}"
            );
        }
        assert!(met > 10_000 && in_plane > 10_000, "{met} {in_plane}");
    }

    #[test]
    fn one_shared_vertex_early_out_keeps_the_rule() {
        // Two triangles sharing one vertex: the plane test that settles most of them first
        // gives what the rule's two edge tests give (small integer coordinates: in-plane and
        // degenerate cases are frequent; also scaled so that coordinates round).
        let mut rng = Rng::new(22);
        let (mut met, mut apart) = (0, 0);
        for k in 0..300_000 {
            let r = if k % 2 == 0 { 2 } else { 5 };
            let scale = if k % 3 == 0 { 0.1 } else { 1.0 };
            let mut p = || v(point(&mut rng, r)) * scale;
            let (o, a1, a2, b1, b2) = (p(), p(), p(), p(), p());
            let (i, j) = (rng.below(3), rng.below(3));
            let mut a = [o; 3];
            a[(i + 1) % 3] = a1;
            a[(i + 2) % 3] = a2;
            let mut b = [o; 3];
            b[(j + 1) % 3] = b1;
            b[(j + 2) % 3] = b2;
            let (in_b, in_a) = shared(&a, &b);
            if (in_b.count_ones(), in_a.count_ones()) != (1, 1) {
                continue;
            }
            let want =
                unshared_part_meets(&a, in_b, &b, None) || unshared_part_meets(&b, in_a, &a, None);
            met += usize::from(want);
            apart += usize::from(!want);
            assert_eq!(self_contact(&a, &b), want, "{a:?} {b:?}");
            assert_eq!(self_contact(&b, &a), want, "{a:?} {b:?}");
        }
        assert!(met > 10_000 && apart > 10_000, "{met} {apart}");
    }

    /// Every pair `(id1, id2)` of triangles of `b` the rule reports (coordinates compared).
    fn brute_pairs(b: &Bvh) -> Vec<(i32, i32)> {
        let n = b.num_tris();
        let mut out = Vec::new();
        for s in 0..n {
            for t in s + 1..n {
                if self_contact(&b.tri(s), &b.tri(t)) {
                    let (x, y) = (b.ids[s], b.ids[t]);
                    out.push(if b.added[s] < b.added[t] {
                        (x, y)
                    } else {
                        (y, x)
                    });
                }
            }
        }
        out.sort();
        out
    }

    fn searched_pairs(b: &Bvh) -> Vec<(i32, i32)> {
        let mut pairs = Vec::new();
        search(b, &mut pairs, ContactMode::All).unwrap();
        let mut out: Vec<_> = pairs.iter().map(|p| (p.id1, p.id2)).collect();
        out.sort();
        out
    }

    #[test]
    fn a_repeated_vertex_is_still_shared() {
        // A loaded model's file may store a vertex twice: triangles using either copy share it.
        // Found on first use, and the search then compares coordinates.
        let (n, m) = (12, 6);
        let pt = |i: usize, j: usize| {
            let (u, w) = (
                std::f64::consts::TAU * (i % n) as f64 / n as f64,
                std::f64::consts::TAU * (j % m) as f64 / m as f64,
            );
            let r = 1.0 + 0.3 * w.cos();
            Vec3::new(r * u.cos(), r * u.sin(), 0.3 * w.sin())
        };
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..m {
                let id = 2 * (i * m + j) as i32;
                tris.push(([pt(i, j), pt(i + 1, j), pt(i + 1, j + 1)], id));
                tris.push(([pt(i, j), pt(i + 1, j + 1), pt(i, j + 1)], id + 1));
            }
        }
        let built = Bvh::build(tris, VolumeKind::Rss, CollisionVolume::Obb).unwrap();
        assert!(built.distinct_vertices());
        // Closed: no pair, by index or by coordinates.
        assert_eq!(searched_pairs(&built), Vec::<(i32, i32)>::new());
        assert_eq!(brute_pairs(&built), Vec::<(i32, i32)>::new());
        let mut b = built.try_clone().unwrap();
        // Every other use of vertex 0 and vertex 7 goes to a copy of it.
        for v in [0u32, 7] {
            let copy = b.verts.len() as u32;
            b.verts.push(b.verts[v as usize]);
            let mut k = 0;
            for f in b.faces.iter_mut() {
                for x in f.iter_mut().filter(|x| **x == v) {
                    if k % 2 == 1 {
                        *x = copy;
                    }
                    k += 1;
                }
            }
        }
        b.distinct = std::sync::OnceLock::new();
        assert!(!b.distinct_vertices());
        // By index the copies would not be shared, and neighbours touching there reported.
        assert_eq!(searched_pairs(&b), Vec::<(i32, i32)>::new());
        assert_eq!(brute_pairs(&b), Vec::<(i32, i32)>::new());
    }
}
