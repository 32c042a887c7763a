//! Saved models that cannot lie. Every 32-bit word of a small model's saved bytes set to 0 and to
//! 0xffffffff, in version 1 (its Fletcher-64 cannot tell those two values apart), in version 2 as
//! written (CRC-32C) and in version 2 with the checksum made to match (so that every change
//! reaches the checks of the contents): each buffer is refused, or loads into a model whose
//! answers (collide, distance, tolerance, closest points, rays) are right, against brute force,
//! for the triangles it holds (read back from the bytes). Version 1 bytes of every volume choice
//! load as the model saved. The layout offsets are those of docs/saved-model-format.md.

mod common;

use common::{Mesh, Random, RandomPqp, Rng, borderline, brute, point_tri, segment_crosses_tri};
use pqp::{
    CollisionVolume, ContactMode, DistanceOptions, Error, Model, Pose, Search, Vec3, VolumeKind,
    closest_point, collide, distance, ray_cast, tolerance,
};

/// CRC-32C from its definition, a bit at a time (reflected, polynomial 0x82F63B78).
fn crc32c(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 == 1 {
                (c >> 1) ^ 0x82f6_3b78
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// Fletcher-64 from its definition (version 1's checksum).
fn fletcher64(bytes: &[u8]) -> u64 {
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

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

fn f64_at(b: &[u8], at: usize) -> f64 {
    f64::from_le_bytes(b[at..at + 8].try_into().unwrap())
}

/// Version 2 bytes with the checksum recomputed.
fn sealed_v2(mut b: Vec<u8>) -> Vec<u8> {
    let body = b.len() - 8;
    let sum = u64::from(crc32c(&b[..body]));
    b[body..].copy_from_slice(&sum.to_le_bytes());
    b
}

/// Version 2 bytes written as version 1 (the version word and the checksum: what the writer of
/// version 1 wrote).
fn as_v1(mut b: Vec<u8>) -> Vec<u8> {
    b[8..12].copy_from_slice(&1u32.to_le_bytes());
    let body = b.len() - 8;
    let sum = fletcher64(&b[..body]);
    b[body..].copy_from_slice(&sum.to_le_bytes());
    b
}

/// The triangles a saved model holds, with their ids, in leaf order.
fn held(b: &[u8]) -> (Mesh, Vec<i32>) {
    let (n, v) = (u32_at(b, 20) as usize, u32_at(b, 24) as usize);
    let verts = 40 + 152 * (n - 1);
    let faces = verts + 24 * v;
    let ids = faces + 12 * n;
    let vert = |k: usize| {
        let at = verts + 24 * k;
        [f64_at(b, at), f64_at(b, at + 8), f64_at(b, at + 16)]
    };
    let tris = (0..n)
        .map(|t| [0, 1, 2].map(|c| vert(u32_at(b, faces + 12 * t + 4 * c) as usize)))
        .collect();
    let idv = (0..n).map(|t| u32_at(b, ids + 4 * t) as i32).collect();
    (Mesh { tris }, idv)
}

fn small_model(volume: VolumeKind, collision: CollisionVolume) -> Model {
    let mut rng = Rng::new(38);
    let mut mesh = Mesh::sphere(1.0, 5, 3);
    mesh.tris.extend(Mesh::soup(&mut rng, 7, 1.0, 0.3).tris);
    let mut m = Model::new();
    m.set_volume(volume).unwrap();
    m.set_collision_volume(collision).unwrap();
    for (i, t) in mesh.tris.iter().enumerate() {
        m.add_triangle(t[0], t[1], t[2], i as i32).unwrap();
    }
    m.end().unwrap();
    m
}

/// Checks every answer of `m` against brute force over `tris` (ids `ids`), against `other`.
fn answers_right(m: &Model, tris: &Mesh, ids: &[i32], other: &Mesh, what: &str) {
    let om = other.model();
    let mut rng = Rng::new(39);
    for k in 0..3 {
        let (p1, p2): (Pose, Pose) = (rng.pose(0.2), rng.pose(1.0));
        if borderline(tris, &p1, other, &p2, 1e-9) {
            continue;
        }
        let want = brute(tris, &p1, other, &p2);
        let mut want_pairs: Vec<(i32, i32)> = want
            .pairs
            .iter()
            .map(|&(i, j)| (ids[i as usize], j))
            .collect();
        want_pairs.sort();
        let c = collide(m, &p1, &om, &p2, ContactMode::All).unwrap();
        let mut pairs: Vec<(i32, i32)> = c.pairs().iter().map(|p| (p.id1, p.id2)).collect();
        pairs.sort();
        assert_eq!(pairs, want_pairs, "{what}: collide at pose {k}");
        let first = collide(m, &p1, &om, &p2, ContactMode::First).unwrap();
        assert_eq!(first.pairs().is_empty(), want_pairs.is_empty(), "{what}");
        let d = distance(m, &p1, &om, &p2, &DistanceOptions::exact()).unwrap();
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + y);
        assert!(close(d.distance, want.distance), "{what}: distance {k}");
        let t = tolerance(m, &p1, &om, &p2, 0.05, &Search::default()).unwrap();
        if (want.distance - 0.05).abs() > 1e-9 {
            assert_eq!(t.closer_than_tolerance, want.distance <= 0.05, "{what}");
        }
    }
    let id = Pose::identity();
    for _ in 0..4 {
        // Closest points: the least distance to any triangle.
        let q = rng.point(1.5);
        let r = closest_point(m, &id, &Vec3::from(q), f64::INFINITY).unwrap();
        let want = tris
            .tris
            .iter()
            .map(|t| point_tri(q, t))
            .fold(f64::INFINITY, f64::min);
        assert!(
            (r.distance - want).abs() <= 1e-12 * (1.0 + want),
            "{what}: point"
        );
        // Rays: nothing crossed before the hit, the hit on a triangle of its id; without a hit,
        // nothing crossed within max_t.
        let (o, dir) = (rng.point(1.5), rng.point(1.0));
        let at = |t: f64| [o[0] + t * dir[0], o[1] + t * dir[1], o[2] + t * dir[2]];
        let hit = ray_cast(m, &id, &Vec3::from(o), &Vec3::from(dir), 3.0).unwrap();
        let crosses = |t1: f64| tris.tris.iter().any(|t| segment_crosses_tri(o, at(t1), t));
        match hit {
            Some(h) => {
                assert!(!crosses(h.t - 1e-7), "{what}: a triangle before the hit");
                let p = at(h.t);
                let on = |i: usize| ids[i] == h.triangle && point_tri(p, &tris.tris[i]) < 1e-9;
                assert!((0..ids.len()).any(on), "{what}: the hit is on its triangle");
            }
            None => assert!(!crosses(3.0), "{what}: a crossing missed"),
        }
    }
}

/// Each word of `bytes` set to 0 and to all ones (and sealed by `seal`): refused, or right. The
/// number accepted.
fn every_word(bytes: &[u8], seal: impl Fn(Vec<u8>) -> Vec<u8>, what: &str) -> usize {
    let other = Mesh::sphere(0.6, 6, 4);
    let mut accepted = 0;
    for w in 0..bytes.len() / 4 {
        for x in [0u32, u32::MAX] {
            let mut bad = bytes.to_vec();
            bad[4 * w..4 * w + 4].copy_from_slice(&x.to_le_bytes());
            let bad = seal(bad);
            if bad == bytes {
                continue;
            }
            match Model::from_bytes(&bad) {
                Err(e) => assert_eq!(e, Error::InvalidData, "{what} word {w} = {x:#x}"),
                Ok(m) => {
                    accepted += 1;
                    let (tris, ids) = held(&bad);
                    answers_right(
                        &m,
                        &tris,
                        &ids,
                        &other,
                        &format!("{what} word {w} = {x:#x}"),
                    );
                }
            }
        }
    }
    accepted
}

#[test]
fn every_word_set_to_0_or_all_ones_is_refused_or_answers_right() {
    for (volume, collision) in [
        (VolumeKind::Rss, CollisionVolume::Obb),
        (VolumeKind::Hybrid, CollisionVolume::Ssv),
    ] {
        let v2 = small_model(volume, collision).to_bytes().unwrap();
        assert_eq!(u32_at(&v2, 8), 2);
        let v1 = as_v1(v2.clone());
        let a1 = every_word(&v1, |b| b, "version 1");
        let a2 = every_word(&v2, |b| b, "version 2");
        let sealed = every_word(&v2, sealed_v2, "version 2 sealed");
        eprintln!(
            "{volume:?} {collision:?}, {} words: accepted {a1} (version 1), {a2} (version 2), \
             {sealed} (version 2, checksum made to match)",
            v2.len() / 4
        );
        // CRC-32C sees every one-word change.
        assert_eq!(a2, 0);
    }
}

#[test]
fn version_1_bytes_load_as_the_model_saved() {
    for volume in [
        VolumeKind::Rss,
        VolumeKind::Pss,
        VolumeKind::Lss,
        VolumeKind::Hybrid,
    ] {
        for collision in [CollisionVolume::Obb, CollisionVolume::Ssv] {
            let m = small_model(volume, collision);
            let v2 = m.to_bytes().unwrap();
            let loaded = Model::from_bytes(&as_v1(v2.clone())).unwrap();
            assert_eq!(loaded.volume(), volume);
            assert_eq!(loaded.collision_volume(), collision);
            // Saved again: version 2, the same model.
            assert!(loaded.to_bytes().unwrap() == v2);
        }
    }
}
