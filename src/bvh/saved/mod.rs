//! Saved hierarchies: a built hierarchy as bytes and back (the layout is documented in
//! `docs/saved-model-format.md`; this module and that file change together).
//!
//! Every value is written with an explicit little-endian conversion, so the bytes are the same on
//! every machine; nothing is written or read by reinterpreting memory (`codec.rs`). Writers write
//! version 2 (checksum CRC-32C); readers read versions 1 (Fletcher-64) and 2 (`checksum.rs`).
//! Reading trusts nothing: the size, the checksum and then every value are checked, in O(n),
//! before a hierarchy is made (`threads.rs`, on two threads for a large model), so that no
//! buffer, truncated, corrupted or crafted, gives a hierarchy a query could misuse: indices in
//! range, a tree whose leaves are the triangles in slot order (each node reached once from the
//! root), depth within [`MAX_DEPTH`](super::MAX_DEPTH) (the queries' fixed stacks), finite
//! coordinates within range, consistent counts, and every node's volumes containing the triangles
//! below it to within a stated rounding (`validate.rs`, O(n depth)), so that a loaded model
//! answers right for the triangles it holds whatever the checksum said. Derived values (`scale`, `tiny`, each
//! node's volume size) are not stored but recomputed, bit for bit as the build computed them.

mod checksum;
mod codec;
mod threads;
mod validate;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_volumes;

use super::{Bvh, VolumeKind};
use crate::error::Error;
use codec::{
    HEADER, MAGIC, NODE, TRAILER, TRIANGLE, VERTEX, collision_code, put_f64s, put_node, put_u32s,
    volume_code,
};

/// The versions of the layout this crate reads; it writes the last.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Version {
    /// Checksum Fletcher-64.
    V1,
    /// Checksum CRC-32C; the layout is otherwise version 1's.
    V2,
}

impl Version {
    /// The version a writer writes.
    pub(crate) const CURRENT: Version = Version::V2;

    fn code(self) -> u32 {
        match self {
            Version::V1 => 1,
            Version::V2 => 2,
        }
    }

    fn from_code(code: u32) -> Option<Version> {
        match code {
            1 => Some(Version::V1),
            2 => Some(Version::V2),
            _ => None,
        }
    }
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
    /// is exactly [`saved_size`](Bvh::saved_size) bytes long, in the current version.
    pub fn save(&self, volume: VolumeKind, out: &mut [u8]) {
        self.save_as(volume, out, Version::CURRENT);
    }

    /// [`save`](Bvh::save) in layout `version` (an older one for tests of reading it).
    pub(crate) fn save_as(&self, volume: VolumeKind, out: &mut [u8], version: Version) {
        let total = self.saved_size();
        debug_assert_eq!(out.len(), total);
        let (header, rest) = out.split_at_mut(HEADER);
        header[..8].copy_from_slice(&MAGIC);
        // Counts fit: at most i32::MAX triangles, and vertices are indexed by u32.
        put_u32s(
            &mut header[8..32],
            &[
                version.code(),
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
            put_node(out, n, b);
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
        trailer.copy_from_slice(&checksum::checksum(version, body).to_le_bytes());
    }

    /// Reads a hierarchy [`save`](Bvh::save) wrote (in any version this crate reads), with the
    /// model's swept sphere volume kind.
    ///
    /// `Err(InvalidData)` for anything else (see the module's documentation for what is checked);
    /// `Err(ModelOutOfMemory)` if its storage could not be allocated. Allocations are sized from
    /// counts already checked against the length of `bytes`.
    pub fn load(bytes: &[u8]) -> Result<(Bvh, VolumeKind), Error> {
        Bvh::load_with(bytes, threads::TWO_THREADS)
    }
}

/// The checksum of `body` as the current version's trailer stores it (for tests that edit saved
/// bytes and seal them again).
#[cfg(test)]
pub(crate) fn seal(version: Version, bytes: &mut [u8]) {
    let body = bytes.len() - TRAILER;
    let sum = checksum::checksum(version, &bytes[..body]);
    bytes[body..].copy_from_slice(&sum.to_le_bytes());
}
