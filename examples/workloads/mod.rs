//! The benchmark workloads the examples share, generated exactly as `bench/workloads.hpp` does
//! (same generator, same seed, same order of operations, so the same bits), and readers for the
//! reference models of `examples/models` (`.tris` meshes and `.path` motions).
// Each example uses part of this.
#![allow(dead_code)]

use pqp::Pose;

/// The same double as `bench::kPi` (3.14159265358979323846 rounds to it).
const PI: f64 = std::f64::consts::PI;

/// SplitMix64, as in bench/workloads.hpp.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        z ^ (z >> 31)
    }
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / 9007199254740992.0)
    }
}

/// Row-major rotation from a uniform unit quaternion (Shoemake), as in bench/workloads.hpp.
pub fn random_rotation(rng: &mut Rng) -> [[f64; 3]; 3] {
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

pub fn random_direction(rng: &mut Rng) -> [f64; 3] {
    let z = 2.0 * rng.uniform() - 1.0;
    let phi = 2.0 * PI * rng.uniform();
    let r = (1.0 - z * z).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

pub type Tri = ([f64; 3], [f64; 3], [f64; 3], i32);

/// The UV sphere of bench/workloads.hpp: 2 * nlon * (nlat - 1) triangles, ids in order.
pub fn uv_sphere(radius: f64, nlat: i32, nlon: i32) -> Vec<Tri> {
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
pub fn spheres_poses(per_gap: usize) -> (Vec<(f64, Pose, Pose)>, f64) {
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

pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// A `.tris` file: the triangle count, then nine coordinates per triangle; ids are indices.
pub fn read_tris(path: &std::path::Path) -> std::io::Result<Vec<Tri>> {
    let nums = read_numbers(path)?;
    let n = nums.first().copied().unwrap_or(0.0) as usize;
    let bad = || std::io::Error::new(std::io::ErrorKind::InvalidData, "short .tris file");
    if nums.len() < 1 + 9 * n {
        return Err(bad());
    }
    Ok((0..n)
        .map(|i| {
            let v = &nums[1 + 9 * i..10 + 9 * i];
            (
                [v[0], v[1], v[2]],
                [v[3], v[4], v[5]],
                [v[6], v[7], v[8]],
                i as i32,
            )
        })
        .collect())
}

/// A `.path` file: the frame count, then a row-major rotation and a translation per frame.
pub fn read_path(path: &std::path::Path) -> std::io::Result<Vec<Pose>> {
    let nums = read_numbers(path)?;
    let n = nums.first().copied().unwrap_or(0.0) as usize;
    if nums.len() < 1 + 12 * n {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "short .path file",
        ));
    }
    Ok((0..n)
        .map(|i| {
            let v = &nums[1 + 12 * i..13 + 12 * i];
            Pose::new(
                [[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]],
                [v[9], v[10], v[11]],
            )
        })
        .collect())
}

fn read_numbers(path: &std::path::Path) -> std::io::Result<Vec<f64>> {
    let text = std::fs::read_to_string(path)?;
    text.split_whitespace()
        .map(|w| {
            w.parse::<f64>()
                .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e))
        })
        .collect()
}
