//! The saved layout's records: sizes, header codes, and inner nodes to and from bytes, every value
//! by an explicit little-endian conversion (nothing written or read by reinterpreting memory).

use super::super::{CollisionVolume, Node, NodeBox, NodeRef, VolumeKind};
use crate::bounding_volume::{BoundingVolume, CompactSsv};
use crate::error::{Error, MAX_COORDINATE};
use crate::math::Vec3;

/// The first eight bytes of every saved model.
pub(super) const MAGIC: [u8; 8] = *b"PQPMODEL";
/// Bytes of the header: magic, version, volume kind, collision volume, triangle count, vertex
/// count, a reserved zero word and the total size.
pub(super) const HEADER: usize = 40;
/// Bytes of an inner node: 18 doubles (two axes, the swept sphere volume's origin, two lengths and
/// radius, the box's centre and half extents) and its two children.
pub(super) const NODE: usize = 18 * 8 + 2 * 4;
/// Bytes of a vertex.
pub(super) const VERTEX: usize = 3 * 8;
/// Bytes per triangle: three vertex indices, the id and the position in the order added.
pub(super) const TRIANGLE: usize = 3 * 4 + 4 + 4;
/// Bytes of the checksum that ends the buffer.
pub(super) const TRAILER: usize = 8;

/// Largest magnitude of a stored node value (16 times the largest coordinate: a built node's
/// origin, extents and radius stay within a few times its largest vertex coordinate). It keeps
/// squares and products of the values the queries form finite.
const MAX_NODE_VALUE: f64 = 16.0 * MAX_COORDINATE;

/// How far from orthonormal a stored frame may be (built frames are within a few ulps).
const FRAME_TOLERANCE: f64 = 1e-6;

/// The codes of the volume choices in the header (PQP_BV_* and PQP_COLLIDE_* of the C ABI).
pub(super) fn volume_code(v: VolumeKind) -> u32 {
    match v {
        VolumeKind::Rss => 0,
        VolumeKind::Pss => 1,
        VolumeKind::Lss => 2,
        VolumeKind::Hybrid => 3,
    }
}

pub(super) fn volume_from(code: u32) -> Option<VolumeKind> {
    Some(match code {
        0 => VolumeKind::Rss,
        1 => VolumeKind::Pss,
        2 => VolumeKind::Lss,
        3 => VolumeKind::Hybrid,
        _ => return None,
    })
}

pub(super) fn collision_code(c: CollisionVolume) -> u32 {
    match c {
        CollisionVolume::Obb => 0,
        CollisionVolume::Ssv => 1,
    }
}

pub(super) fn collision_from(code: u32) -> Option<CollisionVolume> {
    Some(match code {
        0 => CollisionVolume::Obb,
        1 => CollisionVolume::Ssv,
        _ => return None,
    })
}

/// Little-endian reads at a byte offset of a slice long enough (the callers' sections are sized
/// from the header before any read).
pub(super) fn u32_at(b: &[u8], at: usize) -> u32 {
    let mut w = [0u8; 4];
    w.copy_from_slice(&b[at..at + 4]);
    u32::from_le_bytes(w)
}

pub(super) fn u64_at(b: &[u8], at: usize) -> u64 {
    let mut w = [0u8; 8];
    w.copy_from_slice(&b[at..at + 8]);
    u64::from_le_bytes(w)
}

pub(super) fn f64_at(b: &[u8], at: usize) -> f64 {
    f64::from_bits(u64_at(b, at))
}

/// Writes `values` as consecutive little-endian words from the start of `out`.
pub(super) fn put_f64s(out: &mut [u8], values: &[f64]) {
    for (o, v) in out.chunks_exact_mut(8).zip(values) {
        o.copy_from_slice(&v.to_le_bytes());
    }
}

pub(super) fn put_u32s(out: &mut [u8], values: &[u32]) {
    for (o, v) in out.chunks_exact_mut(4).zip(values) {
        o.copy_from_slice(&v.to_le_bytes());
    }
}

/// The sections of a saved hierarchy of `n` triangles (n >= 1) and `v` vertices, in bytes, in the
/// order they follow the header; `None` if their sum overflows.
pub(super) fn section_sizes(n: u64, v: u64) -> Option<[u64; 5]> {
    Some([
        (n - 1).checked_mul(NODE as u64)?,
        v.checked_mul(VERTEX as u64)?,
        n.checked_mul(12)?,
        n.checked_mul(4)?,
        n.checked_mul(4)?,
    ])
}

/// Writes an inner node and its box as a [`NODE`]-byte record at the start of `out`.
pub(super) fn put_node(out: &mut [u8], n: &Node, b: &NodeBox) {
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

/// An inner node and its box, checked on its own: values finite and within [`MAX_NODE_VALUE`],
/// lengths, radius and half extents not negative, lengths as the model's volume kind allows, axes
/// orthonormal. Its children are checked by `validate::check_tree`, its volumes against its
/// children's by `validate::check_volumes`.
pub(super) fn read_node(b: &[u8], volume: VolumeKind) -> Result<(Node, NodeBox), Error> {
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
