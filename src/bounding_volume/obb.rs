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

/// A box posed in another model's frame (see [`OverlapVolume::pose`]), laid out for the
/// separating axis test: by rows, each a 3-vector padded with a 0 to four lanes, so that the AVX2
/// kernel (see `overlap_posed_avx2`) loads each with one instruction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PosedObb {
    /// Row `k` of the matrix whose columns are the axes in the other frame: the `k`-th coordinate
    /// of each axis.
    rows: [Lanes; 3],
    /// Half extents `[h0, h1, h2]`, then the same rotated by one place, `[h1, h2, h0]`, and by
    /// two, `[h2, h0, h1]`: the products of the edge-pair axes take them so.
    half: [Lanes; 3],
    /// The centre in the other frame.
    center: Vec3,
    /// The magnitudes its coordinates were computed from, for the rounding allowance.
    magnitude: f64,
}

/// Four numbers, aligned for a 256-bit load: a 3-vector and a 0.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
struct Lanes([f64; 4]);

impl Lanes {
    #[inline(always)]
    fn new(x: f64, y: f64, z: f64) -> Lanes {
        Lanes([x, y, z, 0.0])
    }
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
        let m = rel.rot * b.axes;
        let h = &b.half;
        PosedObb {
            rows: [0, 1, 2].map(|k| Lanes::new(m[(k, 0)], m[(k, 1)], m[(k, 2)])),
            half: [
                Lanes::new(h.x, h.y, h.z),
                Lanes::new(h.y, h.z, h.x),
                Lanes::new(h.z, h.x, h.y),
            ],
            center: rel.apply(&b.center),
            magnitude: abs_sum(&b.center) + abs_sum(&rel.trans) + b.half.sum(),
        }
    }

    /// Separating axis test on the 15 candidate axes: the 3 face normals of each box and the 9 cross
    /// products of an edge of each. Every test allows a rounding slack, so touching boxes overlap.
    ///
    /// Most boxes a search tests overlap (about 60% on the bunny), so every axis is usually
    /// evaluated: the axes go in three groups (a's faces, b's faces, the edge pairs), each
    /// evaluated whole, with no branch per axis. Run by a copy written for AVX2 where the
    /// processor has it (`overlap_posed_avx2`: the same operations in the same order, about
    /// half the instructions, which made the collision queries 13-16% faster),
    /// else by the portable `overlap_posed_portable`.
    #[inline]
    fn overlap_posed(a: &Self, b: &PosedObb, _rel: &RelPose) -> bool {
        #[cfg(target_arch = "x86_64")]
        if crate::math::use_avx2() {
            // SAFETY: the processor has AVX2.
            return unsafe { overlap_posed_avx2(a, b) };
        }
        overlap_posed_portable(a, b)
    }

    /// Separating axis test of a box and a triangle on the 13 candidate axes: the box's 3 face
    /// normals, the triangle's normal, and the 9 cross products of a box axis and a triangle edge.
    /// Each test allows a rounding slack in proportion to the axis, so touching counts as overlap.
    /// As in the box-box test, the axes go in groups decided by one branch each, and a copy
    /// written for AVX2 (`overlap_triangle_avx2`, the same operations in the same order) runs
    /// where the processor has it, else `overlap_triangle_portable`.
    #[inline]
    fn overlap_triangle(a: &Self, t: &Tri) -> Option<bool> {
        #[cfg(target_arch = "x86_64")]
        if crate::math::use_avx2() {
            // SAFETY: the processor has AVX2.
            return Some(unsafe { overlap_triangle_avx2(a, t) });
        }
        Some(overlap_triangle_portable(a, t))
    }
}

/// The box-triangle test (see [`Obb::overlap_triangle`]), portable.
#[inline(never)]
fn overlap_triangle_portable(a: &Obb, t: &Tri) -> bool {
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
        return false;
    }
    let e = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    let n = e[0].cross(&e[1]);
    let p = [n.dot(&v[0]), n.dot(&v[1]), n.dot(&v[2])];
    if misses(p, h.dot(&n.abs()), slack * abs_sum(&n)) {
        return false;
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
    !apart
}

/// The box-box test (see [`Obb::overlap_posed`]), portable: a's face normals, then b's, then the
/// nine edge pairs, a group at a time.
#[inline(never)]
fn overlap_posed_portable(a: &Obb, b: &PosedObb) -> bool {
    let (ha, hb) = (&a.half, &b.half[0].0);
    // Work in a's box frame: b's axes are the columns of R = A^T B', its centre is t (B' and
    // the centre posed in a's model frame once, for all the boxes b is tested against).
    let d = b.center - a.center;
    let slack = slack(a, b);
    let axes = &a.axes;
    let brows = b.rows.map(|l| l.0);
    // Row i of R (a's axis i against b's axes), its absolute values, and t[i].
    let row = |i: usize| {
        let c = axes.column(i);
        [0, 1, 2].map(|j| c.x * brows[0][j] + c.y * brows[1][j] + c.z * brows[2][j])
    };
    let r = [row(0), row(1), row(2)];
    let ar = r.map(|x| x.map(f64::abs));
    let t = [
        axes.column(0).dot(&d),
        axes.column(1).dot(&d),
        axes.column(2).dot(&d),
    ];
    let ha = [ha.x, ha.y, ha.z];
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

/// The rounding allowance of a box-box test (the same in both copies of the kernel).
#[inline(always)]
fn slack(a: &Obb, b: &PosedObb) -> f64 {
    OVERLAP_SLACK * (abs_sum(&a.center) + a.half.sum() + b.magnitude) + UNDERFLOW_SLACK
}

/// `overlap_posed_portable` with AVX2 (see `math::use_avx2`): the same operations on the same
/// numbers in the same order, so the same answer, four lanes at a time. The rows of R (a's axis
/// `i` against each of b's) are vectors over b's axes `j`; on them b's face normals and, for each
/// `i`, the three edge pairs `a_i x b_j` take a few vector operations each, with no shuffle but
/// the rotation of a row for the edge pairs' terms in b's half extents. a's face normals want the
/// sums along the rows: a transposition of three vectors. Lane 3 holds zeros (b's rows are
/// padded with 0) and is left out of the verdict.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline(never)]
fn overlap_posed_avx2(a: &Obb, b: &PosedObb) -> bool {
    use std::arch::x86_64::*;
    let load = |l: &Lanes| {
        // SAFETY: `Lanes` are four f64, aligned to 32 bytes.
        unsafe { _mm256_load_pd(l.0.as_ptr()) }
    };
    let slack = slack(a, b);
    let d = b.center - a.center;
    let axes = &a.axes;
    let t = [
        axes.column(0).dot(&d),
        axes.column(1).dot(&d),
        axes.column(2).dot(&d),
    ];
    let ha = [a.half.x, a.half.y, a.half.z];
    let brows = [load(&b.rows[0]), load(&b.rows[1]), load(&b.rows[2])];
    let sign = _mm256_set1_pd(-0.0);
    let abs = |v: __m256d| _mm256_andnot_pd(sign, v);
    // Row i of R: c.x * b_0 + c.y * b_1 + c.z * b_2 lane by lane (the dot products, as above).
    let row = |i: usize| {
        let c = axes.column(i);
        let xy = _mm256_add_pd(
            _mm256_mul_pd(_mm256_set1_pd(c.x), brows[0]),
            _mm256_mul_pd(_mm256_set1_pd(c.y), brows[1]),
        );
        _mm256_add_pd(xy, _mm256_mul_pd(_mm256_set1_pd(c.z), brows[2]))
    };
    let r = [row(0), row(1), row(2)];
    let ar = r.map(abs);
    let hb = load(&b.half[0]);
    let sl = _mm256_set1_pd(slack);
    let tb = t.map(|x| _mm256_set1_pd(x));
    let hab = ha.map(|x| _mm256_set1_pd(x));
    // a's face normals: sums along the rows of |R| times b's half extents, transposed to lanes i.
    let p = ar.map(|x| _mm256_mul_pd(x, hb));
    let zero = _mm256_setzero_pd();
    let (u, v) = (
        _mm256_unpacklo_pd(p[0], p[1]),
        _mm256_unpackhi_pd(p[0], p[1]),
    );
    let (w, x) = (
        _mm256_unpacklo_pd(p[2], zero),
        _mm256_unpackhi_pd(p[2], zero),
    );
    let rb = _mm256_add_pd(
        _mm256_add_pd(
            _mm256_permute2f128_pd::<0x20>(u, w),
            _mm256_permute2f128_pd::<0x20>(v, x),
        ),
        _mm256_permute2f128_pd::<0x31>(u, w),
    );
    let tv = _mm256_set_pd(0.0, t[2], t[1], t[0]);
    let hav = _mm256_set_pd(0.0, ha[2], ha[1], ha[0]);
    let mut apart = _mm256_cmp_pd::<_CMP_GT_OQ>(abs(tv), _mm256_add_pd(_mm256_add_pd(hav, rb), sl));
    // b's face normals: R^T t against |R|^T a's half extents plus b's.
    let proj = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(r[0], tb[0]), _mm256_mul_pd(r[1], tb[1])),
        _mm256_mul_pd(r[2], tb[2]),
    );
    let ra = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(ar[0], hab[0]), _mm256_mul_pd(ar[1], hab[1])),
        _mm256_mul_pd(ar[2], hab[2]),
    );
    apart = _mm256_or_pd(
        apart,
        _mm256_cmp_pd::<_CMP_GT_OQ>(abs(proj), _mm256_add_pd(_mm256_add_pd(ra, hb), sl)),
    );
    if _mm256_movemask_pd(apart) & 7 != 0 {
        return false;
    }
    // Edge pairs a_i x b_j, lanes j, as in the portable copy.
    let (hb1, hb2) = (load(&b.half[1]), load(&b.half[2]));
    const NEXT: [(usize, usize); 3] = [(1, 2), (2, 0), (0, 1)];
    for (i, &(i1, i2)) in NEXT.iter().enumerate() {
        let proj = _mm256_sub_pd(_mm256_mul_pd(tb[i2], r[i1]), _mm256_mul_pd(tb[i1], r[i2]));
        let ra = _mm256_add_pd(
            _mm256_mul_pd(hab[i1], ar[i2]),
            _mm256_mul_pd(hab[i2], ar[i1]),
        );
        // |R[i][j+2]| and |R[i][j+1]| at lane j.
        let ar2 = _mm256_permute4x64_pd::<0b11_01_00_10>(ar[i]);
        let ar1 = _mm256_permute4x64_pd::<0b11_00_10_01>(ar[i]);
        let rb = _mm256_add_pd(_mm256_mul_pd(hb1, ar2), _mm256_mul_pd(hb2, ar1));
        apart = _mm256_or_pd(
            apart,
            _mm256_cmp_pd::<_CMP_GT_OQ>(abs(proj), _mm256_add_pd(_mm256_add_pd(ra, rb), sl)),
        );
    }
    _mm256_movemask_pd(apart) & 7 == 0
}

/// [`overlap_triangle_portable`] with AVX2 (see `math::use_avx2`): the same operations on the
/// same numbers in the same order, so the same answer. The vertices in box coordinates are
/// vectors over the box's axes: its face normals take a minimum and a maximum of three vectors;
/// the nine edge axes, `e_i x edge` for each edge, three at a time (one per box axis `i`), each
/// with its two non-zero components brought to the lanes of the vertices' coordinates they
/// multiply. The triangle's normal is tested on scalars, as in the portable copy. Lane 3 holds
/// zeros and is left out of the verdict.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline(never)]
fn overlap_triangle_avx2(a: &Obb, t: &Tri) -> bool {
    use std::arch::x86_64::*;
    let h = &a.half;
    let scale = abs_sum(&a.center) + abs_sum(&t[0]) + abs_sum(&t[1]) + abs_sum(&t[2]) + h.sum();
    let slack = OVERLAP_SLACK * scale + UNDERFLOW_SLACK;
    let m = &a.axes;
    // Row k of the axes (the k-th coordinate of each axis), and the vertices in box coordinates:
    // lane i the dot product with axis i, as `local` computes it.
    let arow = |k: usize| _mm256_set_pd(0.0, m[(k, 2)], m[(k, 1)], m[(k, 0)]);
    let rows = [arow(0), arow(1), arow(2)];
    let local = |p: &Vec3| {
        let q = p - a.center;
        let xy = _mm256_add_pd(
            _mm256_mul_pd(rows[0], _mm256_set1_pd(q.x)),
            _mm256_mul_pd(rows[1], _mm256_set1_pd(q.y)),
        );
        _mm256_add_pd(xy, _mm256_mul_pd(rows[2], _mm256_set1_pd(q.z)))
    };
    let v = [local(&t[0]), local(&t[1]), local(&t[2])];
    let sign = _mm256_set1_pd(-0.0);
    let abs = |x: __m256d| _mm256_andnot_pd(sign, x);
    let sl = _mm256_set1_pd(slack);
    // Whether the projections `p` (lanes: axes) of the vertices miss `[-r, r]` by more than `s`;
    // minimum and maximum as the portable `least` and `most` select.
    let misses = |p: [__m256d; 3], r: __m256d, s: __m256d| {
        let lo = _mm256_min_pd(_mm256_min_pd(p[0], p[1]), p[2]);
        let hi = _mm256_max_pd(_mm256_max_pd(p[0], p[1]), p[2]);
        let far = _mm256_add_pd(r, s);
        let near = _mm256_sub_pd(_mm256_xor_pd(r, sign), s);
        _mm256_or_pd(
            _mm256_cmp_pd::<_CMP_GT_OQ>(lo, far),
            _mm256_cmp_pd::<_CMP_LT_OQ>(hi, near),
        )
    };
    let hv = _mm256_set_pd(0.0, h.z, h.y, h.x);
    if _mm256_movemask_pd(misses(v, hv, sl)) & 7 != 0 {
        return false;
    }
    let e = [
        _mm256_sub_pd(v[1], v[0]),
        _mm256_sub_pd(v[2], v[1]),
        _mm256_sub_pd(v[0], v[2]),
    ];
    // The triangle's normal, on scalars.
    let vec3 = |x: __m256d| {
        let mut l = Lanes([0.0; 4]);
        // SAFETY: `Lanes` are four f64, aligned to 32 bytes.
        unsafe { _mm256_store_pd(l.0.as_mut_ptr(), x) };
        Vec3::new(l.0[0], l.0[1], l.0[2])
    };
    let (vs, e0, e1) = (v.map(vec3), vec3(e[0]), vec3(e[1]));
    let n = e0.cross(&e1);
    let p = [n.dot(&vs[0]), n.dot(&vs[1]), n.dot(&vs[2])];
    let lo = least(least(p[0], p[1]), p[2]);
    let hi = most(most(p[0], p[1]), p[2]);
    let (r, s) = (h.dot(&n.abs()), slack * abs_sum(&n));
    if (lo > r + s) | (hi < -r - s) {
        return false;
    }
    // Edge axes: for box axis i (lane i) and edge `d`, `e_i x d` has components `x` at index
    // `j` and `y` at `k`: (0, -z, y), (z, 0, -x), (-y, x, 0). `jk` brings a vector's j-th and
    // k-th coordinates to lane i.
    const J: i32 = 0b11_00_00_01;
    const K: i32 = 0b11_01_10_10;
    let jk = |w: __m256d| (_mm256_permute4x64_pd::<J>(w), _mm256_permute4x64_pd::<K>(w));
    let (vj, vk) = (v.map(|w| jk(w).0), v.map(|w| jk(w).1));
    let (hj, hk) = jk(hv);
    let (neg_x, neg_y) = (
        _mm256_set_pd(0.0, -0.0, 0.0, -0.0),
        _mm256_set_pd(0.0, 0.0, -0.0, 0.0),
    );
    let mut apart = _mm256_setzero_pd();
    for d in e {
        // x = (-z, z, -y), y = (y, -x, x).
        let x = _mm256_xor_pd(_mm256_permute4x64_pd::<K>(d), neg_x);
        let y = _mm256_xor_pd(_mm256_permute4x64_pd::<J>(d), neg_y);
        let p = [0, 1, 2].map(|k| _mm256_add_pd(_mm256_mul_pd(vj[k], x), _mm256_mul_pd(vk[k], y)));
        let (ax, ay) = (abs(x), abs(y));
        let r = _mm256_add_pd(_mm256_mul_pd(hj, ax), _mm256_mul_pd(hk, ay));
        let s = _mm256_mul_pd(sl, _mm256_add_pd(ax, ay));
        apart = _mm256_or_pd(apart, misses(p, r, s));
    }
    _mm256_movemask_pd(apart) & 7 == 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::portable_only;
    use crate::test_rng::Lcg;
    use nalgebra::{Rotation3, Unit};

    /// Tests the offsets either side of where `test`'s verdict flips, between the offset 0
    /// (overlap) and a far one (found by bisection), for case `k`.
    fn around_flip(k: usize, test: impl Fn(f64) -> bool) {
        let (mut lo, mut hi) = (0.0, 100.0);
        assert!(test(lo) && !test(hi), "case {k}");
        while hi - lo > f64::EPSILON * hi {
            let mid = 0.5 * (lo + hi);
            if test(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        for s in [lo.next_down(), hi.next_up()] {
            test(s);
        }
    }

    /// The box-box test's copy compiled for AVX2 gives the same verdict as the portable one
    /// (where the processor has no AVX2, both are the portable one): on random poses, and at the
    /// last representable offsets either side of where the portable copy's verdict flips, with
    /// flat boxes among them.
    #[test]
    fn box_test_copies_agree() {
        let mut rng = Lcg(17);
        let mut f = move || rng.signed();
        let (mut hits, mut misses) = (0, 0);
        for k in 0..20000 {
            let mut rot = || -> Mat3 {
                let axis = Unit::new_normalize(Vec3::new(f(), f(), f() + 1e-3));
                Rotation3::from_axis_angle(&axis, 3.0 * f()).into_inner()
            };
            let (axes_a, axes_b, rot_rel) = (rot(), rot(), rot());
            let v: [f64; 12] = std::array::from_fn(|_| f());
            // Flat boxes too (one half extent 0).
            let a = Obb {
                axes: axes_a,
                center: Vec3::new(v[0], v[1], v[2]),
                half: Vec3::new(
                    v[3].abs(),
                    v[4].abs(),
                    (k % 7 != 0) as u8 as f64 * v[5].abs(),
                ),
            };
            let b = Obb {
                axes: axes_b,
                center: Vec3::new(v[6], v[7], v[8]),
                half: Vec3::new(
                    v[9].abs(),
                    v[10].abs(),
                    (k % 5 != 0) as u8 as f64 * v[11].abs(),
                ),
            };
            // Offset 0 puts b's centre on a's.
            let (dir, base) = (Vec3::new(f(), f(), f()), a.center - rot_rel * b.center);
            let test = |s: f64| {
                let rel = RelPose {
                    rot: rot_rel,
                    trans: base + dir * s,
                };
                let posed = Obb::pose(&b, &rel);
                let x = portable_only(|| Obb::overlap_posed(&a, &posed, &rel));
                let y = Obb::overlap_posed(&a, &posed, &rel);
                assert_eq!(x, y, "case {k}, offset {s}");
                x
            };
            if test(4.0 * f()) {
                hits += 1;
            } else {
                misses += 1;
            }
            around_flip(k, test);
        }
        assert!(hits > 2000 && misses > 2000, "{hits} {misses}");
    }

    /// The box-triangle test's copy compiled for AVX2 gives the same verdict as the portable one,
    /// as [`box_test_copies_agree`]; degenerate triangles among them.
    #[test]
    fn triangle_test_copies_agree() {
        let mut rng = Lcg(23);
        let mut f = move || rng.signed();
        let (mut hits, mut misses) = (0, 0);
        for k in 0..20000 {
            let axis = Unit::new_normalize(Vec3::new(f(), f(), f() + 1e-3));
            let axes = Rotation3::from_axis_angle(&axis, 3.0 * f()).into_inner();
            let v: [f64; 15] = std::array::from_fn(|_| f());
            let a = Obb {
                axes,
                center: Vec3::new(v[0], v[1], v[2]),
                half: Vec3::new(
                    v[3].abs(),
                    v[4].abs(),
                    (k % 7 != 0) as u8 as f64 * v[5].abs(),
                ),
            };
            let p = |i: usize| Vec3::new(v[i], v[i + 1], v[i + 2]);
            // A repeated vertex, collinear vertices, or a triangle.
            let tri = match k % 9 {
                0 => [p(6), p(6), p(9)],
                1 => [p(6), p(9), p(6) * 0.5 + p(9) * 0.5],
                _ => [p(6), p(9), p(12)],
            };
            // Offset 0 puts the triangle's first vertex on the box's centre.
            let (dir, base) = (Vec3::new(f(), f(), f()), a.center - tri[0]);
            let test = |s: f64| {
                let moved = tri.map(|q| q + base + dir * s);
                let x = portable_only(|| Obb::overlap_triangle(&a, &moved));
                let y = Obb::overlap_triangle(&a, &moved);
                assert_eq!(x, y, "case {k}, offset {s}");
                x == Some(true)
            };
            if test(4.0 * f()) {
                hits += 1;
            } else {
                misses += 1;
            }
            around_flip(k, test);
        }
        assert!(hits > 2000 && misses > 2000, "{hits} {misses}");
    }
}
