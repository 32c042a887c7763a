//! Convex models: hull validity, V-Clip against brute force, warm starts, penetration depth.
//!
//! The references here are written independently of the library: plain formulas over the posed
//! vertices and faces (point-polygon and segment-segment distances, separating-axis overlaps).

use pqp::convex::{
    ConvexModel, ConvexPairCache, Feature, FeatureKind, convex_distance, convex_intersect,
    convex_penetration,
};
use pqp::{Error, Pose, Vec3};

mod common;
use common::{Random, RandomPqp, Rng};

/// Poses these tests' cases and thresholds were chosen on: a rotation about a random axis by an
/// angle uniform in [-pi, pi] (not uniform over rotations, unlike the kit's `rotation`).
trait AxisAngle: Random + RandomPqp {
    /// The rotation, row-major.
    fn axis_angle_rotation(&mut self) -> [[f64; 3]; 3] {
        let axis = self.direction3();
        let angle = self.range(-std::f64::consts::PI, std::f64::consts::PI);
        rotation_about(&axis, angle)
    }
    /// That rotation and a translation in the cube of side `2 * half`.
    fn axis_angle_pose(&mut self, half: f64) -> Pose {
        Pose::new(self.axis_angle_rotation(), self.point(half))
    }
}

impl AxisAngle for Rng {}

fn rotation_about(axis: &Vec3, angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    let (x, y, z) = (axis.x, axis.y, axis.z);
    let t = 1.0 - c;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
}

/// Multiplier of the random rounds, from `CONVEX_TEST_SCALE` (default 1), for stress runs.
fn rounds(n: usize) -> usize {
    n * std::env::var("CONVEX_TEST_SCALE")
        .ok()
        .and_then(|s| s.parse::<usize>().ok())
        .unwrap_or(1)
}

fn v3(p: &[f64; 3]) -> Vec3 {
    Vec3::new(p[0], p[1], p[2])
}

// ---------------------------------------------------------------------------------------------
// Point sets

fn random_cloud(rng: &mut Rng, n: usize, half: [f64; 3]) -> Vec<[f64; 3]> {
    (0..n)
        .map(|_| {
            [
                rng.range(-half[0], half[0]),
                rng.range(-half[1], half[1]),
                rng.range(-half[2], half[2]),
            ]
        })
        .collect()
}

/// Points on a k x k x k grid of the cube [-1, 1]^3: many coplanar and collinear points.
fn cube_grid(k: usize) -> Vec<[f64; 3]> {
    let mut v = Vec::new();
    for i in 0..k {
        for j in 0..k {
            for l in 0..k {
                let f = |a: usize| -1.0 + 2.0 * a as f64 / (k - 1) as f64;
                v.push([f(i), f(j), f(l)]);
            }
        }
    }
    v
}

/// Rings of a cylinder (coplanar caps, many cocircular points) plus the cap centres.
fn cylinder(rings: usize, per_ring: usize, radius: f64, height: f64) -> Vec<[f64; 3]> {
    let mut v = Vec::new();
    for r in 0..rings {
        let z = -height / 2.0 + height * r as f64 / (rings - 1) as f64;
        for k in 0..per_ring {
            let a = std::f64::consts::TAU * k as f64 / per_ring as f64;
            v.push([radius * a.cos(), radius * a.sin(), z]);
        }
    }
    v.push([0.0, 0.0, -height / 2.0]);
    v.push([0.0, 0.0, height / 2.0]);
    v
}

// ---------------------------------------------------------------------------------------------
// Independent geometry

/// Newell normal of a polygon, normalised.
fn polygon_normal(pts: &[Vec3]) -> Vec3 {
    let mut n = Vec3::zeros();
    for k in 0..pts.len() {
        let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
        n += Vec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    n.normalize()
}

fn point_segment(p: &Vec3, a: &Vec3, b: &Vec3) -> (f64, Vec3) {
    let d = b - a;
    let t = if d.norm_squared() > 0.0 {
        ((p - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = a + d * t;
    ((p - q).norm(), q)
}

/// Segment-segment distance: the interior critical point of the squared distance if it lies in
/// the unit square, else the best of the four endpoint-to-segment distances (the boundary).
fn segment_segment(p0: &Vec3, p1: &Vec3, q0: &Vec3, q1: &Vec3) -> (f64, Vec3, Vec3) {
    let mut best = {
        let (d, q) = point_segment(p0, q0, q1);
        (d, *p0, q)
    };
    for (p, a, b, swap) in [(p1, q0, q1, false), (q0, p0, p1, true), (q1, p0, p1, true)] {
        let (d, q) = point_segment(p, a, b);
        if d < best.0 {
            best = if swap { (d, q, *p) } else { (d, *p, q) };
        }
    }
    let (u, v, w) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, b, c, d, e) = (u.dot(&u), u.dot(&v), v.dot(&v), u.dot(&w), v.dot(&w));
    let den = a * c - b * b;
    if den > 1e-12 * a * c {
        let s = (b * e - c * d) / den;
        let t = (a * e - b * d) / den;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            let (x, y) = (p0 + u * s, q0 + v * t);
            let dist = (x - y).norm();
            if dist < best.0 {
                best = (dist, x, y);
            }
        }
    }
    best
}

/// A model posed in the world, with its own geometry recomputed from vertices and face lists.
struct Posed {
    verts: Vec<Vec3>,
    faces: Vec<Vec<usize>>,
    normals: Vec<Vec3>,
    /// The library's face normals, posed: extra candidate axes only (any axis bounds the depth
    /// from above, so they cannot make the reference wrong; they make it sharp on slivers, where
    /// a float cross product is not).
    lib_normals: Vec<Vec3>,
    edges: Vec<(usize, usize)>,
}

fn posed(m: &ConvexModel, pose: &Pose) -> Posed {
    let verts: Vec<Vec3> = m
        .vertices()
        .iter()
        .map(|v| pose.transform_point(v))
        .collect();
    let faces: Vec<Vec<usize>> = (0..m.num_faces())
        .map(|f| m.face(f).iter().map(|&i| i as usize).collect())
        .collect();
    let normals = faces
        .iter()
        .map(|f| polygon_normal(&f.iter().map(|&i| verts[i]).collect::<Vec<_>>()))
        .collect();
    let mut edges = Vec::new();
    for f in &faces {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            if a < b {
                edges.push((a, b));
            }
        }
    }
    let lib_normals = (0..m.num_faces())
        .map(|f| pose.rotation * m.face_plane(f).0)
        .collect();
    Posed {
        verts,
        faces,
        normals,
        lib_normals,
        edges,
    }
}

/// Distance from a point to a triangle: the least-squares barycentric point if it is inside, else
/// the nearest edge. The candidate is always a convex combination of the corners, a point of the
/// triangle, so cancellation on slivers can only overestimate, by at most the sliver's width.
fn point_triangle(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> (f64, Vec3) {
    let (e0, e1, w) = (b - a, c - a, p - a);
    let (g00, g01, g11) = (e0.dot(&e0), e0.dot(&e1), e1.dot(&e1));
    let (r0, r1) = (e0.dot(&w), e1.dot(&w));
    let det = g00 * g11 - g01 * g01;
    let mut best = (f64::INFINITY, *a);
    if det > 0.0 {
        let s = (g11 * r0 - g01 * r1) / det;
        let t = (g00 * r1 - g01 * r0) / det;
        if s >= 0.0 && t >= 0.0 && s + t <= 1.0 {
            let q = a + e0 * s + e1 * t;
            best = ((p - q).norm(), q);
        }
    }
    for (u, v) in [(a, b), (b, c), (c, a)] {
        let r = point_segment(p, u, v);
        if r.0 < best.0 {
            best = r;
        }
    }
    best
}

/// Distance from a point to a convex polygon face (its fan triangles).
fn point_face(p: &Vec3, h: &Posed, f: usize) -> (f64, Vec3) {
    let face = &h.faces[f];
    let mut best = (f64::INFINITY, Vec3::zeros());
    for k in 1..face.len() - 1 {
        let r = point_triangle(
            p,
            &h.verts[face[0]],
            &h.verts[face[k]],
            &h.verts[face[k + 1]],
        );
        if r.0 < best.0 {
            best = r;
        }
    }
    best
}

/// Brute-force separation distance of two disjoint posed hulls: minimum over vertex-face pairs
/// (both ways) and edge-edge pairs, with the closest points (on a, on b).
fn brute_distance(a: &Posed, b: &Posed) -> (f64, Vec3, Vec3) {
    let mut best = (f64::INFINITY, Vec3::zeros(), Vec3::zeros());
    for p in &a.verts {
        for f in 0..b.faces.len() {
            let (d, q) = point_face(p, b, f);
            if d < best.0 {
                best = (d, *p, q);
            }
        }
    }
    for p in &b.verts {
        for f in 0..a.faces.len() {
            let (d, q) = point_face(p, a, f);
            if d < best.0 {
                best = (d, q, *p);
            }
        }
    }
    for &(i, j) in &a.edges {
        for &(k, l) in &b.edges {
            let r = segment_segment(&a.verts[i], &a.verts[j], &b.verts[k], &b.verts[l]);
            if r.0 < best.0 {
                best = r;
            }
        }
    }
    best
}

fn extent(h: &Posed, n: &Vec3) -> (f64, f64) {
    h.verts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            let x = v.dot(n);
            (lo.min(x), hi.max(x))
        })
}

/// Separating-axis brute force: the smallest translation of b separating it from a, over all
/// candidate axes (face normals of both, cross products of all edge pairs), both senses. Positive:
/// overlap depth and the direction to move b; negative: the hulls are apart along that axis.
fn brute_depth(a: &Posed, b: &Posed) -> (f64, Vec3) {
    let mut axes: Vec<Vec3> = [&a.normals, &b.normals, &a.lib_normals, &b.lib_normals]
        .iter()
        .flat_map(|n| n.iter().copied())
        .collect();
    for &(i, j) in &a.edges {
        for &(k, l) in &b.edges {
            let c = (a.verts[j] - a.verts[i]).cross(&(b.verts[l] - b.verts[k]));
            let n = c.norm();
            if n > 1e-9 * (a.verts[j] - a.verts[i]).norm() * (b.verts[l] - b.verts[k]).norm() {
                axes.push(c / n);
            }
        }
    }
    let mut best = (f64::INFINITY, Vec3::zeros());
    for n in axes {
        let (alo, ahi) = extent(a, &n);
        let (blo, bhi) = extent(b, &n);
        // Move b along +n until its minimum passes a's maximum, or along -n.
        for (d, dir) in [(ahi - blo, n), (bhi - alo, -n)] {
            if d < best.0 {
                best = (d, dir);
            }
        }
    }
    best
}

fn size_of(h: &Posed) -> f64 {
    let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
    for v in &h.verts {
        lo = lo.inf(v);
        hi = hi.sup(v);
    }
    (hi - lo).norm()
}

// ---------------------------------------------------------------------------------------------
// An exact orientation oracle for the hull checks: big integers, nothing shared with the library.

/// A signed big integer: magnitude in base 2^32, little-endian, no trailing zero limbs.
#[derive(Clone, Debug)]
struct Big {
    neg: bool,
    mag: Vec<u32>,
}

impl Big {
    /// `m * 2^shift`.
    fn from_shifted(m: i64, shift: u32) -> Big {
        let mut mag = vec![0u32; (shift / 32) as usize];
        let (bits, mut carry) = (shift % 32, 0u64);
        let mut x = m.unsigned_abs();
        while x > 0 || carry > 0 {
            let limb = ((x & 0xFFFF_FFFF) << bits) | carry;
            mag.push(limb as u32);
            carry = limb >> 32;
            x >>= 32;
        }
        let mut b = Big { neg: m < 0, mag };
        b.trim();
        b
    }
    fn trim(&mut self) {
        while self.mag.last() == Some(&0) {
            self.mag.pop();
        }
        if self.mag.is_empty() {
            self.neg = false;
        }
    }
    fn cmp_mag(a: &[u32], b: &[u32]) -> std::cmp::Ordering {
        a.len()
            .cmp(&b.len())
            .then_with(|| a.iter().rev().cmp(b.iter().rev()))
    }
    fn add(&self, o: &Big) -> Big {
        if self.neg == o.neg {
            let mut mag = Vec::new();
            let mut carry = 0u64;
            for i in 0..self.mag.len().max(o.mag.len()) {
                let s = *self.mag.get(i).unwrap_or(&0) as u64
                    + *o.mag.get(i).unwrap_or(&0) as u64
                    + carry;
                mag.push(s as u32);
                carry = s >> 32;
            }
            mag.push(carry as u32);
            let mut b = Big { neg: self.neg, mag };
            b.trim();
            return b;
        }
        let (big, small, neg) = if Big::cmp_mag(&self.mag, &o.mag) == std::cmp::Ordering::Less {
            (&o.mag, &self.mag, o.neg)
        } else {
            (&self.mag, &o.mag, self.neg)
        };
        let mut mag = Vec::new();
        let mut borrow = 0i64;
        for (i, &limb) in big.iter().enumerate() {
            let mut d = limb as i64 - *small.get(i).unwrap_or(&0) as i64 - borrow;
            borrow = 0;
            if d < 0 {
                d += 1 << 32;
                borrow = 1;
            }
            mag.push(d as u32);
        }
        let mut b = Big { neg, mag };
        b.trim();
        b
    }
    fn neg(&self) -> Big {
        let mut b = self.clone();
        b.neg = !b.neg;
        b.trim();
        b
    }
    fn sub(&self, o: &Big) -> Big {
        self.add(&o.neg())
    }
    fn mul(&self, o: &Big) -> Big {
        let mut mag = vec![0u32; self.mag.len() + o.mag.len() + 1];
        for (i, &x) in self.mag.iter().enumerate() {
            let mut carry = 0u64;
            for (j, &y) in o.mag.iter().enumerate() {
                let t = mag[i + j] as u64 + x as u64 * y as u64 + carry;
                mag[i + j] = t as u32;
                carry = t >> 32;
            }
            let mut k = i + o.mag.len();
            while carry > 0 {
                let t = mag[k] as u64 + carry;
                mag[k] = t as u32;
                carry = t >> 32;
                k += 1;
            }
        }
        let mut b = Big {
            neg: self.neg != o.neg,
            mag,
        };
        b.trim();
        b
    }
    fn sign(&self) -> i32 {
        if self.mag.is_empty() {
            0
        } else if self.neg {
            -1
        } else {
            1
        }
    }
}

/// `x = m * 2^e` with integer `m`.
fn decompose(x: f64) -> (i64, i32) {
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7FF) as i32;
    let frac = (bits & ((1u64 << 52) - 1)) as i64;
    let (m, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1i64 << 52), exp - 1075)
    };
    (if x.is_sign_negative() { -m } else { m }, e)
}

/// Exact sign of `(b - a) . ((c - a) x (d - a))`, with a floating-point shortcut when clear.
fn exact_orient(a: &Vec3, b: &Vec3, c: &Vec3, d: &Vec3) -> i32 {
    let (u, v, w) = (b - a, c - a, d - a);
    let det = u.dot(&v.cross(&w));
    let perm = u.abs().dot(&(v.abs().cross_abs(&w.abs())));
    if det.abs() > 1e-12 * perm && perm > 1e-250 {
        return if det > 0.0 { 1 } else { -1 };
    }
    let coords: Vec<f64> = [a, b, c, d]
        .iter()
        .flat_map(|p| p.iter().copied())
        .collect();
    let parts: Vec<(i64, i32)> = coords.iter().map(|&x| decompose(x)).collect();
    let e0 = parts
        .iter()
        .filter(|p| p.0 != 0)
        .map(|p| p.1)
        .min()
        .unwrap_or(0);
    let big: Vec<Big> = parts
        .iter()
        .map(|&(m, e)| Big::from_shifted(m, if m == 0 { 0 } else { (e - e0) as u32 }))
        .collect();
    let p = |i: usize, k: usize| &big[3 * i + k];
    let diff = |i: usize, k: usize| p(i, k).sub(p(0, k));
    let (ux, uy, uz) = (diff(1, 0), diff(1, 1), diff(1, 2));
    let (vx, vy, vz) = (diff(2, 0), diff(2, 1), diff(2, 2));
    let (wx, wy, wz) = (diff(3, 0), diff(3, 1), diff(3, 2));
    let cx = vy.mul(&wz).sub(&vz.mul(&wy));
    let cy = vz.mul(&wx).sub(&vx.mul(&wz));
    let cz = vx.mul(&wy).sub(&vy.mul(&wx));
    ux.mul(&cx).add(&uy.mul(&cy)).add(&uz.mul(&cz)).sign()
}

trait CrossAbs {
    fn cross_abs(&self, o: &Vec3) -> Vec3;
}
impl CrossAbs for Vec3 {
    /// The cross product's terms in absolute value (a permanent, for error bounds).
    fn cross_abs(&self, o: &Vec3) -> Vec3 {
        Vec3::new(
            self.y * o.z + self.z * o.y,
            self.z * o.x + self.x * o.z,
            self.x * o.y + self.y * o.x,
        )
    }
}

// ---------------------------------------------------------------------------------------------
// Hull validity

/// Checks that `m` is a valid hull of `pts` and returns nothing; panics with `what` otherwise.
fn check_hull(m: &ConvexModel, pts: &[[f64; 3]], what: &str) {
    let scale = pts
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |s, v| s.max(v.abs()))
        .max(1e-300);
    let tol = 1e-12 * scale;
    let (nv, ne, nf) = (m.num_vertices(), m.num_edges(), m.num_faces());
    assert_eq!(nv + nf, ne + 2, "{what}: Euler characteristic");
    // Every hull vertex is an input point.
    for i in 0..nv {
        assert_eq!(
            m.vertex(i),
            v3(&pts[m.vertex_source(i)]),
            "{what}: vertex source"
        );
    }
    // Each undirected edge in exactly two faces, once in each direction; recomputed from faces.
    let mut directed = std::collections::HashMap::new();
    for f in 0..nf {
        let face = m.face(f);
        assert!(face.len() >= 3, "{what}: face size");
        for k in 0..face.len() {
            let e = (face[k], face[(k + 1) % face.len()]);
            assert!(
                directed.insert(e, f).is_none(),
                "{what}: directed edge twice"
            );
        }
    }
    assert_eq!(directed.len(), 2 * ne, "{what}: edge count");
    for &(a, b) in directed.keys() {
        assert!(directed.contains_key(&(b, a)), "{what}: open edge");
    }
    let verts: Vec<Vec3> = m.vertices().to_vec();
    let pts3: Vec<Vec3> = pts.iter().map(v3).collect();
    let centroid = m.centroid();
    for f in 0..nf {
        let face: Vec<Vec3> = m.face(f).iter().map(|&i| verts[i as usize]).collect();
        let (a, b, c) = (face[0], face[1], face[2]);
        // Exactly planar.
        for v in &face[3..] {
            assert_eq!(exact_orient(&a, &b, &c, v), 0, "{what}: face not planar");
        }
        // Every input point on or below; some hull vertex strictly below (outward, not flat).
        for p in &pts3 {
            assert!(
                exact_orient(&a, &b, &c, p) <= 0,
                "{what}: input point outside the hull"
            );
        }
        let below = verts
            .iter()
            .find(|v| exact_orient(&a, &b, &c, v) < 0)
            .unwrap_or_else(|| panic!("{what}: flat hull"));
        // Strictly convex, counter-clockwise seen from outside: every other vertex of the face
        // strictly left of each edge (orientation against a point below the face).
        for k in 0..face.len() {
            let (p, q) = (face[k], face[(k + 1) % face.len()]);
            for (j, r) in face.iter().enumerate() {
                if j != k && j != (k + 1) % face.len() {
                    assert_eq!(
                        exact_orient(&p, &q, r, below),
                        -1,
                        "{what}: face not strictly convex"
                    );
                }
            }
        }
        // The library's plane contains the face (to rounding) and points outward.
        let (n, d) = m.face_plane(f);
        for v in &face {
            assert!((v.dot(&n) - d).abs() <= tol * 1e3, "{what}: face plane");
        }
        assert!(centroid.dot(&n) < d, "{what}: face normal");
    }
    // Neighbour lists agree with the faces.
    for e in 0..ne {
        let (t, h) = m.edge(e);
        let (l, r) = m.edge_faces(e);
        assert_eq!(
            directed.get(&(t, h)),
            Some(&(l as usize)),
            "{what}: left face"
        );
        assert_eq!(
            directed.get(&(h, t)),
            Some(&(r as usize)),
            "{what}: right face"
        );
        assert!(m.vertex_edges(t as usize).contains(&(e as u32)));
        assert!(m.vertex_edges(h as usize).contains(&(e as u32)));
    }
}

#[test]
fn hull_of_random_sets_with_duplicates() {
    let mut rng = Rng(11);
    for round in 0..rounds(60) {
        let n = 4 + rng.below(200);
        let mut pts = random_cloud(&mut rng, n, [1.0, 2.0, 0.5]);
        // Duplicates, including of future hull vertices.
        for _ in 0..rng.below(n) {
            let p = pts[rng.below(pts.len())];
            pts.push(p);
        }
        match ConvexModel::from_points(&pts) {
            Ok(m) => check_hull(&m, &pts, &format!("random {round}")),
            // Four random points are never coplanar in practice.
            Err(e) => panic!("random {round}: {e}"),
        }
    }
    // A thousand points.
    let pts = random_cloud(&mut rng, 1000, [1.0, 1.0, 1.0]);
    check_hull(
        &ConvexModel::from_points(&pts).unwrap(),
        &pts,
        "1000 points",
    );
}

#[test]
fn hull_of_coplanar_rich_sets() {
    for k in [2, 3, 5, 8] {
        let pts = cube_grid(k);
        let m = ConvexModel::from_points(&pts).unwrap();
        check_hull(&m, &pts, &format!("grid {k}"));
        assert_eq!((m.num_vertices(), m.num_edges(), m.num_faces()), (8, 12, 6));
    }
    let pts = cylinder(5, 24, 1.0, 3.0);
    let m = ConvexModel::from_points(&pts).unwrap();
    check_hull(&m, &pts, "cylinder");
    // Two caps and 24 sides; the middle rings and cap centres are not corners.
    assert_eq!((m.num_vertices(), m.num_faces()), (48, 26));
    // Cube grid with the points shuffled and duplicated.
    let mut rng = Rng(5);
    let mut pts = cube_grid(6);
    for i in (1..pts.len()).rev() {
        pts.swap(i, rng.below(i + 1));
    }
    let more: Vec<_> = pts.iter().step_by(3).copied().collect();
    pts.extend(more);
    let m = ConvexModel::from_points(&pts).unwrap();
    check_hull(&m, &pts, "shuffled grid");
    assert_eq!(m.num_faces(), 6);
}

#[test]
fn hull_of_nearly_coplanar_sets() {
    let mut rng = Rng(23);
    for round in 0..rounds(20) {
        // Grid points perturbed by a few ulps to 1e-10: nearly coplanar, nearly collinear.
        let eps = [1e-15, 1e-13, 1e-10][round % 3];
        let mut pts = cube_grid(4 + round % 3);
        for p in pts.iter_mut() {
            for c in p.iter_mut() {
                *c += rng.range(-eps, eps);
            }
        }
        let m = ConvexModel::from_points(&pts).unwrap();
        check_hull(&m, &pts, &format!("perturbed grid {round}"));
        // Points on a sphere of radius 1 with a tiny noise (nearly cospherical too).
        let sphere: Vec<[f64; 3]> = (0..300)
            .map(|_| {
                let u = rng.direction3() * (1.0 + rng.range(-eps, eps));
                [u.x, u.y, u.z]
            })
            .collect();
        check_hull(
            &ConvexModel::from_points(&sphere).unwrap(),
            &sphere,
            &format!("sphere {round}"),
        );
    }
}

#[test]
fn hull_of_thin_and_needle_sets() {
    let mut rng = Rng(31);
    for round in 0..rounds(20) {
        let n = 4 + rng.below(100);
        let thin = [1e-3, 1e-6, 1e-9][round % 3];
        // Needle: long in x, tiny across.
        let needle = random_cloud(&mut rng, n, [10.0, thin, thin]);
        check_hull(
            &ConvexModel::from_points(&needle).unwrap(),
            &needle,
            &format!("needle {round}"),
        );
        // Slab: thin in z.
        let slab = random_cloud(&mut rng, n, [1.0, 1.0, thin]);
        check_hull(
            &ConvexModel::from_points(&slab).unwrap(),
            &slab,
            &format!("slab {round}"),
        );
    }
    // Tetrahedra, the smallest hulls, at extreme scales.
    for s in [1e-100, 1e-6, 1.0, 1e6, 1e100] {
        let pts = [[0.0, 0.0, 0.0], [s, 0.0, 0.0], [0.0, s, 0.0], [0.0, 0.0, s]];
        let m = ConvexModel::from_points(&pts).unwrap();
        check_hull(&m, &pts, "tetrahedron");
        assert_eq!((m.num_vertices(), m.num_faces()), (4, 4));
    }
}

#[test]
fn degenerate_sets_are_refused() {
    let e = Err(Error::DegeneratePoints);
    let kind = |pts: &[[f64; 3]]| ConvexModel::from_points(pts).map(|_| ());
    assert_eq!(kind(&[]), e);
    assert_eq!(kind(&[[0.0, 0.0, 0.0]; 10]), e);
    assert_eq!(
        kind(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
        e
    );
    // Collinear.
    let line: Vec<[f64; 3]> = (0..50)
        .map(|i| [i as f64, 2.0 * i as f64, -(i as f64)])
        .collect();
    assert_eq!(kind(&line), e);
    // Coplanar, including a grid and points exactly on a tilted plane.
    let plane: Vec<[f64; 3]> = (0..200)
        .map(|i| {
            let (x, y) = ((i % 17) as f64, (i / 17) as f64);
            [x, y, 3.0 * x - 2.0 * y + 1.0]
        })
        .collect();
    assert_eq!(kind(&plane), e);
    let square: Vec<[f64; 3]> = cube_grid(4).into_iter().filter(|p| p[2] == 1.0).collect();
    assert_eq!(kind(&square), e);
    // Non-finite input.
    let mut bad = cube_grid(2);
    bad[3][1] = f64::NAN;
    assert_eq!(kind(&bad), Err(Error::NonFiniteCoordinate));
    bad[3][1] = f64::INFINITY;
    assert_eq!(kind(&bad), Err(Error::NonFiniteCoordinate));
}

fn cube_mesh() -> (Vec<[f64; 3]>, Vec<u32>, Vec<u32>) {
    let v = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let faces = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
    ];
    (
        v,
        vec![4; 6],
        faces.iter().flatten().copied().collect::<Vec<u32>>(),
    )
}

#[test]
fn meshes_are_verified() {
    let (v, counts, idx) = cube_mesh();
    let m = ConvexModel::from_polygons(&v, &counts, &idx).unwrap();
    check_hull(&m, &v, "cube mesh");
    assert_eq!((m.num_vertices(), m.num_edges(), m.num_faces()), (8, 12, 6));
    // The same cube as triangles: coplanar pairs merge back into squares.
    let mut tris = Vec::new();
    for f in idx.chunks(4) {
        tris.push([f[0], f[1], f[2]]);
        tris.push([f[0], f[2], f[3]]);
    }
    let m = ConvexModel::from_triangles(&v, &tris).unwrap();
    assert_eq!(m.num_faces(), 6);
    check_hull(&m, &v, "cube triangles");
    let refused_as = |v: &[[f64; 3]], c: &[u32], i: &[u32], e: Error| {
        ConvexModel::from_polygons(v, c, i).map(|_| ()) == Err(e)
    };
    let refused =
        |v: &[[f64; 3]], c: &[u32], i: &[u32]| refused_as(v, c, i, Error::InvalidConvexMesh);
    // Inside out.
    let flipped: Vec<u32> = idx
        .chunks(4)
        .flat_map(|f| f.iter().rev().copied())
        .collect();
    assert!(refused(&v, &counts, &flipped));
    // One face flipped: not consistently oriented.
    let mut one = idx.clone();
    one[..4].reverse();
    assert!(refused(&v, &counts, &one));
    // Open (a face missing).
    assert!(refused(&v, &counts[..5], &idx[..20]));
    // Not convex: a vertex pushed in (faces stay planar triangles).
    let mut dent = v.clone();
    dent[6] = [0.6, 0.6, 0.6];
    assert_eq!(
        ConvexModel::from_triangles(&dent, &tris).map(|_| ()),
        Err(Error::InvalidConvexMesh)
    );
    // Non-planar quad.
    let mut warp = v.clone();
    warp[6] = [1.0, 1.0, 1.1];
    assert!(refused(&warp, &counts, &idx));
    // Index out of range, unused vertex, bad counts.
    let mut oob = idx.clone();
    oob[0] = 99;
    assert!(refused_as(&v, &counts, &oob, Error::InvalidArgument));
    let mut extra = v.clone();
    extra.push([5.0, 5.0, 5.0]);
    assert!(refused(&extra, &counts, &idx));
    assert!(refused_as(
        &v,
        &[4, 4, 4, 4, 4, 3],
        &idx,
        Error::InvalidArgument
    ));
    assert!(refused_as(
        &v,
        &[4, 4, 4, 4, 6, 2],
        &idx,
        Error::InvalidArgument
    ));
    // Flat: a square given twice, back to back.
    let flat = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    assert!(refused(&flat, &[4, 4], &[0, 1, 2, 3, 3, 2, 1, 0]));
}

// ---------------------------------------------------------------------------------------------
// Queries

/// A hull of `min` to `min + spread - 1` random points in a random box.
fn random_hull(rng: &mut Rng, min: usize, spread: usize) -> (ConvexModel, Vec<[f64; 3]>) {
    let n = min + rng.below(spread);
    let shape = [
        rng.range(0.2, 1.5),
        rng.range(0.2, 1.5),
        rng.range(0.2, 1.5),
    ];
    loop {
        let pts = random_cloud(rng, n, shape);
        if let Ok(m) = ConvexModel::from_points(&pts) {
            return (m, pts);
        }
    }
}

/// Checks that `p` (model frame) lies on feature `f` of `m`.
fn on_feature(m: &ConvexModel, f: Feature, p: &Vec3, tol: f64) -> bool {
    match f.kind {
        FeatureKind::Vertex => (m.vertex(f.index as usize) - p).norm() <= tol,
        FeatureKind::Edge => {
            let (t, h) = m.edge(f.index as usize);
            point_segment(p, &m.vertex(t as usize), &m.vertex(h as usize)).0 <= tol
        }
        FeatureKind::Face => {
            let (n, d) = m.face_plane(f.index as usize);
            let face = m.face(f.index as usize);
            (p.dot(&n) - d).abs() <= tol
                && (0..face.len()).all(|k| {
                    let a = m.vertex(face[k] as usize);
                    let b = m.vertex(face[(k + 1) % face.len()] as usize);
                    (b - a).normalize().cross(&(p - a)).dot(&n) >= -tol
                })
        }
    }
}

struct Tally {
    apart: usize,
    touching: usize,
    overlapping: usize,
}

/// One pair against brute force: distance, verdict, closest points on the reported features,
/// and (when overlapping) the penetration depth and direction.
fn check_pair(
    a: &ConvexModel,
    pa: &Pose,
    b: &ConvexModel,
    pb: &Pose,
    tally: &mut Tally,
    what: &str,
) {
    let (wa, wb) = (posed(a, pa), posed(b, pb));
    let size = size_of(&wa).max(size_of(&wb));
    let tol = 1e-9 * size;
    let r = convex_distance(a, pa, b, pb, None).unwrap();
    assert_eq!(r.stats.cycles_broken, 0, "{what}: rounding cycle");
    let (sat, _) = brute_depth(&wa, &wb);
    if sat > tol {
        // Overlapping.
        assert!(r.intersecting, "{what}: overlap missed (depth {sat:e})");
        tally.overlapping += 1;
    } else {
        let (bd, _, _) = brute_distance(&wa, &wb);
        if bd > tol {
            assert!(!r.intersecting, "{what}: false overlap (distance {bd:e})");
            tally.apart += 1;
        } else {
            tally.touching += 1;
        }
        assert!(
            (r.distance - bd).abs() <= 1e-9 * (bd + size),
            "{what}: distance {} vs brute {bd}",
            r.distance
        );
    }
    let (w1, w2) = (pa.transform_point(&r.p1), pb.transform_point(&r.p2));
    assert!(
        ((w1 - w2).norm() - r.distance).abs() <= tol,
        "{what}: points vs distance"
    );
    if !r.intersecting {
        assert!(
            on_feature(a, r.feature1, &r.p1, tol),
            "{what}: p1 off its feature"
        );
        assert!(
            on_feature(b, r.feature2, &r.p2, tol),
            "{what}: p2 off its feature"
        );
    }
    assert_eq!(convex_intersect(a, pa, b, pb, None), Ok(r.intersecting));
}

#[test]
fn vclip_matches_brute_force_on_random_pairs() {
    let mut rng = Rng(101);
    let mut tally = Tally {
        apart: 0,
        touching: 0,
        overlapping: 0,
    };
    for round in 0..rounds(1500) {
        let (a, _) = random_hull(&mut rng, 4, 16);
        let (b, _) = random_hull(&mut rng, 4, 16);
        let pa = rng.axis_angle_pose(0.5);
        let pb = rng.axis_angle_pose(1.5);
        check_pair(&a, &pa, &b, &pb, &mut tally, &format!("pair {round}"));
    }
    assert!(
        tally.apart > 300 && tally.overlapping > 300,
        "{}/{}",
        tally.apart,
        tally.overlapping
    );
}

#[test]
fn vclip_matches_brute_force_when_touching() {
    // Separated pairs moved along their brute-force closest direction until they touch.
    let mut rng = Rng(202);
    let mut tally = Tally {
        apart: 0,
        touching: 0,
        overlapping: 0,
    };
    let mut done = 0;
    while done < rounds(500) {
        let (a, _) = random_hull(&mut rng, 4, 12);
        let (b, _) = random_hull(&mut rng, 4, 12);
        let pa = rng.axis_angle_pose(0.5);
        let mut pb = rng.axis_angle_pose(4.0);
        let (wa, wb) = (posed(&a, &pa), posed(&b, &pb));
        if brute_depth(&wa, &wb).0 > -1e-6 {
            continue;
        }
        let (_, qa, qb) = brute_distance(&wa, &wb);
        pb.translation -= qb - qa;
        check_pair(&a, &pa, &b, &pb, &mut tally, &format!("touching {done}"));
        let r = convex_distance(&a, &pa, &b, &pb, None).unwrap();
        assert!(r.distance <= 1e-9 * size_of(&wa).max(size_of(&wb)));
        done += 1;
    }
}

#[test]
fn vclip_on_boxes_with_parallel_faces() {
    // Axis-aligned boxes: face-face, edge-edge and vertex ties everywhere.
    let boxes: Vec<ConvexModel> = [[1.0, 1.0, 1.0], [2.0, 0.5, 1.0], [0.25, 3.0, 0.5]]
        .iter()
        .map(|s| {
            let mut p = Vec::new();
            for &x in &[-s[0], s[0]] {
                for &y in &[-s[1], s[1]] {
                    for &z in &[-s[2], s[2]] {
                        p.push([x, y, z]);
                    }
                }
            }
            ConvexModel::from_points(&p).unwrap()
        })
        .collect();
    let mut tally = Tally {
        apart: 0,
        touching: 0,
        overlapping: 0,
    };
    let mut rng = Rng(303);
    let steps = [
        -4.0, -3.0, -2.5, -2.0, -1.5, -1.25, -1.0, 0.0, 0.75, 1.25, 2.0, 3.0, 3.5,
    ];
    for round in 0..rounds(1500) {
        let a = &boxes[rng.below(3)];
        let b = &boxes[rng.below(3)];
        let t = [
            steps[rng.below(steps.len())],
            steps[rng.below(steps.len())],
            steps[rng.below(steps.len())],
        ];
        let pb = if round % 2 == 0 {
            Pose::from_translation(t)
        } else {
            // Quarter turns keep faces parallel.
            let r = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
            Pose::new(r, t)
        };
        check_pair(
            a,
            &Pose::identity(),
            b,
            &pb,
            &mut tally,
            &format!("boxes {round}"),
        );
    }
    assert!(tally.touching > 50 && tally.apart > 50 && tally.overlapping > 50);
}

#[test]
fn vclip_on_large_hulls() {
    let mut rng = Rng(404);
    let mut tally = Tally {
        apart: 0,
        touching: 0,
        overlapping: 0,
    };
    let clouds = [
        random_cloud(&mut rng, 1000, [1.0, 1.0, 1.0]),
        cylinder(2, 64, 1.0, 2.0),
        cube_grid(6),
    ];
    let models: Vec<ConvexModel> = clouds
        .iter()
        .map(|c| ConvexModel::from_points(c).unwrap())
        .collect();
    for round in 0..rounds(40) {
        let a = &models[round % 3];
        let b = &models[(round / 3) % 3];
        let (pa, pb) = (rng.axis_angle_pose(1.0), rng.axis_angle_pose(3.0));
        check_pair(a, &pa, b, &pb, &mut tally, &format!("large {round}"));
    }
}

#[test]
fn vclip_on_sliver_hulls() {
    // Hulls of perturbed grids, noisy spheres and needles: slivers and near-flat dihedrals.
    let mut rng = Rng(808);
    let mut tally = Tally {
        apart: 0,
        touching: 0,
        overlapping: 0,
    };
    let mut models = Vec::new();
    for k in 0..6 {
        let eps = [1e-15, 1e-12, 1e-9][k % 3];
        let mut grid = cube_grid(3 + k % 2);
        for p in grid.iter_mut() {
            for c in p.iter_mut() {
                *c += rng.range(-eps, eps);
            }
        }
        models.push(ConvexModel::from_points(&grid).unwrap());
        let sphere: Vec<[f64; 3]> = (0..40)
            .map(|_| {
                let u = rng.direction3() * (1.0 + rng.range(-eps, eps));
                [u.x, u.y, u.z]
            })
            .collect();
        models.push(ConvexModel::from_points(&sphere).unwrap());
        let needle = random_cloud(&mut rng, 12, [2.0, 1e-4, 1e-4]);
        models.push(ConvexModel::from_points(&needle).unwrap());
    }
    for round in 0..rounds(300) {
        let a = &models[rng.below(models.len())];
        let b = &models[rng.below(models.len())];
        let (pa, pb) = (rng.axis_angle_pose(0.5), rng.axis_angle_pose(2.0));
        check_pair(a, &pa, b, &pb, &mut tally, &format!("sliver {round}"));
    }
    assert!(tally.apart > 50 && tally.overlapping > 50);
}

#[test]
fn warm_starts_agree_with_cold_starts() {
    let mut rng = Rng(505);
    for round in 0..rounds(30) {
        let (a, _) = random_hull(&mut rng, 6, 40);
        let (b, _) = random_hull(&mut rng, 6, 40);
        let pa = rng.axis_angle_pose(0.5);
        let mut pb = rng.axis_angle_pose(3.0);
        let axis = rng.direction3();
        let drift = rng.direction3() * -0.02;
        let mut cache = ConvexPairCache::new();
        let (mut warm_iters, mut cold_iters) = (0u64, 0u64);
        for frame in 0..150 {
            let spin = rotation_about(&axis, 0.03);
            let r = Pose::new(spin, [0.0; 3]).rotation * pb.rotation;
            pb = Pose {
                rotation: r,
                translation: pb.translation + drift,
            };
            let warm = convex_distance(&a, &pa, &b, &pb, Some(&mut cache)).unwrap();
            let cold = convex_distance(&a, &pa, &b, &pb, None).unwrap();
            let what = format!("warm {round}/{frame}");
            assert!(
                (warm.distance - cold.distance).abs() <= 1e-9 * (1.0 + cold.distance),
                "{what}"
            );
            if cold.distance > 1e-9 {
                assert!(!warm.intersecting && !cold.intersecting, "{what}");
            } else {
                assert_eq!(warm.intersecting, cold.intersecting, "{what}");
            }
            assert_eq!(cache.features(), Some((warm.feature1, warm.feature2)));
            warm_iters += warm.stats.iterations as u64;
            cold_iters += cold.stats.iterations as u64;
        }
        assert!(
            warm_iters <= cold_iters,
            "round {round}: warm {warm_iters} cold {cold_iters}"
        );
    }
    // A cache is ignored for other models.
    let (a, _) = random_hull(&mut rng, 10, 1);
    let (b, _) = random_hull(&mut rng, 10, 1);
    let (c, _) = random_hull(&mut rng, 40, 1);
    let mut cache = ConvexPairCache::new();
    let p = Pose::from_translation([3.0, 0.0, 0.0]);
    convex_distance(&a, &Pose::identity(), &b, &p, Some(&mut cache)).unwrap();
    let x = convex_distance(&a, &Pose::identity(), &c, &p, Some(&mut cache)).unwrap();
    let y = convex_distance(&a, &Pose::identity(), &c, &p, None).unwrap();
    assert!((x.distance - y.distance).abs() < 1e-12);
}

#[test]
fn long_coherent_sequence_terminates() {
    // Many frames of small motion through separation, contact and deep overlap, warm-started: every
    // query must end (an exceeded bound would be `Err(Internal)`), without rounding cycles.
    let mut rng = Rng(606);
    let (a, _) = random_hull(&mut rng, 60, 1);
    let (b, _) = random_hull(&mut rng, 60, 1);
    let pa = Pose::identity();
    let mut cache = ConvexPairCache::new();
    let (mut total, mut worst) = (0u64, 0u32);
    let axis = rng.direction3();
    let frames = rounds(20_000);
    for frame in 0..frames {
        let t = frame as f64 * 0.002;
        let pb = Pose::new(
            rotation_about(&axis, t * 0.7),
            [
                3.0 * (t * 0.9).cos(),
                2.0 * (t * 1.3).sin(),
                1.5 * (t * 0.5).sin(),
            ],
        );
        let r = convex_distance(&a, &pa, &b, &pb, Some(&mut cache))
            .unwrap_or_else(|e| panic!("frame {frame}: {e}"));
        assert_eq!(r.stats.cycles_broken, 0, "frame {frame}");
        total += r.stats.iterations as u64;
        worst = worst.max(r.stats.iterations);
    }
    let avg = total as f64 / frames as f64;
    assert!(avg < 10.0, "average iterations {avg}");
    let _ = worst;
}

/// Largest signed distance of `p` to the face planes of `h`: 0 on the boundary.
fn boundary_offset(h: &Posed, p: &Vec3) -> f64 {
    h.faces
        .iter()
        .zip(&h.normals)
        .map(|(f, n)| {
            let off = f
                .iter()
                .map(|&i| h.verts[i].dot(n))
                .fold(f64::NEG_INFINITY, f64::max);
            p.dot(n) - off
        })
        .fold(f64::NEG_INFINITY, f64::max)
}

/// One pair's penetration against the separating-axis brute force; true if they overlapped.
/// `witnesses_on_boundary`: also check that the witnesses lie on the hulls' boundaries (with the
/// test's own float face planes, so not on sliver hulls).
fn check_penetration(
    a: &ConvexModel,
    pa: &Pose,
    b: &ConvexModel,
    pb: &Pose,
    witnesses_on_boundary: bool,
    what: &str,
) -> bool {
    let (wa, wb) = (posed(a, pa), posed(b, pb));
    let size = size_of(&wa).max(size_of(&wb));
    let tol = 1e-9 * size;
    let (depth, _) = brute_depth(&wa, &wb);
    let r = convex_penetration(a, pa, b, pb, None).unwrap();
    if depth <= tol {
        assert!(r.depth <= tol, "{what}");
        return false;
    }
    assert!(r.intersecting, "{what}");
    assert!(
        (r.depth - depth).abs() <= tol,
        "{what}: {} vs {depth}",
        r.depth
    );
    assert!((r.normal.norm() - 1.0).abs() < 1e-12);
    // Moving b by the depth along the normal separates the hulls (to rounding); a little less
    // does not.
    let moved = |s: f64| {
        let mut p = *pb;
        p.translation += r.normal * s;
        brute_depth(&wa, &posed(b, &p)).0
    };
    assert!(
        moved(r.depth).abs() <= tol,
        "{what}: normal does not separate"
    );
    assert!(moved(r.depth - 1e-6 * size) > 0.0, "{what}");
    // Witnesses: world(p1) = world(p2) + depth * normal, p1 on a's boundary, p2 on b's.
    let (w1, w2) = (pa.transform_point(&r.p1), pb.transform_point(&r.p2));
    assert!(
        (w1 - w2 - r.normal * r.depth).norm() <= tol,
        "{what}: witnesses"
    );
    if witnesses_on_boundary {
        assert!(
            boundary_offset(&wa, &w1).abs() <= tol,
            "{what}: p1 not on a"
        );
        assert!(
            boundary_offset(&wb, &w2).abs() <= tol,
            "{what}: p2 not on b"
        );
    }
    true
}

#[test]
fn penetration_depth_matches_brute_force() {
    let mut rng = Rng(707);
    let mut checked = 0;
    for round in 0..rounds(600) {
        let (a, _) = random_hull(&mut rng, 4, 12);
        let (b, _) = random_hull(&mut rng, 4, 12);
        let (pa, pb) = (rng.axis_angle_pose(0.5), rng.axis_angle_pose(1.5));
        checked +=
            check_penetration(&a, &pa, &b, &pb, true, &format!("penetration {round}")) as usize;
    }
    assert!(checked > 150, "{checked}");
    // Apart: depth 0, normal along the closest points.
    let (a, _) = random_hull(&mut rng, 8, 1);
    let p = Pose::from_translation([10.0, 0.0, 0.0]);
    let r = convex_penetration(&a, &Pose::identity(), &a, &p, None).unwrap();
    assert!(!r.intersecting && r.depth == 0.0 && r.normal.x > 0.5);
}

#[test]
fn penetration_depth_on_larger_and_degenerate_hulls() {
    let mut rng = Rng(909);
    let sphere = |rng: &mut Rng, n: usize| {
        let p: Vec<[f64; 3]> = (0..n)
            .map(|_| {
                let u = rng.direction3();
                [u.x, u.y, u.z]
            })
            .collect();
        ConvexModel::from_points(&p).unwrap()
    };
    let mut perturbed = cube_grid(4);
    for p in perturbed.iter_mut() {
        for c in p.iter_mut() {
            *c += rng.range(-1e-13, 1e-13);
        }
    }
    let models = [
        sphere(&mut rng, 40),
        sphere(&mut rng, 60),
        ConvexModel::from_points(&cube_grid(2)).unwrap(),
        ConvexModel::from_points(&cylinder(2, 12, 0.7, 2.0)).unwrap(),
        ConvexModel::from_points(&perturbed).unwrap(),
    ];
    let mut checked = 0;
    for round in 0..rounds(60) {
        let (i, j) = (rng.below(models.len()), rng.below(models.len()));
        // Axis-aligned poses half of the time: parallel faces and edges, ties between candidates.
        let (pa, pb) = if round % 2 == 0 {
            (rng.axis_angle_pose(0.5), rng.axis_angle_pose(1.5))
        } else {
            let t = [rng.range(-1.5, 1.5), rng.range(-1.5, 1.5), 0.0];
            (Pose::identity(), Pose::from_translation(t))
        };
        let what = format!("larger penetration {round} ({i}, {j})");
        checked +=
            check_penetration(&models[i], &pa, &models[j], &pb, i != 4 && j != 4, &what) as usize;
    }
    assert!(checked > 20, "{checked}");
}

#[test]
fn bad_poses_are_refused_and_models_are_shareable() {
    fn shareable<T: Send + Sync>() {}
    shareable::<ConvexModel>();
    shareable::<ConvexPairCache>();
    let a = ConvexModel::from_points(&cube_grid(2)).unwrap();
    let mut bad = Pose::identity();
    bad.translation.x = f64::NAN;
    assert_eq!(
        convex_distance(&a, &bad, &a, &Pose::identity(), None).map(|_| ()),
        Err(Error::NonFinitePose)
    );
    // Threads querying one model pair at once, each with its own cache.
    let b = ConvexModel::from_points(&cylinder(2, 16, 0.5, 1.0)).unwrap();
    std::thread::scope(|s| {
        for k in 0..2 {
            let (a, b) = (&a, &b);
            s.spawn(move || {
                let mut cache = ConvexPairCache::new();
                for i in 0..200 {
                    let x = 3.0 - 0.01 * (i + k) as f64;
                    let d = convex_distance(
                        a,
                        &Pose::identity(),
                        b,
                        &Pose::from_translation([x, 0.0, 0.0]),
                        Some(&mut cache),
                    )
                    .unwrap();
                    assert!((d.distance - (x - 1.5).max(0.0)).abs() < 1e-12);
                }
            });
        }
    });
}
