//! Time of first contact: a thin plate thrown through a wall in one step is still caught, and the
//! tumbling tori of /work/shared/models are swept between frames of their path (their rotations
//! carry 6 digits), with the time per query and the number of advancement steps.
//!
//! `cargo run --release --example time_of_contact [models-dir]`

use pqp::{DistanceOptions, Model, Motion, Pose, distance, time_of_contact};
use std::time::Instant;

/// Numbers of a whitespace-separated text file.
fn numbers(path: &std::path::Path) -> Vec<f64> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect()
}

/// A `.tris` model (first number the count, then nine coordinates per triangle).
fn model(path: &std::path::Path) -> Model {
    let v = numbers(path);
    Model::from_triangles(v[1..].chunks_exact(9).enumerate().map(|(i, c)| {
        (
            [c[0], c[1], c[2]],
            [c[3], c[4], c[5]],
            [c[6], c[7], c[8]],
            i as i32,
        )
    }))
    .unwrap()
}

/// A `.path` file (first number the count, then a rotation row by row and a translation).
fn path(path: &std::path::Path) -> Vec<Pose> {
    let v = numbers(path);
    v[1..]
        .chunks_exact(12)
        .map(|c| {
            Pose::new(
                [[c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[6], c[7], c[8]]],
                [c[9], c[10], c[11]],
            )
        })
        .collect()
}

/// A flat box of half extents `h` centred on the origin (12 triangles).
/// The frames of a `.path` file as written: rotation row by row, then translation.
fn frames(path: &std::path::Path) -> Vec<[f64; 12]> {
    let v = numbers(path);
    v[1..]
        .chunks_exact(12)
        .map(|c| std::array::from_fn(|k| c[k]))
        .collect()
}

/// The largest |vertex| of a `.tris` file.
fn radius(path: &std::path::Path) -> f64 {
    let v = numbers(path);
    v[1..]
        .chunks_exact(3)
        .map(|p| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt())
        .fold(0.0, f64::max)
}

/// The angle of the turn from frame a's rotation to frame b's, `acos((trace(Ra^T Rb) - 1) / 2)`,
/// and the translation's change.
fn turn_and_shift(a: &[f64; 12], b: &[f64; 12]) -> (f64, [f64; 3]) {
    let trace: f64 = (0..9).map(|k| a[k] * b[k]).sum();
    let angle = ((trace - 1.0) / 2.0).clamp(-1.0, 1.0).acos();
    (angle, [b[9] - a[9], b[10] - a[10], b[11] - a[11]])
}

/// What a run of sweeps gives: queries, contacts (of which at t = 0), steps (total and most),
/// and the time per query in seconds.
struct Row {
    queries: u64,
    contacts: u64,
    at_start: u64,
    steps: u64,
    most: u64,
    per: f64,
}

/// Sweeps the tori from frame a to frame a + stride (a every max(stride, 4) frames) at the
/// tolerance `tol(a)`.
fn sweeps(
    (t1, t2): (&Model, &Model),
    (p1, p2): (&[Pose], &[Pose]),
    stride: usize,
    tol: impl Fn(usize) -> f64,
) -> Row {
    let n = p1.len().min(p2.len());
    let mut row = Row {
        queries: 0,
        contacts: 0,
        at_start: 0,
        steps: 0,
        most: 0,
        per: 0.0,
    };
    let start = Instant::now();
    for a in (0..n - stride).step_by(stride.max(4)) {
        let m1 = Motion::new(p1[a], p1[a + stride]);
        let m2 = Motion::new(p2[a], p2[a + stride]);
        let c = time_of_contact(t1, &m1, t2, &m2, tol(a)).unwrap();
        row.queries += 1;
        row.contacts += c.contact as u64;
        row.at_start += (c.toc == 0.0) as u64;
        row.steps += c.steps;
        row.most = row.most.max(c.steps);
    }
    row.per = start.elapsed().as_secs_f64() / row.queries as f64;
    row
}

fn slab(h: [f64; 3]) -> Model {
    let c = |i: usize| {
        let s = |bit: usize, k: usize| if i & bit == 0 { -h[k] } else { h[k] };
        [s(1, 0), s(2, 1), s(4, 2)]
    };
    let quads = [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ];
    Model::from_triangles(quads.iter().enumerate().flat_map(|(k, q)| {
        let k = 2 * k as i32;
        [
            (c(q[0]), c(q[1]), c(q[2]), k),
            (c(q[0]), c(q[2]), c(q[3]), k + 1),
        ]
    }))
    .unwrap()
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "/work/shared/models".into());
    let dir = std::path::Path::new(&dir);

    // A plate 1e-3 thick thrown 100 units through a wall 1e-3 thick, spinning as it goes.
    let wall = slab([0.0005, 1.0, 1.0]);
    let plate = slab([0.0005, 0.5, 0.5]);
    let still = Motion::new(Pose::identity(), Pose::identity());
    let throw = Motion::new(
        Pose::from_translation([-50.0, 0.0, 0.0]),
        Pose::new(
            [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]],
            [50.0, 0.0, 0.0],
        ),
    );
    let c = time_of_contact(&wall, &still, &plate, &throw, 1e-4).unwrap();
    println!(
        "thin plate: contact {} at t = {:.9} (distance {:.3e}, {} steps)",
        c.contact, c.toc, c.distance, c.steps
    );

    let (t1, t2) = (
        model(&dir.join("torus1.tris")),
        model(&dir.join("torus2.tris")),
    );
    let (p1, p2) = (
        path(&dir.join("torus1.path")),
        path(&dir.join("torus2.path")),
    );
    let n = p1.len().min(p2.len());
    // One exact distance query per frame, for scale.
    let start = Instant::now();
    for k in 0..n {
        distance(&t1, &p1[k], &t2, &p2[k], &DistanceOptions::exact()).unwrap();
    }
    let per_distance = start.elapsed().as_secs_f64() / n as f64;
    println!(
        "tori, {n} frames: exact distance {:.1} us per query (fresh result each)",
        per_distance * 1e6
    );
    println!(
        "| frames apart | tolerance | queries | contact (at t = 0) | time per query | steps: mean | max |"
    );
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for stride in [1, 10, 100] {
        for tol in [0.01, 0.001] {
            let r = sweeps((&t1, &t2), (&p1, &p2), stride, |_| tol);
            println!(
                "| {stride} | {tol} | {} | {} ({}) | {:.1} us ({:.1}x a distance) | {:.1} | {} |",
                r.queries,
                r.contacts,
                r.at_start,
                r.per * 1e6,
                r.per / per_distance,
                r.steps as f64 / r.queries as f64,
                r.most
            );
        }
    }

    // The motions of bench/toc_bench.cpp (against FCL's continuous collision), at the tolerance
    // FCL's time error implies, 1e-5 B (B bounding every point's speed: |dT2 - dT1| + angle1 r1 +
    // angle2 r2), and at 1e-12 of the scene's size (touching): the steps ours takes there.
    let (f1, f2) = (
        frames(&dir.join("torus1.path")),
        frames(&dir.join("torus2.path")),
    );
    let (r1, r2) = (
        radius(&dir.join("torus1.tris")),
        radius(&dir.join("torus2.tris")),
    );
    println!(
        "\n| frames apart | tolerance | queries | contact (at t = 0) | time per query | steps: mean | max |"
    );
    println!("| ---: | --- | ---: | ---: | ---: | ---: | ---: |");
    for stride in [1, 10, 100] {
        for touching in [false, true] {
            let tol = |a: usize| {
                let (angle1, shift1) = turn_and_shift(&f1[a], &f1[a + stride]);
                let (angle2, shift2) = turn_and_shift(&f2[a], &f2[a + stride]);
                let rel: f64 = (0..3)
                    .map(|k| (shift2[k] - shift1[k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                let speed = rel + angle1 * r1 + angle2 * r2;
                let scale = [&f1[a], &f1[a + stride], &f2[a], &f2[a + stride]]
                    .iter()
                    .map(|f| (f[9] * f[9] + f[10] * f[10] + f[11] * f[11]).sqrt() + r1 + r2)
                    .fold(1.0, f64::max);
                if touching {
                    1e-12 * scale
                } else {
                    (1e-5 * speed).max(1e-9 * scale)
                }
            };
            let r = sweeps((&t1, &t2), (&p1, &p2), stride, tol);
            println!(
                "| {stride} | {} | {} | {} ({}) | {:.1} us | {:.1} | {} |",
                if touching {
                    "1e-12 of the scene"
                } else {
                    "1e-5 B"
                },
                r.queries,
                r.contacts,
                r.at_start,
                r.per * 1e6,
                r.steps as f64 / r.queries as f64,
                r.most
            );
        }
    }
}
