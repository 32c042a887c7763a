//! Point queries: the closest point of a posed model to a point, and the signed distance (negative
//! inside, by the winding number of `winding.rs`).
//!
//! Both work in the model's frame: the point is carried there by the inverse pose (the rotation
//! taken as orthonormal), and the answer carried back.

use super::prepare_point as prepare;
use super::winding::winding_at;
use crate::bvh::{Bvh, MAX_DEPTH, RayChild};
use crate::error::Error;
use crate::geometry::point_triangle;
use crate::math::{Pose, Vec3};
use crate::model::Model;
use std::mem::MaybeUninit;

/// The answer of [`closest_point`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointResult {
    /// Distance from the point to the posed model; `INFINITY` if it exceeds the `max_distance`
    /// asked for.
    pub distance: f64,
    /// The closest point of the model, in world coordinates; NaN in every coordinate if the
    /// model is beyond `max_distance`.
    pub point: Vec3,
    /// The caller's id of the triangle holding it (one of the closest triangles when several are:
    /// always the same one for the same model, pose and point); `None` beyond `max_distance`.
    pub triangle: Option<i32>,
}

/// The closest point of `model` posed by `pose` to `point` (world coordinates), if it lies within
/// `max_distance` (which may be infinite).
///
/// Exact: the distance is that of the exact point-triangle routine to the nearest triangle, found
/// by a depth-first descent of the model's four-wide tree of axis-aligned boxes (made on the
/// model's first point query or ray cast and kept in it), nearer boxes first, pruned by the
/// distance to each box and by the best distance so far (`max_distance` to start with).
/// Degenerate triangles count as the segment or point they span.
///
/// Errors: `UnprocessedModel` (not built), `NonFinitePose`, `NonFiniteCoordinate` (a coordinate
/// of `point` NaN, infinite or beyond 1e150 in magnitude), `InvalidArgument` (`max_distance`
/// negative or NaN), `OutOfMemory` if the tree of boxes cannot be allocated.
///
/// ```
/// use pqp::{Model, Pose, Vec3, closest_point};
/// let m = Model::from_triangles([([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 7)]).unwrap();
/// let r = closest_point(&m, &Pose::identity(), &Vec3::new(0.2, 0.2, 3.0), f64::INFINITY).unwrap();
/// assert_eq!((r.distance, r.triangle), (3.0, Some(7)));
/// assert_eq!(r.point, Vec3::new(0.2, 0.2, 0.0));
/// ```
pub fn closest_point(
    model: &Model,
    pose: &Pose,
    point: &Vec3,
    max_distance: f64,
) -> Result<PointResult, Error> {
    if max_distance.is_nan() || max_distance < 0.0 {
        return Err(Error::InvalidArgument);
    }
    let (bvh, p) = prepare(model, pose, point)?;
    Ok(match nearest(bvh, &p, max_distance)? {
        Some(c) => PointResult {
            distance: c.distance,
            point: pose.transform_point(&c.q),
            triangle: Some(bvh.ids[c.slot]),
        },
        None => PointResult {
            distance: f64::INFINITY,
            point: Vec3::repeat(f64::NAN),
            triangle: None,
        },
    })
}

/// The signed distance from `point` (world coordinates) to `model` posed by `pose`: the distance,
/// negated when the point is inside, that is when the model's generalized winding number about
/// it ([`winding_number`](super::winding_number)) is at least 1/2 in magnitude. Exact for closed
/// meshes of either orientation; for open or self-intersecting ones, inside is where the surface
/// wraps the point at least half way round. A point on the surface has distance 0.
///
/// Errors as [`closest_point`], and `OutOfMemory` if the per-node data of the winding number,
/// computed on the model's first signed distance, or the tree of boxes cannot be allocated.
///
/// ```
/// use pqp::{Model, Pose, Vec3, signed_distance};
/// // A tetrahedron, its faces outwards.
/// let v = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
/// let m = Model::from_triangles(faces.iter().map(|f| (v[f[0]], v[f[1]], v[f[2]], 0))).unwrap();
/// let here = Pose::identity();
/// assert_eq!(signed_distance(&m, &here, &Vec3::new(0.1, 0.1, 0.2)).unwrap(), -0.1);
/// assert_eq!(signed_distance(&m, &here, &Vec3::new(0.1, 0.1, -0.5)).unwrap(), 0.5);
/// ```
pub fn signed_distance(model: &Model, pose: &Pose, point: &Vec3) -> Result<f64, Error> {
    let (bvh, p) = prepare(model, pose, point)?;
    let d = nearest(bvh, &p, f64::INFINITY)?.map_or(f64::INFINITY, |c| c.distance);
    if d == 0.0 {
        return Ok(0.0);
    }
    let w = winding_at(bvh, &p)?;
    Ok(if w.abs() >= 0.5 { -d } else { d })
}

/// A closest triangle found: its slot in leaf order, distance and closest point (model frame).
struct Nearest {
    slot: usize,
    distance: f64,
    q: Vec3,
}

/// The nearest triangle to `p` (model frame) within `max_distance`, if any (of equally near
/// triangles, the first found): a depth-first descent of the model's axis-aligned four-wide tree
/// ([`Bvh::ray_tree`], built on the model's first ray cast or point query), nearer boxes first,
/// pruned by the squared distance to each box against the best distance so far
/// (`max_distance` to start with). `Err(OutOfMemory)` if the tree cannot be built.
fn nearest(bvh: &Bvh, p: &Vec3, max_distance: f64) -> Result<Option<Nearest>, Error> {
    let tree = bvh.ray_tree()?;
    // The gaps' subtraction rounds by an ulp of the larger operand: far less than this.
    let slack = 1e-12 * (p.amax() + tree.extent()) + 1e-300;
    let q = [p.x, p.y, p.z];
    let mut best: Option<Nearest> = None;
    let mut cutoff = max_distance;
    // A box is opened while its bound is within the best distance squared (rounded up a little:
    // the bound's own rounding is a few ulps).
    let reach = |c: f64| c * c * (1.0 + 1e-12);
    let mut stack = [const { MaybeUninit::<(RayChild, f64)>::uninit() }; 3 * MAX_DEPTH + 4];
    let mut len = 0;
    let mut node = RayChild::Inner(tree.root());
    loop {
        match node {
            RayChild::Inner(i) => {
                let d2 = tree.gaps(i, &q, slack);
                let limit = reach(cutoff);
                // The children within reach, farthest first: all but the nearest are stacked.
                let mut near = [(0usize, 0.0f64); 4];
                let mut n = 0;
                for (k, &d) in d2.iter().enumerate() {
                    if d <= limit {
                        let mut j = n;
                        while j > 0 && near[j - 1].1 < d {
                            near[j] = near[j - 1];
                            j -= 1;
                        }
                        near[j] = (k, d);
                        n += 1;
                    }
                }
                if n > 0 {
                    for &(k, d) in &near[..n - 1] {
                        // Checked indexing: the depth bound keeps it in range.
                        stack[len] = MaybeUninit::new((tree.child(i, k), d));
                        len += 1;
                    }
                    node = tree.child(i, near[n - 1].0);
                    continue;
                }
            }
            RayChild::Leaf { first, count } => {
                for j in first..first + count {
                    let t = tree.slot(j);
                    let c = point_triangle(p, &bvh.tri(t));
                    // `<=` on the first keeps a triangle exactly at max_distance; `<` after keeps
                    // the first of equally near triangles.
                    if c.distance <= cutoff && best.as_ref().is_none_or(|b| c.distance < b.distance)
                    {
                        cutoff = c.distance;
                        best = Some(Nearest {
                            slot: t,
                            distance: c.distance,
                            q: c.q,
                        });
                    }
                }
            }
        }
        loop {
            if len == 0 {
                return Ok(best);
            }
            len -= 1;
            // SAFETY: the entries below `len` were written above.
            let (next, d) = unsafe { stack[len].assume_init() };
            if d <= reach(cutoff) {
                node = next;
                break;
            }
        }
    }
}
