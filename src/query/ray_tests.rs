//! Tests of the ray search against testing every triangle, and of its helpers.

use super::*;
use crate::geometry::Tri;
use crate::test_rng::{Random, Rng};

/// The search against every triangle tested in turn with the same kernel: bit for bit the same
/// answer (the traversal loses nothing), on random soups and closed meshes, at random poses.
#[test]
fn search_equals_testing_every_triangle() {
    let mut r = Rng(41);
    for iter in 0..60 {
        let n = 1 + r.below(300);
        let size = [0.05, 0.5, 3.0][iter % 3];
        let tris: Vec<(Tri, i32)> = (0..n)
            .map(|i| {
                let c = Vec3::from(r.point(1.0));
                let t = [0, 1, 2].map(|_| c + Vec3::from(r.point(size)));
                (t, i as i32)
            })
            .collect();
        let model = Model::from_triangles(
            tris.iter()
                .map(|(t, id)| (t[0].into(), t[1].into(), t[2].into(), *id)),
        )
        .unwrap();
        let bvh = model.bvh().unwrap();
        for _ in 0..200 {
            let o = Vec3::from(r.point(2.5));
            let d = Vec3::from(r.direction()) * r.log_uniform(1e-3, 1e3);
            let max_t = if r.below(4) == 0 {
                r.range(0.0, 3.0)
            } else {
                f64::INFINITY
            };
            search_equals_brute_force(bvh, o, d, max_t);
        }
    }
}

/// Asserts that the search finds bit for bit what testing every triangle of `bvh` in turn
/// finds for the ray `o + t d` (`d`'s largest coordinate in `[1, 2)` or not: the search is
/// given it as it is); returns whether it hit.
fn search_equals_brute_force(bvh: &Bvh, o: Vec3, d: Vec3, max_t: f64) -> bool {
    let ray = LocalRay::new(o, d, bvh.scale);
    let tree = bvh.ray_tree().unwrap();
    let fast = ray
        .search(bvh, tree, max_t, |t| t <= max_t)
        .map(|b| (b.t, tree.slot(b.at)));
    let mut brute: Option<(f64, usize, u32)> = None;
    for slot in 0..bvh.num_tris() {
        if let Some(t) = ray.hit_slot(bvh, slot) {
            let a = bvh.added[slot];
            if t <= max_t && brute.is_none_or(|(bt, _, ba)| t < bt || (t == bt && a < ba)) {
                brute = Some((t, slot, a));
            }
        }
    }
    assert_eq!(fast, brute.map(|(t, s, _)| (t, s)), "{o:?} {d:?}");
    fast.is_some()
}

/// The slab test's boxes lose no hit where rays graze them: rays in the planes of an
/// axis-aligned cube's faces, along its edges, through its corners, parallel to an axis or
/// nearly (direction components down to 1e-40, below the single-precision test's tilt), at
/// scales from 1e-25 to 1e140 (both the single- and the double-precision slab tests), each
/// against every triangle tested in turn; and every ray that should hit does.
#[test]
fn grazing_rays_at_every_scale_lose_nothing() {
    let mut r = Rng(29);
    for scale in [1e-25, 1e-9, 1.0, 3e7, 1e25, 1e31, 1e80, 1e140] {
        // A closed cube [0, s]^3 (12 triangles), and small triangles lying on its faces'
        // planes and across its edges, whose boxes are flat or thin.
        let s = scale;
        let c = |x: f64, y: f64, z: f64| [x * s, y * s, z * s];
        let mut tris: Vec<[[f64; 3]; 3]> = Vec::new();
        for axis in 0..3 {
            for side in [0.0, 1.0] {
                let p = |u: f64, v: f64| {
                    let mut q = [0.0; 3];
                    q[axis] = side;
                    q[(axis + 1) % 3] = u;
                    q[(axis + 2) % 3] = v;
                    c(q[0], q[1], q[2])
                };
                tris.push([p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]);
                tris.push([p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]);
                let (u, v) = (r.range(0.0, 0.9), r.range(0.0, 0.9));
                tris.push([p(u, v), p(u + 0.1, v), p(u, v + 0.1)]);
            }
        }
        tris.push([c(1.0, 0.0, 0.0), c(1.0, 1.0, 0.0), c(1.2, 0.5, 0.0)]);
        tris.push([c(0.0, 1.0, 1.0), c(0.0, 1.0, 0.0), c(0.0, 1.3, 0.5)]);
        let model = Model::from_triangles(tris.iter().zip(0..).map(|(t, i)| (t[0], t[1], t[2], i)))
            .unwrap();
        let bvh = model.bvh().unwrap();
        let coordinate = |r: &mut Rng| [0.0, 0.0, 1.0, 1.0, 0.5, r.range(0.0, 1.0)][r.below(6)];
        let mut hits = 0;
        for _ in 0..400 {
            // From outside the cube or on its surface, along an axis, tilted a little off
            // it, or at a corner's diagonal.
            let mut o = [0.0; 3].map(|_| coordinate(&mut r));
            let axis = r.below(3);
            o[axis] = [-1.0, 0.0, 2.0][r.below(3)];
            let mut d = [0.0; 3];
            d[axis] = if o[axis] > 0.5 { -1.0 } else { 1.0 };
            for (j, dj) in d.iter_mut().enumerate() {
                if j != axis && r.below(2) == 0 {
                    *dj = [1e-40, -1e-40, 1e-20, -1e-7, 1.0][r.below(5)];
                }
            }
            let o = Vec3::from(c(o[0], o[1], o[2]));
            let d = Vec3::from(d) * r.log_uniform(1e-3, 1e3);
            hits += usize::from(search_equals_brute_force(bvh, o, d, f64::INFINITY));
        }
        assert!(hits > 100, "{scale}: {hits}");
        // Straight at the middle of every face, from outside: always a hit.
        for axis in 0..3 {
            for (from, dir) in [(-1.0, 1.0), (2.0, -1.0)] {
                let mut o = [0.5; 3];
                o[axis] = from;
                let mut d = [0.0; 3];
                d[axis] = dir;
                let o = Vec3::from(c(o[0], o[1], o[2]));
                assert!(search_equals_brute_force(
                    bvh,
                    o,
                    Vec3::from(d),
                    f64::INFINITY
                ));
            }
        }
    }
}

/// A tree large enough to be offered huge pages: the search equals testing every triangle.
#[test]
fn large_tree_equals_testing_every_triangle() {
    // A wavy height field of 2 * 300 * 300 triangles: more than 32,768 nodes of 128 bytes.
    let n = 300;
    let h = |i: usize, j: usize| {
        let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
        [x, y, 0.05 * (13.0 * x).sin() * (17.0 * y).cos()]
    };
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            tris.push((h(i, j), h(i + 1, j), h(i + 1, j + 1), tris.len() as i32));
            tris.push((h(i, j), h(i + 1, j + 1), h(i, j + 1), tris.len() as i32));
        }
    }
    let model = Model::from_triangles(tris).unwrap();
    let bvh = model.bvh().unwrap();
    let mut r = Rng(5);
    let mut hits = 0;
    for _ in 0..40 {
        let o = Vec3::new(r.range(-0.2, 1.2), r.range(-0.2, 1.2), r.range(0.3, 1.0));
        let at = Vec3::new(r.range(0.0, 1.0), r.range(0.0, 1.0), 0.0);
        hits += usize::from(search_equals_brute_force(bvh, o, at - o, f64::INFINITY));
    }
    assert!(hits > 20, "{hits}");
}

/// A refit drops the ray tree (its boxes are the old vertices'): casts after it see the new
/// positions.
#[test]
fn refit_remakes_the_ray_tree() {
    let strip = |dx: f64| -> Vec<[[f64; 3]; 3]> {
        (0..50)
            .map(|i| {
                let x = dx + f64::from(i);
                [[x, 0.0, 0.0], [x + 1.0, 0.0, 0.0], [x, 1.0, 0.0]]
            })
            .collect()
    };
    let mut model = Model::from_triangles(
        strip(0.0)
            .iter()
            .zip(0..)
            .map(|(t, i)| (t[0], t[1], t[2], i)),
    )
    .unwrap();
    let down = Vec3::new(0.0, 0.0, -1.0);
    let at = |x: f64| Vec3::new(x, 0.25, 3.0);
    let hit = |m: &Model, x: f64| ray_cast(m, &Pose::identity(), &at(x), &down, f64::INFINITY);
    assert_eq!(hit(&model, 10.25).unwrap().unwrap().triangle, 10);
    model.refit(&strip(100.0)).unwrap();
    assert_eq!(hit(&model, 10.25).unwrap(), None);
    let h = hit(&model, 110.25).unwrap().unwrap();
    assert_eq!((h.triangle, h.t), (10, 3.0));
}

#[test]
fn scaling_helpers() {
    for &x in &[1.0, 3.5e-310, 1e-300, 7e200, f64::MAX] {
        let (v, k) = unit_scale(&Vec3::new(x, -x / 3.0, 0.0));
        assert!((1.0..2.0).contains(&v.amax()), "{x}");
        assert_eq!(scaled(v.x, k), x);
    }
    assert_eq!(upper_scaled(1e-300, -500), f64::from_bits(1));
    assert_eq!(scaled(3.0, 2000), f64::INFINITY);
}
