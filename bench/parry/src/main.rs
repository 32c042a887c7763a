//! pqp-rs against parry3d-f64, in one process, on the same meshes, poses, points and rays: the
//! pair queries of `bench/pqp_bench.cpp`'s peers workload (collide all and first, exact distance,
//! tolerance), builds of 40,000 and 1,000,000 triangles, the closest point of a mesh to a point,
//! and ray casting on one thread. See README.md here and BENCHMARKS.md, "Against parry3d-f64".
//!
//! `cargo run --release --manifest-path bench/parry/Cargo.toml -- [--quick] [--rounds N]
//! [--models DIR] [--only NAME,...]` (names: spheres shells bunny coherent within build points
//! rays).
//!
//! Each row is timed in alternating rounds (the order of the two libraries swaps from round to
//! round); a round times each query on its own and keeps the median over the poses (rays: the
//! median over chunks of 200 rays, per ray), and the table gives the median over the rounds.
//! Before the timed rounds, an untimed pass compares the answers pose by pose.

#[path = "../../../examples/workloads/mod.rs"]
mod workloads;

use parry3d_f64::bounding_volume::BoundingVolume;
use parry3d_f64::math::{Matrix, Pose as PPose, Real, Rotation, Vector};
use parry3d_f64::query::{
    self, ClosestPoints, DefaultQueryDispatcher, PointQuery, QueryDispatcher, Ray, RayCast,
};
use parry3d_f64::shape::{Shape, TriMesh, TriMeshFlags};
use pqp::geometry::tri_distance;
use pqp::{
    CollideResult, ContactMode, DistanceOptions, DistanceResult, Model, Pose, Search, Vec3,
    closest_point, collide, distance, distance_into, ray_cast, signed_distance, tolerance,
    within_distance,
};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;
use workloads::{Rng, Tri, median, random_direction, random_rotation, read_path, read_tris};

struct Options {
    quick: bool,
    rounds: usize,
    models: PathBuf,
    only: Option<Vec<String>>,
}

impl Options {
    fn parse() -> Options {
        let mut o = Options {
            quick: false,
            rounds: 3,
            models: PathBuf::from(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../examples/models"
            )),
            only: None,
        };
        let mut args = std::env::args().skip(1);
        while let Some(a) = args.next() {
            let mut value = || {
                args.next()
                    .unwrap_or_else(|| die(&format!("{a} needs a value")))
            };
            match a.as_str() {
                "--quick" => o.quick = true,
                "--rounds" => o.rounds = value().parse().unwrap_or_else(|_| die("bad --rounds")),
                "--models" => o.models = PathBuf::from(value()),
                "--only" => o.only = Some(value().split(',').map(String::from).collect()),
                _ => die(&format!("unknown argument {a}")),
            }
        }
        o
    }

    fn wants(&self, name: &str) -> bool {
        self.only
            .as_ref()
            .is_none_or(|v| v.iter().any(|x| x == name))
    }

    fn shared(&self, file: &str) -> PathBuf {
        let p = self.models.join(file);
        if p.exists() {
            p
        } else {
            Path::new("/work/shared/models").join(file)
        }
    }
}

fn die(msg: &str) -> ! {
    eprintln!("pqp-bench-parry: {msg}");
    std::process::exit(2)
}

fn load(path: &Path) -> Vec<Tri> {
    read_tris(path).unwrap_or_else(|e| die(&format!("{}: {e}", path.display())))
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default()
}

// ----------------------------------------------------------------------------------------------
// The two libraries' models and poses

fn build_ours(tris: &[Tri]) -> Model {
    Model::from_triangles(tris.iter().copied()).unwrap_or_else(|e| die(&format!("ours: {e:?}")))
}

/// A parry `TriMesh` with its default flags, from the same triangle soup: three vertices per
/// triangle, as our model stores them (no vertex sharing to find).
fn build_parry(tris: &[Tri]) -> TriMesh {
    build_parry_with(tris, TriMeshFlags::empty())
}

/// As [`build_parry`], with `flags` (none: parry's defaults).
fn build_parry_with(tris: &[Tri], flags: TriMeshFlags) -> TriMesh {
    let mut vertices = Vec::with_capacity(3 * tris.len());
    let mut indices = Vec::with_capacity(tris.len());
    for (i, (a, b, c, _)) in tris.iter().enumerate() {
        for p in [a, b, c] {
            vertices.push(Vector::new(p[0], p[1], p[2]));
        }
        let k = 3 * i as u32;
        indices.push([k, k + 1, k + 2]);
    }
    TriMesh::with_flags(vertices, indices, flags).unwrap_or_else(|e| die(&format!("parry: {e:?}")))
}

/// Our pose as parry's (a unit quaternion and a translation).
fn to_parry(p: &Pose) -> PPose {
    let r = &p.rotation;
    let col = |j: usize| Vector::new(r[(0, j)], r[(1, j)], r[(2, j)]);
    let m = Matrix::from_cols(col(0), col(1), col(2));
    let t = &p.translation;
    PPose::from_parts(
        Vector::new(t.x, t.y, t.z),
        Rotation::from_mat3(&m).normalize(),
    )
}

/// parry's pose as ours.
fn from_parry(p: &PPose) -> Pose {
    let m = Matrix::from_quat(p.rotation);
    let (x, y, z) = (m.x_axis, m.y_axis, m.z_axis);
    let t = p.translation;
    Pose::new(
        [[x.x, y.x, z.x], [x.y, y.y, z.y], [x.z, y.z, z.z]],
        [t.x, t.y, t.z],
    )
}

fn world_tri(t: &Tri, p: &Pose) -> [Vec3; 3] {
    let v = |a: &[f64; 3]| p.transform_point(&Vec3::new(a[0], a[1], a[2]));
    [v(&t.0), v(&t.1), v(&t.2)]
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

fn rel_diff(a: f64, b: f64) -> f64 {
    let m = a.abs().max(b.abs());
    if m == 0.0 { 0.0 } else { (a - b).abs() / m }
}

// ----------------------------------------------------------------------------------------------
// parry's answers

/// Every intersecting triangle pair, with parry's own pieces: its BVH over each mesh (the first
/// mesh's leaves against the second mesh's box, then each such triangle's box against the second
/// mesh's tree: the descent parry's composite-composite contact manifolds make) and its
/// triangle-triangle intersection test through its default dispatcher.
fn parry_collide_all(
    m1: &TriMesh,
    p1: &PPose,
    m2: &TriMesh,
    p2: &PPose,
    out: &mut Vec<(u32, u32)>,
) {
    out.clear();
    let pos12 = p1.inv_mul(p2);
    let pos21 = pos12.inverse();
    let box2_in1 = m2.local_aabb().transform_by(&pos12);
    for i in m1.bvh().intersect_aabb(&box2_in1) {
        let t1 = m1.triangle(i);
        let box1_in2 = t1.compute_aabb(&pos21);
        for j in m2.bvh().intersect_aabb(&box1_in2) {
            let t2 = m2.triangle(j);
            let hit = DefaultQueryDispatcher.intersection_test(&pos12, &t1, &t2);
            if hit.is_ok_and(|h| h.intersecting) {
                out.push((i, j));
            }
        }
    }
}

/// Every triangle pair at distance at most `tol`, with parry's pieces as [`parry_collide_all`]:
/// its BVH of mesh 1 against mesh 2's box grown by `tol`, each such triangle's box grown by `tol`
/// against mesh 2's tree, and its triangle-triangle distance through its default dispatcher.
fn parry_within_pairs(
    m1: &TriMesh,
    p1: &PPose,
    m2: &TriMesh,
    p2: &PPose,
    tol: f64,
    out: &mut Vec<(u32, u32)>,
) {
    out.clear();
    let pos12 = p1.inv_mul(p2);
    let pos21 = pos12.inverse();
    let box2_in1 = m2.local_aabb().transform_by(&pos12).loosened(tol);
    for i in m1.bvh().intersect_aabb(&box2_in1) {
        let t1 = m1.triangle(i);
        let box1_in2 = t1.compute_aabb(&pos21).loosened(tol);
        for j in m2.bvh().intersect_aabb(&box1_in2) {
            let t2 = m2.triangle(j);
            let d = DefaultQueryDispatcher.distance(&pos12, &t1, &t2);
            if d.is_ok_and(|d| d.distance <= tol) {
                out.push((i, j));
            }
        }
    }
}

fn parry_first(m1: &TriMesh, p1: &PPose, m2: &TriMesh, p2: &PPose) -> bool {
    query::intersection_test(p1, m1, p2, m2).is_ok_and(|h| h.intersecting)
}

fn parry_distance(m1: &TriMesh, p1: &PPose, m2: &TriMesh, p2: &PPose) -> f64 {
    query::distance(p1, m1, p2, m2).map_or(f64::NAN, |d| d.distance)
}

/// Closer than `tol`: parry's closest points with a margin (intersecting or within it).
fn parry_within(m1: &TriMesh, p1: &PPose, m2: &TriMesh, p2: &PPose, tol: f64) -> bool {
    matches!(
        query::closest_points(p1, m1, p2, m2, tol),
        Ok(ClosestPoints::Intersecting | ClosestPoints::WithinMargin(..))
    )
}

// ----------------------------------------------------------------------------------------------
// Timing

/// Times `fs` (one closure per library, called with the query's index) over `n` queries in
/// `rounds` alternating rounds; per library, the median over rounds of the per-round median time
/// of a query, in seconds.
fn alternate(n: usize, rounds: usize, fs: &mut [&mut dyn FnMut(usize)]) -> Vec<f64> {
    let mut per_round = vec![Vec::new(); fs.len()];
    let mut times = Vec::with_capacity(n);
    for r in 0..rounds {
        for k in 0..fs.len() {
            let j = (k + r) % fs.len();
            times.clear();
            for i in 0..n {
                let t0 = Instant::now();
                (fs[j])(i);
                times.push(t0.elapsed().as_secs_f64());
            }
            per_round[j].push(median(times.clone()));
        }
    }
    per_round.into_iter().map(median).collect()
}

/// As [`alternate`], for queries too quick to time one by one: a round times the queries in
/// chunks of [`CHUNK`] and keeps the median chunk (so that a chunk during which the thread was
/// descheduled on the shared machine does not count), per query.
fn alternate_chunks(n: usize, rounds: usize, fs: &mut [&mut dyn FnMut(usize)]) -> Vec<f64> {
    let mut per_round = vec![Vec::new(); fs.len()];
    let mut times = Vec::new();
    for r in 0..rounds {
        for k in 0..fs.len() {
            let j = (k + r) % fs.len();
            times.clear();
            for start in (0..n).step_by(CHUNK) {
                let end = (start + CHUNK).min(n);
                let t0 = Instant::now();
                for i in start..end {
                    (fs[j])(i);
                }
                times.push(t0.elapsed().as_secs_f64() / (end - start) as f64);
            }
            per_round[j].push(median(times.clone()));
        }
    }
    per_round.into_iter().map(median).collect()
}

/// A timing of [`alternate`]'s form.
type Timing = fn(usize, usize, &mut [&mut dyn FnMut(usize)]) -> Vec<f64>;

/// [`alternate`] of two queries whose answers are only kept from being optimised away.
fn alternate_pair<A, B>(
    n: usize,
    rounds: usize,
    a: impl Fn(usize) -> A,
    b: impl Fn(usize) -> B,
) -> Vec<f64> {
    time_pair(alternate, n, rounds, a, b)
}

/// Two queries timed by `timing` (their answers only kept from being optimised away).
fn time_pair<A, B>(
    timing: Timing,
    n: usize,
    rounds: usize,
    a: impl Fn(usize) -> A,
    b: impl Fn(usize) -> B,
) -> Vec<f64> {
    timing(
        n,
        rounds,
        &mut [
            &mut |i| {
                black_box(a(i));
            },
            &mut |i| {
                black_box(b(i));
            },
        ],
    )
}

/// Queries per timed chunk in [`alternate_chunks`].
const CHUNK: usize = 200;

struct Row {
    workload: String,
    query: String,
    n: usize,
    ours: f64,
    parry: f64,
    unit: &'static str,
    answers: String,
}

struct Report {
    rows: Vec<Row>,
}

impl Report {
    fn add(
        &mut self,
        workload: &str,
        query: &str,
        n: usize,
        t: &[f64],
        unit: &'static str,
        answers: String,
    ) {
        let row = Row {
            workload: workload.into(),
            query: query.into(),
            n,
            ours: t[0],
            parry: t[1],
            unit,
            answers,
        };
        eprintln!(
            "{} / {}: ours {} parry {} ({:.2}x) [{}]",
            row.workload,
            row.query,
            fmt_time(row.ours, unit),
            fmt_time(row.parry, unit),
            row.parry / row.ours,
            row.answers
        );
        self.rows.push(row);
    }

    fn print(&self) {
        println!("| workload | query | n | ours | parry3d-f64 | parry / ours | answers |");
        println!("|---|---|---:|---:|---:|---:|---|");
        for r in &self.rows {
            println!(
                "| {} | {} | {} | {} | {} | {:.2} | {} |",
                r.workload,
                r.query,
                r.n,
                fmt_time(r.ours, r.unit),
                fmt_time(r.parry, r.unit),
                r.parry / r.ours,
                r.answers
            );
        }
    }
}

fn fmt_time(secs: f64, unit: &str) -> String {
    match unit {
        "ms" => format!("{:.1} ms", secs * 1e3),
        "rays/s" => format!("{:.3} Mrays/s", 1e-6 / secs),
        _ => {
            let us = secs * 1e6;
            if us >= 1000.0 {
                format!("{us:.0} us")
            } else {
                format!("{us:.2} us")
            }
        }
    }
}

// ----------------------------------------------------------------------------------------------
// Pair queries

struct PairCase {
    m1: Model,
    m2: Model,
    q1: TriMesh,
    q2: TriMesh,
    tris1: Vec<Tri>,
    tris2: Vec<Tri>,
    poses: Vec<(Pose, Pose)>,
    ppose: Vec<(PPose, PPose)>,
}

impl PairCase {
    /// Each pose's rotation is first rounded to parry's unit quaternion (normalised) and back,
    /// for both libraries: the `.path` files give their rotations to 6 digits (orthonormal to
    /// about 1e-6), and a library that uses R as given (ours) and one that keeps a unit
    /// quaternion (parry) would otherwise answer for poses 1e-7 apart.
    fn new(t1: &[Tri], t2: &[Tri], poses: Vec<(Pose, Pose)>) -> PairCase {
        let ppose: Vec<(PPose, PPose)> = poses
            .iter()
            .map(|(a, b)| (to_parry(a), to_parry(b)))
            .collect();
        let poses = ppose
            .iter()
            .map(|(a, b)| (from_parry(a), from_parry(b)))
            .collect();
        PairCase {
            m1: build_ours(t1),
            m2: build_ours(t2),
            q1: build_parry(t1),
            q2: build_parry(t2),
            tris1: t1.to_vec(),
            tris2: t2.to_vec(),
            poses,
            ppose,
        }
    }

    fn ours_distance(&self, i: usize) -> f64 {
        let (a, b) = &self.poses[i];
        distance(&self.m1, a, &self.m2, b, &DistanceOptions::exact())
            .unwrap()
            .distance
    }

    /// The least distance over every triangle pair (our exact triangle distance).
    fn brute_distance(&self, i: usize) -> f64 {
        let (a, b) = &self.poses[i];
        let w2: Vec<_> = self.tris2.iter().map(|t| world_tri(t, b)).collect();
        let mut best = f64::INFINITY;
        for t in &self.tris1 {
            let w1 = world_tri(t, a);
            for u in &w2 {
                best = best.min(tri_distance(&w1, u).distance);
            }
        }
        best
    }

    fn parry_distance(&self, i: usize) -> f64 {
        let (a, b) = &self.ppose[i];
        parry_distance(&self.q1, a, &self.q2, b)
    }
}

fn run_distance(
    rep: &mut Report,
    c: &PairCase,
    workload: &str,
    query: &str,
    rounds: usize,
    reuse: bool,
) {
    let n = c.poses.len();
    let (mut bad, mut parry_above, mut refereed, mut brute_ours) = (0, 0, 0, 0);
    let mut worst: f64 = 0.0;
    for i in 0..n {
        let (a, b) = (c.ours_distance(i), c.parry_distance(i));
        worst = worst.max(rel_diff(a, b));
        if !close(a, b, 1e-9) {
            bad += 1;
            parry_above += (b > a) as usize;
            // Referee the first few by brute force over every triangle pair.
            if refereed < 5 {
                refereed += 1;
                let brute = c.brute_distance(i);
                brute_ours += close(brute, a, 1e-9) as usize;
                eprintln!(
                    "{query}, pose {i}: ours {a:.17e}, parry {b:.17e}, brute force {brute:.17e}"
                );
            }
        }
    }
    let answers = if bad == 0 {
        format!("same distances (largest relative difference {worst:.1e})")
    } else {
        format!(
            "**{bad} poses differ by more than 1e-9 relative** (largest {worst:.1e}; parry's is the \
             larger on {parry_above}); brute force over all pairs gives ours on {brute_ours} of \
             {refereed} refereed"
        )
    };
    let mut cached = DistanceResult::new();
    let opts = DistanceOptions::exact();
    let mut ours = |i: usize| {
        let (a, b) = &c.poses[i];
        if reuse {
            distance_into(&mut cached, &c.m1, a, &c.m2, b, &opts).unwrap();
            black_box(cached.distance);
        } else {
            black_box(c.ours_distance(i));
        }
    };
    let mut theirs = |i: usize| {
        black_box(c.parry_distance(i));
    };
    let t = alternate(n, rounds, &mut [&mut ours, &mut theirs]);
    rep.add(workload, query, n, &t, "us", answers);
}

fn run_tolerance(rep: &mut Report, c: &PairCase, workload: &str, tol: f64, rounds: usize) {
    let n = c.poses.len();
    let search = Search::default();
    let ours_flag = |i: usize| {
        let (a, b) = &c.poses[i];
        tolerance(&c.m1, a, &c.m2, b, tol, &search)
            .unwrap()
            .closer_than_tolerance
    };
    let parry_flag = |i: usize| {
        let (a, b) = &c.ppose[i];
        parry_within(&c.q1, a, &c.q2, b, tol)
    };
    let (mut bad, mut closer) = (0, 0);
    for i in 0..n {
        let f = ours_flag(i);
        closer += f as usize;
        if f != parry_flag(i) {
            bad += 1;
        }
    }
    let answers = if bad == 0 {
        format!("same flags ({closer} closer)")
    } else {
        format!("**{bad} flags differ** (ours: {closer} closer)")
    };
    let t = alternate_pair(n, rounds, ours_flag, parry_flag);
    rep.add(workload, &format!("tolerance {tol}"), n, &t, "us", answers);
}

/// The pairs of `r` as sorted id pairs.
fn sorted_ids(r: &CollideResult) -> Vec<(u32, u32)> {
    let mut ids: Vec<(u32, u32)> = r
        .pairs()
        .iter()
        .map(|p| (p.id1 as u32, p.id2 as u32))
        .collect();
    ids.sort_unstable();
    ids
}

/// Every pair within `tol`: ours `within_distance`, parry's pieces ([`parry_within_pairs`]); pair
/// sets compared pose by pose.
fn run_within(rep: &mut Report, c: &PairCase, workload: &str, tol: f64, rounds: usize) {
    let n = c.poses.len();
    let mut pairs = Vec::new();
    let (mut poses_differ, mut total) = (0, 0);
    for i in 0..n {
        let (a, b) = &c.poses[i];
        let ours = sorted_ids(&within_distance(&c.m1, a, &c.m2, b, tol).unwrap());
        let (pa, pb) = &c.ppose[i];
        parry_within_pairs(&c.q1, pa, &c.q2, pb, tol, &mut pairs);
        pairs.sort_unstable();
        total += ours.len();
        poses_differ += (ours != pairs) as usize;
    }
    let answers = if poses_differ == 0 {
        format!("same pairs ({total} pairs)")
    } else {
        format!("**{poses_differ} poses differ** (ours {total} pairs)")
    };
    let mut ours = |i: usize| {
        let (a, b) = &c.poses[i];
        black_box(
            within_distance(&c.m1, a, &c.m2, b, tol)
                .unwrap()
                .num_pairs(),
        );
    };
    let mut theirs = |i: usize| {
        let (a, b) = &c.ppose[i];
        parry_within_pairs(&c.q1, a, &c.q2, b, tol, &mut pairs);
        black_box(pairs.len());
    };
    let t = alternate(n, rounds, &mut [&mut ours, &mut theirs]);
    rep.add(
        workload,
        &format!("within distance {tol}"),
        n,
        &t,
        "us",
        answers,
    );
}

fn run_collide(rep: &mut Report, c: &PairCase, workload: &str, all: bool, rounds: usize) {
    let n = c.poses.len();
    let mode = if all {
        ContactMode::All
    } else {
        ContactMode::First
    };
    let mut pairs = Vec::new();
    let answers = if all {
        // Pair sets, pose by pose; a pair only one library reports is refereed by our exact
        // triangle distance of the posed triangles (0: they touch).
        let (mut poses_differ, mut colliding, mut total) = (0, 0, 0);
        let (mut parry_only_apart, mut parry_only_touch, mut ours_only_touch, mut ours_only_apart) =
            (0, 0, 0, 0);
        for i in 0..n {
            let (a, b) = &c.poses[i];
            let ours = sorted_ids(&collide(&c.m1, a, &c.m2, b, ContactMode::All).unwrap());
            let (pa, pb) = &c.ppose[i];
            parry_collide_all(&c.q1, pa, &c.q2, pb, &mut pairs);
            pairs.sort_unstable();
            colliding += !ours.is_empty() as usize;
            total += ours.len();
            if ours != pairs {
                poses_differ += 1;
                let touch = |&(x, y): &(u32, u32)| {
                    let t1 = world_tri(&c.tris1[x as usize], a);
                    let t2 = world_tri(&c.tris2[y as usize], b);
                    tri_distance(&t1, &t2).distance == 0.0
                };
                for p in pairs.iter().filter(|p| ours.binary_search(p).is_err()) {
                    if touch(p) {
                        parry_only_touch += 1
                    } else {
                        parry_only_apart += 1
                    }
                }
                for p in ours.iter().filter(|p| pairs.binary_search(p).is_err()) {
                    if touch(p) {
                        ours_only_touch += 1
                    } else {
                        ours_only_apart += 1
                    }
                }
            }
        }
        if poses_differ == 0 {
            format!("same pairs ({colliding} colliding poses, {total} pairs)")
        } else {
            format!(
                "{poses_differ} poses differ ({colliding} colliding, {total} pairs ours); pairs only parry \
                 reports: {parry_only_apart} apart, {parry_only_touch} touching; only ours: \
                 {ours_only_touch} touching, {ours_only_apart} apart"
            )
        }
    } else {
        let (mut bad, mut colliding) = (0, 0);
        for i in 0..n {
            let (a, b) = &c.poses[i];
            let ours = collide(&c.m1, a, &c.m2, b, ContactMode::First)
                .unwrap()
                .colliding();
            let (pa, pb) = &c.ppose[i];
            colliding += ours as usize;
            if ours != parry_first(&c.q1, pa, &c.q2, pb) {
                bad += 1;
            }
        }
        if bad == 0 {
            format!("same verdicts ({colliding} colliding)")
        } else {
            format!("**{bad} verdicts differ** (ours: {colliding} colliding)")
        }
    };
    let mut ours = |i: usize| {
        let (a, b) = &c.poses[i];
        black_box(collide(&c.m1, a, &c.m2, b, mode).unwrap().num_pairs());
    };
    let mut theirs = |i: usize| {
        let (a, b) = &c.ppose[i];
        if all {
            parry_collide_all(&c.q1, a, &c.q2, b, &mut pairs);
            black_box(pairs.len());
        } else {
            black_box(parry_first(&c.q1, a, &c.q2, b));
        }
    };
    let t = alternate(n, rounds, &mut [&mut ours, &mut theirs]);
    let query = if all { "collide all" } else { "collide first" };
    rep.add(workload, query, n, &t, "us", answers);
}

// ----------------------------------------------------------------------------------------------
// Workloads (as bench/workloads.hpp and bench/pqp_bench.cpp's peers workload)

const SPHERE_LAT: i32 = 101;
const SPHERE_LON: i32 = 200;

fn bounds(tris: &[Tri]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for (a, b, c, _) in tris {
        for p in [a, b, c] {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    (lo, hi)
}

fn centre_and_radius(tris: &[Tri]) -> ([f64; 3], f64) {
    let (lo, hi) = bounds(tris);
    let c = [
        0.5 * (lo[0] + hi[0]),
        0.5 * (lo[1] + hi[1]),
        0.5 * (lo[2] + hi[2]),
    ];
    let r = (0..3).map(|k| 0.5 * (hi[k] - lo[k])).fold(0.0, f64::max);
    (c, r)
}

/// pqp_bench's bunny poses (seed 3): random rotations, the first model's box centre at the
/// origin, the second's at an offset uniform in the cube of half side `s`.
fn bunny_poses(m1: &[Tri], m2: &[Tri], s: f64, n: usize) -> Vec<(Pose, Pose)> {
    let mut rng = Rng(3);
    let (c1, _) = centre_and_radius(m1);
    let (c2, _) = centre_and_radius(m2);
    let place = |r: &[[f64; 3]; 3], c: &[f64; 3], off: &[f64; 3]| {
        let mut t = [0.0; 3];
        for k in 0..3 {
            t[k] = off[k] - (r[k][0] * c[0] + r[k][1] * c[1] + r[k][2] * c[2]);
        }
        t
    };
    (0..n)
        .map(|_| {
            let r1 = random_rotation(&mut rng);
            let r2 = random_rotation(&mut rng);
            let mut off = [0.0; 3];
            for x in &mut off {
                *x = (2.0 * rng.uniform() - 1.0) * s;
            }
            let t1 = place(&r1, &c1, &[0.0; 3]);
            let t2 = place(&r2, &c2, &off);
            (Pose::new(r1, t1), Pose::new(r2, t2))
        })
        .collect()
}

fn workload_spheres(rep: &mut Report, o: &Options) {
    let sphere = workloads::uv_sphere(1.0, SPHERE_LAT, SPHERE_LON);
    let (poses, _) = workloads::spheres_poses(if o.quick { 2 } else { 5 });
    let poses = poses.into_iter().map(|(_, a, b)| (a, b)).collect();
    let c = PairCase::new(&sphere, &sphere, poses);
    run_distance(rep, &c, "1 spheres", "distance", o.rounds, false);
}

fn workload_shells(rep: &mut Report, o: &Options, n: usize) {
    let inner = workloads::uv_sphere(1.0, SPHERE_LAT, SPHERE_LON);
    let outer = workloads::uv_sphere(1.05, SPHERE_LAT, SPHERE_LON);
    let mut rng = Rng(2);
    let poses = (0..n)
        .map(|_| {
            (
                Pose::identity(),
                Pose::new(random_rotation(&mut rng), [0.0; 3]),
            )
        })
        .collect();
    let c = PairCase::new(&inner, &outer, poses);
    run_distance(rep, &c, "2 shells", "distance exact", o.rounds, false);
}

/// Workloads 3 and 4's cases: the bunny against itself and against the torus, at the same poses.
fn bunny_cases(o: &Options) -> [(&'static str, PairCase); 2] {
    let bunny = load(&o.shared("bunny.tris"));
    let torus = load(&o.shared("torus.tris"));
    let (_, radius) = centre_and_radius(&bunny);
    let n = if o.quick { 100 } else { 1000 };
    [("bunny-bunny", &bunny), ("bunny-torus", &torus)].map(|(name, other)| {
        (
            name,
            PairCase::new(&bunny, other, bunny_poses(&bunny, other, radius, n)),
        )
    })
}

fn workload_bunny(rep: &mut Report, o: &Options) {
    for (name, c) in &bunny_cases(o) {
        run_collide(rep, c, &format!("3 {name}"), true, o.rounds);
        run_collide(rep, c, &format!("3 {name}"), false, o.rounds);
        run_distance(rep, c, &format!("4 {name}"), "distance", o.rounds, false);
        run_tolerance(rep, c, &format!("4 {name}"), 0.05, o.rounds);
    }
}

/// Every pair within a distance, on workload 4's poses.
fn workload_within(rep: &mut Report, o: &Options) {
    for (name, c) in &bunny_cases(o) {
        for tol in [0.0, 0.01] {
            run_within(rep, c, &format!("4 {name}"), tol, o.rounds);
        }
    }
}

fn workload_coherent(rep: &mut Report, o: &Options) {
    let t1 = load(&o.shared("torus1.tris"));
    let t2 = load(&o.shared("torus2.tris"));
    let read = |f: &str| read_path(&o.shared(f)).unwrap_or_else(|e| die(&format!("{f}: {e}")));
    let (p1, p2) = (read("torus1.path"), read("torus2.path"));
    let n = p1.len().min(p2.len()).min(if o.quick { 100 } else { 600 });
    let poses = p1.into_iter().zip(p2).take(n).collect();
    let c = PairCase::new(&t1, &t2, poses);
    run_distance(
        rep,
        &c,
        "5 coherent",
        "distance (ours: result reused)",
        o.rounds,
        true,
    );
}

fn workload_build(rep: &mut Report, tris: &[Tri], rounds: usize) {
    // A build is timed with its model's destruction, as in pqp_bench.
    let mut ours = |_| drop(black_box(build_ours(tris)));
    let mut theirs = |_| drop(black_box(build_parry(tris)));
    let t = alternate(1, rounds, &mut [&mut ours, &mut theirs]);
    let mem = build_ours(tris).memory_usage() as f64 / tris.len() as f64;
    rep.add(
        "build",
        &format!("{} triangles", tris.len()),
        1,
        &t,
        "ms",
        format!("{rounds} rounds; ours {mem:.0} B/triangle"),
    );
}

/// ray_bench's closed bumpy sphere: radius 1 + 0.05 sin(13 theta) sin(17 phi) on a
/// latitude-longitude grid, 2 * slices * (slices / 2 - 1) triangles.
fn bumpy_sphere(slices: usize) -> Vec<Tri> {
    use std::f64::consts::PI;
    let stacks = slices / 2;
    let pt = |i: usize, j: usize| {
        let th = PI * i as f64 / stacks as f64;
        let ph = 2.0 * PI * (j % slices) as f64 / slices as f64;
        let r = 1.0 + 0.05 * (13.0 * th).sin() * (17.0 * ph).sin();
        let s = if i == 0 || i == stacks { 0.0 } else { th.sin() };
        let z = if i == 0 {
            1.0
        } else if i == stacks {
            -1.0
        } else {
            th.cos()
        };
        [r * s * ph.cos(), r * s * ph.sin(), r * z]
    };
    let mut m = Vec::with_capacity(2 * slices * stacks);
    for i in 0..stacks {
        for j in 0..slices {
            let (a, b, c, d) = (pt(i, j), pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1));
            if i != 0 {
                m.push((a, b, d, m.len() as i32));
            }
            if i != stacks - 1 {
                m.push((b, c, d, m.len() as i32));
            }
        }
    }
    m
}

/// point_bench's queries: each a random pose of the model and a point uniform in the model's box
/// grown by half its size on each side.
fn workload_points(rep: &mut Report, name: &str, tris: &[Tri], n: usize, rounds: usize) {
    let ours_m = build_ours(tris);
    let parry_m = build_parry(tris);
    let (lo, hi) = bounds(tris);
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let mut rng = Rng(22);
    let queries: Vec<(Pose, Vec3)> = (0..n)
        .map(|_| {
            let r = random_rotation(&mut rng);
            let t = [(); 3].map(|_| 2.0 * rng.uniform() - 1.0);
            let p = [0, 1, 2].map(|k| lo[k] - 0.5 * size + 2.0 * size * rng.uniform());
            let pose = Pose::new(r, t);
            (pose, pose.transform_point(&Vec3::new(p[0], p[1], p[2])))
        })
        .collect();
    let pq: Vec<(PPose, Vector)> = queries
        .iter()
        .map(|(p, x)| (to_parry(p), Vector::new(x.x, x.y, x.z)))
        .collect();
    let ours = |i: usize| {
        let (p, x) = &queries[i];
        closest_point(&ours_m, p, x, f64::INFINITY)
            .unwrap()
            .distance
    };
    let theirs = |i: usize| {
        let (p, x) = &pq[i];
        let proj = parry_m.project_point(p, *x, false);
        (proj.point - *x).length()
    };
    let (mut bad, mut worst) = (0, 0.0f64);
    for i in 0..n {
        let (a, b) = (ours(i), theirs(i));
        worst = worst.max(rel_diff(a, b));
        bad += !close(a, b, 1e-9) as usize;
    }
    let answers = if bad == 0 {
        format!("same distances (largest relative difference {worst:.1e})")
    } else {
        format!("**{bad} distances differ by more than 1e-9 relative** (largest {worst:.1e})")
    };
    let t = alternate_pair(n, rounds, ours, theirs);
    rep.add(
        &format!("points {name}"),
        &format!("closest point ({} triangles)", tris.len()),
        n,
        &t,
        "us",
        answers,
    );
    // Signed distance: ours by the winding number; parry's projection on a mesh with its
    // pseudo-normals (`ORIENTED`, vertices merged so that it has a topology), inside when its
    // projection says so.
    let oriented = build_parry_with(
        tris,
        TriMeshFlags::MERGE_DUPLICATE_VERTICES | TriMeshFlags::ORIENTED,
    );
    let ours_signed = |i: usize| {
        let (p, x) = &queries[i];
        signed_distance(&ours_m, p, x).unwrap()
    };
    let theirs_signed = |i: usize| {
        let (p, x) = &pq[i];
        let proj = oriented.project_point(p, *x, false);
        let d = (proj.point - *x).length();
        if proj.is_inside { -d } else { d }
    };
    let (mut signs, mut bad, mut worst, mut inside) = (0, 0, 0.0f64, 0);
    for i in 0..n {
        let (a, b) = (ours_signed(i), theirs_signed(i));
        inside += (a < 0.0) as usize;
        if (a < 0.0) != (b < 0.0) && a != 0.0 && b != 0.0 {
            signs += 1;
        }
        worst = worst.max(rel_diff(a.abs(), b.abs()));
        bad += !close(a.abs(), b.abs(), 1e-9) as usize;
    }
    let answers = format!(
        "{} distances, {signs} signs differ (ours: {inside} inside)",
        if bad == 0 {
            format!("same (largest relative difference {worst:.1e})")
        } else {
            format!("**{bad} differ** (largest {worst:.1e})")
        }
    );
    let t = alternate_pair(n, rounds, ours_signed, theirs_signed);
    rep.add(
        &format!("points {name}"),
        "signed distance (parry: pseudo-normals)",
        n,
        &t,
        "us",
        answers,
    );
}

/// ray_bench's rays: from random points on the sphere of 2.5 model radii around the box centre,
/// aimed at random points of the ball of 0.8 radii, one in five in a random direction instead;
/// cast on the model in place, `max_t` infinite, one thread.
fn workload_rays(rep: &mut Report, name: &str, tris: &[Tri], n: usize, rounds: usize) {
    let ours_m = build_ours(tris);
    let parry_m = build_parry(tris);
    let (c, r) = centre_and_radius(tris);
    let mut rng = Rng(5);
    let rays: Vec<(Vec3, Vec3)> = (0..n)
        .map(|i| {
            let u = random_direction(&mut rng);
            let o = Vec3::new(
                c[0] + 2.5 * r * u[0],
                c[1] + 2.5 * r * u[1],
                c[2] + 2.5 * r * u[2],
            );
            let v = random_direction(&mut rng);
            if i % 5 == 4 {
                (o, Vec3::new(v[0], v[1], v[2]))
            } else {
                let s = 0.8 * r * rng.uniform().cbrt();
                (
                    o,
                    Vec3::new(c[0] + s * v[0], c[1] + s * v[1], c[2] + s * v[2]) - o,
                )
            }
        })
        .collect();
    let prays: Vec<Ray> = rays
        .iter()
        .map(|(o, d)| Ray::new(Vector::new(o.x, o.y, o.z), Vector::new(d.x, d.y, d.z)))
        .collect();
    let id = Pose::identity();
    let pid = PPose::IDENTITY;
    let ours = |i: usize| {
        let (o, d) = &rays[i];
        ray_cast(&ours_m, &id, o, d, f64::INFINITY)
            .unwrap()
            .map(|h| h.t)
    };
    let theirs = |i: usize| parry_m.cast_ray(&pid, &prays[i], Real::MAX, false);
    let (mut hits, mut differ, mut worst) = (0, 0, 0.0f64);
    for i in 0..n {
        match (ours(i), theirs(i)) {
            (Some(a), Some(b)) => {
                hits += 1;
                worst = worst.max(rel_diff(a, b));
                differ += !close(a, b, 1e-9) as usize;
            }
            (None, None) => {}
            _ => differ += 1,
        }
    }
    let answers = if differ == 0 {
        format!("same hits ({hits} hit, largest relative difference of t {worst:.1e})")
    } else {
        format!(
            "**{differ} rays differ** ({hits} hit by both; largest relative difference of t {worst:.1e})"
        )
    };
    let t = time_pair(alternate_chunks, n, rounds, ours, theirs);
    let query = format!("ray cast, 1 thread ({} triangles)", tris.len());
    rep.add(&format!("rays {name}"), &query, n, &t, "rays/s", answers);
    // Ours answers the point, normal and triangle too: parry's form that adds the normal and
    // the feature hit.
    let t = time_pair(alternate_chunks, n, rounds, ours, |i| {
        parry_m.cast_ray_and_get_normal(&pid, &prays[i], Real::MAX, false)
    });
    let query = "ray cast, parry with normal (`cast_ray_and_get_normal`)";
    rep.add(
        &format!("rays {name}"),
        query,
        n,
        &t,
        "rays/s",
        "as above".into(),
    );
}

fn main() {
    let o = Options::parse();
    let before = load_average();
    let start = Instant::now();
    let mut rep = Report { rows: Vec::new() };
    if o.wants("spheres") {
        workload_spheres(&mut rep, &o);
    }
    if o.wants("shells") {
        workload_shells(&mut rep, &o, if o.quick { 1 } else { 3 });
    }
    if o.wants("bunny") {
        workload_bunny(&mut rep, &o);
    }
    if o.wants("coherent") {
        workload_coherent(&mut rep, &o);
    }
    if o.wants("within") {
        workload_within(&mut rep, &o);
    }
    let big: usize = if o.quick { 200 } else { 1000 };
    if o.wants("build") {
        let s40k = workloads::uv_sphere(1.0, SPHERE_LAT, SPHERE_LON);
        workload_build(&mut rep, &s40k, o.rounds.max(5));
        let s1m = workloads::uv_sphere(1.0, (big / 2 + 1) as i32, big as i32);
        workload_build(&mut rep, &s1m, o.rounds);
    }
    let bunny = || load(&o.shared("bunny.tris"));
    if o.wants("points") {
        workload_points(
            &mut rep,
            "bunny",
            &bunny(),
            if o.quick { 2000 } else { 20000 },
            o.rounds,
        );
        workload_points(
            &mut rep,
            "bumpy sphere",
            &bumpy_sphere(big),
            if o.quick { 500 } else { 5000 },
            o.rounds,
        );
    }
    if o.wants("rays") {
        let n = if o.quick { 20000 } else { 200000 };
        workload_rays(&mut rep, "bunny", &bunny(), n, o.rounds);
        workload_rays(&mut rep, "bumpy sphere", &bumpy_sphere(big), n, o.rounds);
    }
    println!(
        "\npqp-rs against parry3d-f64: {} alternating rounds, median per query; load average {} before, {} after; {:.0} s\n",
        o.rounds,
        before,
        load_average(),
        start.elapsed().as_secs_f64()
    );
    rep.print();
}
