//! Top-down build, as the SSV paper describes it: principal axes from the covariance of the node's
//! vertices, split across the axis of largest spread at the mean of the triangle centroids.

use super::{Bvh, Node};
use crate::bounding_volume::{BoundingVolume, Obb, Rss};
use crate::error::Error;
use crate::geometry::Tri;
use crate::math::{Mat3, Vec3};
use nalgebra::SymmetricEigen;

/// Below this depth the split is at the mean, as the paper says; past it (only on adversarial input
/// such as exponentially spaced triangles, where a mean split peels one triangle at a time) the split
/// is at the median, so the depth stays O(log n) and traversal stacks stay small.
const MEAN_SPLIT_MAX_DEPTH: usize = 40;

/// Upper bound on the depth of any built tree: the mean-split levels plus a median-split tail.
pub(crate) const MAX_DEPTH: usize = MEAN_SPLIT_MAX_DEPTH + 33;

impl Bvh {
    /// Builds the hierarchy over `tris` (not empty). O(n log n).
    pub fn build(tris: Vec<(Tri, i32)>) -> Result<Bvh, Error> {
        let n = tris.len();
        debug_assert!(n > 0);
        let mut order: Vec<u32> = Vec::new();
        order.try_reserve_exact(n).map_err(|_| Error::ModelOutOfMemory)?;
        order.extend(0..n as u32);
        let mut centroids: Vec<Vec3> = Vec::new();
        centroids.try_reserve_exact(n).map_err(|_| Error::ModelOutOfMemory)?;
        centroids.extend(tris.iter().map(|(t, _)| (t[0] + t[1] + t[2]) / 3.0));
        let mut nodes: Vec<Node> = Vec::new();
        nodes.try_reserve_exact(2 * n - 1).map_err(|_| Error::ModelOutOfMemory)?;
        let mut points: Vec<Vec3> = Vec::new();
        points.try_reserve(3 * n).map_err(|_| Error::ModelOutOfMemory)?;
        let mut keys: Vec<f64> = Vec::new();

        // Work list of (node index, first, last exclusive, depth) over `order`.
        let mut work = vec![(0usize, 0usize, n, 0usize)];
        nodes.push(placeholder());
        while let Some((ni, lo, hi, depth)) = work.pop() {
            let range = &mut order[lo..hi];
            points.clear();
            for &t in range.iter() {
                points.extend_from_slice(&tris[t as usize].0);
            }
            let axes = principal_axes(&points);
            let node = &mut nodes[ni];
            node.rss = Rss::fit(&axes, &points);
            node.obb = Obb::fit(&axes, &points);
            if hi - lo == 1 {
                // Leaves point at the triangle's slot in leaf order, which is its place in `order`.
                node.child = -(lo as i32) - 1;
                continue;
            }
            let axis: Vec3 = axes.column(0).into();
            let mid = split(range, &centroids, &axis, depth >= MEAN_SPLIT_MAX_DEPTH, &mut keys);
            let first = nodes.len();
            nodes[ni].child = first as i32;
            nodes.push(placeholder());
            nodes.push(placeholder());
            work.push((first + 1, lo + mid, hi, depth + 1));
            work.push((first, lo, lo + mid, depth + 1));
        }

        let mut leaf_tris = Vec::new();
        leaf_tris.try_reserve_exact(n).map_err(|_| Error::ModelOutOfMemory)?;
        let mut ids = Vec::new();
        ids.try_reserve_exact(n).map_err(|_| Error::ModelOutOfMemory)?;
        for &t in &order {
            leaf_tris.push(tris[t as usize].0);
            ids.push(tris[t as usize].1);
        }
        Ok(Bvh {
            nodes,
            tris: leaf_tris,
            ids,
        })
    }
}

fn placeholder() -> Node {
    Node {
        rss: Rss {
            axes: Mat3::identity(),
            origin: Vec3::zeros(),
            lengths: [0.0; 2],
            radius: 0.0,
        },
        obb: Obb {
            axes: Mat3::identity(),
            center: Vec3::zeros(),
            half: Vec3::zeros(),
        },
        child: 0,
    }
}

/// Partitions `range` (at least two triangles) and returns how many go to the first child (never 0
/// nor all): those whose centroid projects below the mean, or the lower half by projection when the
/// mean splits nothing off or `median` is asked for.
fn split(range: &mut [u32], centroids: &[Vec3], axis: &Vec3, median: bool, keys: &mut Vec<f64>) -> usize {
    let count = range.len();
    if !median {
        let mean = range
            .iter()
            .map(|&t| centroids[t as usize].dot(axis))
            .sum::<f64>()
            / count as f64;
        let mut left = 0;
        for i in 0..count {
            if centroids[range[i] as usize].dot(axis) < mean {
                range.swap(i, left);
                left += 1;
            }
        }
        if left > 0 && left < count {
            return left;
        }
    }
    // Halves by projection. Sort keys alongside the indices so equal projections split evenly too.
    keys.clear();
    keys.extend(range.iter().map(|&t| centroids[t as usize].dot(axis)));
    let mut pairs: Vec<(f64, u32)> = keys.iter().copied().zip(range.iter().copied()).collect();
    let mid = count / 2;
    pairs.select_nth_unstable_by(mid, |a, b| a.0.total_cmp(&b.0));
    for (slot, (_, t)) in range.iter_mut().zip(pairs) {
        *slot = t;
    }
    mid
}

/// Principal axes of a point set: eigenvectors of its covariance, as orthonormal right-handed
/// columns in decreasing order of eigenvalue. Identity when the covariance gives no usable frame.
pub(crate) fn principal_axes(points: &[Vec3]) -> Mat3 {
    let n = points.len() as f64;
    let mean = points.iter().fold(Vec3::zeros(), |a, p| a + p) / n;
    let mut cov = Mat3::zeros();
    for p in points {
        let d = p - mean;
        cov += d * d.transpose();
    }
    cov /= n;
    if !cov.iter().all(|v| v.is_finite()) {
        return Mat3::identity();
    }
    let eig = SymmetricEigen::new(cov);
    let mut idx = [0usize, 1, 2];
    idx.sort_by(|&a, &b| eig.eigenvalues[b].total_cmp(&eig.eigenvalues[a]));
    let v0: Vec3 = eig.eigenvectors.column(idx[0]).into();
    let v1: Vec3 = eig.eigenvectors.column(idx[1]).into();
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
