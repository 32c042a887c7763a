use super::point_triangle::{FaceFrame, face_normal};
use super::predicates::{PlaneFilter, kernel_rescale, max_abs, pow2};
use super::segment_segment::{length, point_on, recip, seg_seg};
use super::tri_overlap::{Sides, intersect};
use super::{ClosestPoints, Tri};
use crate::math::Vec3;

/// Distance between two triangles with a closest point on each (`p` on `a`, `q` on `b`). When
/// they intersect or touch, the distance is 0 and `p == q` is a common point.
///
/// Contact is decided exactly (as [`tri_overlap`](super::tri_overlap()), with which this function
/// agrees: the distance is 0 exactly when the triangles share a point; a separation that rounds to
/// 0 is reported as one rounding of the coordinates' magnitude, never as 0). Otherwise the closest
/// pair is among the 9 edge pairs and the 6 vertex-against-face pairs, each computed to a few
/// roundings of the triangles' size.
/// Degenerate triangles count as the segment or point they span.
pub fn tri_distance(a: &Tri, b: &Tri) -> ClosestPoints {
    match tri_distance_below(a, b, f64::INFINITY, Plane::A, false) {
        Near::Closest(c) => c,
        // Nothing is at least an infinite distance apart.
        Near::Apart(_) => unreachable!(),
    }
}

/// What [`tri_distance_below`] finds.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Near {
    /// The distance and closest points, as [`tri_distance`] gives them.
    Closest(ClosestPoints),
    /// The triangles are at least the cutoff apart, as the plane of this one showed.
    Apart(Plane),
}

/// One of the two triangles of [`tri_distance_below`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Plane {
    A,
    B,
}

/// As [`tri_distance`] below `cutoff`. At or beyond it, when one triangle lies strictly on one side
/// of the other's plane and its nearest vertex there is at least `cutoff` from the plane, only
/// that comes back: a search that prunes such pairs needs no more, and it is most of a triangle
/// test's work saved. `first`: the triangle whose plane is tried first (where the last pair was
/// settled, say: a search meets the same configuration again and again). `in_range`: the caller
/// knows that the largest coordinate magnitude of the six vertices lies in
/// `[RESCALE_LO, RESCALE_HI]`, so that the kernel needs no rescaling (see [`kernel_rescale`]); a
/// search knows it for all its pairs at once.
pub(crate) fn tri_distance_below(
    a: &Tri,
    b: &Tri,
    cutoff: f64,
    first: Plane,
    in_range: bool,
) -> Near {
    if in_range {
        return distance_core(a, b, cutoff, first);
    }
    let m = max_abs(&[&a[0], &a[1], &a[2], &b[0], &b[1], &b[2]]);
    if let Some(k) = kernel_rescale(m) {
        // Huge or tiny coordinates: work at unit scale (exactly, by a power of two).
        let (s, inv) = (pow2(k), pow2(-k));
        return match distance_core(&a.map(|v| v * s), &b.map(|v| v * s), cutoff * s, first) {
            Near::Closest(r) => Near::Closest(ClosestPoints {
                distance: r.distance * inv,
                p: r.p * inv,
                q: r.q * inv,
            }),
            far => far,
        };
    }
    distance_core(a, b, cutoff, first)
}

/// Whether the points of `sides` (relative to `plane`) are certainly on one side of it and at
/// least `cutoff` from it.
#[inline]
fn apart(plane: &PlaneFilter, sides: &Sides, cutoff: f64) -> bool {
    far_enough(sides.clearance(), cutoff, needed(plane))
}

/// With the least exact orientation's magnitude of some points at least `clearance` (0 when they
/// are not certainly strictly on one side of the plane), whether they are at least `cutoff` from
/// it; `needed` is the plane's [`needed`].
#[inline(always)]
fn far_enough(clearance: f64, cutoff: f64, needed: f64) -> bool {
    if clearance <= 0.0 {
        return false;
    }
    // The exact heights are the exact orientations over the exact normal's length, which is at
    // most |n| + e: the test is clearance / cutoff >= |n| + e, without a root (see `needed`). The
    // quotient, not the squares of the orientations (fourth powers of the coordinates), so that
    // nothing overflows: a quotient too large to square is far beyond the cutoff.
    let q = clearance / cutoff;
    q * q >= needed
}

/// A bound on the square of the exact normal's length of `plane`, `|n| + e` with `e` the bound
/// on its rounding, without a root: (|n| + e)^2 <= (1 + 2^-40) |n|^2 + (1 + 2^40) e^2. NaN (no
/// comparison with it holds) when too small to prove anything (see below).
#[inline(always)]
fn needed(plane: &PlaneFilter) -> f64 {
    const K: f64 = 1.0 / (1u64 << 40) as f64;
    // Squares that underflow prove nothing (a triangle tiny beside the other's coordinates, after
    // the kernel's rescaling, has a normal whose square is subnormal or zero): only a right side
    // far above the subnormals, where their loss is below the margins, decides.
    const LEAST: f64 = 1e-270;
    let e = plane.normal_error_bound();
    let needed = (1.0 + K) * plane.n.norm_squared() + (1.0 + 1.0 / K) * (e * e);
    if needed >= LEAST { needed } else { f64::NAN }
}

/// A triangle with its plane prepared for [`PlanedTri::apart`]: kept with a triangle tested
/// against many others (a search's cache of recent ones), it saves each test the plane's cross
/// product, its error bound and a division.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlanedTri {
    pub tri: Tri,
    plane: PlaneFilter,
    /// An upper bound on `|n| + e`, the exact normal's length (see [`needed`]); NaN when
    /// [`needed`] is (no comparison with it then holds).
    reach: f64,
}

impl PlanedTri {
    #[inline]
    pub(crate) fn new(tri: Tri) -> PlanedTri {
        let plane = PlaneFilter::new(&tri[0], &tri[1], &tri[2]);
        // The root and the product each round by at most half a unit in the last place: the
        // factor more than covers both, and the rounding of the product with the cutoff in
        // `apart` (all within the normal range, see there).
        const UP: f64 = 1.0 + 1.0 / (1u64 << 49) as f64;
        PlanedTri {
            tri,
            plane,
            reach: needed(&plane).sqrt() * UP,
        }
    }

    /// Whether `a` lies certainly strictly on one side of this triangle's plane with its nearest
    /// vertex at least `cutoff` from it, which the pair is then too: the test that
    /// [`tri_distance_below`] with `first` = [`Plane::B`] tries first (for `a` and this triangle),
    /// as sound (it may differ from that one's verdict only within a few roundings). Only that
    /// test, inlined where a search tests its pairs: in the common case, that the plane settles
    /// the pair, the test needs no more.
    #[inline(always)]
    pub(crate) fn apart(&self, a: &Tri, cutoff: f64) -> bool {
        // 0 unless `a` is certainly strictly on one side, which the comparison below then fails
        // (its right side is positive, or NaN).
        let clearance = Sides::eval(&self.plane, a).clearance();
        // The heights are at least clearance / (|n| + e): at least `cutoff` when clearance >=
        // cutoff * reach, a product without the division of `far_enough`. The product rounds
        // by a relative half unit (covered by `reach`'s margin) when normal; when it underflows,
        // by 2^-1075 at most, which the added 2^-1060 covers (and a normal product hardly
        // notices).
        const TINY: f64 = f64::from_bits(1 << 14); // 2^-1060
        clearance >= cutoff * self.reach + TINY
    }
}

/// Which candidate is closest so far.
#[derive(Clone, Copy)]
enum Feature {
    /// Edge `i` of `a` (from vertex `i` to `i + 1`) and edge `j` of `b`, at parameters `s`, `t`.
    Edges(usize, usize, f64, f64),
    /// Vertex `j` of `b` over the face of `a`, whose closest point is `b[j] - n * k`.
    VertexOfB(usize, Vec3, f64),
    /// Vertex `i` of `a` over the face of `b`, whose closest point is `a[i] - n * k`.
    VertexOfA(usize, Vec3, f64),
}

fn distance_core(a: &Tri, b: &Tri, cutoff: f64, first: Plane) -> Near {
    let cut = cutoff < f64::INFINITY;
    if cut && first == Plane::B {
        let pb = PlaneFilter::new(&b[0], &b[1], &b[2]);
        let oa = Sides::eval(&pb, a);
        if apart(&pb, &oa, cutoff) {
            return Near::Apart(Plane::B);
        }
        let pa = PlaneFilter::new(&a[0], &a[1], &a[2]);
        let ob = Sides::eval(&pa, b);
        if apart(&pa, &ob, cutoff) {
            return Near::Apart(Plane::A);
        }
        return Near::Closest(closest(a, b, &pa, &pb, oa, ob));
    }
    let pa = PlaneFilter::new(&a[0], &a[1], &a[2]);
    // Either triangle strictly on one side of the other's plane is the common, cheap case; then
    // the other side's values are needed only for distances, without error bounds.
    let ob = Sides::eval(&pa, b);
    if cut && apart(&pa, &ob, cutoff) {
        return Near::Apart(Plane::A);
    }
    // Without a cutoff, a's sides of b's plane are needed only for distances when b is strictly
    // on one side of a's plane: then no error bounds.
    let pb = PlaneFilter::new(&b[0], &b[1], &b[2]);
    let oa = if ob.separated() && !cut {
        Sides::values(&pb, a)
    } else {
        Sides::eval(&pb, a)
    };
    if cut && apart(&pb, &oa, cutoff) {
        return Near::Apart(Plane::B);
    }
    Near::Closest(closest(a, b, &pa, &pb, oa, ob))
}

/// The distance and closest points, from the triangles' planes and the sides of each triangle's
/// vertices relative to the other's plane.
fn closest(
    a: &Tri,
    b: &Tri,
    pa: &PlaneFilter,
    pb: &PlaneFilter,
    oa: Sides,
    ob: Sides,
) -> ClosestPoints {
    if !ob.separated()
        && !oa.separated()
        && let Some(x) = intersect::<true>(a, b, oa, ob)
    {
        return ClosestPoints {
            distance: 0.0,
            p: x,
            q: x,
        };
    }
    // Disjoint: a closest pair has a point on an edge of each, or a vertex of one whose
    // projection falls inside the other's face.
    let ea = [a[1] - a[0], a[2] - a[1], a[0] - a[2]];
    let eb = [b[1] - b[0], b[2] - b[1], b[0] - b[2]];
    let la = ea.map(|e| e.norm_squared());
    let lb = eb.map(|e| e.norm_squared());
    let fa = Face::new(a, &ea, &la, &pa.n, &ob.o, b);
    let fb = Face::new(b, &eb, &lb, &pb.n, &oa.o, a);
    // A triangle strictly on one side of the other's plane is at least as far from it as its
    // vertex nearest the plane; if that vertex projects inside the face, this is the distance.
    if let Some((d2, j, k)) = fa.nearest_vertex_if_one_side(a, &ea, b) {
        let foot = b[j] - fa.n * k;
        return vertex_face(a, b, d2, fa.n * k, foot, b[j]);
    }
    if let Some((d2, i, k)) = fb.nearest_vertex_if_one_side(b, &eb, a) {
        let foot = a[i] - fb.n * k;
        return vertex_face(a, b, d2, fb.n * k, a[i], foot);
    }
    let mut best = f64::INFINITY;
    let mut feature = Feature::Edges(0, 0, 0.0, 0.0);
    let mut gap = Vec3::zeros();
    // An edge whose ends are strictly on one side of the other triangle's plane is at least as far
    // from that triangle as the nearer end is from the plane.
    let bound_a = fb.edge_bounds();
    let bound_b = fa.edge_bounds();
    let (ia, ib) = (la.map(recip), lb.map(recip));
    // Try first the edges at each triangle's vertex nearest the other's plane, where the closest
    // pair usually is: the separating-slab test below then ends the search early.
    let order_a = edge_order(&oa.o);
    let order_b = edge_order(&ob.o);
    for i in order_a {
        for j in order_b {
            if bound_a[i].max(bound_b[j]) >= best {
                continue;
            }
            let c = seg_seg(&a[i], &ea[i], la[i], ia[i], &b[j], &eb[j], lb[j], ib[j]);
            if c.dist2 < best {
                best = c.dist2;
                feature = Feature::Edges(i, j, c.s, c.t);
                gap = c.gap;
                // The closest points P, Q of two edges already have every point of either edge on
                // its own side of the slab between the planes through P and Q normal to the gap.
                // If the third vertices are too, the slab separates the triangles: this pair is
                // the answer.
                let g = c.gap; // P - Q
                let third_a = -ea[(i + 2) % 3]; // a[i + 2] - a[i]
                let third_b = -eb[(j + 2) % 3];
                if third_a.dot(&g) - c.s * ea[i].dot(&g) >= 0.0
                    && third_b.dot(&g) - c.t * eb[j].dot(&g) <= 0.0
                {
                    return finish(a, b, &ea, &eb, Feature::Edges(i, j, c.s, c.t), c.gap, best);
                }
            }
        }
    }
    // Vertices over faces, for what the edges left (no separating slab was found).
    if let Some((d2, j, k)) = fa.nearest_vertex_over(a, &ea, b, best) {
        best = d2;
        feature = Feature::VertexOfB(j, fa.n, k);
        gap = fa.n * k;
    }
    if let Some((d2, i, k)) = fb.nearest_vertex_over(b, &eb, a, best) {
        best = d2;
        feature = Feature::VertexOfA(i, fb.n, k);
        gap = fb.n * k;
    }
    finish(a, b, &ea, &eb, feature, gap, best)
}

/// Edge indices starting with the two edges at the vertex of least `|o|`.
#[inline]
fn edge_order(o: &[f64; 3]) -> [usize; 3] {
    let (a0, a1, a2) = (o[0].abs(), o[1].abs(), o[2].abs());
    // Edge k joins vertices k and k + 1.
    if a0 <= a1 && a0 <= a2 {
        [0, 2, 1]
    } else if a1 <= a2 {
        [1, 0, 2]
    } else {
        [2, 1, 0]
    }
}

/// The answer from the closest feature pair, its gap vector and squared distance.
#[inline]
fn finish(
    a: &Tri,
    b: &Tri,
    ea: &[Vec3; 3],
    eb: &[Vec3; 3],
    feature: Feature,
    gap: Vec3,
    d2: f64,
) -> ClosestPoints {
    let (p, q) = match feature {
        Feature::Edges(i, j, s, t) => (
            point_on(&a[i], &a[(i + 1) % 3], &ea[i], s),
            point_on(&b[j], &b[(j + 1) % 3], &eb[j], t),
        ),
        Feature::VertexOfB(j, n, k) => (b[j] - n * k, b[j]),
        Feature::VertexOfA(i, n, k) => (a[i], a[i] - n * k),
    };
    ClosestPoints {
        distance: separation(a, b, &gap, d2),
        p,
        q,
    }
}

/// The answer for a vertex over a face: squared distance, gap `p - q`, and the points.
#[inline]
fn vertex_face(a: &Tri, b: &Tri, d2: f64, gap: Vec3, p: Vec3, q: Vec3) -> ClosestPoints {
    ClosestPoints {
        distance: separation(a, b, &gap, d2),
        p,
        q,
    }
}

/// The distance of triangles found apart, from their closest points' gap and its squared length:
/// never 0, which is kept for triangles that share a point (decided exactly). A gap that rounds to
/// 0 is below the rounding of the coordinates: it is reported as one rounding of them.
#[inline]
fn separation(a: &Tri, b: &Tri, gap: &Vec3, d2: f64) -> f64 {
    let distance = length(gap, d2);
    if distance > 0.0 {
        distance
    } else {
        below_rounding(a, b)
    }
}

#[cold]
#[inline(never)]
fn below_rounding(a: &Tri, b: &Tri) -> f64 {
    let m = max_abs(&[&a[0], &a[1], &a[2], &b[0], &b[1], &b[2]]);
    (f64::EPSILON * m).max(f64::from_bits(1))
}

/// The plane of a triangle `t` and the other triangle's vertices relative to it.
struct Face {
    /// `(t1 - t0) x (t2 - t0)`, accurate also for slivers; zero for a degenerate triangle.
    n: Vec3,
    nn: f64,
    /// `n . (v - t0)` for the other triangle's vertices `v`.
    o: [f64; 3],
}

impl Face {
    /// From the float normal and orientations of the contact test (`n`, `o`); `e`, `l` are `t`'s
    /// edge vectors and squared lengths.
    #[inline]
    fn new(t: &Tri, e: &[Vec3; 3], l: &[f64; 3], n: &Vec3, o: &[f64; 3], pts: &Tri) -> Face {
        let nn = n.norm_squared();
        if nn > 1e-6 * l[0] * l[2] {
            return Face { n: *n, nn, o: *o };
        }
        // A sliver (or degenerate) face: the float normal may be tilted by rounding; redo it
        // accurately. A truly degenerate face gets nn = 0 and is covered by its edges.
        let n = face_normal(&e[0], &(-e[2]));
        Face {
            n,
            nn: n.norm_squared(),
            o: pts.map(|v| n.dot(&(v - t[0]))),
        }
    }

    /// The vertex of `pts` nearest to the face among those whose projection falls inside it, if
    /// nearer than `best` (squared): `(squared distance, index, k)`, its foot being
    /// `pts[i] - n * k`.
    #[inline]
    fn nearest_vertex_over(
        &self,
        t: &Tri,
        e: &[Vec3; 3],
        pts: &Tri,
        best: f64,
    ) -> Option<(f64, usize, f64)> {
        if self.nn == 0.0 {
            return None;
        }
        let mut frame = None;
        let mut found = None;
        let mut best = best;
        for (i, (o, v)) in self.o.iter().zip(pts).enumerate() {
            // `o / nn` before the product: o^2 could underflow for tiny triangles.
            let d2 = o * (o / self.nn);
            if d2 < best {
                let f =
                    frame.get_or_insert_with(|| FaceFrame::new(&e[0], &(-e[2]), &self.n, self.nn));
                if let Some(h) = f.projection(&(v - t[0])) {
                    let k = h / self.nn;
                    best = h * k;
                    found = Some((best, i, k));
                }
            }
        }
        found
    }

    /// When all of `pts` are strictly on one side and the nearest to the plane projects inside the
    /// face, `(squared distance, index, k)` as in [`Face::nearest_vertex_over`].
    #[inline]
    fn nearest_vertex_if_one_side(
        &self,
        t: &Tri,
        e: &[Vec3; 3],
        pts: &Tri,
    ) -> Option<(f64, usize, f64)> {
        let [o0, o1, o2] = self.o;
        let one_side = o0 > 0.0 && o1 > 0.0 && o2 > 0.0 || o0 < 0.0 && o1 < 0.0 && o2 < 0.0;
        if !one_side || self.nn == 0.0 {
            return None;
        }
        let (a0, a1, a2) = (o0.abs(), o1.abs(), o2.abs());
        let i = if a0 <= a1 && a0 <= a2 {
            0
        } else if a1 <= a2 {
            1
        } else {
            2
        };
        let h = FaceFrame::new(&e[0], &(-e[2]), &self.n, self.nn).projection(&(pts[i] - t[0]))?;
        let k = h / self.nn;
        Some((h * k, i, k))
    }

    /// For each edge `(j, j + 1)` of the other triangle, a lower bound on its squared distance to
    /// this triangle: the squared distance of its nearer end to the plane when both ends are
    /// strictly on one side, else 0.
    #[inline]
    fn edge_bounds(&self) -> [f64; 3] {
        let mut out = [0.0; 3];
        if self.nn == 0.0 {
            return out;
        }
        for (j, b) in out.iter_mut().enumerate() {
            let (x, y) = (self.o[j], self.o[(j + 1) % 3]);
            if x > 0.0 && y > 0.0 || x < 0.0 && y < 0.0 {
                let m = x.abs().min(y.abs());
                *b = m * (m / self.nn);
            }
        }
        out
    }
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Lcg;

    fn point(rng: &mut Lcg, scale: f64) -> Vec3 {
        Vec3::new(rng.signed(), rng.signed(), rng.signed()) * scale
    }

    /// A pair of triangles: random ones, or nearly parallel ones facing each other across a gap
    /// (where the planes settle most pairs), at coordinates from tiny to huge.
    fn pair(rng: &mut Lcg, k: usize) -> (Tri, Tri) {
        let scale = [1.0, 1e-160, 1e160, 1e3][k % 4];
        let a: Tri = [0, 1, 2].map(|_| point(rng, 1.0));
        let b = if k.is_multiple_of(3) {
            [0, 1, 2].map(|_| point(rng, 1.0))
        } else {
            let n = (a[1] - a[0]).cross(&(a[2] - a[0])).normalize();
            let lift = n * (0.01 + rng.unit());
            a.map(|v| v + lift + point(rng, 0.2))
        };
        let (a, b) = (a.map(|v| v * scale), b.map(|v| v * scale));
        if k.is_multiple_of(2) { (a, b) } else { (b, a) }
    }

    /// Below the cutoff the answer is the exact one; beyond it, either the exact one or the word
    /// that the triangles are at least that far apart.
    #[test]
    fn below_the_cutoff_exact_beyond_maybe_apart() {
        let mut rng = Lcg(31);
        let (mut beyond, mut apart) = (0, 0);
        for k in 0..20000 {
            let (a, b) = pair(&mut rng, k);
            let exact = tri_distance(&a, &b);
            let cutoff = exact.distance * (0.5 + rng.unit());
            let first = [Plane::A, Plane::B][k % 2];
            match tri_distance_below(&a, &b, cutoff, first, false) {
                Near::Closest(c) => assert_eq!(c, exact, "case {k}"),
                Near::Apart(_) => {
                    apart += 1;
                    assert!(exact.distance >= cutoff, "case {k}: {cutoff} {exact:?}");
                }
            }
            beyond += usize::from(exact.distance >= cutoff);
        }
        // The planes do settle pairs (the point of the cutoff), most of the facing ones.
        assert!(apart > beyond / 3, "{apart} of {beyond}");
    }

    /// The cached plane's test: never apart below the cutoff (pairs at and a hair around it, and
    /// at a zero cutoff), and apart for the facing pairs that `tri_distance_below` shows apart by
    /// `b`'s plane, but for a few roundings.
    #[test]
    fn planed_tri_apart_is_sound_and_agrees() {
        let mut rng = Lcg(41);
        let (mut both, mut only_below) = (0, 0);
        for k in 0..20000 {
            let (a, b) = pair(&mut rng, k);
            // As a search's `in_range`: no rescaling (the planes are then the same).
            let in_range =
                kernel_rescale(max_abs(&[&a[0], &a[1], &a[2], &b[0], &b[1], &b[2]])).is_none();
            let planed = PlanedTri::new(b);
            let exact = tri_distance(&a, &b).distance;
            for f in [0.0, 0.5, 1.0 - 1e-15, 1.0, 1.0 + 1e-15, 1.0 + 1e-12] {
                let cutoff = exact * f;
                if planed.apart(&a, cutoff) {
                    assert!(
                        exact >= cutoff * (1.0 - 1e-13),
                        "case {k}: {exact} {cutoff}"
                    );
                }
            }
            if in_range {
                let cutoff = exact * 0.5;
                let below = matches!(
                    tri_distance_below(&a, &b, cutoff, Plane::B, false),
                    Near::Apart(Plane::B)
                );
                match (below, planed.apart(&a, cutoff)) {
                    (true, true) => both += 1,
                    (true, false) => only_below += 1,
                    (false, fast) => assert!(!fast, "case {k}"),
                }
            }
        }
        assert!(both > 1000 && only_below == 0, "{both} {only_below}");
    }

    /// Pairs a hair beyond the cutoff: whether they are called apart or not, never one nearer.
    #[test]
    fn apart_is_never_called_below_the_cutoff() {
        let mut rng = Lcg(37);
        for k in 0..20000 {
            let (a, b) = pair(&mut rng, k);
            let exact = tri_distance(&a, &b).distance;
            for f in [1.0 - 1e-15, 1.0, 1.0 + 1e-15, 1.0 + 1e-12] {
                let cutoff = exact * f;
                let first = [Plane::A, Plane::B][k % 2];
                if let Near::Apart(_) = tri_distance_below(&a, &b, cutoff, first, false) {
                    assert!(
                        exact >= cutoff * (1.0 - 1e-13),
                        "case {k}: {exact} {cutoff}"
                    );
                }
            }
        }
    }
}
