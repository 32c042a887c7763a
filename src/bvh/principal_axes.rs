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

/// Where [`frame_eigen`] stops sweeping: when every off-diagonal entry left is at most this
/// fraction of the difference of its two diagonal entries (the angle still to turn in that plane).
const FIRST_ORDER_BELOW: f64 = 1e-3;

/// Eigenvalues and eigenvectors (columns) of the symmetric matrix `a`, by cyclic Jacobi rotations:
/// each rotation zeroes one off-diagonal entry; sweeps over the three converge quadratically, and
/// the rotations' product is orthonormal to rounding whatever the spectrum (repeated eigenvalues
/// included). A handful of sweeps for a 3x3 matrix; a fraction of a general solver's work.
#[cfg(test)]
pub(super) fn symmetric_eigen(a: &Mat3) -> ([f64; 3], Mat3) {
    jacobi(a, false)
}

/// [`symmetric_eigen`] for a node's frame, where an angle of 1e-6 does not matter: after the
/// first sweep, once every off-diagonal entry `f` left is below `FIRST_ORDER_BELOW` of the gap
/// `d_q - d_p` between its diagonal entries, the eigenvectors are turned by `f / (d_q - d_p)`
/// (first-order perturbation: three independent divisions) instead of sweeping again (three
/// rotations, each a chain of two divisions, two square roots and a third division, one after
/// the other). The angle error left is about the square of what is corrected, at most 1e-6.
/// From the parent's frame one sweep is nearly always enough (3.2 rotations a node instead of 6.2
/// on the 40,000-triangle sphere). Where the gap is small (near-repeated eigenvalues, whose
/// eigenvectors the matrix's rounding decides) the sweeps go on exactly as in
/// [`symmetric_eigen`], so such a node gets the same frame as from it, and the hierarchy is the
/// same whichever computes it.
pub(super) fn frame_eigen(a: &Mat3) -> ([f64; 3], Mat3) {
    jacobi(a, true)
}

/// The Jacobi sweeps of [`symmetric_eigen`] and [`frame_eigen`] (`first_order`).
#[inline(always)]
fn jacobi(a: &Mat3, first_order: bool) -> ([f64; 3], Mat3) {
    let mut a = *a;
    let mut v = Mat3::identity();
    const PAIRS: [(usize, usize, usize); 3] = [(0, 1, 2), (0, 2, 1), (1, 2, 0)];
    for sweep in 0..32 {
        let off = a[(0, 1)] * a[(0, 1)] + a[(0, 2)] * a[(0, 2)] + a[(1, 2)] * a[(1, 2)];
        let diag = a[(0, 0)] * a[(0, 0)] + a[(1, 1)] * a[(1, 1)] + a[(2, 2)] * a[(2, 2)];
        // Off-diagonal entries below rounding of the diagonal: converged.
        if off <= 1e-28 * diag || off == 0.0 {
            break;
        }
        if first_order
            && sweep > 0
            && PAIRS.iter().all(|&(p, q, _)| {
                a[(p, q)].abs() < FIRST_ORDER_BELOW * (a[(q, q)] - a[(p, p)]).abs()
            })
        {
            // The eigenvector near axis p gains a_qp / (a_pp - a_qq) of axis q.
            let mut x = Mat3::identity();
            for (p, q, _) in PAIRS {
                let t = a[(p, q)] / (a[(q, q)] - a[(p, p)]);
                x[(p, q)] = t;
                x[(q, p)] = -t;
            }
            v *= x;
            break;
        }
        for (p, q, r) in PAIRS {
            let apq = a[(p, q)];
            if apq == 0.0 {
                continue;
            }
            // The rotation by angle phi in the (p, q) plane with cot(2 phi) = theta zeroes a_pq;
            // t = tan(phi), the root of t^2 + 2 theta t - 1 = 0 of smaller magnitude (|phi| <=
            // pi/4, which keeps the rotations small and the iteration convergent).
            let theta = (a[(q, q)] - a[(p, p)]) / (2.0 * apq);
            let t = if theta.abs() > 1e150 {
                0.5 / theta
            } else {
                let t = 1.0 / (theta.abs() + (theta * theta + 1.0).sqrt());
                if theta < 0.0 { -t } else { t }
            };
            let c = 1.0 / (t * t + 1.0).sqrt();
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
    ([a[(0, 0)], a[(1, 1)], a[(2, 2)]], v)
}

/// Principal axes from a covariance: its eigenvectors as orthonormal right-handed columns in
/// decreasing order of eigenvalue. Identity when the covariance gives no usable frame (not
/// finite: coordinates whose squares overflow). `guess` (orthonormal columns) is where the Jacobi
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
    use crate::test_rng::Lcg;

    #[test]
    fn eigen_decomposes_symmetric_matrices() {
        // Random, nearly diagonal, repeated and zero spectra, and wide dynamic ranges: A V = V L
        // with V orthonormal, to rounding of A's norm.
        let mut s = Lcg(21);
        for case in 0..2000 {
            let r = Mat3::from_fn(|_, _| s.unit() - 0.5);
            let mut a = r + r.transpose();
            match case % 5 {
                1 => a = Mat3::from_diagonal(&Vec3::new(1.0, 1.0, 2.0)) + a * 1e-9,
                2 => a = Mat3::from_diagonal(&Vec3::new(3.0, 3.0, 3.0)),
                3 => a = r * Mat3::from_diagonal(&Vec3::new(1e6, 1.0, 1e-8)) * r.transpose(),
                4 if case % 10 == 4 => a = Mat3::zeros(),
                _ => {}
            }
            let (l, v) = symmetric_eigen(&a);
            let scale = a.norm().max(f64::MIN_POSITIVE);
            assert!(
                (v.transpose() * v - Mat3::identity()).norm() < 1e-13,
                "{case}"
            );
            let res = a * v - v * Mat3::from_diagonal(&Vec3::from(l));
            assert!(
                res.norm() <= 1e-13 * scale,
                "{case}: {}",
                res.norm() / scale
            );
            // The eigenvalues agree with a general solver's.
            let mut want: Vec<f64> = nalgebra::SymmetricEigen::new(a)
                .eigenvalues
                .iter()
                .copied()
                .collect();
            let mut got = l.to_vec();
            want.sort_by(f64::total_cmp);
            got.sort_by(f64::total_cmp);
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() <= 1e-13 * scale, "{case}: {got:?} {want:?}");
            }
        }
    }

    #[test]
    fn frame_eigen_is_within_a_micro_radian() {
        // Matrices as a node's solver meets them (nearly diagonal in the parent's frame: small
        // rotations of a diagonal) and any: A V = V L to 1e-5 of A's norm, V orthonormal to
        // 1e-5, and where the eigenvalues are 1% of the norm apart, the same eigenvectors as a
        // general solver's to 1e-5. Near-repeated eigenvalues go through the full sweeps.
        let mut s = Lcg(35);
        let (mut shortcut, mut cases) = (0, 0);
        for case in 0..3000 {
            let d = Vec3::new(s.unit() + 0.5, s.unit() * 0.5, s.unit() * 0.1);
            let angle = [0.3, 0.03, 0.003, 1e-6][case % 4] * (s.unit() - 0.5);
            let axis = Vec3::new(s.unit() - 0.5, s.unit() - 0.5, s.unit() - 0.5);
            let r = *nalgebra::Rotation3::new(axis.normalize() * angle).matrix();
            let mut a = r * Mat3::from_diagonal(&d) * r.transpose();
            if case % 5 == 4 {
                let m = Mat3::from_fn(|_, _| s.unit() - 0.5);
                a = m + m.transpose();
            }
            let a = Mat3::from_fn(|i, j| if i <= j { a[(i, j)] } else { a[(j, i)] });
            let (l, v) = frame_eigen(&a);
            let exact = symmetric_eigen(&a);
            cases += 1;
            if v != exact.1 {
                shortcut += 1;
            }
            let scale = a.norm();
            assert!(
                (v.transpose() * v - Mat3::identity()).norm() < 1e-5,
                "{case}"
            );
            let res = a * v - v * Mat3::from_diagonal(&Vec3::from(l));
            assert!(res.norm() <= 1e-5 * scale, "{case}: {}", res.norm() / scale);
            let (el, ev) = exact;
            for i in 0..3 {
                assert!((l[i] - el[i]).abs() <= 1e-5 * scale, "{case}");
                let gap = (0..3)
                    .filter(|&j| j != i)
                    .map(|j| (el[i] - el[j]).abs())
                    .fold(f64::INFINITY, f64::min);
                if gap > 1e-2 * scale {
                    let cos = v.column(i).dot(&ev.column(i)).abs() / v.column(i).norm();
                    assert!(1.0 - cos < 1e-10, "{case}: {}", 1.0 - cos);
                }
            }
        }
        // The shortcut is taken (else this tests nothing of it).
        assert!(shortcut > cases / 4, "{shortcut} of {cases}");
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
