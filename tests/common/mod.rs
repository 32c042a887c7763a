//! Shared by the integration tests: a seeded generator, meshes, poses, and brute force written
//! independently of the library (plain formulas, no shared code), used as the reference.
#![allow(dead_code)]

use pqp::{Model, Pose};

/// The test kit's generator, shared with the crate's unit tests (src/test_rng.rs).
#[path = "../../src/test_rng.rs"]
mod test_rng;
pub use test_rng::{Random, Rng};

/// The library's types from the kit's arrays.
pub trait RandomPqp: Random {
    /// A random pose: a uniformly random rotation and a translation in the cube of side
    /// `2 * half`.
    fn pose(&mut self, half: f64) -> Pose {
        Pose::new(self.rotation(), self.point(half))
    }
    /// [`Random::point`] as a `Vec3`.
    fn vec3(&mut self, half: f64) -> pqp::Vec3 {
        pqp::Vec3::from(self.point(half))
    }
    /// [`Random::direction`] as a `Vec3`.
    fn direction3(&mut self) -> pqp::Vec3 {
        pqp::Vec3::from(self.direction())
    }
    /// [`Random::in_ball`] as a `Vec3`.
    fn in_ball3(&mut self, r: f64) -> pqp::Vec3 {
        pqp::Vec3::from(self.in_ball(r))
    }
    /// [`Random::rotation`] as a matrix.
    fn rotation3(&mut self) -> pqp::math::Mat3 {
        let r = self.rotation();
        pqp::math::Mat3::new(
            r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2],
        )
    }
}

impl<R: Random> RandomPqp for R {}

pub type V = [f64; 3];
pub type T = [V; 3];

pub fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn scale(a: V, s: f64) -> V {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: V) -> f64 {
    dot(a, a).sqrt()
}

/// Applies a pose to a point: R p + T.
pub fn apply(pose: &Pose, p: V) -> V {
    let q = pose.transform_point(&pqp::Vec3::from(p));
    [q.x, q.y, q.z]
}

pub fn apply_tri(pose: &Pose, t: &T) -> T {
    [apply(pose, t[0]), apply(pose, t[1]), apply(pose, t[2])]
}

/// Distance from `p` to segment `[a, b]` (which may be a point), by clamped projection.
pub fn point_segment(p: V, a: V, b: V) -> f64 {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    let t = if len2 > 0.0 {
        (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm(sub(p, add(a, scale(ab, t))))
}

/// Distance from `p` to a triangle: the plane distance when the projection falls inside, else the
/// nearest edge. Degenerate triangles fall back to their edges.
pub fn point_tri(p: V, t: &T) -> f64 {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let nn = dot(n, n);
    let edges = point_segment(p, t[0], t[1])
        .min(point_segment(p, t[1], t[2]))
        .min(point_segment(p, t[2], t[0]));
    if nn <= 0.0 {
        return edges;
    }
    let d = dot(sub(p, t[0]), n) / nn;
    let proj = sub(p, scale(n, d));
    let inside = (0..3).all(|i| {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        dot(cross(sub(b, a), sub(proj, a)), n) >= 0.0
    });
    if inside {
        (d * nn.sqrt()).abs().min(edges)
    } else {
        edges
    }
}

/// Distance between two segments: the interior critical point when it exists, else the four
/// endpoint-to-segment distances (the minimum of a convex function on a square is inside or on an
/// edge).
pub fn segment_segment(p0: V, p1: V, q0: V, q1: V) -> f64 {
    let mut best = point_segment(p0, q0, q1)
        .min(point_segment(p1, q0, q1))
        .min(point_segment(q0, p0, p1))
        .min(point_segment(q1, p0, p1));
    let (u, v, w) = (sub(p1, p0), sub(q1, q0), sub(p0, q0));
    let (a, b, c, d, e) = (dot(u, u), dot(u, v), dot(v, v), dot(u, w), dot(v, w));
    let den = a * c - b * b;
    if den > 1e-12 * a * c && a > 0.0 && c > 0.0 {
        let s = (b * e - c * d) / den;
        let t = (a * e - b * d) / den;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            best = best.min(norm(sub(add(p0, scale(u, s)), add(q0, scale(v, t)))));
        }
    }
    best
}

/// Whether segment `[p, q]` crosses the triangle's interior or boundary (general position: by the
/// parametric intersection with the plane and barycentric coordinates).
pub fn segment_crosses_tri(p: V, q: V, t: &T) -> bool {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let dp = dot(sub(p, t[0]), n);
    let dq = dot(sub(q, t[0]), n);
    if dp * dq > 0.0 || dp == dq {
        return false;
    }
    let s = dp / (dp - dq);
    let x = add(p, scale(sub(q, p), s));
    (0..3).all(|i| {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        dot(cross(sub(b, a), sub(x, a)), n) >= 0.0
    })
}

/// Whether two triangles in general position intersect.
pub fn tris_intersect(a: &T, b: &T) -> bool {
    (0..3).any(|i| segment_crosses_tri(a[i], a[(i + 1) % 3], b))
        || (0..3).any(|i| segment_crosses_tri(b[i], b[(i + 1) % 3], a))
}

/// Distance between two triangles: 0 if they intersect, else the least of the 6 vertex-triangle and
/// 9 edge-edge distances.
pub fn tri_tri(a: &T, b: &T) -> f64 {
    if tris_intersect(a, b) {
        return 0.0;
    }
    let mut best = f64::INFINITY;
    for i in 0..3 {
        best = best.min(point_tri(a[i], b)).min(point_tri(b[i], a));
        for j in 0..3 {
            best = best.min(segment_segment(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]));
        }
    }
    best
}

/// A triangle mesh with ids equal to indices.
pub struct Mesh {
    pub tris: Vec<T>,
}

impl Mesh {
    pub fn model(&self) -> Model {
        let mut m = Model::new();
        m.begin(self.tris.len()).unwrap();
        for (i, t) in self.tris.iter().enumerate() {
            m.add_triangle(t[0], t[1], t[2], i as i32).unwrap();
        }
        m.end().unwrap();
        m
    }

    /// `n` random triangles with vertices in a cube of side `2 * half`, each of size about `size`.
    pub fn soup(rng: &mut Rng, n: usize, half: f64, size: f64) -> Mesh {
        let tris = (0..n)
            .map(|_| {
                let c = rng.point(half);
                let mut v = || add(c, rng.point(size));
                [v(), v(), v()]
            })
            .collect();
        Mesh { tris }
    }

    /// A UV sphere of radius `r` with `slices * stacks * 2` triangles (poles included).
    pub fn sphere(r: f64, slices: usize, stacks: usize) -> Mesh {
        let pt = |i: usize, j: usize| {
            let th = std::f64::consts::PI * i as f64 / stacks as f64;
            let ph = std::f64::consts::TAU * j as f64 / slices as f64;
            [
                r * th.sin() * ph.cos(),
                r * th.sin() * ph.sin(),
                r * th.cos(),
            ]
        };
        let mut tris = Vec::new();
        for i in 0..stacks {
            for j in 0..slices {
                let (a, b, c, d) = (pt(i, j), pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1));
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
        Mesh { tris }
    }

    /// A torus with major radius `big` and minor radius `small`.
    pub fn torus(big: f64, small: f64, n: usize, m: usize) -> Mesh {
        let pt = |i: usize, j: usize| {
            let u = std::f64::consts::TAU * i as f64 / n as f64;
            let v = std::f64::consts::TAU * j as f64 / m as f64;
            let w = big + small * v.cos();
            [w * u.cos(), w * u.sin(), small * v.sin()]
        };
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..m {
                let (a, b, c, d) = (pt(i, j), pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1));
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
        Mesh { tris }
    }

    pub fn world(&self, pose: &Pose) -> Vec<T> {
        self.tris.iter().map(|t| apply_tri(pose, t)).collect()
    }
}

/// Brute-force answers over all triangle pairs, in world coordinates.
pub struct Brute {
    pub pairs: Vec<(i32, i32)>,
    pub distance: f64,
}

pub fn brute(a: &Mesh, pa: &Pose, b: &Mesh, pb: &Pose) -> Brute {
    let (wa, wb) = (a.world(pa), b.world(pb));
    let mut pairs = Vec::new();
    let mut distance = f64::INFINITY;
    for (i, ta) in wa.iter().enumerate() {
        for (j, tb) in wb.iter().enumerate() {
            let d = tri_tri(ta, tb);
            if d == 0.0 {
                pairs.push((i as i32, j as i32));
            }
            distance = distance.min(d);
        }
    }
    pairs.sort();
    Brute { pairs, distance }
}

/// The smallest distance between two triangles among pairs in general position, used to skip
/// configurations whose answer depends on rounding (a contact within `eps`).
pub fn borderline(a: &Mesh, pa: &Pose, b: &Mesh, pb: &Pose, eps: f64) -> bool {
    let (wa, wb) = (a.world(pa), b.world(pb));
    wa.iter().any(|ta| {
        wb.iter().any(|tb| {
            let d = tri_tri(ta, tb);
            d > 0.0 && d < eps
        })
    })
}
