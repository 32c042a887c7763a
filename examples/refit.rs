//! Refit: a cloth-like sheet sags step by step under a load; the model is refitted to each new
//! shape instead of rebuilt, and a ball under it is checked at every step.
//!
//! `cargo run --example refit`

use pqp::{ContactMode, DistanceOptions, Model, Pose, collide, distance};

/// An `n x n` grid sheet of side 2 at height `z(x, y)`.
fn sheet(n: usize, z: impl Fn(f64, f64) -> f64) -> Vec<[[f64; 3]; 3]> {
    let p = |i: usize, j: usize| {
        let (x, y) = (
            2.0 * i as f64 / n as f64 - 1.0,
            2.0 * j as f64 / n as f64 - 1.0,
        );
        [x, y, z(x, y)]
    };
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    tris
}

/// A small octahedron standing in for a ball of radius `r`.
fn ball(r: f64) -> Model {
    let v = [
        [r, 0.0, 0.0],
        [-r, 0.0, 0.0],
        [0.0, r, 0.0],
        [0.0, -r, 0.0],
        [0.0, 0.0, r],
        [0.0, 0.0, -r],
    ];
    let faces = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    Model::from_triangles(
        faces
            .iter()
            .enumerate()
            .map(|(k, f)| (v[f[0]], v[f[1]], v[f[2]], k as i32)),
    )
    .unwrap()
}

fn main() {
    let n = 40;
    let flat = sheet(n, |_, _| 0.0);
    let mut cloth = Model::from_triangles(
        flat.iter()
            .enumerate()
            .map(|(k, t)| (t[0], t[1], t[2], k as i32)),
    )
    .unwrap();
    let probe = ball(0.1);
    // The ball sits 0.5 below the sheet's centre.
    let under = Pose::from_translation([0.0, 0.0, -0.5]);
    for step in 0..=8 {
        let sag = 0.06 * step as f64;
        let now = sheet(n, |x, y| -sag * (1.0 - x * x) * (1.0 - y * y));
        cloth.refit(&now).expect("same count, finite coordinates");
        let d = distance(
            &cloth,
            &Pose::identity(),
            &probe,
            &under,
            &DistanceOptions::exact(),
        )
        .unwrap();
        let hit = collide(
            &cloth,
            &Pose::identity(),
            &probe,
            &under,
            ContactMode::First,
        )
        .unwrap();
        println!(
            "sag {sag:.2}: distance to the ball {:.4}{}",
            d.distance,
            if hit.colliding() { ", touching" } else { "" }
        );
    }
}
