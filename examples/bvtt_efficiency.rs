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

mod workloads;

use pqp::diagnostics::minimal_bvtt;
use pqp::{DistanceOptions, DistanceResult, Model, Search, distance_into};
use workloads::{median, read_path, read_tris, spheres_poses, uv_sphere};

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
         median per-pose efficiency | tri tests/q | minimal leaf pairs/q | \
         expanded minimal nodes with one child below/q | with none below/q |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut result = DistanceResult::new();
    let mut sum_d = 0.0;
    let mut total = [0.0f64; 7];
    let mut all_ratios = Vec::new();
    for chunk in poses.chunks(per_gap) {
        let mut acc = [0.0f64; 7]; // bv, nodes, bound tests, tri, leaves, single, none
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
                m.single_child_below as f64,
                m.no_child_below as f64,
            ];
            for k in 0..7 {
                acc[k] += row[k];
                total[k] += row[k];
            }
            ratios.push(row[0] / row[1]);
        }
        let n = chunk.len() as f64;
        println!(
            "| {} | {} | {:.0} | {:.0} | {:.0} | {:.3} | {:.3} | {:.3} | {:.1} | {:.1} | {:.0} | {:.0} |",
            chunk[0].0,
            chunk.len(),
            acc[0] / n,
            acc[1] / n,
            acc[2] / n,
            acc[0] / acc[1],
            acc[0] / acc[2],
            median(ratios.clone()),
            acc[3] / n,
            acc[4] / n,
            acc[5] / n,
            acc[6] / n
        );
        all_ratios.extend(ratios);
    }
    let n = poses.len() as f64;
    println!(
        "| all | {} | {:.0} | {:.0} | {:.0} | {:.3} | {:.3} | {:.3} | {:.1} | {:.1} | {:.0} | {:.0} |",
        poses.len(),
        total[0] / n,
        total[1] / n,
        total[2] / n,
        total[0] / total[1],
        total[0] / total[2],
        median(all_ratios),
        total[3] / n,
        total[4] / n,
        total[5] / n,
        total[6] / n
    );
    println!("sum d = {sum_d:.12} (compare with pqp_bench's workload-1 checksum)");
    coherent(search);
}

/// Workload 5 (the tumbling tori of /work/shared/models, every frame in order): the same ratio for
/// a query that reuses its result, so that under coherent motion it starts from the last query's
/// BVTT front (and its bounds), against one that searches from the root every frame.
fn coherent(search: Search) {
    let dir = std::path::Path::new("/work/shared/models");
    let files = ["torus1.tris", "torus2.tris", "torus1.path", "torus2.path"].map(|f| dir.join(f));
    if !files.iter().all(|f| f.exists()) {
        println!(
            "\n(workload 5 skipped: the tumbling tori are not in {})",
            dir.display()
        );
        return;
    }
    let t1 = Model::from_triangles(read_tris(&files[0]).expect("torus1")).expect("builds");
    let t2 = Model::from_triangles(read_tris(&files[1]).expect("torus2")).expect("builds");
    let (p1, p2) = (
        read_path(&files[2]).expect("path"),
        read_path(&files[3]).expect("path"),
    );
    let opts = DistanceOptions {
        search,
        ..DistanceOptions::exact()
    };
    println!("\nworkload 5: tumbling tori, {} frames in order", p1.len());
    println!(
        "| result | BV tests/q | minimal BVTT nodes/q | efficiency (BV tests / minimal nodes) | \
         tri tests/q | sum d |"
    );
    println!("|---|---:|---:|---:|---:|---|");
    for reused in [true, false] {
        let mut result = DistanceResult::new();
        let (mut bv, mut nodes, mut tri, mut sum_d) = (0.0, 0.0, 0.0, 0.0);
        for (a, b) in p1.iter().zip(&p2) {
            if !reused {
                result = DistanceResult::new();
            }
            distance_into(&mut result, &t1, a, &t2, b, &opts).expect("query runs");
            let m = minimal_bvtt(&t1, a, &t2, b, result.distance).expect("walk runs");
            bv += result.stats.bv_tests as f64;
            tri += result.stats.tri_tests as f64;
            nodes += m.nodes_below as f64;
            sum_d += result.distance;
        }
        let n = p1.len() as f64;
        println!(
            "| {} | {:.0} | {:.0} | {:.3} | {:.1} | {:.12} |",
            if reused {
                "reused (front tracking)"
            } else {
                "fresh each frame"
            },
            bv / n,
            nodes / n,
            bv / nodes,
            tri / n,
            sum_d
        );
    }
}
