//! Top-down build, as the SSV paper describes it: principal axes from the covariance of the node's
//! triangles' corners, split across the axis of largest spread at the mean of the triangle
//! centroids.
//!
//! What makes it quick: everything a node computes is taken from its distinct vertices (in a mesh
//! about a sixth of its corners: a vertex is shared by about six triangles), found with a
//! per-thread stamp array as the parent splits: the covariance of the corners is the covariance of
//! the distinct vertices weighted by how many of the node's corners each is; the volumes fitted
//! around them are the same box and, up to the order points are met in, the same swept sphere
//! volume; and a triangle's split key is the sum of its three vertices' coordinates along the axis,
//! read from the points already taken into the node's frame. So the triangles themselves are only
//! 16-byte records (vertex indices and position as added), partitioned in place: at every level
//! the build moves a fifth of the bytes a record of moments would take. Nothing is allocated per
//! node.
//!
//! Nodes are numbered in pre-order (a node, its first child's subtree, its second child's; the
//! first child is the side of the split with more triangles):
//! a subtree of `m` triangles holds exactly `m - 1` inner nodes, so every node's index is known
//! before its subtree is built, and subtrees are built independently, on any number of threads
//! (`build_threads.rs`), into the same array: the hierarchy is the same, bit for bit, whatever the
//! thread count.

use super::build_threads::{GRAIN, Pool, run_tasks};
use super::memory::populate_pages;
use super::principal_axes::{axes_of, weighted_scatter};
use super::{Bvh, CollisionVolume, Node, NodeBox, NodeRef, NodeSlots, Scans, VolumeKind};
use crate::bounding_volume::{Obb, Ssv, SsvKind};
use crate::error::Error;
use crate::geometry::Tri;
use crate::math::{Mat3, Vec3, frame_from, prefetch_line};
use std::sync::atomic::{AtomicU32, Ordering};

/// Below this depth the split is at the mean, as the paper says; past it (only on adversarial input
/// such as exponentially spaced triangles, where a mean split peels one triangle at a time) the split
/// is at the median, so the depth stays O(log n) and traversal stacks stay small.
const MEAN_SPLIT_MAX_DEPTH: usize = 40;

/// Upper bound on the depth of any built tree: the mean-split levels plus a median-split tail.
pub(crate) const MAX_DEPTH: usize = MEAN_SPLIT_MAX_DEPTH + 33;

/// What the build keeps of a triangle, permuted in place into leaf order as nodes split: a node's
/// triangles are always one contiguous run of these. 16 bytes: what the node needs of the
/// triangle's geometry it reads through its vertices.
#[derive(Clone, Copy, Debug)]
pub(super) struct Record {
    /// Its vertices, indices into the distinct vertices of the input.
    face: [u32; 3],
    /// Its position among the triangles as added: becomes `Bvh::added`.
    added: u32,
}

/// What every node's build reads: the distinct vertices, the volumes asked for, and the bound on
/// the vertices' `|p|_1` the fits' rounding allowances take.
pub(super) struct Input<'a> {
    verts: &'a [Vec3],
    volume: VolumeKind,
    scale: f64,
}

/// A subtree to build: its triangles' records, the slots of its inner nodes (`recs.len() - 1`,
/// the first its root's), the index of the first of those slots and of its first triangle in leaf
/// order, its depth, its root's distinct vertices (indices into `Input::verts`) with how many of
/// its triangles' corners each is (both empty for a subtree handed to another thread, which lists
/// them from the records), and its parent's frame (where the root's eigensolver starts).
pub(super) struct Subtree<'a> {
    pub recs: &'a mut [Record],
    pub nodes: NodeSlots<'a>,
    pub base: usize,
    pub first_leaf: usize,
    pub depth: usize,
    pub verts: Vec<u32>,
    pub counts: Vec<u32>,
    pub frame: Mat3,
}

/// One builder's scratch, reused from node to node: for each vertex, its stamp (the index of the
/// node that last listed it: what finds a node's distinct vertices) and its position in the list
/// that last listed it (valid for the node being built: its list was made just before), side by
/// side so that a corner's look-up reads one place; the node's points, the same in its frame, its
/// triangles' split keys, and a stack of vertex lists (each node's, along the path from the
/// subtree's root) with, alongside, how many of the node's corners each vertex is.
pub(super) struct Scratch {
    slots: Vec<Slot>,
    points: Vec<Vec3>,
    local: Vec<Vec3>,
    keys: Vec<f64>,
    lists: Vec<u32>,
    counts: Vec<u32>,
}

/// A vertex's stamp and position (see [`Scratch`]).
#[derive(Clone, Copy)]
struct Slot {
    stamp: u32,
    pos: u32,
}

impl Scratch {
    pub fn new(num_verts: usize) -> Result<Scratch, Error> {
        let mut slots = with_room(num_verts)?;
        slots.resize(
            num_verts,
            Slot {
                stamp: u32::MAX,
                pos: 0,
            },
        );
        Ok(Scratch {
            slots,
            points: Vec::new(),
            local: Vec::new(),
            keys: Vec::new(),
            lists: Vec::new(),
            counts: Vec::new(),
        })
    }
}

impl Bvh {
    /// Builds the hierarchy over `tris` (not empty), with swept sphere volumes of `volume` and
    /// collision on `collision`, on this thread. O(n log n).
    #[cfg(test)]
    pub fn build(
        tris: Vec<(Tri, i32)>,
        volume: VolumeKind,
        collision: CollisionVolume,
    ) -> Result<Bvh, Error> {
        Bvh::build_threads(tris, volume, collision, 1)
    }

    /// The hierarchy of [`Bvh::build`], on up to `threads` threads (1: this one only; the
    /// hierarchy is the same, bit for bit, whatever the number).
    pub fn build_threads(
        tris: Vec<(Tri, i32)>,
        volume: VolumeKind,
        collision: CollisionVolume,
        threads: usize,
    ) -> Result<Bvh, Error> {
        let n = tris.len();
        debug_assert!(n > 0);
        // The distinct vertices in the order they first appear in the input, each triangle's
        // by index.
        // No more threads than subtrees worth one.
        let threads = threads.clamp(1, 1 + n / GRAIN);
        let (in_verts, in_faces) = share_corners(n, |c| &tris[c / 3].0[c % 3], threads)?;
        // The records, and (the root's) how many corners each vertex is.
        let (mut recs, counts) = records(&in_faces, in_verts.len(), threads)?;
        drop(in_faces);
        // The ids in insertion order, for the leaf-order arrays; then the input is dropped. On
        // several threads, another thread does this while this one builds the root.
        let mut given_ids: Vec<i32> = with_room(n)?;
        let ids_of = |tris: Vec<(Tri, i32)>, given_ids: &mut Vec<i32>| {
            given_ids.extend(tris.iter().map(|(_, id)| *id));
        };
        // At least every vertex's `|p|_1` (twice the largest, which is rounded): for the rounding
        // allowances of `fit_volumes`.
        let scale = 2.0 * in_verts.iter().fold(0.0f64, |m, p| m.max(p.abs().sum()));
        let input = Input {
            verts: &in_verts,
            volume,
            scale,
        };
        let mut nodes: Vec<Node> = zeroed(n - 1)?;
        let mut boxes: Vec<NodeBox> = zeroed(n - 1)?;
        // The leaf-order arrays: ids, insertion indices, and the vertices renumbered in the order
        // they first appear in leaf order (what `share_vertices` of the leaf-ordered triangles
        // gives, as the hierarchy's triangles of a subtree are then near each other). In fresh
        // zeroed memory, each entry written once, after the hierarchy is built.
        let mut ids: Vec<i32> = zeroed(n)?;
        let mut added: Vec<u32> = zeroed(n)?;
        let mut faces: Vec<[u32; 3]> = zeroed(n)?;
        let mut verts: Vec<Vec3> = zeroed(in_verts.len())?;
        if n == 1 {
            ids_of(tris, &mut given_ids);
        } else {
            // Where the nodes and their boxes are, for the thread that maps their pages in.
            let node_bytes = [
                (nodes.as_mut_ptr().cast::<u8>(), size_of_val(&nodes[..])),
                (boxes.as_mut_ptr().cast::<u8>(), size_of_val(&boxes[..])),
            ]
            .map(|(p, len)| (p as usize, len));
            // The root's vertices: all of them, each as many times as the triangles' corners.
            let mut all: Vec<u32> = with_room(in_verts.len())?;
            all.extend(0..in_verts.len() as u32);
            let root = Subtree {
                recs: &mut recs,
                nodes: NodeSlots::new(&mut nodes, &mut boxes),
                base: 0,
                first_leaf: 0,
                depth: 0,
                verts: all,
                counts,
                frame: Mat3::identity(),
            };
            if threads == 1 {
                ids_of(tris, &mut given_ids);
                let mut scratch = Scratch::new(in_verts.len())?;
                build_subtree(&input, &mut scratch, root, None)?;
            } else {
                Pool::run(
                    threads,
                    root,
                    |scratch, sub, pool| build_subtree(&input, scratch, sub, Some(pool)),
                    || Scratch::new(in_verts.len()),
                    || {
                        ids_of(tris, &mut given_ids);
                        // The fresh arrays the build will write are then mapped in here, while
                        // this thread would otherwise wait for the root's split (the first page
                        // faults of 200 bytes a triangle, in one call a run of pages rather than
                        // one fault a page on the building threads): first the nodes and boxes
                        // (the building threads write them meanwhile: only the kernel's call,
                        // which touches no byte, may map them in here), then the leaf-order
                        // arrays, which only this closure holds until the build ends.
                        for (at, len) in node_bytes {
                            populate_in_runs(at as *mut u8, len);
                        }
                        prefault(&mut ids);
                        prefault(&mut added);
                        prefault(&mut faces);
                        prefault(&mut verts);
                        Ok(())
                    },
                )?;
            }
        }

        let out = LeafOrder {
            ids: &mut ids,
            added: &mut added,
            faces: &mut faces,
            verts: &mut verts,
        };
        let (inner, scans) = out.fill_on(threads, &recs, &given_ids, &in_verts, &nodes)?;
        drop(recs);
        drop(given_ids);
        // `in_verts` are shared, and `verts` is a permutation of them.
        Ok(Bvh::assemble(
            nodes, boxes, verts, faces, ids, added, collision, inner, true, scans,
        ))
    }
}

/// The records of the triangles `faces` (of `verts` distinct vertices), in insertion order, and
/// how many of their corners each vertex is. On several threads, a run of the triangles a task,
/// each counting its corners apart; the counts are then added up, a run of the vertices a task
/// (integers: the same sums in any order).
fn records(
    faces: &[[u32; 3]],
    verts: usize,
    threads: usize,
) -> Result<(Vec<Record>, Vec<u32>), Error> {
    let mut recs: Vec<Record> = zeroed(faces.len())?;
    let fill = |start: usize, recs: &mut [Record], counts: &mut [u32]| {
        for (k, (r, f)) in (start..).zip(recs.iter_mut().zip(&faces[start..])) {
            *r = Record {
                face: *f,
                added: k as u32,
            };
            for &v in f {
                counts[v as usize] += 1;
            }
        }
    };
    if threads == 1 {
        let mut counts: Vec<u32> = zeroed(verts)?;
        fill(0, &mut recs, &mut counts);
        return Ok((recs, counts));
    }
    let mut parts = run_tasks(
        threads,
        runs_of(&mut recs, threads),
        |_: &mut (), (start, recs)| {
            let mut counts: Vec<u32> = zeroed(verts)?;
            fill(start, recs, &mut counts);
            Ok(counts)
        },
        || Ok(()),
    )?;
    let mut counts = parts.remove(0);
    let parts = &parts;
    run_tasks(
        threads,
        runs_of(&mut counts, threads),
        |_: &mut (), (start, counts)| {
            for part in parts {
                for (c, p) in counts.iter_mut().zip(&part[start..]) {
                    *c += p;
                }
            }
            Ok(())
        },
        || Ok(()),
    )?;
    Ok((recs, counts))
}

/// Builds `sub`'s nodes, depth first; `pool` (if any) may take a child's subtree to build on
/// another thread. Each node's volumes and split depend only on its triangles' records, in their
/// order, and on its vertex list, so the hierarchy does not depend on what the pool takes.
fn build_subtree<'a>(
    input: &Input,
    scratch: &mut Scratch,
    mut sub: Subtree<'a>,
    pool: Option<&Pool<Subtree<'a>>>,
) -> Result<(), Error> {
    let oom = |_| Error::ModelOutOfMemory;
    // The subtree's vertex lists go on the scratch stack: room for the root's, and for every
    // node's along a path (each at most three per triangle below it, a geometric series).
    let bottom = scratch.lists.len();
    let m = sub.recs.len();
    let room = sub.verts.len().max(3 * m) + 6 * m + 64;
    scratch.lists.try_reserve(room).map_err(oom)?;
    scratch.counts.try_reserve(room).map_err(oom)?;
    if sub.verts.is_empty() {
        // A subtree handed over by another thread: its vertices are listed here.
        list_vertices(scratch, sub.recs, sub.base);
    } else {
        for (i, &v) in sub.verts.iter().enumerate() {
            scratch.slots[v as usize].pos = i as u32;
        }
        scratch.lists.extend_from_slice(&sub.verts);
        scratch.counts.extend_from_slice(&sub.counts);
    }
    // Freed before the build below, which may take long: the list is on the stack now.
    drop(std::mem::take(&mut sub.verts));
    drop(std::mem::take(&mut sub.counts));
    build_listed(input, scratch, sub, bottom, pool)
}

/// Builds `sub`'s nodes, depth first, once its root's vertex list is on the scratch stack from
/// `list` on; takes the list (and every list above it) off the stack again.
fn build_listed<'a>(
    input: &Input,
    scratch: &mut Scratch,
    sub: Subtree<'a>,
    list: usize,
    pool: Option<&Pool<Subtree<'a>>>,
) -> Result<(), Error> {
    let r = node(
        input,
        scratch,
        sub.recs,
        sub.nodes,
        sub.base,
        sub.first_leaf,
        sub.depth,
        &sub.frame,
        list,
        pool,
    );
    scratch.lists.truncate(list);
    scratch.counts.truncate(list);
    r
}

/// An empty vector with room for `n`, or `Err(ModelOutOfMemory)`. Unlike a load's arrays
/// (`saved/`), the build's are not offered huge pages: with the kernel's default `defrag`
/// setting a huge-page fault may compact memory synchronously, and in measurements the
/// single-thread 1M build became 1.2-1.3x slower and erratic with them.
fn with_room<T>(n: usize) -> Result<Vec<T>, Error> {
    let mut v = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|_| Error::ModelOutOfMemory)?;
    Ok(v)
}

/// How many records (or list entries) ahead the leaf-order passes fetch what they will read.
const AHEAD: usize = 8;

/// The hierarchy's arrays in leaf order, to fill from the records in leaf order: `ids`, `added`
/// and `faces` (as long as the records), and `verts` (as long as the input's vertices; cut to
/// those some record has).
struct LeafOrder<'a> {
    ids: &'a mut [i32],
    added: &'a mut [u32],
    faces: &'a mut [[u32; 3]],
    verts: &'a mut Vec<Vec3>,
}

impl LeafOrder<'_> {
    /// [`LeafOrder::fill_on`] on one thread, in one pass.
    fn fill(self, recs: &[Record], given_ids: &[i32], in_verts: &[Vec3]) -> Result<(), Error> {
        // Each input vertex's number plus one, 0 while not met.
        let mut remap: Vec<u32> = zeroed(in_verts.len())?;
        let (verts, mut met) = (self.verts, 0);
        let out = self
            .ids
            .iter_mut()
            .zip(self.added.iter_mut())
            .zip(self.faces.iter_mut());
        // The reads by insertion index and by vertex jump about: each record's are fetched into
        // the cache a few records early (as `first_corners` does), here and in `fill_on`.
        for (k, (r, ((id, added), face))) in recs.iter().zip(out).enumerate() {
            if let Some(next) = recs.get(k + AHEAD) {
                prefetch(given_ids, next.added as usize);
                for &v in &next.face {
                    prefetch(&remap, v as usize);
                }
            }
            *id = given_ids[r.added as usize];
            *added = r.added;
            *face = r.face.map(|v| {
                let slot = &mut remap[v as usize];
                if *slot == 0 {
                    verts[met] = in_verts[v as usize];
                    met += 1;
                    *slot = met as u32;
                }
                *slot - 1
            });
        }
        verts.truncate(met);
        Ok(())
    }

    /// Fills the arrays from `recs` (in leaf order), the ids given in insertion order, and the
    /// distinct vertices of the input, on `threads` threads, and returns [`Bvh::inner_scale`]
    /// of `nodes`: the same whatever the thread count. On several threads the records are cut
    /// into runs, and every step runs on the threads, a task a run: each run's ids and insertion
    /// indices are copied, and its vertices listed in the order they first appear in it, while
    /// each vertex keeps the first run that lists it (an atomic maximum of `runs - run`); then
    /// each run keeps, of its list, the vertices it lists first: in the order they first appear
    /// in all, the vertices are those of the first run, then those of the second, and so on,
    /// each run's in its order. So each run numbers its own, from where the earlier runs' end,
    /// and copies them into place; then each run's faces are renumbered, and a share of the
    /// nodes scanned for their largest scale, and a share of the faces and vertices for what
    /// [`Bvh::assemble`] reads of them (on one thread, `None`: `assemble` scans them).
    fn fill_on(
        self,
        threads: usize,
        recs: &[Record],
        given_ids: &[i32],
        in_verts: &[Vec3],
        nodes: &[Node],
    ) -> Result<(f64, Option<Scans>), Error> {
        if threads == 1 {
            self.fill(recs, given_ids, in_verts)?;
            return Ok((Bvh::inner_scale(nodes), None));
        }
        let runs = 4 * threads;
        let cut = |k: usize, len: usize| k * len / runs;
        let n = recs.len();
        let (mut ids, mut added) = (self.ids, self.added);
        // For each input vertex, `runs` minus the first run that lists it (0 while none has).
        // Relaxed atomics throughout: each step's tasks end (their threads joined) before the
        // next step's start, which orders every write before every read of the next step.
        let first: Vec<AtomicU32> = zeroed(in_verts.len())?;
        let first = &first;
        let mut listing = Vec::new();
        for k in 0..runs {
            let len = cut(k + 1, n) - cut(k, n);
            let (i, rest) = std::mem::take(&mut ids).split_at_mut(len);
            ids = rest;
            let (a, rest) = std::mem::take(&mut added).split_at_mut(len);
            added = rest;
            listing.push((&recs[cut(k, n)..cut(k + 1, n)], i, a, k));
        }
        let lists = run_tasks(
            threads,
            listing,
            |stamps: &mut Vec<u32>, (recs, ids, added, k)| {
                // Stamps: the run (plus one) that last listed each vertex on this thread.
                let tag = k as u32 + 1;
                let mut list: Vec<u32> = with_room(recs.len() / 2 + 16)?;
                let out = ids.iter_mut().zip(added.iter_mut());
                for (j, (r, (id, added))) in recs.iter().zip(out).enumerate() {
                    if let Some(next) = recs.get(j + AHEAD) {
                        prefetch(given_ids, next.added as usize);
                        for &v in &next.face {
                            prefetch(stamps, v as usize);
                        }
                    }
                    *id = given_ids[r.added as usize];
                    *added = r.added;
                    for &v in &r.face {
                        let stamp = &mut stamps[v as usize];
                        if *stamp != tag {
                            *stamp = tag;
                            if list.len() == list.capacity() {
                                list.try_reserve(list.len())
                                    .map_err(|_| Error::ModelOutOfMemory)?;
                            }
                            list.push(v);
                            first[v as usize].fetch_max((runs - k) as u32, Ordering::Relaxed);
                        }
                    }
                }
                Ok(list)
            },
            || zeroed::<u32>(in_verts.len()),
        )?;
        // Each run's own vertices.
        let lists = run_tasks(
            threads,
            lists.into_iter().enumerate().collect(),
            |_: &mut (), (k, mut list)| {
                let own = (runs - k) as u32;
                let mut kept = 0;
                for j in 0..list.len() {
                    if let Some(&next) = list.get(j + AHEAD) {
                        prefetch(first, next as usize);
                    }
                    let v = list[j];
                    if first[v as usize].load(Ordering::Relaxed) == own {
                        list[kept] = v;
                        kept += 1;
                    }
                }
                list.truncate(kept);
                Ok(list)
            },
            || Ok(()),
        )?;
        // Each input vertex's number.
        let remap: Vec<AtomicU32> = zeroed(in_verts.len())?;
        let remap = &remap;
        let mut verts = &mut self.verts[..];
        let mut numbering = Vec::new();
        let mut from = 0;
        for list in &lists {
            let (v, rest) = std::mem::take(&mut verts).split_at_mut(list.len());
            verts = rest;
            numbering.push((list, v, from));
            from += list.len();
        }
        run_tasks(
            threads,
            numbering,
            |_: &mut (), (list, verts, from)| {
                for (j, ((number, &v), out)) in
                    (from as u32..).zip(list).zip(verts.iter_mut()).enumerate()
                {
                    if let Some(&next) = list.get(j + AHEAD) {
                        prefetch(in_verts, next as usize);
                        prefetch(remap, next as usize);
                    }
                    remap[v as usize].store(number, Ordering::Relaxed);
                    *out = in_verts[v as usize];
                }
                Ok(())
            },
            || Ok(()),
        )?;
        drop(lists);
        self.verts.truncate(from);
        let verts = &self.verts[..];
        let mut faces = self.faces;
        let mut renumbering = Vec::new();
        for k in 0..runs {
            let len = cut(k + 1, n) - cut(k, n);
            let (f, rest) = std::mem::take(&mut faces).split_at_mut(len);
            faces = rest;
            let (m, v) = (nodes.len(), verts.len());
            renumbering.push((
                &recs[cut(k, n)..cut(k + 1, n)],
                f,
                &nodes[cut(k, m)..cut(k + 1, m)],
                &verts[cut(k, v)..cut(k + 1, v)],
            ));
        }
        let scans = run_tasks(
            threads,
            renumbering,
            |_: &mut (), (recs, faces, nodes, part)| {
                for (j, (r, face)) in recs.iter().zip(faces.iter_mut()).enumerate() {
                    if let Some(next) = recs.get(j + AHEAD) {
                        for &v in &next.face {
                            prefetch(remap, v as usize);
                        }
                    }
                    *face = r.face.map(|v| remap[v as usize].load(Ordering::Relaxed));
                }
                Ok((Bvh::inner_scale(nodes), Scans::of(part, faces, verts)))
            },
            || Ok(()),
        )?;
        // The largest of the largest, and the scans merged: the same whatever the cut, as `max`
        // and "some" are.
        Ok(scans
            .into_iter()
            .reduce(|(a, s), (b, t)| (a.max(b), s.merge(t)))
            .map(|(inner, s)| (inner, Some(s)))
            .unwrap_or((0.0, None)))
    }
}

/// Builds the node of triangles `recs` (at least two), whose distinct vertices are
/// `scratch.lists[list..]` (their multiplicities `scratch.counts[list..]`, their positions in the
/// list in `scratch.slots`), into `nodes[0]` (its index `base`), and the subtrees below it into the
/// rest of `nodes`. `guess` is the parent's frame, where the eigensolver starts.
#[allow(clippy::too_many_arguments)]
fn node<'a>(
    input: &Input,
    scratch: &mut Scratch,
    recs: &'a mut [Record],
    nodes: NodeSlots<'a>,
    base: usize,
    first_leaf: usize,
    depth: usize,
    guess: &Mat3,
    list: usize,
    pool: Option<&Pool<Subtree<'a>>>,
) -> Result<(), Error> {
    let m = recs.len();
    debug_assert!(m >= 2 && nodes.len() == m - 1);
    // The node's points, and their mean weighted by how many corners each is, in one pass.
    // (`extend` of a zip of slices: room is made once, no check per point.)
    scratch.points.clear();
    let (mut sum, mut total) = (Vec3::zeros(), 0.0f64);
    scratch.points.extend(
        scratch.lists[list..]
            .iter()
            .zip(&scratch.counts[list..])
            .map(|(&v, &w)| {
                let p = input.verts[v as usize];
                let w = f64::from(w);
                sum += p * w;
                total += w;
                p
            }),
    );
    // The covariance of the node's corners: of its distinct vertices, each weighted by how many
    // corners it is.
    let a = axes_of(
        &weighted_scatter(
            &scratch.points,
            &scratch.counts[list..],
            &(sum / total),
            total,
        ),
        guess,
    );
    // The frame exactly as the node will give it back.
    let axes = frame_from(&a.column(0).into(), &a.column(1).into());
    let (ssv, obb) = fit_volumes(
        input.volume,
        &axes,
        &scratch.points,
        input.scale,
        &mut scratch.local,
    );
    // Each triangle's key: its corners' coordinates along the first axis, summed (three times
    // its centroid's), from the points in the frame that the fits computed.
    scratch.keys.clear();
    let (slots, local) = (&scratch.slots, &scratch.local);
    scratch.keys.extend(recs.iter().map(|r| {
        let x = |k: usize| local[slots[r.face[k] as usize].pos as usize].x;
        x(0) + x(1) + x(2)
    }));
    let mid = split(recs, &mut scratch.keys, depth >= MEAN_SPLIT_MAX_DEPTH);
    let (mut this, below) = nodes.split_first_mut().expect("a node for every split");
    this.set(&ssv, &obb);
    let (left_recs, right_recs) = recs.split_at_mut(mid);
    let (left_nodes, right_nodes) = below.split_at_mut(mid - 1);
    let children = [
        (left_recs, left_nodes, base + 1, first_leaf),
        (right_recs, right_nodes, base + mid, first_leaf + mid),
    ];
    for (k, (crecs, cnodes, cbase, cleaf)) in children.into_iter().enumerate() {
        if crecs.len() == 1 {
            // Leaves point at the triangle's slot in leaf order.
            this.children[k] = NodeRef::leaf(cleaf);
            continue;
        }
        this.children[k] = NodeRef::inner(cbase);
        let sub = Subtree {
            recs: crecs,
            nodes: cnodes,
            base: cbase,
            first_leaf: cleaf,
            depth: depth + 1,
            verts: Vec::new(),
            counts: Vec::new(),
            frame: axes,
        };
        // Offered before its vertex list is made: a thread that takes it lists the vertices
        // itself (the same list, which depends only on the records), while this one goes on.
        if let Some(sub) = offer_subtree(sub, pool) {
            let start = scratch.lists.len();
            list_vertices(scratch, sub.recs, sub.base);
            build_listed(input, scratch, sub, start, pool)?;
        }
    }
    Ok(())
}

/// Lists the distinct vertices of the triangles `recs` (of the node numbered `base`) on the
/// scratch stack, in the order the triangles first give them, with how many corners each is, and
/// their positions in the list in `scratch.slots`.
fn list_vertices(scratch: &mut Scratch, recs: &[Record], base: usize) {
    // Written into room for every corner, then cut to the vertices met: no capacity check per
    // corner, and the only branch is on a vertex being new. A new vertex's count is written as 1
    // there (rather than the room zeroed first, a pass over every corner's slot, and added to
    // after), a repeat's added to. The stamp is the node's number, which no other node has: a
    // thread's stamps need no clearing between the subtrees it builds.
    let start = scratch.lists.len();
    let tag = base as u32;
    let corners = 3 * recs.len();
    scratch.lists.reserve(corners);
    scratch.counts.reserve(corners);
    let room = &mut scratch.lists.spare_capacity_mut()[..corners];
    let counts = &mut scratch.counts.spare_capacity_mut()[..corners];
    let mut len = 0usize;
    for r in recs {
        for &v in &r.face {
            let slot = &mut scratch.slots[v as usize];
            if slot.stamp != tag {
                *slot = Slot {
                    stamp: tag,
                    pos: len as u32,
                };
                room[len].write(v);
                counts[len].write(1);
                len += 1;
            } else {
                // SAFETY: a vertex met before has its count at `pos < len`, written when it was
                // first met.
                unsafe { *counts[slot.pos as usize].assume_init_mut() += 1 };
            }
        }
    }
    // SAFETY: the first `len` entries of both spare capacities were written just above.
    unsafe {
        scratch.lists.set_len(start + len);
        scratch.counts.set_len(start + len);
    }
}

/// Offers `sub` (without its vertex list) to the pool: `None` if taken, else the subtree back, to
/// build here. Only subtrees worth a thread are offered, and only while a thread is idle.
fn offer_subtree<'a>(sub: Subtree<'a>, pool: Option<&Pool<Subtree<'a>>>) -> Option<Subtree<'a>> {
    match pool {
        Some(pool) if sub.recs.len() >= GRAIN && pool.wants() => pool.offer(sub),
        _ => Some(sub),
    }
}

/// The distinct vertices of the triangles (equal coordinates, bit for bit, stored once, in the order
/// they first appear) and each triangle's vertex indices. Finds repeats with a hash table of
/// corners, kept at most half full: expected O(n).
pub(super) fn share_vertices(tris: &[Tri]) -> Result<(Vec<Vec3>, Vec<[u32; 3]>), Error> {
    let corners = tris.as_flattened();
    share_corners(tris.len(), |c| &corners[c], 1)
}

/// [`share_vertices`] of the `count` triangles whose corner `c` (`3 t + k`: corner `k` of
/// triangle `t`) is `corner(c)`, on up to `threads` threads, the same whatever their number.
/// On several, the corners are cut into runs (one a thread), each of which numbers the bit
/// patterns met in it, in order, with a hash table of them. The runs' patterns, taken run after
/// run, are then looked up (on the threads) in the tables of the runs before theirs: a pattern
/// found there is a repeat of the first one found, the others are new. A pass over the patterns
/// on this thread numbers the new ones in order and gives each repeat the number of the pattern
/// it repeats (a pattern's first corner is in the first run that has it, where it comes in the
/// order met: the numbers are those of the order of first appearance); for a mesh that is about
/// one pattern a vertex, each read once, rather than six corners. Then each run's corners are
/// renumbered on the threads.
fn share_corners<'a>(
    count: usize,
    corner: impl Fn(usize) -> &'a Vec3 + Sync,
    threads: usize,
) -> Result<(Vec<Vec3>, Vec<[u32; 3]>), Error> {
    let bits = |c: usize| {
        let v = corner(c);
        [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
    };
    let vertex = |k: &[u64; 3]| {
        Vec3::new(
            f64::from_bits(k[0]),
            f64::from_bits(k[1]),
            f64::from_bits(k[2]),
        )
    };
    let mut faces: Vec<[u32; 3]> = zeroed(count)?;
    let face_ids = faces.as_flattened_mut();
    let corners = face_ids.len();
    if threads <= 1 {
        let met = first_corners(corners, corners / 6, &bits, |c, k| face_ids[c] = k)?;
        let mut verts: Vec<Vec3> = with_room(met.keys.len())?;
        verts.extend(met.keys.iter().map(vertex));
        return Ok((verts, faces));
    }
    let runs = run_tasks(
        threads,
        runs_of(face_ids, threads),
        |_: &mut (), (start, ids)| {
            first_corners(ids.len(), ids.len() / 6, &|c| bits(start + c), |c, k| {
                ids[c] = k
            })
        },
        || Ok(()),
    )?;
    // Where each run's patterns start among all of them, taken run after run.
    let mut starts = vec![0];
    for run in &runs {
        starts.push(starts[starts.len() - 1] + run.keys.len());
    }
    let total = starts[threads];
    // For each pattern (by its index among all): its own index if no earlier run has it, else
    // the index of the first earlier run's. The first run's are all new.
    let mut numbers: Vec<u32> = with_room(total)?;
    numbers.extend(0..total as u32);
    let (runs, starts) = (&runs, &starts);
    run_tasks(
        threads,
        runs_of(&mut numbers[starts[1]..], threads),
        |_: &mut (), (offset, out)| {
            let key_of = |i: usize| {
                let run = starts.partition_point(|&s| s <= i) - 1;
                (run, &runs[run].keys[i - starts[run]])
            };
            let end = starts[1] + offset + out.len();
            for (i, slot) in (starts[1] + offset..).zip(out.iter_mut()) {
                // The earlier runs' slots for the pattern `AHEAD` on, fetched into the cache.
                if i + AHEAD < end {
                    let (run, key) = key_of(i + AHEAD);
                    let h = hash(key);
                    for earlier in &runs[..run] {
                        prefetch(&earlier.table, (h >> earlier.shift) as usize);
                    }
                }
                let (run, key) = key_of(i);
                let h = hash(key);
                if let Some((j, k)) = runs[..run]
                    .iter()
                    .enumerate()
                    .find_map(|(j, earlier)| earlier.find(key, h).map(|k| (j, k)))
                {
                    *slot = (starts[j] + k as usize) as u32;
                }
            }
            Ok(())
        },
        || Ok(()),
    )?;
    // Numbered in order: a repeat's pattern comes earlier, and is numbered by then.
    let mut verts: Vec<Vec3> = with_room(total)?;
    for i in 0..total {
        let first = numbers[i] as usize;
        numbers[i] = if first == i {
            let run = starts.partition_point(|&s| s <= i) - 1;
            verts.push(vertex(&runs[run].keys[i - starts[run]]));
            verts.len() as u32 - 1
        } else {
            numbers[first]
        };
    }
    let numbers = &numbers;
    run_tasks(
        threads,
        runs_of(face_ids, threads).into_iter().enumerate().collect(),
        |_: &mut (), (run, (_, ids))| {
            for id in ids.iter_mut() {
                *id = numbers[starts[run] + *id as usize];
            }
            Ok(())
        },
        || Ok(()),
    )?;
    Ok((verts, faces))
}

/// `v` cut into `runs` runs of about equal length (their first index, the run).
fn runs_of<T>(v: &mut [T], runs: usize) -> Vec<(usize, &mut [T])> {
    let len = v.len();
    let cut = |k: usize| k * len / runs;
    let mut rest = v;
    (0..runs)
        .map(|k| {
            let (run, r) = std::mem::take(&mut rest).split_at_mut(cut(k + 1) - cut(k));
            rest = r;
            (cut(k), run)
        })
        .collect()
}

/// For each of the `corners`, in increasing order, `found(c, k)`: `k` the number of distinct bit
/// patterns met before the first corner with the same bits as `c` (`bits(c)`). Returns the
/// distinct patterns, in the order met, with the hash table that found repeats among them, kept
/// at most half full (sized for `room` patterns at first): expected O(corners).
fn first_corners(
    corners: usize,
    room: usize,
    bits: &impl Fn(usize) -> [u64; 3],
    mut found: impl FnMut(usize, u32),
) -> Result<Met, Error> {
    // The distinct bit patterns met: repeats are compared against these rather than the
    // input's corners, a compact array in which the patterns met lately (a mesh's repeats are
    // mostly of vertices of nearby triangles) are near each other.
    let mut keys: Vec<[u64; 3]> = Vec::new();
    // Slots hold an index into `keys` plus one (0: empty); doubled whenever half full.
    let mut shift = 64 - (2 * room).max(8).next_power_of_two().trailing_zeros();
    let mut table: Vec<u32> = Vec::new();
    let grow = |table: &mut Vec<u32>, keys: &[[u64; 3]], shift: u32| -> Result<(), Error> {
        let size = 1usize << (64 - shift);
        let mut new: Vec<u32> = with_room(size)?;
        new.resize(size, 0);
        for (k, key) in keys.iter().enumerate() {
            let mut i = (hash(key) >> shift) as usize;
            while new[i] != 0 {
                i = (i + 1) & (size - 1);
            }
            new[i] = k as u32 + 1;
        }
        *table = new;
        Ok(())
    };
    grow(&mut table, &keys, shift)?;
    let oom = |_| Error::ModelOutOfMemory;
    // The table's slots are far apart in memory from one corner to the next: each corner's key
    // and hash are computed `AHEAD` corners early, and its slot fetched into the cache then, so
    // that the lookups' cache misses overlap.
    const AHEAD: usize = 16;
    let key_hash = |c: usize| {
        if c < corners {
            let key = bits(c);
            (key, hash(&key))
        } else {
            ([0; 3], 0)
        }
    };
    let mut ring = [([0u64; 3], 0u64); AHEAD];
    for (c, slot) in ring.iter_mut().enumerate() {
        *slot = key_hash(c);
    }
    for c in 0..corners {
        let (key, h) = ring[c % AHEAD];
        let next = key_hash(c + AHEAD);
        prefetch(&table, (next.1 >> shift) as usize);
        ring[c % AHEAD] = next;
        let mask = table.len() - 1;
        let mut i = (h >> shift) as usize;
        loop {
            let e = table[i] as usize;
            if e == 0 {
                let k = keys.len() as u32;
                keys.try_reserve(1).map_err(oom)?;
                keys.push(key);
                table[i] = k + 1;
                found(c, k);
                if 2 * keys.len() > table.len() {
                    shift -= 1;
                    grow(&mut table, &keys, shift)?;
                }
                break;
            }
            if keys[e - 1] == key {
                found(c, e as u32 - 1);
                break;
            }
            i = (i + 1) & mask;
        }
    }
    Ok(Met { keys, table, shift })
}

/// The distinct bit patterns of some corners, in the order met, and a hash table of them: slots
/// hold an index into `keys` plus one (0: empty), a pattern's first slot is `hash >> shift`.
struct Met {
    keys: Vec<[u64; 3]>,
    table: Vec<u32>,
    shift: u32,
}

impl Met {
    /// The index of `key` (its hash `h`) among the patterns, if met.
    fn find(&self, key: &[u64; 3], h: u64) -> Option<u32> {
        let mask = self.table.len() - 1;
        let mut i = (h >> self.shift) as usize;
        loop {
            match self.table[i] as usize {
                0 => return None,
                e if self.keys[e - 1] == *key => return Some(e as u32 - 1),
                _ => i = (i + 1) & mask,
            }
        }
    }
}

/// Asks the processor to bring `v[i]` (if `i` is in bounds) into the cache, where it can.
#[inline(always)]
fn prefetch<T>(v: &[T], i: usize) {
    if let Some(p) = v.get(i) {
        prefetch_line(std::ptr::from_ref(p).cast());
    }
}

/// A multiplicative hash of a vertex's bit pattern: a table of `2^(64 - shift)` slots takes its
/// slot from the top bits, `hash >> shift`.
#[inline]
fn hash(key: &[u64; 3]) -> u64 {
    const K: u64 = 0x9e37_79b9_7f4a_7c15;
    let h = (key[0].wrapping_mul(K) ^ key[1])
        .wrapping_mul(K)
        .rotate_left(29)
        ^ key[2];
    h.wrapping_mul(K)
}

/// Bytes mapped in by one call of [`populate_in_runs`]: the kernel holds the memory map's lock
/// (for reading) through a call, so the building threads' own page faults are not kept waiting
/// long.
const POPULATE_RUN: usize = 1 << 21;

/// [`populate_pages`] of the `len` bytes at `start` (an allocation), a run of [`POPULATE_RUN`]
/// bytes at a time; stops at the first refusal (nothing is lost: the pages are then mapped in by
/// the first writes, as without it). Whether every call succeeded.
fn populate_in_runs(start: *mut u8, len: usize) -> bool {
    let mut done = 0;
    while done < len {
        let run = POPULATE_RUN.min(len - done);
        // (`wrapping_add`: the address stays inside the allocation; no reference is made.)
        if !populate_pages(start.wrapping_add(done), run) {
            return false;
        }
        done += run;
    }
    true
}

/// Maps in the pages of `v` before its first writes, with [`populate_in_runs`] or, where that is
/// refused, by [`touch_pages`].
fn prefault<T>(v: &mut [T]) {
    if !populate_in_runs(v.as_mut_ptr().cast(), size_of_val(v)) {
        touch_pages(v);
    }
}

/// Writes one byte in every 4 KiB of `v` back with the value it has (what maps in a fresh page,
/// the contents unchanged). Volatile, so the compiler keeps the writes that change nothing.
fn touch_pages<T>(v: &mut [T]) {
    let (start, len) = (v.as_mut_ptr().cast::<u8>(), size_of_val(v));
    for offset in (0..len).step_by(1 << 12) {
        // SAFETY: `offset < len`: the byte is inside `v`, which this function holds exclusively;
        // every byte of it is initialized (a `T`'s padding aside, which is never read or written
        // here as a value of `T`: read as a byte it may be uninitialized, so it is read and
        // written as `MaybeUninit<u8>`).
        unsafe {
            let p = start.add(offset).cast::<std::mem::MaybeUninit<u8>>();
            p.write_volatile(p.read_volatile());
        }
    }
}

/// Types for which zero bits are a valid value: only floats and integers.
///
/// # Safety
/// Only for such types.
unsafe trait ZeroBits {}
// SAFETY: a node is floats and integers only (its volume's coordinates and size, its children).
unsafe impl ZeroBits for Node {}
// SAFETY: floats (a box's centre and half extents).
unsafe impl ZeroBits for NodeBox {}
// SAFETY: integers.
unsafe impl ZeroBits for u32 {}
// SAFETY: integers (a record's vertex indices and insertion index).
unsafe impl ZeroBits for Record {}
// SAFETY: integers.
unsafe impl ZeroBits for i32 {}
// SAFETY: integers.
unsafe impl ZeroBits for [u32; 3] {}
// SAFETY: an integer (`AtomicU32` has the layout of `u32`).
unsafe impl ZeroBits for AtomicU32 {}
// SAFETY: floats.
unsafe impl ZeroBits for Vec3 {}

/// `len` values of zero bits, or `Err(ModelOutOfMemory)`. For arrays the build writes once,
/// entry by entry, and for counts and marks that start at zero: they are asked of the allocator
/// already zeroed (`calloc`), so a large one is fresh pages, which the system maps in zeroed as
/// they are first written (for the node array, on whichever thread builds that subtree) rather
/// than a pass on this thread writing all of it (the node array: 160 MB at 1M triangles) before
/// the build writes it again.
fn zeroed<T: ZeroBits>(len: usize) -> Result<Vec<T>, Error> {
    let oom = |_| Error::ModelOutOfMemory;
    let layout = std::alloc::Layout::array::<T>(len).map_err(oom)?;
    if layout.size() == 0 {
        // No type of the trait has size zero: `len` is 0.
        return Ok(Vec::new());
    }
    // SAFETY: the layout's size is not zero (`alloc_zeroed` requires it).
    let ptr = unsafe { std::alloc::alloc_zeroed(layout) }.cast::<T>();
    if ptr.is_null() {
        return Err(Error::ModelOutOfMemory);
    }
    // SAFETY: `ptr` was allocated by the global allocator with the layout of `len` values of
    // `T` (the alignment of `T`, the size of a capacity of `len`), as `Vec` allocates; its
    // `len` values are initialized: all their bits are zero, a valid value of `T` (`ZeroBits`).
    Ok(unsafe { Vec::from_raw_parts(ptr, len, len) })
}

/// Partitions the triangles `recs` (at least two; their split `keys` alongside) and returns how
/// many go to the first child (never 0 nor all): those whose centroid projects below the mean or
/// those above it, whichever are more, or the lower half by projection when the mean splits
/// nothing off or `median` is asked for.
fn split(recs: &mut [Record], keys: &mut [f64], median: bool) -> usize {
    let count = recs.len();
    debug_assert_eq!(keys.len(), count);
    if !median {
        let mean = keys.iter().sum::<f64>() / count as f64;
        // The side with more triangles goes first (becomes the first child): searches that stop
        // early or prune by a bound (collide first, distance, tolerance) meet it first, and do
        // fewer tests for it (BENCHMARKS.md, "Build speed").
        let below = keys.iter().filter(|&&k| k < mean).count();
        let upper_first = 2 * below < count;
        let mut left = 0;
        for i in 0..count {
            if (keys[i] < mean) != upper_first {
                if i != left {
                    recs.swap(i, left);
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
    // too, then move the records to the positions' new order.
    let mut pairs: Vec<(f64, u32)> = keys.iter().copied().zip(0..count as u32).collect();
    let mid = count / 2;
    pairs.select_nth_unstable_by(mid, |a, b| a.0.total_cmp(&b.0));
    let old = recs.to_vec();
    for (k, &(_, i)) in pairs.iter().enumerate() {
        recs[k] = old[i as usize];
    }
    mid
}

/// The node's volumes on `axes` around its `points` (not empty): the swept sphere volume of the
/// model's kind (for the hybrid the kind that suits the points) and the box. The same as
/// [`Ssv::fit`] and [`Obb::fit`], bit for bit, for less work: the points are taken into the frame
/// once for all the fits (into `local`, scratch), and both volumes are covered in one pass that
/// (above `SMALL_COVER` points) skips the points clearly inside both. `scale` is at least every
/// point's `|p|_1`.
fn fit_volumes(
    volume: VolumeKind,
    axes: &Mat3,
    points: &[Vec3],
    scale: f64,
    local: &mut Vec<Vec3>,
) -> (Ssv, Obb) {
    let first = axes.tr_mul(&points[0]);
    let (mut lo, mut hi) = (first, first);
    local.clear();
    // (`extend` of a slice's map: room is made once, no check per point.)
    local.extend(points.iter().map(|p| {
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
        q
    }));
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
    if points.len() <= SMALL_COVER {
        // Every point, exactly as `Ssv::cover` and `Obb::cover` measure it; a point inside
        // changes neither the largest distance nor the extents, so this is the same, bit for
        // bit, as the pass below.
        let mut far2 = 0.0f64;
        for p in points {
            let d2 = ssv.core_distance_squared(p);
            if d2 > far2 {
                far2 = d2;
            }
            obb.cover_point(p);
        }
        ssv.radius = ssv.radius.max(far2.sqrt());
        return (ssv, obb);
    }

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

/// Up to this many points, `fit_volumes` covers both volumes by the exact computation for every
/// point, without the test that skips the points clearly inside: in a small node most points are
/// on a boundary (about a third of a 40,000-triangle build's points take the exact computation,
/// nearly all of them in small nodes), so the test rarely saves work and its branch is
/// unpredictable. 16 gave the fewest instructions of the sizes tried.
const SMALL_COVER: usize = 16;

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

#[cfg(test)]
mod tests {
    use super::super::principal_axes::principal_axes;
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
                let (ssv, obb) = fit_volumes(volume, &axes, pts, scale, &mut local);
                assert_eq!(ssv, Ssv::fit(kind, &axes, pts), "case {case} {kind:?}");
                assert_eq!(obb, Obb::fit(&axes, pts), "case {case}");
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

    /// A bumpy closed mesh of `2 * lat * lon` triangles (shared vertices, as a mesh has them).
    fn bumpy_sphere(lat: usize, lon: usize) -> Vec<(Tri, i32)> {
        let point = |i: usize, j: usize| {
            let th = std::f64::consts::PI * i as f64 / lat as f64;
            let ph = 2.0 * std::f64::consts::PI * (j % lon) as f64 / lon as f64;
            let r = 1.0 + 0.1 * (5.0 * th).sin() * (7.0 * ph).cos();
            Vec3::new(
                r * th.sin() * ph.cos(),
                r * th.sin() * ph.sin(),
                r * th.cos(),
            )
        };
        let mut tris = Vec::new();
        for i in 0..lat {
            for j in 0..lon {
                let (a, b, c, d) = (
                    point(i, j),
                    point(i + 1, j),
                    point(i + 1, j + 1),
                    point(i, j + 1),
                );
                let id = tris.len() as i32;
                tris.push(([a, b, c], id));
                tris.push(([a, c, d], id + 1));
            }
        }
        tris
    }

    /// Every array of the two hierarchies equal, bit for bit.
    fn assert_same(a: &Bvh, b: &Bvh, what: &str) {
        assert_eq!(a.nodes.len(), b.nodes.len(), "{what}");
        for i in 0..a.nodes.len() {
            let r = NodeRef::inner(i);
            assert_eq!(a.ssv(r), b.ssv(r), "{what}: node {i}");
            assert_eq!(a.obb(r), b.obb(r), "{what}: node {i}");
            assert_eq!(a.children(r), b.children(r), "{what}: node {i}");
        }
        assert_eq!(a.verts, b.verts, "{what}");
        assert_eq!(a.faces, b.faces, "{what}");
        assert_eq!(a.ids, b.ids, "{what}");
        assert_eq!(a.added, b.added, "{what}");
        // What `assemble` derives from the arrays (on several threads, scanned by `fill_on`).
        assert_eq!(a.scale, b.scale, "{what}");
        assert_eq!(a.tiny, b.tiny, "{what}");
        assert_eq!(a.distinct.get(), b.distinct.get(), "{what}");
    }

    #[test]
    fn threads_scan_the_arrays_as_one_thread() {
        // A mesh big enough for several threads, as built, then with one triangle tiny (every
        // coordinate below RESCALE_LO) far from the first run of leaves, and a negative zero.
        // (Adding zero turns the sphere's negative zeros into zeros.)
        let mesh: Vec<(Tri, i32)> = bumpy_sphere(60, 150)
            .into_iter()
            .map(|(t, id)| (t.map(|p| p + Vec3::zeros()), id))
            .collect();
        assert!(mesh.len() > 4 * GRAIN);
        let mut odd = mesh.clone();
        let tiny = Vec3::new(1e-160, 2e-160, 0.0);
        odd[mesh.len() - 5].0 = [tiny, tiny * 2.0, tiny * 3.0];
        odd[mesh.len() / 3].0[1].x = -0.0;
        for (tris, has_odd) in [(&mesh, false), (&odd, true)] {
            let one =
                Bvh::build_threads(tris.clone(), VolumeKind::Rss, CollisionVolume::Obb, 1).unwrap();
            assert_eq!(one.tiny, has_odd);
            assert_eq!(one.distinct.get(), Some(&!has_odd));
            for threads in [2, 3, 5] {
                let many = Bvh::build_threads(
                    tris.clone(),
                    VolumeKind::Rss,
                    CollisionVolume::Obb,
                    threads,
                )
                .unwrap();
                assert_same(&one, &many, &format!("{has_odd}, {threads} threads"));
            }
        }
    }

    #[test]
    fn prefaulting_keeps_contents() {
        // Both ways of mapping pages in (the kernel's call, and the writes where it is refused)
        // leave every value as it was, on a whole number of pages and on a ragged end.
        for len in [1, 1000, 3 * 4096 + 7, 1 << 20] {
            let want: Vec<u32> = (0..len as u32)
                .map(|i| i.wrapping_mul(2_654_435_761))
                .collect();
            let mut v = want.clone();
            prefault(&mut v);
            assert_eq!(v, want);
            touch_pages(&mut v);
            assert_eq!(v, want);
            let mut z: Vec<Vec3> = zeroed(len).unwrap();
            touch_pages(&mut z);
            assert!(z.iter().all(|p| *p == Vec3::zeros()));
            prefault(&mut z);
            assert!(z.iter().all(|p| *p == Vec3::zeros()));
        }
    }

    #[test]
    fn threads_build_the_same_hierarchy() {
        // Big enough for several subtrees to be handed over (GRAIN triangles each); every volume
        // kind; and a soup (no shared vertices) with duplicated triangles.
        let mesh = bumpy_sphere(60, 150);
        assert!(mesh.len() > 4 * GRAIN);
        let mut s = Lcg(3);
        let mut soup: Vec<(Tri, i32)> = (0..3 * GRAIN)
            .map(|i| {
                let c = Vec3::new(lcg(&mut s), lcg(&mut s), lcg(&mut s)) * 20.0;
                let mut v = || c + Vec3::new(lcg(&mut s), lcg(&mut s), lcg(&mut s));
                ([v(), v(), v()], i as i32)
            })
            .collect();
        soup.extend_from_within(..GRAIN);
        for (tris, volumes) in [
            (
                &mesh,
                &[
                    VolumeKind::Rss,
                    VolumeKind::Pss,
                    VolumeKind::Lss,
                    VolumeKind::Hybrid,
                ][..],
            ),
            (&soup, &[VolumeKind::Rss][..]),
        ] {
            for &v in volumes {
                let one = Bvh::build_threads(tris.clone(), v, CollisionVolume::Obb, 1).unwrap();
                for threads in [2, 3, 8] {
                    let many =
                        Bvh::build_threads(tris.clone(), v, CollisionVolume::Obb, threads).unwrap();
                    assert_same(&one, &many, &format!("{v:?}, {threads} threads"));
                }
                if v == VolumeKind::Rss {
                    check_containment(&one);
                    check_insertion_order(&one, tris);
                }
            }
        }
    }

    #[test]
    fn nodes_are_in_pre_order() {
        // Each node's first child follows it, and its second child follows the first's subtree;
        // on a mean split the first child has at least as many triangles as the second.
        let b = Bvh::build(bumpy_sphere(10, 20), VolumeKind::Rss, CollisionVolume::Obb).unwrap();
        fn count(b: &Bvh, r: NodeRef) -> usize {
            if r.is_leaf() {
                1
            } else {
                b.children(r).iter().map(|&c| count(b, c)).sum()
            }
        }
        fn walk(b: &Bvh, r: NodeRef, next: &mut usize) {
            if r.is_leaf() {
                return;
            }
            assert_eq!(r, NodeRef::inner(*next));
            *next += 1;
            let [c0, c1] = b.children(r);
            assert!(count(b, c0) >= count(b, c1));
            walk(b, c0, next);
            walk(b, c1, next);
        }
        let mut next = 0;
        walk(&b, b.root(), &mut next);
        assert_eq!(next, b.num_inner());
    }

    #[test]
    fn zeroed_nodes_are_zero() {
        assert!(zeroed::<Node>(0).unwrap().is_empty());
        let nodes: Vec<Node> = zeroed(5).unwrap();
        assert_eq!(nodes.len(), 5);
        for n in &nodes {
            assert_eq!(n.children, [NodeRef::inner(0); 2]);
            assert_eq!(n.ssv_size().to_bits(), 0);
        }
        let boxes: Vec<NodeBox> = zeroed(5).unwrap();
        let zero = Obb {
            axes: Mat3::zeros(),
            center: Vec3::zeros(),
            half: Vec3::zeros(),
        };
        assert!(boxes.iter().all(|b| *b == NodeBox::new(&zero)));
    }

    /// `count` points uniform in the cube [-0.5, 0.5)^3.
    fn points(s: &mut Lcg, count: usize) -> Vec<Vec3> {
        (0..count)
            .map(|_| Vec3::new(lcg(s), lcg(s), lcg(s)))
            .collect()
    }

    #[test]
    fn leaf_order_runs_match_one_pass() {
        // Cut into runs on any number of threads, the leaf-order arrays and the nodes' largest
        // scale are those of the one pass: on records with vertices repeated within and across
        // runs, and some vertices unused.
        let mut s = Lcg(9);
        let in_verts = points(&mut s, 40);
        let n = 37;
        let recs: Vec<Record> = (0..n)
            .map(|k| Record {
                face: [0, 1, 2].map(|_| (s.unit() * 30.0) as u32),
                added: ((k * 11) % n) as u32,
            })
            .collect();
        let given_ids: Vec<i32> = (0..n as i32).map(|i| 1000 - 7 * i).collect();
        let nodes = Bvh::build(bumpy_sphere(3, 5), VolumeKind::Rss, CollisionVolume::Obb)
            .unwrap()
            .nodes;
        let fill = |threads: usize| {
            let (mut i, mut a, mut f) = (vec![0; n], vec![0; n], vec![[0; 3]; n]);
            let mut v = vec![Vec3::zeros(); in_verts.len()];
            let out = LeafOrder {
                ids: &mut i,
                added: &mut a,
                faces: &mut f,
                verts: &mut v,
            };
            let (scale, scans) = out
                .fill_on(threads, &recs, &given_ids, &in_verts, &nodes)
                .unwrap();
            ((i, a, f, v, scale), scans)
        };
        let (one, none) = fill(1);
        assert!(one.3.len() <= 30 && one.4 > 0.0 && none.is_none());
        // On several threads the scans of what `assemble` reads come along, as of all of it.
        let want = Scans::of(&one.3, &one.2, &one.3);
        for threads in 2..6 {
            assert_eq!(
                fill(threads),
                (one.clone(), Some(want)),
                "{threads} threads"
            );
        }
    }

    #[test]
    fn threads_share_vertices_the_same() {
        // Cut into runs on any number of threads, vertex sharing numbers the vertices as the one
        // pass does: equal bits once (a negative zero apart), in the order they first appear.
        let mut s = Lcg(4);
        let pool = points(&mut s, 25);
        let mut tris: Vec<Tri> = (0..60)
            .map(|_| [0, 1, 2].map(|_| pool[(s.unit() * 25.0) as usize]))
            .collect();
        tris[7][1] = Vec3::new(-0.0, 0.0, 0.0);
        tris[9][2] = Vec3::zeros();
        let one = share_vertices(&tris).unwrap();
        let bits = |v: &Vec3| [v.x, v.y, v.z].map(f64::to_bits);
        let mut seen = 0;
        for (t, f) in one.1.iter().enumerate() {
            for k in 0..3 {
                let v = f[k] as usize;
                assert_eq!(bits(&one.0[v]), bits(&tris[t][k]), "triangle {t}");
                // Numbered as first met.
                assert!(v <= seen);
                seen = seen.max(v + 1);
            }
        }
        assert_eq!(seen, one.0.len());
        let mut distinct: Vec<_> = one.0.iter().map(bits).collect();
        distinct.sort_unstable();
        distinct.dedup();
        assert_eq!(distinct.len(), one.0.len());
        for threads in 2..6 {
            let corners = tris.as_flattened();
            let many = share_corners(tris.len(), |c| &corners[c], threads).unwrap();
            assert_eq!(many, one, "{threads} threads");
        }
    }

    #[test]
    fn vertices_are_shared_in_leaf_order() {
        // The build's vertex arrays are `share_vertices` of its triangles in leaf order.
        let tris = bumpy_sphere(12, 30);
        let b = Bvh::build(tris, VolumeKind::Rss, CollisionVolume::Obb).unwrap();
        let leaf: Vec<Tri> = (0..b.num_tris()).map(|t| b.tri(t)).collect();
        let (verts, faces) = share_vertices(&leaf).unwrap();
        assert_eq!(verts, b.verts);
        assert_eq!(faces, b.faces);
    }
}
