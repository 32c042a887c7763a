//! Saved models: how long a model of 40,000 and of 1,000,000 triangles takes to build (one
//! thread, `Model::end`, what `pqp_model_end` runs), to save (`Model::serialize_into` into a
//! buffer already allocated) and to load (`Model::from_bytes`: checksum, checks and copies, the
//! model's memory included), and the bytes per triangle; plus, for scale, a plain copy of the
//! buffer into freshly allocated memory (`to_vec`, 4 KiB pages: the load asks for huge pages).
//! Median of several rounds, the steps alternating within each round.
//!
//! `cargo run --release --example saved_models [rounds]`

mod workloads;

use pqp::Model;
use std::hint::black_box;
use std::time::Instant;
use workloads::{Tri, median, uv_sphere};

/// Seconds `f` takes, and what it returns.
fn timed<T>(f: impl FnOnce() -> T) -> (f64, T) {
    let t = Instant::now();
    let v = f();
    (t.elapsed().as_secs_f64(), v)
}

fn report(name: &str, tris: &[Tri], rounds: usize) {
    let (mut build, mut save, mut load, mut copy) = (vec![], vec![], vec![], vec![]);
    let mut size = 0;
    for _ in 0..rounds {
        let mut m = Model::new();
        m.begin(tris.len()).unwrap();
        for &(a, b, c, id) in tris {
            m.add_triangle(a, b, c, id).unwrap();
        }
        let (t, r) = timed(|| m.end());
        r.unwrap();
        build.push(t);

        // A buffer the program already has (allocated and touched).
        let mut buf = vec![1u8; m.serialized_size().unwrap()];
        let (t, r) = timed(|| m.serialize_into(&mut buf));
        size = r.unwrap();
        save.push(t);
        drop(m);

        let (t, loaded) = timed(|| Model::from_bytes(&buf).unwrap());
        load.push(t);
        // The loaded model is the saved one: it saves to the same bytes.
        assert!(loaded.to_bytes().unwrap() == buf);
        drop(loaded);

        let (t, c) = timed(|| buf.to_vec());
        copy.push(t);
        black_box(c);
    }
    let ms = |v: Vec<f64>| median(v) * 1e3;
    let (b, s, l, c) = (ms(build), ms(save), ms(load), ms(copy));
    println!(
        "| {name} | {} | {b:.1} | {s:.1} | {l:.1} | {:.1}x | {c:.1} | {:.1} |",
        tris.len(),
        b / l,
        size as f64 / tris.len() as f64
    );
}

fn main() {
    let rounds: usize = std::env::args()
        .nth(1)
        .map_or(5, |a| a.parse().expect("rounds"));
    println!(
        "| mesh | triangles | build (ms) | save (ms) | load (ms) | build / load | plain copy (ms) | \
         bytes/triangle |\n|---|---:|---:|---:|---:|---:|---:|---:|"
    );
    report("sphere 40k", &uv_sphere(1.0, 101, 200), rounds);
    report("sphere 1M", &uv_sphere(1.0, 501, 1000), rounds);
}
