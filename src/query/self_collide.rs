//! Self-collision: which pairs of distinct triangles of one model intersect, neighbours that meet
//! only in what they share excepted.
//!
//! The hierarchy is searched against itself (see `collide::search_pairs`): a node against itself
//! is its two children against themselves and against each other, so each pair of triangles is
//! met once, at the node where their paths part, and pairs in volumes that do not overlap are
//! never looked at. Neighbours in a mesh always have overlapping volumes, so every pair sharing a
//! vertex or an edge reaches the triangle test: [`self_contact`] settles most of them with one
//! filtered orientation test.

use super::collide::{CollideResult, ContactMode, ContactPair, search_pairs};
use crate::error::Error;
use crate::geometry::predicates::{P2, PlaneFilter, orient2d, orient3d, orient3d_exact};
use crate::geometry::{Tri, tri_overlap};
use crate::math::{RelPose, Vec3};
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
    let b = m.bvh()?;
    let pairs = result.pairs_mut();
    pairs.clear();
    let leaf_pair = |s: usize, t: usize, _: &Tri| {
        self_contact(&b.tri(s), &b.tri(t)).then(|| {
            let (first, second) = if b.added[s] < b.added[t] {
                (s, t)
            } else {
                (t, s)
            };
            ContactPair {
                id1: b.ids[first],
                id2: b.ids[second],
            }
        })
    };
    let mut stats = search_pairs(pairs, b, b, &RelPose::identity(), mode, true, leaf_pair);
    stats.query_time_secs = start.elapsed().as_secs_f64();
    result.stats = stats;
    Ok(())
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
    // Which vertices of each are among the other's.
    let mut in_b = [false; 3];
    let mut in_a = [false; 3];
    for i in 0..3 {
        for j in 0..3 {
            if a[i] == b[j] {
                in_b[i] = true;
                in_a[j] = true;
            }
        }
    }
    let count = |f: &[bool; 3]| f.iter().filter(|&&s| s).count();
    let (na, nb) = (count(&in_b), count(&in_a));
    if na == 0 {
        // Most such pairs met by a search are apart along a coordinate axis.
        return !boxes_apart(a, b) && tri_overlap(a, b);
    }
    if na == 3 && nb == 3 {
        // The same vertex sets.
        return true;
    }
    let mut edge = None;
    if na == 2 && nb == 2 {
        // Each has two shared vertices and one other, x and y. If a's two are one point (a
        // repeats a vertex), b's are that point too and the other shared one is missing: so
        // a's two are distinct, the shared edge p q.
        let i = in_b.iter().position(|&s| !s).unwrap_or(0);
        let j = in_a.iter().position(|&s| !s).unwrap_or(0);
        let (p, q, x, y) = (a[(i + 1) % 3], a[(i + 2) % 3], a[i], b[j]);
        if p != q {
            if orient3d(&p, &q, &x, &y) != 0.0 {
                // Not coplanar (so both have area): their planes meet in the edge's line.
                return false;
            }
            if let Some(folded) = same_side(&p, &q, &x, &y) {
                return folded;
            }
            edge = Some((p, q));
        }
    }
    unshared_part_meets(a, &in_b, b, edge) || unshared_part_meets(b, &in_a, a, edge)
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

/// Whether the hull of the vertices of `t` not flagged in `shared` (a point, a segment or the
/// triangle) meets `other`; false when every vertex is flagged, or when `edge` (the shared
/// edge, if any) holds the one vertex not flagged: `t` then lies in the edge.
fn unshared_part_meets(
    t: &Tri,
    shared: &[bool; 3],
    other: &Tri,
    edge: Option<(Vec3, Vec3)>,
) -> bool {
    let mut rest = [Vec3::zeros(); 3];
    let mut n = 0;
    for (v, s) in t.iter().zip(shared) {
        if !s {
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
    let side = |s: &Vec3| match plane.eval(s) {
        (v, true) => v,
        _ => orient3d_exact(&t[0], &t[1], &t[2], s),
    };
    let (o0, o1) = (side(s0), side(s1));
    if (o0 > 0.0 && o1 > 0.0) || (o0 < 0.0 && o1 < 0.0) {
        return false;
    }
    if o0 == 0.0 && o1 == 0.0 {
        // In the plane of t, or t has none (degenerate).
        return tri_overlap(t, &[*s0, *s1, *s1]);
    }
    let e = [
        orient3d(s0, s1, &t[0], &t[1]),
        orient3d(s0, s1, &t[1], &t[2]),
        orient3d(s0, s1, &t[2], &t[0]),
    ];
    !(e.iter().any(|&x| x > 0.0) && e.iter().any(|&x| x < 0.0))
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
