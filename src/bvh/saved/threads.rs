//! Reading a saved hierarchy: the header, then every section read, checked record by record and
//! summed in one pass (on two threads for a large model, in shares of every section whose checks
//! and checksums are joined afterwards: the same checks, the same verdict), then the checks of the
//! whole (`validate.rs`).

use super::super::build_threads::run_tasks;
use super::super::memory::with_room;
use super::super::{Bvh, Node, NodeBox, NodeRef, VolumeKind};
use super::Version;
use super::checksum::{Piece, Running};
use super::codec::{
    HEADER, MAGIC, NODE, TRAILER, VERTEX, collision_from, f64_at, read_node, section_sizes, u32_at,
    u64_at, volume_from,
};
use super::validate::{Spans, check_tree, check_volumes};
use crate::error::{Error, MAX_COORDINATE};
use crate::geometry::RESCALE_LO;
use crate::math::Vec3;
use std::mem::MaybeUninit;
use std::sync::OnceLock;

impl Bvh {
    /// [`load`](Bvh::load), on two threads from `two_from` triangles.
    pub(super) fn load_with(bytes: &[u8], two_from: usize) -> Result<(Bvh, VolumeKind), Error> {
        let bad = Error::InvalidData;
        if bytes.len() < HEADER + TRAILER || bytes[..8] != MAGIC {
            return Err(bad);
        }
        let version = Version::from_code(u32_at(bytes, 8)).ok_or(bad)?;
        if u64_at(bytes, 32) != bytes.len() as u64 {
            return Err(bad);
        }
        let volume = volume_from(u32_at(bytes, 12)).ok_or(bad)?;
        let collision = collision_from(u32_at(bytes, 16)).ok_or(bad)?;
        let (n, v) = (u32_at(bytes, 20), u32_at(bytes, 24));
        // A triangle has three vertices, and slots are NodeRef leaves (below 2^31).
        if n == 0 || n > i32::MAX as u32 || v == 0 || u64::from(v) > 3 * u64::from(n) {
            return Err(bad);
        }
        if u32_at(bytes, 28) != 0 {
            return Err(bad);
        }
        let sizes = section_sizes(u64::from(n), u64::from(v)).ok_or(bad)?;
        let expected = sizes
            .iter()
            .try_fold((HEADER + TRAILER) as u64, |s, &x| s.checked_add(x))
            .ok_or(bad)?;
        if expected != bytes.len() as u64 {
            return Err(bad);
        }
        // Every section now fits: the counts are bounded by the buffer's length, and so is every
        // allocation below.
        let (body, trailer) = bytes.split_at(bytes.len() - TRAILER);
        let mut rest = &body[HEADER..];
        let mut section = |size: u64| {
            let (s, r) = rest.split_at(size as usize);
            rest = r;
            s
        };
        let [node_bytes, vert_bytes, face_bytes, id_bytes, added_bytes] = sizes.map(&mut section);
        let (tris, inner, verts_len) = (n as usize, n as usize - 1, v as usize);
        let mut nodes = with_room(inner)?;
        let mut boxes = with_room(inner)?;
        let mut children = with_room(inner)?;
        let mut verts = with_room(verts_len)?;
        let mut faces = with_room(tris)?;
        let mut ids = with_room(tris)?;
        let mut added = with_room(tris)?;
        // The shares: each a run of 1/k of every section, in buffer order (one share for a
        // small model).
        let k = if tris >= two_from { SHARES } else { 1 };
        let bounds = |len: usize| move |i: usize| len * i / k;
        let (bn, bv, bt) = (bounds(inner), bounds(verts_len), bounds(tris));
        let mut to_nodes = pieces(&mut nodes, inner, k).into_iter();
        let mut to_boxes = pieces(&mut boxes, inner, k).into_iter();
        let mut to_children = pieces(&mut children, inner, k).into_iter();
        let mut to_verts = pieces(&mut verts, verts_len, k).into_iter();
        let mut to_faces = pieces(&mut faces, tris, k).into_iter();
        let mut to_ids = pieces(&mut ids, tris, k).into_iter();
        let mut to_added = pieces(&mut added, tris, k).into_iter();
        let mut shares = Vec::new();
        shares
            .try_reserve_exact(k)
            .map_err(|_| Error::ModelOutOfMemory)?;
        for i in 0..k {
            let (n0, n1, v0, v1, t0, t1) = (bn(i), bn(i + 1), bv(i), bv(i + 1), bt(i), bt(i + 1));
            shares.push(Share {
                nodes: &node_bytes[n0 * NODE..n1 * NODE],
                verts: &vert_bytes[v0 * VERTEX..v1 * VERTEX],
                faces: &face_bytes[t0 * 12..t1 * 12],
                ids: &id_bytes[t0 * 4..t1 * 4],
                added: &added_bytes[t0 * 4..t1 * 4],
                to_nodes: to_nodes.next().ok_or(Error::Internal)?,
                to_boxes: to_boxes.next().ok_or(Error::Internal)?,
                to_children: to_children.next().ok_or(Error::Internal)?,
                to_verts: to_verts.next().ok_or(Error::Internal)?,
                to_faces: to_faces.next().ok_or(Error::Internal)?,
                to_ids: to_ids.next().ok_or(Error::Internal)?,
                to_added: to_added.next().ok_or(Error::Internal)?,
            });
        }
        let read = |_: &mut (), s: Share<'_>| read_share(s, volume, v, n, version);
        let mut found = if k > 1 {
            // This thread and a started one take the shares in turn as they finish one, so
            // neither waits long for the other (nor for a thread the system is slow to run, or
            // does not start: this one then reads them all). Each first touches the memory it
            // writes, so the kernel's page zeroing is shared between the cores too.
            run_tasks(2, shares, read, || Ok(()))?
        } else {
            shares
                .into_iter()
                .map(|s| read(&mut (), s))
                .collect::<Result<Vec<_>, _>>()?
        };
        // The checksum, the pieces joined in the buffer's order.
        let mut sum = Running::new(version);
        sum.update(&body[..HEADER]);
        let mut sums = sum.piece();
        for k in 0..5 {
            for f in &found {
                sums = sums.then(f.sums[k]);
            }
        }
        if sums.finish() != u64_at(trailer, 0) {
            return Err(bad);
        }
        // The faces' numbering across the shares, and every vertex used.
        let mut seen = 0u32;
        for f in &found {
            if f.past > seen {
                return Err(bad);
            }
            seen = seen.max(f.seen);
        }
        if seen != v {
            return Err(bad);
        }
        // The order added: each share's values distinct and below n, and no value in both
        // shares, so n distinct values below n, a permutation.
        // (A share without triangles has no set: the first set met is the start.)
        let mut all: Vec<u64> = Vec::new();
        for f in &mut found {
            if all.is_empty() {
                all = std::mem::take(&mut f.added);
                continue;
            }
            for (a, x) in all.iter_mut().zip(&f.added) {
                if *a & x != 0 {
                    return Err(bad);
                }
                *a |= x;
            }
        }
        // SAFETY: the shares' slots partition the first `len` of each vector's capacity
        // (`halves`), and both shares returned `Ok`, which `read_share` does only after writing
        // every one of its slots.
        unsafe {
            nodes.set_len(inner);
            boxes.set_len(inner);
            children.set_len(inner);
            verts.set_len(verts_len);
            faces.set_len(tris);
            ids.set_len(tris);
            added.set_len(tris);
        }
        check_tree(&children, tris)?;
        drop(children);
        let inner_scale = found.iter().map(|f| f.inner_scale).fold(0.0, f64::max);
        let vertex_scale = found.iter().map(|f| f.vertex_scale).fold(0.0, f64::max);
        // The volumes, in runs of nodes checked on their own (on two threads for a large model).
        let spans = Spans::new(&nodes, &faces)?;
        let runs: Vec<_> = (0..k).map(|i| bn(i)..bn(i + 1)).collect();
        let check = |_: &mut (), r: std::ops::Range<usize>| {
            check_volumes(&nodes, &boxes, &verts, &faces, &spans, vertex_scale, r)
        };
        if k > 1 {
            run_tasks(2, runs, check, || Ok(()))?;
        } else {
            runs.into_iter().try_for_each(|r| check(&mut (), r))?;
        }
        // As `Bvh::scale_bound` and `Bvh::has_tiny` compute them: no triangle is tiny without a
        // tiny vertex (the common case, which needs no pass over the faces).
        let scale = inner_scale.max(5.0 * vertex_scale);
        let tiny = found.iter().any(|f| f.tiny_vertex) && Bvh::has_tiny(&verts, &faces);
        Ok((
            Bvh::assembled(
                nodes,
                boxes,
                verts,
                faces,
                ids,
                added,
                collision,
                scale,
                tiny,
                OnceLock::new(),
            ),
            volume,
        ))
    }
}

/// Fewest triangles for which a load runs on two threads (under it, starting a thread costs about
/// as much as it saves).
pub(super) const TWO_THREADS: usize = 16_384;
/// Shares of a load on two threads: each thread takes the next as it finishes one.
pub(super) const SHARES: usize = 8;
/// Records summed at a time before they are read (while they are in cache).
const PIECE: usize = 256;

/// The first `len` slots of `v`'s capacity in `k` runs, their lengths differing by at most one
/// (as `len * i / k` splits them).
fn pieces<T>(v: &mut Vec<T>, len: usize, k: usize) -> Vec<&mut [MaybeUninit<T>]> {
    let mut rest = &mut v.spare_capacity_mut()[..len];
    let mut out = Vec::with_capacity(k);
    for i in 0..k {
        let (piece, r) = std::mem::take(&mut rest).split_at_mut(len * (i + 1) / k - len * i / k);
        out.push(piece);
        rest = r;
    }
    out
}

/// One thread's share of a load: a run of the records of each section, and the slots they go to
/// (as many as the records).
struct Share<'a> {
    nodes: &'a [u8],
    verts: &'a [u8],
    faces: &'a [u8],
    ids: &'a [u8],
    added: &'a [u8],
    to_nodes: &'a mut [MaybeUninit<Node>],
    to_boxes: &'a mut [MaybeUninit<NodeBox>],
    to_children: &'a mut [MaybeUninit<[NodeRef; 2]>],
    to_verts: &'a mut [MaybeUninit<Vec3>],
    to_faces: &'a mut [MaybeUninit<[u32; 3]>],
    to_ids: &'a mut [MaybeUninit<i32>],
    to_added: &'a mut [MaybeUninit<u32>],
}

/// What a share found, for the checks across shares.
struct Found {
    /// The checksum of its piece of each section.
    sums: [Piece; 5],
    /// The largest scale of its nodes' swept sphere volumes ([`Bvh::inner_scale`]).
    inner_scale: f64,
    /// The largest `|x| + |y| + |z|` of its vertices (as [`Bvh::scale_bound`] folds it).
    vertex_scale: f64,
    /// Some vertex of it has every coordinate below `RESCALE_LO` in magnitude.
    tiny_vertex: bool,
    /// Its faces' vertex indices: one more than the largest (0 if none), and the largest index
    /// that was more than one past the largest before it in the share (0 if none), which the
    /// shares before must have reached.
    seen: u32,
    past: u32,
    /// Its part of the order added as a set of bits (empty without one).
    added: Vec<u64>,
}

/// Reads a share: every record checked on its own (see the file's documentation), written to its
/// slot, and summed; `Ok` only once every slot is written.
fn read_share(
    s: Share<'_>,
    volume: VolumeKind,
    v: u32,
    n: u32,
    version: Version,
) -> Result<Found, Error> {
    let inner = s.to_nodes.len();
    let tris = s.to_faces.len();
    let sized = s.nodes.len() == inner * NODE
        && s.to_boxes.len() == inner
        && s.to_children.len() == inner
        && s.verts.len() == s.to_verts.len() * VERTEX
        && s.faces.len() == tris * 12
        && s.ids.len() == tris * 4
        && s.to_ids.len() == tris
        && s.added.len() == tris * 4
        && s.to_added.len() == tris;
    if !sized {
        return Err(Error::Internal);
    }
    let mut found = Found {
        sums: [Piece::empty(version); 5],
        inner_scale: 0.0,
        vertex_scale: 0.0,
        tiny_vertex: false,
        seen: 0,
        past: 0,
        added: Vec::new(),
    };
    let mut sum = Running::new(version);
    let slots = s
        .to_nodes
        .chunks_mut(PIECE)
        .zip(s.to_boxes.chunks_mut(PIECE));
    let slots = slots.zip(s.to_children.chunks_mut(PIECE));
    for (piece, ((to_n, to_b), to_c)) in s.nodes.chunks(PIECE * NODE).zip(slots) {
        sum.update(piece);
        let slots = to_n.iter_mut().zip(to_b.iter_mut()).zip(to_c.iter_mut());
        for (r, ((to_n, to_b), to_c)) in piece.chunks_exact(NODE).zip(slots) {
            let (node, b) = read_node(r, volume)?;
            // As `Bvh::inner_scale` folds it.
            found.inner_scale = f64::max(found.inner_scale, node.ssv.scale());
            to_c.write(node.children);
            to_n.write(node);
            to_b.write(b);
        }
    }
    found.sums[0] = sum.piece();

    let (mut vertex_scale, mut tiny_vertex) = (0.0, false);
    found.sums[1] = fill(version, s.verts, VERTEX, s.to_verts, |b| {
        let p = Vec3::new(f64_at(b, 0), f64_at(b, 8), f64_at(b, 16));
        // Finite and within range, as `add_triangle` accepts (NaN fails the comparison too).
        if !p.iter().all(|x| x.abs() <= MAX_COORDINATE) {
            return Err(Error::InvalidData);
        }
        vertex_scale = f64::max(vertex_scale, p.abs().sum());
        tiny_vertex |= p.amax() < RESCALE_LO;
        Ok(p)
    })?;
    (found.vertex_scale, found.tiny_vertex) = (vertex_scale, tiny_vertex);

    // The vertices are numbered as they first appear in the faces: each index at most one more
    // than the largest before it (`seen` is that largest plus one), all below `v`. Within a
    // share, the largest index before it is not known: an index more than one past the share's
    // own largest is kept (`past`) for the join to check against the shares before.
    let (mut seen, mut past) = (0u32, 0u32);
    found.sums[2] = fill(version, s.faces, 12, s.to_faces, |b| {
        let f = [u32_at(b, 0), u32_at(b, 4), u32_at(b, 8)];
        for k in f {
            if k >= v {
                return Err(Error::InvalidData);
            }
            past = past.max(if k > seen { k } else { 0 });
            seen = seen.max(k + 1);
        }
        Ok(f)
    })?;
    (found.seen, found.past) = (seen, past);

    found.sums[3] = fill(version, s.ids, 4, s.to_ids, |b| Ok(u32_at(b, 0) as i32))?;

    // The order added: values below `n`, none twice in the share.
    if !s.added.is_empty() {
        let words = (n as usize).div_ceil(64);
        let mut bits: Vec<u64> = with_room(words)?;
        bits.resize(words, 0);
        found.sums[4] = fill(version, s.added, 4, s.to_added, |b| {
            let k = u32_at(b, 0);
            if k >= n {
                return Err(Error::InvalidData);
            }
            let (word, bit) = ((k / 64) as usize, 1u64 << (k % 64));
            if bits[word] & bit != 0 {
                return Err(Error::InvalidData);
            }
            bits[word] |= bit;
            Ok(k)
        })?;
        found.added = bits;
    }
    Ok(found)
}

/// Writes `read` of each `size`-byte record of `section` to the slot of the same rank in `out`
/// (as many), summing each piece of [`PIECE`] records just before reading it (while it is in
/// cache); the sums of the section, or the first error.
fn fill<T>(
    version: Version,
    section: &[u8],
    size: usize,
    out: &mut [MaybeUninit<T>],
    mut read: impl FnMut(&[u8]) -> Result<T, Error>,
) -> Result<Piece, Error> {
    let mut sum = Running::new(version);
    for (piece, slots) in section.chunks(PIECE * size).zip(out.chunks_mut(PIECE)) {
        sum.update(piece);
        for (r, slot) in piece.chunks_exact(size).zip(slots) {
            slot.write(read(r)?);
        }
    }
    Ok(sum.piece())
}
