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
use crate::bvh::{Boundaries, BoundaryLoop, Bvh, NodeKind, NodeRef, NodeSurface};
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
    // One sum for every solid angle of the query (see `SolidAngleSum`: one atan2 in all).
    let mut sum = SolidAngleSum::default();
    let mut add = |a: Vec3, b: Vec3, c: Vec3| sum.add(&(a - p), &(b - p), &(c - p));
    walk(bvh, p, &mut add, |r, gap, margin, add| {
        // Nearer than the margin, the node is opened.
        gap > margin && {
            node_surface(bvh, boundaries, r, add);
            true
        }
    });
    Ok(sum.total() / (4.0 * PI))
}

/// The largest error bound of a far field's term that [`inside`] takes rather than looking
/// closer.
const FAR_FIELD_ERROR: f64 = 0.05;

/// How far from 1/2 the estimate of [`inside`] must be, beyond its error bound, to be taken: far
/// above the rounding of the exact sum, so that whatever the estimate decides the exact sum
/// decides alike.
const CERTAIN: f64 = 1e-9;

/// Whether `p` (model frame) is inside, as the signed distance defines it: the winding number
/// about it ([`winding_at`]) at least 1/2 in magnitude.
///
/// The same answer as comparing [`winding_at`], sooner: first an estimate with a rigorous error
/// bound, in which the boundary loops of nodes seen from afar count for their far field's term
/// (`bvh/far_field.rs`) where it is precise enough, and everything else as in [`winding_at`];
/// when the bound cannot tell which side of 1/2 the number lies, the exact sum.
pub(crate) fn inside(bvh: &Bvh, p: &Vec3) -> Result<bool, Error> {
    if let NodeKind::Inner(_) = bvh.root().kind()
        && let Some(inside) = estimate(bvh, p)?
    {
        return Ok(inside);
    }
    Ok(winding_at(bvh, p)?.abs() >= 0.5)
}

/// [`inside`] by the estimate, if its bound tells.
fn estimate(bvh: &Bvh, p: &Vec3) -> Result<Option<bool>, Error> {
    let boundaries = bvh.boundaries()?;
    let mut sum = SolidAngleSum::default();
    let mut add = |a: Vec3, b: Vec3, c: Vec3| sum.add(&(a - p), &(b - p), &(c - p));
    // The far fields' terms and their error bounds.
    let (mut dipoles, mut error) = (0.0, 0.0);
    walk(bvh, p, &mut add, |r, gap, margin, add| {
        let loops = boundaries.loops(r);
        // Outside the node's volume, and so outside the convex hull of its vertices, its loops'
        // far fields hold; nearer than the margin of `winding_at`, only they do (a fan's
        // triangles may pass close to the point): if one is not precise enough, the node is
        // opened.
        let precise = |l: &BoundaryLoop| l.far.at(p).is_some_and(|(_, e)| e <= FAR_FIELD_ERROR);
        if gap <= margin && (gap <= 0.0 || loops.is_empty() || !loops.iter().all(precise)) {
            return false;
        }
        if loops.is_empty() {
            node_surface(bvh, boundaries, r, add);
        }
        for l in loops {
            match l.far.at(p) {
                Some((w, e)) if e <= FAR_FIELD_ERROR => {
                    dipoles += w;
                    error += e;
                }
                _ => fan(bvh, boundaries.loop_edges(l), add),
            }
        }
        true
    });
    let w = (sum.total() / (4.0 * PI) + dipoles).abs();
    let margin = error + CERTAIN;
    Ok(if w - margin >= 0.5 {
        Some(true)
    } else if w + margin < 0.5 {
        Some(false)
    } else {
        None
    })
}

/// The descent of [`winding_at`] and [`estimate`] from the root (an inner node): a triangle is
/// added by `add`; an inner node `r` is offered to `far` with the gap between `p` and its volume
/// (less the bounds' slack) and the margin `winding_at` keeps from it (a tenth of its size), and
/// opened unless `far` takes it (answers true).
fn walk<A: FnMut(Vec3, Vec3, Vec3)>(
    bvh: &Bvh,
    p: &Vec3,
    add: &mut A,
    mut far: impl FnMut(NodeRef, f64, f64, &mut A) -> bool,
) {
    let slack = Ssv::slack_for(bvh.scale, p.abs().sum(), &RelPose::identity());
    let mut stack = PairStack::new();
    stack.push(entry(bvh.root()));
    while let Some(NodePair { a: r, .. }) = stack.pop() {
        let NodeKind::Inner(_) = r.kind() else {
            let [a, b, c] = bvh.tri(r.triangle());
            add(a, b, c);
            continue;
        };
        let v = bvh.inner_ssv(r).full();
        if !far(
            r,
            v.core_distance(p) - v.radius - slack,
            FAR * v.size(),
            add,
        ) {
            let [c0, c1] = bvh.children(r);
            stack.push(entry(c0));
            stack.push(entry(c1));
        }
    }
}

/// Adds what inner node `r` subtends from afar: the fan over its boundary from its first vertex
/// (a closed node has none, and adds nothing), or its triangles.
fn node_surface(
    bvh: &Bvh,
    boundaries: &Boundaries,
    r: NodeRef,
    add: &mut impl FnMut(Vec3, Vec3, Vec3),
) {
    match boundaries.node(r) {
        NodeSurface::Fan(edges) => fan(bvh, edges, add),
        NodeSurface::Triangles(slots) => {
            for t in slots {
                let [a, b, c] = bvh.tri(t);
                add(a, b, c);
            }
        }
    }
}

/// Adds the fan over boundary `edges` from its first vertex (nothing if there are none).
#[inline]
fn fan(bvh: &Bvh, edges: &[[u32; 2]], add: &mut impl FnMut(Vec3, Vec3, Vec3)) {
    if let Some(e) = edges.first() {
        let o = bvh.vertex(e[0]);
        for e in edges {
            add(o, bvh.vertex(e[0]), bvh.vertex(e[1]));
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::{CollisionVolume, VolumeKind};
    use crate::test_rng::{Lcg, Random};

    /// A UV sphere of radius 1 about the origin, scaled by `s`, keeping the triangles that
    /// `keep` accepts (by their centroid): holes cut into a closed surface.
    fn cut_sphere(n: usize, s: f64, keep: impl Fn(&Vec3) -> bool) -> Bvh {
        let at = |i: usize, j: usize| {
            let (th, ph) = (PI * i as f64 / n as f64, 2.0 * PI * j as f64 / n as f64);
            Vec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos())
        };
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                for t in [[a, b, c], [a, c, d]] {
                    let area = (t[1] - t[0]).cross(&(t[2] - t[0])).norm();
                    if area > 0.0 && keep(&((t[0] + t[1] + t[2]) / 3.0)) {
                        tris.push((t.map(|v| v * s), tris.len() as i32));
                    }
                }
            }
        }
        Bvh::build(tris, VolumeKind::Rss, CollisionVolume::Obb).unwrap()
    }

    /// The point where the winding number crosses 1/2 on the segment from `a` (|w| below) to
    /// `b` (above), by bisection.
    fn half_crossing(bvh: &Bvh, a: Vec3, b: Vec3) -> Vec3 {
        let (mut lo, mut hi) = (a, b);
        for _ in 0..60 {
            let m = (lo + hi) * 0.5;
            if winding_at(bvh, &m).unwrap().abs() >= 0.5 {
                hi = m;
            } else {
                lo = m;
            }
        }
        lo
    }

    /// The estimate decides as the exact winding number does: on open meshes (a sphere with
    /// holes of several sizes, a hemisphere; the bunny in `tests/point_queries.rs`) at huge, unit
    /// and tiny scales, for points
    /// anywhere in and around them, on and next to the surface, far away, and on either side of
    /// the surface where the number crosses 1/2.
    #[test]
    fn inside_decides_as_the_exact_winding_number() {
        let mut rng = Lcg(17);
        let holes = |c: &Vec3| {
            (c - Vec3::new(0.0, 0.0, 1.0)).norm() > 0.5
                && (c - Vec3::new(1.0, 0.0, 0.0)).norm() > 0.25
                && (c - Vec3::new(0.0, -1.0, 0.0)).norm() > 0.1
        };
        let (mut estimated, mut near_half) = (0, 0);
        for s in [1e-120, 1.0, 1e120] {
            let meshes = [
                cut_sphere(40, s, holes),
                cut_sphere(30, s, |c| c.z > -0.3),
                cut_sphere(16, s, |c| c.x < 0.9),
            ];
            for bvh in &meshes {
                let mut check = |p: Vec3| {
                    let exact = winding_at(bvh, &p).unwrap().abs() >= 0.5;
                    assert_eq!(inside(bvh, &p).unwrap(), exact, "{p} at scale {s}");
                    if let Some(e) = estimate(bvh, &p).unwrap() {
                        assert_eq!(e, exact);
                        estimated += 1;
                    }
                };
                for _ in 0..150 {
                    let p = Vec3::from(rng.point(2.0)) * s;
                    check(p);
                    check(p * 10.0);
                    // On and next to the surface.
                    let [a, b, c] = bvh.tri(rng.below(bvh.faces.len()));
                    let (u, v) = (rng.unit(), rng.unit());
                    let q = if u + v <= 1.0 {
                        a + (b - a) * u + (c - a) * v
                    } else {
                        a + (b - a) * (1.0 - u) + (c - a) * (1.0 - v)
                    };
                    check(q);
                    check(q + Vec3::from(rng.direction()) * (s * 1e-6));
                    // Across 1/2, from a point far out to the centre (w is near 1 inside).
                    let far = Vec3::from(rng.direction()) * (3.0 * s);
                    let centre = Vec3::from(rng.point(0.1)) * s;
                    if winding_at(bvh, &far).unwrap().abs() < 0.5
                        && winding_at(bvh, &centre).unwrap().abs() >= 0.5
                    {
                        let x = half_crossing(bvh, far, centre);
                        let step = (centre - far) * 1e-9;
                        for k in -3..=3 {
                            check(x + step * f64::from(k));
                        }
                        near_half += 1;
                    }
                }
            }
        }
        // Both paths were taken: most points by the estimate, those next to 1/2 exactly.
        assert!(estimated > 5000, "{estimated}");
        assert!(near_half > 100, "{near_half}");
    }
}
