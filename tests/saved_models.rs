//! Saved models: `Model::to_bytes` / `serialize_into` / `from_bytes` and the C functions
//! `pqp_model_serialize` / `pqp_model_deserialize`.
//!
//! A loaded model must be the saved one: every query answer (pairs, distances, points, ids) and
//! every count of bound and triangle tests identical, bit for bit, over sequences of random poses
//! (results reused, so the triangle cache and front tracking are exercised too), for every volume
//! choice, on the shared models and random meshes; and it must answer as brute force does. Bad
//! bytes must be refused with `InvalidData`: every truncation, every flipped byte, and, with the
//! checksum recomputed here (an independent CRC-32C, from its definition) so that the structural
//! checks are reached, bad indices, cycles, shared nodes, out-of-range and non-finite values, bad
//! counts, a tree too deep. The layout offsets used are those of docs/saved-model-format.md.

mod common;

use common::{Mesh, Random, RandomPqp, Rng, brute};
use pqp::capi::*;
use pqp::{
    CollisionVolume, ContactMode, DistanceOptions, DistanceResult, Error, Model, Pose, Search,
    ToleranceResult, VolumeKind, collide, distance, distance_into, tolerance, tolerance_into,
};
use std::ptr::{null, null_mut};

const VOLUMES: [VolumeKind; 4] = [
    VolumeKind::Rss,
    VolumeKind::Pss,
    VolumeKind::Lss,
    VolumeKind::Hybrid,
];
const COLLISIONS: [CollisionVolume; 2] = [CollisionVolume::Obb, CollisionVolume::Ssv];

/// Layout of docs/saved-model-format.md.
const HEADER: usize = 40;
const NODE: usize = 152;

/// A mesh of /work/shared/models.
fn shared(name: &str) -> Mesh {
    let text = std::fs::read_to_string(format!("/work/shared/models/{name}.tris")).unwrap();
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    let n = v[0] as usize;
    let tris = (0..n)
        .map(|i| {
            let p = |k: usize| {
                let at = 1 + 9 * i + 3 * k;
                [v[at], v[at + 1], v[at + 2]]
            };
            [p(0), p(1), p(2)]
        })
        .collect();
    Mesh { tris }
}

/// `mesh` built with the given volume choices (ids: the triangle's index).
fn build(mesh: &Mesh, volume: VolumeKind, collision: CollisionVolume) -> Model {
    let mut m = Model::new();
    m.set_volume(volume).unwrap();
    m.set_collision_volume(collision).unwrap();
    for (i, t) in mesh.tris.iter().enumerate() {
        m.add_triangle(t[0], t[1], t[2], i as i32).unwrap();
    }
    m.end().unwrap();
    m
}

/// CRC-32C from its definition, a bit at a time: reflected, polynomial 0x82F63B78 (0x1EDC6F41
/// reversed), initial value and final xor 0xffffffff.
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

/// `bytes` with its checksum (version 2: CRC-32C in the low half of the last 8 bytes) recomputed
/// (so that a change gets past it to the structural checks).
fn resealed(mut bytes: Vec<u8>) -> Vec<u8> {
    let body = bytes.len() - 8;
    let sum = u64::from(crc32c(&bytes[..body]));
    bytes[body..].copy_from_slice(&sum.to_le_bytes());
    bytes
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

fn put_u32(b: &mut [u8], at: usize, v: u32) {
    b[at..at + 4].copy_from_slice(&v.to_le_bytes());
}

fn put_f64(b: &mut [u8], at: usize, v: f64) {
    b[at..at + 8].copy_from_slice(&v.to_le_bytes());
}

/// Where the sections of a saved model start: nodes, vertices, faces, ids, added.
fn sections(bytes: &[u8]) -> [usize; 5] {
    let (n, v) = (u32_at(bytes, 20) as usize, u32_at(bytes, 24) as usize);
    let nodes = HEADER;
    let verts = nodes + (n - 1) * NODE;
    let faces = verts + 24 * v;
    let ids = faces + 12 * n;
    [nodes, verts, faces, ids, ids + 4 * n]
}

/// Everything the queries answer at each pose pair, floats as bits, with their counts of bound and
/// triangle tests: collide (all and first contact), exact distance and tolerance with results
/// reused from pose to pose (triangle cache, front tracking), approximate distance afresh.
fn answers(a: &Model, b: &Model, poses: &[(Pose, Pose)]) -> Vec<String> {
    let bits = |v: &pqp::Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
    let mut out = Vec::new();
    let mut dr = DistanceResult::new();
    let mut tr = ToleranceResult::new();
    let search = Search::default();
    for (p1, p2) in poses {
        for mode in [ContactMode::All, ContactMode::First] {
            let c = collide(a, p1, b, p2, mode).unwrap();
            out.push(format!(
                "collide {:?} {:?} {} {}",
                mode,
                c.pairs(),
                c.stats.bv_tests,
                c.stats.tri_tests
            ));
        }
        distance_into(&mut dr, a, p1, b, p2, &DistanceOptions::exact()).unwrap();
        let approx = distance(a, p1, b, p2, &DistanceOptions::approximate(0.1, 0.01)).unwrap();
        for d in [&dr, &approx] {
            out.push(format!(
                "distance {} {:?} {:?} {} {} {} {} {} {} {}",
                d.distance.to_bits(),
                bits(&d.p1),
                bits(&d.p2),
                d.overlap,
                d.id1,
                d.id2,
                d.tri1,
                d.tri2,
                d.stats.bv_tests,
                d.stats.tri_tests
            ));
        }
        tolerance_into(&mut tr, a, p1, b, p2, 0.02, &search).unwrap();
        out.push(format!(
            "tolerance {} {} {:?} {:?} {} {} {} {} {} {}",
            tr.closer_than_tolerance,
            tr.distance.to_bits(),
            bits(&tr.p1),
            bits(&tr.p2),
            tr.id1,
            tr.id2,
            tr.tri1,
            tr.tri2,
            tr.stats.bv_tests,
            tr.stats.tri_tests
        ));
    }
    out
}

/// Pose pairs that bring two models of size ~1 into contact and near misses, and some that
/// follow each other closely (coherent motion, where the front tracking starts).
fn poses(rng: &mut Rng, n: usize, half: f64) -> Vec<(Pose, Pose)> {
    let mut out: Vec<(Pose, Pose)> = Vec::new();
    for i in 0..n {
        if i % 3 == 2 {
            let (p1, p2) = out[i - 1];
            let t = p2.translation + rng.vec3(0.01);
            out.push((p1, Pose::new(rng.rotation(), [t.x, t.y, t.z])));
        } else {
            out.push((rng.pose(0.1), rng.pose(half)));
        }
    }
    out
}

/// Saves `m`, loads it back, and checks the copy: the same bytes when saved again, the same
/// choices and counts.
fn round_trip(m: &Model) -> Model {
    let bytes = m.to_bytes().unwrap();
    assert_eq!(bytes.len(), m.serialized_size().unwrap());
    let loaded = Model::from_bytes(&bytes).unwrap();
    assert!(loaded.is_built());
    assert_eq!(loaded.volume(), m.volume());
    assert_eq!(loaded.collision_volume(), m.collision_volume());
    assert_eq!(loaded.num_triangles(), m.num_triangles());
    assert_eq!(loaded.memory_usage(), m.memory_usage());
    assert!(loaded.to_bytes().unwrap() == bytes);
    loaded
}

#[test]
fn shared_models_answer_identically_after_loading_with_every_volume_choice() {
    let mut rng = Rng::new(21);
    let (bunny, torus) = (shared("bunny"), shared("torus"));
    for volume in VOLUMES {
        for collision in COLLISIONS {
            let a = build(&bunny, volume, collision);
            let b = build(&torus, volume, collision);
            let (la, lb) = (round_trip(&a), round_trip(&b));
            let ps = poses(&mut rng, 24, 0.8);
            let want = answers(&a, &b, &ps);
            assert_eq!(answers(&la, &lb, &ps), want, "{volume:?} {collision:?}");
            // Mixed: a loaded model against an original.
            assert_eq!(answers(&la, &b, &ps), want, "{volume:?} {collision:?}");
        }
    }
    // The tumbling tori, each with its own choice.
    let (t1, t2) = (shared("torus1"), shared("torus2"));
    let a = build(&t1, VolumeKind::Hybrid, CollisionVolume::Ssv);
    let b = build(&t2, VolumeKind::Lss, CollisionVolume::Obb);
    let ps = poses(&mut rng, 24, 1.2);
    assert_eq!(
        answers(&round_trip(&a), &round_trip(&b), &ps),
        answers(&a, &b, &ps)
    );
}

#[test]
fn random_meshes_answer_identically_and_as_brute_force_after_loading() {
    let mut rng = Rng::new(22);
    for case in 0..24 {
        let n1 = [1, 2, 3, 7, 40, 150][case % 6];
        let n2 = [1, 5, 60][case % 3];
        let (volume, collision) = (VOLUMES[case % 4], COLLISIONS[case / 4 % 2]);
        let m1 = Mesh::soup(&mut rng, n1, 1.0, 0.4);
        let m2 = Mesh::soup(&mut rng, n2, 1.0, 0.4);
        let (a, b) = (build(&m1, volume, collision), build(&m2, volume, collision));
        let (la, lb) = (round_trip(&a), round_trip(&b));
        let ps = poses(&mut rng, 12, 1.0);
        assert_eq!(answers(&la, &lb, &ps), answers(&a, &b, &ps), "case {case}");
        for (p1, p2) in &ps {
            let want = brute(&m1, p1, &m2, p2);
            let c = collide(&la, p1, &lb, p2, ContactMode::All).unwrap();
            let mut pairs: Vec<(i32, i32)> = c.pairs().iter().map(|p| (p.id1, p.id2)).collect();
            pairs.sort();
            assert_eq!(pairs, want.pairs, "case {case}");
            let d = distance(&la, p1, &lb, p2, &DistanceOptions::exact()).unwrap();
            assert!(
                (d.distance - want.distance).abs() <= 1e-12 * (1.0 + want.distance),
                "case {case}: {} vs {}",
                d.distance,
                want.distance
            );
            let t = tolerance(&la, p1, &lb, p2, 0.05, &Search::default()).unwrap();
            if (want.distance - 0.05).abs() > 1e-9 {
                assert_eq!(
                    t.closer_than_tolerance,
                    want.distance <= 0.05,
                    "case {case}"
                );
            }
        }
    }
}

#[test]
fn extreme_coordinates_round_trip() {
    // At the 1e150 limit, and all below the kernels' rescaling threshold (the `tiny` flag).
    let mut rng = Rng::new(23);
    for scale in [1e150, 1e-140, 1e-300] {
        let mesh = Mesh::soup(&mut rng, 30, 1.0, 0.5);
        let scaled = Mesh {
            tris: mesh
                .tris
                .iter()
                .map(|t| t.map(|p| p.map(|x| (x * scale).clamp(-1e150, 1e150))))
                .collect(),
        };
        let a = build(&scaled, VolumeKind::Rss, CollisionVolume::Obb);
        let la = round_trip(&a);
        let ps: Vec<(Pose, Pose)> = (0..6)
            .map(|_| {
                let t = rng.point(scale.min(1e149));
                (Pose::identity(), Pose::new(rng.rotation(), t))
            })
            .collect();
        assert_eq!(answers(&la, &la, &ps), answers(&a, &a, &ps), "{scale}");
    }
}

#[test]
fn serialize_into_refuses_a_small_buffer_and_an_unbuilt_model_writing_nothing() {
    let mut rng = Rng::new(24);
    let m = Mesh::soup(&mut rng, 9, 1.0, 0.3).model();
    let size = m.serialized_size().unwrap();
    let mut small = vec![0xa5u8; size - 1];
    assert_eq!(m.serialize_into(&mut small), Err(Error::BufferTooSmall));
    assert!(small.iter().all(|&b| b == 0xa5));
    assert_eq!(m.serialize_into(&mut []), Err(Error::BufferTooSmall));
    // A larger buffer: the saved bytes at its start, the rest untouched.
    let mut large = vec![0xa5u8; size + 10];
    assert_eq!(m.serialize_into(&mut large), Ok(size));
    assert!(large[..size] == m.to_bytes().unwrap()[..]);
    assert!(large[size..].iter().all(|&b| b == 0xa5));

    let mut unbuilt = Model::new();
    assert_eq!(unbuilt.serialized_size(), Err(Error::UnprocessedModel));
    assert_eq!(unbuilt.to_bytes(), Err(Error::UnprocessedModel));
    unbuilt
        .add_triangle([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0)
        .unwrap();
    let mut buf = vec![0xa5u8; 1000];
    assert_eq!(
        unbuilt.serialize_into(&mut buf),
        Err(Error::UnprocessedModel)
    );
    assert!(buf.iter().all(|&b| b == 0xa5));
}

/// A small model with every volume kind's node layout (Hybrid) and shared vertices.
fn small_model() -> Model {
    let mut rng = Rng::new(25);
    let mut mesh = Mesh::sphere(1.0, 4, 3);
    mesh.tris.extend(Mesh::soup(&mut rng, 3, 1.0, 0.3).tris);
    build(&mesh, VolumeKind::Hybrid, CollisionVolume::Ssv)
}

#[test]
fn every_truncation_and_extension_is_invalid() {
    let bytes = small_model().to_bytes().unwrap();
    for len in 0..bytes.len() {
        assert_eq!(
            Model::from_bytes(&bytes[..len]).err(),
            Some(Error::InvalidData),
            "{len}"
        );
    }
    let mut longer = bytes.clone();
    longer.push(0);
    assert_eq!(Model::from_bytes(&longer).err(), Some(Error::InvalidData));
    // Even with the size field and checksum made to agree with the extra bytes.
    put_u32(&mut longer, 32, (bytes.len() + 8) as u32);
    longer.extend([0; 7]);
    assert_eq!(
        Model::from_bytes(&resealed(longer)).err(),
        Some(Error::InvalidData)
    );
}

#[test]
fn every_flipped_byte_is_invalid_and_past_the_checksum_loads_only_what_it_saves() {
    let bytes = small_model().to_bytes().unwrap();
    let mut accepted = 0;
    for at in 0..bytes.len() {
        for flip in [0x01u8, 0x80, 0xff] {
            let mut bad = bytes.clone();
            bad[at] ^= flip;
            assert_eq!(
                Model::from_bytes(&bad).err(),
                Some(Error::InvalidData),
                "byte {at} ^ {flip:#x}"
            );
            // Past the checksum: refused, or (a value that is still valid: an id, a coordinate)
            // loaded as exactly those bytes.
            if at < bytes.len() - 8 {
                let bad = resealed(bad);
                match Model::from_bytes(&bad) {
                    Err(e) => assert_eq!(e, Error::InvalidData),
                    Ok(m) => {
                        assert!(m.to_bytes().unwrap() == bad, "byte {at} ^ {flip:#x}");
                        accepted += 1;
                    }
                }
            }
        }
    }
    // Some changes make valid models (ids take any value), others do not.
    assert!(
        accepted > 0 && accepted < 3 * (bytes.len() - 8),
        "{accepted}"
    );
}

#[test]
fn large_models_load_on_two_threads_and_answer_identically() {
    // Above 16,384 triangles a load reads its sections in eight shares on two threads: the
    // loaded model is the saved one, query by query and count by count.
    let mut rng = Rng::new(26);
    let mut big = Mesh::sphere(1.0, 100, 90);
    big.tris.extend(Mesh::soup(&mut rng, 200, 1.0, 0.05).tris);
    assert!(big.tris.len() > 16_384);
    let other = Mesh::sphere(0.7, 30, 20);
    for (volume, collision) in [
        (VolumeKind::Rss, CollisionVolume::Obb),
        (VolumeKind::Hybrid, CollisionVolume::Ssv),
    ] {
        let (a, b) = (
            build(&big, volume, collision),
            build(&other, volume, collision),
        );
        let la = round_trip(&a);
        let ps = poses(&mut rng, 9, 0.8);
        let want = answers(&a, &b, &ps);
        assert_eq!(answers(&la, &b, &ps), want, "{volume:?} {collision:?}");
        assert_eq!(answers(&b, &la, &ps), answers(&b, &a, &ps));
    }
    // A flipped byte anywhere (any share of each section) is refused, with the
    // checksum as it was or recomputed so that the structural checks are reached; past the
    // checksum a load that succeeds gives back exactly those bytes.
    let bytes = build(&big, VolumeKind::Lss, CollisionVolume::Obb)
        .to_bytes()
        .unwrap();
    let [nodes, verts, faces, ids, added] = sections(&bytes);
    let mut at: Vec<usize> = (0..bytes.len()).step_by(bytes.len() / 150).collect();
    for [lo, hi] in [
        [nodes, verts],
        [verts, faces],
        [faces, ids],
        [ids, added],
        [added, bytes.len() - 8],
    ] {
        // At either end, and around two of the boundaries between shares (an eighth of each
        // section each).
        at.extend([lo, lo + 5, hi - 1]);
        for i in [1, 5] {
            let k = lo + (hi - lo) / 8 * i;
            at.extend([k - 200, k - 3, k, k + 3, k + 200]);
        }
    }
    for at in at {
        let mut bad = bytes.clone();
        bad[at] ^= 0x40;
        assert_eq!(
            Model::from_bytes(&bad).err(),
            Some(Error::InvalidData),
            "{at}"
        );
        if at < bytes.len() - 8 {
            let bad = resealed(bad);
            match Model::from_bytes(&bad) {
                Err(e) => assert_eq!(e, Error::InvalidData),
                Ok(m) => assert!(m.to_bytes().unwrap() == bad, "{at}"),
            }
        }
    }
}

/// A change made to saved bytes.
type Change<'a> = Box<dyn Fn(&mut Vec<u8>) + 'a>;

#[test]
fn structural_faults_are_caught_past_the_checksum() {
    let m = small_model();
    let bytes = m.to_bytes().unwrap();
    let n = m.num_triangles();
    let [nodes, verts, faces, _ids, added] = sections(&bytes);
    let node = |k: usize| nodes + k * NODE;
    let child = |k: usize, side: usize| node(k) + 144 + 4 * side;
    let try_with = |change: &dyn Fn(&mut Vec<u8>)| {
        let mut b = bytes.clone();
        change(&mut b);
        Model::from_bytes(&resealed(b))
    };
    // The resealing itself is right: unchanged bytes load.
    assert!(try_with(&|_| {}).is_ok());

    let cases: Vec<(&str, Change<'_>)> = vec![
        ("magic", Box::new(|b| b[0] = b'X')),
        ("version 3", Box::new(|b| put_u32(b, 8, 3))),
        (
            "version 1 (its checksum is another)",
            Box::new(|b| put_u32(b, 8, 1)),
        ),
        ("version 0", Box::new(|b| put_u32(b, 8, 0))),
        ("volume kind 4", Box::new(|b| put_u32(b, 12, 4))),
        ("collision volume 2", Box::new(|b| put_u32(b, 16, 2))),
        ("no triangles", Box::new(|b| put_u32(b, 20, 0))),
        (
            "one triangle more",
            Box::new(move |b| put_u32(b, 20, n as u32 + 1)),
        ),
        ("2^31 triangles", Box::new(|b| put_u32(b, 20, 1 << 31))),
        (
            "huge triangle count",
            Box::new(|b| put_u32(b, 20, u32::MAX)),
        ),
        ("no vertices", Box::new(|b| put_u32(b, 24, 0))),
        ("huge vertex count", Box::new(|b| put_u32(b, 24, u32::MAX))),
        ("reserved word", Box::new(|b| put_u32(b, 28, 1))),
        ("size field", Box::new(|b| put_u32(b, 32, 7))),
        ("size field high", Box::new(|b| put_u32(b, 36, 1))),
        // The tree.
        (
            "root as a child",
            Box::new(move |b| put_u32(b, child(1, 0), 0)),
        ),
        (
            "node its own child",
            Box::new(move |b| put_u32(b, child(2, 1), 2)),
        ),
        (
            "inner child out of range",
            Box::new(move |b| put_u32(b, child(0, 1), n as u32 - 1)),
        ),
        (
            "inner child 2^31 - 1",
            Box::new(move |b| put_u32(b, child(0, 0), i32::MAX as u32)),
        ),
        (
            "leaf out of range",
            Box::new(move |b| put_u32(b, child(n - 2, 0), (-(n as i32) - 1) as u32)),
        ),
        (
            "leaf i32::MIN",
            Box::new(move |b| put_u32(b, child(n - 2, 0), i32::MIN as u32)),
        ),
        (
            "shared child",
            Box::new(move |b| {
                let c = u32_at(b, child(0, 0));
                put_u32(b, child(0, 1), c)
            }),
        ),
        (
            "children swapped",
            Box::new(move |b| {
                let (c0, c1) = (u32_at(b, child(0, 0)), u32_at(b, child(0, 1)));
                put_u32(b, child(0, 0), c1);
                put_u32(b, child(0, 1), c0)
            }),
        ),
        // Node values.
        ("NaN axis", Box::new(move |b| put_f64(b, node(0), f64::NAN))),
        (
            "infinite origin",
            Box::new(move |b| put_f64(b, node(1) + 48, f64::INFINITY)),
        ),
        (
            "huge radius",
            Box::new(move |b| put_f64(b, node(0) + 88, 1e200)),
        ),
        (
            "negative radius",
            Box::new(move |b| put_f64(b, node(0) + 88, -1.0)),
        ),
        (
            "negative length",
            Box::new(move |b| put_f64(b, node(0) + 72, -0.5)),
        ),
        (
            "negative half extent",
            Box::new(move |b| put_f64(b, node(2) + 128, -1e-9)),
        ),
        (
            "NaN box centre",
            Box::new(move |b| put_f64(b, node(2) + 96, f64::NAN)),
        ),
        ("axis not unit", Box::new(move |b| put_f64(b, node(0), 2.0))),
        (
            "axes not orthogonal",
            Box::new(move |b| {
                for k in 0..3 {
                    let x = f64::from_le_bytes(b[node(0) + 8 * k..][..8].try_into().unwrap());
                    put_f64(b, node(0) + 24 + 8 * k, x);
                }
            }),
        ),
        // Vertices.
        (
            "NaN vertex",
            Box::new(move |b| put_f64(b, verts + 8, f64::NAN)),
        ),
        (
            "vertex beyond 1e150",
            Box::new(move |b| put_f64(b, verts, -2e150)),
        ),
        (
            "infinite vertex",
            Box::new(move |b| put_f64(b, verts + 16, f64::NEG_INFINITY)),
        ),
        // Faces.
        (
            "vertex index out of range",
            Box::new(move |b| put_u32(b, faces + 4, u32::MAX)),
        ),
        (
            "vertex index past first use",
            Box::new(move |b| put_u32(b, faces, 2)),
        ),
        (
            "vertices not numbered in first use",
            Box::new(move |b| {
                // The first face is [0, 1, 2]: [1, 0, 2] uses every vertex, out of order.
                assert_eq!([u32_at(b, faces), u32_at(b, faces + 4)], [0, 1]);
                put_u32(b, faces, 1);
                put_u32(b, faces + 4, 0);
            }),
        ),
        (
            "last vertex unused",
            Box::new(move |b| {
                let last = u32_at(b, 24) - 1;
                for at in (faces..faces + 12 * n).step_by(4) {
                    if u32_at(b, at) == last {
                        put_u32(b, at, 0);
                    }
                }
            }),
        ),
        // The order added.
        (
            "order added repeated",
            Box::new(move |b| {
                let k = u32_at(b, added);
                put_u32(b, added + 4, k)
            }),
        ),
        (
            "order added out of range",
            Box::new(move |b| put_u32(b, added + 8, n as u32)),
        ),
    ];
    for (what, change) in &cases {
        assert_eq!(
            try_with(change.as_ref()).err(),
            Some(Error::InvalidData),
            "{what}"
        );
    }
}

#[test]
fn volume_kinds_constrain_the_stored_lengths() {
    // A point swept sphere has no lengths, a line swept sphere one.
    let mut rng = Rng::new(26);
    let mesh = Mesh::soup(&mut rng, 12, 1.0, 0.5);
    for (volume, at) in [
        (VolumeKind::Pss, 72),
        (VolumeKind::Pss, 80),
        (VolumeKind::Lss, 80),
    ] {
        let bytes = build(&mesh, volume, CollisionVolume::Obb)
            .to_bytes()
            .unwrap();
        let mut b = bytes.clone();
        put_f64(&mut b, HEADER + at, 0.25);
        assert_eq!(
            Model::from_bytes(&resealed(b)).err(),
            Some(Error::InvalidData),
            "{volume:?} {at}"
        );
        // The same lengths are fine for a rectangle swept sphere model.
        let mut b = bytes.clone();
        put_f64(&mut b, HEADER + at, 0.25);
        put_u32(&mut b, 12, 0);
        assert!(Model::from_bytes(&resealed(b)).is_ok(), "{volume:?} {at}");
    }
}

/// A saved model of `n` triangles whose tree is rewired as a caterpillar (node i: leaf i and node
/// i + 1; the last node two leaves): leaves in slot order, depth `n`. With `fitted`, every node
/// has the root's volumes (which contain every triangle), so that the volumes are valid too.
fn caterpillar(n: usize, fitted: bool) -> Vec<u8> {
    let mut rng = Rng::new(27);
    let m = Mesh::soup(&mut rng, n, 1.0, 0.5).model();
    let mut b = m.to_bytes().unwrap();
    for i in 0..n - 1 {
        if fitted {
            b.copy_within(HEADER..HEADER + 144, HEADER + i * NODE);
        }
        let at = HEADER + i * NODE + 144;
        let leaf = |t: usize| (-(t as i32) - 1) as u32;
        put_u32(&mut b, at, leaf(i));
        let second = if i + 2 == n {
            leaf(i + 1)
        } else {
            i as u32 + 1
        };
        put_u32(&mut b, at + 4, second);
    }
    resealed(b)
}

#[test]
fn depth_is_bounded_and_a_tree_at_the_bound_is_queried_safely() {
    // pqp's hierarchies are at most 73 deep (the queries' fixed stacks are sized for it).
    for fitted in [false, true] {
        for n in [74, 500] {
            assert_eq!(
                Model::from_bytes(&caterpillar(n, fitted)).err(),
                Some(Error::InvalidData)
            );
        }
    }
    // The build's volumes on the rewired tree do not contain the triangles below them.
    assert_eq!(
        Model::from_bytes(&caterpillar(73, false)).err(),
        Some(Error::InvalidData)
    );
    let deep = Model::from_bytes(&caterpillar(73, true)).unwrap();
    // Every query runs and ends on it, against itself and against a normal model.
    let mut rng = Rng::new(28);
    let other = Mesh::soup(&mut rng, 50, 1.0, 0.5).model();
    let ps = poses(&mut rng, 12, 1.0);
    answers(&deep, &deep, &ps);
    answers(&deep, &other, &ps);
    answers(&other, &deep, &ps);
}

// The C functions.

/// A C model of `mesh`.
unsafe fn c_model(mesh: &Mesh) -> *mut pqp_model {
    unsafe {
        let m = pqp_model_create();
        for (i, t) in mesh.tris.iter().enumerate() {
            let rc = pqp_model_add_tri(m, t[0].as_ptr(), t[1].as_ptr(), t[2].as_ptr(), i as i32);
            assert_eq!(rc, PQP_OK);
        }
        assert_eq!(pqp_model_end(m), PQP_OK);
        m
    }
}

/// A C model's saved bytes.
unsafe fn c_saved(m: *const pqp_model) -> Vec<u8> {
    unsafe {
        let mut size = 0usize;
        assert_eq!(
            pqp_model_serialize(m, null_mut(), 0, &mut size),
            PQP_ERR_BUFFER_TOO_SMALL
        );
        let mut buf = vec![0u8; size];
        let mut written = 0usize;
        assert_eq!(
            pqp_model_serialize(m, buf.as_mut_ptr().cast(), size, &mut written),
            PQP_OK
        );
        assert_eq!(written, size);
        buf
    }
}

/// The exact distance (bits), its ids and counts, between C models at fixed poses.
unsafe fn c_distance(a: *const pqp_model, b: *const pqp_model) -> Vec<u64> {
    unsafe {
        let r = pqp_distance_result_create();
        let rot = [0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        let (mut out, id) = (Vec::new(), [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]);
        for t in [[0.3, 0.1, 0.0], [1.5, 0.0, 0.2], [0.0, 0.0, 3.0]] {
            let rc = pqp_distance(
                r,
                id.as_ptr(),
                [0.0; 3].as_ptr(),
                a,
                rot.as_ptr(),
                t.as_ptr(),
                b,
                0.0,
                0.0,
                2,
            );
            assert_eq!(rc, PQP_OK);
            out.push(pqp_distance_result_distance(r).to_bits());
            out.push(pqp_distance_result_num_bv_tests(r) as u64);
            out.push(pqp_distance_result_num_tri_tests(r) as u64);
        }
        pqp_distance_result_destroy(r);
        out
    }
}

#[test]
fn c_serialize_reports_sizes_and_codes_and_writes_nothing_on_error() {
    let mut rng = Rng::new(29);
    // SAFETY: every handle is live and every buffer as long as said.
    unsafe {
        let m = c_model(&Mesh::soup(&mut rng, 20, 1.0, 0.4));
        let bytes = c_saved(m);
        let (mut size, mut buf) = (usize::MAX, vec![0x5au8; bytes.len()]);
        // NULL arguments.
        assert_eq!(
            pqp_model_serialize(null(), buf.as_mut_ptr().cast(), buf.len(), &mut size),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_model_serialize(m, buf.as_mut_ptr().cast(), buf.len(), null_mut()),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(size, usize::MAX);
        // NULL buffer, whatever the capacity, and too small a capacity: the size, nothing else.
        for (p, cap) in [
            (null_mut(), 0),
            (null_mut(), usize::MAX),
            (buf.as_mut_ptr(), bytes.len() - 1),
            (buf.as_mut_ptr(), 0),
        ] {
            size = 0;
            assert_eq!(
                pqp_model_serialize(m, p.cast(), cap, &mut size),
                PQP_ERR_BUFFER_TOO_SMALL
            );
            assert_eq!(size, bytes.len());
            assert!(buf.iter().all(|&b| b == 0x5a));
        }
        // Enough room: the bytes, and the same as the Rust API's.
        let mut big = vec![0u8; bytes.len() + 3];
        assert_eq!(
            pqp_model_serialize(m, big.as_mut_ptr().cast(), big.len(), &mut size),
            PQP_OK
        );
        assert_eq!(size, bytes.len());
        assert!(big[..size] == bytes[..]);

        // Unbuilt models: nothing written, *size untouched.
        let fresh = pqp_model_create();
        let begun = pqp_model_create();
        assert_eq!(pqp_model_begin(begun, 4), PQP_OK);
        for u in [fresh, begun] {
            size = 7;
            assert_eq!(
                pqp_model_serialize(u, buf.as_mut_ptr().cast(), buf.len(), &mut size),
                PQP_ERR_UNPROCESSED_MODEL
            );
            assert_eq!(size, 7);
            assert!(buf.iter().all(|&b| b == 0x5a));
        }
        for h in [m, fresh, begun] {
            pqp_model_destroy(h);
        }
    }
}

#[test]
fn c_deserialize_replaces_any_model_and_a_failure_changes_nothing() {
    let mut rng = Rng::new(30);
    let (soup, torus) = (Mesh::soup(&mut rng, 30, 1.0, 0.4), shared("torus"));
    // SAFETY: every handle is live and every buffer as long as said.
    unsafe {
        let (a, b) = (c_model(&soup), c_model(&torus));
        let saved_b = c_saved(b);
        let want = c_distance(a, b);

        // A built model, one being built, a fresh one: each becomes b.
        let begun = pqp_model_create();
        assert_eq!(pqp_model_set_volume(begun, PQP_BV_PSS), PQP_OK);
        let t = &soup.tris[0];
        assert_eq!(
            pqp_model_add_tri(begun, t[0].as_ptr(), t[1].as_ptr(), t[2].as_ptr(), 5),
            PQP_OK
        );
        let built = c_model(&soup);
        // Its PQP 1.3 view, made before: replaced too.
        let (mut tris, mut nt) = (null(), 0);
        assert_eq!(pqp_model_tris(built, &mut tris, &mut nt), PQP_OK);
        assert_eq!(nt as usize, soup.tris.len());
        for target in [built, begun, pqp_model_create()] {
            assert_eq!(
                pqp_model_deserialize(target, saved_b.as_ptr().cast(), saved_b.len()),
                PQP_OK
            );
            assert_eq!(pqp_model_is_built(target), 1);
            assert_eq!(pqp_model_build_state(target), PQP_BUILD_STATE_PROCESSED);
            assert_eq!(pqp_model_num_tris(target) as usize, torus.tris.len());
            assert_eq!(c_distance(a, target), want);
            assert!(c_saved(target) == saved_b);
            let (mut tris, mut nt) = (null(), 0);
            assert_eq!(pqp_model_tris(target, &mut tris, &mut nt), PQP_OK);
            assert_eq!(nt as usize, torus.tris.len());
            let first = &*tris;
            assert_eq!((first.p1, first.id), (torus.tris[0][0], 0));
            // Again into the loaded model: still fine.
            assert_eq!(
                pqp_model_deserialize(target, saved_b.as_ptr().cast(), saved_b.len()),
                PQP_OK
            );
            pqp_model_destroy(target);
        }

        // Failures: NULL, truncated, corrupted; b is unchanged and answers as before.
        let mut corrupt = saved_b.clone();
        corrupt[HEADER + 3] ^= 0x10;
        assert_eq!(
            pqp_model_deserialize(null_mut(), saved_b.as_ptr().cast(), saved_b.len()),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_model_deserialize(b, null(), saved_b.len()),
            PQP_ERR_NULL_POINTER
        );
        for (p, len) in [
            (saved_b.as_ptr(), saved_b.len() - 1),
            (saved_b.as_ptr(), 0),
            (corrupt.as_ptr(), corrupt.len()),
            (saved_b.as_ptr(), usize::MAX),
        ] {
            // The last length is refused before any byte is read.
            assert_eq!(
                pqp_model_deserialize(b, p.cast(), len),
                PQP_ERR_INVALID_DATA
            );
            assert_eq!(pqp_model_num_tris(b) as usize, torus.tris.len());
            assert_eq!(c_distance(a, b), want);
        }
        // An unbuilt model stays unbuilt, with its triangles.
        let begun = pqp_model_create();
        assert_eq!(
            pqp_model_add_tri(begun, t[0].as_ptr(), t[1].as_ptr(), t[2].as_ptr(), 5),
            PQP_OK
        );
        assert_eq!(
            pqp_model_deserialize(begun, corrupt.as_ptr().cast(), corrupt.len()),
            PQP_ERR_INVALID_DATA
        );
        assert_eq!(pqp_model_build_state(begun), PQP_BUILD_STATE_BEGUN);
        assert_eq!(pqp_model_num_tris(begun), 1);
        assert_eq!(pqp_model_end(begun), PQP_OK);
        for h in [a, b, begun] {
            pqp_model_destroy(h);
        }
    }
}
