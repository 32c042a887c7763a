//! Ray casting against brute force over all triangles (an independent Moller-Trumbore test in
//! world coordinates), watertightness on closed meshes with exactly representable vertices, the
//! special cases (grazing, parallel, starting on the surface, max_t, scales, degenerate
//! triangles), batches against single calls, and every bad input.

mod common;

use common::{
    Mesh, Random, RandomPqp, Rng, T, V, add, apply_tri, cross, dot, norm, point_tri, scale, sub,
};
use pqp::{Error, Model, Pose, RayHit, Vec3, ray_cast, ray_cast_batch};

/// A brute-force hit: the ray parameter, and how far inside the triangle the ray passes (the
/// least barycentric coordinate: negative outside).
struct BruteHit {
    t: f64,
    margin: f64,
    /// |cos| of the angle between the ray and the triangle's normal.
    cos: f64,
}

/// Moller-Trumbore on one world triangle, in plain floats; `None` for a triangle without area or a
/// ray parallel to its plane.
fn brute_hit(o: V, d: V, t: &T) -> Option<BruteHit> {
    let (e1, e2) = (sub(t[1], t[0]), sub(t[2], t[0]));
    let n = cross(e1, e2);
    if norm(n) == 0.0 {
        return None;
    }
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det == 0.0 {
        return None;
    }
    let s = sub(o, t[0]);
    let u = dot(s, p) / det;
    let q = cross(s, e1);
    let v = dot(d, q) / det;
    let tt = dot(e2, q) / det;
    Some(BruteHit {
        t: tt,
        margin: u.min(v).min(1.0 - u - v),
        cos: dot(n, d).abs() / (norm(n) * norm(d)),
    })
}

/// Checks the library's answer for one ray against brute force over the world triangles `w`:
/// a triangle the ray surely crosses (well inside it, not grazing, clear of 0 and max_t) bounds
/// the answer; where the nearest such triangle is clear of every borderline one, it is the answer.
/// Returns whether the case was decided (not borderline).
fn check_ray(w: &[T], o: V, d: V, max_t: f64, got: Option<RayHit>, what: &str) -> bool {
    const EDGE: f64 = 1e-7;
    let dn = norm(d);
    let extent = w
        .iter()
        .flat_map(|t| t.iter())
        .map(|v| norm(sub(*v, o)))
        .fold(0.0, f64::max);
    // A parameter tolerance: a few ulps of the scene, in the direction's units.
    let tol = 1e-9 * extent / dn;
    let (mut sure, mut border): (Option<(f64, usize)>, Option<f64>) = (None, None);
    for (i, t) in w.iter().enumerate() {
        let Some(h) = brute_hit(o, d, t) else {
            continue;
        };
        let clear_t = h.t > tol && h.t < max_t - tol;
        if h.margin > EDGE && h.cos > 1e-6 && clear_t {
            if sure.is_none_or(|(st, _)| h.t < st) {
                sure = Some((h.t, i));
            }
        } else if h.margin >= -EDGE && h.t > -tol && h.t <= max_t + tol {
            border = Some(border.map_or(h.t, |b: f64| b.min(h.t)));
        }
    }
    match got {
        None => {
            assert!(sure.is_none(), "{what}: missed {sure:?} ({o:?} {d:?})");
            border.is_none()
        }
        Some(h) => {
            let i = h.triangle as usize;
            assert!(h.t >= 0.0 && h.t <= max_t, "{what}: t {} max {max_t}", h.t);
            // The point is o + t d and lies on the triangle reported.
            let p = add(o, scale(d, h.t));
            let pv: V = h.point.into();
            assert!(norm(sub(p, pv)) <= 1e-12 * (extent + norm(o)), "{what}");
            let off = point_tri(pv, &w[i]);
            assert!(
                off <= 1e-12 * (extent + norm(o)),
                "{what}: point {off} off triangle {i}"
            );
            // The unit normal of (p2 - p1) x (p3 - p1).
            let n = cross(sub(w[i][1], w[i][0]), sub(w[i][2], w[i][0]));
            let want = scale(n, 1.0 / norm(n));
            assert!(
                norm(sub(h.normal.into(), want)) < 1e-6,
                "{what}: normal {:?} {want:?}",
                h.normal
            );
            if let Some((st, si)) = sure {
                assert!(
                    h.t <= st + tol,
                    "{what}: t {} beyond a sure hit at {st}",
                    h.t
                );
                if border.is_none_or(|b| b > st + tol) {
                    assert_eq!(i, si, "{what}: triangle");
                    assert!((h.t - st).abs() <= tol, "{what}: t {} vs {st}", h.t);
                    return true;
                }
            }
            false
        }
    }
}

/// Random rays around a mesh of radius about `r` at `pose`: from outside and inside, aimed at
/// random points, at vertices (exactly) and near edges.
fn random_ray(rng: &mut Rng, w: &[T], r: f64) -> (V, V) {
    let o = rng.point(2.0 * r);
    let d = match rng.below(4) {
        0 => rng.direction(),
        1 => {
            let t = &w[rng.below(w.len())];
            sub(t[rng.below(3)], o)
        }
        2 => {
            let t = &w[rng.below(w.len())];
            let s = rng.unit();
            sub(add(scale(t[0], s), scale(t[1], 1.0 - s)), o)
        }
        _ => sub(rng.point(r), o),
    };
    let d = scale(d, rng.log_uniform(1e-3, 1e3));
    (o, d)
}

fn cast(m: &Model, pose: &Pose, o: V, d: V, max_t: f64) -> Option<RayHit> {
    ray_cast(m, pose, &o.into(), &d.into(), max_t).unwrap()
}

fn load(name: &str) -> Mesh {
    let root = env!("CARGO_MANIFEST_DIR");
    let path = ["/work/shared/models", &format!("{root}/examples/models")]
        .iter()
        .map(|d| format!("{d}/{name}"))
        .find(|p| std::path::Path::new(p).exists())
        .expect("model file");
    let text = std::fs::read_to_string(path).unwrap();
    let mut nums = text.split_whitespace().map(|s| s.parse::<f64>().unwrap());
    let n = nums.next().unwrap() as usize;
    let tris = (0..n)
        .map(|_| {
            let mut v = || {
                [
                    nums.next().unwrap(),
                    nums.next().unwrap(),
                    nums.next().unwrap(),
                ]
            };
            [v(), v(), v()]
        })
        .collect();
    Mesh { tris }
}

fn against_brute_force(mesh: &Mesh, rng: &mut Rng, poses: usize, rays: usize, what: &str) {
    let model = mesh.model();
    let r = mesh
        .tris
        .iter()
        .flat_map(|t| t.iter())
        .map(|v| norm(*v))
        .fold(0.0, f64::max);
    let mut decided = 0;
    for _ in 0..poses {
        let pose = rng.pose(r);
        let w = mesh.world(&pose);
        for _ in 0..rays {
            let (o, d) = random_ray(rng, &w, r + norm(pose.translation.into()));
            let max_t = if rng.below(5) == 0 {
                rng.range(0.0, 2.0)
            } else {
                f64::INFINITY
            };
            let got = cast(&model, &pose, o, d, max_t);
            decided += usize::from(check_ray(&w, o, d, max_t, got, what));
        }
    }
    // Most cases are decided (not borderline): the comparison has teeth.
    assert!(decided * 3 > poses * rays, "{what}: only {decided} decided");
}

#[test]
fn shared_models_against_brute_force() {
    let mut rng = Rng(2201);
    for name in ["bunny.tris", "torus.tris"] {
        against_brute_force(&load(name), &mut rng, 6, 150, name);
    }
}

#[test]
fn random_meshes_against_brute_force() {
    let mut rng = Rng(2202);
    for iter in 0..30 {
        let mesh = match iter % 3 {
            0 => {
                let n = 1 + rng.below(400);
                Mesh::soup(&mut rng, n, 1.0, 0.3)
            }
            1 => Mesh::sphere(1.0, 5 + rng.below(20), 3 + rng.below(20)),
            _ => Mesh::torus(1.0, 0.3, 5 + rng.below(20), 3 + rng.below(20)),
        };
        against_brute_force(&mesh, &mut rng, 2, 60, &format!("mesh {iter}"));
    }
}

/// A closed mesh given by vertices and index triangles, every shared vertex stored once.
struct Closed {
    verts: Vec<V>,
    faces: Vec<[usize; 3]>,
}

impl Closed {
    fn mesh(&self) -> Mesh {
        Mesh {
            tris: self
                .faces
                .iter()
                .map(|f| [self.verts[f[0]], self.verts[f[1]], self.verts[f[2]]])
                .collect(),
        }
    }

    /// The box [0, n]^3 with each face cut into n x n unit squares of two triangles, integer
    /// vertices, diagonals in alternating directions.
    fn grid_box(n: usize) -> Closed {
        let mut index = std::collections::HashMap::new();
        let mut verts = Vec::new();
        let mut id = |p: [i64; 3]| {
            *index.entry(p).or_insert_with(|| {
                verts.push(p.map(|c| c as f64));
                verts.len() - 1
            })
        };
        let mut faces = Vec::new();
        let n = n as i64;
        for axis in 0..3 {
            for side in [0, n] {
                for i in 0..n {
                    for j in 0..n {
                        let p = |a: i64, b: i64| {
                            let mut q = [0; 3];
                            q[axis] = side;
                            q[(axis + 1) % 3] = a;
                            q[(axis + 2) % 3] = b;
                            q
                        };
                        let c = [p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)].map(&mut id);
                        if (i + j) % 2 == 0 {
                            faces.push([c[0], c[1], c[2]]);
                            faces.push([c[0], c[2], c[3]]);
                        } else {
                            faces.push([c[0], c[1], c[3]]);
                            faces.push([c[1], c[2], c[3]]);
                        }
                    }
                }
            }
        }
        Closed { verts, faces }
    }

    /// A sphere of latitude-longitude triangles, the seam and poles closed by shared indices.
    fn sphere(slices: usize, stacks: usize) -> Closed {
        let mut verts = vec![[0.0, 0.0, 1.0]];
        for i in 1..stacks {
            let th = std::f64::consts::PI * i as f64 / stacks as f64;
            for j in 0..slices {
                let ph = std::f64::consts::TAU * j as f64 / slices as f64;
                verts.push([th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()]);
            }
        }
        verts.push([0.0, 0.0, -1.0]);
        let south = verts.len() - 1;
        let ring = |i: usize, j: usize| 1 + (i - 1) * slices + j % slices;
        let mut faces = Vec::new();
        for j in 0..slices {
            faces.push([0, ring(1, j), ring(1, j + 1)]);
            faces.push([south, ring(stacks - 1, j + 1), ring(stacks - 1, j)]);
            for i in 1..stacks - 1 {
                let (a, b, c, d) = (
                    ring(i, j),
                    ring(i + 1, j),
                    ring(i + 1, j + 1),
                    ring(i, j + 1),
                );
                faces.push([a, b, c]);
                faces.push([a, c, d]);
            }
        }
        Closed { verts, faces }
    }
}

/// From a point inside a closed mesh every ray hits it: rays through every vertex and through
/// points on the edges (midpoints, and points a few ulps off), at random poses.
#[test]
fn watertight_through_vertices_and_edges() {
    let mut rng = Rng(2203);
    // The shapes, a point inside, and for boxes their side.
    let shapes = [
        (Closed::grid_box(6), [3.0, 3.0, 3.0], Some(6.0)),
        (Closed::grid_box(5), [2.5, 1.25, 3.75], Some(5.0)),
        (Closed::sphere(24, 13), [0.0, 0.0, 0.0], None),
        (Closed::sphere(7, 5), [0.125, -0.25, 0.0625], None),
    ];
    for (shape, inside, side) in &shapes {
        let model = shape.mesh().model();
        let mut targets: Vec<V> = shape.verts.clone();
        for f in &shape.faces {
            for k in 0..3 {
                let (a, b) = (shape.verts[f[k]], shape.verts[f[(k + 1) % 3]]);
                targets.push(scale(add(a, b), 0.5));
                let s = rng.unit();
                targets.push(add(scale(a, s), scale(b, 1.0 - s)));
            }
        }
        for pose in [Pose::identity(), rng.pose(10.0), rng.pose(1e3)] {
            let o = pose.transform_point(&Vec3::from(*inside));
            for p in &targets {
                let d = pose.transform_point(&Vec3::from(*p)) - o;
                let hit = ray_cast(&model, &pose, &o, &d, f64::INFINITY).unwrap();
                let hit = hit.unwrap_or_else(|| panic!("slipped through at {p:?}"));
                assert!((hit.t - 1.0).abs() < 1e-9, "{p:?}: t {}", hit.t);
            }
        }
        // On the boxes (integer vertices), axis-aligned rays through the targets from points level
        // with the inside point: exact arithmetic all the way. (Not from the surface: a ray starting
        // on it hits at 0, tests/ray_origins.rs.)
        let Some(side) = side else {
            continue;
        };
        for p in &targets {
            for axis in 0..3 {
                let mut o = *p;
                o[axis] = inside[axis];
                let mut d = [0.0; 3];
                d[axis] = p[axis] - inside[axis];
                if d[axis] == 0.0 || o.iter().any(|&c| c == 0.0 || c == *side) {
                    continue;
                }
                let hit = cast(&model, &Pose::identity(), o, d, f64::INFINITY);
                let hit = hit.unwrap_or_else(|| panic!("axis {axis} slipped through at {p:?}"));
                assert!(hit.t <= 1.0 + 1e-12, "{p:?}: t {}", hit.t);
            }
        }
    }
}

/// From outside, axis-aligned rays through every vertex and edge of the grid box's faces hit the
/// face they are aimed at, at the exact parameter.
#[test]
fn axis_rays_through_grid_edges_and_vertices() {
    let n = 4;
    let model = Closed::grid_box(n).mesh().model();
    let here = Pose::identity();
    let nf = n as f64;
    for axis in 0..3 {
        for (start, dir) in [(-2.0, 1.0), (nf + 2.0, -1.0)] {
            for i in 0..=2 * n {
                for j in 0..=2 * n {
                    // Vertices, edge midpoints and square centres (i, j odd or even halves).
                    let (a, b) = (i as f64 * 0.5, j as f64 * 0.5);
                    let mut o = [0.0; 3];
                    o[axis] = start;
                    o[(axis + 1) % 3] = a;
                    o[(axis + 2) % 3] = b;
                    let mut d = [0.0; 3];
                    d[axis] = dir * 0.5;
                    let hit = cast(&model, &here, o, d, f64::INFINITY).expect("hit");
                    assert_eq!(hit.t, 4.0, "{o:?}");
                }
            }
        }
    }
}

#[test]
fn grazing_parallel_and_on_the_surface() {
    let model = Closed::grid_box(4).mesh().model();
    let here = Pose::identity();
    // In the plane of the top face: the face is edge-on, the side face's edge is hit.
    let h = cast(
        &model,
        &here,
        [-1.0, 2.0, 4.0],
        [1.0, 0.0, 0.0],
        f64::INFINITY,
    )
    .unwrap();
    assert_eq!(h.t, 1.0);
    assert_eq!(h.normal.x.abs(), 1.0);
    // Just above it: nothing; just below: the side face.
    assert!(
        cast(
            &model,
            &here,
            [-1.0, 2.0, 4.0 + 1e-12],
            [1.0, 0.0, 0.0],
            9.0
        )
        .is_none()
    );
    let h = cast(
        &model,
        &here,
        [-1.0, 2.0, 4.0 - 1e-12],
        [1.0, 0.0, 0.0],
        9.0,
    )
    .unwrap();
    assert_eq!(h.t, 1.0);
    // Grazing at a tiny angle: hits the side face, with the point on it.
    let h = cast(
        &model,
        &here,
        [-1.0, 2.0, 4.0],
        [1.0, 0.0, -1e-9],
        f64::INFINITY,
    )
    .unwrap();
    assert!((h.t - 1.0).abs() < 1e-12 && h.normal.x.abs() == 1.0);
    // Starting on a face, inwards or outwards: a hit at 0.
    for dz in [1.0, -1.0] {
        let h = cast(
            &model,
            &here,
            [1.3, 2.1, 0.0],
            [0.2, 0.1, dz],
            f64::INFINITY,
        )
        .unwrap();
        assert_eq!(h.t, 0.0);
        assert_eq!(h.point, Vec3::new(1.3, 2.1, 0.0));
    }
    // Starting on an edge and a vertex.
    assert_eq!(
        cast(&model, &here, [1.0, 2.5, 0.0], [0.3, 0.1, 1.0], 1.0)
            .unwrap()
            .t,
        0.0
    );
    assert_eq!(
        cast(&model, &here, [1.0, 2.0, 4.0], [0.3, 0.1, -1.0], 1.0)
            .unwrap()
            .t,
        0.0
    );
    // From inside, the far face.
    let h = cast(
        &model,
        &here,
        [1.0, 1.0, 1.0],
        [0.0, 0.0, 2.0],
        f64::INFINITY,
    )
    .unwrap();
    assert_eq!(h.t, 1.5);
    assert_eq!(h.normal, Vec3::new(0.0, 0.0, 1.0));
}

#[test]
fn max_t_cuts_off() {
    let model = Closed::grid_box(4).mesh().model();
    let here = Pose::identity();
    let (o, d) = ([1.5, 1.25, -2.0], [0.0, 0.0, 0.5]);
    assert_eq!(cast(&model, &here, o, d, 4.0).unwrap().t, 4.0);
    assert!(cast(&model, &here, o, d, 3.999999).is_none());
    assert!(cast(&model, &here, o, d, 0.0).is_none());
    assert_eq!(cast(&model, &here, o, d, f64::INFINITY).unwrap().t, 4.0);
    // -0 is 0: a ray starting on the surface still hits.
    assert_eq!(
        cast(&model, &here, [1.5, 1.25, 0.0], d, -0.0).unwrap().t,
        0.0
    );
    // The nearest hit within max_t is reported even if a farther one is cut.
    assert_eq!(
        cast(&model, &here, [1.5, 1.25, 1.0], d, 100.0).unwrap().t,
        6.0
    );
}

/// The same scene scaled by powers of two gives the same answers (t scaled by the direction's
/// scale), from 2^-600 to 2^450; so does a direction scaled from 2^-1000 to 2^1000.
#[test]
fn huge_and_tiny_scales() {
    let mut rng = Rng(2204);
    let mesh = Closed::sphere(16, 9).mesh();
    let rays: Vec<(V, V)> = (0..300)
        .map(|_| {
            let o = rng.point(2.0);
            (o, scale(sub(rng.in_ball(0.9), o), rng.range(0.5, 2.0)))
        })
        .collect();
    let base: Vec<Option<RayHit>> = {
        let m = mesh.model();
        rays.iter()
            .map(|&(o, d)| cast(&m, &Pose::identity(), o, d, f64::INFINITY))
            .collect()
    };
    assert!(base.iter().filter(|h| h.is_some()).count() > 50);
    for k in [-600, -300, -100, 100, 300, 450] {
        let s = 2f64.powi(k);
        let scaled = Mesh {
            tris: mesh.tris.iter().map(|t| t.map(|v| scale(v, s))).collect(),
        };
        let m = scaled.model();
        for (&(o, d), want) in rays.iter().zip(&base) {
            let got = cast(
                &m,
                &Pose::identity(),
                scale(o, s),
                scale(d, s),
                f64::INFINITY,
            );
            assert_eq!(
                got.map(|h| (h.t, h.triangle)),
                want.map(|h| (h.t, h.triangle)),
                "2^{k}"
            );
        }
    }
    let m = mesh.model();
    for k in [-1000, -500, 500, 1000] {
        let s = 2f64.powi(k);
        for (&(o, d), want) in rays.iter().zip(&base) {
            let got = cast(&m, &Pose::identity(), o, scale(d, s), f64::INFINITY);
            assert_eq!(
                got.map(|h| (h.t, h.triangle)),
                want.map(|h| (h.t / s, h.triangle))
            );
        }
    }
}

#[test]
fn degenerate_triangles_are_never_hit() {
    let line = ([0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, 2.0, 0.0], 0);
    let point = ([0.5, 0.5, 0.0], [0.5, 0.5, 0.0], [0.5, 0.5, 0.0], 1);
    let behind = ([-5.0, -5.0, -1.0], [5.0, -5.0, -1.0], [0.0, 5.0, -1.0], 2);
    let m = Model::from_triangles([line, point, behind]).unwrap();
    let here = Pose::identity();
    for o in [[1.0, 1.0, 3.0], [0.5, 0.5, 3.0], [1.5, 1.5, 3.0]] {
        let h = cast(&m, &here, o, [0.0, 0.0, -1.0], f64::INFINITY).unwrap();
        assert_eq!((h.triangle, h.t), (2, 4.0));
        // Along the segment's own line too.
        let h = cast(&m, &here, [-1.0, -1.0, 0.0], [1.0, 1.0, 0.0], f64::INFINITY);
        assert!(h.is_none());
    }
    let only = Model::from_triangles([line, point]).unwrap();
    assert!(
        cast(
            &only,
            &here,
            [1.0, 1.0, 3.0],
            [0.0, 0.0, -1.0],
            f64::INFINITY
        )
        .is_none()
    );
}

#[test]
fn ties_go_to_the_triangle_added_first() {
    // Two copies of a square at z = 0 (ids 5.. and 9..) and the ray through the middle.
    let sq = |id: i32| {
        [
            ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], id),
            ([0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], id + 1),
        ]
    };
    let m = Model::from_triangles(sq(5).into_iter().chain(sq(9))).unwrap();
    let mut rng = Rng(2205);
    for _ in 0..200 {
        let o = [rng.unit(), rng.unit(), 1.0];
        let h = cast(&m, &Pose::identity(), o, [0.0, 0.0, -1.0], f64::INFINITY).unwrap();
        assert!(h.triangle == 5 || h.triangle == 6, "{}", h.triangle);
    }
}

#[test]
fn batches_equal_single_calls() {
    let mut rng = Rng(2206);
    let mesh = load("bunny.tris");
    let model = mesh.model();
    let pose = rng.pose(0.5);
    let w = mesh.world(&pose);
    for n in [0, 1, 63, 64, 65, 1000] {
        let rays: Vec<(V, V)> = (0..n).map(|_| random_ray(&mut rng, &w, 1.0)).collect();
        let origins: Vec<Vec3> = rays.iter().map(|r| r.0.into()).collect();
        let directions: Vec<Vec3> = rays.iter().map(|r| r.1.into()).collect();
        let single: Vec<Option<RayHit>> = rays
            .iter()
            .map(|&(o, d)| cast(&model, &pose, o, d, 5.0))
            .collect();
        for threads in [0, 1, 2, 64] {
            let got = ray_cast_batch(&model, &pose, &origins, &directions, 5.0, threads).unwrap();
            assert_eq!(got, single, "n {n} threads {threads}");
        }
    }
}

#[test]
fn bad_input_is_refused() {
    let model = Closed::grid_box(2).mesh().model();
    let here = Pose::identity();
    let o = Vec3::new(0.5, 0.5, -1.0);
    let d = Vec3::new(0.0, 0.0, 1.0);
    let cast = |m: &Model, p: &Pose, o: Vec3, d: Vec3, t: f64| ray_cast(m, p, &o, &d, t).err();
    assert_eq!(
        cast(&Model::new(), &here, o, d, 1.0),
        Some(Error::UnprocessedModel)
    );
    let mut bad = here;
    bad.rotation[(1, 2)] = f64::NAN;
    assert_eq!(cast(&model, &bad, o, d, 1.0), Some(Error::NonFinitePose));
    bad = Pose::from_translation([1e151, 0.0, 0.0]);
    assert_eq!(cast(&model, &bad, o, d, 1.0), Some(Error::NonFinitePose));
    for v in [f64::NAN, f64::INFINITY, -f64::INFINITY, 2e150] {
        assert_eq!(
            cast(&model, &here, Vec3::new(0.0, v, 0.0), d, 1.0),
            Some(Error::NonFiniteCoordinate)
        );
    }
    for v in [f64::NAN, f64::INFINITY] {
        assert_eq!(
            cast(&model, &here, o, Vec3::new(v, 0.0, 1.0), 1.0),
            Some(Error::NonFiniteCoordinate)
        );
    }
    assert_eq!(
        cast(&model, &here, o, Vec3::zeros(), 1.0),
        Some(Error::InvalidArgument)
    );
    assert_eq!(
        cast(&model, &here, o, -Vec3::zeros(), 1.0),
        Some(Error::InvalidArgument)
    );
    for t in [-1.0, -1e-300, f64::NAN, -f64::INFINITY] {
        assert_eq!(cast(&model, &here, o, d, t), Some(Error::InvalidArgument));
    }
    // Huge but finite directions and origins at the limit are fine.
    assert!(
        cast(
            &model,
            &here,
            Vec3::new(0.5, 0.5, -1e150),
            Vec3::new(0.0, 0.0, 1e300),
            1.0
        )
        .is_none()
    );
    // A batch with one bad ray fails whole; so do slices of different lengths.
    let mut origins = vec![o; 100];
    let directions = vec![d; 100];
    assert!(ray_cast_batch(&model, &here, &origins, &directions, 9.0, 2).is_ok());
    origins[77].y = f64::NAN;
    assert_eq!(
        ray_cast_batch(&model, &here, &origins, &directions, 9.0, 2),
        Err(Error::NonFiniteCoordinate)
    );
    assert_eq!(
        ray_cast_batch(&model, &here, &origins[..3], &directions, 9.0, 2),
        Err(Error::InvalidArgument)
    );
}

/// The reported point lies on the hit triangle (the accuracy documented on `RayHit`) far from the
/// model, at large translations.
#[test]
fn point_accuracy_far_away() {
    let mut rng = Rng(2207);
    let mesh = Closed::sphere(20, 11).mesh();
    let model = mesh.model();
    for _ in 0..20 {
        let mut pose = rng.pose(1.0);
        pose.translation = rng.vec3(1e6);
        let w = mesh.world(&pose);
        for _ in 0..50 {
            let o: V = add(
                pose.translation.into(),
                scale(rng.direction(), rng.log_uniform(2.0, 1e6)),
            );
            let target = apply_tri(&pose, &mesh.tris[rng.below(mesh.tris.len())])[0];
            let d = sub(add(target, scale(rng.direction(), 0.3)), o);
            if let Some(h) = cast(&model, &pose, o, d, f64::INFINITY) {
                let off = point_tri(h.point.into(), &w[h.triangle as usize]);
                let bound = 1e-14 * (norm(o) + pose.translation.norm() + 1.0);
                assert!(off <= bound, "off {off} bound {bound}");
            }
        }
    }
}
