//! PQP 1.3's BV.h through the C ABI: pqp_bv_fit, pqp_bv_overlap and pqp_bv_distance against
//! brute force written here (an independent separating-axis test, point sampling, and rectangles
//! as triangle pairs measured by the tests' own triangle distance).

// Edition 2024: these helpers' bodies call the C ABI under their own `unsafe fn` contract.
#![allow(unsafe_op_in_unsafe_fn)]

mod common;

use common::{Random, Rng, T, V, add, cross, dot, norm, scale, sub, tri_tri};
use pqp::capi::*;
use std::ptr;

type M3 = [[f64; 3]; 3];

fn flat(r: &M3) -> [f64; 9] {
    [
        r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2],
    ]
}

fn column(r: &M3, j: usize) -> V {
    [r[0][j], r[1][j], r[2][j]]
}

fn mat_vec(r: &M3, v: V) -> V {
    [dot(r[0], v), dot(r[1], v), dot(r[2], v)]
}

/// `r^T v`.
fn tr_vec(r: &M3, v: V) -> V {
    [
        dot(column(r, 0), v),
        dot(column(r, 1), v),
        dot(column(r, 2), v),
    ]
}

/// A volume with the given half extents, sides and radius (the rest zero).
fn bv(d: V, l: [f64; 2], r: f64) -> pqp_bv {
    pqp_bv {
        d,
        l,
        r,
        ..pqp_bv::default()
    }
}

unsafe fn overlap(r: &M3, t: V, b1: &pqp_bv, b2: &pqp_bv) -> bool {
    let mut o = -1;
    assert_eq!(
        pqp_bv_overlap(&mut o, flat(r).as_ptr(), t.as_ptr(), b1, b2),
        PQP_OK
    );
    assert!(o == 0 || o == 1);
    o == 1
}

unsafe fn distance(r: &M3, t: V, b1: &pqp_bv, b2: &pqp_bv) -> f64 {
    let mut d = f64::NAN;
    assert_eq!(
        pqp_bv_distance(&mut d, flat(r).as_ptr(), t.as_ptr(), b1, b2),
        PQP_OK
    );
    d
}

/// The largest gap between the boxes' projections on the 15 candidate axes (box 1 about the
/// origin with half extents `d1`, box 2 placed by `(r, t)`), each axis normalized, with whether it
/// came from a face normal: positive means separated by that much.
fn separation(r: &M3, t: V, d1: V, d2: V) -> (f64, bool) {
    let e = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let b = [column(r, 0), column(r, 1), column(r, 2)];
    let gap = |axis: V| {
        let n = norm(axis);
        if n < 1e-9 {
            return f64::NEG_INFINITY;
        }
        let a = scale(axis, 1.0 / n);
        let ra: f64 = (0..3).map(|i| d1[i] * dot(e[i], a).abs()).sum();
        let rb: f64 = (0..3).map(|i| d2[i] * dot(b[i], a).abs()).sum();
        dot(t, a).abs() - ra - rb
    };
    let faces = e
        .iter()
        .chain(&b)
        .map(|&a| gap(a))
        .fold(f64::NEG_INFINITY, f64::max);
    let mut edges = f64::NEG_INFINITY;
    for ei in &e {
        for bj in &b {
            edges = edges.max(gap(cross(*ei, *bj)));
        }
    }
    (faces.max(edges), faces >= edges)
}

/// A point of box 2 (half extents `d2`, placed by `(r, t)`) in box 1 (about the origin), by
/// sampling box 2's corners, edges and faces and its inside.
fn sampled_overlap(rng: &mut Rng, r: &M3, t: V, d1: V, d2: V) -> bool {
    let inside = |p: V| (0..3).all(|i| p[i].abs() <= d1[i]);
    for k in 0..400 {
        // Corners and points pushed to the boundary on one or two axes, then the inside.
        let mut c = [0.0; 3];
        for (i, ci) in c.iter_mut().enumerate() {
            let u = rng.range(-1.0, 1.0);
            *ci = d2[i] * if k % 4 <= i { u.signum() } else { u };
        }
        if inside(add(mat_vec(r, c), t)) {
            return true;
        }
    }
    false
}

#[test]
fn overlap_agrees_with_an_independent_separating_axis_test() {
    let mut rng = Rng::new(2024);
    let (mut apart, mut by_edges, mut together, mut sampled) = (0, 0, 0, 0);
    for k in 0..20000 {
        let rot = rng.rotation();
        let d1 = [
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
        ];
        let mut d2 = [
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
        ];
        if k % 5 == 0 {
            // Flat and thin boxes.
            d2[k % 3] = 0.0;
        }
        let t = rng.point(2.0);
        let (b1, b2) = (bv(d1, [0.0; 2], 0.0), bv(d2, [0.0; 2], 0.0));
        let got = unsafe { overlap(&rot, t, &b1, &b2) };
        let (gap, face) = separation(&rot, t, d1, d2);
        if gap > 1e-9 {
            assert!(!got, "case {k}: apart by {gap} but reported overlapping");
            apart += 1;
            by_edges += usize::from(!face);
        } else if gap < -1e-9 {
            assert!(got, "case {k}: overlapping by {gap} but reported apart");
            together += 1;
        }
        // Never 0 for boxes that share a point.
        if sampled_overlap(&mut rng, &rot, t, d1, d2) {
            assert!(got, "case {k}: a point of box 2 in box 1, reported apart");
            sampled += 1;
        }
    }
    // The cases cover both answers and the edge-pair axes.
    assert!(
        apart > 2000 && together > 2000 && sampled > 1000,
        "{apart} {together} {sampled}"
    );
    assert!(by_edges > 50, "{by_edges} separated only along edge pairs");
}

#[test]
fn overlap_of_known_configurations() {
    let i3: M3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let (c, s) = (0.5f64.sqrt(), 0.5f64.sqrt());
    let z45: M3 = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
    let unit = bv([1.0, 1.0, 1.0], [0.0; 2], 0.0);
    let small = bv([0.5, 0.5, 0.5], [0.0; 2], 0.0);
    unsafe {
        // Face to face: touching counts; a gap does not.
        assert!(overlap(&i3, [1.5, 0.0, 0.0], &unit, &small));
        assert!(!overlap(&i3, [1.5 + 1e-9, 0.0, 0.0], &unit, &small));
        // Corner to corner.
        assert!(overlap(&i3, [1.5, 1.5, -1.5], &unit, &small));
        assert!(!overlap(&i3, [1.5, 1.5, -1.5 - 1e-9], &unit, &small));
        // Box 2 turned 45 degrees about z: its edge reaches sqrt(2) / 2 along x.
        let reach = 1.0 + 0.5 * 2f64.sqrt();
        assert!(overlap(&z45, [reach - 1e-9, 0.0, 0.0], &unit, &small));
        assert!(!overlap(&z45, [reach + 1e-9, 0.0, 0.0], &unit, &small));
        // Nested, and a flat box through the middle.
        assert!(overlap(&z45, [0.1, 0.2, 0.3], &unit, &small));
        assert!(overlap(
            &i3,
            [0.0; 3],
            &unit,
            &bv([3.0, 3.0, 0.0], [0.0; 2], 0.0)
        ));
        // Only the volumes' d is read: frames, centres and sizes of the rectangles do not matter.
        let mut odd = small;
        odd.R = [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]];
        odd.To = [100.0; 3];
        odd.Tr = [-100.0; 3];
        odd.l = [1e3, 1e3];
        odd.r = 50.0;
        assert!(!overlap(&i3, [1.5 + 1e-9, 0.0, 0.0], &unit, &odd));
    }
}

/// Rectangle `[0, l0] x [0, l1]` of a frame placed by `(r, t)` as two triangles.
fn rect_tris(r: &M3, t: V, l: [f64; 2]) -> [T; 2] {
    let p = |x: f64, y: f64| add(mat_vec(r, [x, y, 0.0]), t);
    let (a, b, c, d) = (p(0.0, 0.0), p(l[0], 0.0), p(l[0], l[1]), p(0.0, l[1]));
    [[a, b, c], [a, c, d]]
}

/// An upper bound of the rectangles' distance from a grid of points on each, and the bound on
/// how far above the distance it can be (half the grids' cell diagonals).
fn sampled_distance(r: &M3, t: V, l1: [f64; 2], l2: [f64; 2]) -> (f64, f64) {
    let steps = 20;
    let grid = |rr: &M3, tt: V, l: [f64; 2]| {
        let mut pts = Vec::new();
        for i in 0..=steps {
            for j in 0..=steps {
                let (x, y) = (
                    l[0] * i as f64 / steps as f64,
                    l[1] * j as f64 / steps as f64,
                );
                pts.push(add(mat_vec(rr, [x, y, 0.0]), tt));
            }
        }
        pts
    };
    let i3: M3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let (a, b) = (grid(&i3, [0.0; 3], l1), grid(r, t, l2));
    let mut best = f64::INFINITY;
    for p in &a {
        for q in &b {
            best = best.min(norm(sub(*p, *q)));
        }
    }
    let cell = |l: [f64; 2]| 0.5 * (l[0] * l[0] + l[1] * l[1]).sqrt() / steps as f64;
    (best, cell(l1) + cell(l2))
}

#[test]
fn distance_agrees_with_brute_force() {
    let mut rng = Rng::new(99);
    let i3: M3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let (mut apart, mut meeting) = (0, 0);
    for k in 0..3000 {
        let rot = if k % 7 == 0 { i3 } else { rng.rotation() };
        let mut side = || match rng.next_u64() % 6 {
            0 => 0.0,
            _ => rng.range(0.0, 2.0),
        };
        let (l1, l2) = ([side(), side()], [side(), side()]);
        // Every third case close: the cores often meet.
        let t = rng.point(if k % 3 == 0 { 0.7 } else { 2.0 });
        let (r1, r2) = (rng.range(0.0, 0.3), rng.range(0.0, 0.3));
        let got = unsafe { distance(&rot, t, &bv([0.0; 3], l1, r1), &bv([0.0; 3], l2, r2)) };
        // The rectangles' distance, as two triangles each.
        let (a, b) = (rect_tris(&i3, [0.0; 3], l1), rect_tris(&rot, t, l2));
        let exact = a
            .iter()
            .flat_map(|x| b.iter().map(move |y| tri_tri(x, y)))
            .fold(f64::INFINITY, f64::min);
        let (upper, slack) = sampled_distance(&rot, t, l1, l2);
        let core = got + r1 + r2;
        assert!((core - exact).abs() <= 1e-9, "case {k}: {core} vs {exact}");
        assert!(
            core <= upper + 1e-12,
            "case {k}: {core} above a sampled pair {upper}"
        );
        assert!(
            upper - core <= slack + 1e-12,
            "case {k}: {core} far below {upper}"
        );
        if exact > 0.0 {
            apart += 1;
        } else {
            // Meeting cores: exactly minus both radii, up to their rounding.
            meeting += 1;
            assert!(core.abs() <= 1e-12, "case {k}: {core}");
        }
    }
    assert!(apart > 1000 && meeting > 50, "{apart} {meeting}");
}

#[test]
fn distance_of_known_configurations() {
    let i3: M3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let (c, s) = (0.6, 0.8);
    let tilted: M3 = [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]];
    let sq = |r: f64| bv([0.0; 3], [1.0, 1.0], r);
    unsafe {
        // Stacked squares 2 apart, radii 0.25 and 0.5.
        assert_eq!(distance(&i3, [0.0, 0.0, 2.0], &sq(0.25), &sq(0.5)), 1.25);
        // Side by side in a plane, 3 apart along x.
        assert_eq!(distance(&i3, [4.0, 0.0, 0.0], &sq(0.0), &sq(0.0)), 3.0);
        // Overlapping cores: minus both radii (negative, as PQP's).
        assert_eq!(distance(&i3, [0.5, 0.5, 0.0], &sq(0.25), &sq(0.5)), -0.75);
        // Points (spheres) 5 apart in x and y: 3-4-5.
        let ball = bv([0.0; 3], [0.0, 0.0], 1.0);
        assert_eq!(distance(&i3, [3.0, 4.0, 0.0], &ball, &ball), 3.0);
        // A point above the middle of a square.
        assert_eq!(distance(&i3, [0.5, 0.5, 7.0], &sq(0.0), &ball), 6.0);
        // A tilted square whose corner is 2 above square 1's far corner: the corner is nearest.
        let d = distance(&tilted, [1.0, 1.0, 2.0], &sq(0.0), &sq(0.0));
        assert!((d - 2.0).abs() < 1e-15, "{d}");
        // Segments crossing at right angles, 1.5 apart.
        let seg = bv([0.0; 3], [2.0, 0.0], 0.0);
        let z90: M3 = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(distance(&z90, [1.0, -1.0, 1.5], &seg, &seg), 1.5);
    }
}

/// Every vertex's excess over the rectangle swept sphere and the box of `b` (negative inside).
fn excesses(b: &pqp_bv, p: V) -> (f64, f64) {
    let q = tr_vec(&b.R, sub(p, b.Tr));
    let out = |x: f64, len: f64| (-x).max(x - len).max(0.0);
    let (dx, dy) = (out(q[0], b.l[0]), out(q[1], b.l[1]));
    let rss = (dx * dx + dy * dy + q[2] * q[2]).sqrt() - b.r;
    let qb = tr_vec(&b.R, sub(p, b.To));
    let boxed = (0..3)
        .map(|i| qb[i].abs() - b.d[i])
        .fold(f64::MIN, f64::max);
    (rss, boxed)
}

#[test]
fn fit_contains_the_vertices_tightly() {
    let mut rng = Rng::new(17);
    for k in 0..500 {
        let n = 1 + k % 40;
        let c = rng.point(10.0);
        let tris: Vec<pqp_tri> = (0..n)
            .map(|i| {
                let mut v = || add(c, rng.point(1.0));
                pqp_tri {
                    p1: v(),
                    p2: v(),
                    p3: if k % 3 == 0 { [0.0; 3] } else { v() },
                    id: i,
                }
            })
            .collect();
        let rot = rng.rotation();
        let mut b = pqp_bv {
            first_child: 12345,
            ..pqp_bv::default()
        };
        let o = flat(&rot);
        assert_eq!(
            unsafe { pqp_bv_fit(&mut b, o.as_ptr(), tris.as_ptr(), n) },
            PQP_OK
        );
        assert_eq!(b.R, rot);
        assert_eq!(b.first_child, 12345);
        assert!(b.l[0] >= 0.0 && b.l[1] >= 0.0 && b.r >= 0.0 && b.d.iter().all(|&x| x >= 0.0));
        let points: Vec<V> = tris.iter().flat_map(|t| [t.p1, t.p2, t.p3]).collect();
        let (mut worst_rss, mut worst_box) = (f64::MIN, f64::MIN);
        for &p in &points {
            let (e1, e2) = excesses(&b, p);
            assert!(e1 <= 1e-12 && e2 <= 1e-12, "case {k}: {e1} {e2}");
            worst_rss = worst_rss.max(e1);
            worst_box = worst_box.max(e2);
        }
        // Tight: some vertex on each; the box's every face has one.
        assert!(worst_rss >= -1e-9 && worst_box >= -1e-9, "case {k}");
        for i in 0..3 {
            let proj = |p: &V| tr_vec(&b.R, sub(*p, b.To))[i];
            let lo = points.iter().map(proj).fold(f64::INFINITY, f64::min);
            let hi = points.iter().map(proj).fold(f64::NEG_INFINITY, f64::max);
            assert!(
                (hi - b.d[i]).abs() < 1e-9 && (lo + b.d[i]).abs() < 1e-9,
                "case {k}"
            );
        }
    }
}

/// PQP's FitToTris on a model's root axes gives the root's volumes, bit for bit: the builder fits
/// exactly as pqp_bv_fit does.
#[test]
fn fit_on_the_root_axes_gives_the_root() {
    let mut rng = Rng::new(5);
    let tris: Vec<pqp_tri> = (0..500)
        .map(|i| {
            let c = rng.point(3.0);
            let mut v = || add(c, rng.point(0.2));
            pqp_tri {
                p1: v(),
                p2: v(),
                p3: v(),
                id: i,
            }
        })
        .collect();
    unsafe {
        let m = pqp_model_create();
        for t in &tris {
            assert_eq!(
                pqp_model_add_tri(m, t.p1.as_ptr(), t.p2.as_ptr(), t.p3.as_ptr(), t.id),
                PQP_OK
            );
        }
        assert_eq!(pqp_model_end(m), PQP_OK);
        let (mut bvs, mut n) = (ptr::null(), 0);
        assert_eq!(pqp_model_bvs(m, &mut bvs, &mut n), PQP_OK);
        let root = *bvs;
        let mut fit = pqp_bv {
            first_child: root.first_child,
            ..pqp_bv::default()
        };
        let o = flat(&root.R);
        assert_eq!(pqp_bv_fit(&mut fit, o.as_ptr(), tris.as_ptr(), 500), PQP_OK);
        assert_eq!(fit, root);
        pqp_model_destroy(m);
    }
}

#[test]
fn bv_functions_refuse_bad_input_and_leave_their_outputs() {
    let i3 = flat(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    let t = [0.0; 3];
    let tri = pqp_tri {
        p1: [0.0; 3],
        p2: [1.0, 0.0, 0.0],
        p3: [0.0, 1.0, 0.0],
        id: 0,
    };
    let b = bv([1.0; 3], [1.0, 1.0], 0.5);
    unsafe {
        // Fit.
        let mut out = pqp_bv {
            r: 42.0,
            ..pqp_bv::default()
        };
        let before = out;
        let fit = |out: &mut pqp_bv, o: *const f64, tris: *const pqp_tri, n: i32| {
            pqp_bv_fit(out, o, tris, n)
        };
        assert_eq!(
            pqp_bv_fit(ptr::null_mut(), i3.as_ptr(), &tri, 1),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(fit(&mut out, ptr::null(), &tri, 1), PQP_ERR_NULL_POINTER);
        assert_eq!(
            fit(&mut out, i3.as_ptr(), ptr::null(), 1),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            fit(&mut out, i3.as_ptr(), &tri, 0),
            PQP_ERR_INVALID_ARGUMENT
        );
        assert_eq!(
            fit(&mut out, i3.as_ptr(), &tri, -3),
            PQP_ERR_INVALID_ARGUMENT
        );
        let mut bad_o = i3;
        bad_o[4] = f64::NAN;
        assert_eq!(
            fit(&mut out, bad_o.as_ptr(), &tri, 1),
            PQP_ERR_NONFINITE_POSE
        );
        for bad in [f64::NAN, f64::INFINITY, 1e151] {
            let mut t2 = tri;
            t2.p3[1] = bad;
            assert_eq!(
                fit(&mut out, i3.as_ptr(), &t2, 1),
                PQP_ERR_NONFINITE_COORDINATE
            );
        }
        assert_eq!(out, before);

        // Overlap and distance.
        let mut o = 7;
        let mut d = 7.0;
        assert_eq!(
            pqp_bv_overlap(ptr::null_mut(), i3.as_ptr(), t.as_ptr(), &b, &b),
            PQP_ERR_NULL_POINTER
        );
        assert_eq!(
            pqp_bv_distance(ptr::null_mut(), i3.as_ptr(), t.as_ptr(), &b, &b),
            PQP_ERR_NULL_POINTER
        );
        for (r, tt, b1, b2) in [
            (
                ptr::null(),
                t.as_ptr(),
                &b as *const pqp_bv,
                &b as *const pqp_bv,
            ),
            (i3.as_ptr(), ptr::null(), &b, &b),
            (i3.as_ptr(), t.as_ptr(), ptr::null(), &b),
            (i3.as_ptr(), t.as_ptr(), &b, ptr::null()),
        ] {
            assert_eq!(pqp_bv_overlap(&mut o, r, tt, b1, b2), PQP_ERR_NULL_POINTER);
            assert_eq!(pqp_bv_distance(&mut d, r, tt, b1, b2), PQP_ERR_NULL_POINTER);
        }
        for bad in [f64::NAN, f64::NEG_INFINITY, -2e150] {
            let mut r = i3;
            r[2] = bad;
            assert_eq!(
                pqp_bv_overlap(&mut o, r.as_ptr(), t.as_ptr(), &b, &b),
                PQP_ERR_NONFINITE_POSE
            );
            assert_eq!(
                pqp_bv_distance(&mut d, r.as_ptr(), t.as_ptr(), &b, &b),
                PQP_ERR_NONFINITE_POSE
            );
            let tt = [0.0, bad, 0.0];
            assert_eq!(
                pqp_bv_overlap(&mut o, i3.as_ptr(), tt.as_ptr(), &b, &b),
                PQP_ERR_NONFINITE_POSE
            );
            assert_eq!(
                pqp_bv_distance(&mut d, i3.as_ptr(), tt.as_ptr(), &b, &b),
                PQP_ERR_NONFINITE_POSE
            );
            let mut nb = b;
            nb.d[1] = bad;
            nb.l[1] = bad;
            nb.r = bad;
            let want = if bad.is_finite() && bad.abs() <= 1e150 {
                PQP_ERR_INVALID_ARGUMENT
            } else {
                PQP_ERR_NONFINITE_COORDINATE
            };
            assert_eq!(
                pqp_bv_overlap(&mut o, i3.as_ptr(), t.as_ptr(), &b, &nb),
                want
            );
            assert_eq!(
                pqp_bv_distance(&mut d, i3.as_ptr(), t.as_ptr(), &nb, &b),
                want
            );
        }
        // Negative sizes.
        let mut nb = b;
        nb.d[0] = -1.0;
        assert_eq!(
            pqp_bv_overlap(&mut o, i3.as_ptr(), t.as_ptr(), &nb, &b),
            PQP_ERR_INVALID_ARGUMENT
        );
        let mut nb = b;
        nb.r = -0.5;
        assert_eq!(
            pqp_bv_distance(&mut d, i3.as_ptr(), t.as_ptr(), &b, &nb),
            PQP_ERR_INVALID_ARGUMENT
        );
        let mut nb = b;
        nb.l[0] = -0.5;
        assert_eq!(
            pqp_bv_distance(&mut d, i3.as_ptr(), t.as_ptr(), &b, &nb),
            PQP_ERR_INVALID_ARGUMENT
        );
        assert_eq!((o, d), (7, 7.0));
        // And they answer on good input.
        assert_eq!(
            pqp_bv_overlap(&mut o, i3.as_ptr(), t.as_ptr(), &b, &b),
            PQP_OK
        );
        assert_eq!(
            pqp_bv_distance(&mut d, i3.as_ptr(), t.as_ptr(), &b, &b),
            PQP_OK
        );
        assert_eq!((o, d), (1, -1.0));
    }
}
