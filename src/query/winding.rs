//! The generalized winding number of a model about a point: the solid angle its triangles
//! subtend there, over 4 pi. For a closed mesh it is the number of times the surface wraps the
//! point (0 outside, 1 or -1 inside as the triangles face out or in); for an open or
//! self-intersecting one it varies smoothly in between, and the signed distance takes a point as
//! inside where it is at least 1/2 in magnitude.
//!
//! Computed hierarchically and exactly: a node whose swept sphere volume lies away from the point
//! (by a tenth of its size) subtends the same solid angle as any surface with the same boundary
//! inside the same convex volume, since the two together close up a surface that does not wrap the
//! point. So it is summed as a fan from one of its boundary vertices over its boundary edges
//! (`bvh/boundary.rs`), or over its triangles where those are fewer, and a closed node costs
//! nothing; only the nodes near the point are opened, down to their triangles. The margin keeps
//! every fan triangle well away from the point, where its solid angle is well conditioned.

use super::prepare_point as prepare;
use super::traversal::{NodePair, PairStack};
use crate::bounding_volume::{BoundingVolume, Ssv};
use crate::bvh::{Bvh, NodeKind, NodeRef, NodeSurface};
use crate::error::Error;
use crate::geometry::{SolidAngleSum, solid_angle};
use crate::math::{Pose, RelPose, Vec3};
use crate::model::Model;
use std::f64::consts::PI;

/// How far, in units of its size, a node's volume must be from the point to be summed as a fan
/// rather than opened.
const FAR: f64 = 0.1;

/// The generalized winding number of `model` posed by `pose` about `point` (world coordinates):
/// the signed solid angle its triangles subtend at the point, over 4 pi, a triangle counting
/// positively when the point is behind it (its normal `(p2 - p1) x (p3 - p1)` pointing away).
///
/// For a closed mesh it is an integer up to rounding (0 outside, 1 inside when the triangles
/// face outwards, -1 when they face inwards); [`signed_distance`](super::signed_distance) counts a
/// point as inside when it is at least 1/2 in magnitude. On the surface itself it is undefined
/// (any value may come back).
///
/// The first call on a model computes each node's boundary edges (kept in the model, see
/// `Model::memory_usage`); it fails with `OutOfMemory` if they cannot be allocated. Other errors
/// as [`closest_point`](super::closest_point) (`max_distance` aside).
///
/// ```
/// use pqp::{Model, Pose, Vec3, winding_number};
/// let v = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
/// let m = Model::from_triangles(faces.iter().map(|f| (v[f[0]], v[f[1]], v[f[2]], 0))).unwrap();
/// let w = winding_number(&m, &Pose::identity(), &Vec3::new(0.1, 0.1, 0.2)).unwrap();
/// assert!((w - 1.0).abs() < 1e-12);
/// ```
pub fn winding_number(model: &Model, pose: &Pose, point: &Vec3) -> Result<f64, Error> {
    let (bvh, p) = prepare(model, pose, point)?;
    winding_at(bvh, &p)
}

/// The winding number about `p` (model frame).
pub(crate) fn winding_at(bvh: &Bvh, p: &Vec3) -> Result<f64, Error> {
    let root = bvh.root();
    if let NodeKind::Leaf(t) = root.kind() {
        let [a, b, c] = bvh.tri(t);
        return Ok(solid_angle(&(a - p), &(b - p), &(c - p)) / (4.0 * PI));
    }
    let boundaries = bvh.boundaries()?;
    let slack = Ssv::slack_for(bvh.scale, p.abs().sum(), &RelPose::identity());
    // One sum for every solid angle of the query (see `SolidAngleSum`: one atan2 in all).
    let mut sum = SolidAngleSum::default();
    let mut add = |a: Vec3, b: Vec3, c: Vec3| sum.add(&(a - p), &(b - p), &(c - p));
    let mut stack = PairStack::new();
    stack.push(entry(root));
    while let Some(NodePair { a: r, .. }) = stack.pop() {
        let NodeKind::Inner(_) = r.kind() else {
            let [a, b, c] = bvh.tri(r.triangle());
            add(a, b, c);
            continue;
        };
        let v = bvh.inner_ssv(r).full();
        if v.core_distance(p) <= v.radius + FAR * v.size() + slack {
            let [c0, c1] = bvh.children(r);
            stack.push(entry(c0));
            stack.push(entry(c1));
            continue;
        }
        match boundaries.node(r) {
            NodeSurface::Fan(edges) => {
                // From the first boundary vertex (a closed node has none, and adds nothing).
                if let Some(e) = edges.first() {
                    let o = bvh.vertex(e[0]);
                    for e in edges {
                        add(o, bvh.vertex(e[0]), bvh.vertex(e[1]));
                    }
                }
            }
            NodeSurface::Triangles(slots) => {
                for t in slots {
                    let [a, b, c] = bvh.tri(t);
                    add(a, b, c);
                }
            }
        }
    }
    Ok(sum.total() / (4.0 * PI))
}

/// A stack entry for node `r`.
#[inline(always)]
fn entry(r: NodeRef) -> NodePair {
    NodePair {
        a: r,
        b: r,
        bound: 0.0,
    }
}
