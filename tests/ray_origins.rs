//! Rays that start on a triangle hit it at `t = 0` (the documented guarantee), exactly: origins at
//! exact points of triangles (inside, on edges, on vertices) of meshes with exactly representable
//! vertices, in many directions (across, into and in the triangles' planes), with `max_t = 0` and
//! `max_t = inf`, at exact poses; checked against an exact brute-force containment test over every
//! triangle, in integer arithmetic (every coordinate here is a multiple of 1/64).

mod common;

use common::{Random, Rng};
use pqp::math::Mat3;
use pqp::{Model, Pose, Vec3, ray_cast};

type V = [f64; 3];
type T = [V; 3];

/// `v` in units of 1/64, as exact integers.
fn int(v: &V) -> [i128; 3] {
    v.map(|x| {
        let y = x * 64.0;
        assert!(y == y.trunc() && y.abs() < 1e15, "{x} is not on the grid");
        y as i128
    })
}

/// Whether `o` lies on the closed triangle `t` (exactly, in integers); false for a triangle without
/// area.
fn on_triangle(t: &T, o: &V) -> bool {
    let [a, b, c, p] = [int(&t[0]), int(&t[1]), int(&t[2]), int(o)];
    let sub = |u: [i128; 3], v: [i128; 3]| [u[0] - v[0], u[1] - v[1], u[2] - v[2]];
    let (u, v, w) = (sub(b, a), sub(c, a), sub(p, a));
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    if n == [0, 0, 0] || n[0] * w[0] + n[1] * w[1] + n[2] * w[2] != 0 {
        return false;
    }
    // In the plane: o is on the triangle when it is on the inner side of every edge (or on it),
    // the sides measured along the normal.
    [(a, b), (b, c), (c, a)].iter().all(|&(x, y)| {
        let (e, f) = (sub(y, x), sub(p, x));
        let m = [
            e[1] * f[2] - e[2] * f[1],
            e[2] * f[0] - e[0] * f[2],
            e[0] * f[1] - e[1] * f[0],
        ];
        m[0] * n[0] + m[1] * n[1] + m[2] * n[2] >= 0
    })
}

/// The box `[0, n]^3` with every face cut into `n x n` squares of two triangles (diagonals
/// alternating), scaled by `s` and moved by `shift` (both exact on the grid).
fn grid_box(n: i32, s: f64, shift: V) -> Vec<T> {
    let mut tris = Vec::new();
    for axis in 0..3 {
        for side in [0, n] {
            for i in 0..n {
                for j in 0..n {
                    let p = |a: i32, b: i32| {
                        let mut q = [0.0; 3];
                        q[axis] = f64::from(side);
                        q[(axis + 1) % 3] = f64::from(a);
                        q[(axis + 2) % 3] = f64::from(b);
                        [0, 1, 2].map(|k| q[k] * s + shift[k])
                    };
                    let c = [p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)];
                    if (i + j) % 2 == 0 {
                        tris.push([c[0], c[1], c[2]]);
                        tris.push([c[0], c[2], c[3]]);
                    } else {
                        tris.push([c[0], c[1], c[3]]);
                        tris.push([c[1], c[2], c[3]]);
                    }
                }
            }
        }
    }
    tris
}

/// The octahedron `|x| + |y| + |z| = 2`, each face cut into four by its edges' midpoints: faces
/// leaning to every axis, so that no projection of them is exact by accident.
fn octahedron() -> Vec<T> {
    let mut tris = Vec::new();
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                let (x, y, z) = (
                    [2.0 * sx, 0.0, 0.0],
                    [0.0, 2.0 * sy, 0.0],
                    [0.0, 0.0, 2.0 * sz],
                );
                let mid = |a: V, b: V| [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0);
                let (xy, yz, zx) = (mid(x, y), mid(y, z), mid(z, x));
                tris.extend([[x, xy, zx], [xy, y, yz], [zx, yz, z], [xy, yz, zx]]);
            }
        }
    }
    tris
}

/// Exact points of triangle `t`: its vertices, points on its edges at eighths, and interior points
/// with barycentric weights in eighths (all on the 1/64 grid for vertices on the 1/8 grid).
fn points_of(t: &T) -> Vec<V> {
    let mut out = Vec::new();
    for i in 0..=8 {
        for j in 0..=8 - i {
            let (u, v) = (f64::from(i) / 8.0, f64::from(j) / 8.0);
            let w = 1.0 - u - v;
            out.push([0, 1, 2].map(|k| u * t[0][k] + v * t[1][k] + w * t[2][k]));
        }
    }
    out
}

/// Directions to try from `o` on triangle `t`: the six axes, eight diagonals, towards and away
/// from each vertex (in the plane), along each edge, and a few random ones.
fn directions(rng: &mut Rng, t: &T, o: &V) -> Vec<V> {
    let mut out = vec![];
    for k in 0..3 {
        for s in [-1.0, 1.0] {
            let mut d = [0.0; 3];
            d[k] = s;
            out.push(d);
        }
    }
    for s in 0..8 {
        out.push([0, 1, 2].map(|k| if s >> k & 1 == 0 { 1.0 } else { -1.0 }));
    }
    for k in 0..3 {
        let to = [0, 1, 2].map(|j| t[k][j] - o[j]);
        if to != [0.0; 3] {
            out.push(to);
            out.push(to.map(|x| -x));
        }
        out.push([0, 1, 2].map(|j| t[(k + 1) % 3][j] - t[k][j]));
    }
    for _ in 0..4 {
        out.push(rng.direction());
    }
    out
}

/// The 24 rotations of the cube (signed permutation matrices of determinant 1): exact poses.
fn cube_rotations() -> Vec<Mat3> {
    let mut out = Vec::new();
    for p in [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [0, 2, 1],
        [2, 1, 0],
        [1, 0, 2],
    ] {
        let even = p[0] == 0 && p[1] == 1 || p[0] == 1 && p[1] == 2 || p[0] == 2 && p[1] == 0;
        for signs in 0..8 {
            let s = [0, 1, 2].map(|k| if signs >> k & 1 == 0 { 1.0 } else { -1.0 });
            if (s[0] * s[1] * s[2] > 0.0) != even {
                continue;
            }
            let mut m = Mat3::zeros();
            for r in 0..3 {
                m[(r, p[r])] = s[r];
            }
            out.push(m);
        }
    }
    assert_eq!(out.len(), 24);
    out
}

/// What [`check_mesh`] counted.
#[derive(Default, Debug)]
struct Tally {
    /// Rays cast.
    cast: usize,
    /// Rays that did not hit at `t = 0`: all of them, and those across the triangle's plane.
    not_zero: usize,
    not_zero_across: usize,
    /// Rays that hit at 0 but reported another triangle than the first the origin lies on.
    wrong_triangle: usize,
}

impl Tally {
    fn add(&mut self, o: Tally) {
        self.cast += o.cast;
        self.not_zero += o.not_zero;
        self.not_zero_across += o.not_zero_across;
        self.wrong_triangle += o.wrong_triangle;
    }

    fn assert_clean(&self, what: &str) {
        eprintln!("{what}: {self:?}");
        assert_eq!(
            (self.not_zero, self.wrong_triangle),
            (0, 0),
            "{what}: {self:?}"
        );
    }
}

/// Casts every ray from exact points of the triangles of `tris` (every `every`-th triangle), at
/// `pose` (exact), with `max_t` 0 and infinite; each must hit at `t = 0` the triangle added first
/// among those the origin lies on.
fn check_mesh(tris: &[T], pose: &Pose, rng: &mut Rng, every: usize) -> Tally {
    let model = Model::from_triangles(
        tris.iter()
            .zip(0..)
            .map(|(t, i): (&T, i32)| (t[0], t[1], t[2], i)),
    )
    .unwrap();
    let mut tally = Tally::default();
    for (ti, t) in tris.iter().enumerate().step_by(every) {
        if !on_triangle(t, &t[0]) {
            // Without area: never hit.
            continue;
        }
        // The normal (exact: small grid coordinates).
        let (e1, e2) = (
            [0, 1, 2].map(|k| t[1][k] - t[0][k]),
            [0, 1, 2].map(|k| t[2][k] - t[0][k]),
        );
        let n = Vec3::from(e1).cross(&Vec3::from(e2));
        for o in points_of(t) {
            let first = tris.iter().position(|u| on_triangle(u, &o));
            assert!(first.is_some_and(|f| f <= ti), "{o:?} not on triangle {ti}");
            let wo = pose.transform_point(&Vec3::from(o));
            for d in directions(rng, t, &o) {
                let across = n.dot(&Vec3::from(d)) != 0.0;
                let wd = pose.rotation * Vec3::from(d);
                for max_t in [0.0, f64::INFINITY] {
                    tally.cast += 1;
                    let h = ray_cast(&model, pose, &wo, &wd, max_t).unwrap();
                    match h {
                        Some(h) if h.t == 0.0 && h.point == wo => {
                            if Some(h.triangle as usize) != first {
                                tally.wrong_triangle += 1;
                            }
                        }
                        _ => {
                            tally.not_zero += 1;
                            tally.not_zero_across += usize::from(across);
                            if tally.not_zero <= 3 {
                                eprintln!("{o:?} {d:?} max_t {max_t}: {h:?}, want {first:?}");
                            }
                        }
                    }
                }
            }
        }
    }
    tally
}

/// The case: one triangle, an origin exactly inside it.
#[test]
fn origin_inside_a_triangle_hits_at_zero() {
    let m = Model::from_triangles([([-2.0, -2.0, -1.0], [-2.0, -1.0, 0.0], [-2.0, -1.0, -1.0], 0)])
        .unwrap();
    let o = Vec3::new(-2.0, -1.5, -0.75);
    let d = Vec3::new(-1.5, -1.75, -0.625);
    for max_t in [0.0, f64::INFINITY] {
        let h = ray_cast(&m, &Pose::identity(), &o, &d, max_t).unwrap();
        let h = h.unwrap_or_else(|| panic!("max_t {max_t}: no hit"));
        assert_eq!((h.t, h.triangle), (0.0, 0), "max_t {max_t}");
        assert_eq!(h.point, o);
    }
}

/// Every exact point of a 4 x 4 subdivided box, of a scaled and moved one and of a subdivided
/// octahedron, in many directions, at the identity pose.
#[test]
fn exact_points_of_grid_meshes_hit_at_zero() {
    let mut rng = Rng(3801);
    let here = Pose::identity();
    let meshes = [
        grid_box(4, 1.0, [0.0; 3]),
        grid_box(3, 0.375, [-1.25, 0.5, -0.625]),
        octahedron(),
        // The triangle alone: its edges are nobody's neighbours'.
        vec![[[-2.0, -2.0, -1.0], [-2.0, -1.0, 0.0], [-2.0, -1.0, -1.0]]],
    ];
    let mut tally = Tally::default();
    for tris in &meshes {
        tally.add(check_mesh(tris, &here, &mut rng, 1));
    }
    tally.assert_clean("grid meshes");
    assert!(tally.cast > 50_000, "{tally:?}");
}

/// The same at the 24 exact rotations with integer translations (the ray reaches the model's
/// frame exactly), on a few triangles of each mesh.
#[test]
fn exact_points_hit_at_zero_at_exact_poses() {
    let mut rng = Rng(3802);
    let meshes = [grid_box(4, 1.0, [0.0; 3]), octahedron()];
    let mut tally = Tally::default();
    for (k, r) in cube_rotations().into_iter().enumerate() {
        let pose = Pose {
            rotation: r,
            translation: Vec3::new(k as f64 - 12.0, 3.0, -(k as f64)),
        };
        for tris in &meshes {
            tally.add(check_mesh(tris, &pose, &mut rng, 7));
        }
    }
    tally.assert_clean("exact poses");
}

/// Random triangles with vertices on the 1/8 grid (slanted every way, some long and thin), each
/// alone and with a copy added later (ties: the first), from their exact points.
#[test]
fn exact_points_of_random_grid_triangles_hit_at_zero() {
    let mut rng = Rng(3803);
    let mut tally = Tally::default();
    for _ in 0..150 {
        let mut v = || [0; 3].map(|_: i32| (rng.below(129) as f64 - 64.0) / 8.0);
        let t = [v(), v(), v()];
        // A neighbour across the first edge, the triangle, and a copy of it added later.
        let tris = [[t[1], t[0], v()], t, [t[1], t[2], t[0]]];
        let mut rng2 = Rng(rng.below(1 << 30) as u64);
        let k = 1 + rng2.below(3);
        tally.add(check_mesh(&tris[..k], &Pose::identity(), &mut rng2, 1));
    }
    tally.assert_clean("random grid triangles");
}
