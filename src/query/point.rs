//! Point queries: the closest point of a posed model to a point, and the signed distance (negative
//! inside, by the winding number of `winding.rs`).
//!
//! Both work in the model's frame: the point is carried there by the inverse pose (the rotation
//! taken as orthonormal), and the answer carried back.

use super::bound_heap::BoundHeap;
use super::prepare_point as prepare;
use super::winding::inside;
use crate::bounding_volume::Ssv;
use crate::bvh::{Bvh, MAX_DEPTH, NodeKind, NodeRef, RayChild, RayTree, TriangleBounds};
use crate::error::Error;
use crate::geometry::{ClosestPoints, Tri, point_triangle};
use crate::math::{Pose, RelPose, UNDERFLOW_SLACK, Vec3, most};
use crate::model::Model;
use std::cell::RefCell;
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
/// by a priority-directed descent of the hierarchy (the node of least distance bound first),
/// pruned by the swept sphere volumes' distance bounds and by the best distance so far
/// (`max_distance` to start with); on models of at most 8,192 triangles, by a depth-first descent
/// of the ray casts' tree of boxes instead, where the exact routine runs only for triangles that a
/// cheap bound from each triangle's frame (plane and edges) cannot rule out (the tree and the
/// frames are built on the first such query, about 40 + 248 B/triangle).
/// Degenerate triangles count as the segment or point they span.
///
/// Errors: `UnprocessedModel` (not built), `NonFinitePose`, `NonFiniteCoordinate` (a coordinate
/// of `point` NaN, infinite or beyond 1e150 in magnitude), `InvalidArgument` (`max_distance`
/// negative or NaN).
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
    Ok(match nearest(bvh, &p, max_distance) {
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
/// computed on the model's first signed distance, cannot be allocated.
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
    let d = nearest(bvh, &p, f64::INFINITY).map_or(f64::INFINITY, |c| c.distance);
    if d == 0.0 {
        return Ok(0.0);
    }
    Ok(if inside(bvh, &p)? { -d } else { d })
}

/// A closest triangle found: its slot in leaf order, distance and closest point (model frame).
struct Nearest {
    slot: usize,
    distance: f64,
    q: Vec3,
}

thread_local! {
    /// The queue of the closest-point search, one per thread and reused from query to query (it
    /// keeps its capacity), so that only a thread's first query allocates.
    static QUEUE: RefCell<BoundHeap> = RefCell::new(BoundHeap::default());
}

/// The nearest triangle to `p` (model frame) within `max_distance`, if any: the first found at the
/// least distance by a priority-directed descent, the node of least bound first (the nearer child
/// straight away when nothing queued comes before it), so that no node whose bound exceeds the
/// final distance is opened; small models by [`nearest_in_boxes`].
fn nearest(bvh: &Bvh, p: &Vec3, max_distance: f64) -> Option<Nearest> {
    // Every bound below is a distance computed from p and a volume: its rounding is within the
    // allowance of a bound between volumes of the model's scale and the point's.
    let slack = Ssv::slack_for(bvh.scale, p.abs().sum(), &RelPose::identity());
    let mut best: Option<Nearest> = None;
    let mut cutoff = max_distance;
    let leaf = |t: usize, cutoff: &mut f64, best: &mut Option<Nearest>| {
        let tri = bvh.tri(t);
        // The triangle's box first: a triangle whose box is farther than the cutoff (by more
        // than the bounds' rounding allowance) cannot be accepted below, and its exact distance
        // (ten times the box's cost) is not needed.
        let limit = *cutoff + slack;
        if box_gap_squared(p, &tri) > limit * limit || plane_beyond(p, &tri, limit) {
            return;
        }
        keep(t, point_triangle(p, &tri), cutoff, best);
    };
    let root = bvh.root();
    if bvh.faces.len() <= BOX_SEARCH_TRIANGLES
        && let NodeKind::Inner(_) = root.kind()
        && let Ok(tree) = bvh.ray_tree()
        && let Ok(frames) = tree.triangle_bounds(bvh)
    {
        return nearest_small(bvh, tree, frames, p, max_distance);
    }
    if let NodeKind::Leaf(t) = root.kind() {
        leaf(t, &mut cutoff, &mut best);
        return best;
    }
    QUEUE.with(|q| {
        // A query never calls another while it holds the queue, so the borrow cannot fail.
        let mut queue = q.borrow_mut();
        queue.clear();
        let (mut r, mut bound) = (root, 0.0);
        loop {
            // The inner children within the cutoff, with their bounds.
            let mut near: [(NodeRef, f64); 2] = [(r, f64::INFINITY); 2];
            for (k, c) in bvh.children(r).into_iter().enumerate() {
                match c.kind() {
                    NodeKind::Leaf(t) => leaf(t, &mut cutoff, &mut best),
                    NodeKind::Inner(_) => {
                        // Raised to the parent's (which bounds the child's triangles too), so
                        // that bounds never decrease along the search.
                        let v = bvh.inner_ssv(c).full();
                        let b = most(v.core_distance(p) - v.radius - slack, bound);
                        if b <= cutoff {
                            near[k] = (c, b);
                        }
                    }
                }
            }
            // The nearer child next, straight away if no queued node comes before it (the
            // order of queueing both and taking the least); the other queued.
            let [c0, c1] = near;
            let (first, second) = if c1.1 <= c0.1 { (c1, c0) } else { (c0, c1) };
            if second.1 <= cutoff {
                queue.push(second.0, second.1);
            }
            if first.1 <= cutoff && queue.peek_bound().is_none_or(|b| first.1 <= b) {
                (r, bound) = first;
                continue;
            }
            if first.1 <= cutoff {
                queue.push(first.0, first.1);
            }
            match queue.pop() {
                Some((n, b)) if b <= cutoff => (r, bound) = (n, b),
                _ => break,
            }
        }
    });
    best
}

/// [`nearest`] on a small model: the search of its ray tree's boxes ([`nearest_in_boxes`]), each
/// triangle tested exactly only where its frame's bound does not rule it out. A function of its
/// own, so that the compiler lays out its registers apart from the volumes' search.
#[inline(never)]
fn nearest_small(
    bvh: &Bvh,
    tree: &RayTree,
    frames: &TriangleBounds,
    p: &Vec3,
    max_distance: f64,
) -> Option<Nearest> {
    let (mut best, mut cutoff) = (None, max_distance);
    // A triangle whose frame's distance exceeds the cutoff by more than both its rounding and
    // the exact routine's cannot be accepted (a triangle without a frame has bound NaN, never
    // skipped).
    let allowance = FRAME_ALLOWANCE * (p.abs().sum() + bvh.scale) + UNDERFLOW_SLACK;
    let leaf = |j: u32, cutoff: &mut f64, best: &mut Option<Nearest>| {
        let reach = *cutoff + allowance;
        if frames.distance_squared(j, p) > reach * reach {
            return;
        }
        exact(bvh, p, tree.slot(j), cutoff, best);
    };
    nearest_in_boxes(tree, p, &mut cutoff, &mut best, leaf);
    best
}

/// The exact test of the triangle of slot `t`, kept if nearer ([`keep`]); out of line, which keeps
/// the box search's loop small (the test runs for few of the triangles it visits).
#[inline(never)]
fn exact(bvh: &Bvh, p: &Vec3, t: usize, cutoff: &mut f64, best: &mut Option<Nearest>) {
    keep(t, point_triangle(p, &bvh.tri(t)), cutoff, best);
}

/// Keeps `c`, the exact routine's answer for the triangle of slot `t`, if nearer than the best so
/// far: `<=` the cutoff on the first keeps a triangle exactly at `max_distance`; `<` the best
/// after keeps the first of equally near triangles.
#[inline(always)]
fn keep(t: usize, c: ClosestPoints, cutoff: &mut f64, best: &mut Option<Nearest>) {
    if c.distance <= *cutoff && best.as_ref().is_none_or(|b| c.distance < b.distance) {
        *cutoff = c.distance;
        *best = Some(Nearest {
            slot: t,
            distance: c.distance,
            q: c.q,
        });
    }
}

/// Models of at most this many triangles find the nearest triangle in the ray tree's boxes
/// ([`Bvh::ray_tree`], built on their first ray cast or point query, about 40 B/triangle, and the
/// triangles' frames, 248 B/triangle, built on the first point query): on the
/// bunny (2,204 triangles) it took half the time of the search of the swept sphere volumes, on a
/// million-triangle closed sphere three times as long (a box's bound is 0 for the many points
/// inside the boxes, where a swept sphere volume's is not).
const BOX_SEARCH_TRIANGLES: usize = 8192;

/// The allowance of the triangles' frames' bound ([`TriangleBounds::distance_squared`]), relative
/// to the point's coordinate sum plus the model's scale: the bound is within a few thousand ulps
/// of these magnitudes of the distance, times at most 1e3 near a vertex (see there), so within
/// about 2e-9 of them; the exact routine's distance within less. Fifty times that.
const FRAME_ALLOWANCE: f64 = 1e-7;

/// The search of [`nearest`] in the ray tree's boxes: depth-first, the nearest box first, pruned
/// by the squared distance to each box against the cutoff (squared, rounded up); `leaf` tests a
/// triangle by its position in the tree's order and lowers the cutoff.
fn nearest_in_boxes(
    tree: &RayTree,
    p: &Vec3,
    cutoff: &mut f64,
    best: &mut Option<Nearest>,
    leaf: impl Fn(u32, &mut f64, &mut Option<Nearest>),
) {
    // The gaps' subtraction rounds by an ulp of the larger operand: far less than this.
    let slack = 1e-12 * (p.amax() + tree.extent()) + 1e-300;
    let q = [p.x, p.y, p.z];
    let reach = |c: f64| c * c * (1.0 + 1e-12);
    // Left uninitialised: clearing an array sized for the deepest tree cost more than a small
    // model's whole search. Entries below `len` are written before they are read.
    let mut stack = [const { MaybeUninit::<(RayChild, f64)>::uninit() }; 3 * MAX_DEPTH + 4];
    let mut len = 0;
    let mut node = RayChild::Inner(tree.root());
    loop {
        match node {
            RayChild::Inner(i) => {
                let d2 = tree.box_gaps(i, &q, slack);
                let limit = reach(*cutoff);
                // The children within reach, farthest first; all but the nearest stacked.
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
                        // Checked indexing: the tree's depth bound keeps it in range.
                        stack[len] = MaybeUninit::new((tree.child(i, k), d));
                        len += 1;
                    }
                    node = tree.child(i, near[n - 1].0);
                    continue;
                }
            }
            RayChild::Leaf { first, count } => {
                for j in first..first + count {
                    leaf(j, cutoff, best);
                }
            }
        }
        loop {
            if len == 0 {
                return;
            }
            len -= 1;
            // SAFETY: every entry below the stack's length was written when it was pushed.
            let (next, d) = unsafe { stack[len].assume_init() };
            if d <= reach(*cutoff) {
                node = next;
                break;
            }
        }
    }
}

/// The squared distance from `p` to the axis-aligned box of triangle `t`: at most the square of
/// the triangle's distance, up to rounding.
#[inline(always)]
fn box_gap_squared(p: &Vec3, t: &Tri) -> f64 {
    // Plain comparisons (vertices are never NaN), which compile to single min and max
    // instructions, unlike `f64::min` and `max`.
    let min = |a: f64, b: f64| if a < b { a } else { b };
    let max = |a: f64, b: f64| if a > b { a } else { b };
    let mut sum = 0.0;
    for k in 0..3 {
        let lo = min(min(t[0][k], t[1][k]), t[2][k]);
        let hi = max(max(t[0][k], t[1][k]), t[2][k]);
        let g = max(max(lo - p[k], p[k] - hi), 0.0);
        sum += g * g;
    }
    sum
}

/// Whether the plane of triangle `t` is farther from `p` than `limit`, with an allowance far above
/// the rounding of the normal's direction and of the product: a cheap test that spares the exact
/// distance of triangles facing the point from beyond the cutoff. Slivers (sine of their angle
/// below 1e-3, where the rounded normal may tilt) are never skipped.
#[inline(always)]
fn plane_beyond(p: &Vec3, t: &Tri, limit: f64) -> bool {
    let (e1, e2, w) = (t[1] - t[0], t[2] - t[0], p - t[0]);
    let n = e1.cross(&e2);
    let nn = n.norm_squared();
    let h = n.dot(&w);
    let allowance = 1e-12 * (w.abs().sum() + e1.abs().sum() + e2.abs().sum());
    let reach = limit + allowance;
    nn > 1e-6 * e1.norm_squared() * e2.norm_squared() && h * h > reach * reach * nn
}
