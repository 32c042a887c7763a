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

/// Eigenvalues and eigenvectors (columns) of the symmetric matrix `a`, by cyclic Jacobi rotations:
/// each rotation zeroes one off-diagonal entry; sweeps over the three converge quadratically, and
/// the rotations' product is orthonormal to rounding whatever the spectrum (repeated eigenvalues
/// included). A handful of sweeps for a 3x3 matrix; a fraction of a general solver's work.
pub(super) fn symmetric_eigen(a: &Mat3) -> ([f64; 3], Mat3) {
    let mut a = *a;
    let mut v = Mat3::identity();
    const PAIRS: [(usize, usize, usize); 3] = [(0, 1, 2), (0, 2, 1), (1, 2, 0)];
    for _sweep in 0..32 {
        let off = a[(0, 1)] * a[(0, 1)] + a[(0, 2)] * a[(0, 2)] + a[(1, 2)] * a[(1, 2)];
        let diag = a[(0, 0)] * a[(0, 0)] + a[(1, 1)] * a[(1, 1)] + a[(2, 2)] * a[(2, 2)];
        // Off-diagonal entries below rounding of the diagonal: converged.
        if off <= 1e-28 * diag || off == 0.0 {
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
    let (values, rotation) = symmetric_eigen(&b);
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
