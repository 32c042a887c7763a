//! Geometric kernels against independent brute-force references.
//!
//! The reference distance between two simplices (point, segment or triangle) enumerates every pair
//! of faces (vertex, edge, face of each), solves the unconstrained least-squares problem on their
//! affine hulls, and keeps the feasible solutions: the minimum over the face pairs whose relative
//! interiors hold a closest pair is the distance. It shares no code or formulation with the
//! library (which clamps parameters and decides contact by orientation signs).

use pqp::Vec3;
use pqp::geometry::{
    ClosestPoints, Tri, point_triangle, segment_segment, tri_distance, tri_overlap,
};

mod common;
use common::{Random, RandomPqp, Rng};

// ---------------------------------------------------------------------------------------------
// References
// ---------------------------------------------------------------------------------------------

/// Solves the `k x k` system `m x = r` (k <= 3) by Gaussian elimination with partial pivoting;
/// `None` when a pivot is negligible (the face pair is degenerate or parallel: smaller faces
/// cover it).
fn solve(mut m: [[f64; 3]; 3], mut r: [f64; 3], k: usize) -> Option<[f64; 3]> {
    let scale = (0..k).map(|i| m[i][i].abs()).fold(0.0, f64::max);
    for c in 0..k {
        let p = (c..k).max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))?;
        if m[p][c].abs() <= 1e-14 * scale || m[p][c] == 0.0 {
            return None;
        }
        m.swap(c, p);
        r.swap(c, p);
        for i in c + 1..k {
            let f = m[i][c] / m[c][c];
            let pivot_row = m[c];
            for (x, &y) in m[i][c..k].iter_mut().zip(&pivot_row[c..k]) {
                *x -= f * y;
            }
            r[i] -= f * r[c];
        }
    }
    let mut x = [0.0; 3];
    for c in (0..k).rev() {
        let mut s = r[c];
        for j in c + 1..k {
            s -= m[c][j] * x[j];
        }
        x[c] = s / m[c][c];
    }
    Some(x)
}

/// Distance and a closest pair between the convex hulls of `a` and `b` (1 to 3 points each), by
/// enumeration of face pairs.
fn ref_closest(a: &[Vec3], b: &[Vec3]) -> (f64, Vec3, Vec3) {
    // Work relative to a vertex: the subtraction is where inputs far from the origin lose bits.
    let o = a[0];
    let a: Vec<Vec3> = a.iter().map(|v| v - o).collect();
    let b: Vec<Vec3> = b.iter().map(|v| v - o).collect();
    let mut best = (f64::INFINITY, Vec3::zeros(), Vec3::zeros());
    for fa in 1u32..(1 << a.len()) {
        for fb in 1u32..(1 << b.len()) {
            let ia: Vec<usize> = (0..a.len()).filter(|i| fa >> i & 1 == 1).collect();
            let ib: Vec<usize> = (0..b.len()).filter(|i| fb >> i & 1 == 1).collect();
            let k = ia.len() + ib.len() - 2;
            if k > 3 {
                continue;
            }
            let (a0, b0) = (a[ia[0]], b[ib[0]]);
            let mut cols = Vec::new();
            for &i in &ia[1..] {
                cols.push(a[i] - a0);
            }
            for &j in &ib[1..] {
                cols.push(b0 - b[j]);
            }
            let r0 = a0 - b0;
            let mut m = [[0.0; 3]; 3];
            let mut r = [0.0; 3];
            for i in 0..k {
                for j in 0..k {
                    m[i][j] = cols[i].dot(&cols[j]);
                }
                r[i] = -cols[i].dot(&r0);
            }
            let Some(x) = solve(m, r, k) else { continue };
            let (la, lb) = (&x[..ia.len() - 1], &x[ia.len() - 1..k]);
            let feasible = |l: &[f64]| l.iter().all(|&v| v >= 0.0) && l.iter().sum::<f64>() <= 1.0;
            if !feasible(la) || !feasible(lb) {
                continue;
            }
            let mut p = a0;
            for (n, &i) in ia[1..].iter().enumerate() {
                p += (a[i] - a0) * la[n];
            }
            let mut q = b0;
            for (n, &j) in ib[1..].iter().enumerate() {
                q += (b[j] - b0) * lb[n];
            }
            let d = (p - q).norm();
            if d < best.0 {
                best = (d, p + o, q + o);
            }
        }
    }
    best
}

fn ref_tri(a: &Tri, b: &Tri) -> f64 {
    ref_closest(a, b).0
}

/// Distance from `p` to triangle `t`, by the reference.
fn ref_point_tri(p: &Vec3, t: &Tri) -> f64 {
    ref_closest(&[*p], t).0
}

/// Segment distance by nested ternary search on the convex function
/// `s -> distance(p(s), segment q)`, with the inner distance by projection.
fn ref_seg_seg(p0: &Vec3, p1: &Vec3, q0: &Vec3, q1: &Vec3) -> f64 {
    let point_seg = |x: Vec3| {
        let d = q1 - q0;
        let dd = d.norm_squared();
        let t = if dd > 0.0 {
            ((x - q0).dot(&d) / dd).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (x - (q0 + d * t)).norm()
    };
    let at = |s: f64| point_seg(p0 + (p1 - p0) * s);
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    // (2/3)^120 ~ 1e-21 of the interval.
    for _ in 0..120 {
        let m1 = lo + (hi - lo) / 3.0;
        let m2 = hi - (hi - lo) / 3.0;
        if at(m1) <= at(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    at(0.5 * (lo + hi)).min(at(0.0)).min(at(1.0))
}

/// Largest distance between vertices: the size of the configuration.
fn spread(pts: &[Vec3]) -> f64 {
    let mut s = 0.0f64;
    for p in pts {
        for q in pts {
            s = s.max((p - q).norm());
        }
    }
    s
}

fn max_coord(pts: &[Vec3]) -> f64 {
    pts.iter().fold(0.0f64, |m, p| m.max(p.amax()))
}

/// What the kernels can be held to: 1e-9 relative, plus a few hundred roundings of the
/// configuration's size and of its coordinates (inputs far from the origin carry absolute
/// rounding in every difference).
fn tolerance(d: f64, pts: &[Vec3]) -> f64 {
    1e-9 * d + 1e-13 * spread(pts) + 1e-15 * max_coord(pts)
}

fn all6(a: &Tri, b: &Tri) -> Vec<Vec3> {
    vec![a[0], a[1], a[2], b[0], b[1], b[2]]
}

/// Checks a `tri_distance` answer against the reference and the contract; returns the reference
/// distance.
fn check_distance(a: &Tri, b: &Tri, what: &str) -> f64 {
    let r = tri_distance(a, b);
    let want = ref_tri(a, b);
    let pts = all6(a, b);
    let tol = tolerance(want, &pts);
    assert!(
        (r.distance - want).abs() <= tol,
        "{what}: distance {} vs reference {want} (tol {tol})\na = {a:?}\nb = {b:?}",
        r.distance
    );
    // The points are on their triangles and as far apart as reported.
    assert!(ref_point_tri(&r.p, a) <= tol, "{what}: p off a: {r:?}");
    assert!(ref_point_tri(&r.q, b) <= tol, "{what}: q off b: {r:?}");
    assert!(
        ((r.p - r.q).norm() - r.distance).abs() <= tol,
        "{what}: |p - q| != distance: {r:?}"
    );
    if r.distance == 0.0 {
        assert_eq!(r.p, r.q, "{what}: contact must give one point");
    }
    // Symmetric.
    let s = tri_distance(b, a);
    assert!(
        (s.distance - r.distance).abs() <= tol,
        "{what}: asymmetric {} {}",
        s.distance,
        r.distance
    );
    want
}

// ---------------------------------------------------------------------------------------------
// Random configurations
// ---------------------------------------------------------------------------------------------

fn random_tri(rng: &mut Rng, center: Vec3, size: f64) -> Tri {
    [
        center + rng.vec3(size),
        center + rng.vec3(size),
        center + rng.vec3(size),
    ]
}

/// An offset far from the origin: up to 1e6 in a random direction.
fn random_offset(rng: &mut Rng) -> Vec3 {
    if rng.unit() < 0.3 {
        Vec3::zeros()
    } else {
        rng.direction3() * rng.log10_uniform(0.0, 6.0)
    }
}

/// A random point of triangle `t` (uniform barycentric).
fn point_in(rng: &mut Rng, t: &Tri) -> Vec3 {
    let (mut u, mut v) = (rng.unit(), rng.unit());
    if u + v > 1.0 {
        u = 1.0 - u;
        v = 1.0 - v;
    }
    t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v
}

/// A triangle with vertex `v` and the rest of it on the far side of the plane through `v`
/// normal to `dir`.
fn tri_beyond(rng: &mut Rng, v: Vec3, dir: &Vec3, size: f64) -> Tri {
    let mut w = || loop {
        let u = rng.vec3(size);
        let along = u.dot(dir);
        if along > 0.05 * size {
            return v + u;
        }
        if along < -0.05 * size {
            return v - u;
        }
    };
    [v, w(), w()]
}

/// Unit normal of a nondegenerate triangle.
fn unit_normal(t: &Tri) -> Vec3 {
    (t[1] - t[0]).cross(&(t[2] - t[0])).normalize()
}

/// A pair at a known separation `g` (in exact arithmetic; the construction rounds) with the given
/// contact type: 0 vertex over face, 1 edge across edge, 2 vertex near edge, 3 parallel faces.
fn near_pair(rng: &mut Rng, kind: u32, offset: Vec3, size: f64, g: f64) -> (Tri, Tri) {
    let a = random_tri(rng, offset, size);
    let n = unit_normal(&a);
    let side = if rng.unit() < 0.5 { 1.0 } else { -1.0 };
    match kind {
        0 => {
            let x = point_in(rng, &a);
            let dir = n * side;
            (a, tri_beyond(rng, x + dir * g, &dir, size))
        }
        1 | 2 => {
            // A point on edge i and a direction in the edge's normal cone.
            let i = rng.int(0, 2) as usize;
            let (e0, e1) = (a[i], a[(i + 1) % 3]);
            let x = e0 + (e1 - e0) * rng.unit();
            let e = (e1 - e0).normalize();
            let mut m = n.cross(&e);
            if m.dot(&(a[(i + 2) % 3] - e0)) > 0.0 {
                m = -m;
            }
            let phi = rng.range(-1.5, 1.5);
            let dir = m * phi.cos() + n * phi.sin();
            let y = x + dir * g;
            if kind == 2 {
                return (a, tri_beyond(rng, y, &dir, size));
            }
            // An edge through y normal to dir, the third vertex beyond.
            let f = dir.cross(&rng.direction3()).normalize() * size;
            let (s0, s1) = (rng.range(0.1, 1.0), rng.range(0.1, 1.0));
            let third = tri_beyond(rng, y, &dir, size)[1];
            (a, [y - f * s0, y + f * s1, third])
        }
        _ => {
            // A copy moved off the plane by g and slid, spun in the plane.
            let c = (a[0] + a[1] + a[2]) / 3.0;
            let slide = n.cross(&rng.direction3()) * rng.range(0.0, size);
            let ang = rng.range(0.0, 6.3);
            let (u, w) = (
                (a[1] - a[0]).normalize(),
                n.cross(&(a[1] - a[0]).normalize()),
            );
            let spin = |p: Vec3| {
                let d = p - c;
                let (x, y) = (d.dot(&u), d.dot(&w));
                c + u * (x * ang.cos() - y * ang.sin()) + w * (x * ang.sin() + y * ang.cos())
            };
            let b = a.map(|p| spin(p) + slide + n * (g * side));
            (a, b)
        }
    }
}

#[test]
fn random_pairs_match_reference() {
    let mut rng = Rng(0x5eed);
    let mut hits = 0;
    for iter in 0..3000 {
        let off = random_offset(&mut rng);
        let size = rng.log10_uniform(-3.0, 3.0);
        let a = random_tri(&mut rng, off, size);
        // From far apart to overlapping.
        let sep = size * rng.range(0.0, 3.0);
        let cb = off + rng.direction3() * sep;
        let sb = size * rng.log10_uniform(-1.0, 1.0);
        let b = random_tri(&mut rng, cb, sb);
        let d = check_distance(&a, &b, &format!("random #{iter}"));
        hits += (d < 1e-12 * size) as u32;
        // Overlap agrees with distance 0 away from the borderline.
        if d > 1e-12 * size || d == 0.0 {
            assert_eq!(
                tri_overlap(&a, &b),
                tri_distance(&a, &b).distance == 0.0,
                "#{iter}"
            );
        }
    }
    // Both outcomes were exercised.
    assert!(hits > 100, "{hits}");
}

#[test]
fn nearly_touching_pairs_at_known_gaps() {
    let mut rng = Rng(42);
    for iter in 0..3000 {
        let kind = (iter % 4) as u32;
        let size = rng.log10_uniform(-2.0, 3.0);
        let off = if iter % 3 == 0 {
            Vec3::zeros()
        } else {
            rng.vec3(1.0) * rng.log10_uniform(0.0, 4.0)
        };
        let g = size * rng.log10_uniform(-12.0, 0.0);
        let (a, b) = near_pair(&mut rng, kind, off, size, g);
        let want = check_distance(&a, &b, &format!("near kind {kind} #{iter}"));
        let pts = all6(&a, &b);
        // The construction itself rounds by a few ulps of the coordinates.
        let slack = tolerance(g, &pts) + 8.0 * f64::EPSILON * max_coord(&pts);
        let got = tri_distance(&a, &b).distance;
        if kind != 3 {
            assert!(
                (got - g).abs() <= slack,
                "kind {kind} #{iter}: {got} vs gap {g} (ref {want})"
            );
        } else {
            // Parallel faces: at least the gap, exactly it where the projections overlap.
            assert!(got >= g - slack, "parallel #{iter}: {got} < {g}");
        }
        assert_eq!(tri_overlap(&a, &b), got == 0.0, "kind {kind} #{iter}");
        if g > slack {
            assert!(
                !tri_overlap(&a, &b),
                "kind {kind} #{iter}: separated by {g}"
            );
        }
    }
}

/// PQP 1.3 answers about 688 here: coordinates in the thousands, a vertex of one triangle within
/// 1.8e-12 of an edge of the other.
#[test]
fn vertex_near_edge_with_large_coordinates() {
    let mut rng = Rng(1812);
    // Random orientations: coordinates up to ~6000 round at ~1e-12 / 2, so the construction and
    // any double computation are good to a few 1e-13 only; the point is not answering hundreds.
    for iter in 0..3000 {
        let size = rng.range(500.0, 3000.0);
        let off = rng.vec3(3000.0);
        let g = 1.8e-12 * rng.range(0.5, 2.0);
        let (a, b) = near_pair(&mut rng, 2, off, size, g);
        let ulp = f64::EPSILON * max_coord(&all6(&a, &b));
        let got = tri_distance(&a, &b).distance;
        let want = ref_tri(&a, &b);
        assert!(
            (got - want).abs() <= 4.0 * ulp,
            "#{iter}: {got} vs reference {want}"
        );
        assert!((got - g).abs() <= 4.0 * ulp, "#{iter}: {got} vs gap {g}");
        assert_eq!(tri_overlap(&a, &b), got == 0.0);
    }
    // Exact instances: an edge along a coordinate axis in the thousands, a vertex of the other
    // triangle moved off it by exactly representable amounts, under exact axis permutations and
    // sign flips. The distance of these floats is known exactly.
    for iter in 0..3000 {
        let grid = 2f64.powi(-42); // ulp of [1024, 2048)
        let y0 = 1024.0 + rng.int(0, 1 << 20) as f64 * 2f64.powi(-10);
        let z0 = 1024.0 + rng.int(0, 1 << 20) as f64 * 2f64.powi(-10);
        let (x0, x1) = (rng.range(1030.0, 1400.0), rng.range(1600.0, 2000.0));
        let xm = rng.range(x0, x1);
        let xc = rng.range(1030.0, 2000.0);
        // a lies in the plane z = z0, on the side y < y0 of its edge.
        let a: Tri = [
            v(x0, y0, z0),
            v(x1, y0, z0),
            v(xc, y0 - rng.range(10.0, 900.0), z0),
        ];
        // Offsets: none (touching), or multiples of the grid from 0 to ~2e-12; gy >= 0 keeps the
        // closest point of a on the edge.
        let (gy, gz) = match iter % 4 {
            0 => (0.0, 0.0),
            1 => (rng.int(0, 9) as f64 * grid, 0.0),
            2 => (0.0, rng.int(-9, 9) as f64 * grid),
            _ => (rng.int(0, 9) as f64 * grid, rng.int(-9, 9) as f64 * grid),
        };
        let p = v(xm, y0 + gy, z0 + gz);
        // The rest of b away from a: beyond the plane through p normal to (gy, gz) if nonzero,
        // else up and outward.
        let dir = if gy == 0.0 && gz == 0.0 {
            v(0.0, 1.0, 1.0)
        } else {
            v(0.0, gy, gz)
        };
        let w1 = p
            + v(rng.range(-300.0, 300.0), 0.0, 0.0)
            + v(0.0, dir.y, dir.z).normalize() * rng.range(100.0, 900.0);
        let w2 = p
            + v(rng.range(-300.0, 300.0), 0.0, 0.0)
            + v(0.0, dir.y + 1e-13, dir.z).normalize() * rng.range(100.0, 900.0);
        let b: Tri = [p, w1, w2];
        let exact = (gy * gy + gz * gz).sqrt();
        // Exact relabelling of the axes.
        let perm = iter % 6;
        let flip = [iter % 7 < 3, iter % 5 < 2, iter % 3 == 0].map(|f| if f { -1.0 } else { 1.0 });
        let map = |q: Vec3| {
            let c = [q.x, q.y, q.z];
            let idx = [
                [0, 1, 2],
                [0, 2, 1],
                [1, 0, 2],
                [1, 2, 0],
                [2, 0, 1],
                [2, 1, 0],
            ][perm];
            v(
                c[idx[0]] * flip[0],
                c[idx[1]] * flip[1],
                c[idx[2]] * flip[2],
            )
        };
        let (a, b) = (a.map(map), b.map(map));
        let got = tri_distance(&a, &b);
        // Rounding of the foot along the edge (~1e-13 at these coordinates) adds in quadrature.
        let err2 = (got.distance * got.distance - exact * exact).abs();
        assert!(
            err2 <= 1e-25 + 2e-3 * exact * exact,
            "#{iter}: {} vs {exact}",
            got.distance
        );
        assert_eq!(tri_overlap(&a, &b), exact == 0.0, "#{iter}");
        if exact == 0.0 {
            assert_eq!(got.p, map(p));
        }
    }
    // The fixed case.
    let a: Tri = [
        v(1000.0, 2000.0, 1000.0),
        v(3000.0, 2000.0, 1000.0),
        v(2000.0, 4000.0, 1000.0),
    ];
    let b: Tri = [
        v(2000.0, 2000.0, 1000.0),
        v(2500.0, 1000.0, 1500.0),
        v(1500.0, 1000.0, 2000.0),
    ];
    let r = tri_distance(&a, &b);
    assert_eq!(r.distance, 0.0);
    assert_eq!(r.p, v(2000.0, 2000.0, 1000.0));
    assert!(tri_overlap(&a, &b));
    let lift = 1000.0 + 1.8e-12;
    let b2: Tri = [v(2000.0, 2000.0, lift), b[1], b[2]];
    assert_eq!(tri_distance(&a, &b2).distance, lift - 1000.0);
    assert!(!tri_overlap(&a, &b2));
    let b3: Tri = [v(2000.0, 2000.0 - 1.8e-12, 1000.0), b[1], b[2]];
    assert_eq!(tri_distance(&a, &b3).distance, 2000.0 - b3[0].y);
    assert!(!tri_overlap(&a, &b3));
}

// ---------------------------------------------------------------------------------------------
// Exact contact on lattice configurations
// ---------------------------------------------------------------------------------------------

/// Small-integer coordinates make touching, coplanar and degenerate configurations common; their
/// nonzero distances are far above rounding, so the reference separates contact from near miss.
/// The lattice is scaled by a power of two and moved by an exactly representable offset.
#[test]
fn lattice_contact_is_exact() {
    let mut rng = Rng(99);
    let mut counts = [0u32; 2];
    let shifts = [
        (1.0, 0.0),
        (2f64.powi(-20), 1000.0),
        (2f64.powi(30), -2f64.powi(40)),
        (2f64.powi(-60), 2f64.powi(-50)),
    ];
    for iter in 0..4000 {
        let n = if iter % 2 == 0 { 2 } else { 3 };
        let mut v = || {
            Vec3::new(
                rng.int(0, n) as f64,
                rng.int(0, n) as f64,
                rng.int(0, n) as f64,
            )
        };
        let a: Tri = [v(), v(), v()];
        let b: Tri = [v(), v(), v()];
        let (s, off) = shifts[iter % 4];
        let map = |t: &Tri| t.map(|p| p * s + Vec3::new(off, off, off));
        let (sa, sb) = (map(&a), map(&b));
        let d = ref_tri(&a, &b);
        let touching = d < 1e-9;
        counts[touching as usize] += 1;
        assert_eq!(
            tri_overlap(&sa, &sb),
            touching,
            "#{iter}: {a:?} {b:?} ref {d}"
        );
        let r = tri_distance(&sa, &sb);
        assert_eq!(r.distance == 0.0, touching, "#{iter}: {a:?} {b:?} {r:?}");
        if touching {
            assert_eq!(r.p, r.q);
            // The common point is on both (to rounding, in lattice units).
            // The common point is on both, to the rounding of the shifted coordinates.
            let back = (r.p - Vec3::new(off, off, off)) / s;
            let tol = 1e-9 + 8.0 * f64::EPSILON * (off.abs() + 3.0 * s) / s;
            assert!(
                ref_point_tri(&back, &a) < tol && ref_point_tri(&back, &b) < tol,
                "#{iter}: {back:?}"
            );
        } else {
            assert!(
                (r.distance / s - d).abs() < 1e-9,
                "#{iter}: {} vs {d}",
                r.distance / s
            );
        }
        // Exactness makes the answer independent of vertex order and argument order.
        let perm = |t: &Tri, k: usize| match k {
            0 => [t[1], t[2], t[0]],
            1 => [t[2], t[1], t[0]],
            _ => [t[0], t[2], t[1]],
        };
        for k in 0..3 {
            assert_eq!(
                tri_overlap(&perm(&sa, k), &sb),
                touching,
                "#{iter} perm {k}"
            );
            assert_eq!(
                tri_overlap(&sb, &perm(&sa, k)),
                touching,
                "#{iter} swapped perm {k}"
            );
        }
    }
    assert!(counts[0] > 700 && counts[1] > 700, "{counts:?}");
}

// ---------------------------------------------------------------------------------------------
// Named configurations
// ---------------------------------------------------------------------------------------------

fn v(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(x, y, z)
}

fn unit_tri(z: f64) -> Tri {
    [v(0.0, 0.0, z), v(1.0, 0.0, z), v(0.0, 1.0, z)]
}

#[test]
fn overlap_known_cases() {
    let a = unit_tri(0.0);
    let cases: Vec<(&str, Tri, bool)> = vec![
        (
            "crossing",
            [v(0.2, 0.2, -1.0), v(0.3, 0.2, 1.0), v(0.2, 0.3, 1.0)],
            true,
        ),
        (
            "piercing edge",
            [v(0.5, -0.5, 0.5), v(0.5, 0.5, -0.5), v(5.0, 5.0, 5.0)],
            true,
        ),
        (
            "vertex on face",
            [v(0.25, 0.25, 0.0), v(1.0, 1.0, 1.0), v(0.0, 1.0, 1.0)],
            true,
        ),
        (
            "vertex on edge",
            [v(0.5, 0.0, 0.0), v(0.5, -1.0, 1.0), v(0.0, -1.0, 1.0)],
            true,
        ),
        (
            "vertex on vertex",
            [v(1.0, 0.0, 0.0), v(2.0, 0.0, 1.0), v(2.0, 1.0, 0.0)],
            true,
        ),
        (
            "edge across edge",
            [v(0.5, -0.5, 0.0), v(0.5, 0.5, 0.0), v(0.5, 0.0, 1.0)],
            true,
        ),
        (
            "edges touching off-plane",
            [v(0.25, -0.5, 0.5), v(0.25, 0.5, -0.5), v(0.25, -1.0, -1.0)],
            true,
        ),
        (
            "coplanar overlapping",
            [v(0.5, 0.5, 0.0), v(-0.5, 0.5, 0.0), v(0.5, -0.5, 0.0)],
            true,
        ),
        (
            "coplanar contained",
            [v(0.1, 0.1, 0.0), v(0.2, 0.1, 0.0), v(0.1, 0.2, 0.0)],
            true,
        ),
        (
            "coplanar containing",
            [v(-1.0, -1.0, 0.0), v(3.0, -1.0, 0.0), v(-1.0, 3.0, 0.0)],
            true,
        ),
        (
            "coplanar shared edge",
            [v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0), v(1.0, 1.0, 0.0)],
            true,
        ),
        (
            "coplanar vertex touch",
            [v(1.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(2.0, 1.0, 0.0)],
            true,
        ),
        ("identical", unit_tri(0.0), true),
        (
            "coplanar disjoint",
            [v(0.6, 0.6, 0.0), v(1.6, 0.6, 0.0), v(0.6, 1.6, 0.0)],
            false,
        ),
        ("parallel", unit_tri(1e-300), false),
        (
            "above",
            [v(0.2, 0.2, 0.1), v(0.3, 0.2, 1.0), v(0.2, 0.3, 1.0)],
            false,
        ),
        (
            "edge passing by",
            [v(0.6, 0.6, -1.0), v(0.6, 0.6, 1.0), v(3.0, 3.0, 0.0)],
            false,
        ),
        (
            "plane crossed outside",
            [v(2.0, 2.0, -1.0), v(2.0, 3.0, 1.0), v(3.0, 2.0, 1.0)],
            false,
        ),
    ];
    for (name, b, want) in cases {
        for (x, y) in [(&a, &b), (&b, &a)] {
            assert_eq!(tri_overlap(x, y), want, "{name}");
            let r = tri_distance(x, y);
            assert_eq!(r.distance == 0.0, want, "{name}: {r:?}");
            check_distance(x, y, name);
        }
    }
}

#[test]
fn degenerate_triangles() {
    let a = unit_tri(0.0);
    let seg = |p: Vec3, q: Vec3| -> Tri { [p, q, q] };
    let mid = |p: Vec3, q: Vec3| -> Tri { [p, (p + q) * 0.5, q] };
    let pt = |p: Vec3| -> Tri { [p, p, p] };
    let cases: Vec<(&str, Tri, bool)> = vec![
        (
            "segment piercing",
            seg(v(0.2, 0.2, -1.0), v(0.2, 0.2, 1.0)),
            true,
        ),
        (
            "segment (3 collinear) piercing",
            mid(v(0.2, 0.2, -1.0), v(0.2, 0.2, 1.0)),
            true,
        ),
        (
            "segment touching face",
            seg(v(0.2, 0.2, 0.0), v(0.2, 0.2, 1.0)),
            true,
        ),
        (
            "segment in plane crossing",
            mid(v(-1.0, 0.5, 0.0), v(2.0, 0.25, 0.0)),
            true,
        ),
        (
            "segment in plane inside",
            seg(v(0.1, 0.1, 0.0), v(0.2, 0.3, 0.0)),
            true,
        ),
        (
            "segment in plane outside",
            seg(v(1.0, 1.0, 0.0), v(2.0, 0.5, 0.0)),
            false,
        ),
        (
            "segment missing",
            seg(v(2.0, 2.0, -1.0), v(2.0, 2.0, 1.0)),
            false,
        ),
        (
            "segment above",
            seg(v(0.2, 0.2, 0.5), v(0.3, 0.1, 1.0)),
            false,
        ),
        ("point on face", pt(v(0.25, 0.5, 0.0)), true),
        ("point on edge", pt(v(0.5, 0.5, 0.0)), true),
        ("point at vertex", pt(v(0.0, 1.0, 0.0)), true),
        ("point off", pt(v(0.25, 0.5, 1e-9)), false),
        ("point in plane outside", pt(v(0.6, 0.6, 0.0)), false),
    ];
    for (name, b, want) in cases {
        for (x, y) in [(&a, &b), (&b, &a)] {
            assert_eq!(tri_overlap(x, y), want, "{name}");
            assert_eq!(tri_distance(x, y).distance == 0.0, want, "{name}");
            check_distance(x, y, name);
        }
    }
    // Both degenerate.
    let both: Vec<(&str, Tri, Tri, bool)> = vec![
        (
            "crossing segments",
            seg(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0)),
            mid(v(0.0, 2.0, 0.0), v(2.0, 0.0, 2.0)),
            true,
        ),
        (
            "skew segments",
            seg(v(0.0, 0.0, 0.0), v(2.0, 2.0, 0.0)),
            seg(v(0.0, 2.0, 1.0), v(2.0, 0.0, 1.0)),
            false,
        ),
        (
            "collinear overlapping",
            seg(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0)),
            seg(v(1.0, 1.0, 1.0), v(3.0, 3.0, 3.0)),
            true,
        ),
        (
            "collinear disjoint",
            seg(v(0.0, 0.0, 0.0), v(1.0, 1.0, 1.0)),
            seg(v(2.0, 2.0, 2.0), v(3.0, 3.0, 3.0)),
            false,
        ),
        (
            "vertical collinear touching",
            seg(v(1.0, 1.0, 0.0), v(1.0, 1.0, 1.0)),
            seg(v(1.0, 1.0, 1.0), v(1.0, 1.0, 3.0)),
            true,
        ),
        (
            "vertical collinear apart",
            seg(v(1.0, 1.0, 0.0), v(1.0, 1.0, 1.0)),
            seg(v(1.0, 1.0, 2.0), v(1.0, 1.0, 3.0)),
            false,
        ),
        (
            "point on segment",
            pt(v(1.0, 1.0, 1.0)),
            seg(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0)),
            true,
        ),
        (
            "point off segment",
            pt(v(1.0, 1.0, 1.5)),
            seg(v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0)),
            false,
        ),
        (
            "same point",
            pt(v(1.0, 2.0, 3.0)),
            pt(v(1.0, 2.0, 3.0)),
            true,
        ),
        (
            "two points",
            pt(v(1.0, 2.0, 3.0)),
            pt(v(1.0, 2.0, 4.0)),
            false,
        ),
    ];
    for (name, x, y, want) in both {
        for (x, y) in [(&x, &y), (&y, &x)] {
            assert_eq!(tri_overlap(x, y), want, "{name}");
            assert_eq!(tri_distance(x, y).distance == 0.0, want, "{name}");
            check_distance(x, y, name);
        }
    }
}

#[test]
fn random_degenerate_and_sliver_triangles() {
    let mut rng = Rng(2024);
    for iter in 0..2000 {
        let size = rng.log10_uniform(-1.0, 1.0);
        let a = random_tri(&mut rng, Vec3::zeros(), size);
        let p = rng.vec3(size);
        let q = rng.vec3(size);
        let b: Tri = match iter % 4 {
            0 => [p, p, p],
            1 => [p, q, q],
            2 => [p, q, p + (q - p) * 0.5],
            // A sliver: the third vertex off the segment by a tiny amount.
            _ => {
                let w = (q - p).cross(&rng.direction3()).normalize()
                    * size
                    * rng.log10_uniform(-14.0, -6.0);
                [p, q, p + (q - p) * rng.unit() + w]
            }
        };
        check_distance(&a, &b, &format!("degenerate #{iter}"));
        check_distance(
            &b,
            &b.map(|x| x + rng.vec3(size)),
            &format!("degenerate pair #{iter}"),
        );
    }
}

/// A vertex hovering over the interior of a sliver face (sine of its angle down to 1e-12) at a
/// known height: the plain float normal of a sliver is tilted by rounding far more than the height.
/// (The reference's normal equations are as ill-conditioned here, so the construction is the
/// reference.)
#[test]
fn vertex_over_a_sliver_face() {
    let mut rng = Rng(31);
    for iter in 0..2000 {
        let size = rng.log10_uniform(-1.0, 2.0);
        let p = rng.vec3(size);
        let q = p + rng.direction3() * size;
        let along = (q - p).normalize();
        let m = along.cross(&rng.direction3()).normalize();
        let width = size * rng.log10_uniform(-12.0, -4.0);
        let a: Tri = [p, q, p + (q - p) * rng.range(0.2, 0.8) + m * width];
        // The exact normal direction of this sliver: along x m, to the rounding of the inputs.
        let n = along.cross(&m);
        let x = (a[0] + a[1] + a[2]) / 3.0;
        let h = size * rng.log10_uniform(-9.0, -1.0);
        let top = x + n * h;
        let b = tri_beyond(&mut rng, top, &n, size);
        let got = tri_distance(&a, &b).distance;
        // The vertex is within the sliver's footprint by about width / 3; rounding of the
        // construction moves things by ~1e-16 size.
        let slack = 1e-9 * h + 1e-14 * size;
        assert!(
            (got - h).abs() <= slack,
            "#{iter}: {got} vs {h} (width {width})"
        );
        let r = point_triangle(&top, &a);
        assert!(
            (r.distance - h).abs() <= slack,
            "#{iter}: point {} vs {h}",
            r.distance
        );
    }
}

#[test]
fn shared_features_and_identity() {
    let mut rng = Rng(5);
    for iter in 0..500 {
        let off = random_offset(&mut rng);
        let a = random_tri(&mut rng, off, 1.0);
        let c = rng.vec3(2.0) + a[0];
        for (name, b) in [
            ("identical", a),
            ("shared edge", [a[1], a[0], c]),
            ("shared vertex", [a[2], c, c + rng.vec3(1.0)]),
            ("reversed", [a[2], a[1], a[0]]),
        ] {
            let r = tri_distance(&a, &b);
            assert_eq!(r.distance, 0.0, "{name} #{iter}");
            assert!(tri_overlap(&a, &b), "{name} #{iter}");
            check_distance(&a, &b, name);
        }
    }
}

#[test]
fn extreme_scales_are_exact_rescalings() {
    let mut rng = Rng(77);
    for iter in 0..300 {
        let g = rng.log10_uniform(-6.0, 0.0);
        let (a, b) = near_pair(&mut rng, (iter % 4) as u32, Vec3::zeros(), 1.0, g);
        let base = tri_distance(&a, &b);
        for k in [-500, -200, -100, 100, 200, 300, 480] {
            let s = 2f64.powi(k);
            let (sa, sb) = (a.map(|p| p * s), b.map(|p| p * s));
            let r = tri_distance(&sa, &sb);
            assert!(
                (r.distance / s - base.distance).abs() <= 1e-12 * base.distance,
                "k {k}: {} {}",
                r.distance / s,
                base.distance
            );
            assert_eq!(tri_overlap(&sa, &sb), base.distance == 0.0);
            let c = segment_segment(&sa[0], &sa[1], &sb[0], &sb[1]);
            let c0 = segment_segment(&a[0], &a[1], &b[0], &b[1]);
            assert!((c.distance / s - c0.distance).abs() <= 1e-12 * c0.distance.max(1e-300));
            let t = point_triangle(&sb[0], &sa);
            let t0 = point_triangle(&b[0], &a);
            assert!((t.distance / s - t0.distance).abs() <= 1e-12 * t0.distance.max(1e-300));
        }
    }
    // Crossing triangles at 1e140 still touch exactly, with a common point.
    let s = 1e140;
    let a = unit_tri(0.0).map(|p| p * s);
    let b = [v(0.2, 0.2, -1.0), v(0.3, 0.2, 1.0), v(0.2, 0.3, 1.0)].map(|p| p * s);
    let r = tri_distance(&a, &b);
    assert_eq!(r.distance, 0.0);
    assert!(ref_point_tri(&(r.p / s), &unit_tri(0.0)) < 1e-12);
    assert!(tri_overlap(&a, &b));
}

// ---------------------------------------------------------------------------------------------
// Segment-segment and point-triangle
// ---------------------------------------------------------------------------------------------

fn check_segments(p0: &Vec3, p1: &Vec3, q0: &Vec3, q1: &Vec3, what: &str) {
    let r: ClosestPoints = segment_segment(p0, p1, q0, q1);
    let want = ref_seg_seg(p0, p1, q0, q1);
    let pts = [*p0, *p1, *q0, *q1];
    let tol = tolerance(want, &pts);
    assert!(
        (r.distance - want).abs() <= tol,
        "{what}: {} vs {want}",
        r.distance
    );
    assert!(ref_closest(&[r.p], &[*p0, *p1]).0 <= tol, "{what}: p off");
    assert!(ref_closest(&[r.q], &[*q0, *q1]).0 <= tol, "{what}: q off");
    assert!(((r.p - r.q).norm() - r.distance).abs() <= tol, "{what}");
    // And the face-pair reference agrees too.
    assert!(
        (ref_closest(&[*p0, *p1], &[*q0, *q1]).0 - want).abs() <= tol,
        "{what}: references disagree"
    );
}

#[test]
fn segments_match_reference() {
    let mut rng = Rng(3);
    for iter in 0..2000 {
        let size = rng.log10_uniform(-3.0, 3.0);
        let off = random_offset(&mut rng);
        let p0 = off + rng.vec3(size);
        let mut p1 = off + rng.vec3(size);
        let mut q0 = off + rng.vec3(size);
        let mut q1 = off + rng.vec3(size);
        match iter % 6 {
            // Parallel (to rounding), collinear, zero length, nearly parallel.
            0 => {
                let d = p1 - p0;
                q1 = q0 + d * rng.range(-2.0, 2.0);
            }
            1 => {
                let d = p1 - p0;
                q0 = p0 + d * rng.range(-2.0, 2.0);
                q1 = p0 + d * rng.range(-2.0, 2.0);
            }
            2 => p1 = p0,
            3 => {
                q1 = q0;
                if iter % 12 == 3 {
                    p1 = p0;
                }
            }
            4 => {
                let d = p1 - p0;
                q1 = q0
                    + (d + rng.vec3(size) * rng.log10_uniform(-12.0, -3.0)) * rng.range(-2.0, 2.0);
            }
            _ => {}
        }
        check_segments(&p0, &p1, &q0, &q1, &format!("segments #{iter}"));
    }
}

#[test]
fn nearly_parallel_crossing_segments_are_accurate() {
    // Segments through a common point c at angles down to 1e-12: the distance must stay at
    // rounding level, not grow as rounding / angle.
    let mut rng = Rng(8);
    for iter in 0..2000 {
        let c = rng.vec3(10.0);
        let u = rng.direction3();
        let w = u.cross(&rng.direction3()).normalize();
        let ang = rng.log10_uniform(-12.0, -1.0);
        let v = u * ang.cos() + w * ang.sin();
        let (s0, s1, t0, t1) = (
            rng.range(0.1, 5.0),
            rng.range(0.1, 5.0),
            rng.range(0.1, 5.0),
            rng.range(0.1, 5.0),
        );
        let r = segment_segment(&(c - u * s0), &(c + u * s1), &(c - v * t0), &(c + v * t1));
        // Rounding of the endpoints alone moves the lines by ~1e-15 of their extent.
        assert!(r.distance <= 1e-13, "#{iter} angle {ang}: {}", r.distance);
    }
}

#[test]
fn point_triangle_matches_reference() {
    let mut rng = Rng(13);
    for iter in 0..3000 {
        let size = rng.log10_uniform(-3.0, 3.0);
        let off = random_offset(&mut rng);
        let mut t = random_tri(&mut rng, off, size);
        match iter % 5 {
            0 => t[2] = t[1],
            1 => t = [t[0], t[0], t[0]],
            2 => t[2] = t[0] + (t[1] - t[0]) * 0.25,
            _ => {}
        }
        let p = if iter % 7 == 0 {
            point_in(&mut rng, &t)
        } else {
            off + rng.vec3(2.0 * size)
        };
        let r = point_triangle(&p, &t);
        let want = ref_point_tri(&p, &t);
        let mut pts = t.to_vec();
        pts.push(p);
        let tol = tolerance(want, &pts);
        assert_eq!(r.p, p);
        assert!(
            (r.distance - want).abs() <= tol,
            "#{iter}: {} vs {want}",
            r.distance
        );
        assert!(
            ref_point_tri(&r.q, &t) <= tol,
            "#{iter}: q off the triangle"
        );
        assert!(((r.p - r.q).norm() - r.distance).abs() <= tol, "#{iter}");
    }
}

// ---------------------------------------------------------------------------------------------
// Throughput (run with `cargo test --release --test geometry -- --ignored --nocapture`)
// ---------------------------------------------------------------------------------------------

#[test]
#[ignore]
fn throughput() {
    use std::time::Instant;
    let reps: usize = std::env::var("THROUGHPUT_REPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(40);
    let rounds: usize = std::env::var("THROUGHPUT_ROUNDS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(7);
    let mut rng = Rng(1);
    // Leaf pairs of a distance query: mostly apart by a few triangle sizes ("far"); near contact
    // and intersecting ("near").
    let only = std::env::var("THROUGHPUT_SET").unwrap_or_default();
    for (name, lo, hi) in [("far", 2.0, 6.0), ("near", 0.0, 2.0)] {
        if !only.is_empty() && only != name {
            continue;
        }
        let pairs: Vec<(Tri, Tri)> = (0..4096)
            .map(|_| {
                let a = random_tri(&mut rng, Vec3::zeros(), 1.0);
                let c = rng.direction3() * rng.range(lo, hi);
                (a, random_tri(&mut rng, c, 1.0))
            })
            .collect();
        // Best of several rounds: the machine is shared.
        let (mut dt, mut dt2) = (f64::INFINITY, f64::INFINITY);
        let (mut acc, mut hits) = (0.0, 0usize);
        for _ in 0..rounds {
            let t = Instant::now();
            for _ in 0..reps {
                for (a, b) in &pairs {
                    acc += tri_distance(a, b).distance;
                }
            }
            dt = dt.min(t.elapsed().as_secs_f64() / (reps * pairs.len()) as f64);
            let t2 = Instant::now();
            for _ in 0..reps {
                for (a, b) in &pairs {
                    hits += tri_overlap(a, b) as usize;
                }
            }
            dt2 = dt2.min(t2.elapsed().as_secs_f64() / (reps * pairs.len()) as f64);
        }
        println!(
            "{name}: tri_distance {:.1} ns/call, tri_overlap {:.1} ns/call ({acc:.3} {hits})",
            dt * 1e9,
            dt2 * 1e9
        );
    }
}

/// Non-finite coordinates are refused when models are built, but the kernels must still not
/// panic on them (the library never panics across the C ABI).
#[test]
fn non_finite_input_does_not_panic() {
    let a = unit_tri(0.0);
    for bad in [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MAX,
        f64::MIN_POSITIVE / 3.0,
    ] {
        for k in 0..9 {
            let mut b = unit_tri(0.5);
            b[k / 3][k % 3] = bad;
            let _ = tri_distance(&a, &b);
            let _ = tri_distance(&b, &a);
            let _ = tri_overlap(&a, &b);
            let _ = tri_overlap(&b, &b);
            let _ = segment_segment(&a[0], &a[1], &b[0], &b[1]);
            let _ = point_triangle(&b[0], &b);
        }
    }
}

/// Near-touching disjoint triangles (a vertex of one a few ulps off an edge or the face of the
/// other): the distance is 0 exactly when `tri_overlap` finds contact, and otherwise positive,
/// however far below rounding the gap is (it was once reported as 0, with the models flagged as
/// overlapping while collision found no contact).
#[test]
fn disjoint_triangles_are_never_at_distance_zero() {
    let v = |x: f64, y: f64, z: f64| Vec3::new(x, y, z);
    // A gap of 5.45e-18, exactly (rational arithmetic).
    let a: Tri = [
        v(1.0, 0.0, 0.25),
        v(
            9.064322256678745e-1,
            -1.2520958041876146e-1,
            1.7506994258459135e-1,
        ),
        v(
            9.088266031750115e-1,
            -1.2407574393634253e-1,
            1.7435222752896343e-1,
        ),
    ];
    let b: Tri = [
        v(
            9.087561920911569e-1,
            -1.2410908648796735e-1,
            1.7437333326304877e-1,
        ),
        v(0.0, 0.0, 0.0),
        v(0.0, -3.828125e-1, 0.0),
    ];
    assert!(!tri_overlap(&a, &b));
    let d = tri_distance(&a, &b).distance;
    assert!(d > 0.0 && d <= 1e-15, "{d:e}");

    let mut rng = Rng(61);
    let (mut apart, mut touching) = (0, 0);
    for k in 0..20000 {
        let a: Tri = [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)];
        // A point on an edge or inside the face of a, nudged by a few ulps.
        let (s, t) = (rng.unit(), rng.unit());
        let on = if k % 2 == 0 {
            a[0] + (a[1] - a[0]) * s
        } else {
            a[0] + (a[1] - a[0]) * (s * 0.5) + (a[2] - a[0]) * (t * 0.5)
        };
        let tip = on + rng.direction3() * (f64::EPSILON * rng.range(0.0, 4.0));
        let away = rng.direction3();
        let b: Tri = [tip, tip + away, tip + rng.vec3(1.0).cross(&away)];
        let d = tri_distance(&a, &b).distance;
        if tri_overlap(&a, &b) {
            touching += 1;
            assert_eq!(d, 0.0, "case {k}");
        } else {
            apart += 1;
            assert!(d > 0.0 && d <= 1e-14, "case {k}: {d:e}");
        }
    }
    assert!(
        apart > 1000 && touching > 1000,
        "{apart} apart, {touching} touching"
    );
}

/// Contact between triangles whose coordinates span more magnitudes than the orientation
/// predicates' expansions hold (1e128 beside 1e-6): an exactly collinear triangle far above a
/// small one, the signs must still be exact (the expansions once underflowed and found the small
/// triangle's vertices off the collinear one's degenerate plane, so that contact was reported).
#[test]
fn contact_is_exact_across_any_span_of_magnitudes() {
    let v = |x: f64, y: f64, z: f64| Vec3::new(x, y, z);
    let cases: [(Tri, Tri, f64); 2] = [
        (
            [
                v(
                    1101.5697305148933,
                    -1531.2841024189256,
                    7.067056208293714e128,
                ),
                v(
                    1.8277582005830482,
                    -5.824099390767515,
                    7.067056208293714e128,
                ),
                v(
                    -1097.9142141137272,
                    1519.6359036373906,
                    7.067056208293714e128,
                ),
            ],
            [
                v(
                    -3.5142293199896812e-6,
                    1.4300458133220673e-6,
                    814531.7163514459,
                ),
                v(
                    0.001003365614451468,
                    -0.03957756399177015,
                    814531.7163514459,
                ),
                v(0.0004999256925657392, -0.019788066972978413, 0.0),
            ],
            7.067056208293714e128,
        ),
        (
            [
                v(-544314.4081678336, 693886.4847471683, 5.883840431647178e128),
                v(-542974.0179784893, 691890.3785868773, 5.883840431647178e128),
                v(-543644.2130731614, 692888.4316670228, 5.883840431647178e128),
            ],
            [
                v(-543744.1748092918, 692023.2762037627, 726198.0302589582),
                v(-543744.8681597573, 692023.1733819772, 726197.774868045),
                v(-543744.5214845246, 692023.22479287, 726197.9025635016),
            ],
            5.883840431647178e128,
        ),
    ];
    for (a, b, height) in cases {
        for (x, y) in [(&a, &b), (&b, &a)] {
            assert!(!tri_overlap(x, y));
            let d = tri_distance(x, y).distance;
            assert!((d - height).abs() <= 1e-9 * height, "{d:e}");
        }
    }
}
