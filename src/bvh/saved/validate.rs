//! What a load checks of a hierarchy as a whole, once every record has passed its own checks: that
//! the children make the tree a build makes ([`check_tree`]), and that every inner node's volumes
//! contain the triangles below it ([`check_volumes`]), whatever the checksum said.

use super::super::memory::with_room;
use super::super::{MAX_DEPTH, Node, NodeBox, NodeKind, NodeRef};
use crate::bounding_volume::Ssv;
use crate::error::Error;
use crate::math::{Mat3, Vec3};

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

/// How far outside an inner node's volumes [`check_volumes`] lets a vertex of a triangle below it
/// lie, as a fraction of the model's vertex scale `S` (the largest `|x| + |y| + |z|` of a vertex):
/// 2^-45, about 2.8e-14, some hundreds of times the rounding of the check's own arithmetic. A
/// build's volumes contain their triangles exactly as `contains` measures them, so a saved model
/// always passes.
pub(crate) const VOLUME_STEP: f64 = 1.0 / (1u64 << 45) as f64;

/// What [`check_volumes`] needs of the whole tree, made in O(n) by [`Spans::new`]: each inner
/// node's run of triangle slots, and for each slot how many vertices the slots before it use
/// (vertices are numbered in first use, so the vertices first used in a run of slots are a run of
/// indices).
pub(super) struct Spans {
    /// `slots[i]`: the first and one past the last slot below inner node `i`.
    slots: Vec<[u32; 2]>,
    /// `seen[t]`: the vertices used by slots `0..t` (`0..=n`).
    seen: Vec<u32>,
}

impl Spans {
    /// For `nodes` (a tree [`check_tree`] accepted) and `faces` (numbered in first use, as the
    /// reading checked). `Err(ModelOutOfMemory)` if the arrays cannot be allocated.
    pub(super) fn new(nodes: &[Node], faces: &[[u32; 3]]) -> Result<Spans, Error> {
        let mut seen = with_room(faces.len() + 1)?;
        seen.push(0u32);
        let mut last = 0u32;
        for f in faces {
            last = last.max(f[0].max(f[1]).max(f[2]) + 1);
            seen.push(last);
        }
        // Children come after their parent: one backward pass has both children's runs.
        let mut slots = with_room(nodes.len())?;
        slots.resize(nodes.len(), [0u32; 2]);
        for i in (0..nodes.len()).rev() {
            let span = |c: NodeRef| match c.kind() {
                NodeKind::Leaf(t) => [t as u32, t as u32 + 1],
                NodeKind::Inner(j) => slots[j],
            };
            let [c0, c1] = nodes[i].children;
            slots[i] = [span(c0)[0], span(c1)[1]];
        }
        Ok(Spans { slots, seen })
    }
}

/// Checks that every vertex of every triangle below each inner node of `nodes` in `range` lies
/// within the node's swept sphere volume and its box, up to `VOLUME_STEP * vertex_scale`.
///
/// Each node is checked on its own (so ranges can be checked on several threads), against every
/// vertex below it: the run of vertices first used below it, in order, and the earlier vertices
/// its triangles share with triangles before them. A check of a node against its children's
/// volumes would cost O(1) per node, but it fails on a build's hierarchies as a rule (a build fits
/// each node to its triangles, not to its children's volumes: the child holding a triangle that
/// touches a face of its parent's box sticks out of that face when their frames differ), and a
/// descent that follows the children's volumes to the triangles near each node's boundary makes
/// about 7 volume and 7 triangle tests per triangle, unpredictable branches and scattered reads,
/// several times the cost of these plain passes. Each vertex is tested once per level above it:
/// `O(depth n)`, at most `MAX_DEPTH n`, in sequential reads.
pub(super) fn check_volumes(
    nodes: &[Node],
    boxes: &[NodeBox],
    verts: &[Vec3],
    faces: &[[u32; 3]],
    spans: &Spans,
    vertex_scale: f64,
    range: std::ops::Range<usize>,
) -> Result<(), Error> {
    let tol = VOLUME_STEP * vertex_scale;
    for i in range {
        let checked = Checked::new(&nodes[i].ssv(), &boxes[i], tol);
        let [t0, t1] = spans.slots[i].map(|t| t as usize);
        let (v0, v1) = (spans.seen[t0], spans.seen[t1]);
        let mut out = verts[v0 as usize..v1 as usize]
            .iter()
            .fold(false, |out, p| out | checked.outside(p));
        for f in &faces[t0..t1] {
            for &k in f {
                if k < v0 {
                    out |= checked.outside(&verts[k as usize]);
                }
            }
        }
        if out {
            return Err(Error::InvalidData);
        }
    }
    Ok(())
}

/// A node's volumes as [`check_volumes`] tests points against them, within `tol`.
pub(super) struct Checked {
    /// The node's frame (columns).
    axes: Mat3,
    center: Vec3,
    /// The box's half extents, plus `tol`.
    limit: Vec3,
    /// The swept sphere volume's origin in the frame, from the box's centre.
    origin: Vec3,
    lengths: [f64; 2],
    /// `(radius + tol)^2`.
    reach2: f64,
}

impl Checked {
    pub(super) fn new(ssv: &Ssv, b: &NodeBox, tol: f64) -> Checked {
        let reach = ssv.radius + tol;
        Checked {
            axes: ssv.axes,
            center: b.center,
            limit: b.half.add_scalar(tol),
            origin: ssv.axes.tr_mul(&(ssv.origin - b.center)),
            lengths: ssv.lengths,
            reach2: reach * reach,
        }
    }

    /// Whether `p` lies outside the box or the swept sphere volume by more than `tol` (without
    /// branches: the passes over the vertices stay straight).
    #[inline(always)]
    pub(super) fn outside(&self, p: &Vec3) -> bool {
        let q = self.axes.tr_mul(&(p - self.center));
        let boxed =
            (q.x.abs() > self.limit.x) | (q.y.abs() > self.limit.y) | (q.z.abs() > self.limit.z);
        let y = q - self.origin;
        let out = |x: f64, len: f64| (-x).max(x - len).max(0.0);
        let (dx, dy) = (out(y.x, self.lengths[0]), out(y.y, self.lengths[1]));
        // NaN-free: every value is finite and bounded (`codec::read_node`, the vertices' checks).
        boxed | (dx * dx + dy * dy + y.z * y.z > self.reach2)
    }
}
