//! The bounding-volume hierarchy of a model: layout (this file) and top-down build (`build.rs`).
//!
//! Only inner nodes are stored, in one array, the root first. Each carries one frame (the principal
//! axes both its volumes were fitted on; the third axis is stored as the cross product of the first
//! two, recomputed on use exactly as the build computed it), a swept sphere volume (a PSS, LSS or
//! RSS, as the model's [`VolumeKind`] chooses) for the distance and tolerance queries, and for
//! collision when the model asks for it, and an overlap volume (OBB) for collision, both in model
//! coordinates (a test composes the relative pose with the axes, so no
//! per-node frame chain is needed). The boxes, which only collision reads, are kept in an array of
//! their own at the nodes' indices (see [`Node`]).
//!
//! A leaf is one triangle and stores no volume: its volumes are computed on use from the triangle
//! (the exact rectangle around it, see [`Ssv::triangle`]). Triangles are three indices into a vertex
//! array in which equal vertices are stored once, in leaf order so that a subtree's triangles are
//! contiguous.

mod boundary;
mod build;
mod build_threads;
mod far_field;
mod memory;
mod point_bounds;
mod pqp_view;
mod principal_axes;
mod ray_tree;
mod refit;
mod saved;
mod volume_choice;

pub(crate) use boundary::{Boundaries, BoundaryLoop, NodeSurface};
pub(crate) use build::MAX_DEPTH;
pub(crate) use point_bounds::TriangleBounds;
pub(crate) use pqp_view::PqpBv;
pub(crate) use ray_tree::{Lane, RayChild, RayTree, Slab, SlabRay};
pub use volume_choice::{CollisionVolume, VolumeKind};

use crate::bounding_volume::{BoundingVolume, CompactSsv, Obb, Ssv};
use crate::error::Error;
use crate::geometry::Tri;
use crate::geometry::{RESCALE_HI, RESCALE_LO};
use crate::math::{Mat3, RelPose, Vec3, frame_from, prefetch_line};
use std::sync::OnceLock;

/// A handle on a node of the hierarchy: an inner node or a leaf (one triangle). What the queries
/// hold in their stacks and queues; they ask the [`Bvh`] for its volumes, its children and its
/// triangle, and never read the node array themselves.
///
/// Four bytes, as the integer it wraps (`>= 0`: an inner node's index, `< 0`: the leaf of triangle
/// `-r - 1`): copied, compared and stored as cheaply, and every method inlines to the integer test
/// or arithmetic.
///
/// A descent to every triangle below a node (the shape of every query's traversal; this runs as
/// the unit test `bvh::tests::descent_example`):
///
/// ```ignore
/// fn triangles_below(bvh: &Bvh, r: NodeRef, out: &mut Vec<usize>) {
///     match r.kind() {
///         NodeKind::Leaf(t) => out.push(t),
///         NodeKind::Inner(_) => {
///             for c in bvh.children(r) {
///                 triangles_below(bvh, c, out);
///             }
///         }
///     }
/// }
/// let mut all = Vec::new();
/// triangles_below(&bvh, bvh.root(), &mut all);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[repr(transparent)]
pub(crate) struct NodeRef(i32);

impl std::fmt::Display for NodeRef {
    /// The integer it wraps (`>= 0` inner, `< 0` leaf).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

/// What a [`NodeRef`] designates ([`NodeRef::kind`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum NodeKind {
    /// A leaf: the triangle's slot in leaf order (for [`Bvh::tri`]).
    Leaf(usize),
    /// An inner node: its index among the inner nodes (the root is 0).
    Inner(usize),
}

impl NodeRef {
    /// The inner node of index `i`.
    #[inline(always)]
    pub(crate) const fn inner(i: usize) -> NodeRef {
        NodeRef(i as i32)
    }

    /// The leaf of triangle `t` (in leaf order).
    #[inline(always)]
    pub(crate) const fn leaf(t: usize) -> NodeRef {
        NodeRef(-(t as i32) - 1)
    }

    /// Whether it is a leaf.
    #[inline(always)]
    pub(crate) fn is_leaf(self) -> bool {
        self.0 < 0
    }

    /// A leaf with its triangle, or an inner node with its index.
    #[inline(always)]
    pub(crate) fn kind(self) -> NodeKind {
        if self.is_leaf() {
            NodeKind::Leaf(self.triangle())
        } else {
            NodeKind::Inner(self.0 as usize)
        }
    }

    /// A leaf's triangle (in leaf order). Only for leaves.
    #[inline(always)]
    pub(crate) fn triangle(self) -> usize {
        debug_assert!(self.is_leaf());
        (-(self.0 as i64) - 1) as usize
    }

    /// The integer it wraps, for keys of caches (distinct for distinct nodes of one hierarchy).
    #[inline(always)]
    pub(crate) fn raw(self) -> i32 {
        self.0
    }

    /// The handle whose [`raw`](NodeRef::raw) integer is `r` (for tests that make up handles).
    #[cfg(test)]
    pub(crate) const fn from_raw(r: i32) -> NodeRef {
        NodeRef(r)
    }

    /// The inner node's index, for the array.
    #[inline(always)]
    fn index(self) -> usize {
        debug_assert!(!self.is_leaf());
        self.0 as usize
    }
}

/// One inner node of the hierarchy, as the distance and tolerance queries read it: its swept
/// sphere volume, that volume's size and its children. Laid out in the order written (`repr(C)`),
/// 112 bytes. The node's box, which only collision reads, lies apart in [`Bvh`]'s `boxes` (see
/// [`NodeBox`]), so that the nodes a distance query walks are not spread over cache lines holding
/// boxes it never reads.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct Node {
    /// The swept sphere volume, on the node's frame: its first two axes (orthonormal), the third
    /// being their cross product (the box is on the same frame).
    ssv: CompactSsv,
    /// The swept sphere volume's size, which the descent rule compares at every step.
    ssv_size: f64,
    /// The two children.
    children: [NodeRef; 2],
}

// What the prefetch of a node ([`Bvh::prefetch`]) and the queries' cache use count on.
const _: () = assert!(size_of::<Node>() == 112 && size_of::<NodeBox>() == 48);

impl Node {
    /// A node with volume `ssv` (whose third axis must be the cross product of the first two, as
    /// [`Node::frame`] recomputes it), its children not yet set.
    pub fn new(ssv: &Ssv) -> Node {
        Node {
            ssv: ssv.compact(),
            ssv_size: ssv.size(),
            children: [NodeRef::inner(0); 2],
        }
    }

    /// The node's frame, from the two stored axes.
    #[inline(always)]
    pub fn frame(&self) -> Mat3 {
        frame_from(&self.ssv.axes[0], &self.ssv.axes[1])
    }

    /// The swept sphere volume.
    #[inline(always)]
    pub fn ssv(&self) -> Ssv {
        self.ssv.full()
    }

    /// The size of the swept sphere volume (as [`BoundingVolume::size`] measures it).
    #[inline(always)]
    pub fn ssv_size(&self) -> f64 {
        self.ssv_size
    }
}

/// An inner node's box (see [`Obb`]) without its axes, which are the node's frame: its centre and
/// half extents, at the node's index in [`Bvh`]'s `boxes`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub(crate) struct NodeBox {
    center: Vec3,
    half: Vec3,
}

impl NodeBox {
    /// The centre and half extents of `obb`.
    pub fn new(obb: &Obb) -> NodeBox {
        NodeBox {
            center: obb.center,
            half: obb.half,
        }
    }

    /// The box, on the frame of its node `node`.
    #[inline(always)]
    pub fn obb(&self, node: &Node) -> Obb {
        Obb {
            axes: node.frame(),
            center: self.center,
            half: self.half,
        }
    }
}

/// The slots of a run of inner nodes, each node with its box: what the build fills, a node at a
/// time (see [`NodeSlots::split_first_mut`]), its subtrees' runs split off for each child.
pub(crate) struct NodeSlots<'a> {
    nodes: &'a mut [Node],
    boxes: &'a mut [NodeBox],
}

/// One slot of [`NodeSlots`]: a node (read and written through it, as a `&mut Node`) and its box.
pub(crate) struct NodeSlot<'a> {
    node: &'a mut Node,
    obb: &'a mut NodeBox,
}

impl<'a> NodeSlots<'a> {
    /// The slots of `nodes` with their boxes (as many).
    pub fn new(nodes: &'a mut [Node], boxes: &'a mut [NodeBox]) -> NodeSlots<'a> {
        debug_assert_eq!(nodes.len(), boxes.len());
        NodeSlots { nodes, boxes }
    }

    /// Number of slots.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// The first slot and the rest, or `None` if there are none.
    pub fn split_first_mut(self) -> Option<(NodeSlot<'a>, NodeSlots<'a>)> {
        let (node, nodes) = self.nodes.split_first_mut()?;
        let (obb, boxes) = self.boxes.split_first_mut()?;
        Some((NodeSlot { node, obb }, NodeSlots { nodes, boxes }))
    }

    /// The first `mid` slots and the rest.
    pub fn split_at_mut(self, mid: usize) -> (NodeSlots<'a>, NodeSlots<'a>) {
        let (n0, n1) = self.nodes.split_at_mut(mid);
        let (b0, b1) = self.boxes.split_at_mut(mid);
        (
            NodeSlots {
                nodes: n0,
                boxes: b0,
            },
            NodeSlots {
                nodes: n1,
                boxes: b1,
            },
        )
    }
}

impl NodeSlot<'_> {
    /// Stores the node fitted on `axes`: volume `ssv` and box `obb` (on the same axes, whose third
    /// column must be the cross product of the first two, as [`Node::frame`] recomputes it), its
    /// children not yet set.
    pub fn set(&mut self, ssv: &Ssv, obb: &Obb) {
        debug_assert_eq!(ssv.axes, obb.axes);
        *self.node = Node::new(ssv);
        *self.obb = NodeBox::new(obb);
    }
}

impl std::ops::Deref for NodeSlot<'_> {
    type Target = Node;
    fn deref(&self) -> &Node {
        self.node
    }
}

impl std::ops::DerefMut for NodeSlot<'_> {
    fn deref_mut(&mut self) -> &mut Node {
        self.node
    }
}

/// A built hierarchy: inner nodes, and the triangles with their caller ids in leaf order.
#[derive(Clone, Debug)]
pub(crate) struct Bvh {
    /// The inner nodes, the root first; read through [`NodeRef`]s and the accessors below.
    nodes: Vec<Node>,
    /// Each inner node's box, at the node's index (apart from the nodes: see [`Node`]).
    boxes: Vec<NodeBox>,
    /// The distinct vertices.
    pub verts: Vec<Vec3>,
    /// Each triangle's vertices, by index into `verts`, in leaf order.
    pub faces: Vec<[u32; 3]>,
    /// Each triangle's caller id, in leaf order.
    pub ids: Vec<i32>,
    /// Insertion order: `added[t]` is the position among the triangles as they were added (to
    /// [`Bvh::build`], in the order of [`Model::add_triangle`](crate::model::Model::add_triangle)
    /// calls) of the triangle in leaf slot `t`. A permutation of `0..num_tris()`. It maps what
    /// the hierarchy knows back to what the caller gave: PQP 1.3's view of a model lists triangles
    /// in the order added, and refitting takes new vertices in that order.
    pub added: Vec<u32>,
    /// Which volume this model offers the collision query.
    pub collision: CollisionVolume,
    /// A bound on the scale of every node's swept sphere volume, a leaf's included (the magnitudes
    /// a bound's rounding is relative to, see [`Ssv::slack_for`]): a search takes one rounding
    /// allowance for all its pairs rather than one per pair.
    pub scale: f64,
    /// Some triangle has every coordinate below `RESCALE_LO` in magnitude: a triangle test against
    /// it may need rescaling (see [`in_kernel_range`](Bvh::in_kernel_range)).
    pub tiny: bool,
    /// Each inner node's boundary edges, for the winding number: computed on first use
    /// ([`Bvh::boundaries`]), so a model that never asks for one does not hold them.
    pub boundary: OnceLock<Boundaries>,
    /// The ray-casting layout (axis-aligned four-wide nodes): computed on the first ray cast, or
    /// a small model's first closest point (see `query/point.rs`) ([`Bvh::ray_tree`]), so a model
    /// that asks for neither does not hold it.
    pub ray: OnceLock<RayTree>,
    /// Whether no two stored vertices are equal as numbers, so that two triangles share a vertex
    /// exactly when they share its index (see [`Bvh::distinct_vertices`]).
    pub distinct: OnceLock<bool>,
}

impl Bvh {
    /// A hierarchy from its arrays (`boxes` as many as `nodes`), with what is derived from them
    /// (`scale`, `tiny`) computed: how a build and a load both end. `inner_scale` is
    /// [`Bvh::inner_scale`] of `nodes` (a load
    /// computes it as it reads them). `shared`: `verts` are known to have distinct bit patterns
    /// (a build's, shared by [`build::share_vertices`]), which leaves only negative zeros to
    /// check for [`Bvh::distinct_vertices`]; a load's are checked on first use.
    #[allow(clippy::too_many_arguments)]
    fn assemble(
        nodes: Vec<Node>,
        boxes: Vec<NodeBox>,
        verts: Vec<Vec3>,
        faces: Vec<[u32; 3]>,
        ids: Vec<i32>,
        added: Vec<u32>,
        collision: CollisionVolume,
        inner_scale: f64,
        shared: bool,
        scans: Option<Scans>,
    ) -> Bvh {
        let (scale, tiny, distinct) = match scans {
            // A parallel build's, scanned on its threads.
            Some(s) => (
                inner_scale.max(5.0 * s.vertex),
                s.tiny,
                OnceLock::from(!s.negative_zero),
            ),
            None => (
                Bvh::scale_bound(inner_scale, &verts),
                Bvh::has_tiny(&verts, &faces),
                if shared {
                    OnceLock::from(!has_negative_zero(&verts))
                } else {
                    OnceLock::new()
                },
            ),
        };
        Bvh::assembled(
            nodes, boxes, verts, faces, ids, added, collision, scale, tiny, distinct,
        )
    }

    /// [`Bvh::assemble`] with `scale` ([`Bvh::scale_bound`]), `tiny` ([`Bvh::has_tiny`]) and
    /// `distinct` (see [`Bvh::distinct_vertices`]; empty: checked on first use) already computed
    /// (a load takes the first two as it reads the vertices, in no extra pass).
    #[allow(clippy::too_many_arguments)]
    fn assembled(
        nodes: Vec<Node>,
        boxes: Vec<NodeBox>,
        verts: Vec<Vec3>,
        faces: Vec<[u32; 3]>,
        ids: Vec<i32>,
        added: Vec<u32>,
        collision: CollisionVolume,
        scale: f64,
        tiny: bool,
        distinct: OnceLock<bool>,
    ) -> Bvh {
        debug_assert_eq!(nodes.len(), boxes.len());
        Bvh {
            nodes,
            boxes,
            verts,
            faces,
            ids,
            added,
            collision,
            scale,
            tiny,
            boundary: OnceLock::new(),
            ray: OnceLock::new(),
            distinct,
        }
    }

    /// The bound kept in `scale`: the largest of `inner_scale` ([`Bvh::inner_scale`]) and five
    /// times the largest coordinate sum over the vertices (a leaf's corner is a vertex, its sides
    /// are at most twice the triangle's diameter, which is at most twice the largest vertex norm).
    fn scale_bound(inner_scale: f64, verts: &[Vec3]) -> f64 {
        inner_scale.max(5.0 * largest_sum(verts))
    }

    /// The largest scale of the inner nodes' swept sphere volumes (see [`Ssv::slack_for`]), 0
    /// without inner nodes.
    fn inner_scale(nodes: &[Node]) -> f64 {
        nodes.iter().map(|n| n.ssv.scale()).fold(0.0, f64::max)
    }

    /// Whether some triangle has every coordinate below `RESCALE_LO` in magnitude (see `tiny`).
    fn has_tiny(verts: &[Vec3], faces: &[[u32; 3]]) -> bool {
        faces.iter().any(|f| {
            let m = f
                .iter()
                .map(|&i| verts[i as usize].amax())
                .fold(0.0, f64::max);
            m < RESCALE_LO
        })
    }

    /// Whether every pair of a triangle of `self` and one of `other` posed by `rel` has its largest
    /// coordinate magnitude in `[RESCALE_LO, RESCALE_HI]`, so that triangle tests need no
    /// rescaling: no triangle of `self` is tiny, and the coordinates of both stay below
    /// `RESCALE_HI` (a vertex's `|v|_1` is at most `scale`, so a posed one's coordinates are at
    /// most the largest rotation entry times the other's `scale` plus the largest translation).
    /// `false` when unsure (the tests then check each pair).
    pub fn in_kernel_range(&self, other: &Bvh, rel: &RelPose) -> bool {
        let posed = rel.rot.amax() * other.scale + rel.trans.amax();
        // The bound's own rounding is a few ulps: a relative margin of 1e-6 covers it.
        !self.tiny && self.scale <= RESCALE_HI && posed * (1.0 + 1e-6) <= RESCALE_HI
    }

    /// A deep copy, or `Err(ModelOutOfMemory)` (see [`Model::try_clone`](crate::Model::try_clone)).
    pub fn try_clone(&self) -> Result<Bvh, Error> {
        Ok(Bvh {
            nodes: try_copy(&self.nodes)?,
            boxes: try_copy(&self.boxes)?,
            verts: try_copy(&self.verts)?,
            faces: try_copy(&self.faces)?,
            ids: try_copy(&self.ids)?,
            added: try_copy(&self.added)?,
            collision: self.collision,
            scale: self.scale,
            tiny: self.tiny,
            // Rebuilt on use by the copy if it needs them.
            boundary: OnceLock::new(),
            ray: OnceLock::new(),
            distinct: self.distinct.clone(),
        })
    }

    /// Bytes held by the hierarchy.
    pub fn memory_usage(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<Node>()
            + self.boxes.capacity() * std::mem::size_of::<NodeBox>()
            + self.verts.capacity() * std::mem::size_of::<Vec3>()
            + self.faces.capacity() * std::mem::size_of::<[u32; 3]>()
            + self.ids.capacity() * std::mem::size_of::<i32>()
            + self.added.capacity() * std::mem::size_of::<u32>()
            + self.boundary.get().map_or(0, Boundaries::memory_usage)
            + self.ray.get().map_or(0, RayTree::memory_usage)
            + std::mem::size_of::<Bvh>()
    }

    /// Each inner node's boundary (see [`Boundaries`]), computed on the first call (by any
    /// thread; concurrent first calls may each compute it, one result is kept), or
    /// `Err(OutOfMemory)` if it cannot be allocated.
    pub fn boundaries(&self) -> Result<&Boundaries, Error> {
        if let Some(b) = self.boundary.get() {
            return Ok(b);
        }
        let b = Boundaries::build(self)?;
        Ok(self.boundary.get_or_init(|| b))
    }

    /// The ray-casting layout (see [`RayTree`]), computed on the first call (as
    /// [`boundaries`](Bvh::boundaries)), or `Err(OutOfMemory)`.
    pub fn ray_tree(&self) -> Result<&RayTree, Error> {
        if let Some(t) = self.ray.get() {
            return Ok(t);
        }
        let t = RayTree::build(self)?;
        Ok(self.ray.get_or_init(|| t))
    }

    /// Whether no two stored vertices are equal as numbers: then two triangles share a vertex
    /// exactly when their faces share its index, and self-collision compares indices rather than
    /// coordinates. Known after a build or refit (vertices equal bit for bit are stored once,
    /// so only a negative zero, equal to a positive one, can break it); checked on the first call
    /// for a loaded model, whose file may repeat a vertex (by any thread; concurrent first calls
    /// may each check). `false` also when the check cannot allocate.
    pub fn distinct_vertices(&self) -> bool {
        *self.distinct.get_or_init(|| all_distinct(&self.verts))
    }

    /// Vertex `i` (an index of [`Boundaries`]' edges).
    #[inline(always)]
    pub fn vertex(&self, i: u32) -> Vec3 {
        self.verts[i as usize]
    }

    /// Number of triangles.
    #[inline]
    pub fn num_tris(&self) -> usize {
        self.faces.len()
    }

    /// Triangle `t` (in leaf order).
    #[inline(always)]
    pub fn tri(&self, t: usize) -> Tri {
        let f = &self.faces[t];
        [
            self.verts[f[0] as usize],
            self.verts[f[1] as usize],
            self.verts[f[2] as usize],
        ]
    }

    /// The root: the first inner node, or the only triangle's leaf.
    #[inline]
    pub fn root(&self) -> NodeRef {
        if self.nodes.is_empty() {
            NodeRef::leaf(0)
        } else {
            NodeRef::inner(0)
        }
    }

    /// The two children of inner node `r` (not a leaf).
    #[inline(always)]
    pub fn children(&self, r: NodeRef) -> [NodeRef; 2] {
        self.nodes[r.index()].children
    }

    /// The swept sphere volume of inner node `r` (not a leaf), where it is stored.
    #[inline(always)]
    pub fn inner_ssv(&self, r: NodeRef) -> &CompactSsv {
        &self.nodes[r.index()].ssv
    }

    /// The size of inner node `r`'s swept sphere volume (not a leaf; see [`Node::ssv_size`]).
    #[inline(always)]
    pub fn inner_ssv_size(&self, r: NodeRef) -> f64 {
        self.nodes[r.index()].ssv_size()
    }

    /// Asks the processor to bring inner node `r` (not a leaf) into the cache: every line of its
    /// 112 bytes (two or three, by where it starts). A hint; nothing on other architectures.
    #[inline(always)]
    pub fn prefetch(&self, r: NodeRef) {
        let p = std::ptr::from_ref(&self.nodes[r.index()]).cast::<u8>();
        // Its first byte, 64 bytes on and its last byte: every line it spans.
        for at in [0, 64, size_of::<Node>() - 1] {
            prefetch_line(p.wrapping_add(at));
        }
    }

    /// Number of inner nodes (one less than the triangles).
    #[cfg(test)]
    pub fn num_inner(&self) -> usize {
        self.nodes.len()
    }

    /// The swept sphere volume of node `r`.
    #[inline(always)]
    pub fn ssv(&self, r: NodeRef) -> Ssv {
        match r.kind() {
            NodeKind::Inner(i) => self.nodes[i].ssv(),
            NodeKind::Leaf(t) => Ssv::triangle(&self.tri(t)),
        }
    }

    /// The swept sphere volume of leaf `r`, computed from its triangle, as [`CompactSsv`].
    #[inline(always)]
    pub fn leaf_compact_ssv(&self, r: NodeRef) -> CompactSsv {
        Ssv::triangle(&self.tri(r.triangle())).compact()
    }

    /// The box of node `r`.
    #[inline(always)]
    pub fn obb(&self, r: NodeRef) -> Obb {
        match r.kind() {
            NodeKind::Inner(i) => self.boxes[i].obb(&self.nodes[i]),
            NodeKind::Leaf(t) => {
                let t = self.tri(t);
                Obb::fit(&Ssv::triangle(&t).axes, &t)
            }
        }
    }

    /// The size of the root's swept sphere volume (as [`BoundingVolume::size`] measures it).
    pub fn root_size(&self) -> f64 {
        self.ssv(self.root()).size()
    }

    /// A point `o` of node `r`'s volume and a bound `e` on the distance of its points from `o`.
    #[inline]
    pub fn anchor(&self, r: NodeRef) -> (Vec3, f64) {
        if !r.is_leaf() {
            let n = &self.nodes[r.index()];
            // The rectangle's centre: every point is within half its diagonal plus the radius,
            // half the size. Rounded up a little: the centre is computed.
            let v = &n.ssv;
            let l = v.lengths;
            let c = v.origin + v.axes[0] * (0.5 * l[0]) + v.axes[1] * (0.5 * l[1]);
            (
                c,
                0.5 * n.ssv_size * (1.0 + 1e-12) + 4.0 * f64::EPSILON * c.norm(),
            )
        } else {
            // The centroid, and its farthest vertex.
            let [a, b, c] = self.tri(r.triangle());
            let m = (a + b + c) / 3.0;
            let far2 = (a - m)
                .norm_squared()
                .max((b - m).norm_squared())
                .max((c - m).norm_squared());
            (
                m,
                far2.sqrt() * (1.0 + 1e-12) + 4.0 * f64::EPSILON * m.norm(),
            )
        }
    }

    /// A bound on the distance of every point of the model from its frame's origin.
    pub fn reach(&self) -> f64 {
        let v = self.ssv(self.root());
        let l = v.lengths;
        v.origin.norm() + (l[0] * l[0] + l[1] * l[1]).sqrt() + v.radius
    }

    /// Depth of the tree (a single leaf has depth 1).
    #[cfg(test)]
    pub fn depth(&self) -> usize {
        fn rec(b: &Bvh, r: NodeRef) -> usize {
            if r.is_leaf() {
                1
            } else {
                let [c0, c1] = b.children(r);
                1 + rec(b, c0).max(rec(b, c1))
            }
        }
        rec(self, self.root())
    }
}

/// The largest `|v|_1` of `verts` (0 if none).
fn largest_sum(verts: &[Vec3]) -> f64 {
    verts.iter().map(|v| v.abs().sum()).fold(0.0, f64::max)
}

/// What [`Bvh::assemble`] reads of a build's shared vertices and its faces, when the build has
/// scanned them itself (on its threads, a part each): the largest `|v|_1` of a vertex, whether
/// some triangle is tiny (see `tiny`), whether some coordinate is a negative zero. A largest and
/// two "some": the same however the arrays were cut into parts, scanned and merged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Scans {
    vertex: f64,
    tiny: bool,
    negative_zero: bool,
}

impl Scans {
    /// Of the vertices `verts` (a part of `all`) and the triangles `faces` (of `all`).
    pub fn of(verts: &[Vec3], faces: &[[u32; 3]], all: &[Vec3]) -> Scans {
        Scans {
            vertex: largest_sum(verts),
            tiny: Bvh::has_tiny(all, faces),
            negative_zero: has_negative_zero(verts),
        }
    }

    /// Of two parts together.
    pub fn merge(self, other: Scans) -> Scans {
        Scans {
            vertex: self.vertex.max(other.vertex),
            tiny: self.tiny || other.tiny,
            negative_zero: self.negative_zero || other.negative_zero,
        }
    }
}

/// Whether some coordinate is a negative zero.
fn has_negative_zero(verts: &[Vec3]) -> bool {
    verts
        .iter()
        .any(|v| v.iter().any(|c| *c == 0.0 && c.is_sign_negative()))
}

/// Whether no two of `verts` (finite) are equal as numbers: no negative zero, and no two with the
/// same bits (sorted, then neighbours compared: O(n log n), once per loaded model). `false` if
/// the sort's copy cannot be allocated.
fn all_distinct(verts: &[Vec3]) -> bool {
    if has_negative_zero(verts) {
        return false;
    }
    let mut keys: Vec<[u64; 3]> = Vec::new();
    if keys.try_reserve_exact(verts.len()).is_err() {
        return false;
    }
    keys.extend(verts.iter().map(|v| [v.x, v.y, v.z].map(f64::to_bits)));
    keys.sort_unstable();
    keys.windows(2).all(|w| w[0] != w[1])
}

/// A copy of `v` (its length, not its capacity), or `Err(ModelOutOfMemory)`.
pub(crate) fn try_copy<T: Copy>(v: &[T]) -> Result<Vec<T>, Error> {
    let mut out = Vec::new();
    out.try_reserve_exact(v.len())
        .map_err(|_| Error::ModelOutOfMemory)?;
    out.extend_from_slice(v);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The descent of [`NodeRef`]'s documentation: every triangle once.
    #[test]
    fn descent_example() {
        fn triangles_below(bvh: &Bvh, r: NodeRef, out: &mut Vec<usize>) {
            match r.kind() {
                NodeKind::Leaf(t) => out.push(t),
                NodeKind::Inner(_) => {
                    for c in bvh.children(r) {
                        triangles_below(bvh, c, out);
                    }
                }
            }
        }
        let tris = (0..40).map(|i| {
            let x = f64::from(i);
            let t = [
                Vec3::new(x, 0.0, 0.0),
                Vec3::new(x + 1.0, 0.5, 0.0),
                Vec3::new(x, 1.0, 0.25 * x),
            ];
            (t, i)
        });
        let bvh = Bvh::build(tris.collect(), VolumeKind::Rss, CollisionVolume::Obb).unwrap();
        let mut all = Vec::new();
        triangles_below(&bvh, bvh.root(), &mut all);
        all.sort_unstable();
        assert_eq!(all, (0..40).collect::<Vec<_>>());
        assert_eq!(NodeRef::leaf(7).kind(), NodeKind::Leaf(7));
        assert_eq!(NodeRef::inner(3).kind(), NodeKind::Inner(3));
    }

    #[test]
    fn distinct_vertices_after_build_refit_and_load() {
        let fan = |origin: Vec3| -> Vec<(Tri, i32)> {
            (0..6)
                .map(|i| {
                    let (a, b) = (f64::from(i), f64::from(i) + 1.0);
                    let p = |t: f64| Vec3::new(t.cos(), t.sin(), 0.1);
                    ([origin, p(a), p(b)], i)
                })
                .collect()
        };
        let zero = Vec3::zeros();
        let b = Bvh::build(fan(zero), VolumeKind::Rss, CollisionVolume::Obb).unwrap();
        assert!(b.distinct_vertices());
        // One blade's origin with a negative zero: stored apart from the others'.
        let mut tris = fan(zero);
        tris[3].0[0] = Vec3::new(-0.0, 0.0, 0.0);
        let mut c = Bvh::build(tris.clone(), VolumeKind::Rss, CollisionVolume::Obb).unwrap();
        assert!(!c.distinct_vertices());
        // Refit to all positive zeros, then back.
        let added = |tris: &[(Tri, i32)]| -> Vec<Tri> { tris.iter().map(|t| t.0).collect() };
        c.refit(&added(&fan(zero)), VolumeKind::Rss).unwrap();
        assert!(c.distinct_vertices());
        c.refit(&added(&tris), VolumeKind::Rss).unwrap();
        assert!(!c.distinct_vertices());
        // Checked on first use after a load (here: a copy with its answer forgotten).
        let mut d = b.try_clone().unwrap();
        d.distinct = OnceLock::new();
        assert!(d.distinct_vertices());
        d.verts.push(d.verts[2]);
        d.distinct = OnceLock::new();
        assert!(!d.distinct_vertices());
    }
}
