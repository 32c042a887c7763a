//! BVTT efficiency of the exact distance query on benchmark workload 1 (spheres-distance).
//!
//! Regenerates the workload exactly as `bench/workloads.hpp` does (same generator, same seed, same
//! order of operations, so the same bits), runs the queries as `bench/pqp_bench.cpp` does (one result
//! object reused across the poses, the default search), and compares each query's bounding-volume tests with the
//! minimal BVTT (`pqp::diagnostics`). The printed sum of distances must equal the C++ program's
//! workload-1 checksum: that confirms both ran the same workload.
//!
//! ```text
//! cargo run --release --example bvtt_efficiency [-- --per-gap N] [--pqp-qsize N]
//! ```
//!
//! `--pqp-qsize N` runs PQP 1.3's search for queue size N instead of the default (2: depth-first,
//! nearer pair first; larger: a priority queue of N pairs), to see how the search order changes the
//! work.

use pqp::diagnostics::minimal_bvtt;
use pqp::{distance_into, DistanceOptions, DistanceResult, Model, Pose, Search};

/// The same double as `bench::kPi` (3.14159265358979323846 rounds to it).
const PI: f64 = std::f64::consts::PI;

/// SplitMix64, as in bench/workloads.hpp.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        z ^ (z >> 31)
    }
    fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / 9007199254740992.0)
    }
}

/// Row-major rotation from a uniform unit quaternion (Shoemake), as in bench/workloads.hpp.
fn random_rotation(rng: &mut Rng) -> [[f64; 3]; 3] {
    let u1 = rng.uniform();
    let u2 = rng.uniform();
    let u3 = rng.uniform();
    let s1 = (1.0 - u1).sqrt();
    let s2 = u1.sqrt();
    let a = 2.0 * PI * u2;
    let b = 2.0 * PI * u3;
    let w = s2 * b.cos();
    let x = s1 * a.sin();
    let y = s1 * a.cos();
    let z = s2 * b.sin();
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

fn random_direction(rng: &mut Rng) -> [f64; 3] {
    let z = 2.0 * rng.uniform() - 1.0;
    let phi = 2.0 * PI * rng.uniform();
    let r = (1.0 - z * z).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

type Tri = ([f64; 3], [f64; 3], [f64; 3], i32);

/// The UV sphere of bench/workloads.hpp: 2 * nlon * (nlat - 1) triangles, ids in order.
fn uv_sphere(radius: f64, nlat: i32, nlon: i32) -> Vec<Tri> {
    let vertex = |i: i32, j: i32| {
        let theta = PI * i as f64 / nlat as f64;
        let phi = 2.0 * PI * j as f64 / nlon as f64;
        let st = theta.sin();
        [
            radius * st * phi.cos(),
            radius * st * phi.sin(),
            radius * theta.cos(),
        ]
    };
    let mut m: Vec<Tri> = Vec::new();
    let mut push = |a, b, c| {
        let id = m.len() as i32;
        m.push((a, b, c, id));
    };
    for i in 0..nlat {
        for j in 0..nlon {
            let j1 = (j + 1) % nlon;
            if i == 0 {
                push(vertex(0, j), vertex(1, j), vertex(1, j1));
            } else if i == nlat - 1 {
                push(vertex(i, j), vertex(nlat, j), vertex(i, j1));
            } else {
                push(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j1));
                push(vertex(i, j), vertex(i + 1, j1), vertex(i, j1));
            }
        }
    }
    m
}

/// Workload 1's poses, in order: (gap, pose of sphere 1, pose of sphere 2), and the running sum of
/// their entries (R1, T1, R2, T2 per pose) for the generator's fingerprint.
fn spheres_poses(per_gap: usize) -> (Vec<(f64, Pose, Pose)>, f64) {
    let mut rng = Rng(1);
    let mut out = Vec::new();
    let mut sum = 0.0;
    for gap in [0.001, 0.01, 0.1, 1.0] {
        for _ in 0..per_gap {
            let r1 = random_rotation(&mut rng);
            let r2 = random_rotation(&mut rng);
            let dir = random_direction(&mut rng);
            let c = 2.0 + gap;
            let t2 = [dir[0] * c, dir[1] * c, dir[2] * c];
            for x in r1.iter().flatten().chain(&[0.0; 3]) {
                sum += x;
            }
            for x in r2.iter().flatten().chain(&t2) {
                sum += x;
            }
            out.push((gap, Pose::new(r1, [0.0; 3]), Pose::new(r2, t2)));
        }
    }
    (out, sum)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn main() {
    let mut per_gap = 100;
    let mut search = Search::default();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--per-gap" => {
                per_gap = args
                    .next()
                    .and_then(|v| v.parse().ok())
                    .expect("--per-gap N")
            }
            "--pqp-qsize" => {
                let qsize = args.next().and_then(|v| v.parse().ok());
                search = Search::pqp(qsize.expect("--pqp-qsize N"))
            }
            _ => {
                eprintln!("usage: bvtt_efficiency [--per-gap N] [--pqp-qsize N]");
                std::process::exit(2);
            }
        }
    }
    let mesh = uv_sphere(1.0, 101, 200);
    let (poses, pose_sum) = spheres_poses(per_gap);
    // The generator's fingerprint, as pqp_bench prints it: every pose entry, then every coordinate.
    let mut fingerprint = pose_sum;
    for (a, b, c, _) in &mesh {
        for x in a.iter().chain(b).chain(c) {
            fingerprint += x;
        }
    }
    println!(
        "workload 1: two UV spheres of {} triangles, {} poses; generator fingerprint {:.17e} (bits {:016x})",
        mesh.len(),
        poses.len(),
        fingerprint,
        fingerprint.to_bits()
    );
    let s1 = Model::from_triangles(mesh.iter().copied()).expect("sphere builds");
    let s2 = Model::from_triangles(mesh.iter().copied()).expect("sphere builds");

    println!(
        "| gap | poses | BV tests/q | minimal BVTT nodes/q | minimal bound tests/q | \
         efficiency (BV tests / minimal nodes) | BV tests / minimal bound tests | \
         median per-pose efficiency | tri tests/q | minimal leaf pairs/q |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut result = DistanceResult::new();
    let mut sum_d = 0.0;
    let mut total = [0.0f64; 5];
    let mut all_ratios = Vec::new();
    for chunk in poses.chunks(per_gap) {
        let mut acc = [0.0f64; 5]; // bv, nodes, bound tests, tri, leaves
        let mut ratios = Vec::new();
        for (_, p1, p2) in chunk {
            let opts = DistanceOptions {
                search,
                ..DistanceOptions::exact()
            };
            distance_into(&mut result, &s1, p1, &s2, p2, &opts).expect("query runs");
            sum_d += result.distance;
            let m = minimal_bvtt(&s1, p1, &s2, p2, result.distance).expect("walk runs");
            let row = [
                result.stats.bv_tests as f64,
                m.nodes_below as f64,
                m.bound_tests as f64,
                result.stats.tri_tests as f64,
                m.leaf_pairs_below as f64,
            ];
            for k in 0..5 {
                acc[k] += row[k];
                total[k] += row[k];
            }
            ratios.push(row[0] / row[1]);
        }
        let n = chunk.len() as f64;
        println!(
            "| {} | {} | {:.0} | {:.0} | {:.0} | {:.3} | {:.3} | {:.3} | {:.1} | {:.1} |",
            chunk[0].0,
            chunk.len(),
            acc[0] / n,
            acc[1] / n,
            acc[2] / n,
            acc[0] / acc[1],
            acc[0] / acc[2],
            median(ratios.clone()),
            acc[3] / n,
            acc[4] / n
        );
        all_ratios.extend(ratios);
    }
    let n = poses.len() as f64;
    println!(
        "| all | {} | {:.0} | {:.0} | {:.0} | {:.3} | {:.3} | {:.3} | {:.1} | {:.1} |",
        poses.len(),
        total[0] / n,
        total[1] / n,
        total[2] / n,
        total[0] / total[1],
        total[0] / total[2],
        median(all_ratios),
        total[3] / n,
        total[4] / n
    );
    println!("sum d = {sum_d:.12} (compare with pqp_bench's workload-1 checksum)");
}
