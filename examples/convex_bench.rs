//! Timings of the convex module: hull construction, V-Clip cold and warm, penetration depth.
//!
//! `cargo run --release --example convex_bench`

use pqp::Pose;
use pqp::convex::{ConvexModel, ConvexPairCache, convex_distance, convex_penetration};
use std::time::Instant;

/// SplitMix64.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A point uniform in the unit ball.
    fn ball(&mut self) -> [f64; 3] {
        loop {
            let p = [
                2.0 * self.unit() - 1.0,
                2.0 * self.unit() - 1.0,
                2.0 * self.unit() - 1.0,
            ];
            if p.iter().map(|x| x * x).sum::<f64>() <= 1.0 {
                return p;
            }
        }
    }
    /// A point on the unit sphere.
    fn sphere(&mut self) -> [f64; 3] {
        let p = self.ball();
        let n = p.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-9);
        [p[0] / n, p[1] / n, p[2] / n]
    }
}

fn rotation(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let (x, y, z) = (axis[0] / n, axis[1] / n, axis[2] / n);
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
}

fn main() {
    let mut rng = Rng(1);
    println!("hull construction (from_points):");
    for (name, n, on_sphere) in [
        ("ball", 1_000, false),
        ("ball", 100_000, false),
        ("sphere", 1_000, true),
        ("sphere", 10_000, true),
    ] {
        let pts: Vec<[f64; 3]> = (0..n)
            .map(|_| if on_sphere { rng.sphere() } else { rng.ball() })
            .collect();
        let t = Instant::now();
        let m = ConvexModel::from_points(&pts).unwrap();
        println!(
            "  {n:>6} points in a {name:<6}: {:>8.2} ms, V {} E {} F {}",
            t.elapsed().as_secs_f64() * 1e3,
            m.num_vertices(),
            m.num_edges(),
            m.num_faces()
        );
    }
    let grid: Vec<[f64; 3]> = (0..20 * 20 * 20)
        .map(|i| {
            let f = |a: usize| a as f64 / 19.0;
            [f(i % 20), f((i / 20) % 20), f(i / 400)]
        })
        .collect();
    let t = Instant::now();
    let m = ConvexModel::from_points(&grid).unwrap();
    println!(
        "  {:>6} grid points (coplanar-rich): {:>8.2} ms, V {} F {}",
        grid.len(),
        t.elapsed().as_secs_f64() * 1e3,
        m.num_vertices(),
        m.num_faces()
    );

    for n in [50usize, 500, 5_000] {
        let a =
            ConvexModel::from_points(&(0..n).map(|_| rng.sphere()).collect::<Vec<_>>()).unwrap();
        let b =
            ConvexModel::from_points(&(0..n).map(|_| rng.sphere()).collect::<Vec<_>>()).unwrap();
        // A circling, spinning trajectory through separation and overlap.
        let frames = 20_000;
        let poses: Vec<Pose> = (0..frames)
            .map(|k| {
                let s = k as f64 * 0.001;
                Pose::new(
                    rotation([0.3, 1.0, 0.2], s * 3.0),
                    [2.5 * (s * 2.0).cos(), 2.2 * (s * 3.0).sin(), 0.3 * s.sin()],
                )
            })
            .collect();
        let here = Pose::identity();
        let mut cache = ConvexPairCache::new();
        let (mut warm_it, mut cold_it, mut hits) = (0u64, 0u64, 0usize);
        let t = Instant::now();
        for p in &poses {
            let r = convex_distance(&a, &here, &b, p, Some(&mut cache)).unwrap();
            warm_it += r.stats.iterations as u64;
            hits += r.intersecting as usize;
        }
        let warm = t.elapsed().as_secs_f64() / frames as f64;
        let t = Instant::now();
        for p in poses.iter().step_by(10) {
            let r = convex_distance(&a, &here, &b, p, None).unwrap();
            cold_it += r.stats.iterations as u64;
        }
        let cold = t.elapsed().as_secs_f64() / (frames / 10) as f64;
        let deep: Vec<&Pose> = poses.iter().step_by(200).collect();
        let t = Instant::now();
        let mut pen = 0;
        for p in &deep {
            if convex_penetration(&a, &here, &b, p, None)
                .unwrap()
                .intersecting
            {
                pen += 1;
            }
        }
        let pen_t = t.elapsed().as_secs_f64() / deep.len() as f64;
        println!(
            "two {n}-point sphere hulls (V {}, E {}): warm {:.2} us ({:.2} it), cold {:.2} us ({:.1} it), {:.0}% overlapping; penetration query {:.1} us ({pen} of {} overlapping)",
            a.num_vertices(),
            a.num_edges(),
            warm * 1e6,
            warm_it as f64 / frames as f64,
            cold * 1e6,
            cold_it as f64 / (frames / 10) as f64,
            100.0 * hits as f64 / frames as f64,
            pen_t * 1e6,
            deep.len()
        );
    }
}
