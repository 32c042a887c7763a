//! Exact distance between two rectangles in space: the kernel of the swept-sphere volumes (a point
//! swept sphere is a rectangle with both sides 0, a line swept sphere one with a side 0).
//!
//! Why it is exact: if two rectangles are disjoint, a closest pair can be taken with one of its points
//! on an edge (were both interior, the pair could slide in the common parallel planes until one
//! reached an edge); if they meet, the meeting set is convex and reaches an edge of one of them. So the
//! distance is the least of the eight edge-to-other-rectangle distances.
//!
//! Each of those is a one-dimensional convex problem: along an edge `p + t d`, the squared distance to
//! an axis-aligned rectangle is a C1 convex piecewise quadratic in `t`, whose derivative is
//! `(x(t) - clamp(x(t))) . d`, piecewise linear with knots where the edge crosses the lines bounding
//! the rectangle. The minimum is at an end, or where that derivative changes sign, found exactly
//! by bracketing between knots and interpolating linearly.
//!
//! Most pairs never get there: a corner and its nearest point on the other rectangle are a closest
//! pair when each is the other's nearest point (a certificate checked with two dot products), which
//! settles every configuration whose closest points include a corner. Only edge-edge configurations
//! go through the edges, and an edge is looked at only if a bound from its ends' offsets leaves it
//! room to beat the best corner.

use crate::math::{Mat3, Vec3, avx2_or_portable, least, most};

/// Distance between two rectangles (or less, see `cutoff` and `enough` below), with a separating
/// axis that shows it.
///
/// Rectangle A is `[0, la[0]] x [0, la[1]] x {0}` in its own frame. Rectangle B is
/// `{ t + s r.col(0) + u r.col(1) : s in [0, lb[0]], u in [0, lb[1]] }`: `r` holds B's axes (orthonormal
/// columns, the third being its normal) and `t` its corner, both in A's frame. Sides must be `>= 0`.
///
/// Three parameters let a caller that needs less than the exact distance skip work:
/// - `cutoff`: when the distance is at least `cutoff`, any lower bound no less than `cutoff` may be
///   returned (a search that prunes such pairs needs no more). The gap between the boxes around
///   each rectangle in the other's frame often settles it, and the edge searches then need only
///   beat `cutoff`. `f64::INFINITY`: no cutoff.
/// - `enough`: the search may stop at the first candidate pair at most `enough` apart and return
///   its distance (an upper bound of the true one, itself at most `enough`): an overlap test needs
///   no more. 0: exact.
/// - `exact`: false when a distance below `cutoff` need only come back as some lower bound of it
///   (a depth-first search expands such a pair whatever its bound): once a corner of either
///   rectangle is seen nearer than `cutoff` to the other, the gap between A and the box around B
///   comes back, without the certificates or the edges. Whether the answer is below `cutoff` is
///   the same either way.
///
/// The axis `n` (in A's frame, pointing from A towards B; not normalized) is one along which the
/// rectangles' projections are at least the returned value apart (the vector between closest
/// points at a corner, or between the boxes that gave a gap), so that someone who moves B can
/// bound the new distance from how far B's points move along `n`. It is zero when none is given:
/// `enough` stopped the search, or the edges decided (their answer is either below `cutoff`,
/// which a search does not prune, or `cutoff` itself, which no axis shows).
#[inline(always)]
pub(crate) fn rect_distance(
    r: &Mat3,
    t: &Vec3,
    la: [f64; 2],
    lb: [f64; 2],
    enough: f64,
    cutoff: f64,
    exact: bool,
) -> (f64, Vec3) {
    let enough2 = enough * enough;
    // B in A's frame: corners 0, u, v, u + v from `t`, and their offsets from A.
    let u: Vec3 = r.column(0) * lb[0];
    let v: Vec3 = r.column(1) * lb[1];
    let qb = [*t, t + u, t + v, t + u + v];
    let cut2 = cutoff * cutoff;
    let gap_b = box_gap(&qb, la);
    let gap_b2 = gap_b.norm_squared();
    if gap_b2 >= cut2 {
        return (gap_b2.sqrt(), gap_b);
    }
    let rb = [
        offset(&qb[0], la),
        offset(&qb[1], la),
        offset(&qb[2], la),
        offset(&qb[3], la),
    ];
    let (ib, db) = nearest(&rb);
    if !exact & (db < cut2) {
        // A corner nearer than the cutoff: so is the distance, and the box gap bounds it (no axis
        // comes: a pair below the cutoff is not pruned).
        return (gap_b2.sqrt(), Vec3::zeros());
    }
    // A corner and its nearest point on the other rectangle are a closest pair when that point is
    // also nearest to the corner on the corner's own rectangle, that is when both of the corner's
    // edges lead away from it: a plane through each, normal to the offset, then separates the
    // rectangles. That settles every pair whose nearest points include a corner (a touching corner
    // too: its offset is zero). The certificate is global, so b's nearest corner is tried before a
    // is even placed in b's frame.
    // Both tests evaluated, one branch: it goes either way unpredictably.
    if (db <= enough2) | leads_away(&rb[ib], ib, &u, &v) {
        // The offset is the axis, unless `enough` stopped the search: then the value is not a
        // lower bound, and no axis comes (zeroed by a product: a branch costs more).
        return (db.sqrt(), rb[ib] * beyond(db, enough2));
    }

    // A in B's frame (x_B = r^T (x_A - t)): A's axes there are the rows of `r`.
    let ta = -r.tr_mul(t);
    let ua = Vec3::new(r[(0, 0)], r[(0, 1)], r[(0, 2)]) * la[0];
    let va = Vec3::new(r[(1, 0)], r[(1, 1)], r[(1, 2)]) * la[1];
    let pa = [ta, ta + ua, ta + va, ta + ua + va];
    let ra = [
        offset(&pa[0], lb),
        offset(&pa[1], lb),
        offset(&pa[2], lb),
        offset(&pa[3], lb),
    ];
    let (ia, da) = nearest(&ra);
    if !exact & (da < cut2) {
        // As for b's corners above.
        return (gap_b2.sqrt(), Vec3::zeros());
    }
    // A's offsets point from B to A in B's frame: `-r o` is the axis in A's frame.
    if (da < db) & ((da <= enough2) | leads_away(&ra[ia], ia, &ua, &va)) {
        return (da.sqrt(), -(r * ra[ia]) * beyond(da, enough2));
    }
    let gap_a = box_gap(&pa, lb);
    let gap_a2 = gap_a.norm_squared();
    if gap_a2 >= cut2 {
        return (gap_a2.sqrt(), -(r * gap_a));
    }
    // Below the cutoff the answer is exact; at or above it, any value in [cutoff, distance] will
    // do, so the edges need only beat the cutoff. No axis comes from here: an exact answer below
    // the cutoff is not pruned, and the cutoff itself has no axis to show it.
    let best = least(least(db, da), cut2);
    let b = Corners {
        p: qb,
        u,
        v,
        o: rb,
        l: la,
    };
    let a = Corners {
        p: pa,
        u: ua,
        v: va,
        o: ra,
        l: lb,
    };
    if exact {
        return (edges::<true>(&b, &a, best).sqrt(), Vec3::zeros());
    }
    // Loose: whether some edge comes nearer than the cutoff is all that counts; if one does, the
    // larger box gap bounds the distance.
    if edges::<false>(&b, &a, best) < cut2 {
        (most(gap_a2, gap_b2).sqrt(), Vec3::zeros())
    } else {
        (cutoff, Vec3::zeros())
    }
}

/// A rectangle's corners `p` (`p[0]`, `+ u`, `+ v`, `+ u + v`) in the other's frame, their offsets
/// `o` from the other, and the other's sides `l`.
struct Corners {
    p: [Vec3; 4],
    u: Vec3,
    v: Vec3,
    o: [Vec3; 4],
    l: [f64; 2],
}

/// The least of `best` and the squared distances of the edges of each rectangle to the other.
/// Apart from the rest of the kernel (which rarely gets here), so that its registers do not
/// weigh on the common paths; compiled for AVX2 too, as the kernel (see `math::use_avx2`).
#[inline(always)]
fn edges<const ALL: bool>(b: &Corners, a: &Corners, best: f64) -> f64 {
    avx2_or_portable(
        #[inline(always)]
        move || edges_body::<ALL>(b, a, best),
    )
}

/// What [`edges`] computes.
#[inline(always)]
fn edges_body<const ALL: bool>(b: &Corners, a: &Corners, best: f64) -> f64 {
    // The edges of b against a, then those of a against b (unrolled: each call site keeps its
    // own branch history). Without `ALL`, it stops at the first edge below `best`.
    let mut m = edge_min(&b.p[0], &b.u, &b.o[0], &b.o[1], b.l, best);
    if !ALL && m < best {
        return m;
    }
    m = edge_min(&b.p[2], &b.u, &b.o[2], &b.o[3], b.l, m);
    if !ALL && m < best {
        return m;
    }
    m = edge_min(&b.p[0], &b.v, &b.o[0], &b.o[2], b.l, m);
    if !ALL && m < best {
        return m;
    }
    m = edge_min(&b.p[1], &b.v, &b.o[1], &b.o[3], b.l, m);
    if !ALL && m < best {
        return m;
    }
    m = edge_min(&a.p[0], &a.u, &a.o[0], &a.o[1], a.l, m);
    if !ALL && m < best {
        return m;
    }
    m = edge_min(&a.p[2], &a.u, &a.o[2], &a.o[3], a.l, m);
    if !ALL && m < best {
        return m;
    }
    m = edge_min(&a.p[0], &a.v, &a.o[0], &a.o[2], a.l, m);
    if !ALL && m < best {
        return m;
    }
    edge_min(&a.p[1], &a.v, &a.o[1], &a.o[3], a.l, m)
}

/// The gap between the rectangle `[0, l[0]] x [0, l[1]] x {0}` and the box around four points, as
/// the vector from the one to the other (zero where they overlap): its length is a lower bound on
/// the distance between anything spanned by the points and the rectangle, and it is an axis along
/// which they are that far apart.
#[inline(always)]
fn box_gap(q: &[Vec3; 4], l: [f64; 2]) -> Vec3 {
    // Per coordinate, plain comparisons: the generic componentwise min/max cost several times as
    // much here.
    Vec3::new(
        span_gap(q, 0, l[0]),
        span_gap(q, 1, l[1]),
        span_gap(q, 2, 0.0),
    )
}

/// How far the points' coordinate `k` spans beyond `[0, hi_k]`, signed by the side (at most one of
/// the two differences is positive). A function rather than a closure: the closure was not inlined.
#[inline(always)]
fn span_gap(q: &[Vec3; 4], k: usize, hi_k: f64) -> f64 {
    let lo = least(least(q[0][k], q[1][k]), least(q[2][k], q[3][k]));
    let hi = most(most(q[0][k], q[1][k]), most(q[2][k], q[3][k]));
    most(lo - hi_k, 0.0) - most(-hi, 0.0)
}

/// 1 when `x > y`, else 0.
#[inline(always)]
fn beyond(x: f64, y: f64) -> f64 {
    f64::from(u8::from(x > y))
}

/// `p` minus its nearest point on the rectangle `[0, l[0]] x [0, l[1]] x {0}`.
#[inline(always)]
fn offset(p: &Vec3, l: [f64; 2]) -> Vec3 {
    // Comparisons rather than clamp: no panic whatever the input.
    Vec3::new(
        p.x - least(most(p.x, 0.0), l[0]),
        p.y - least(most(p.y, 0.0), l[1]),
        p.z,
    )
}

/// Index and squared length of the shortest of four offsets.
#[inline(always)]
fn nearest(o: &[Vec3; 4]) -> (usize, f64) {
    let n = [
        o[0].norm_squared(),
        o[1].norm_squared(),
        o[2].norm_squared(),
        o[3].norm_squared(),
    ];
    let (i01, n01) = if n[1] < n[0] { (1, n[1]) } else { (0, n[0]) };
    let (i23, n23) = if n[3] < n[2] { (3, n[3]) } else { (2, n[2]) };
    if n23 < n01 { (i23, n23) } else { (i01, n01) }
}

/// Whether both edges of a rectangle leaving its corner `i` (of `c`, `c + u`, `c + v`, `c + u + v`)
/// go away from the point the corner's offset `o` points from.
#[inline(always)]
fn leads_away(o: &Vec3, i: usize, u: &Vec3, v: &Vec3) -> bool {
    let (su, sv) = (o.dot(u), o.dot(v));
    let along_u = if i & 1 == 0 { su >= 0.0 } else { su <= 0.0 };
    let along_v = if i & 2 == 0 { sv >= 0.0 } else { sv <= 0.0 };
    along_u & along_v
}

/// The least of `best` and the squared distance from the interior of the edge `p + s d` (`s` in
/// `[0, 1]`) to the rectangle `[0, l[0]] x [0, l[1]] x {0}`; `o0`, `o1` are the offsets of its ends,
/// whose distances are already in `best`.
#[inline(always)]
fn edge_min(p: &Vec3, d: &Vec3, o0: &Vec3, o1: &Vec3, l: [f64; 2], best: f64) -> f64 {
    // Slope of the squared distance (halved) at the ends: the minimum is at an end unless it goes
    // from negative to positive.
    let g0 = o0.dot(d);
    let g1 = o1.dot(d);
    if g0 >= 0.0 || g1 <= 0.0 {
        return best;
    }
    // Each coordinate's offset keeps its sign along the edge when both ends have it, and then never
    // drops below the smaller end's: a lower bound for the whole edge.
    let gap = |a: f64, b: f64| {
        let m = least(a.abs(), b.abs());
        if a * b > 0.0 { m } else { 0.0 }
    };
    let (gx, gy, gz) = (gap(o0.x, o1.x), gap(o0.y, o1.y), gap(o0.z, o1.z));
    if gx * gx + gy * gy + gz * gz >= best {
        return best;
    }
    // Bracket the sign change of the slope between the knots nearest to it; the slope is linear
    // between consecutive knots, and monotone overall, so a knot outside the current bracket never
    // matters.
    let (mut s_lo, mut g_lo, mut s_hi, mut g_hi) = (0.0, g0, 1.0, g1);
    let mut knot = |s: f64, k: usize| {
        if s > s_lo && s < s_hi {
            // At the knot, coordinate `k` is on the rectangle's border: its offset is 0. Computed,
            // it is a rounding residual, which times a long edge's slope can outweigh the slope of
            // an edge nearly parallel to the rectangle and move the minimum far along the edge.
            let mut o = offset(&(p + d * s), l);
            o[k] = 0.0;
            let g = o.dot(d);
            if g < 0.0 {
                (s_lo, g_lo) = (s, g);
            } else {
                (s_hi, g_hi) = (s, g);
            }
        }
    };
    if d.x != 0.0 {
        let inv = 1.0 / d.x;
        knot(-p.x * inv, 0);
        knot((l[0] - p.x) * inv, 0);
    }
    if d.y != 0.0 {
        let inv = 1.0 / d.y;
        knot(-p.y * inv, 1);
        knot((l[1] - p.y) * inv, 1);
    }
    // g_lo < 0 <= g_hi, so the fraction is in [0, 1].
    let s = s_lo + (s_hi - s_lo) * (-g_lo / (g_hi - g_lo));
    least(best, offset(&(p + d * s), l).norm_squared())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::{Random, Rng};
    use nalgebra::{Rotation3, Unit};

    /// Case `k` of a random pair of rectangles (B's axes and corner in A's frame, the sides), at
    /// one of three spreads, some of them segments.
    fn random_pair(rng: &mut Rng, k: usize) -> (Mat3, Vec3, [f64; 2], [f64; 2]) {
        let axis = Unit::new_normalize(Vec3::new(rng.signed(), rng.signed(), rng.signed() + 1e-3));
        let r: Mat3 = Rotation3::from_axis_angle(&axis, 4.0 * rng.signed()).into_inner();
        let t = Vec3::new(rng.signed(), rng.signed(), rng.signed()) * [0.1, 1.0, 3.0][k % 3];
        let la = [
            rng.signed().abs(),
            if k.is_multiple_of(5) {
                0.0
            } else {
                rng.signed().abs()
            },
        ];
        let lb = [
            rng.signed().abs(),
            if k.is_multiple_of(7) {
                0.0
            } else {
                rng.signed().abs()
            },
        ];
        (r, t, la, lb)
    }

    /// With a cutoff, the answer is the exact distance when that is below the cutoff, and otherwise
    /// lies between the cutoff and the exact distance: a valid lower bound that a search prunes.
    #[test]
    fn cutoff_answers_exactly_below_and_a_bound_above() {
        let mut rng = Rng(17);
        let (mut below, mut above) = (0, 0);
        for k in 0..20000 {
            let axis =
                Unit::new_normalize(Vec3::new(rng.signed(), rng.signed(), rng.signed() + 1e-3));
            let r: Mat3 = Rotation3::from_axis_angle(&axis, 4.0 * rng.signed()).into_inner();
            let spread = [0.1, 1.0, 3.0][k % 3];
            let t = Vec3::new(rng.signed(), rng.signed(), rng.signed()) * spread;
            // Some sides zero: segments and points are rectangles too.
            let side = |rng: &mut Rng, zero: bool| if zero { 0.0 } else { rng.signed().abs() };
            let la = [side(&mut rng, k % 7 == 0), side(&mut rng, k % 5 == 0)];
            let lb = [side(&mut rng, k % 11 == 0), side(&mut rng, k % 4 == 0)];
            let (exact, _) = rect_distance(&r, &t, la, lb, 0.0, f64::INFINITY, true);
            let cutoff = exact * (0.5 + rng.signed().abs());
            let (got, _) = rect_distance(&r, &t, la, lb, 0.0, cutoff, true);
            if exact < cutoff {
                below += 1;
                assert_eq!(got, exact, "case {k}");
            } else {
                above += 1;
                assert!(
                    got >= cutoff && got <= exact,
                    "case {k}: {got} {cutoff} {exact}"
                );
            }
        }
        assert!(below > 5000 && above > 5000, "{below} {above}");
    }

    /// Without `exact`, an answer below the cutoff is a lower bound of the distance, and it is
    /// below the cutoff exactly when the distance is; at or above the cutoff nothing changes.
    #[test]
    fn loose_answers_bound_below_the_cutoff() {
        let mut rng = Rng(23);
        let (mut below, mut loose, mut above) = (0, 0, 0);
        for k in 0..20000 {
            let (r, t, la, lb) = random_pair(&mut rng, k);
            let (exact, _) = rect_distance(&r, &t, la, lb, 0.0, f64::INFINITY, true);
            let cutoff = exact * (0.5 + rng.signed().abs());
            let (strict, _) = rect_distance(&r, &t, la, lb, 0.0, cutoff, true);
            let (got, _) = rect_distance(&r, &t, la, lb, 0.0, cutoff, false);
            if exact < cutoff {
                below += 1;
                assert!(got >= 0.0 && got <= exact, "case {k}: {got} {exact}");
                loose += usize::from(got < exact);
            } else {
                above += 1;
                assert_eq!(got, strict, "case {k}");
            }
        }
        // The loose answers do come (the point of asking for them), on both sides of the cutoff.
        assert!(below > 5000 && above > 5000, "{below} {above}");
        assert!(loose > below / 4, "{loose} of {below}");
    }

    /// When an axis comes with the answer, the rectangles' projections on it are at least that far
    /// apart (a rectangle's projection spans its corners'), with or without a cutoff.
    #[test]
    fn axis_separates_by_the_answer() {
        let mut rng = Rng(29);
        let (mut given, mut none) = (0, 0);
        for k in 0..20000 {
            let (r, t, la, lb) = random_pair(&mut rng, k);
            let (exact, _) = rect_distance(&r, &t, la, lb, 0.0, f64::INFINITY, true);
            let cutoff = [f64::INFINITY, 0.5 * exact, exact * 1.5][k % 3];
            let (got, n) = rect_distance(&r, &t, la, lb, 0.0, cutoff, true);
            if n == Vec3::zeros() {
                none += 1;
                continue;
            }
            given += 1;
            let n = n.normalize();
            let a = [0.0, la[0]].map(|x| [0.0, la[1]].map(|y| n.dot(&Vec3::new(x, y, 0.0))));
            let b = [0.0, lb[0]]
                .map(|x| [0.0, lb[1]].map(|y| n.dot(&(t + r.column(0) * x + r.column(1) * y))));
            let a_hi = a.as_flattened().iter().fold(f64::MIN, |m, &v| m.max(v));
            let b_lo = b.as_flattened().iter().fold(f64::MAX, |m, &v| m.min(v));
            assert!(
                b_lo - a_hi >= got - 1e-12,
                "case {k}: gap {} < {got}",
                b_lo - a_hi
            );
        }
        // Most answers come with an axis (only the edge searches give none).
        assert!(given > 3 * none, "{given} {none}");
    }
}
