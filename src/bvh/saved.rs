//! Saved hierarchies: a built hierarchy as bytes and back (the layout is documented in
//! `docs/saved-model-format.md`; this file and that one change together).
//!
//! Every value is written with an explicit little-endian conversion, so the bytes are the same on
//! every machine; nothing is written or read by reinterpreting memory. Reading trusts nothing: the
//! size, the checksum (Fletcher-64) and then every value are checked, in O(n), before a hierarchy
//! is made, so that no buffer, truncated, corrupted or crafted, gives a hierarchy a query could
//! misuse: indices in range, a tree whose leaves are the triangles in slot order (each node
//! reached once from the root), depth within [`MAX_DEPTH`] (the queries' fixed stacks), finite
//! coordinates within range, consistent counts. Derived values (`scale`, `tiny`, each node's
//! volume size) are not stored but recomputed, bit for bit as the build computed them. A model of
//! [`TWO_THREADS`] triangles or more is read on two threads, in shares of every section whose
//! checks and checksum sums are joined afterwards (the same checks, the same verdict).
//!
//! What reading does not check is that each volume encloses its triangles: that costs as much as a
//! build, which loading exists to avoid. The checksum catches accidental damage; a buffer crafted
//! with wrong volumes and a matching checksum gives a model that is memory-safe and whose queries
//! end, but whose answers may be wrong.

use super::build_threads::run_tasks;
use super::{Bvh, CollisionVolume, MAX_DEPTH, Node, NodeBox, NodeKind, NodeRef, VolumeKind};
use crate::bounding_volume::{BoundingVolume, CompactSsv};
use crate::error::{Error, MAX_COORDINATE};
use crate::geometry::RESCALE_LO;
use crate::math::Vec3;
use std::mem::MaybeUninit;
use std::sync::OnceLock;

/// The first eight bytes of every saved model.
const MAGIC: [u8; 8] = *b"PQPMODEL";
/// The layout's version: readers refuse others.
const VERSION: u32 = 1;
/// Bytes of the header: magic, version, volume kind, collision volume, triangle count, vertex
/// count, a reserved zero word and the total size.
const HEADER: usize = 40;
/// Bytes of an inner node: 18 doubles (two axes, the swept sphere volume's origin, two lengths and
/// radius, the box's centre and half extents) and its two children.
const NODE: usize = 18 * 8 + 2 * 4;
/// Bytes of a vertex.
const VERTEX: usize = 3 * 8;
/// Bytes per triangle: three vertex indices, the id and the position in the order added.
const TRIANGLE: usize = 3 * 4 + 4 + 4;
/// Bytes of the checksum that ends the buffer.
const TRAILER: usize = 8;

/// Largest magnitude of a stored node value (16 times the largest coordinate: a built node's
/// origin, extents and radius stay within a few times its largest vertex coordinate). It keeps
/// squares and products of the values the queries form finite.
const MAX_NODE_VALUE: f64 = 16.0 * MAX_COORDINATE;

/// How far from orthonormal a stored frame may be (built frames are within a few ulps).
const FRAME_TOLERANCE: f64 = 1e-6;

/// The checksum of the layout: Fletcher-64 of `bytes` read as little-endian 32-bit words (a partial
/// last word is padded with zeros; the layout's lengths are multiples of 4): two sums modulo
/// 2^32 - 1 from 0, `a` of the words and `b` of the successive `a`, given as `b * 2^32 + a`.
/// Any change of one word (but 0 <-> 0xffffffff), so of any one byte, and any swap of two
/// different words, changes it; it runs at memory speed (a CRC or FNV-1a over bytes is 7-15x
/// slower, which loading would feel).
pub(crate) fn fletcher64(bytes: &[u8]) -> u64 {
    let mut sum = Fletcher64::default();
    sum.update(bytes);
    sum.finish()
}

/// [`fletcher64`] taken piece by piece, so that a load sums each piece of the buffer while it
/// reads it (one pass over the buffer, not two).
#[derive(Default)]
pub(crate) struct Fletcher64 {
    a: u64,
    b: u64,
    /// Words added since the sums were last reduced.
    words: usize,
    /// Words added in all.
    total: u64,
}

/// The two sums of [`fletcher64`] over one piece of a buffer (reduced), and the piece's length in
/// words: pieces summed apart (on two threads) are joined by [`Sums::then`] into the sums of the
/// whole.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Sums {
    a: u64,
    b: u64,
    words: u64,
}

impl Sums {
    /// The sums of this piece followed by `next`, exactly as if summed in one go. Over `next`'s
    /// `m` words, `a` grows by their sum (`next.a`), and `b`, which adds the running `a` after
    /// each word, by `next.b` plus `m` times the `a` it started from.
    pub(crate) fn then(self, next: Sums) -> Sums {
        let m = Fletcher64::MODULUS;
        // Each term is below 2^32 - 1, the product below 2^64.
        let carried = (next.words % m) * self.a % m;
        Sums {
            a: (self.a + next.a) % m,
            b: (self.b + next.b + carried) % m,
            words: self.words + next.words,
        }
    }

    /// The checksum ([`Fletcher64::finish`]).
    pub(crate) fn finish(self) -> u64 {
        (self.b << 32) | self.a
    }
}

impl Fletcher64 {
    const MODULUS: u64 = 0xffff_ffff;
    /// Words between reductions: `b` stays below 2^64 (it grows by at most `a`, itself below 2^32
    /// times this, per word).
    const BLOCK: usize = 1 << 13;

    /// Adds `bytes`: a multiple of 4 long, except in the last piece (its tail is padded).
    pub(crate) fn update(&mut self, bytes: &[u8]) {
        let (mut a, mut b) = (self.a, self.b);
        let mut rest = bytes;
        while !rest.is_empty() {
            let whole = (rest.len() / 4).min(Self::BLOCK - self.words);
            let (head, tail) = rest.split_at(4 * whole);
            // Eight words at a time: after words w0..w7, `a` has grown by their sum and `b` by
            // eight times the old `a` plus 8 w0 + 7 w1 + ... + 1 w7 (independent sums the
            // compiler vectorises).
            let octets = head.chunks_exact(32);
            let single = octets.remainder();
            for o in octets {
                // 1 KiB ahead (the processor's stream prefetch alone leaves the sum waiting on
                // memory: 27 ms for 184 MB without, 19-20 with); a hint, also past the end.
                crate::math::prefetch_line(o.as_ptr().wrapping_add(1024));
                let (mut s, mut t) = (0u64, 0u64);
                for (k, w) in o.chunks_exact(4).enumerate() {
                    let w = u64::from(u32::from_le_bytes([w[0], w[1], w[2], w[3]]));
                    s += w;
                    t += (8 - k as u64) * w;
                }
                b += 8 * a + t;
                a += s;
            }
            for w in single.chunks_exact(4) {
                a += u64::from(u32::from_le_bytes([w[0], w[1], w[2], w[3]]));
                b += a;
            }
            self.words += whole;
            self.total += whole as u64;
            rest = tail;
            if whole == 0 {
                let mut w = [0u8; 4];
                w[..rest.len()].copy_from_slice(rest);
                a += u64::from(u32::from_le_bytes(w));
                b += a;
                self.words += 1;
                self.total += 1;
                rest = &[];
            }
            if self.words == Self::BLOCK {
                (a, b, self.words) = (a % Self::MODULUS, b % Self::MODULUS, 0);
            }
        }
        (self.a, self.b) = (a, b);
    }

    /// The checksum of everything added.
    pub(crate) fn finish(&self) -> u64 {
        self.sums().finish()
    }

    /// The sums of everything added, to join with others' ([`Sums::then`]).
    pub(crate) fn sums(&self) -> Sums {
        Sums {
            a: self.a % Self::MODULUS,
            b: self.b % Self::MODULUS,
            words: self.total,
        }
    }
}

/// The codes of the volume choices in the header (PQP_BV_* and PQP_COLLIDE_* of the C ABI).
fn volume_code(v: VolumeKind) -> u32 {
    match v {
        VolumeKind::Rss => 0,
        VolumeKind::Pss => 1,
        VolumeKind::Lss => 2,
        VolumeKind::Hybrid => 3,
    }
}

fn volume_from(code: u32) -> Option<VolumeKind> {
    Some(match code {
        0 => VolumeKind::Rss,
        1 => VolumeKind::Pss,
        2 => VolumeKind::Lss,
        3 => VolumeKind::Hybrid,
        _ => return None,
    })
}

fn collision_code(c: CollisionVolume) -> u32 {
    match c {
        CollisionVolume::Obb => 0,
        CollisionVolume::Ssv => 1,
    }
}

fn collision_from(code: u32) -> Option<CollisionVolume> {
    Some(match code {
        0 => CollisionVolume::Obb,
        1 => CollisionVolume::Ssv,
        _ => return None,
    })
}

/// Little-endian reads at a byte offset of a slice long enough (the callers' sections are sized
/// from the header before any read).
fn u32_at(b: &[u8], at: usize) -> u32 {
    let mut w = [0u8; 4];
    w.copy_from_slice(&b[at..at + 4]);
    u32::from_le_bytes(w)
}

fn u64_at(b: &[u8], at: usize) -> u64 {
    let mut w = [0u8; 8];
    w.copy_from_slice(&b[at..at + 8]);
    u64::from_le_bytes(w)
}

fn f64_at(b: &[u8], at: usize) -> f64 {
    f64::from_bits(u64_at(b, at))
}

/// Writes `values` as consecutive little-endian words from the start of `out`.
fn put_f64s(out: &mut [u8], values: &[f64]) {
    for (o, v) in out.chunks_exact_mut(8).zip(values) {
        o.copy_from_slice(&v.to_le_bytes());
    }
}

fn put_u32s(out: &mut [u8], values: &[u32]) {
    for (o, v) in out.chunks_exact_mut(4).zip(values) {
        o.copy_from_slice(&v.to_le_bytes());
    }
}

/// An empty vector with room for `n`, or `Err(ModelOutOfMemory)`. A large one is offered huge
/// pages (see [`advise_huge_pages`]): a load, and the build (`build.rs`), write every byte of
/// their arrays once, into fresh memory.
pub(super) fn with_room<T>(n: usize) -> Result<Vec<T>, Error> {
    let mut v: Vec<T> = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|_| Error::ModelOutOfMemory)?;
    advise_huge_pages(v.as_mut_ptr().cast(), n * std::mem::size_of::<T>());
    Ok(v)
}

#[cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
))]
unsafe extern "C" {
    /// libc's `int madvise(void *addr, size_t length, int advice)`.
    fn madvise(
        addr: *mut std::ffi::c_void,
        length: usize,
        advice: std::ffi::c_int,
    ) -> std::ffi::c_int;
}

/// Asks Linux to back the whole 2 MiB pages of `len` bytes at `start`, freshly allocated and not
/// yet touched, with huge pages (`madvise(MADV_HUGEPAGE)`; transparent huge pages on request are
/// the default setting). A load writes every byte of the model once: with 4 KiB pages most of its
/// time goes to the kernel's page faults (measured: 184 MB copied into fresh memory in 125-190 ms,
/// 35 ms with huge pages). Advice only: contents and ownership do not change, and where it is
/// refused (huge pages off) or not built (other systems, Miri) nothing changes but the speed.
#[cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
))]
pub(super) fn advise_huge_pages(start: *mut u8, len: usize) {
    const HUGE: usize = 1 << 21;
    // MADV_HUGEPAGE on these targets (asm-generic/mman-common.h).
    const MADV_HUGEPAGE: std::ffi::c_int = 14;
    if len < 2 * HUGE {
        return;
    }
    let first = (start as usize).next_multiple_of(HUGE);
    let end = (start as usize + len) & !(HUGE - 1);
    if end > first {
        // SAFETY: [first, end) lies inside the allocation of `len` bytes at `start`, which the
        // caller owns; the advice changes neither its contents nor its mapping's validity. A
        // failure (huge pages disabled) is ignored: it only means no speed-up.
        unsafe { madvise(first as *mut std::ffi::c_void, end - first, MADV_HUGEPAGE) };
    }
}

#[cfg(not(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
)))]
pub(super) fn advise_huge_pages(_start: *mut u8, _len: usize) {}

/// Asks Linux to map in, writable, the 4 KiB pages wholly inside the `len` bytes at `start` (part
/// of an allocation), as the first write to each would (`madvise(MADV_POPULATE_WRITE)`, Linux 5.14
/// on), without reading or writing any byte: the contents do not change, and another thread may
/// be using the memory meanwhile. Whether the call succeeded: false if refused (an older kernel)
/// or not built (other systems, Miri).
#[cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
))]
pub(super) fn populate_pages(start: *mut u8, len: usize) -> bool {
    const PAGE: usize = 1 << 12;
    // MADV_POPULATE_WRITE (asm-generic/mman-common.h).
    const MADV_POPULATE_WRITE: std::ffi::c_int = 23;
    let first = (start as usize).next_multiple_of(PAGE);
    let end = (start as usize + len) & !(PAGE - 1);
    if end <= first {
        return true;
    }
    // SAFETY: [first, end) lies inside the allocation of `len` bytes at `start`; populating maps
    // in its pages with the contents they already have (zeros for pages never touched) and
    // accesses no byte of them as far as the program can tell.
    unsafe {
        madvise(
            first as *mut std::ffi::c_void,
            end - first,
            MADV_POPULATE_WRITE,
        ) == 0
    }
}

#[cfg(not(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(miri)
)))]
pub(super) fn populate_pages(_start: *mut u8, _len: usize) -> bool {
    false
}

/// The sections of a saved hierarchy of `n` triangles (n >= 1) and `v` vertices, in bytes, in the
/// order they follow the header; `None` if their sum overflows.
fn section_sizes(n: u64, v: u64) -> Option<[u64; 5]> {
    Some([
        (n - 1).checked_mul(NODE as u64)?,
        v.checked_mul(VERTEX as u64)?,
        n.checked_mul(12)?,
        n.checked_mul(4)?,
        n.checked_mul(4)?,
    ])
}

impl Bvh {
    /// Bytes [`save`](Bvh::save) writes.
    pub fn saved_size(&self) -> usize {
        HEADER
            + self.nodes.len() * NODE
            + self.verts.len() * VERTEX
            + self.faces.len() * TRIANGLE
            + TRAILER
    }

    /// Writes the hierarchy, with the model's swept sphere volume kind `volume`, into `out`, which
    /// is exactly [`saved_size`](Bvh::saved_size) bytes long.
    pub fn save(&self, volume: VolumeKind, out: &mut [u8]) {
        let total = self.saved_size();
        debug_assert_eq!(out.len(), total);
        let (header, rest) = out.split_at_mut(HEADER);
        header[..8].copy_from_slice(&MAGIC);
        // Counts fit: at most i32::MAX triangles, and vertices are indexed by u32.
        put_u32s(
            &mut header[8..32],
            &[
                VERSION,
                volume_code(volume),
                collision_code(self.collision),
                self.faces.len() as u32,
                self.verts.len() as u32,
                0,
            ],
        );
        header[32..40].copy_from_slice(&(total as u64).to_le_bytes());

        let (nodes, rest) = rest.split_at_mut(self.nodes.len() * NODE);
        let nodes_boxes = self.nodes.iter().zip(&self.boxes);
        for ((n, b), out) in nodes_boxes.zip(nodes.chunks_exact_mut(NODE)) {
            let (s, [u, v], c, h) = (&n.ssv, &n.ssv.axes, &b.center, &b.half);
            let o = &s.origin;
            put_f64s(
                out,
                &[
                    u.x,
                    u.y,
                    u.z,
                    v.x,
                    v.y,
                    v.z,
                    o.x,
                    o.y,
                    o.z,
                    s.lengths[0],
                    s.lengths[1],
                    s.radius,
                    c.x,
                    c.y,
                    c.z,
                    h.x,
                    h.y,
                    h.z,
                ],
            );
            let [c0, c1] = n.children;
            put_u32s(&mut out[144..], &[c0.0 as u32, c1.0 as u32]);
        }
        let (verts, rest) = rest.split_at_mut(self.verts.len() * VERTEX);
        for (p, out) in self.verts.iter().zip(verts.chunks_exact_mut(VERTEX)) {
            put_f64s(out, &[p.x, p.y, p.z]);
        }
        let n = self.faces.len();
        let (faces, rest) = rest.split_at_mut(12 * n);
        put_u32s(faces, self.faces.as_flattened());
        let (ids, rest) = rest.split_at_mut(4 * n);
        for (id, out) in self.ids.iter().zip(ids.chunks_exact_mut(4)) {
            out.copy_from_slice(&id.to_le_bytes());
        }
        put_u32s(rest, &self.added);

        let (body, trailer) = out.split_at_mut(total - TRAILER);
        trailer.copy_from_slice(&fletcher64(body).to_le_bytes());
    }

    /// Reads a hierarchy [`save`](Bvh::save) wrote, with the model's swept sphere volume kind.
    ///
    /// `Err(InvalidData)` for anything else (see the file's documentation for what is checked);
    /// `Err(ModelOutOfMemory)` if its storage could not be allocated. Allocations are sized from
    /// counts already checked against the length of `bytes`.
    pub fn load(bytes: &[u8]) -> Result<(Bvh, VolumeKind), Error> {
        Bvh::load_with(bytes, TWO_THREADS)
    }

    /// [`load`](Bvh::load), on two threads from `two_from` triangles.
    fn load_with(bytes: &[u8], two_from: usize) -> Result<(Bvh, VolumeKind), Error> {
        let bad = Error::InvalidData;
        if bytes.len() < HEADER + TRAILER || bytes[..8] != MAGIC || u32_at(bytes, 8) != VERSION {
            return Err(bad);
        }
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
        let read = |_: &mut (), s: Share<'_>| read_share(s, volume, v, n);
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
        let mut sum = Fletcher64::default();
        sum.update(&body[..HEADER]);
        let mut sums = sum.sums();
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
const TWO_THREADS: usize = 16_384;
/// Shares of a load on two threads: each thread takes the next as it finishes one.
const SHARES: usize = 8;
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
#[derive(Default)]
struct Found {
    /// The checksum's sums of its piece of each section.
    sums: [Sums; 5],
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
fn read_share(s: Share<'_>, volume: VolumeKind, v: u32, n: u32) -> Result<Found, Error> {
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
    let mut found = Found::default();
    let mut sum = Fletcher64::default();
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
    found.sums[0] = sum.sums();

    let (mut vertex_scale, mut tiny_vertex) = (0.0, false);
    found.sums[1] = fill(s.verts, VERTEX, s.to_verts, |b| {
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
    found.sums[2] = fill(s.faces, 12, s.to_faces, |b| {
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

    found.sums[3] = fill(s.ids, 4, s.to_ids, |b| Ok(u32_at(b, 0) as i32))?;

    // The order added: values below `n`, none twice in the share.
    if !s.added.is_empty() {
        let words = (n as usize).div_ceil(64);
        let mut bits: Vec<u64> = with_room(words)?;
        bits.resize(words, 0);
        found.sums[4] = fill(s.added, 4, s.to_added, |b| {
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
    section: &[u8],
    size: usize,
    out: &mut [MaybeUninit<T>],
    mut read: impl FnMut(&[u8]) -> Result<T, Error>,
) -> Result<Sums, Error> {
    let mut sum = Fletcher64::default();
    for (piece, slots) in section.chunks(PIECE * size).zip(out.chunks_mut(PIECE)) {
        sum.update(piece);
        for (r, slot) in piece.chunks_exact(size).zip(slots) {
            slot.write(read(r)?);
        }
    }
    Ok(sum.sums())
}

/// An inner node and its box, checked on its own: values finite and within [`MAX_NODE_VALUE`],
/// lengths, radius and half extents not negative, lengths as the model's volume kind allows, axes
/// orthonormal. Its children are checked by [`check_tree`].
fn read_node(b: &[u8], volume: VolumeKind) -> Result<(Node, NodeBox), Error> {
    let mut f = [0.0f64; 18];
    for (x, w) in f.iter_mut().zip(b.chunks_exact(8)) {
        *x = f64_at(w, 0);
    }
    // NaN fails the comparison too.
    if !f.iter().all(|x| x.abs() <= MAX_NODE_VALUE) {
        return Err(Error::InvalidData);
    }
    let vec = |k: usize| Vec3::new(f[k], f[k + 1], f[k + 2]);
    let ssv = CompactSsv {
        axes: [vec(0), vec(3)],
        origin: vec(6),
        lengths: [f[9], f[10]],
        radius: f[11],
    };
    let (center, half) = (vec(12), vec(15));
    let [u, v] = ssv.axes;
    let near = |x: f64, want: f64| (x - want).abs() <= FRAME_TOLERANCE;
    let allowed_lengths = match volume {
        VolumeKind::Pss => ssv.lengths == [0.0, 0.0],
        VolumeKind::Lss => ssv.lengths[1] == 0.0,
        VolumeKind::Rss | VolumeKind::Hybrid => true,
    };
    let valid = near(u.norm_squared(), 1.0)
        && near(v.norm_squared(), 1.0)
        && near(u.dot(&v), 0.0)
        && ssv.lengths[0] >= 0.0
        && ssv.lengths[1] >= 0.0
        && ssv.radius >= 0.0
        && half.iter().all(|&h| h >= 0.0)
        && allowed_lengths;
    if !valid {
        return Err(Error::InvalidData);
    }
    let children = [
        NodeRef(u32_at(b, 144) as i32),
        NodeRef(u32_at(b, 148) as i32),
    ];
    Ok((
        Node {
            ssv_size: ssv.full().size(),
            ssv,
            children,
        },
        NodeBox { center, half },
    ))
}

/// Checks that the inner nodes' `children` make the tree a build makes over `n` triangles (`n - 1`
/// inner nodes):
/// depth-first from the root, first child first, the leaves come in slot order `0, 1, ..., n - 1`,
/// every inner child is in range, no more than `n - 1` inner nodes are visited, and no leaf is
/// deeper than [`MAX_DEPTH`] (counting the root as 1), and every inner child comes after its
/// parent in the array (refit relies on it). Since every inner node has two children,
/// `n` leaves each met once make it a tree with each node reached exactly once (a node reached
/// twice would show its leaves twice). O(n), and ends early on the first fault, so a crafted
/// graph (cycles, shared nodes) costs no more.
fn check_tree(children: &[[NodeRef; 2]], n: usize) -> Result<(), Error> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::{Random, Rng};

    /// Fletcher-64 from its definition, one word at a time with the modulus taken at every step.
    fn fletcher64_by_definition(bytes: &[u8]) -> u64 {
        let m = 0xffff_ffffu64;
        let (mut a, mut b) = (0u64, 0u64);
        for w in bytes.chunks(4) {
            let mut x = [0u8; 4];
            x[..w.len()].copy_from_slice(w);
            a = (a + u64::from(u32::from_le_bytes(x))) % m;
            b = (b + a) % m;
        }
        (b << 32) | a
    }

    #[test]
    fn fletcher64_matches_its_definition() {
        let mut rng = Rng::new(7);
        // Lengths around the reduction block, and words at the extremes (0xffffffff sums).
        for len in [
            0,
            1,
            3,
            4,
            5,
            8,
            100,
            4 << 13,
            (4 << 13) + 4,
            (12 << 13) + 3,
        ] {
            let random: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
            let ones = vec![0xffu8; len];
            for bytes in [random, ones] {
                assert_eq!(
                    fletcher64(&bytes),
                    fletcher64_by_definition(&bytes),
                    "len {len}"
                );
            }
        }
        // Piece by piece, in pieces of any multiple of 4, as a load takes it.
        let bytes: Vec<u8> = (0..(40 << 13) + 8).map(|_| rng.next_u64() as u8).collect();
        let mut sum = Fletcher64::default();
        let mut rest = &bytes[..];
        while !rest.is_empty() {
            let k = (4 * rng.below(3 << 13)).min(rest.len());
            sum.update(&rest[..k]);
            rest = &rest[k..];
        }
        assert_eq!(sum.finish(), fletcher64_by_definition(&bytes));
        // One word: both sums are the word.
        assert_eq!(fletcher64(b"abcd"), (0x6463_6261 << 32) | 0x6463_6261);
    }

    fn random_bvh(rng: &mut Rng, n: usize, volume: VolumeKind, collision: CollisionVolume) -> Bvh {
        let tris = (0..n)
            .map(|i| {
                let c = Vec3::from(rng.point(5.0));
                let mut v = || c + Vec3::from(rng.point(0.5));
                ([v(), v(), v()], i as i32 * 3 - 7)
            })
            .collect();
        Bvh::build(tris, volume, collision).unwrap()
    }

    #[test]
    fn load_gives_back_every_stored_and_derived_value() {
        let mut rng = Rng::new(11);
        for (k, volume) in [
            VolumeKind::Rss,
            VolumeKind::Pss,
            VolumeKind::Lss,
            VolumeKind::Hybrid,
        ]
        .into_iter()
        .enumerate()
        {
            for n in [1, 2, 3, 17, 200] {
                let collision = [CollisionVolume::Obb, CollisionVolume::Ssv][k % 2];
                let b = random_bvh(&mut rng, n, volume, collision);
                let mut bytes = vec![0u8; b.saved_size()];
                b.save(volume, &mut bytes);
                let (c, v) = Bvh::load(&bytes).unwrap();
                assert_eq!(v, volume);
                assert_eq!(c.collision, collision);
                assert_same(&b, &c);
            }
        }
    }

    #[test]
    fn sums_of_pieces_joined_are_the_sum_of_the_whole() {
        let mut rng = Rng::new(5);
        let len = (3 << 13) * 4 + 36;
        let random: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
        let ones = vec![0xffu8; len];
        let sums = |b: &[u8]| {
            let mut f = Fletcher64::default();
            f.update(b);
            f.sums()
        };
        for bytes in [random, ones] {
            let whole = sums(&bytes);
            assert_eq!(whole.finish(), fletcher64_by_definition(&bytes));
            // Split at every word for the first and last 300 words, around the reduction block
            // and at random words: odd word counts, counts not a multiple of the eight-word step.
            let words = len / 4;
            let mut at: Vec<usize> = (0..300).chain(words - 300..=words).collect();
            for b in [1 << 13, 2 << 13, 3 << 13] {
                at.extend(b - 9..=b + 9);
            }
            at.extend((0..200).map(|_| rng.below(words + 1)));
            for k in at {
                let (x, y) = bytes.split_at(4 * k);
                assert_eq!(sums(x).then(sums(y)), whole, "split at word {k}");
            }
            // Many pieces, joined in order; an empty piece changes nothing.
            let mut joined = Sums::default();
            let mut rest = &bytes[..];
            while !rest.is_empty() {
                let k = (4 * rng.below(5000)).min(rest.len());
                joined = joined.then(sums(&rest[..k])).then(Sums::default());
                rest = &rest[k..];
            }
            assert_eq!(joined, whole);
        }
        // The join is not a plain sum: pieces in the other order differ.
        let bytes: Vec<u8> = (0..64u8).collect();
        let (x, y) = bytes.split_at(20);
        assert_ne!(sums(y).then(sums(x)).finish(), fletcher64(&bytes));
    }

    /// Saved bytes of `b`, with the checksum recomputed after `change`.
    fn saved_with(b: &Bvh, volume: VolumeKind, change: impl Fn(&mut [u8])) -> Vec<u8> {
        let mut bytes = vec![0u8; b.saved_size()];
        b.save(volume, &mut bytes);
        change(&mut bytes);
        let body = bytes.len() - TRAILER;
        let sum = fletcher64(&bytes[..body]);
        bytes[body..].copy_from_slice(&sum.to_le_bytes());
        bytes
    }

    /// Every array and derived value of two hierarchies, bit for bit.
    fn assert_same(b: &Bvh, c: &Bvh) {
        assert_eq!(b.nodes.len(), c.nodes.len());
        for (x, y) in b.nodes.iter().zip(&c.nodes) {
            assert_eq!(x.ssv, y.ssv);
            assert_eq!(x.ssv_size.to_bits(), y.ssv_size.to_bits());
            assert_eq!(x.children, y.children);
        }
        assert_eq!(b.boxes, c.boxes);
        assert_eq!(b.verts, c.verts);
        assert_eq!(b.faces, c.faces);
        assert_eq!(b.ids, c.ids);
        assert_eq!(b.added, c.added);
        assert_eq!(b.collision, c.collision);
        assert_eq!(b.scale.to_bits(), c.scale.to_bits());
        assert_eq!(b.tiny, c.tiny);
    }

    #[test]
    fn two_threads_load_what_one_does_and_refuse_what_it_refuses() {
        let mut rng = Rng::new(13);
        for (n, volume) in [
            (2, VolumeKind::Rss),
            (3, VolumeKind::Lss),
            (40, VolumeKind::Pss),
            (57, VolumeKind::Hybrid),
            (300, VolumeKind::Rss),
        ] {
            let b = random_bvh(&mut rng, n, volume, CollisionVolume::Ssv);
            let bytes = saved_with(&b, volume, |_| {});
            let (one, _) = Bvh::load_with(&bytes, usize::MAX).unwrap();
            let (two, v) = Bvh::load_with(&bytes, 1).unwrap();
            assert_eq!(v, volume);
            assert_same(&b, &one);
            assert_same(&b, &two);
            // A value of the order added repeated, in the same share or another (some shares
            // of a small model have no triangles).
            let added = bytes.len() - TRAILER - 4 * n;
            for (i, j) in [(0, 1), (0, n - 1), (n / 2, n - 1), (1, 0), (n - 1, 0)] {
                if i != j {
                    let bad = saved_with(&b, volume, |x| {
                        let w = u32_at(x, added + 4 * i);
                        x[added + 4 * j..][..4].copy_from_slice(&w.to_le_bytes());
                    });
                    for two_from in [1, usize::MAX] {
                        let r = Bvh::load_with(&bad, two_from);
                        assert_eq!(r.err(), Some(Error::InvalidData), "{n} {i} {j}");
                    }
                }
            }
            // One word changed anywhere (in either share, the header or the trailer): refused
            // by both, the checksum left as it is or made to match.
            let size = bytes.len();
            let mut at: Vec<usize> = (0..size / 4).step_by(1 + size / 4 / 400).collect();
            at.push(size / 4 - 1);
            for w in at {
                for reseal in [false, true] {
                    let mut bad = bytes.clone();
                    let x = u32_at(&bad, 4 * w) ^ (1 << (w % 32));
                    bad[4 * w..4 * w + 4].copy_from_slice(&x.to_le_bytes());
                    if reseal && w < (size - TRAILER) / 4 {
                        let body = size - TRAILER;
                        let sum = fletcher64(&bad[..body]);
                        bad[body..].copy_from_slice(&sum.to_le_bytes());
                    }
                    let (r1, r2) = (Bvh::load_with(&bad, usize::MAX), Bvh::load_with(&bad, 1));
                    match (&r1, &r2) {
                        (Ok((x, vx)), Ok((y, vy))) => {
                            // A change that keeps a valid model (a value still in range, an id)
                            // loads the same on both paths.
                            assert!(reseal, "{n} word {w}");
                            assert_eq!(vx, vy);
                            assert_same(x, y);
                        }
                        (Err(e1), Err(e2)) => {
                            assert_eq!(*e1, Error::InvalidData);
                            assert_eq!(*e2, Error::InvalidData);
                        }
                        _ => panic!("{n} word {w}: {:?} {:?}", r1.is_ok(), r2.is_ok()),
                    }
                }
            }
        }
    }

    /// A change made to saved bytes.
    type Change = Box<dyn Fn(&mut [u8])>;

    #[test]
    fn faults_in_either_share_are_refused_on_two_threads() {
        let mut rng = Rng::new(17);
        let n = 400;
        let b = random_bvh(&mut rng, n, VolumeKind::Rss, CollisionVolume::Obb);
        let v = b.verts.len();
        let nodes = HEADER;
        let verts = nodes + (n - 1) * NODE;
        let faces = verts + v * VERTEX;
        let added = faces + n * TRIANGLE - 4 * n;
        // Records on either side of each boundary between shares, and in the middle of one.
        let mut at = vec![(0, 0), (n - 2, n - 1), ((n - 1) / 16, n / 16)];
        for i in 1..SHARES {
            let (kn, kt) = ((n - 1) * i / SHARES, n * i / SHARES);
            at.extend([(kn - 1, kt - 1), (kn, kt)]);
        }
        for (k, t) in at {
            let cases: Vec<Change> = vec![
                // A node value out of range, a child out of range, the root as a child.
                Box::new(move |b| {
                    b[nodes + k * NODE + 88..][..8].copy_from_slice(&(-1.0f64).to_le_bytes())
                }),
                Box::new(move |b| {
                    b[nodes + k * NODE + 144..][..4].copy_from_slice(&(n as u32).to_le_bytes())
                }),
                Box::new(move |b| {
                    b[nodes + k * NODE + 148..][..4].copy_from_slice(&0u32.to_le_bytes())
                }),
                // A vertex not finite.
                Box::new(move |b| {
                    let at = verts + (t * v / n) * VERTEX;
                    b[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes())
                }),
                // A vertex index out of range or past its first use.
                Box::new(move |b| {
                    b[faces + 12 * t..][..4].copy_from_slice(&(v as u32).to_le_bytes())
                }),
                Box::new(move |b| {
                    b[faces + 12 * t + 8..][..4].copy_from_slice(&(v as u32 - 1).to_le_bytes())
                }),
                // The order added: a value repeated (in the same share, or across the shares),
                // out of range.
                Box::new(move |b| {
                    let w = u32_at(b, added + 4 * ((t + 1) % n));
                    b[added + 4 * t..][..4].copy_from_slice(&w.to_le_bytes())
                }),
                Box::new(move |b| {
                    let w = u32_at(b, added + 4 * (n - 1 - t));
                    b[added + 4 * t..][..4].copy_from_slice(&w.to_le_bytes())
                }),
                Box::new(move |b| {
                    b[added + 4 * t..][..4].copy_from_slice(&(n as u32).to_le_bytes())
                }),
            ];
            for (c, change) in cases.iter().enumerate() {
                let bytes = saved_with(&b, VolumeKind::Rss, change);
                if bytes == saved_with(&b, VolumeKind::Rss, |_| {}) {
                    // The change wrote what was there (the last vertex's index past first use).
                    continue;
                }
                for two_from in [1, usize::MAX] {
                    assert_eq!(
                        Bvh::load_with(&bytes, two_from).err(),
                        Some(Error::InvalidData),
                        "record {k} {t}, case {c}, {two_from}"
                    );
                }
            }
        }
    }

    #[test]
    fn check_tree_refuses_what_is_not_the_build_tree() {
        let mut rng = Rng::new(3);
        let b = random_bvh(&mut rng, 40, VolumeKind::Rss, CollisionVolume::Obb);
        let kids: Vec<[NodeRef; 2]> = b.nodes.iter().map(|n| n.children).collect();
        assert!(check_tree(&kids, 40).is_ok());
        let with = |k: usize, side: usize, r: i32| {
            let mut kids = kids.clone();
            kids[k][side] = NodeRef(r);
            check_tree(&kids, 40)
        };
        for k in 0..b.nodes.len() {
            for side in 0..2 {
                // The root as a child (a cycle), itself, out of range, a leaf out of range, a
                // repeated leaf, the other child (a shared node).
                let other = b.nodes[k].children[1 - side].0;
                for r in [0, k as i32, 39, 1000, i32::MAX, -41, i32::MIN, other] {
                    if r != b.nodes[k].children[side].0 {
                        assert_eq!(with(k, side, r), Err(Error::InvalidData), "{k} {side} {r}");
                    }
                }
            }
        }
        // Children swapped: the leaves come out of order.
        let mut swapped = kids.clone();
        swapped[0].swap(0, 1);
        assert_eq!(check_tree(&swapped, 40), Err(Error::InvalidData));
        // The same tree with the root's first inner child stored last and the last node stored
        // there (references renamed): a valid tree whose child precedes its parent when the
        // moved node is an inner node's child with a larger index than that node.
        let first = (0..kids.len())
            .find(|&k| kids[0].iter().any(|c| c.0 == NodeRef::inner(k).0))
            .expect("the root has an inner child");
        let last = kids.len() - 1;
        let rename = |r: NodeRef| {
            if r.0 == NodeRef::inner(first).0 {
                NodeRef::inner(last)
            } else if r.0 == NodeRef::inner(last).0 {
                NodeRef::inner(first)
            } else {
                r
            }
        };
        let mut moved: Vec<[NodeRef; 2]> = kids.iter().map(|k| k.map(rename)).collect();
        moved.swap(first, last);
        let parent_after_child = (0..moved.len()).any(|i| {
            moved[i]
                .iter()
                .any(|c| matches!(c.kind(), NodeKind::Inner(j) if j <= i))
        });
        assert!(parent_after_child);
        assert_eq!(check_tree(&moved, 40), Err(Error::InvalidData));
    }

    #[test]
    fn check_tree_bounds_the_depth() {
        // A caterpillar: node i has leaf i and node i + 1; the last has two leaves.
        let caterpillar = |n: usize| {
            let kids: Vec<[NodeRef; 2]> = (0..n - 1)
                .map(|i| {
                    if i + 2 == n {
                        [NodeRef::leaf(i), NodeRef::leaf(i + 1)]
                    } else {
                        [NodeRef::leaf(i), NodeRef::inner(i + 1)]
                    }
                })
                .collect();
            check_tree(&kids, n)
        };
        assert!(caterpillar(MAX_DEPTH).is_ok());
        assert_eq!(caterpillar(MAX_DEPTH + 1), Err(Error::InvalidData));
    }
}
