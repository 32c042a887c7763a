//! Pairs within a distance: the contacts of a gripper pad (a small flat patch) hovering over a
//! bumpy floor, with a margin, as a contact generator would ask for them.
//!
//! `cargo run --example within_distance`

use pqp::{Model, Pose, within_distance};

fn grid(n: usize, side: f64, z: impl Fn(f64, f64) -> f64) -> Model {
    let p = |i: usize, j: usize| {
        let (x, y) = (
            side * (i as f64 / n as f64 - 0.5),
            side * (j as f64 / n as f64 - 0.5),
        );
        [x, y, z(x, y)]
    };
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let k = tris.len() as i32;
            tris.push((p(i, j), p(i + 1, j), p(i + 1, j + 1), k));
            tris.push((p(i, j), p(i + 1, j + 1), p(i, j + 1), k + 1));
        }
    }
    Model::from_triangles(tris).unwrap()
}

fn main() {
    let floor = grid(60, 2.0, |x, y| 0.02 * (8.0 * x).sin() * (8.0 * y).cos());
    let pad = grid(4, 0.2, |_, _| 0.0);
    for height in [0.1, 0.04, 0.02, 0.0] {
        let at = Pose::from_translation([0.1, 0.05, height]);
        for margin in [0.0, 0.01, 0.03] {
            let r = within_distance(&floor, &Pose::identity(), &pad, &at, margin).unwrap();
            println!(
                "pad at height {height:.2}, margin {margin:.2}: {} triangle pairs",
                r.num_pairs()
            );
        }
    }
}
