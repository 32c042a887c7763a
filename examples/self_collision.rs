//! Self-collision: a closed torus has none; pulling one vertex through the tube makes its
//! triangles cross the far side, and `self_collide` names the pairs.
//!
//! `cargo run --example self_collision`

use pqp::{ContactMode, Model, self_collide};

fn torus(n: usize, m: usize) -> Vec<[[f64; 3]; 3]> {
    let pt = |i: usize, j: usize| {
        let u = std::f64::consts::TAU * (i % n) as f64 / n as f64;
        let v = std::f64::consts::TAU * (j % m) as f64 / m as f64;
        let w = 1.0 + 0.3 * v.cos();
        [w * u.cos(), w * u.sin(), 0.3 * v.sin()]
    };
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..m {
            tris.push([pt(i, j), pt(i + 1, j), pt(i + 1, j + 1)]);
            tris.push([pt(i, j), pt(i + 1, j + 1), pt(i, j + 1)]);
        }
    }
    tris
}

fn model(tris: &[[[f64; 3]; 3]]) -> Model {
    Model::from_triangles(
        tris.iter()
            .enumerate()
            .map(|(k, t)| (t[0], t[1], t[2], k as i32)),
    )
    .unwrap()
}

fn main() {
    let mut tris = torus(48, 24);
    let clean = self_collide(&model(&tris), ContactMode::All).unwrap();
    println!(
        "closed torus, {} triangles: {} self-intersecting pairs",
        tris.len(),
        clean.num_pairs()
    );
    // Vertex (0, 0) is on the tube's outer equator; move it into the hole.
    let v = tris[0][0];
    for t in tris.iter_mut() {
        for p in t.iter_mut() {
            if *p == v {
                *p = [0.3 * v[0], 0.3 * v[1], v[2]];
            }
        }
    }
    let r = self_collide(&model(&tris), ContactMode::All).unwrap();
    println!("one vertex pulled through: {} pairs", r.num_pairs());
    for p in r.pairs() {
        println!("  triangles {} and {}", p.id1, p.id2);
    }
}
