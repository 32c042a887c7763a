//! The check of the volumes on load: every built model passes; volumes edited not to contain their
//! triangles (and the checksum made to match) are refused.

use super::Version;
use super::codec::{HEADER, NODE, VERTEX, f64_at, u32_at};
use super::tests::{assert_same, random_bvh, saved_in};
use crate::bvh::{Bvh, CollisionVolume, NodeKind, VolumeKind};
use crate::error::Error;
use crate::geometry::Tri;
use crate::math::Vec3;
use crate::test_rng::{Random, Rng};

const KINDS: [VolumeKind; 4] = [
    VolumeKind::Rss,
    VolumeKind::Pss,
    VolumeKind::Lss,
    VolumeKind::Hybrid,
];

/// Models of the shapes a build meets: scattered, on a sphere, flat, all at one point, very large
/// and very small coordinates, long and thin.
fn models(rng: &mut Rng) -> Vec<Vec<(Tri, i32)>> {
    let mut out = Vec::new();
    let scatter = |rng: &mut Rng, n: usize, s: f64, flat: bool| -> Vec<(Tri, i32)> {
        (0..n)
            .map(|i| {
                let c = Vec3::from(rng.point(5.0 * s));
                let mut v = || {
                    let mut p = c + Vec3::from(rng.point(0.5 * s));
                    if flat {
                        p.z = 0.0;
                    }
                    p
                };
                ([v(), v(), v()], i as i32)
            })
            .collect()
    };
    for (n, s, flat) in [
        (300, 1.0, false),
        (200, 1.0, true),
        (100, 1e140, false),
        (100, 1e-140, false),
        (50, 3e-7, false),
    ] {
        out.push(scatter(rng, n, s, flat));
    }
    // A sphere of 20 x 20 quads; a thin strip; one point, many times.
    let mut sphere = Vec::new();
    let at = |i: usize, j: usize| {
        let (t, p) = (i as f64 * 0.157, j as f64 * 0.314);
        Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos()) * 3.0 + Vec3::repeat(1.0)
    };
    for i in 0..20 {
        for j in 0..20 {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            sphere.push(([a, b, c], sphere.len() as i32));
            sphere.push(([a, c, d], sphere.len() as i32));
        }
    }
    out.push(sphere);
    let strip: Vec<(Tri, i32)> = (0..100)
        .map(|i| {
            let x = i as f64;
            let p = |dx: f64, y: f64| Vec3::new(x + dx, y, 1e-3 * x);
            ([p(0.0, 0.0), p(1.0, 0.0), p(0.5, 0.01)], i)
        })
        .collect();
    out.push(strip);
    out.push(vec![([Vec3::repeat(2.5); 3], 0); 9]);
    out
}

#[test]
fn every_built_model_passes_in_both_versions() {
    let mut rng = Rng::new(29);
    for tris in models(&mut rng) {
        for (k, volume) in KINDS.into_iter().enumerate() {
            let collision = [CollisionVolume::Obb, CollisionVolume::Ssv][k % 2];
            let b = Bvh::build(tris.clone(), volume, collision).unwrap();
            for version in [Version::V1, Version::V2] {
                let bytes = saved_in(version, &b, volume, |_| {});
                for two_from in [1, usize::MAX] {
                    let (c, _) = Bvh::load_with(&bytes, two_from).unwrap();
                    assert_same(&b, &c);
                }
            }
        }
    }
}

/// Byte offset of a field of inner node `i`'s record.
fn field(i: usize, at: usize) -> usize {
    HEADER + i * NODE + at
}

fn put_f64(b: &mut [u8], at: usize, x: f64) {
    b[at..at + 8].copy_from_slice(&x.to_le_bytes());
}

/// Refused on one thread and on two, in both versions.
fn refused(b: &Bvh, volume: VolumeKind, change: impl Fn(&mut [u8]) + Copy, what: &str) {
    for version in [Version::V1, Version::V2] {
        let bytes = saved_in(version, b, volume, change);
        for two_from in [1, usize::MAX] {
            let r = Bvh::load_with(&bytes, two_from);
            assert_eq!(r.err(), Some(Error::InvalidData), "{what} {version:?}");
        }
    }
}

#[test]
fn volumes_that_do_not_contain_their_triangles_are_refused() {
    let mut rng = Rng::new(31);
    for volume in KINDS {
        let b = random_bvh(&mut rng, 60, volume, CollisionVolume::Obb);
        let inner = b.nodes.len();
        for i in 0..inner {
            // The swept sphere volume's radius, and each half extent of the box, shrunk.
            refused(
                &b,
                volume,
                |x| put_f64(x, field(i, 88), f64_at(x, field(i, 88)) * 0.5 - 1e-3),
                &format!("radius of {i}"),
            );
            for k in 0..3 {
                let at = field(i, 120 + 8 * k);
                refused(
                    &b,
                    volume,
                    |x| put_f64(x, at, (f64_at(x, at) * 0.5 - 1e-3).max(0.0)),
                    &format!("half extent {k} of {i}"),
                );
            }
            // Moved away: the origin, the centre.
            for at in [field(i, 48), field(i, 96)] {
                refused(
                    &b,
                    volume,
                    |x| put_f64(x, at, f64_at(x, at) + 20.0),
                    &format!("moved {i}"),
                );
            }
        }
        // Two inner nodes' volumes swapped, their children kept (each then holds the other's
        // triangles): siblings, and a node with its first inner child.
        let swap = |x: &mut [u8], i: usize, j: usize| {
            let (a, c) = (field(i, 0), field(j, 0));
            let mut tmp = [0u8; 144];
            tmp.copy_from_slice(&x[a..a + 144]);
            x.copy_within(c..c + 144, a);
            x[c..c + 144].copy_from_slice(&tmp);
        };
        for i in 0..inner {
            let kids = b.nodes[i].children.map(|c| c.kind());
            if let [NodeKind::Inner(j), NodeKind::Inner(k)] = kids {
                refused(&b, volume, |x| swap(x, j, k), &format!("siblings {j} {k}"));
            }
            if let NodeKind::Inner(j) = kids[0] {
                refused(
                    &b,
                    volume,
                    |x| swap(x, i, j),
                    &format!("parent {i} child {j}"),
                );
            }
        }
        // A vertex moved outside its triangles' volumes.
        let verts = HEADER + inner * NODE;
        for v in 0..b.verts.len() {
            refused(
                &b,
                volume,
                |x| {
                    let at = verts + v * VERTEX;
                    put_f64(x, at, f64_at(x, at) + 20.0)
                },
                &format!("vertex {v}"),
            );
        }
        // A triangle given another vertex (numbered in first use still: an earlier one) far
        // from it: the first triangle whose vertices are all new, given vertex 0.
        let faces = verts + b.verts.len() * VERTEX;
        let n = b.faces.len();
        if let Some(t) = (1..n).find(|&t| {
            let f = b.faces[t];
            let first = b.faces[..t].iter().flatten().max().map_or(0, |&m| m + 1);
            f.iter().all(|&k| k >= first) && (b.tri(t)[0] - b.verts[0]).norm() > 1.0
        }) {
            // Its later vertices are then used first later: keep the numbering by changing only
            // its last corner if that one is used again elsewhere, else skip.
            let last = b.faces[t][2];
            if b.faces[t + 1..].iter().flatten().any(|&k| k == last) {
                refused(
                    &b,
                    volume,
                    |x| x[faces + 12 * t + 8..][..4].copy_from_slice(&0u32.to_le_bytes()),
                    &format!("triangle {t}"),
                );
            }
        }
    }
}

#[test]
fn children_swapped_are_refused() {
    let mut rng = Rng::new(37);
    let b = random_bvh(&mut rng, 40, VolumeKind::Rss, CollisionVolume::Obb);
    for i in 0..b.nodes.len() {
        refused(
            &b,
            VolumeKind::Rss,
            |x| {
                let at = field(i, 144);
                let (c0, c1) = (u32_at(x, at), u32_at(x, at + 4));
                x[at..at + 4].copy_from_slice(&c1.to_le_bytes());
                x[at + 4..at + 8].copy_from_slice(&c0.to_le_bytes());
            },
            &format!("children of {i}"),
        );
    }
}
