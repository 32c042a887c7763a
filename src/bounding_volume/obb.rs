use super::ssv_fit::REFIT_SLACK;
use super::{BoundingVolume, OverlapVolume};
use crate::geometry::Tri;
use crate::math::{Mat3, RelPose, UNDERFLOW_SLACK, Vec3, least, most};

/// Oriented bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb {
    /// Orthonormal axes (columns) in the model frame.
    pub axes: Mat3,
    /// Centre, in the model frame.
    pub center: Vec3,
    /// Half extents along the axes.
    pub half: Vec3,
}

/// A box posed in another model's frame (see [`OverlapVolume::pose`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PosedObb {
    /// The axes (columns) in the other frame.
    axes: Mat3,
    /// The centre in the other frame.
    center: Vec3,
    /// Half extents along the axes.
    half: Vec3,
    /// The magnitudes its coordinates were computed from, for the rounding allowance.
    magnitude: f64,
}

/// Rounding allowance of the separation test, relative to the magnitudes that enter it. It also
/// keeps near-parallel edge pairs, whose cross-product axis is nearly zero and all of whose terms are
/// rounding noise, from ever separating overlapping boxes.
/// `|v.x| + |v.y| + |v.z|` (plainly: the generic componentwise form costs more here).
#[inline(always)]
fn abs_sum(v: &Vec3) -> f64 {
    v.x.abs() + v.y.abs() + v.z.abs()
}

const OVERLAP_SLACK: f64 = 64.0 * f64::EPSILON;

impl Obb {
    /// `p` in box coordinates (relative to the centre).
    #[inline]
    fn local(&self, p: &Vec3) -> Vec3 {
        self.axes.tr_mul(&(p - self.center))
    }
}

impl Obb {
    /// The tightest box on the given axes (orthonormal right-handed columns) that contains every
    /// point of `points` (not empty).
    pub fn fit(axes: &Mat3, points: &[Vec3]) -> Self {
        let Some(first) = points.first() else {
            // The builder never asks for this; an empty box at the origin rather than NaNs.
            return Obb {
                axes: *axes,
                center: Vec3::zeros(),
                half: Vec3::zeros(),
            };
        };
        let q = axes.tr_mul(first);
        let (mut lo, mut hi) = (q, q);
        for p in points {
            let q = axes.tr_mul(p);
            lo = lo.inf(&q);
            hi = hi.sup(&q);
        }
        Obb::from_bounds(axes, &lo, &hi).cover(points)
    }

    /// The box on `axes` spanning `lo` to `hi` (frame coordinates), before [`cover`](Obb::cover).
    #[inline]
    pub(crate) fn from_bounds(axes: &Mat3, lo: &Vec3, hi: &Vec3) -> Self {
        // Halve before adding: no overflow whatever the magnitudes.
        let mid = lo * 0.5 + hi * 0.5;
        Obb {
            axes: *axes,
            center: axes * mid,
            half: (hi * 0.5 - lo * 0.5).sup(&Vec3::zeros()),
        }
    }

    /// Rounding of the centre may leave a point a few ulps out: takes the extents up to the offsets
    /// exactly as `contains` measures them.
    #[inline]
    pub(crate) fn cover(mut self, points: &[Vec3]) -> Self {
        for p in points {
            self.cover_point(p);
        }
        self
    }

    /// The box on `axes` (orthonormal right-handed columns) around `points` and `boxes` (not both
    /// empty): what a refit puts around a node's children, a triangle's vertices or a child's box.
    /// The points are covered exactly as `contains` measures them; for boxes the extents get an
    /// allowance for rounding (about 1e-13 of the box's magnitudes), so that every point a child
    /// box contains, as its `contains` measures it, this one contains as its own measures it.
    pub(crate) fn enclosing(axes: &Mat3, points: &[Vec3], boxes: &[Obb]) -> Self {
        let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
        for p in points {
            let q = axes.tr_mul(p);
            lo = lo.inf(&q);
            hi = hi.sup(&q);
        }
        for b in boxes {
            // The child's extents along each of these axes: its centre's projection plus its
            // half extents along the child's axes, projected.
            let c = axes.tr_mul(&b.center);
            let e = axes.tr_mul(&b.axes).abs() * b.half;
            lo = lo.inf(&(c - e));
            hi = hi.sup(&(c + e));
        }
        let mut obb = Obb::from_bounds(axes, &lo, &hi).cover(points);
        if !boxes.is_empty() {
            let margin = REFIT_SLACK * (abs_sum(&obb.center) + obb.half.sum()) + UNDERFLOW_SLACK;
            obb.half = obb.half.add_scalar(margin);
        }
        obb
    }

    /// [`cover`](Obb::cover) for one point.
    #[inline(always)]
    pub(crate) fn cover_point(&mut self, p: &Vec3) {
        self.half = self.half.sup(&self.local(p).abs());
    }
}

impl BoundingVolume for Obb {
    fn contains(&self, p: &Vec3, eps: f64) -> bool {
        let q = self.local(p);
        q.x.abs() <= self.half.x + eps
            && q.y.abs() <= self.half.y + eps
            && q.z.abs() <= self.half.z + eps
    }

    fn size(&self) -> f64 {
        self.half.norm() * 2.0
    }
}

impl OverlapVolume for Obb {
    type Posed = PosedObb;

    #[inline]
    fn pose(b: &Self, rel: &RelPose) -> PosedObb {
        PosedObb {
            axes: rel.rot * b.axes,
            center: rel.apply(&b.center),
            half: b.half,
            magnitude: abs_sum(&b.center) + abs_sum(&rel.trans) + b.half.sum(),
        }
    }

    /// Separating axis test on the 15 candidate axes: the 3 face normals of each box and the 9 cross
    /// products of an edge of each. Every test allows a rounding slack, so touching boxes overlap.
    ///
    /// Most boxes a search tests overlap (about 60% on the bunny), so every axis is usually
    /// evaluated: the axes go in three groups (a's faces, b's faces, the edge pairs), each
    /// evaluated whole and decided by one branch, with no branch per axis; the arithmetic of a
    /// group is straight-line and vectorizes.
    #[inline]
    fn overlap_posed(a: &Self, b: &PosedObb, _rel: &RelPose) -> bool {
        let (ha, hb) = (&a.half, &b.half);
        // Work in a's box frame: b's axes are the columns of R = A^T B', its centre is t (B' and
        // the centre posed in a's model frame once, for all the boxes b is tested against).
        let d = b.center - a.center;
        let slack = OVERLAP_SLACK * (abs_sum(&a.center) + ha.sum() + b.magnitude) + UNDERFLOW_SLACK;
        let (axes, baxes) = (&a.axes, &b.axes);
        // Row i of R (a's axis i against b's axes), its absolute values, and t[i].
        let row = |i: usize| {
            let c = axes.column(i);
            [
                c.dot(&baxes.column(0)),
                c.dot(&baxes.column(1)),
                c.dot(&baxes.column(2)),
            ]
        };
        let r = [row(0), row(1), row(2)];
        let ar = r.map(|x| x.map(f64::abs));
        let t = [
            axes.column(0).dot(&d),
            axes.column(1).dot(&d),
            axes.column(2).dot(&d),
        ];
        let (ha, hb) = ([ha.x, ha.y, ha.z], [hb.x, hb.y, hb.z]);
        // a's face normals.
        let mut apart = false;
        for i in 0..3 {
            let rb = ar[i][0] * hb[0] + ar[i][1] * hb[1] + ar[i][2] * hb[2];
            apart |= t[i].abs() > ha[i] + rb + slack;
        }
        if apart {
            return false;
        }
        // b's face normals.
        for j in 0..3 {
            let proj = r[0][j] * t[0] + r[1][j] * t[1] + r[2][j] * t[2];
            let ra = ar[0][j] * ha[0] + ar[1][j] * ha[1] + ar[2][j] * ha[2];
            apart |= proj.abs() > ra + hb[j] + slack;
        }
        if apart {
            return false;
        }
        // Edge pairs: axis a_i x b_j. In a's frame its components are e_i x R.col(j); its products
        // with b's axes are +-R[i][j'], with a's +-R[i'][j].
        const NEXT: [(usize, usize); 3] = [(1, 2), (2, 0), (0, 1)];
        for (i, &(i1, i2)) in NEXT.iter().enumerate() {
            for (j, &(j1, j2)) in NEXT.iter().enumerate() {
                let proj = t[i2] * r[i1][j] - t[i1] * r[i2][j];
                let ra = ha[i1] * ar[i2][j] + ha[i2] * ar[i1][j];
                let rb = hb[j1] * ar[i][j2] + hb[j2] * ar[i][j1];
                apart |= proj.abs() > ra + rb + slack;
            }
        }
        !apart
    }

    /// Separating axis test of a box and a triangle on the 13 candidate axes: the box's 3 face
    /// normals, the triangle's normal, and the 9 cross products of a box axis and a triangle edge.
    /// Each test allows a rounding slack in proportion to the axis, so touching counts as overlap.
    /// As in the box-box test, the axes go in groups decided by one branch each.
    #[inline]
    fn overlap_triangle(a: &Self, t: &Tri) -> Option<bool> {
        let h = &a.half;
        let v = [a.local(&t[0]), a.local(&t[1]), a.local(&t[2])];
        let scale = abs_sum(&a.center) + abs_sum(&t[0]) + abs_sum(&t[1]) + abs_sum(&t[2]) + h.sum();
        let slack = OVERLAP_SLACK * scale + UNDERFLOW_SLACK;
        // Whether the projections `p` of the triangle's vertices on an axis miss the box's,
        // `[-r, r]`, by more than `s`. (Coordinates are finite: plain selects for min and max.)
        let misses = |p: [f64; 3], r: f64, s: f64| {
            let lo = least(least(p[0], p[1]), p[2]);
            let hi = most(most(p[0], p[1]), p[2]);
            (lo > r + s) | (hi < -r - s)
        };
        let mut apart = false;
        for i in 0..3 {
            apart |= misses([v[0][i], v[1][i], v[2][i]], h[i], slack);
        }
        if apart {
            return Some(false);
        }
        let e = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
        let n = e[0].cross(&e[1]);
        let p = [n.dot(&v[0]), n.dot(&v[1]), n.dot(&v[2])];
        if misses(p, h.dot(&n.abs()), slack * abs_sum(&n)) {
            return Some(false);
        }
        // An axis with components `x` at index `j` and `y` at index `k > j`, 0 at the third: the
        // products with the 0 left out (a float product with 0 is not folded away by the
        // compiler), which changes no value.
        let apart2 = |j: usize, x: f64, k: usize, y: f64| {
            let p = |w: &Vec3| w[j] * x + w[k] * y;
            let r = h[j] * x.abs() + h[k] * y.abs();
            misses(
                [p(&v[0]), p(&v[1]), p(&v[2])],
                r,
                slack * (x.abs() + y.abs()),
            )
        };
        for edge in &e {
            // e_i x edge for the box axes e_i: (0, -z, y), (z, 0, -x), (-y, x, 0).
            apart |= apart2(1, -edge.z, 2, edge.y)
                | apart2(0, edge.z, 2, -edge.x)
                | apart2(0, -edge.y, 1, edge.x);
        }
        Some(!apart)
    }
}
