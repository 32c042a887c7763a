//! The swept sphere volume family compared: for each volume choice (PSS, LSS, RSS, hybrid) the work
//! and time per query on three workloads, build time and memory, and collision on OBBs against
//! collision on the swept sphere volumes.
//!
//! ```text
//! cargo run --release --example volume_family [-- --models DIR] [--per-gap N] [--poses N]
//! ```
//!
//! Workloads:
//! - **spheres**: benchmark workload 1 (two UV spheres of 40,000 triangles, 400 random poses with
//!   surface gaps 0.001/0.01/0.1/1), exact distance, one result reused as `bench/pqp_bench.cpp`
//!   does; the generator is the bench's, shared with `bvtt_efficiency`.
//! - **bunny-torus**: bunny.tris at the identity, torus.tris at 4,000 random poses (uniform
//!   rotation; its centre at the bunny's centre plus an offset uniform in a cube of side twice the
//!   bunny's half-size); collide (all contacts), exact distance and tolerance 0.05, each with a
//!   fresh result.
//! - **tumbling tori**: torus1/torus2 along their paths, every frame in order, exact distance with
//!   the result reused (the triangle cache carries over).
//!
//! Prints a Markdown table; times are medians over the queries of a workload.

mod workloads;

use pqp::{
    CollideResult, CollisionVolume, ContactMode, DistanceOptions, DistanceResult, Model, Pose,
    Search, ToleranceResult, VolumeKind, collide_into, distance_into, tolerance_into,
};
use std::path::{Path, PathBuf};
use std::time::Instant;
use workloads::{
    Rng, Tri, median, random_rotation, read_path, read_tris, spheres_poses, uv_sphere,
};

/// Work and time of one workload: BV tests, triangle tests and median seconds per query.
#[derive(Default, Clone, Copy)]
struct Cost {
    bv: f64,
    tri: f64,
    median: f64,
}

impl Cost {
    fn cell(&self) -> String {
        format!(
            "{:.0} / {:.0} / {:.1}",
            self.bv,
            self.tri,
            self.median * 1e6
        )
    }
}

/// Runs `query` once per item, returning (BV tests, triangle tests) each time, and sums it up.
fn measure<T>(items: &[T], mut query: impl FnMut(&T) -> (u64, u64)) -> Cost {
    let (mut bv, mut tri) = (0u64, 0u64);
    let mut times = Vec::with_capacity(items.len());
    for it in items {
        let t = Instant::now();
        let (b, r) = query(it);
        times.push(t.elapsed().as_secs_f64());
        bv += b;
        tri += r;
    }
    let n = items.len().max(1) as f64;
    Cost {
        bv: bv as f64 / n,
        tri: tri as f64 / n,
        median: median(times),
    }
}

fn build(tris: &[Tri], volume: VolumeKind, collision: CollisionVolume) -> (Model, f64) {
    let t = Instant::now();
    let mut m = Model::new();
    m.set_volume(volume).expect("fresh model");
    m.set_collision_volume(collision).expect("fresh model");
    m.begin(tris.len()).expect("fresh model");
    for &(a, b, c, id) in tris {
        m.add_triangle(a, b, c, id).expect("finite input");
    }
    m.end().expect("model builds");
    (m, t.elapsed().as_secs_f64())
}

/// Centre and half-size (half the largest side) of a mesh's axis-aligned bounding box.
fn centre_and_half_size(tris: &[Tri]) -> ([f64; 3], f64) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (a, b, c, _) in tris {
        for v in [a, b, c] {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
    }
    let centre = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    let half = (0..3).map(|k| 0.5 * (hi[k] - lo[k])).fold(0.0, f64::max);
    (centre, half)
}

/// The bunny-torus poses of the torus (the bunny stays at the identity).
fn bunny_torus_poses(bunny: &[Tri], torus: &[Tri], count: usize) -> Vec<Pose> {
    let (bc, h) = centre_and_half_size(bunny);
    let (tc, _) = centre_and_half_size(torus);
    let mut rng = Rng(2);
    (0..count)
        .map(|_| {
            let r = random_rotation(&mut rng);
            let off = [0, 1, 2].map(|_| h * (2.0 * rng.uniform() - 1.0));
            // Put the torus's centre (R tc + T) at the bunny's centre plus the offset.
            let rtc = [0, 1, 2].map(|i| r[i][0] * tc[0] + r[i][1] * tc[1] + r[i][2] * tc[2]);
            let t = [0, 1, 2].map(|i| bc[i] + off[i] - rtc[i]);
            Pose::new(r, t)
        })
        .collect()
}

struct Args {
    models: PathBuf,
    per_gap: usize,
    poses: usize,
}

fn args() -> Args {
    let mut a = Args {
        models: PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/models"),
        per_gap: 100,
        poses: 4000,
    };
    let mut it = std::env::args().skip(1);
    while let Some(x) = it.next() {
        let mut value = || it.next().unwrap_or_default();
        match x.as_str() {
            "--models" => a.models = PathBuf::from(value()),
            "--per-gap" => a.per_gap = value().parse().expect("--per-gap N"),
            "--poses" => a.poses = value().parse().expect("--poses N"),
            _ => {
                eprintln!("usage: volume_family [--models DIR] [--per-gap N] [--poses N]");
                std::process::exit(2);
            }
        }
    }
    a
}

/// A model file from the models directory, or from /work/shared/models (the tumbling tori are not
/// copied into the repository).
fn model_file(dir: &Path, name: &str) -> Option<PathBuf> {
    [dir.join(name), Path::new("/work/shared/models").join(name)]
        .into_iter()
        .find(|p| p.exists())
}

fn main() {
    let a = args();
    let sphere = uv_sphere(1.0, 101, 200);
    let (sphere_poses, _) = spheres_poses(a.per_gap);
    let load = |name: &str| {
        let p = model_file(&a.models, name).unwrap_or_else(|| panic!("{name} not found"));
        read_tris(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
    };
    let (bunny, torus) = (load("bunny.tris"), load("torus.tris"));
    let bt_poses = bunny_torus_poses(&bunny, &torus, a.poses);
    let tumbling = match (
        model_file(&a.models, "torus1.path"),
        model_file(&a.models, "torus2.path"),
    ) {
        (Some(p1), Some(p2)) => {
            let (t1, t2) = (load("torus1.tris"), load("torus2.tris"));
            let (f1, f2) = (read_path(&p1).expect("path"), read_path(&p2).expect("path"));
            let frames: Vec<(Pose, Pose)> = f1.into_iter().zip(f2).collect();
            Some((t1, t2, frames))
        }
        _ => None,
    };
    let exact = DistanceOptions::exact();
    let id = Pose::identity();

    println!(
        "Cells: BV tests / triangle tests / median microseconds per query. spheres: {} poses; \
         bunny-torus: {} poses; tumbling tori: {} frames.\n",
        sphere_poses.len(),
        bt_poses.len(),
        tumbling.as_ref().map_or(0, |t| t.2.len())
    );
    println!(
        "| volume | spheres distance | bunny-torus distance | bunny-torus tolerance 0.05 | \
         tumbling tori distance | bunny-torus collide, OBB | bunny-torus collide, SSV | \
         build ms (sphere 40k) | bytes/triangle |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let volumes = [
        ("PSS", VolumeKind::Pss),
        ("LSS", VolumeKind::Lss),
        ("RSS", VolumeKind::Rss),
        ("Hybrid", VolumeKind::Hybrid),
    ];
    for (name, volume) in volumes {
        // Spheres: one model pair per volume; collision on OBBs is measured with OBB models, on
        // swept spheres with SSV models (the hierarchies are otherwise identical).
        let (s1, build_time) = build(&sphere, volume, CollisionVolume::Obb);
        let (s2, _) = build(&sphere, volume, CollisionVolume::Obb);
        let bytes = s1.memory_usage() as f64 / sphere.len() as f64;
        let mut reused = DistanceResult::new();
        let spheres = measure(&sphere_poses, |(_, p1, p2)| {
            distance_into(&mut reused, &s1, p1, &s2, p2, &exact).expect("query");
            (reused.stats.bv_tests, reused.stats.tri_tests)
        });

        let (mb, _) = build(&bunny, volume, CollisionVolume::Obb);
        let (mt, _) = build(&torus, volume, CollisionVolume::Obb);
        let (mb_ssv, _) = build(&bunny, volume, CollisionVolume::Ssv);
        let (mt_ssv, _) = build(&torus, volume, CollisionVolume::Ssv);
        let bt_distance = measure(&bt_poses, |p| {
            let mut r = DistanceResult::new();
            distance_into(&mut r, &mb, &id, &mt, p, &exact).expect("query");
            (r.stats.bv_tests, r.stats.tri_tests)
        });
        let bt_tolerance = measure(&bt_poses, |p| {
            let mut r = ToleranceResult::new();
            tolerance_into(&mut r, &mb, &id, &mt, p, 0.05, &Search::default()).expect("query");
            (r.stats.bv_tests, r.stats.tri_tests)
        });
        let mut contacts = [0usize; 2];
        let collide_obb = measure(&bt_poses, |p| {
            let mut r = CollideResult::new();
            collide_into(&mut r, &mb, &id, &mt, p, ContactMode::All).expect("query");
            contacts[0] += r.num_pairs();
            (r.stats.bv_tests, r.stats.tri_tests)
        });
        let collide_ssv = measure(&bt_poses, |p| {
            let mut r = CollideResult::new();
            collide_into(&mut r, &mb_ssv, &id, &mt_ssv, p, ContactMode::All).expect("query");
            contacts[1] += r.num_pairs();
            (r.stats.bv_tests, r.stats.tri_tests)
        });
        assert_eq!(
            contacts[0], contacts[1],
            "both collision volumes find the same pairs"
        );

        let tumble = tumbling.as_ref().map(|(t1, t2, frames)| {
            let (m1, _) = build(t1, volume, CollisionVolume::Obb);
            let (m2, _) = build(t2, volume, CollisionVolume::Obb);
            let mut reused = DistanceResult::new();
            measure(frames, |(p1, p2)| {
                distance_into(&mut reused, &m1, p1, &m2, p2, &exact).expect("query");
                (reused.stats.bv_tests, reused.stats.tri_tests)
            })
        });
        println!(
            "| {name} | {} | {} | {} | {} | {} | {} | {:.0} | {:.0} |",
            spheres.cell(),
            bt_distance.cell(),
            bt_tolerance.cell(),
            tumble.map_or("n/a".to_string(), |c| c.cell()),
            collide_obb.cell(),
            collide_ssv.cell(),
            build_time * 1e3,
            bytes
        );
    }
}
