//! Deforming meshes: refit against rebuild, and self-collision (BENCHMARKS.md, "Refit" and
//! "Self-collision").
//!
//! Refit: a sheet rolling up and a sphere inflating into an ellipsoid, deformed progressively; at
//! each step the time to refit the model against the time to build one from the new triangles,
//! and the cost of the same queries (distance and collision against a small probe placed on the
//! surface; time and bound tests) on the two.
//!
//! Self-collision: `self_collide` against brute force over all pairs (with the same rule) and
//! against the collision query of the model with itself, and on a closed torus of a million
//! triangles.
//!
//! Pairs within a distance: `within_distance` against brute force over all pairs.
//!
//! `cargo run --release --example motion` (`-- --quick` for smaller meshes, `--closed-only` or
//! `--within-only` for one part)

mod workloads;

use pqp::query::self_contact;
use pqp::{ContactMode, DistanceOptions, Model, Pose, Vec3, collide, distance, self_collide};
use std::time::Instant;
use workloads::{Rng, Tri, median, read_tris, uv_sphere};

type T = [[f64; 3]; 3];

/// A deformation of the base mesh's points.
type Deform = Box<dyn Fn([f64; 3]) -> [f64; 3]>;

/// A labelled step of a deformation series.
type Step = (String, Deform);

fn model(tris: &[T]) -> Model {
    let mut m = Model::new();
    m.begin(tris.len()).unwrap();
    for (i, t) in tris.iter().enumerate() {
        m.add_triangle(t[0], t[1], t[2], i as i32).unwrap();
    }
    m.end().unwrap();
    m
}

fn plain(tris: &[Tri]) -> Vec<T> {
    tris.iter().map(|&(a, b, c, _)| [a, b, c]).collect()
}

/// Median seconds of `reps` runs of `f`.
fn time(reps: usize, mut f: impl FnMut()) -> f64 {
    median(
        (0..reps)
            .map(|_| {
                let s = Instant::now();
                f();
                s.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

/// An `n x n` grid sheet of side 2.
fn sheet(n: usize) -> Vec<T> {
    let p = |i: usize, j: usize| {
        [
            2.0 * i as f64 / n as f64 - 1.0,
            2.0 * j as f64 / n as f64 - 1.0,
            0.0,
        ]
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

/// The sheet rolled by `a` radians around an axis along y.
fn roll(p: [f64; 3], a: f64) -> [f64; 3] {
    if a == 0.0 {
        return p;
    }
    let r = 2.0 / a;
    let th = (p[0] + 1.0) / r;
    [r * th.sin() - 1.0, p[1], r * (1.0 - th.cos())]
}

/// Poses putting the probe (a sphere of radius 0.02 at the origin) at `offset` above random
/// triangles of `tris`, along their normals: the query workload on a deformed surface.
fn probe_poses(tris: &[T], offset: f64, n: usize, seed: u64) -> Vec<Pose> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let t = tris[(rng.uniform() * tris.len() as f64) as usize % tris.len()];
            let [a, b, c] = t.map(Vec3::from);
            let nrm = (b - a).cross(&(c - a));
            let nrm = if nrm.norm() > 0.0 {
                nrm.normalize()
            } else {
                Vec3::z()
            };
            let p = (a + b + c) / 3.0 + nrm * offset;
            Pose::from_translation([p.x, p.y, p.z])
        })
        .collect()
}

/// Median time (us) and mean bound tests of a distance query and of a collision query of `m`
/// against the probe at each pose.
fn query_cost(m: &Model, probe: &Model, near: &[Pose], touching: &[Pose]) -> [f64; 4] {
    let id = Pose::identity();
    let opts = DistanceOptions::exact();
    let mut dt = Vec::new();
    let mut db = 0u64;
    for p in near {
        let s = Instant::now();
        let r = distance(m, &id, probe, p, &opts).unwrap();
        dt.push(s.elapsed().as_secs_f64());
        db += r.stats.bv_tests;
    }
    let mut ct = Vec::new();
    let mut cb = 0u64;
    for p in touching {
        let s = Instant::now();
        let r = collide(m, &id, probe, p, ContactMode::All).unwrap();
        ct.push(s.elapsed().as_secs_f64());
        cb += r.stats.bv_tests;
    }
    [
        median(dt) * 1e6,
        db as f64 / near.len() as f64,
        median(ct) * 1e6,
        cb as f64 / touching.len() as f64,
    ]
}

fn refit_series(name: &str, base: &[T], steps: &[Step]) {
    let probe = model(&plain(&uv_sphere(0.02, 8, 16)));
    let mut m = model(base);
    println!("\n{name}: {} triangles", base.len());
    println!(
        "| step | refit ms | rebuild ms | rebuild/refit | distance us refit / rebuilt | bound tests refit / rebuilt | collide us refit / rebuilt | bound tests refit / rebuilt |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for (label, f) in steps {
        let now: Vec<T> = base.iter().map(|t| t.map(f)).collect();
        let refit = time(5, || m.refit(&now).unwrap());
        let mut rebuilt = model(&now);
        let rebuild = time(3, || rebuilt = model(&now));
        let near = probe_poses(&now, 0.1, 200, 7);
        let touching = probe_poses(&now, 0.0, 200, 8);
        let a = query_cost(&m, &probe, &near, &touching);
        let b = query_cost(&rebuilt, &probe, &near, &touching);
        println!(
            "| {label} | {:.2} | {:.1} | {:.1} | {:.1} / {:.1} | {:.0} / {:.0} | {:.1} / {:.1} | {:.0} / {:.0} |",
            refit * 1e3,
            rebuild * 1e3,
            rebuild / refit,
            a[0],
            b[0],
            a[1],
            b[1],
            a[2],
            b[2],
            a[3],
            b[3]
        );
    }
}

fn self_collision_row(name: &str, tris: &[T], brute: bool) {
    let m = model(tris);
    let mut found = 0;
    let mut tests = 0;
    let ours = time(3, || {
        let r = self_collide(&m, ContactMode::All).unwrap();
        found = r.num_pairs();
        tests = r.stats.tri_tests;
    });
    let id = Pose::identity();
    let mut pairs = 0;
    let with_collide = time(3, || {
        // Every colliding pair, both ways round and with each triangle against itself; filtering
        // out neighbours would take the rule on top.
        pairs = collide(&m, &id, &m, &id, ContactMode::All)
            .unwrap()
            .num_pairs();
    });
    let brute_time = if brute {
        let w: Vec<pqp::geometry::Tri> = tris.iter().map(|t| t.map(Vec3::from)).collect();
        let mut n = 0;
        let t = time(1, || {
            n = 0;
            for i in 0..w.len() {
                for j in i + 1..w.len() {
                    n += usize::from(self_contact(&w[i], &w[j]));
                }
            }
        });
        assert_eq!(n, found);
        format!("{:.1}", t * 1e3)
    } else {
        "-".into()
    };
    println!(
        "| {name} | {} | {found} | {:.2} | {tests} | {brute_time} | {:.1} ({pairs} pairs) |",
        tris.len(),
        ours * 1e3,
        with_collide * 1e3
    );
}

fn torus(big: f64, small: f64, n: usize, k: usize) -> Vec<T> {
    let pt = |i: usize, j: usize| {
        let u = std::f64::consts::TAU * (i % n) as f64 / n as f64;
        let v = std::f64::consts::TAU * (j % k) as f64 / k as f64;
        let w = big + small * v.cos();
        [w * u.cos(), w * u.sin(), small * v.sin()]
    };
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..k {
            let (a, b, c, d) = (pt(i, j), pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    tris
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (grid, lat, big) = if quick {
        (60, 60, 200)
    } else {
        (200, 200, 1000)
    };
    let models = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/models");
    if std::env::args().any(|a| a == "--within-only") {
        within_section(&models);
        return;
    }
    if std::env::args().any(|a| a == "--closed-only") {
        closed_torus(big);
        return;
    }

    let base = sheet(grid);
    let steps: Vec<Step> = [0.0, 0.5, 1.0, 2.0, 3.0, 4.5, 6.0]
        .into_iter()
        .map(|a: f64| {
            (
                format!("roll {a:.1} rad"),
                Box::new(move |p| roll(p, a)) as Deform,
            )
        })
        .collect();
    refit_series("Sheet rolling up", &base, &steps);

    let ball = plain(&uv_sphere(1.0, lat, 2 * lat));
    let steps: Vec<Step> = [0.0, 0.25, 0.5, 1.0, 2.0, 4.0]
        .into_iter()
        .map(|s: f64| {
            (
                format!("x {:.2}, y {:.2}", 1.0 + s, 1.0 + 0.5 * s),
                Box::new(move |p: [f64; 3]| [p[0] * (1.0 + s), p[1] * (1.0 + 0.5 * s), p[2]])
                    as Deform,
            )
        })
        .collect();
    refit_series("Sphere inflating into an ellipsoid", &ball, &steps);

    println!("\nSelf-collision");
    println!(
        "| mesh | triangles | pairs | self_collide ms | triangle tests | brute force ms | collide(m, m) ms |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for name in ["bunny.tris", "torus.tris"] {
        let tris = plain(&read_tris(&models.join(name)).unwrap());
        self_collision_row(name, &tris, true);
    }
    let mut bent = torus(1.0, 0.3, 40, 20);
    // A vertex pulled into the hole: its triangles cross the tube.
    let v = bent[0][0];
    for t in bent.iter_mut() {
        for p in t.iter_mut() {
            if *p == v {
                *p = [v[0] * 0.3, v[1] * 0.3, v[2]];
            }
        }
    }
    self_collision_row("torus 1.6k, one vertex pulled through", &bent, true);
    self_collision_row("UV sphere", &ball, false);
    closed_torus(big);
    within_section(&models);
}

/// Pairs within a distance of the bunny and the torus model against brute force over all pairs.
fn within_section(models: &std::path::Path) {
    let bunny = plain(&read_tris(&models.join("bunny.tris")).unwrap());
    let torus = plain(&read_tris(&models.join("torus.tris")).unwrap());
    let (ma, mb) = (model(&bunny), model(&torus));
    // Both about unit size, overlapping at offset 0.
    println!(
        "\nPairs within a distance: bunny ({}) against torus ({})",
        bunny.len(),
        torus.len()
    );
    println!("| offset | tolerance | pairs | within_distance ms | bound tests | brute force ms |");
    println!("|---|---:|---:|---:|---:|---:|");
    let id = Pose::identity();
    for offset in [0.0, 0.05] {
        let pose = Pose::from_translation([offset, 0.0, 0.0]);
        let wb: Vec<pqp::geometry::Tri> = torus
            .iter()
            .map(|t| t.map(|p| pose.transform_point(&Vec3::from(p))))
            .collect();
        let wa: Vec<pqp::geometry::Tri> = bunny.iter().map(|t| t.map(Vec3::from)).collect();
        for tol in [0.0, 0.001, 0.01, 0.05] {
            let mut r = None;
            let ours = time(3, || {
                r = Some(pqp::within_distance(&ma, &id, &mb, &pose, tol).unwrap())
            });
            let r = r.unwrap();
            let mut n = 0;
            let brute = time(1, || {
                n = 0;
                for ta in &wa {
                    for tb in &wb {
                        let near = pqp::geometry::tri_overlap(ta, tb)
                            || (tol > 0.0 && pqp::geometry::tri_distance(ta, tb).distance <= tol);
                        n += usize::from(near);
                    }
                }
            });
            assert_eq!(n, r.num_pairs());
            println!(
                "| {offset} | {tol} | {n} | {:.3} | {} | {:.0} |",
                ours * 1e3,
                r.stats.bv_tests,
                brute * 1e3
            );
        }
    }
}

/// Self-collision of a closed torus of `big * big` triangles, with no self-intersection.
fn closed_torus(big: usize) {
    let s = Instant::now();
    let huge = torus(1.0, 0.3, big, big / 2);
    let made = s.elapsed().as_secs_f64();
    let s = Instant::now();
    let m = model(&huge);
    let built = s.elapsed().as_secs_f64();
    let (s, c) = (Instant::now(), cpu_secs());
    let r = self_collide(&m, ContactMode::All).unwrap();
    let (once, cpu) = (s.elapsed().as_secs_f64(), cpu_secs() - c);
    println!(
        "\nClosed torus, {} triangles: self_collide {:.0} ms, {:.0} ms on the CPU ({} pairs, {} triangle tests, {} bound tests); build {:.0} ms; mesh made in {:.0} ms",
        huge.len(),
        once * 1e3,
        cpu * 1e3,
        r.num_pairs(),
        r.stats.tri_tests,
        r.stats.bv_tests,
        built * 1e3,
        made * 1e3
    );
}

/// Seconds this thread has run on a CPU (from /proc; 0 where there is none): with other work on
/// the machine, wall-clock time overstates what a query costs.
fn cpu_secs() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(0.0, |ns| ns * 1e-9)
}
