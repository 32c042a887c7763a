//! The layout's checksums, reading on one and two threads, and the tree check.

use super::checksum::{Crc32c, Fletcher64, Sums, crc32c, fletcher64};
use super::codec::{HEADER, NODE, TRAILER, TRIANGLE, VERTEX, u32_at};
use super::threads::SHARES;
use super::validate::check_tree;
use super::{Version, seal};
use crate::bvh::{Bvh, CollisionVolume, MAX_DEPTH, NodeKind, NodeRef, VolumeKind};
use crate::error::Error;
use crate::math::Vec3;
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

pub(super) fn random_bvh(
    rng: &mut Rng,
    n: usize,
    volume: VolumeKind,
    collision: CollisionVolume,
) -> Bvh {
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
            for version in [Version::V1, Version::V2] {
                let mut bytes = vec![0u8; b.saved_size()];
                b.save_as(volume, &mut bytes, version);
                let (c, v) = Bvh::load(&bytes).unwrap();
                assert_eq!(v, volume);
                assert_eq!(c.collision, collision);
                assert_same(&b, &c);
                // Saved again: the current version, the same but for the version and checksum.
                let mut again = vec![0u8; c.saved_size()];
                c.save(v, &mut again);
                let body = bytes.len() - TRAILER;
                assert_eq!(u32_at(&again, 8), 2);
                assert_eq!(again[12..body], bytes[12..body]);
            }
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

/// Saved bytes of `b` in the current version, with the checksum recomputed after `change`.
fn saved_with(b: &Bvh, volume: VolumeKind, change: impl Fn(&mut [u8])) -> Vec<u8> {
    saved_in(Version::CURRENT, b, volume, change)
}

/// Saved bytes of `b` in `version`, with the checksum recomputed after `change`.
pub(super) fn saved_in(
    version: Version,
    b: &Bvh,
    volume: VolumeKind,
    change: impl Fn(&mut [u8]),
) -> Vec<u8> {
    let mut bytes = vec![0u8; b.saved_size()];
    b.save_as(volume, &mut bytes, version);
    change(&mut bytes);
    seal(version, &mut bytes);
    bytes
}

/// Every array and derived value of two hierarchies, bit for bit.
pub(super) fn assert_same(b: &Bvh, c: &Bvh) {
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
        for version in [Version::V1, Version::V2] {
            both_paths_agree(&b, volume, version);
        }
    }
}

/// For [`two_threads_load_what_one_does_and_refuse_what_it_refuses`].
fn both_paths_agree(b: &Bvh, volume: VolumeKind, version: Version) {
    let n = b.faces.len();
    {
        let bytes = saved_in(version, b, volume, |_| {});
        let (one, _) = Bvh::load_with(&bytes, usize::MAX).unwrap();
        let (two, v) = Bvh::load_with(&bytes, 1).unwrap();
        assert_eq!(v, volume);
        assert_same(b, &one);
        assert_same(b, &two);
        // A value of the order added repeated, in the same share or another (some shares
        // of a small model have no triangles).
        let added = bytes.len() - TRAILER - 4 * n;
        for (i, j) in [(0, 1), (0, n - 1), (n / 2, n - 1), (1, 0), (n - 1, 0)] {
            if i != j {
                let bad = saved_in(version, b, volume, |x| {
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
                    seal(version, &mut bad);
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
            Box::new(move |b| b[faces + 12 * t..][..4].copy_from_slice(&(v as u32).to_le_bytes())),
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
            Box::new(move |b| b[added + 4 * t..][..4].copy_from_slice(&(n as u32).to_le_bytes())),
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

#[test]
fn crc32c_pieces_join_into_the_crc_of_the_whole() {
    // The standard check value of CRC-32C.
    assert_eq!(crc32c(b"123456789"), 0xe306_9283);
    let mut rng = Rng::new(19);
    let bytes: Vec<u8> = (0..20_000).map(|_| rng.next_u64() as u8).collect();
    let piece = |b: &[u8]| {
        let mut c = Crc32c::default();
        c.update(b);
        c
    };
    let whole = crc32c(&bytes);
    // Splits at either end and at random places.
    let mut at: Vec<usize> = (0..40).chain(bytes.len() - 40..=bytes.len()).collect();
    at.extend((0..60).map(|_| rng.below(bytes.len() + 1)));
    for k in at {
        let (x, y) = bytes.split_at(k);
        let joined = piece(x).then(piece(y));
        assert_eq!(joined, piece(&bytes), "split at {k}");
        // An empty piece on either side changes nothing.
        assert_eq!(
            Crc32c::default().then(joined).then(Crc32c::default()),
            joined
        );
    }
    assert_eq!(piece(&bytes), {
        let mut c = Crc32c::default();
        c.update(&bytes);
        c
    });
    assert_eq!(u64::from(whole), {
        let mut s = super::checksum::Running::new(Version::V2);
        s.update(&bytes[..777]);
        let first = s.piece();
        let mut s = super::checksum::Running::new(Version::V2);
        s.update(&bytes[777..]);
        first.then(s.piece()).finish()
    });
}

#[test]
fn the_checksum_of_version_2_sees_every_word_set_to_0_or_all_ones() {
    // Fletcher-64's blind spot: 0 and 0xffffffff are both 0 modulo 2^32 - 1.
    let mut rng = Rng::new(23);
    let b = random_bvh(&mut rng, 37, VolumeKind::Rss, CollisionVolume::Obb);
    for version in [Version::V1, Version::V2] {
        let bytes = saved_in(version, &b, VolumeKind::Rss, |_| {});
        let body = bytes.len() - TRAILER;
        let mut unseen = 0;
        for w in 0..body / 4 {
            for x in [0u32, u32::MAX] {
                let mut bad = bytes.clone();
                bad[4 * w..4 * w + 4].copy_from_slice(&x.to_le_bytes());
                if bad != bytes
                    && super::checksum::checksum(version, &bad[..body]) == u64_at_end(&bad)
                {
                    unseen += 1;
                }
            }
        }
        match version {
            Version::V1 => assert!(unseen > 0),
            Version::V2 => assert_eq!(unseen, 0),
        }
    }
}

fn u64_at_end(b: &[u8]) -> u64 {
    let mut w = [0u8; 8];
    w.copy_from_slice(&b[b.len() - 8..]);
    u64::from_le_bytes(w)
}
