//! Exact triangle-triangle intersection, from orientation predicates only.
//!
//! Let `L` be the line where the planes of two non-coplanar triangles meet. Each triangle cuts `L`
//! in a closed interval whose ends lie on the two edges leaving its "lone" vertex (the one the
//! other plane separates from the other two), and the triangles intersect exactly when the two
//! intervals overlap. For an end `X` on edge `p q` of one triangle and an end `Y` on edge `u v` of
//! the other, `orient3d(p, q, u, v) = (Y - X) . ((v - u) x (q - p))`, and with
//! `L = nA x nB` one finds `((v - u) x (q - p)) . L = (nA . (v - u)) (nB . (q - p))`: so the
//! order of `X` and `Y` along `L` is the sign of one orientation times two signs already known
//! from the plane tests. Two orientations then decide the overlap. Coplanar and degenerate
//! (segment or point) triangles are settled by exact tests in a coordinate plane.

use super::Tri;
use super::predicates::{P2, PlaneFilter, orient2d, orient3d, orient3d_exact};
use super::segment_segment::{point_on, recip, seg_seg};
use crate::math::Vec3;

/// Whether two triangles share a point. Touching and coplanar overlap count as contact.
///
/// Exact: the answer is decided by the signs of orientation determinants, computed exactly when
/// floating point cannot certify them. Degenerate triangles count as the segment or point they
/// span.
pub fn tri_overlap(a: &Tri, b: &Tri) -> bool {
    let ob = Sides::eval(&PlaneFilter::new(&a[0], &a[1], &a[2]), b);
    if ob.separated() {
        return false;
    }
    let oa = Sides::eval(&PlaneFilter::new(&b[0], &b[1], &b[2]), a);
    if oa.separated() {
        return false;
    }
    intersect::<false>(a, b, oa, ob).is_some()
}

/// The orientations of three points relative to a triangle's plane (`orient3d(t0, t1, t2, x)`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sides {
    pub o: [f64; 3],
    certain: [bool; 3],
    /// Bounds on the rounding error of `o` (infinite when not computed).
    err: [f64; 3],
}

impl Sides {
    /// Float values, each flagged by whether its sign is certain.
    #[inline]
    pub(crate) fn eval(plane: &PlaneFilter, pts: &Tri) -> Sides {
        let (o0, e0) = plane.eval_with_error(&pts[0]);
        let (o1, e1) = plane.eval_with_error(&pts[1]);
        let (o2, e2) = plane.eval_with_error(&pts[2]);
        Sides {
            o: [o0, o1, o2],
            certain: [o0.abs() > e0, o1.abs() > e1, o2.abs() > e2],
            err: [e0, e1, e2],
        }
    }

    /// Float values only, for when the contact question is already settled; flagged uncertain.
    #[inline]
    pub(crate) fn values(plane: &PlaneFilter, pts: &Tri) -> Sides {
        Sides {
            o: [
                plane.value(&pts[0]),
                plane.value(&pts[1]),
                plane.value(&pts[2]),
            ],
            certain: [false; 3],
            err: [f64::INFINITY; 3],
        }
    }

    /// When the three points are certainly strictly on one side, a lower bound on the least of
    /// their orientations' magnitudes (exact ones, not the float values); else 0.
    #[inline]
    pub(crate) fn clearance(&self) -> f64 {
        if !self.separated() {
            return 0.0;
        }
        let [o0, o1, o2] = self.o;
        let [e0, e1, e2] = self.err;
        (o0.abs() - e0).min(o1.abs() - e1).min(o2.abs() - e2)
    }

    /// All three points certainly strictly on the same side.
    #[inline]
    pub(crate) fn separated(&self) -> bool {
        let [o0, o1, o2] = self.o;
        self.certain == [true; 3]
            && (o0 > 0.0 && o1 > 0.0 && o2 > 0.0 || o0 < 0.0 && o1 < 0.0 && o2 < 0.0)
    }

    /// Makes every sign exact.
    fn refine(&mut self, t: &Tri, pts: &Tri) {
        for ((o, certain), x) in self.o.iter_mut().zip(&mut self.certain).zip(pts) {
            if !*certain {
                *o = orient3d_exact(&t[0], &t[1], &t[2], x);
                *certain = true;
            }
        }
    }
}

#[inline]
fn sign(x: f64) -> i32 {
    (x > 0.0) as i32 - (x < 0.0) as i32
}

/// Whether `a` and `b` intersect, given the sides of `a`'s vertices relative to `b`'s plane (`oa`)
/// and of `b`'s relative to `a`'s (`ob`). With `W`, `Some` carries a common point (computed in
/// floating point: common to both up to rounding); without, the point is meaningless.
pub(crate) fn intersect<const W: bool>(
    a: &Tri,
    b: &Tri,
    mut oa: Sides,
    mut ob: Sides,
) -> Option<Vec3> {
    oa.refine(b, a);
    ob.refine(a, b);
    let sa = oa.o.map(sign);
    let sb = ob.o.map(sign);
    let one_side = |s: [i32; 3]| s == [1; 3] || s == [-1; 3];
    if one_side(sa) || one_side(sb) {
        return None;
    }
    // A degenerate triangle has every point on its "plane": all-zero sides of the other's vertices.
    match (sa == [0; 3], sb == [0; 3]) {
        // Both nondegenerate, planes not the same.
        (false, false) => general::<W>(a, b, &oa.o, &ob.o),
        // `a` degenerate (b's vertices would otherwise be on a's plane and vice versa): a segment
        // that reaches b's plane.
        (false, true) => segment_through_plane::<W>(a, &oa.o, b),
        (true, false) => segment_through_plane::<W>(b, &ob.o, a),
        (true, true) => coplanar::<W>(a, b),
    }
}

/// The vertex of a triangle separated by the other plane from its two companions (which may lie
/// on the plane, or the lone vertex itself may lie on it with both companions strictly on one
/// side), and `sign(nB . (q - p))` for an edge `p q` leaving it.
fn lone(s: [i32; 3]) -> (usize, i32) {
    for i in 0..3 {
        let (sj, sk) = (s[(i + 1) % 3], s[(i + 2) % 3]);
        let lone = match s[i] {
            1 => sj <= 0 && sk <= 0,
            -1 => sj >= 0 && sk >= 0,
            _ => sj == sk && sj != 0,
        };
        if lone {
            return (i, if s[i] != 0 { -s[i] } else { sj });
        }
    }
    // Unreachable for the sign patterns `general` receives.
    (0, 1)
}

/// Non-coplanar, nondegenerate triangles, each reaching the other's plane: compare the intervals
/// they cut on the common line (see the module comment).
fn general<const W: bool>(a: &Tri, b: &Tri, oa: &[f64; 3], ob: &[f64; 3]) -> Option<Vec3> {
    let (ia, sig_a) = lone(oa.map(sign));
    let (ib, sig_b) = lone(ob.map(sign));
    // Order the edges so that X1 (on p q) precedes X2 (on p r) along L = nA x nB, and Y1 (on u v)
    // precedes Y2 (on u w). Along L, X2 - X1 has the sign of sig_a when p q r is a rotation of
    // a0 a1 a2, and Y2 - Y1 the opposite of sig_b for the same order of b's vertices.
    let (mut qa, mut ra) = ((ia + 1) % 3, (ia + 2) % 3);
    if sig_a < 0 {
        std::mem::swap(&mut qa, &mut ra);
    }
    let (mut vb, mut wb) = ((ib + 1) % 3, (ib + 2) % 3);
    if sig_b > 0 {
        std::mem::swap(&mut vb, &mut wb);
    }
    let sig = sig_a * sig_b;
    let (p, q, r) = (&a[ia], &a[qa], &a[ra]);
    let (u, v, w) = (&b[ib], &b[vb], &b[wb]);
    // X1 <= Y2 along L.
    if sign(orient3d(p, q, u, w)) * sig < 0 {
        return None;
    }
    // Y1 <= X2 along L.
    if sign(orient3d(p, r, u, v)) * sig > 0 {
        return None;
    }
    if !W {
        return Some(*p);
    }
    // The intersection is [max(X1, Y1), min(X2, Y2)]; return its first end.
    let x1 = point_on(p, q, &(q - p), oa[ia] / (oa[ia] - oa[qa]));
    let y1 = point_on(u, v, &(v - u), ob[ib] / (ob[ib] - ob[vb]));
    if sign(orient3d(p, q, u, v)) * sig >= 0 {
        Some(y1)
    } else {
        Some(x1)
    }
}

/// Indices of the lexicographically smallest and largest vertices: for collinear vertices, the
/// ends of the segment they span (coordinates are monotone along a line).
fn extremes(t: &Tri) -> (usize, usize) {
    let key = |i: usize| (t[i].x, t[i].y, t[i].z);
    let (mut lo, mut hi) = (0, 0);
    for i in 1..3 {
        if key(i) < key(lo) {
            lo = i;
        }
        if key(i) > key(hi) {
            hi = i;
        }
    }
    (lo, hi)
}

/// A degenerate triangle `s` (a segment, with sides `os` relative to `t`'s plane) that reaches the
/// plane of the nondegenerate `t` without lying in it: the crossing point must be in `t`, i.e. the
/// line must pass no edge of `t` on the outside.
fn segment_through_plane<const W: bool>(s: &Tri, os: &[f64; 3], t: &Tri) -> Option<Vec3> {
    let (i, j) = extremes(s);
    let (p, q) = (&s[i], &s[j]);
    let o = [
        orient3d(p, q, &t[0], &t[1]),
        orient3d(p, q, &t[1], &t[2]),
        orient3d(p, q, &t[2], &t[0]),
    ];
    if o.iter().any(|&x| x > 0.0) && o.iter().any(|&x| x < 0.0) {
        return None;
    }
    Some(point_on(p, q, &(q - p), os[i] / (os[i] - os[j])))
}

/// A triangle's shape once degeneracy is decided exactly: a proper triangle, with a coordinate
/// axis along which it projects one to one, or the segment (possibly a point) it spans.
enum Shape {
    Tri(usize),
    Seg(Vec3, Vec3),
}

/// Drops coordinate `k`.
#[inline]
fn proj(v: &Vec3, k: usize) -> P2 {
    match k {
        0 => [v.y, v.z],
        1 => [v.z, v.x],
        _ => [v.x, v.y],
    }
}

fn shape(t: &Tri) -> Shape {
    let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
    // Try the axis of the largest normal component first: the projection is best conditioned.
    let mut axes = [(n.x.abs(), 0), (n.y.abs(), 1), (n.z.abs(), 2)];
    axes.sort_unstable_by(|x, y| y.0.total_cmp(&x.0));
    for (_, k) in axes {
        if orient2d(proj(&t[0], k), proj(&t[1], k), proj(&t[2], k)) != 0.0 {
            return Shape::Tri(k);
        }
    }
    let (i, j) = extremes(t);
    Shape::Seg(t[i], t[j])
}

/// Every point of both triangles lies in one plane (or a triangle is degenerate).
fn coplanar<const W: bool>(a: &Tri, b: &Tri) -> Option<Vec3> {
    match (shape(a), shape(b)) {
        (Shape::Tri(k), Shape::Tri(_)) => tri_tri_2d::<W>(a, b, k),
        (Shape::Tri(k), Shape::Seg(p, q)) => seg_tri_2d::<W>(&p, &q, a, k),
        (Shape::Seg(p, q), Shape::Tri(k)) => seg_tri_2d::<W>(&p, &q, b, k),
        (Shape::Seg(p, q), Shape::Seg(r, s)) => seg_seg_3d::<W>(&p, &q, &r, &s),
    }
}

/// Closed-triangle membership in a coordinate plane (`t` nondegenerate there).
fn in_tri_2d(x: &Vec3, t: &Tri, k: usize) -> bool {
    let (x, t0, t1, t2) = (proj(x, k), proj(&t[0], k), proj(&t[1], k), proj(&t[2], k));
    let o = [
        orient2d(t0, t1, x),
        orient2d(t1, t2, x),
        orient2d(t2, t0, x),
    ];
    !(o.iter().any(|&v| v > 0.0) && o.iter().any(|&v| v < 0.0))
}

/// Closed segments `[p, q]` and `[r, s]` (either may be a point) compared in coordinate plane `k`.
/// The witness is a common point in 3D when the projection is one to one on a plane holding both.
fn seg_seg_2d<const W: bool>(p: &Vec3, q: &Vec3, r: &Vec3, s: &Vec3, k: usize) -> Option<Vec3> {
    let (p2, q2, r2, s2) = (proj(p, k), proj(q, k), proj(r, k), proj(s, k));
    let o1 = orient2d(p2, q2, r2);
    let o2 = orient2d(p2, q2, s2);
    if o1 > 0.0 && o2 > 0.0 || o1 < 0.0 && o2 < 0.0 {
        return None;
    }
    let o3 = orient2d(r2, s2, p2);
    let o4 = orient2d(r2, s2, q2);
    if o3 > 0.0 && o4 > 0.0 || o3 < 0.0 && o4 < 0.0 {
        return None;
    }
    if o1 == 0.0 && o2 == 0.0 && o3 == 0.0 && o4 == 0.0 {
        // Collinear (or points): overlap of the lexicographic intervals.
        let (pl, ph) = if p2 <= q2 {
            ((p2, p), q2)
        } else {
            ((q2, q), p2)
        };
        let (rl, rh) = if r2 <= s2 {
            ((r2, r), s2)
        } else {
            ((s2, s), r2)
        };
        if ph < rl.0 || rh < pl.0 {
            return None;
        }
        return Some(if pl.0 < rl.0 { *rl.1 } else { *pl.1 });
    }
    if !W {
        return Some(*p);
    }
    // Not both of a pair are zero here, and the pair's signs differ: the ratio is in [0, 1].
    Some(if o1 != o2 {
        point_on(r, s, &(s - r), o1 / (o1 - o2))
    } else {
        point_on(p, q, &(q - p), o3 / (o3 - o4))
    })
}

/// Segment (or point) `[p, q]` against triangle `t`, all in one plane along which coordinate
/// plane `k` projects `t` one to one.
fn seg_tri_2d<const W: bool>(p: &Vec3, q: &Vec3, t: &Tri, k: usize) -> Option<Vec3> {
    if in_tri_2d(p, t, k) {
        return Some(*p);
    }
    if p == q {
        return None;
    }
    if in_tri_2d(q, t, k) {
        return Some(*q);
    }
    (0..3).find_map(|i| seg_seg_2d::<W>(p, q, &t[i], &t[(i + 1) % 3], k))
}

/// Two coplanar nondegenerate triangles: one holds a vertex of the other, or their edges cross.
fn tri_tri_2d<const W: bool>(a: &Tri, b: &Tri, k: usize) -> Option<Vec3> {
    if let Some(v) = a.iter().find(|v| in_tri_2d(v, b, k)) {
        return Some(*v);
    }
    if let Some(v) = b.iter().find(|v| in_tri_2d(v, a, k)) {
        return Some(*v);
    }
    for i in 0..3 {
        for j in 0..3 {
            let x = seg_seg_2d::<W>(&a[i], &a[(i + 1) % 3], &b[j], &b[(j + 1) % 3], k);
            if x.is_some() {
                return x;
            }
        }
    }
    None
}

/// Two segments (or points) in space. Coplanar ones meet exactly when their projections meet in
/// all three coordinate planes (a plane holding both projects one to one onto at least one).
fn seg_seg_3d<const W: bool>(p: &Vec3, q: &Vec3, r: &Vec3, s: &Vec3) -> Option<Vec3> {
    if orient3d(p, q, r, s) != 0.0 {
        return None;
    }
    for k in 0..3 {
        seg_seg_2d::<false>(p, q, r, s, k)?;
    }
    if !W {
        return Some(*p);
    }
    let (d1, d2) = (q - p, s - r);
    let (a, e) = (d1.norm_squared(), d2.norm_squared());
    let c = seg_seg(p, &d1, a, recip(a), r, &d2, e, recip(e));
    Some(point_on(p, q, &d1, c.s))
}
