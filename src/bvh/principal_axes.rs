//! A node's frame: the principal axes of its triangles' corners (the eigenvectors of their
//! covariance, largest spread first), from the node's distinct vertices weighted by their
//! multiplicities, and the symmetric 3x3 eigensolver it takes.

use crate::math::{Mat3, Vec3};

/// Adds `w d d^T` to the six distinct entries `s`.
#[inline(always)]
fn add_outer(s: &mut [f64; 6], d: &Vec3, w: f64) {
    s[0] += w * d.x * d.x;
    s[1] += w * d.x * d.y;
    s[2] += w * d.x * d.z;
    s[3] += w * d.y * d.y;
    s[4] += w * d.y * d.z;
    s[5] += w * d.z * d.z;
}

/// The covariance about their mean of the points `points` (not empty), point `i` counted
/// `weights[i]` times (not all 0): a node's corners from its distinct vertices and their
/// multiplicities. Two passes: the mean, then the scatter about it (no cancellation however far
/// the points are from the origin).
#[cfg(test)]
pub(super) fn weighted_covariance(points: &[Vec3], weights: &[u32]) -> Mat3 {
    debug_assert_eq!(points.len(), weights.len());
    let mut total = 0.0f64;
    let mut sum = Vec3::zeros();
    for (p, &w) in points.iter().zip(weights) {
        let w = f64::from(w);
        sum += p * w;
        total += w;
    }
    weighted_scatter(points, weights, &(sum / total), total)
}

/// The second pass of [`weighted_covariance`]: the scatter about `mean` (the points' weighted
/// mean, `total` the weights' sum), divided by `total`. The builder sums the mean as it gathers a
/// node's points.
pub(super) fn weighted_scatter(points: &[Vec3], weights: &[u32], mean: &Vec3, total: f64) -> Mat3 {
    debug_assert_eq!(points.len(), weights.len());
    let mut s = [0.0f64; 6];
    for (p, &w) in points.iter().zip(weights) {
        add_outer(&mut s, &(p - mean), f64::from(w));
    }
    let s = s.map(|v| v / total);
    Mat3::new(s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5])
}

/// The covariance of a point set (not empty), about its mean.
#[cfg(test)]
pub(super) fn point_covariance(points: &[Vec3]) -> Mat3 {
    let n = points.len() as f64;
    let mean = points.iter().fold(Vec3::zeros(), |a, p| a + p) / n;
    let mut s = [0.0f64; 6];
    for p in points {
        add_outer(&mut s, &(p - mean), 1.0);
    }
    let s = s.map(|v| v / n);
    Mat3::new(s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5])
}

/// How far the Jacobi sweeps of [`frame_eigen`] go: until the off-diagonal entries' squares sum
/// to at most this much of the diagonal's (entries about 1e-3 of the diagonal's).
const SWEEP_UNTIL: f64 = 1e-6;

/// Eigenvalues and eigenvectors (columns, orthonormal up to about `SWEEP_UNTIL`) of the symmetric
/// matrix `a` (finite), for a node's frame: cyclic Jacobi sweeps until the off-diagonal entries
/// are small, then a first-order correction for what is left.
///
/// Each Jacobi rotation zeroes one off-diagonal entry; sweeps over the three converge
/// quadratically once the entries are small, and the rotations' product is orthonormal to
/// rounding whatever the spectrum. The solver's time is the latency of the rotations' square
/// roots and divisions, one rotation after the other, so this does few of them:
/// - A rotation is computed from the difference `d` of the two diagonal entries and twice the
///   off-diagonal one `h`: `r = sqrt(d^2 + h^2)`, `tan = sign(d) h / (|d| + r)`,
///   `cos = sqrt((|d| + r) / (2 r))` (the textbook `theta = d / h`, `tan = sign(theta) /
///   (|theta| + sqrt(theta^2 + 1))`, `cos = 1 / sqrt(tan^2 + 1)`, multiplied through by `|h|`): a
///   chain of a root, a division and a root instead of two of each and a third division. The
///   matrix is first scaled by a power of two (exact) to bring its largest entry near 1, so that
///   `d^2 + h^2` neither overflows nor, for an entry that still matters, underflows.
/// - The builder starts from the parent's frame, where a child's covariance is nearly diagonal:
///   one sweep usually leaves entries below `SWEEP_UNTIL` (the old criterion, rounding of the
///   diagonal, took two sweeps and a check). What is left, `f` between diagonal entries `d_p`
///   and `d_q`, turns the eigenvectors by about `f / (d_q - d_p)` (first-order perturbation),
///   applied to all three pairs at once (three independent divisions); an angle error of about
///   its square remains (at most 1e-4 where the eigenvalues are apart by a tenth of the largest,
///   far less as a rule: the sweep usually leaves much less than `SWEEP_UNTIL`). Where they are
///   not (`|f|` above a tenth of the gap) the axes in that plane are about equally good and the
///   correction is left out.
///
/// A frame a little off the exact principal axes costs the volumes nothing in containment (they
/// are fitted around the points on whatever frame they get) and, at these angles, nothing
/// measurable in tightness (BENCHMARKS.md, section 32).
fn frame_eigen(a: &Mat3) -> ([f64; 3], Mat3) {
    let big = a.amax();
    // 2^-e with 2^e <= big < 2^(e + 1) (e at most 1022, so that 2^-e is a normal number): the
    // largest entry then in [1, 4).
    let e = (((big.to_bits() >> 52) & 0x7ff) as i64 - 1023).min(1022);
    let down = if big > 0.0 {
        f64::from_bits(((1023 - e) as u64) << 52)
    } else {
        1.0
    };
    let mut a = a * down;
    let mut v = Mat3::identity();
    const PAIRS: [(usize, usize, usize); 3] = [(0, 1, 2), (0, 2, 1), (1, 2, 0)];
    for _sweep in 0..32 {
        let off = a[(0, 1)] * a[(0, 1)] + a[(0, 2)] * a[(0, 2)] + a[(1, 2)] * a[(1, 2)];
        let diag = a[(0, 0)] * a[(0, 0)] + a[(1, 1)] * a[(1, 1)] + a[(2, 2)] * a[(2, 2)];
        if off <= SWEEP_UNTIL * diag || off == 0.0 {
            break;
        }
        for (p, q, r) in PAIRS {
            let apq = a[(p, q)];
            // The rotation by angle phi in the (p, q) plane with cot(2 phi) = d / h zeroes a_pq;
            // t = tan(phi), the root of t^2 + 2 (d / h) t - 1 = 0 of smaller magnitude (|phi| <=
            // pi/4, which keeps the rotations small and the iteration convergent).
            let d = a[(q, q)] - a[(p, p)];
            let h = 2.0 * apq;
            let root = (d * d + h * h).sqrt();
            // An entry this small against the largest (near 1) is far below the rounding of the
            // diagonal: nothing to rotate (and `h^2` may have underflowed). Zero included.
            if root <= 1e-150 {
                continue;
            }
            let ad = d.abs() + root;
            let t = if d < 0.0 { -h } else { h } / ad;
            let c = (ad / (2.0 * root)).sqrt();
            let s = t * c;
            a[(p, p)] -= t * apq;
            a[(q, q)] += t * apq;
            a[(p, q)] = 0.0;
            a[(q, p)] = 0.0;
            let (arp, arq) = (a[(r, p)], a[(r, q)]);
            a[(r, p)] = c * arp - s * arq;
            a[(p, r)] = a[(r, p)];
            a[(r, q)] = s * arp + c * arq;
            a[(q, r)] = a[(r, q)];
            for k in 0..3 {
                let (vkp, vkq) = (v[(k, p)], v[(k, q)]);
                v[(k, p)] = c * vkp - s * vkq;
                v[(k, q)] = s * vkp + c * vkq;
            }
        }
    }
    // First-order correction: the eigenvector near axis q gains f / (d_q - d_p) of axis p.
    let mut x = Mat3::identity();
    for (p, q, _) in PAIRS {
        let f = a[(p, q)];
        let gap = a[(q, q)] - a[(p, p)];
        // Strict: a zero gap (with a zero entry) takes no correction rather than 0 / 0.
        if f.abs() < 0.1 * gap.abs() {
            x[(p, q)] = f / gap;
            x[(q, p)] = -f / gap;
        }
    }
    // Back to the given scale (a power of two: exact).
    (
        [a[(0, 0)] / down, a[(1, 1)] / down, a[(2, 2)] / down],
        v * x,
    )
}

/// Principal axes from a covariance: its eigenvectors as orthonormal right-handed columns in
/// decreasing order of eigenvalue. Identity when the covariance gives no usable frame (not
/// finite: coordinates whose squares overflow). The eigenvectors are [`frame_eigen`]'s, taken
/// to orthonormal columns (Gram-Schmidt). `guess` (orthonormal columns) is where the Jacobi
/// rotations start: the covariance is taken into that frame first, so a frame close to the answer
/// (the parent node's: a child's shape is usually much like its parent's) leaves little to rotate
/// and the solver converges in fewer sweeps.
pub(super) fn axes_of(cov: &Mat3, guess: &Mat3) -> Mat3 {
    if !cov.iter().all(|v| v.is_finite()) {
        return Mat3::identity();
    }
    let b = guess.tr_mul(&(cov * guess));
    // Symmetric to the bit, from the upper triangle.
    let b = Mat3::new(
        b[(0, 0)],
        b[(0, 1)],
        b[(0, 2)],
        b[(0, 1)],
        b[(1, 1)],
        b[(1, 2)],
        b[(0, 2)],
        b[(1, 2)],
        b[(2, 2)],
    );
    let (values, rotation) = frame_eigen(&b);
    let vectors = guess * rotation;
    let mut idx = [0usize, 1, 2];
    idx.sort_by(|&a, &b| values[b].total_cmp(&values[a]));
    let v0: Vec3 = vectors.column(idx[0]).into();
    let v1: Vec3 = vectors.column(idx[1]).into();
    let a0 = v0.normalize();
    let a1 = (v1 - a0 * a0.dot(&v1)).normalize();
    let a2 = a0.cross(&a1);
    let axes = Mat3::from_columns(&[a0, a1, a2]);
    if axes.iter().all(|v| v.is_finite()) && (a2.norm() - 1.0).abs() < 1e-6 {
        axes
    } else {
        Mat3::identity()
    }
}

/// Principal axes of a point set (not empty): [`axes_of`] its covariance.
#[cfg(test)]
pub(super) fn principal_axes(points: &[Vec3]) -> Mat3 {
    axes_of(&point_covariance(points), &Mat3::identity())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::frame_from;
    use crate::test_rng::Lcg;

    /// The rotation taking a random unit quaternion's frame, orthonormal to rounding.
    fn random_rotation(s: &mut Lcg) -> Mat3 {
        let q = nalgebra::Quaternion::new(
            s.unit() - 0.5,
            s.unit() - 0.5,
            s.unit() - 0.5,
            s.unit() - 0.5,
        );
        *nalgebra::UnitQuaternion::from_quaternion(q)
            .to_rotation_matrix()
            .matrix()
    }

    #[test]
    fn frames_are_principal_axes() {
        // Random, nearly diagonal, repeated and zero spectra, and wide dynamic ranges, each from
        // the identity, from a guess near the answer (a child's from its parent's) and from a
        // random one: `frame_eigen`'s eigenvalues agree with a general solver's (to the 1e-3 of
        // the largest entry left off the diagonal), and `axes_of`
        // gives orthonormal right-handed axes in decreasing order of eigenvalue, each within
        // 1e-4 of the general solver's eigenvector where the eigenvalues are apart (by a tenth
        // of the largest entry; see `frame_eigen`).
        let mut s = Lcg(21);
        for case in 0..3000 {
            let r = Mat3::from_fn(|_, _| s.unit() - 0.5);
            let q = random_rotation(&mut s);
            let spectrum = Vec3::new(s.unit(), 0.5 * s.unit(), 0.1 * s.unit());
            let mut a = match case % 6 {
                0 => r + r.transpose(),
                1 => Mat3::from_diagonal(&Vec3::new(1.0, 1.0, 2.0)) + (r + r.transpose()) * 1e-9,
                2 => q * Mat3::from_diagonal(&Vec3::new(3.0, 3.0, 3.0)) * q.transpose(),
                3 => q * Mat3::from_diagonal(&Vec3::new(1e6, 1.0, 1e-8)) * q.transpose(),
                4 if case % 12 == 4 => Mat3::zeros(),
                _ => q * Mat3::from_diagonal(&spectrum) * q.transpose(),
            };
            a = (a + a.transpose()) * 0.5;
            a *= [1.0, 1e-200, 1e200, 1e-3][case % 4];
            // The largest entry (the norm's squares would underflow at 1e-200).
            let scale = a.amax().max(f64::MIN_POSITIVE);
            let (l, _) = frame_eigen(&a);
            let general = nalgebra::SymmetricEigen::new(a);
            let mut want: Vec<f64> = general.eigenvalues.iter().copied().collect();
            let mut got = l.to_vec();
            want.sort_by(f64::total_cmp);
            got.sort_by(f64::total_cmp);
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() <= 1e-3 * scale, "{case}: {got:?} {want:?}");
            }
            let near = q * random_rotation(&mut s).map(|v| v * 1e-1) + q;
            let near = frame_from(&near.column(0).into(), &near.column(1).into());
            for guess in [Mat3::identity(), q, near, random_rotation(&mut s)] {
                let guess = frame_from(&guess.column(0).normalize(), &{
                    let g0 = guess.column(0).normalize();
                    let g1: Vec3 = guess.column(1).into();
                    (g1 - g0 * g0.dot(&g1)).normalize()
                });
                let ax = axes_of(&a, &guess);
                assert!(
                    (ax.transpose() * ax - Mat3::identity()).norm() < 1e-12,
                    "{case}"
                );
                assert!((ax.determinant() - 1.0).abs() < 1e-12, "{case}");
                let rq: Vec<f64> = (0..3)
                    .map(|i| {
                        let c: Vec3 = ax.column(i).into();
                        c.dot(&(a * c))
                    })
                    .collect();
                assert!(
                    rq[0] >= rq[1] - 1e-5 * scale && rq[1] >= rq[2] - 1e-5 * scale,
                    "{case}: {rq:?}"
                );
                let mut order: Vec<usize> = (0..3).collect();
                order.sort_by(|&i, &j| general.eigenvalues[j].total_cmp(&general.eigenvalues[i]));
                for (i, &k) in order.iter().enumerate() {
                    let apart = order.iter().filter(|&&j| j != k).all(|&j| {
                        (general.eigenvalues[j] - general.eigenvalues[k]).abs() > 0.1 * scale
                    });
                    if apart {
                        let c: Vec3 = ax.column(i).into();
                        let e: Vec3 = general.eigenvectors.column(k).into();
                        assert!(c.cross(&e).norm() < 1e-4, "{case}: axis {i}");
                    }
                }
            }
        }
    }

    #[test]
    fn weighted_vertices_give_the_corners_covariance() {
        // Triangles over a few shared vertices: the distinct vertices weighted by how many
        // corners each is give the corners' covariance.
        let mut s = Lcg(8);
        for case in 0..200 {
            let offset = [0.0, 1e3, -1e6][case % 3];
            let pool: Vec<Vec3> = (0..2 + case % 9)
                .map(|_| Vec3::new(s.unit(), 0.2 * s.unit(), s.unit()).add_scalar(offset))
                .collect();
            let n = 1 + case % 17;
            let pick = |s: &mut Lcg| (s.unit() * pool.len() as f64) as usize % pool.len();
            let faces: Vec<[usize; 3]> = (0..n)
                .map(|_| [pick(&mut s), pick(&mut s), pick(&mut s)])
                .collect();
            let mut weights = vec![0u32; pool.len()];
            for f in &faces {
                for &v in f {
                    weights[v] += 1;
                }
            }
            let corners: Vec<Vec3> = faces.iter().flatten().map(|&v| pool[v]).collect();
            let got = weighted_covariance(&pool, &weights);
            let want = point_covariance(&corners);
            assert!((got - want).norm() <= 1e-9 * (1.0 + want.norm()), "{case}");
        }
    }
}
