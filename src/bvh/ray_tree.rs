//! The ray-casting layout of a hierarchy: four-wide nodes of axis-aligned boxes, for the slab test.
//!
//! The oriented boxes of the main hierarchy bound tightly, but cutting one with a ray means
//! bringing the ray into the box's frame (two 3x3 products and three divisions per node). A ray
//! cast instead cuts axis-aligned boxes with a reciprocal direction computed once per ray: per box
//! and axis a subtraction and a product for each of the two planes. Four boxes sit side by side in
//! a node, each coordinate an array of four (structure of arrays, so the four slab tests run as
//! vector operations), and the node is one aligned 128-byte block.
//!
//! The tree is built for rays, on the triangles' boxes: top-down, each split the one of least
//! surface area cost (the expected number of triangle tests of a random ray, each side's box area
//! times its triangles) among 16 bins of centroids per axis, down to leaves of at most
//! [`LEAF_MAX`] triangles (median splits past [`SAH_DEPTH`] levels bound the depth); then the
//! binary tree is collapsed, a node's four children being its descendants reached by opening the
//! largest (by surface area) until there are four. A leaf is a run of the tree's own triangle
//! order (slots of the main hierarchy's leaf order). Coordinates are stored in single precision,
//! each rounded outwards, so a stored box holds the exact one.
//!
//! Built on first use (see [`Bvh::ray_tree`]): a model that never casts a ray pays nothing for it.
//! The nodes of a large tree are offered huge pages (see [`huge_page_copy`]).
//!
//! Ray casts read the triangles from their own copy, in this tree's leaf order ([`LeafTri`],
//! made on the first ray cast: [`RayTree::leaf_tris`]): a leaf's triangles are then side by side
//! in memory, one read with no indirection, rather than a face read through the order and its
//! vertices read through the face (on a model larger than the caches, three dependent misses).

use super::memory::advise_huge_pages;
use super::{Bvh, MAX_DEPTH, TriangleBounds};
use crate::error::Error;
use crate::geometry::predicates::max_abs;
use crate::math::{Vec3, prefetch_line};
use std::sync::OnceLock;

/// The most triangles a leaf holds.
pub(crate) const LEAF_MAX: usize = 2;

/// Children per node.
const WIDTH: usize = 4;

/// One node: four child boxes (an unused slot has the box whose bounds are all `+inf`, which no
/// ray cuts: see [`RayTree::cut`]).
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
    hi: [[f32::INFINITY; WIDTH]; 3],
    child: [0; WIDTH],
    count: [0; WIDTH],
};

/// A triangle as ray casts read it: its vertices (the hierarchy's, copied), and what a hit on it
/// needs: its insertion index (ties) and the caller's id. 80 bytes.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct LeafTri {
    pub v: [Vec3; 3],
    pub added: u32,
    pub id: i32,
}

/// What a node's child is: a node of the tree, or a leaf's triangle slots (for the closest-point
/// search of `query/point.rs` and the tests' walks; ray casts read [`RayTree::links`]).
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
    /// The largest finite value.
    const LARGEST: Self;
    /// A stored coordinate (exact).
    fn stored(x: f32) -> Self;
    /// `x` rounded up.
    fn above(x: f64) -> Self;
    /// The smaller of two values that are not NaN (as a vector minimum compiles).
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        if other < self { other } else { self }
    }
    /// The larger of two values that are not NaN.
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        if other > self { other } else { self }
    }
}

impl Lane for f32 {
    const ZERO: f32 = 0.0;
    const LARGEST: f32 = f32::MAX;
    #[inline(always)]
    fn stored(x: f32) -> f32 {
        x
    }
    #[inline(always)]
    fn above(x: f64) -> f32 {
        round_up(x)
    }
}

impl Lane for f64 {
    const ZERO: f64 = 0.0;
    const LARGEST: f64 = f64::MAX;
    #[inline(always)]
    fn stored(x: f32) -> f64 {
        f64::from(x)
    }
    #[inline(always)]
    fn above(x: f64) -> f64 {
        x
    }
}

/// A ray prepared for the slab test in arithmetic `T`, in the frame of the hierarchy.
///
/// A box's slab on axis `j` is crossed between the parameters of its two planes; each plane is
/// moved outwards by a growth `g` (which covers the rounding of the test and of a hit point),
/// folded into the origin: the lower plane `lo - g` is crossed at `(lo - (o + g)) / d`, the upper
/// `hi + g` at `(hi - (o - g)) / d`, whichever the direction's sign. The nearer of the two is
/// where the ray enters the slab: the lower's for a positive direction (`lo - g <= hi + g`, and
/// each rounding is monotonic, so the computed parameters keep that order), the upper's for a
/// negative one.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Slab<T> {
    /// Per axis, the origin moved for the lower plane (`o + g`) and for the upper (`o - g`).
    lo_origin: [T; 3],
    hi_origin: [T; 3],
    /// Per axis, the reciprocal of the direction (never infinite: a zero component is tilted).
    inv: [T; 3],
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
        let s = max_abs(&[o]) + extent;
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
        // A direction parallel to the slab is tilted (far below the growth): no 0 * inf, so no
        // NaN.
        let inv = |j: usize| to(1.0 / d[j].abs().max(tilt).copysign(d[j]));
        Slab {
            lo_origin: [0, 1, 2].map(|j| to(o[j] + g)),
            hi_origin: [0, 1, 2].map(|j| to(o[j] - g)),
            inv: [0, 1, 2].map(inv),
        }
    }
}

/// The ray-casting layout of a hierarchy (see the module's documentation).
#[derive(Clone, Debug, Default)]
pub(crate) struct RayTree {
    /// The nodes, the root first.
    nodes: Vec<WideNode>,
    /// The triangles' slots (leaf order of the main hierarchy) in this tree's leaf order: a leaf
    /// holds a run of it.
    order: Vec<u32>,
    /// The largest coordinate magnitude of the vertices.
    extent: f64,
    /// The triangles in this tree's order, for ray casts (see [`LeafTri`]), made on the first
    /// ray cast.
    tris: OnceLock<Vec<LeafTri>>,
    /// The triangles' frames for the closest-point search (see `point_bounds.rs`), computed on a
    /// small model's first closest point.
    pub(super) points: OnceLock<TriangleBounds>,
}

/// A node of the binary tree the build makes before collapsing it: its box, and its children
/// (indices in the build's array) or, for a leaf (`kids[0] == LEAF`), its run of `order`.
#[derive(Clone, Copy)]
struct Binary {
    lo: Vec3,
    hi: Vec3,
    kids: [u32; 2],
    first: u32,
    count: u32,
}

impl Binary {
    fn area(&self) -> f64 {
        let e = self.hi - self.lo;
        e.x * e.y + e.y * e.z + e.z * e.x
    }
}

/// The `kids` of a binary leaf.
const LEAF: u32 = u32::MAX;

/// Bins of the surface area heuristic's split search, per axis.
const BINS: usize = 16;

/// Levels split by the surface area heuristic; below, splits at the median (so the depth stays
/// below [`MAX_DEPTH`], which the traversal's stack assumes, whatever the input).
const SAH_DEPTH: usize = MAX_DEPTH - 33;

/// A triangle's box and centroid, for the build.
#[derive(Clone, Copy)]
struct Prim {
    lo: Vec3,
    hi: Vec3,
    c: Vec3,
}

/// The box of `prims` over `order`.
fn bounds(prims: &[Prim], order: &[u32]) -> (Vec3, Vec3) {
    let mut lo = Vec3::repeat(f64::INFINITY);
    let mut hi = Vec3::repeat(f64::NEG_INFINITY);
    for &i in order {
        let p = &prims[i as usize];
        lo = lo.inf(&p.lo);
        hi = hi.sup(&p.hi);
    }
    (lo, hi)
}

/// Surface area (halved) of a box, 0 for an empty one.
fn half_area(lo: &Vec3, hi: &Vec3) -> f64 {
    let e = (hi - lo).map(|x| x.max(0.0));
    e.x * e.y + e.y * e.z + e.z * e.x
}

impl RayTree {
    /// The tree of `bvh` (built, at least one triangle), or `Err(OutOfMemory)`.
    pub fn build(bvh: &Bvh) -> Result<RayTree, Error> {
        let oom = |_| Error::OutOfMemory;
        let n = bvh.num_tris();
        let mut prims: Vec<Prim> = Vec::new();
        prims.try_reserve_exact(n).map_err(oom)?;
        prims.extend((0..n).map(|t| {
            let [a, b, c] = bvh.tri(t);
            let (lo, hi) = (a.inf(&b).inf(&c), a.sup(&b).sup(&c));
            Prim {
                lo,
                hi,
                c: (lo + hi) * 0.5,
            }
        }));
        let mut order: Vec<u32> = Vec::new();
        order.try_reserve_exact(n).map_err(oom)?;
        order.extend(0..n as u32);
        let mut bin: Vec<Binary> = Vec::new();
        bin.try_reserve_exact(2 * n).map_err(oom)?;
        split(&prims, &mut order, 0, 0, &mut bin);
        drop(prims);
        let root = bin[0];
        let mut tree = RayTree {
            nodes: Vec::new(),
            order: Vec::new(),
            extent: root.lo.amax().max(root.hi.amax()),
            tris: OnceLock::new(),
            points: OnceLock::new(),
        };
        if root.kids[0] == LEAF {
            let mut w = EMPTY;
            set(&mut w, 0, &root, root.first, root.count);
            tree.nodes.try_reserve_exact(1).map_err(oom)?;
            tree.nodes.push(w);
        } else {
            tree.collapse(&bin, 0)?;
        }
        drop(bin);
        // Grown by doubling: keep what is used, on huge pages.
        tree.nodes = huge_page_copy(&tree.nodes)?;
        tree.order = order;
        Ok(tree)
    }

    /// Appends the node of binary inner node `r` and its subtree; returns its index.
    fn collapse(&mut self, bin: &[Binary], r: u32) -> Result<u32, Error> {
        let mut kids = [0u32; WIDTH];
        kids[..2].copy_from_slice(&bin[r as usize].kids);
        let mut n = 2;
        // Open the largest inner child, until there are four.
        while n < WIDTH {
            let open = (0..n)
                .filter(|&k| bin[kids[k] as usize].kids[0] != LEAF)
                .max_by(|&x, &y| {
                    let (a, b) = (&bin[kids[x] as usize], &bin[kids[y] as usize]);
                    a.area().total_cmp(&b.area())
                });
            let Some(k) = open else { break };
            let [c0, c1] = bin[kids[k] as usize].kids;
            kids[k] = c0;
            kids[n] = c1;
            n += 1;
        }
        let index = self.nodes.len();
        self.nodes.try_reserve(1).map_err(|_| Error::OutOfMemory)?;
        self.nodes.push(EMPTY);
        for (k, &c) in kids[..n].iter().enumerate() {
            let b = &bin[c as usize];
            let (child, count) = if b.kids[0] == LEAF {
                (b.first, b.count)
            } else {
                (self.collapse(bin, c)?, 0)
            };
            set(&mut self.nodes[index], k, b, child, count);
        }
        Ok(index as u32)
    }

    /// Bytes held.
    pub fn memory_usage(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<WideNode>()
            + self.order.capacity() * std::mem::size_of::<u32>()
            + std::mem::size_of::<RayTree>()
            + self
                .tris
                .get()
                .map_or(0, |t| t.capacity() * std::mem::size_of::<LeafTri>())
            + self.points.get().map_or(0, TriangleBounds::memory_usage)
    }

    /// The root's index.
    #[inline(always)]
    pub fn root(&self) -> u32 {
        0
    }

    /// Child `k` of node `i`.
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

    /// Asks the processor to bring node `i` into the cache (a hint; nothing on other
    /// architectures): for a node stacked now and visited later, so that on models larger than
    /// the caches its loading overlaps other work.
    #[inline(always)]
    pub fn prefetch(&self, i: u32) {
        if let Some(n) = self.nodes.get(i as usize) {
            // Its two lines (128 bytes, aligned to 64).
            let p = std::ptr::from_ref(n).cast::<u8>();
            prefetch_line(p);
            prefetch_line(p.wrapping_add(64));
        }
    }

    /// Asks the processor to bring the cache lines of `items` into the cache (a hint; nothing on
    /// other architectures, or for `None`): for a leaf's triangles ([`RayTree::leaf_tris`])
    /// stacked now and tested later.
    #[inline(always)]
    pub fn prefetch_items<T>(items: Option<&[T]>) {
        if let Some(items) = items {
            let start = items.as_ptr() as usize;
            let end = start + std::mem::size_of_val(items);
            let mut line = start & !63;
            while line < end {
                prefetch_line(line as *const u8);
                line += 64;
            }
        }
    }

    /// The links of node `i`'s children: per child, an inner node's index or a leaf's first
    /// position in the order, and 0 or the leaf's number of triangles (for children
    /// [`cut`](RayTree::cut) found crossed).
    #[inline(always)]
    pub fn links(&self, i: u32) -> (&[u32; WIDTH], &[u32; WIDTH]) {
        let n = &self.nodes[i as usize];
        (&n.child, &n.count)
    }

    /// Where `ray` enters each child box of node `i` within `[0, reach]` (`reach` finite), and
    /// the mask of the children it crosses there (bit `k` for child `k`).
    ///
    /// Per axis the two planes' parameters are computed and ordered by a minimum and a maximum
    /// (no choice by the direction's sign). An unused slot's bounds are `+inf`: both its
    /// parameters are `+inf` (entered beyond any finite `reach`) or both `-inf` (left before 0),
    /// so it is never crossed. No NaN can arise (the reciprocal is finite and not zero, the moved
    /// origins finite). A stored box has no lower bound `+inf` and no upper bound `-inf`, so a
    /// slab's entry is `+inf` only where both its planes' parameters overflow: the ray meets that
    /// slab only beyond `T::LARGEST`, and no point of the tree (coordinates at most `extent`,
    /// the ray's dominant direction coordinate at least 1, see [`SlabRay::new`]) lies that far
    /// along it, so a finite `reach` loses nothing.
    #[inline(always)]
    pub fn cut<T: Lane>(&self, i: u32, ray: &Slab<T>, reach: T) -> ([T; WIDTH], u32) {
        let n = &self.nodes[i as usize];
        let mut enter = [T::ZERO; WIDTH];
        let mut leave = [reach; WIDTH];
        for j in 0..3 {
            for k in 0..WIDTH {
                let t0 = (T::stored(n.lo[j][k]) - ray.lo_origin[j]) * ray.inv[j];
                let t1 = (T::stored(n.hi[j][k]) - ray.hi_origin[j]) * ray.inv[j];
                enter[k] = enter[k].max(t0.min(t1));
                leave[k] = leave[k].min(t0.max(t1));
            }
        }
        let mut mask = 0;
        for k in 0..WIDTH {
            mask |= u32::from(enter[k] <= leave[k]) << k;
        }
        (enter, mask)
    }

    /// Lower bounds on the squared distance from `p` to each child box of node `i`: per axis the
    /// gap between `p` and the box, less `slack` (covering the subtraction's rounding), squared
    /// and summed; infinity for an unused slot (whose bounds are `+inf`: its lower bound's gap
    /// is infinite, with no test, so the lanes stay side by side).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lanes side by side, as in `cut`
    pub fn box_gaps(&self, i: u32, p: &[f64; 3], slack: f64) -> [f64; WIDTH] {
        let n = &self.nodes[i as usize];
        let mut d2 = [0.0f64; WIDTH];
        for j in 0..3 {
            for k in 0..WIDTH {
                // Plain comparisons, which compile to vector min and max.
                let below = f64::from(n.lo[j][k]) - p[j];
                let above = p[j] - f64::from(n.hi[j][k]);
                let g = if below > above { below } else { above } - slack;
                let g = if g > 0.0 { g } else { 0.0 };
                d2[k] += g * g;
            }
        }
        d2
    }

    /// The slot (leaf order of the main hierarchy) of the triangle at position `j` of this tree's
    /// order (a leaf's run is `first..first + count`).
    #[inline(always)]
    pub fn slot(&self, j: u32) -> usize {
        self.order[j as usize] as usize
    }

    /// The largest coordinate magnitude of the boxes (finite: the vertices').
    pub fn extent(&self) -> f64 {
        self.extent
    }

    /// The triangles of `bvh` (the hierarchy this tree was built from) in this tree's order (a
    /// leaf's run is `first..first + count`), copied on the first call (on huge pages if large,
    /// as the nodes), or `Err(OutOfMemory)`.
    pub fn leaf_tris(&self, bvh: &Bvh) -> Result<&[LeafTri], Error> {
        if let Some(t) = self.tris.get() {
            return Ok(t);
        }
        let t = huge_page_vec(self.order.len(), |out| {
            out.extend(self.order.iter().map(|&s| {
                let s = s as usize;
                LeafTri {
                    v: bvh.tri(s),
                    added: bvh.added[s],
                    id: bvh.ids[s],
                }
            }))
        })?;
        Ok(self.tris.get_or_init(|| t))
    }
}

/// `nodes` copied into a new array, offered huge pages before it is written.
///
/// A search on a large model reads nodes scattered over tens of megabytes: with 4 KiB pages,
/// most of those reads also miss the address translation cache, which huge pages (one entry
/// per 2 MiB) make rarer. The whole 2 MiB pages of a fresh allocation of at least two are advised as huge
/// pages ([`advise_huge_pages`], shared with loading saved models), before the nodes are
/// written to it.
fn huge_page_copy(nodes: &[WideNode]) -> Result<Vec<WideNode>, Error> {
    huge_page_vec(nodes.len(), |out| out.extend_from_slice(nodes))
}

/// A new array of `n` items, offered huge pages (as [`huge_page_copy`]) before `fill` writes them.
fn huge_page_vec<T>(n: usize, fill: impl FnOnce(&mut Vec<T>)) -> Result<Vec<T>, Error> {
    let mut out: Vec<T> = Vec::new();
    out.try_reserve_exact(n).map_err(|_| Error::OutOfMemory)?;
    advise_huge_pages(out.as_mut_ptr().cast(), n * std::mem::size_of::<T>());
    fill(&mut out);
    Ok(out)
}

/// Stores child `k` of node `n`: `s`'s box rounded outwards to single precision, and its link.
fn set(n: &mut WideNode, k: usize, s: &Binary, child: u32, count: u32) {
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

/// Builds the binary subtree of the triangles `order` (a run of the whole order starting at
/// `first`) at depth `depth`, appending its nodes to `bin` (the subtree's root first); returns
/// its root's index. Top-down: the binned surface area heuristic over the three axes, then
/// median splits below [`SAH_DEPTH`] or where every centroid is the same.
fn split(
    prims: &[Prim],
    order: &mut [u32],
    first: u32,
    depth: usize,
    bin: &mut Vec<Binary>,
) -> u32 {
    let (lo, hi) = bounds(prims, order);
    let index = bin.len() as u32;
    // Within the reserved capacity: a binary tree of n leaves has 2n - 1 nodes.
    bin.push(Binary {
        lo,
        hi,
        kids: [LEAF, LEAF],
        first,
        count: order.len() as u32,
    });
    if order.len() <= LEAF_MAX {
        return index;
    }
    let (clo, chi) = order.iter().fold(
        (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
        |(l, h), &i| (l.inf(&prims[i as usize].c), h.sup(&prims[i as usize].c)),
    );
    let mut cut = None;
    if depth < SAH_DEPTH {
        let mut best = f64::INFINITY;
        for axis in 0..3 {
            let (a, b) = (clo[axis], chi[axis]);
            if b <= a {
                continue;
            }
            let scale = BINS as f64 / (b - a);
            let which = |i: u32| {
                let x = (prims[i as usize].c[axis] - a) * scale;
                (x as usize).min(BINS - 1)
            };
            let mut count = [0usize; BINS];
            let mut boxes = [(Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)); BINS];
            for &i in order.iter() {
                let k = which(i);
                count[k] += 1;
                let p = &prims[i as usize];
                boxes[k] = (boxes[k].0.inf(&p.lo), boxes[k].1.sup(&p.hi));
            }
            // Right-hand sweeps: the cost of the triangles of bins k.. on the right.
            let mut right = [0.0f64; BINS];
            let (mut rl, mut rh, mut rn) = (
                Vec3::repeat(f64::INFINITY),
                Vec3::repeat(f64::NEG_INFINITY),
                0,
            );
            for k in (1..BINS).rev() {
                rl = rl.inf(&boxes[k].0);
                rh = rh.sup(&boxes[k].1);
                rn += count[k];
                right[k] = half_area(&rl, &rh) * rn as f64;
            }
            let (mut ll, mut lh, mut ln) = (
                Vec3::repeat(f64::INFINITY),
                Vec3::repeat(f64::NEG_INFINITY),
                0,
            );
            for k in 1..BINS {
                ll = ll.inf(&boxes[k - 1].0);
                lh = lh.sup(&boxes[k - 1].1);
                ln += count[k - 1];
                let cost = half_area(&ll, &lh) * ln as f64 + right[k];
                if ln > 0 && ln < order.len() && cost < best {
                    best = cost;
                    cut = Some((axis, a, scale, k));
                }
            }
        }
    }
    let mid = match cut {
        Some((axis, a, scale, k)) => {
            // Partition: bins below k first.
            let left = |i: &u32| {
                let x = (prims[*i as usize].c[axis] - a) * scale;
                (x as usize).min(BINS - 1) < k
            };
            let mut m = 0;
            for j in 0..order.len() {
                if left(&order[j]) {
                    order.swap(m, j);
                    m += 1;
                }
            }
            m
        }
        None => {
            // The median along the centroids' longest extent (any split if they all coincide).
            let e = chi - clo;
            let axis = e.iamax();
            let m = order.len() / 2;
            order.select_nth_unstable_by(m, |&x, &y| {
                prims[x as usize].c[axis].total_cmp(&prims[y as usize].c[axis])
            });
            m
        }
    };
    let (l, r) = order.split_at_mut(mid);
    let a = split(prims, l, first, depth + 1, bin);
    let b = split(prims, r, first + mid as u32, depth + 1, bin);
    bin[index as usize].kids = [a, b];
    index
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
                            for j in first..first + count {
                                let s = tree.slot(j);
                                assert!(inside(s));
                                seen[s] += 1;
                            }
                        }
                        RayChild::Inner(c) if lo.x != f64::INFINITY => {
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
