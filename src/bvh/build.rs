//! Top-down build, as the SSV paper describes it: principal axes from the covariance of the node's
//! vertices, split across the axis of largest spread at the mean of the triangle centroids.

use super::{Bvh, CollisionVolume, Node, NodeRef, VolumeKind};
use crate::bounding_volume::{Obb, Ssv, SsvKind};
use crate::error::Error;
use crate::geometry::Tri;
use crate::math::{Mat3, Vec3, frame_from};
use nalgebra::SymmetricEigen;

/// Below this depth the split is at the mean, as the paper says; past it (only on adversarial input
/// such as exponentially spaced triangles, where a mean split peels one triangle at a time) the split
/// is at the median, so the depth stays O(log n) and traversal stacks stay small.
const MEAN_SPLIT_MAX_DEPTH: usize = 40;

/// Upper bound on the depth of any built tree: the mean-split levels plus a median-split tail.
pub(crate) const MAX_DEPTH: usize = MEAN_SPLIT_MAX_DEPTH + 33;

impl Bvh {
    /// Builds the hierarchy over `tris` (not empty), with swept sphere volumes of `volume` and
    /// collision on `collision`. O(n log n).
    pub fn build(
        tris: Vec<(Tri, i32)>,
        volume: VolumeKind,
        collision: CollisionVolume,
    ) -> Result<Bvh, Error> {
        let oom = |_| Error::ModelOutOfMemory;
        let n = tris.len();
        debug_assert!(n > 0);
        // The triangles and their insertion indices, permuted in place into leaf order as the nodes
        // split them:
        // a node's triangles are always one contiguous run, so its vertices are one slice.
        let mut corners: Vec<Tri> = Vec::new();
        corners.try_reserve_exact(n).map_err(oom)?;
        corners.extend(tris.iter().map(|(t, _)| *t));
        // Each triangle's position in `tris`, permuted alongside: becomes `Bvh::added`.
        let mut added: Vec<u32> = Vec::new();
        added.try_reserve_exact(n).map_err(oom)?;
        added.extend(0..n as u32);
        let mut given_ids: Vec<i32> = Vec::new();
        given_ids.try_reserve_exact(n).map_err(oom)?;
        given_ids.extend(tris.iter().map(|(_, id)| *id));
        drop(tris);
        // At least every vertex's `|p|_1` (twice the largest, which is rounded): for the rounding
        // allowances of `fit_volumes`.
        let scale = 2.0
            * corners
                .as_flattened()
                .iter()
                .fold(0.0f64, |m, p| m.max(p.abs().sum()));
        let mut nodes: Vec<Node> = Vec::new();
        nodes.try_reserve_exact(n - 1).map_err(oom)?;
        // Scratch: the node's vertices in its frame, and its triangles' split keys.
        let mut local: Vec<Vec3> = Vec::new();
        local.try_reserve_exact(3 * n).map_err(oom)?;
        let mut keys: Vec<f64> = Vec::new();
        keys.try_reserve_exact(n).map_err(oom)?;

        // Work list of (node index, first, last exclusive, depth) over the triangles, for ranges of
        // at least two triangles (a single triangle is a leaf and gets no node).
        let mut work = Vec::new();
        if n > 1 {
            work.push((0usize, 0usize, n, 0usize));
            nodes.push(placeholder());
        }
        while let Some((ni, lo, hi, depth)) = work.pop() {
            let a = principal_axes(corners[lo..hi].as_flattened());
            // The frame exactly as the node will give it back.
            let axes = frame_from(&a.column(0).into(), &a.column(1).into());
            let (ssv, obb) = fit_volumes(
                volume,
                &axes,
                &corners[lo..hi],
                scale,
                &mut local,
                &mut keys,
            );
            let mut node = Node::new(&ssv, &obb);
            let mid = split(
                &mut corners[lo..hi],
                &mut added[lo..hi],
                &mut keys,
                depth >= MEAN_SPLIT_MAX_DEPTH,
            );
            for (k, (clo, chi)) in [(lo, lo + mid), (lo + mid, hi)].into_iter().enumerate() {
                node.children[k] = if chi - clo == 1 {
                    // Leaves point at the triangle's slot in leaf order.
                    NodeRef::leaf(clo)
                } else {
                    let c = nodes.len();
                    nodes.push(placeholder());
                    work.push((c, clo, chi, depth + 1));
                    NodeRef::inner(c)
                };
            }
            nodes[ni] = node;
        }
        drop(local);
        drop(keys);

        // The ids in leaf order.
        let mut ids: Vec<i32> = Vec::new();
        ids.try_reserve_exact(n).map_err(oom)?;
        ids.extend(added.iter().map(|&k| given_ids[k as usize]));
        drop(given_ids);

        let (verts, faces) = share_vertices(&corners)?;
        let inner = Bvh::inner_scale(&nodes);
        Ok(Bvh::assemble(
            nodes, verts, faces, ids, added, collision, inner,
        ))
    }
}

/// The distinct vertices of the triangles (equal coordinates, bit for bit, stored once, in the order
/// they first appear) and each triangle's vertex indices. Finds repeats with a hash table of
/// corners, kept at most half full: expected O(n).
pub(super) fn share_vertices(tris: &[Tri]) -> Result<(Vec<Vec3>, Vec<[u32; 3]>), Error> {
    let oom = |_| Error::ModelOutOfMemory;
    let corners = tris.as_flattened();
    let bits = |c: usize| {
        let v = &corners[c];
        [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
    };
    let mut faces: Vec<[u32; 3]> = Vec::new();
    faces.try_reserve_exact(tris.len()).map_err(oom)?;
    faces.resize(tris.len(), [0; 3]);
    let face_ids = faces.as_flattened_mut();
    // Slots hold a corner index plus one (0: empty); that corner's vertex is the entry's. Sized
    // for a mesh's usual one vertex per two triangles, doubled whenever it gets half full.
    let mut shift = 64 - (tris.len().max(8)).next_power_of_two().trailing_zeros();
    let mut table: Vec<u32> = Vec::new();
    let grow = |table: &mut Vec<u32>, shift: u32| -> Result<(), Error> {
        let size = 1usize << (64 - shift);
        let mut new: Vec<u32> = Vec::new();
        new.try_reserve_exact(size).map_err(oom)?;
        new.resize(size, 0);
        for &e in table.iter().filter(|&&e| e != 0) {
            let mut i = slot(&bits(e as usize - 1), shift);
            while new[i] != 0 {
                i = (i + 1) & (size - 1);
            }
            new[i] = e;
        }
        *table = new;
        Ok(())
    };
    grow(&mut table, shift)?;
    let mut distinct = 0usize;
    for c in 0..corners.len() {
        let key = bits(c);
        let mask = table.len() - 1;
        let mut i = slot(&key, shift);
        loop {
            let e = table[i] as usize;
            if e == 0 {
                table[i] = c as u32 + 1;
                face_ids[c] = distinct as u32;
                distinct += 1;
                if 2 * distinct > table.len() {
                    shift -= 1;
                    grow(&mut table, shift)?;
                }
                break;
            }
            if bits(e - 1) == key {
                face_ids[c] = face_ids[e - 1];
                break;
            }
            i = (i + 1) & mask;
        }
    }
    drop(table);
    let mut verts: Vec<Vec3> = Vec::new();
    verts.try_reserve_exact(distinct).map_err(oom)?;
    for (c, &v) in face_ids.iter().enumerate() {
        // A vertex's first corner is the one that gave it the next index.
        if v as usize == verts.len() {
            verts.push(corners[c]);
        }
    }
    Ok((verts, faces))
}

/// The table slot of a vertex's bit pattern, for a table of `2^(64 - shift)` slots: a
/// multiplicative hash, which takes its slot from the product's high bits.
#[inline]
fn slot(key: &[u64; 3], shift: u32) -> usize {
    const K: u64 = 0x9e37_79b9_7f4a_7c15;
    let h = (key[0].wrapping_mul(K) ^ key[1])
        .wrapping_mul(K)
        .rotate_left(29)
        ^ key[2];
    (h.wrapping_mul(K) >> shift) as usize
}

/// The covariance of a point set (not empty), about its mean. Sums the six distinct products only:
/// `d[i] * d[j]` and `d[j] * d[i]` are the same number, so the matrix is the full sum's, bit for bit.
fn covariance(points: &[Vec3]) -> Mat3 {
    let n = points.len() as f64;
    let mean = points.iter().fold(Vec3::zeros(), |a, p| a + p) / n;
    let [mut xx, mut xy, mut xz, mut yy, mut yz, mut zz] = [0.0f64; 6];
    for p in points {
        let d = p - mean;
        xx += d.x * d.x;
        xy += d.x * d.y;
        xz += d.x * d.z;
        yy += d.y * d.y;
        yz += d.y * d.z;
        zz += d.z * d.z;
    }
    let (xx, xy, xz, yy, yz, zz) = (xx / n, xy / n, xz / n, yy / n, yz / n, zz / n);
    Mat3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

fn placeholder() -> Node {
    let axes = Mat3::identity();
    Node::new(
        &Ssv {
            axes,
            origin: Vec3::zeros(),
            lengths: [0.0; 2],
            radius: 0.0,
        },
        &Obb {
            axes,
            center: Vec3::zeros(),
            half: Vec3::zeros(),
        },
    )
}

/// A triangle's split key: its centroid's projection on the splitting axis.
#[inline(always)]
fn split_key(t: &Tri, axis: &Vec3) -> f64 {
    ((t[0] + t[1] + t[2]) / 3.0).dot(axis)
}

/// Partitions the triangles `tris` (at least two; their insertion indices `added` and split `keys`
/// alongside) and
/// returns how many go to the first child (never 0 nor all): those whose centroid projects below
/// the mean, or the lower half by projection when the mean splits nothing off or `median` is asked
/// for.
fn split(tris: &mut [Tri], added: &mut [u32], keys: &mut [f64], median: bool) -> usize {
    let count = tris.len();
    debug_assert_eq!(keys.len(), count);
    if !median {
        let mean = keys.iter().sum::<f64>() / count as f64;
        let mut left = 0;
        for i in 0..count {
            if keys[i] < mean {
                if i != left {
                    tris.swap(i, left);
                    added.swap(i, left);
                    keys.swap(i, left);
                }
                left += 1;
            }
        }
        if left > 0 && left < count {
            return left;
        }
        // Nothing moved: every triangle went to the same side, each swapped with itself.
    }
    // Halves by projection. Sort keys alongside the positions so equal projections split evenly
    // too, then move the triangles and their insertion indices to the positions' new order.
    let mut pairs: Vec<(f64, u32)> = keys.iter().copied().zip(0..count as u32).collect();
    let mid = count / 2;
    pairs.select_nth_unstable_by(mid, |a, b| a.0.total_cmp(&b.0));
    let (old_tris, old_added) = (tris.to_vec(), added.to_vec());
    for (k, &(_, i)) in pairs.iter().enumerate() {
        tris[k] = old_tris[i as usize];
        added[k] = old_added[i as usize];
    }
    mid
}

/// The node's volumes on `axes` around its `points` (not empty): the swept sphere volume of the
/// model's kind (for the hybrid the kind that suits the points) and the box. The same as
/// [`Ssv::fit`] and [`Obb::fit`], bit for bit, for less work: the points are taken into the frame
/// once for all the fits (into `local`, scratch), and both volumes are covered in one pass that
/// skips the points clearly inside both. `scale` is at least every point's `|p|_1`. While the
/// triangles are at hand, puts their split keys (see [`split_key`]) into `keys`.
fn fit_volumes(
    volume: VolumeKind,
    axes: &Mat3,
    tris: &[Tri],
    scale: f64,
    local: &mut Vec<Vec3>,
    keys: &mut Vec<f64>,
) -> (Ssv, Obb) {
    let points = tris.as_flattened();
    let axis: Vec3 = axes.column(0).into();
    let first = axes.tr_mul(&points[0]);
    let (mut lo, mut hi) = (first, first);
    local.clear();
    keys.clear();
    for t in tris {
        keys.push(split_key(t, &axis));
        for p in t {
            let q = axes.tr_mul(p);
            // Plain comparisons rather than `f64::min`: no NaN here to handle.
            for k in 0..3 {
                if q[k] < lo[k] {
                    lo[k] = q[k];
                }
                if q[k] > hi[k] {
                    hi[k] = q[k];
                }
            }
            local.push(q);
        }
    }
    let local = &local[..];
    let at = |i: usize| local[i];
    let kind = match volume {
        VolumeKind::Pss => SsvKind::Point,
        VolumeKind::Lss => SsvKind::Line,
        VolumeKind::Rss => SsvKind::Rect,
        VolumeKind::Hybrid => {
            let ssv = hybrid_by_volume(axes, points, at, lo.z, hi.z);
            return (ssv, Obb::from_bounds(axes, &lo, &hi).cover(points));
        }
    };
    let mut ssv = Ssv::fit_uncovered(kind, axes, points.len(), at, &[], lo.z, hi.z);
    let mut obb = Obb::from_bounds(axes, &lo, &hi);

    // Both covers in one pass, each exactly as `Ssv::cover` and `Obb::cover` do it, but only for
    // the points that might move them. A point's offsets from a volume's reference point, as the
    // covers compute them (`A^T (p - o)`, rounded), differ from `q - A^T o` (`q = A^T p` the
    // point in the frame, also rounded) by less than `slack`: a few roundings of terms no larger
    // than `|A| (|p|_1 + |o|_1)`, each at most `EPSILON / 2` of them; COVER_SLACK allows ten times
    // that. A point whose offsets are inside the volume by more than that (and by a relative
    // margin for the rounding of the test itself) is inside as the covers measure it, so it
    // leaves them unchanged: skipping it gives the same volumes, bit for bit. Only points within
    // the margin of a boundary, usually a few per node, take the exact computation.
    let amax = axes.amax();
    let ssv_ref = axes.tr_mul(&ssv.origin);
    let ssv_slack = COVER_SLACK * amax * (scale + ssv.origin.abs().sum());
    let r2_inside = ssv.radius * ssv.radius * (1.0 - COVER_SLACK);
    let [l0, l1] = ssv.lengths;
    let obb_ref = axes.tr_mul(&obb.center);
    let obb_slack = COVER_SLACK * amax * (scale + obb.center.abs().sum());
    let half_inside = obb.half * (1.0 - COVER_SLACK);
    // The largest squared distance, then its root (as `Ssv::cover`).
    let mut far2 = 0.0f64;
    for (p, q) in points.iter().zip(local) {
        let s = q - ssv_ref;
        let dx = outside(s.x, l0) + ssv_slack;
        let dy = outside(s.y, l1) + ssv_slack;
        let dz = s.z.abs() + ssv_slack;
        let ssv_inside = dx * dx + dy * dy + dz * dz < r2_inside;
        let b = q - obb_ref;
        // Non-short-circuit `&`: one well-predicted branch rather than four.
        let obb_inside = (b.x.abs() + obb_slack < half_inside.x)
            & (b.y.abs() + obb_slack < half_inside.y)
            & (b.z.abs() + obb_slack < half_inside.z);
        if ssv_inside & obb_inside {
            continue;
        }
        if !ssv_inside {
            let d2 = ssv.core_distance_squared(p);
            if d2 > far2 {
                far2 = d2;
            }
        }
        if !obb_inside {
            obb.cover_point(p);
        }
    }
    ssv.radius = ssv.radius.max(far2.sqrt());
    (ssv, obb)
}

/// Bound on the rounding of a volume's offsets from a point (see `fit_volumes`), relative to the
/// magnitudes involved, and the relative margin of the test that uses it.
const COVER_SLACK: f64 = 64.0 * f64::EPSILON;

/// How far `x` is outside `[0, len]` (`len >= 0`), without branches.
#[inline(always)]
fn outside(x: f64, len: f64) -> f64 {
    let below = -x;
    let above = x - len;
    let d = if below > above { below } else { above };
    if d > 0.0 { d } else { 0.0 }
}

/// The smallest by volume of the three fits (covered; arguments as [`Ssv::fit_uncovered`] takes
/// them). Measured against choosing by the spread of the covariance eigenvalues (a capsule when the
/// second is below a quarter of the first, a sphere when the third is above it, else a rectangle):
/// this rule did less work and was faster on every workload of `examples/volume_family.rs`, as a
/// smaller volume prunes more.
fn hybrid_by_volume(
    axes: &Mat3,
    points: &[Vec3],
    local: impl Fn(usize) -> Vec3 + Copy,
    zmin: f64,
    zmax: f64,
) -> Ssv {
    let fit =
        |kind| Ssv::fit_uncovered(kind, axes, points.len(), local, &[], zmin, zmax).cover(points);
    let mut best = fit(SsvKind::Point);
    // The sphere is the largest of the three: measure in its radius (a positive one).
    let unit = if best.radius > 0.0 { best.radius } else { 1.0 };
    let mut least = best.volume(unit);
    for kind in [SsvKind::Line, SsvKind::Rect] {
        let v = fit(kind);
        let vol = v.volume(unit);
        if vol < least {
            (best, least) = (v, vol);
        }
    }
    best
}

/// Principal axes of a point set: eigenvectors of its covariance, as orthonormal right-handed
/// columns in decreasing order of eigenvalue. Identity when the covariance gives no usable frame.
pub(crate) fn principal_axes(points: &[Vec3]) -> Mat3 {
    let cov = covariance(points);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bounding_volume::BoundingVolume;
    use crate::test_rng::Lcg;

    fn check_containment(bvh: &Bvh) {
        // Every node's volumes contain every vertex of every triangle below it.
        fn rec(b: &Bvh, r: NodeRef, out: &mut Vec<usize>) {
            if r.is_leaf() {
                out.push(r.triangle());
            } else {
                let [c0, c1] = b.children(r);
                rec(b, c0, out);
                rec(b, c1, out);
            }
        }
        let refs = (0..bvh.nodes.len())
            .map(NodeRef::inner)
            .chain((0..bvh.num_tris()).map(NodeRef::leaf));
        for r in refs {
            let mut tris = Vec::new();
            rec(bvh, r, &mut tris);
            let (ssv, obb) = (bvh.ssv(r), bvh.obb(r));
            // The model-wide bound on the volumes' scales (their rounding allowance) holds.
            assert!(
                ssv.scale() <= bvh.scale,
                "node {r}: {} {}",
                ssv.scale(),
                bvh.scale
            );
            for t in tris {
                for v in &bvh.tri(t) {
                    let eps = 1e-9 * (1.0 + v.norm());
                    assert!(ssv.contains(v, eps), "ssv of node {r} misses {v:?}");
                    assert!(obb.contains(v, eps), "obb of node {r} misses {v:?}");
                    assert!(ssv.contains(v, 0.0) && obb.contains(v, 0.0), "node {r}");
                }
            }
        }
    }

    /// `added` is a permutation that maps every leaf slot to the triangle given in that position,
    /// with its id, bit for bit.
    fn check_insertion_order(bvh: &Bvh, tris: &[(Tri, i32)]) {
        let mut seen = vec![false; tris.len()];
        assert_eq!(bvh.added.len(), tris.len());
        for (t, &k) in bvh.added.iter().enumerate() {
            let k = k as usize;
            assert!(!std::mem::replace(&mut seen[k], true), "{k} twice");
            assert_eq!(bvh.tri(t), tris[k].0, "slot {t}");
            assert_eq!(bvh.ids[t], tris[k].1, "slot {t}");
        }
    }

    /// Builds with every volume kind, checks that every node's volumes contain its vertices, and
    /// returns the default build.
    fn build_checked(tris: Vec<(Tri, i32)>) -> Bvh {
        for v in [VolumeKind::Pss, VolumeKind::Lss, VolumeKind::Hybrid] {
            let b = Bvh::build(tris.clone(), v, CollisionVolume::Ssv).unwrap();
            check_containment(&b);
        }
        let b = Bvh::build(tris, VolumeKind::Rss, CollisionVolume::Obb).unwrap();
        check_containment(&b);
        b
    }

    fn tri(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Tri {
        [Vec3::from(a), Vec3::from(b), Vec3::from(c)]
    }

    /// Uniform in [-0.5, 0.5).
    fn lcg(rng: &mut Lcg) -> f64 {
        rng.unit() - 0.5
    }

    #[test]
    fn every_node_contains_its_triangles() {
        let mut s = Lcg(11);
        for (n, scale, offset) in [
            (1, 1.0, 0.0),
            (2, 1.0, 0.0),
            (57, 1.0, 0.0),
            (300, 1e-4, 5.0),
            (500, 1e3, 1e6),
        ] {
            let tris: Vec<(Tri, i32)> = (0..n)
                .map(|i| {
                    let c = Vec3::new(lcg(&mut s), lcg(&mut s), lcg(&mut s)) * 10.0 * scale;
                    let mut v = || {
                        (c + Vec3::new(lcg(&mut s), lcg(&mut s), lcg(&mut s)) * scale)
                            .add_scalar(offset)
                    };
                    ([v(), v(), v()], i)
                })
                .collect();
            let bvh = build_checked(tris.clone());
            assert_eq!(bvh.nodes.len(), n as usize - 1);
            let mut ids = bvh.ids.clone();
            ids.sort();
            assert_eq!(ids, (0..n).collect::<Vec<_>>());
            check_insertion_order(&bvh, &tris);
        }
    }

    #[test]
    fn flat_and_degenerate_input_builds_with_small_depth() {
        // All triangles identical: centroids all equal, the mean splits nothing off.
        let same: Vec<(Tri, i32)> = (0..1000)
            .map(|i| (tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), i))
            .collect();
        let b = build_checked(same.clone());
        assert!(b.depth() <= 11, "depth {}", b.depth());
        check_insertion_order(&b, &same);
        // All points at one place.
        let points: Vec<(Tri, i32)> = (0..64)
            .map(|i| (tri([2.0; 3], [2.0; 3], [2.0; 3]), i))
            .collect();
        let b = build_checked(points);
        assert!(b.depth() <= 7);
        // Collinear segments.
        let segs: Vec<(Tri, i32)> = (0..100)
            .map(|i| {
                let x = i as f64;
                (
                    tri([x, 0.0, 0.0], [x + 0.5, 0.0, 0.0], [x + 0.25, 0.0, 0.0]),
                    i,
                )
            })
            .collect();
        build_checked(segs);
    }

    #[test]
    fn exponentially_spaced_input_keeps_depth_bounded() {
        // A mean split peels one triangle per level here; the median fallback bounds the depth.
        let n = 2000;
        let tris: Vec<(Tri, i32)> = (0..n)
            .map(|i| {
                let x = 1.01f64.powi(i);
                (tri([x, 0.0, 0.0], [x, 1.0, 0.0], [x, 0.0, 1.0]), i)
            })
            .collect();
        let b = build_checked(tris.clone());
        assert!(b.depth() <= MAX_DEPTH, "depth {}", b.depth());
        // The median split's moves keep the mapping too.
        check_insertion_order(&b, &tris);
    }

    #[test]
    fn node_fits_equal_the_separate_fits() {
        // `fit_volumes` (shared frame coordinates, skipped covers) gives exactly the volumes of
        // `Ssv::fit` and `Obb::fit`, on clouds, flat and duplicated sets, far from the origin.
        let mut s = Lcg(5);
        let mut local = Vec::new();
        let mut keys = Vec::new();
        for case in 0..400 {
            let n = 1 + case % 37;
            let (scale, offset) = [(1.0, 0.0), (1e-3, 7.0), (1e4, -3e6), (1.0, 1e9)][case % 4];
            let flat = case % 5 == 0;
            let mut point = || {
                let z = if flat { 0.25 } else { lcg(&mut s) };
                (Vec3::new(lcg(&mut s), 0.3 * lcg(&mut s), z) * scale).add_scalar(offset)
            };
            let mut tris: Vec<Tri> = (0..n).map(|_| [point(), point(), point()]).collect();
            if case % 3 == 0 {
                let dup = tris.clone();
                tris.extend(dup);
            }
            let pts = tris.as_flattened();
            let a = principal_axes(pts);
            let axes = frame_from(&a.column(0).into(), &a.column(1).into());
            let scale = 2.0 * pts.iter().fold(0.0f64, |m, p| m.max(p.abs().sum()));
            for (volume, kind) in [
                (VolumeKind::Pss, SsvKind::Point),
                (VolumeKind::Lss, SsvKind::Line),
                (VolumeKind::Rss, SsvKind::Rect),
            ] {
                let (ssv, obb) = fit_volumes(volume, &axes, &tris, scale, &mut local, &mut keys);
                assert_eq!(ssv, Ssv::fit(kind, &axes, pts), "case {case} {kind:?}");
                assert_eq!(obb, Obb::fit(&axes, pts), "case {case}");
                let axis: Vec3 = axes.column(0).into();
                let want: Vec<f64> = tris.iter().map(|t| split_key(t, &axis)).collect();
                assert_eq!(keys, want);
            }
        }
    }

    #[test]
    fn principal_axes_are_orthonormal_and_ordered() {
        let pts: Vec<Vec3> = (0..50)
            .map(|i| {
                let t = i as f64;
                Vec3::new(3.0 * t.sin(), t.cos(), 0.1 * (2.0 * t).sin())
            })
            .collect();
        let ax = principal_axes(&pts);
        assert!((ax.transpose() * ax - Mat3::identity()).norm() < 1e-12);
        assert!((ax.determinant() - 1.0).abs() < 1e-12);
        assert!(ax.column(0).x.abs() > 0.9);
        // A single point has no spread: any orthonormal frame will do, but it must be one.
        let one = principal_axes(&[Vec3::new(1.0, 2.0, 3.0)]);
        assert!((one.transpose() * one - Mat3::identity()).norm() < 1e-12);
        // Coordinates whose squares overflow fall back to the identity rather than NaN.
        let huge = principal_axes(&[Vec3::new(1e200, 0.0, 0.0), Vec3::new(-1e200, 1.0, 0.0)]);
        assert_eq!(huge, Mat3::identity());
    }
}
