//! What a load checks of a hierarchy as a whole, once every record has passed its own checks: that
//! the children make the tree a build makes ([`check_tree`]), and that every inner node's volumes
//! contain the triangles below it ([`check_volumes`]), whatever the checksum said.

use super::super::{MAX_DEPTH, Node, NodeBox, NodeKind, NodeRef};
use crate::bounding_volume::{BoundingVolume, Obb, Ssv};
use crate::error::Error;
use crate::math::Vec3;

/// Checks that the inner nodes' `children` make the tree a build makes over `n` triangles (`n - 1`
/// inner nodes):
/// depth-first from the root, first child first, the leaves come in slot order `0, 1, ..., n - 1`,
/// every inner child is in range, no more than `n - 1` inner nodes are visited, and no leaf is
/// deeper than [`MAX_DEPTH`] (counting the root as 1), and every inner child comes after its
/// parent in the array (refit relies on it). Since every inner node has two children,
/// `n` leaves each met once make it a tree with each node reached exactly once (a node reached
/// twice would show its leaves twice). O(n), and ends early on the first fault, so a crafted
/// graph (cycles, shared nodes) costs no more.
pub(super) fn check_tree(children: &[[NodeRef; 2]], n: usize) -> Result<(), Error> {
    debug_assert_eq!(children.len() + 1, n);
    let root = if children.is_empty() {
        NodeRef::leaf(0)
    } else {
        NodeRef::inner(0)
    };
    // The stack holds at most one pending sibling per level, and the nodes' depths are checked.
    let mut stack = [(NodeRef::leaf(0), 0usize); MAX_DEPTH + 1];
    stack[0] = (root, 1);
    let (mut len, mut next_leaf, mut inner_seen) = (1usize, 0usize, 0usize);
    while len > 0 {
        len -= 1;
        let (r, depth) = stack[len];
        if depth > MAX_DEPTH {
            return Err(Error::InvalidData);
        }
        match r.kind() {
            NodeKind::Leaf(t) => {
                if t != next_leaf {
                    return Err(Error::InvalidData);
                }
                next_leaf += 1;
            }
            NodeKind::Inner(i) => {
                inner_seen += 1;
                if i >= children.len() || inner_seen > children.len() || len + 2 > stack.len() {
                    return Err(Error::InvalidData);
                }
                let [c0, c1] = children[i];
                // Children after their parent, as a build numbers them (pre-order): refit
                // recomputes the volumes in one backward pass over the nodes.
                let before = |c: NodeRef| matches!(c.kind(), NodeKind::Inner(j) if j <= i);
                if before(c0) || before(c1) {
                    return Err(Error::InvalidData);
                }
                stack[len] = (c1, depth + 1);
                stack[len + 1] = (c0, depth + 1);
                len += 2;
            }
        }
    }
    if next_leaf == n {
        Ok(())
    } else {
        Err(Error::InvalidData)
    }
}

/// How far, per level, [`check_volumes`] lets what a node bounds reach outside its volumes, as a
/// fraction of the model's vertex scale `S` (the largest `|x| + |y| + |z|` of a vertex): 2^-45,
/// about 3e-14, a few hundred times the rounding of the checks' own arithmetic. A build's volumes
/// contain their triangles exactly as `contains` measures them, so a saved model always passes.
pub(crate) const VOLUME_STEP: f64 = 1.0 / (1u64 << 45) as f64;

/// Checks that every vertex of every triangle below each inner node of `nodes` in `range` lies
/// within the node's swept sphere volume and its box, up to `VOLUME_STEP * vertex_scale` per
/// level below it (so within `MAX_DEPTH * VOLUME_STEP * vertex_scale`, about 2e-12 `S`, in all).
///
/// `nodes` and `boxes` make a tree [`check_tree`] accepted; `faces` index `verts`. Each node is
/// checked on its own (so ranges can be checked on several threads), by a descent of its subtree
/// that stops at every node whose volumes show it inside the checked node's within one step
/// ([`bound_inside`]) and checks the triangles of the leaves it reaches exactly; by induction from
/// the leaves, what is below is then inside within one step per level. A child's volumes do not
/// show it inside its parent's as a rule (a build fits each node to its triangles, not to its
/// children's volumes: the child holding a triangle that touches a face of its parent's box sticks
/// out of that face when their frames differ), so the descent goes on near the checked node's
/// boundary only: a few times the subtree's boundary in all, O(n) over the tree for the shapes
/// builds meet. A crafted buffer can make it visit every node below: `O(MAX_DEPTH n)` at worst.
pub(super) fn check_volumes(
    nodes: &[Node],
    boxes: &[NodeBox],
    verts: &[Vec3],
    faces: &[[u32; 3]],
    vertex_scale: f64,
    range: std::ops::Range<usize>,
) -> Result<(), Error> {
    let tol = VOLUME_STEP * vertex_scale;
    // One pending sibling per level below the node checked (`check_tree` bounded the depth).
    let mut stack = [NodeRef::leaf(0); MAX_DEPTH + 2];
    for i in range {
        let node = &nodes[i];
        let (ssv, obb) = (node.ssv(), boxes[i].obb(node));
        let [c0, c1] = node.children;
        (stack[0], stack[1]) = (c1, c0);
        let mut len = 2;
        while len > 0 {
            len -= 1;
            let r = stack[len];
            match r.kind() {
                NodeKind::Leaf(t) => {
                    let inside = faces[t].iter().all(|&k| {
                        let p = &verts[k as usize];
                        ssv.contains(p, tol) && obb.contains(p, tol)
                    });
                    if !inside {
                        return Err(Error::InvalidData);
                    }
                }
                NodeKind::Inner(j) => {
                    let below = &nodes[j];
                    if !bound_inside(&ssv, &obb, &below.ssv(), &boxes[j].obb(below), tol) {
                        if len + 2 > stack.len() {
                            return Err(Error::Internal);
                        }
                        let [d0, d1] = below.children;
                        (stack[len], stack[len + 1]) = (d1, d0);
                        len += 2;
                    }
                }
            }
        }
    }
    Ok(())
}

/// Whether what a child with volumes `cs` and `cb` holds is inside a node's volumes `ps` and `pb`
/// (on one frame) within `tol`, as far as the child's volumes tell: for the box, along each of
/// its six faces' normals, the nearer of the two volumes' extents; for the swept sphere volume,
/// either every corner of the child's box or every corner of the child's swept sphere volume's
/// core (padded with its radius) within its radius of the node's core (a point's distance from a
/// rectangle is convex, so the corners bound every point between them). False may be wrong (the
/// caller then checks the triangles); true is not, up to the rounding of these few operations on
/// values of the model's magnitude, well below `tol`.
pub(super) fn bound_inside(ps: &Ssv, pb: &Obb, cs: &Ssv, cb: &Obb, tol: f64) -> bool {
    let a = &ps.axes;
    // The child's frame and points in the node's frame.
    let m = a.tr_mul(&cs.axes);
    let (e0, e1) = (m.column(0) * cs.lengths[0], m.column(1) * cs.lengths[1]);
    let core = [Vec3::zeros(), e0, e1, e0 + e1];
    let ext = m.abs() * cb.half;
    // The box: the child's box's extents and its core's padded by its radius, from the centre.
    let (bc, sc) = (
        a.tr_mul(&(cb.center - pb.center)),
        a.tr_mul(&(cs.origin - pb.center)),
    );
    for k in 0..3 {
        let (mut hi, mut lo) = (f64::NEG_INFINITY, f64::INFINITY);
        for x in &core {
            hi = hi.max(sc[k] + x[k]);
            lo = lo.min(sc[k] + x[k]);
        }
        let hi = (hi + cs.radius).min(bc[k] + ext[k]);
        let lo = (lo - cs.radius).max(bc[k] - ext[k]);
        let limit = pb.half[k] + tol;
        // NaN-free: every value is finite and bounded (`codec::read_node`).
        if hi > limit || -lo > limit {
            return false;
        }
    }
    // The swept sphere volume: distances from the node's core, in its frame from its origin.
    let [l0, l1] = ps.lengths;
    let out = |x: f64, len: f64| (-x).max(x - len).max(0.0);
    let far = |y: Vec3| {
        let (dx, dy) = (out(y.x, l0), out(y.y, l1));
        (dx * dx + dy * dy + y.z * y.z).sqrt()
    };
    let limit = ps.radius + tol;
    let so = a.tr_mul(&(cs.origin - ps.origin));
    if core.iter().all(|x| far(so + x) + cs.radius <= limit) {
        return true;
    }
    let bo = a.tr_mul(&(cb.center - ps.origin));
    let h = [
        m.column(0) * cb.half.x,
        m.column(1) * cb.half.y,
        m.column(2) * cb.half.z,
    ];
    (0..8).all(|s: usize| {
        let sign = |b: usize| if s >> b & 1 == 1 { 1.0 } else { -1.0 };
        far(bo + h[0] * sign(0) + h[1] * sign(1) + h[2] * sign(2)) <= limit
    })
}
