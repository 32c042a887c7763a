//! The ray-casting layout of a hierarchy: four-wide nodes of axis-aligned boxes, for the slab test.
//!
//! The oriented boxes of the main hierarchy bound tightly, but cutting one with a ray means
//! bringing the ray into the box's frame (two 3x3 products and three divisions per node). A ray
//! cast instead cuts axis-aligned boxes with a reciprocal direction computed once per ray: per box
//! and axis a subtraction and a product for each of the two planes. Four boxes sit side by side in
//! a node, each coordinate an array of four (structure of arrays, so the four slab tests run as
//! vector operations), and the node is one aligned 128-byte block.
//!
//! The tree is the main hierarchy collapsed: a node's four children are its binary descendants
//! reached by opening the largest (by surface area) until there are four, and a subtree of at
//! most [`LEAF_MAX`] triangles is a leaf, a run of consecutive triangle slots (a subtree's
//! triangles are contiguous in leaf order). Coordinates are stored in single precision, each
//! rounded outwards, so a stored box holds the exact one.
//!
//! Built on first use (see [`Bvh::ray_tree`]): a model that never casts a ray pays nothing for it.

use super::{Bvh, NodeKind, NodeRef, try_copy};
use crate::error::Error;
use crate::math::Vec3;

/// The most triangles a leaf holds.
pub(crate) const LEAF_MAX: usize = 1;

/// Children per node.
const WIDTH: usize = 4;

/// One node: four child boxes (an unused slot has an empty box, `lo > hi`, which no ray cuts).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct WideNode {
    /// Per axis, the four boxes' lower and upper bounds.
    lo: [[f32; WIDTH]; 3],
    hi: [[f32; WIDTH]; 3],
    /// Per child: an inner node's index, or a leaf's first triangle slot.
    child: [u32; WIDTH],
    /// Per child: 0 for an inner node, else the leaf's number of triangles.
    count: [u32; WIDTH],
}

const EMPTY: WideNode = WideNode {
    lo: [[f32::INFINITY; WIDTH]; 3],
    hi: [[f32::NEG_INFINITY; WIDTH]; 3],
    child: [0; WIDTH],
    count: [0; WIDTH],
};

/// What a node's child is: a node of the tree, or a leaf's triangle slots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RayChild {
    Inner(u32),
    Leaf { first: u32, count: u32 },
}

/// The arithmetic of a slab test: single precision where the scene's magnitudes allow, else
/// double.
pub(crate) trait Lane:
    Copy + PartialOrd + std::ops::Sub<Output = Self> + std::ops::Mul<Output = Self>
{
    const ZERO: Self;
    /// A stored coordinate (exact).
    fn stored(x: f32) -> Self;
    /// `x` rounded up.
    fn above(x: f64) -> Self;
    /// As `f64` (exact).
    fn wide(self) -> f64;
}

impl Lane for f32 {
    const ZERO: f32 = 0.0;
    #[inline(always)]
    fn stored(x: f32) -> f32 {
        x
    }
    #[inline(always)]
    fn above(x: f64) -> f32 {
        round_up(x)
    }
    #[inline(always)]
    fn wide(self) -> f64 {
        f64::from(self)
    }
}

impl Lane for f64 {
    const ZERO: f64 = 0.0;
    #[inline(always)]
    fn stored(x: f32) -> f64 {
        f64::from(x)
    }
    #[inline(always)]
    fn above(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn wide(self) -> f64 {
        self
    }
}

/// A ray prepared for the slab test in arithmetic `T`, in the frame of the hierarchy.
///
/// A box's slab on axis `j` is crossed between the parameters of its near and far planes; each
/// plane is moved outwards by a growth `g` (which covers the rounding of the test and of a hit
/// point), folded into the origin: the near plane `lo - g` (direction positive) is crossed at
/// `(lo - (o + g)) / d`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Slab<T> {
    /// Per axis, the origin moved for the near and the far plane.
    near_origin: [T; 3],
    far_origin: [T; 3],
    /// Per axis, the reciprocal of the direction (never infinite: a zero component is tilted).
    inv: [T; 3],
    /// Per axis, whether the direction is positive (the near plane is the lower bound).
    positive: [bool; 3],
}

/// A ray prepared for the slab test (see [`SlabRay::new`]).
#[derive(Clone, Copy, Debug)]
pub(crate) enum SlabRay {
    Single(Slab<f32>),
    Double(Slab<f64>),
}

/// The growth of a single-precision slab test, relative to the magnitudes involved: many times
/// the few single-precision roundings of the test.
const SINGLE_GROW: f64 = 1e-5;

impl SlabRay {
    /// The ray `o + t d` (`d`'s largest coordinate in `[1, 2)`), the boxes grown by at least
    /// `grow` (positive), against a tree whose coordinates are at most `extent` in magnitude.
    ///
    /// Single precision when the magnitudes `s = |o| + extent` are within `[1e-30, 1e30]`: the
    /// boxes are then grown by `1e-5 s`, many times the test's roundings (a few single-precision
    /// ulps of `s` in position); a direction component below `1e-30` is tilted to `1e-30`, which
    /// moves the ray by at most `1e-30 t`, and `t <= s` within any box (the dominant coordinate
    /// moves at least `t`), far below the growth. Otherwise double precision, grown by `grow`.
    pub fn new(o: &Vec3, d: &Vec3, grow: f64, extent: f64) -> SlabRay {
        let s = o.amax() + extent;
        if (1e-30..=1e30).contains(&s) {
            let g = grow.max(SINGLE_GROW * s);
            SlabRay::Single(Slab::make(o, d, g, 1e-30, |x| x as f32))
        } else {
            SlabRay::Double(Slab::make(o, d, grow, 1e-300, |x| x))
        }
    }
}

impl<T: Lane> Slab<T> {
    fn make(o: &Vec3, d: &Vec3, g: f64, tilt: f64, to: impl Fn(f64) -> T) -> Slab<T> {
        let mut r = Slab {
            near_origin: [T::ZERO; 3],
            far_origin: [T::ZERO; 3],
            inv: [T::ZERO; 3],
            positive: [true; 3],
        };
        for j in 0..3 {
            // A direction parallel to the slab is tilted (far below the growth): no 0 * inf, so
            // no NaN.
            let inv = 1.0 / d[j].abs().max(tilt).copysign(d[j]);
            let s = if inv > 0.0 { g } else { -g };
            r.inv[j] = to(inv);
            r.positive[j] = inv > 0.0;
            r.near_origin[j] = to(o[j] + s);
            r.far_origin[j] = to(o[j] - s);
        }
        r
    }
}

/// The ray-casting layout of a hierarchy (see the module's documentation).
#[derive(Clone, Debug, Default)]
pub(crate) struct RayTree {
    /// The nodes, the root first.
    nodes: Vec<WideNode>,
    /// The largest coordinate magnitude of the vertices.
    extent: f64,
}

/// Per node of the binary hierarchy: what the collapse needs.
#[derive(Clone, Copy)]
struct Summary {
    lo: Vec3,
    hi: Vec3,
    first: u32,
    count: u32,
}

impl Summary {
    fn area(&self) -> f64 {
        let e = self.hi - self.lo;
        e.x * e.y + e.y * e.z + e.z * e.x
    }
}

impl RayTree {
    /// The tree of `bvh` (built, at least one triangle), or `Err(OutOfMemory)`.
    pub fn build(bvh: &Bvh) -> Result<RayTree, Error> {
        let oom = |_| Error::OutOfMemory;
        let inner = bvh.nodes.len();
        let mut sums: Vec<Summary> = Vec::new();
        sums.try_reserve_exact(inner).map_err(oom)?;
        sums.resize(
            inner,
            Summary {
                lo: Vec3::zeros(),
                hi: Vec3::zeros(),
                first: 0,
                count: 0,
            },
        );
        let root = bvh.root();
        let top = summarize(bvh, root, &mut sums);
        let mut tree = RayTree::default();
        let slot = |r: NodeRef| match r.kind() {
            NodeKind::Leaf(t) => leaf_summary(bvh, t),
            NodeKind::Inner(i) => sums[i],
        };
        if top.count as usize <= LEAF_MAX || root.is_leaf() {
            let mut n = EMPTY;
            set(&mut n, 0, &top, top.first, top.count);
            tree.nodes.try_reserve_exact(1).map_err(oom)?;
            tree.nodes.push(n);
        } else {
            tree.collapse(bvh, root, &slot)?;
        }
        drop(sums);
        // Grown by doubling: keep what is used.
        Ok(RayTree {
            nodes: try_copy(&tree.nodes).map_err(|_| Error::OutOfMemory)?,
            extent: top.lo.amax().max(top.hi.amax()),
        })
    }

    /// Appends the node of binary inner node `r` (more than `LEAF_MAX` triangles) and its
    /// subtree; returns its index.
    fn collapse(
        &mut self,
        bvh: &Bvh,
        r: NodeRef,
        slot: &impl Fn(NodeRef) -> Summary,
    ) -> Result<u32, Error> {
        let mut kids: [NodeRef; WIDTH] = [NodeRef::default(); WIDTH];
        let [a, b] = bvh.children(r);
        kids[0] = a;
        kids[1] = b;
        let mut n = 2;
        // Open the largest child that is not to be a leaf, until there are four.
        while n < WIDTH {
            let open = (0..n)
                .filter(|&k| !kids[k].is_leaf() && slot(kids[k]).count as usize > LEAF_MAX)
                .max_by(|&x, &y| slot(kids[x]).area().total_cmp(&slot(kids[y]).area()));
            let Some(k) = open else { break };
            let [c0, c1] = bvh.children(kids[k]);
            kids[k] = c0;
            kids[n] = c1;
            n += 1;
        }
        let index = self.nodes.len();
        self.nodes.try_reserve(1).map_err(|_| Error::OutOfMemory)?;
        self.nodes.push(EMPTY);
        for (k, &c) in kids[..n].iter().enumerate() {
            let s = slot(c);
            let (child, count) = if c.is_leaf() || s.count as usize <= LEAF_MAX {
                (s.first, s.count)
            } else {
                (self.collapse(bvh, c, slot)?, 0)
            };
            set(&mut self.nodes[index], k, &s, child, count);
        }
        Ok(index as u32)
    }

    /// Bytes held.
    pub fn memory_usage(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<WideNode>() + std::mem::size_of::<RayTree>()
    }

    /// The root's index.
    #[inline(always)]
    pub fn root(&self) -> u32 {
        0
    }

    /// Child `k` of node `i` (only for a child [`cut`](RayTree::cut) found crossed).
    #[inline(always)]
    pub fn child(&self, i: u32, k: usize) -> RayChild {
        let n = &self.nodes[i as usize];
        match n.count[k] {
            0 => RayChild::Inner(n.child[k]),
            count => RayChild::Leaf {
                first: n.child[k],
                count,
            },
        }
    }

    /// Where `ray` enters each child box of node `i`, within `[0, reach]`: the entry parameter,
    /// or infinity where it misses the box there.
    #[inline(always)]
    pub fn cut<T: Lane>(&self, i: u32, ray: &Slab<T>, reach: f64) -> [f64; WIDTH] {
        let n = &self.nodes[i as usize];
        let mut enter = [T::ZERO; WIDTH];
        let mut leave = [T::above(reach); WIDTH];
        for j in 0..3 {
            let (near, far) = if ray.positive[j] {
                (&n.lo[j], &n.hi[j])
            } else {
                (&n.hi[j], &n.lo[j])
            };
            for k in 0..WIDTH {
                // Plain comparisons (no NaN can arise: the reciprocal is finite and not zero, the
                // moved origins finite), which compile to vector min and max.
                let t0 = (T::stored(near[k]) - ray.near_origin[j]) * ray.inv[j];
                let t1 = (T::stored(far[k]) - ray.far_origin[j]) * ray.inv[j];
                enter[k] = if t0 > enter[k] { t0 } else { enter[k] };
                leave[k] = if t1 < leave[k] { t1 } else { leave[k] };
            }
        }
        let mut out = [f64::INFINITY; WIDTH];
        for k in 0..WIDTH {
            if enter[k] <= leave[k] {
                out[k] = enter[k].wide();
            }
        }
        out
    }

    /// The largest coordinate magnitude of the boxes (finite: the vertices').
    pub fn extent(&self) -> f64 {
        self.extent
    }
}

/// Stores child `k` of node `n`: `s`'s box rounded outwards to single precision, and its link.
fn set(n: &mut WideNode, k: usize, s: &Summary, child: u32, count: u32) {
    for j in 0..3 {
        n.lo[j][k] = round_down(s.lo[j]);
        n.hi[j][k] = round_up(s.hi[j]);
    }
    n.child[k] = child;
    n.count[k] = count;
}

/// The largest `f32` not above `x` (`-inf` below the range).
fn round_down(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) > x { y.next_down() } else { y }
}

/// The smallest `f32` not below `x` (`inf` above the range).
fn round_up(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) < x { y.next_up() } else { y }
}

/// Leaf `t`'s summary: its triangle's box and slot.
fn leaf_summary(bvh: &Bvh, t: usize) -> Summary {
    let [a, b, c] = bvh.tri(t);
    Summary {
        lo: a.inf(&b).inf(&c),
        hi: a.sup(&b).sup(&c),
        first: t as u32,
        count: 1,
    }
}

/// Node `r`'s summary, recording every inner node's below it in `sums` (by index).
fn summarize(bvh: &Bvh, r: NodeRef, sums: &mut [Summary]) -> Summary {
    match r.kind() {
        NodeKind::Leaf(t) => leaf_summary(bvh, t),
        NodeKind::Inner(i) => {
            let [a, b] = bvh.children(r).map(|c| summarize(bvh, c, sums));
            let s = Summary {
                lo: a.lo.inf(&b.lo),
                hi: a.hi.sup(&b.hi),
                first: a.first.min(b.first),
                count: a.count + b.count,
            };
            sums[i] = s;
            s
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::{CollisionVolume, VolumeKind};
    use crate::test_rng::{Random, Rng};

    /// Every triangle in exactly one leaf, and every box holding its subtree's triangles.
    #[test]
    fn leaves_cover_every_triangle_once_inside_their_boxes() {
        let mut r = Rng(7);
        for n in [1usize, 2, 3, 4, 5, 9, 40, 333] {
            let tris = (0..n).map(|i| {
                let c = Vec3::from(r.point(1.0));
                ([0, 1, 2].map(|_| c + Vec3::from(r.point(0.3))), i as i32)
            });
            let bvh = Bvh::build(tris.collect(), VolumeKind::Rss, CollisionVolume::Obb).unwrap();
            let tree = RayTree::build(&bvh).unwrap();
            let mut seen = vec![0; n];
            fn walk(tree: &RayTree, bvh: &Bvh, i: u32, seen: &mut [u32]) {
                let node = &tree.nodes[i as usize];
                for k in 0..WIDTH {
                    let (lo, hi) = (
                        Vec3::from(node.lo.map(|a| f64::from(a[k]))),
                        Vec3::from(node.hi.map(|a| f64::from(a[k]))),
                    );
                    let inside = |slot: usize| {
                        bvh.tri(slot)
                            .iter()
                            .all(|v| (0..3).all(|j| lo[j] <= v[j] && v[j] <= hi[j]))
                    };
                    match tree.child(i, k) {
                        RayChild::Leaf { first, count } => {
                            for s in first..first + count {
                                assert!(inside(s as usize));
                                seen[s as usize] += 1;
                            }
                        }
                        RayChild::Inner(c) if lo.x <= hi.x => {
                            let mut below = vec![0; seen.len()];
                            walk(tree, bvh, c, &mut below);
                            for (s, m) in below.iter().enumerate() {
                                if *m > 0 {
                                    assert!(inside(s));
                                }
                                seen[s] += m;
                            }
                        }
                        RayChild::Inner(_) => {}
                    }
                }
            }
            walk(&tree, &bvh, tree.root(), &mut seen);
            assert!(seen.iter().all(|&m| m == 1), "{n}");
        }
    }
}
