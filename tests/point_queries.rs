//! Point queries (closest point, winding number, signed distance) against brute force over every
//! triangle, and the sign against a ray-parity count on closed meshes, on the example models and
//! random meshes, poses and points.

mod common;

use common::*;
use pqp::{Error, Model, Pose, Vec3, closest_point, signed_distance, winding_number};
use std::f64::consts::PI;

/// The triangles of a `.tris` file (count, then nine numbers per triangle).
fn load(path: &std::path::Path) -> Mesh {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    let n = v[0] as usize;
    let tris = (0..n)
        .map(|t| {
            let c = |k: usize| {
                [
                    v[1 + 9 * t + 3 * k],
                    v[2 + 9 * t + 3 * k],
                    v[3 + 9 * t + 3 * k],
                ]
            };
            [c(0), c(1), c(2)]
        })
        .collect();
    Mesh { tris }
}

/// The example models, and the shared ones where they are present.
fn example_models() -> Vec<(String, Mesh)> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    for dir in [root.join("examples/models"), "/work/shared/models".into()] {
        for name in ["bunny.tris", "torus.tris", "torus1.tris", "torus2.tris"] {
            let p = dir.join(name);
            if p.exists() {
                out.push((p.display().to_string(), load(&p)));
            }
        }
    }
    assert!(out.len() >= 2);
    out
}

/// A closed, star-shaped mesh around the origin: a UV sphere of radius about `r`, each vertex
/// moved radially by up to `lump` of it, with every vertex shared exactly between its triangles
/// (so the surface has no crack). Triangles face outwards.
fn lumpy_sphere(rng: &mut Rng, r: f64, lump: f64, slices: usize, stacks: usize) -> Mesh {
    let mut verts = vec![[0.0, 0.0, r * (1.0 + lump * rng.signed())]];
    for i in 1..stacks {
        for j in 0..slices {
            let th = PI * i as f64 / stacks as f64;
            let ph = 2.0 * PI * j as f64 / slices as f64;
            let s = r * (1.0 + lump * rng.signed());
            verts.push([
                s * th.sin() * ph.cos(),
                s * th.sin() * ph.sin(),
                s * th.cos(),
            ]);
        }
    }
    verts.push([0.0, 0.0, -r * (1.0 + lump * rng.signed())]);
    let south = verts.len() - 1;
    let at = |i: usize, j: usize| -> usize {
        match i {
            0 => 0,
            i if i == stacks => south,
            i => 1 + (i - 1) * slices + j % slices,
        }
    };
    let mut tris = Vec::new();
    for i in 0..stacks {
        for j in 0..slices {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if i + 1 < stacks {
                tris.push([verts[a], verts[b], verts[c]]);
            }
            if i > 0 {
                tris.push([verts[a], verts[c], verts[d]]);
            }
        }
    }
    Mesh { tris }
}

/// The mesh with every triangle turned round (normals inwards).
fn flipped(m: &Mesh) -> Mesh {
    Mesh {
        tris: m.tris.iter().map(|t| [t[0], t[2], t[1]]).collect(),
    }
}

/// The upper half of a UV sphere of radius 1 (open: its rim is a boundary), facing outwards.
fn hemisphere(slices: usize, stacks: usize) -> Mesh {
    let full = Mesh::sphere(1.0, slices, 2 * stacks);
    Mesh {
        tris: full.tris[..2 * slices * stacks].to_vec(),
    }
}

/// The least distance from `p` to the triangles and the first triangle at it (brute force).
fn brute_closest(tris: &[T], p: V) -> (f64, usize) {
    let mut best = (f64::INFINITY, usize::MAX);
    for (i, t) in tris.iter().enumerate() {
        let d = point_tri(p, t);
        if d < best.0 {
            best = (d, i);
        }
    }
    best
}

/// The winding number about `p`: every triangle's solid angle (the tangent half-angle formula on
/// plain arrays), over 4 pi.
fn brute_winding(tris: &[T], p: V) -> f64 {
    let mut sum = 0.0;
    for t in tris {
        let (a, b, c) = (sub(t[0], p), sub(t[1], p), sub(t[2], p));
        let (la, lb, lc) = (norm(a), norm(b), norm(c));
        let det = dot(a, cross(b, c));
        let den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
        sum += 2.0 * det.atan2(den);
    }
    sum / (4.0 * PI)
}

/// How far two winding numbers about a point at distance `d` from a mesh of extent `e` may differ
/// when one is computed in the model's frame and the other in the world's: the triangles nearest
/// the point move by a few roundings of `e` between the frames, which turns their solid angle by
/// about that over `d`.
fn winding_tol(e: f64, d: f64) -> f64 {
    1e-10 + 1e-13 * e / d
}

/// Whether `p` is inside the closed mesh, by the parity of the triangles a ray from it crosses
/// (Moller-Trumbore); `None` when every ray tried passes too near an edge to count reliably.
fn ray_parity(tris: &[T], p: V, rng: &mut Rng) -> Option<bool> {
    'ray: for _ in 0..8 {
        let d = rng.direction();
        let mut crossings = 0;
        for t in tris {
            let (e1, e2) = (sub(t[1], t[0]), sub(t[2], t[0]));
            let h = cross(d, e2);
            let det = dot(e1, h);
            let scale = norm(e1) * norm(e2);
            if det.abs() <= 1e-12 * scale {
                continue;
            }
            let s = sub(p, t[0]);
            let u = dot(s, h) / det;
            let q = cross(s, e1);
            let v = dot(d, q) / det;
            let tt = dot(e2, q) / det;
            let margin = 1e-9;
            let near_edge = [u, v, 1.0 - u - v].iter().any(|x| x.abs() < margin);
            if tt > 0.0 && u > -margin && v > -margin && u + v < 1.0 + margin {
                if near_edge {
                    continue 'ray;
                }
                crossings += 1;
            }
        }
        return Some(crossings % 2 == 1);
    }
    None
}

/// The largest coordinate magnitude of the triangles (for tolerances).
fn extent(tris: &[T]) -> f64 {
    tris.iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Points to ask about: near the surface (a point of a triangle moved a little), far, on a
/// triangle, at vertices and edge midpoints, and random ones in the mesh's box.
fn query_points(tris: &[T], rng: &mut Rng, n: usize) -> Vec<V> {
    let e = extent(tris);
    let mut out = Vec::new();
    for k in 0..n {
        let t = &tris[rng.below(tris.len())];
        let (u, v) = (rng.unit(), rng.unit());
        let (u, v) = if u + v > 1.0 {
            (1.0 - u, 1.0 - v)
        } else {
            (u, v)
        };
        let on = add(
            t[0],
            add(scale(sub(t[1], t[0]), u), scale(sub(t[2], t[0]), v)),
        );
        out.push(match k % 6 {
            0 => add(
                on,
                scale(rng.direction(), e * rng.log10_uniform(-8.0, -1.0)),
            ),
            1 => scale(rng.direction(), e * rng.range(2.0, 50.0)),
            2 => on,
            3 => t[rng.below(3)],
            4 => scale(add(t[0], t[1]), 0.5),
            _ => rng.point(1.2 * e),
        });
    }
    out
}

/// Checks one closest-point answer against brute force over the world triangles: the distance,
/// that the triangle reported is at that distance, and that the point lies on it at that
/// distance from `p`.
fn check_closest(model: &Model, world: &[T], pose: &Pose, p: V, tol: f64, what: &str) -> f64 {
    let r = closest_point(model, pose, &Vec3::from(p), f64::INFINITY).unwrap();
    let (d, _) = brute_closest(world, p);
    assert!(
        (r.distance - d).abs() <= tol,
        "{what}: {} vs brute {d}",
        r.distance
    );
    let id = r.triangle.expect("a triangle") as usize;
    let dt = point_tri(p, &world[id]);
    assert!(
        (dt - d).abs() <= tol,
        "{what}: triangle {id} at {dt}, closest {d}"
    );
    let q = [r.point.x, r.point.y, r.point.z];
    assert!(
        point_tri(q, &world[id]) <= tol,
        "{what}: point off its triangle"
    );
    assert!(
        (norm(sub(q, p)) - r.distance).abs() <= tol,
        "{what}: point not at the distance"
    );
    r.distance
}

#[test]
fn closest_point_matches_brute_force_on_the_models() {
    let mut rng = Rng::new(22);
    for (name, mesh) in example_models() {
        let model = mesh.model();
        let e = extent(&mesh.tris);
        for k in 0..6 {
            let pose = if k == 0 {
                Pose::identity()
            } else {
                rng.pose(3.0 * e)
            };
            let world = mesh.world(&pose);
            let tol = 1e-12 * (e + norm(pose.translation.into())) * 10.0;
            for p in query_points(&world, &mut rng, 60) {
                check_closest(&model, &world, &pose, p, tol, &name);
            }
        }
    }
}

#[test]
fn closest_point_matches_brute_force_on_random_meshes() {
    let mut rng = Rng::new(2201);
    for round in 0..40 {
        let n = 1 + rng.below(400);
        let size = rng.log10_uniform(-3.0, 0.0);
        let mut mesh = Mesh::soup(&mut rng, n, 1.0, size);
        // Degenerate triangles: a repeated vertex, collinear vertices, a point.
        if round % 3 == 0 {
            let a = rng.point(1.0);
            let b = rng.point(1.0);
            mesh.tris.push([a, a, b]);
            mesh.tris.push([a, scale(add(a, b), 0.5), b]);
            mesh.tris.push([b, b, b]);
        }
        let model = mesh.model();
        let pose = rng.pose(2.0);
        let world = mesh.world(&pose);
        for p in query_points(&world, &mut rng, 30) {
            check_closest(&model, &world, &pose, p, 1e-11, "soup");
        }
    }
}

/// In the model's frame (identity pose, so the point reaches it unchanged) the distance is exactly
/// the least of the exact point-triangle routine over every triangle, and the triangle reported
/// is at exactly that distance: no pruning of the search (boxes, the triangles' frames on small
/// models) ever skips the nearest triangle. On the bunny, and on soups with slivers, collinear
/// and repeated vertices, at scales from 1e-150 to 1e140, for points near and on the surface, at
/// vertices and edge midpoints, and far away.
#[test]
fn closest_point_is_the_exact_routines_least_distance() {
    let mut rng = Rng::new(2207);
    let bunny =
        load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/models/bunny.tris"));
    let mut meshes = vec![(1.0, bunny)];
    for round in 0..24 {
        let s = [1.0, 1e-150, 1e-20, 1e20, 1e140, 3.0][round % 6];
        let (n, size) = (1 + rng.below(300), rng.log10_uniform(-3.0, 0.0));
        let mut mesh = Mesh::soup(&mut rng, n, 1.0, size);
        for _ in 0..8 {
            let (a, b) = (rng.point(1.0), rng.point(1.0));
            let near = add(scale(add(a, b), 0.5), scale(rng.direction(), 1e-7));
            mesh.tris.push([a, near, b]);
            mesh.tris.push([a, scale(add(a, b), 0.5), b]);
            mesh.tris.push([a, a, b]);
            mesh.tris.push([b, b, b]);
        }
        for t in &mut mesh.tris {
            *t = t.map(|v| scale(v, s));
        }
        meshes.push((s, mesh));
    }
    let here = Pose::identity();
    for (s, mesh) in &meshes {
        let model = mesh.model();
        let tris: Vec<[Vec3; 3]> = mesh.tris.iter().map(|t| t.map(Vec3::from)).collect();
        for p in query_points(&mesh.tris, &mut rng, 200) {
            let p = Vec3::from(p);
            let least = tris
                .iter()
                .map(|t| pqp::geometry::point_triangle(&p, t).distance)
                .fold(f64::INFINITY, f64::min);
            let r = closest_point(&model, &here, &p, f64::INFINITY).unwrap();
            assert_eq!(r.distance, least, "scale {s}, point {p:?}");
            let t = &tris[r.triangle.unwrap() as usize];
            assert_eq!(pqp::geometry::point_triangle(&p, t).distance, least);
            // Exactly at the least distance as max_distance still finds it.
            let at = closest_point(&model, &here, &p, least).unwrap();
            assert_eq!(at.distance, least);
        }
    }
}

/// Vertices of the model and points on its triangles are at distance 0 (identity pose: the point
/// reaches the model's frame unchanged).
#[test]
fn points_of_the_surface_are_at_distance_zero() {
    let mesh =
        load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/models/bunny.tris"));
    let model = mesh.model();
    let here = Pose::identity();
    for (i, t) in mesh.tris.iter().enumerate().step_by(7) {
        for v in t {
            let r = closest_point(&model, &here, &Vec3::from(*v), 0.0).unwrap();
            assert_eq!(r.distance, 0.0, "vertex of {i}");
            assert_eq!(r.point, Vec3::from(*v));
            assert_eq!(
                signed_distance(&model, &here, &Vec3::from(*v)).unwrap(),
                0.0
            );
        }
        let mid = scale(add(t[0], t[1]), 0.5);
        let r = closest_point(&model, &here, &Vec3::from(mid), f64::INFINITY).unwrap();
        assert!(r.distance <= 1e-15, "edge of {i}: {}", r.distance);
    }
}

#[test]
fn max_distance_prunes_and_answers_consistently() {
    let mut rng = Rng::new(2202);
    let mesh = Mesh::torus(1.0, 0.3, 40, 20);
    let model = mesh.model();
    for _ in 0..200 {
        let pose = rng.pose(1.0);
        let p = Vec3::from(rng.point(3.0));
        let full = closest_point(&model, &pose, &p, f64::INFINITY).unwrap();
        let d = full.distance;
        for max in [d, 2.0 * d, d + 1e-9, 1e300] {
            let r = closest_point(&model, &pose, &p, max).unwrap();
            assert_eq!(r, full, "max {max} (distance {d})");
        }
        for max in [0.0, d * (1.0 - 1e-9), d * 0.5] {
            if d > 0.0 {
                let r = closest_point(&model, &pose, &p, max).unwrap();
                assert_eq!((r.distance, r.triangle), (f64::INFINITY, None), "max {max}");
                assert!(r.point.iter().all(|c| c.is_nan()));
            }
        }
    }
}

/// Ties: the centre of a regular octahedron is equally near its eight faces; the answer is one of
/// them, the same every time, for copies of the model too.
#[test]
fn ties_are_answered_deterministically() {
    let v = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let faces = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    let mesh = Mesh {
        tris: faces.iter().map(|f| [v[f[0]], v[f[1]], v[f[2]]]).collect(),
    };
    let model = mesh.model();
    let here = Pose::identity();
    let first = closest_point(&model, &here, &Vec3::zeros(), f64::INFINITY).unwrap();
    assert!((first.distance - 1.0 / 3f64.sqrt()).abs() < 1e-15);
    let copy = model.clone();
    for _ in 0..5 {
        assert_eq!(
            closest_point(&model, &here, &Vec3::zeros(), f64::INFINITY).unwrap(),
            first
        );
        assert_eq!(
            closest_point(&copy, &here, &Vec3::zeros(), f64::INFINITY).unwrap(),
            first
        );
    }
    assert_eq!(
        signed_distance(&model, &here, &Vec3::zeros()).unwrap(),
        -first.distance
    );
}

/// The same scene scaled by 1e100, 1e-100, 1e140 and 1e-140 gives the answers at unit scale
/// (checked against brute force), scaled.
#[test]
fn huge_and_tiny_scales() {
    let mut rng = Rng::new(2203);
    let base = lumpy_sphere(&mut rng, 1.0, 0.2, 24, 12);
    let unit = base.model();
    for s in [1e100, 1e-100, 1e140, 1e-140] {
        let mesh = Mesh {
            tris: base.tris.iter().map(|t| t.map(|v| scale(v, s))).collect(),
        };
        let model = mesh.model();
        for _ in 0..20 {
            let (rot, t, p) = (rng.rotation(), rng.point(1.0), rng.point(2.0));
            let pose = Pose::new(rot, t);
            let world = base.world(&pose);
            let d = check_closest(&unit, &world, &pose, p, 1e-12, "unit scale");
            let sd = signed_distance(&unit, &pose, &Vec3::from(p)).unwrap();
            if let Some(inside) = ray_parity(&world, p, &mut rng).filter(|_| d > 1e-9) {
                assert_eq!(sd < 0.0, inside);
            }
            let scaled = Pose::new(rot, scale(t, s));
            let q = Vec3::from(scale(p, s));
            let r = closest_point(&model, &scaled, &q, f64::INFINITY).unwrap();
            assert!(
                (r.distance / s - d).abs() <= 1e-12,
                "scale {s}: {} vs {d}",
                r.distance / s
            );
            let id = r.triangle.unwrap() as usize;
            let on = [r.point.x / s, r.point.y / s, r.point.z / s];
            assert!(
                point_tri(on, &world[id]) <= 1e-12,
                "scale {s}: point off its triangle"
            );
            assert!((point_tri(p, &world[id]) - d).abs() <= 1e-12);
            let sds = signed_distance(&model, &scaled, &q).unwrap();
            assert!((sds / s - sd).abs() <= 1e-12, "scale {s}: {sds} vs {sd}");
            let w = winding_number(&unit, &pose, &Vec3::from(p)).unwrap();
            let ws = winding_number(&model, &scaled, &q).unwrap();
            assert!((ws - w).abs() < 1e-9, "scale {s}: w {ws} vs {w}");
        }
    }
}

#[test]
fn winding_number_matches_brute_force_and_ray_parity_on_closed_meshes() {
    let mut rng = Rng::new(2204);
    let mut meshes = vec![
        ("torus".to_string(), Mesh::torus(1.0, 0.4, 48, 24)),
        (
            "lumpy".to_string(),
            lumpy_sphere(&mut rng, 1.0, 0.3, 40, 20),
        ),
    ];
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    meshes.push((
        "torus.tris".into(),
        load(&root.join("examples/models/torus.tris")),
    ));
    for (name, mesh) in meshes {
        let (model, inward) = (mesh.model(), flipped(&mesh).model());
        let e = extent(&mesh.tris);
        for _ in 0..4 {
            let pose = rng.pose(e);
            let world = mesh.world(&pose);
            for p in query_points(&world, &mut rng, 60) {
                let (d, _) = brute_closest(&world, p);
                if d <= 1e-9 * e {
                    continue;
                }
                let q = Vec3::from(p);
                let w = winding_number(&model, &pose, &q).unwrap();
                let wb = brute_winding(&world, p);
                assert!(
                    (w - wb).abs() < winding_tol(e, d),
                    "{name}: {w} vs brute {wb}"
                );
                // Turned round, the same number with the other sign.
                let wi = winding_number(&inward, &pose, &q).unwrap();
                assert!(
                    (wi + w).abs() < winding_tol(e, d),
                    "{name}: {wi} turned round, {w}"
                );
                let Some(inside) = ray_parity(&world, p, &mut rng) else {
                    continue;
                };
                let expected = if inside { 1.0 } else { 0.0 };
                let tol = winding_tol(e, d);
                assert!(
                    (w.abs() - expected).abs() < tol,
                    "{name}: w {w}, inside {inside}"
                );
                for m in [&model, &inward] {
                    let sd = signed_distance(m, &pose, &q).unwrap();
                    assert_eq!(sd < 0.0, inside, "{name}: {sd}");
                    assert!((sd.abs() - d).abs() <= 1e-12 * e * 10.0);
                }
            }
        }
    }
}

/// Open and self-intersecting meshes: the hierarchy's winding number is the brute-force sum, and
/// the sign of the signed distance follows |w| >= 1/2 wherever w is not within rounding of 1/2.
#[test]
fn winding_number_on_open_meshes() {
    let mut rng = Rng::new(2205);
    let models = example_models();
    let bunny = models.iter().find(|(n, _)| n.contains("bunny")).unwrap();
    let mut meshes = vec![
        ("hemisphere".to_string(), hemisphere(32, 8)),
        (
            "bunny".to_string(),
            Mesh {
                tris: bunny.1.tris.clone(),
            },
        ),
        ("soup".to_string(), Mesh::soup(&mut rng, 300, 1.0, 0.5)),
    ];
    // Two tori through each other: self-intersecting.
    let mut two = Mesh::torus(1.0, 0.4, 32, 16);
    let other = Mesh::torus(1.0, 0.4, 32, 16).world(&Pose::new(
        [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]],
        [1.0, 0.0, 0.0],
    ));
    two.tris.extend(other);
    meshes.push(("two tori".to_string(), two));
    for (name, mesh) in meshes {
        let model = mesh.model();
        let e = extent(&mesh.tris);
        for _ in 0..4 {
            let pose = rng.pose(e);
            let world = mesh.world(&pose);
            let mut points = query_points(&world, &mut rng, 60);
            // Near the hemisphere's centre, where w is near 1/2.
            points.extend((0..20).map(|_| apply(&pose, rng.point(0.3))));
            for p in points {
                let (d, _) = brute_closest(&world, p);
                if d <= 1e-9 * e {
                    continue;
                }
                let w = winding_number(&model, &pose, &Vec3::from(p)).unwrap();
                let wb = brute_winding(&world, p);
                assert!(
                    (w - wb).abs() < winding_tol(e, d),
                    "{name}: {w} vs brute {wb}"
                );
                if (wb.abs() - 0.5).abs() > 1e-6 {
                    let sd = signed_distance(&model, &pose, &Vec3::from(p)).unwrap();
                    assert_eq!(sd < 0.0, wb.abs() >= 0.5, "{name}: sd {sd}, w {wb}");
                }
            }
        }
    }
}

/// The per-node boundary edges are built on the first signed distance only, and threads racing
/// to build them get the same answers. (A small model's closest point builds the ray tree of
/// boxes, about 40 B/triangle, and its triangles' frames, 248 B/triangle, and no more.)
#[test]
fn boundary_data_is_built_on_first_use_and_shared_by_threads() {
    let mut rng = Rng::new(2206);
    let mesh = lumpy_sphere(&mut rng, 1.0, 0.3, 64, 32);
    let model = mesh.model();
    let built = model.memory_usage();
    assert!(built as f64 / mesh.tris.len() as f64 <= 200.0);
    let pose = Pose::identity();
    closest_point(&model, &pose, &Vec3::new(0.1, 0.2, 0.3), f64::INFINITY).unwrap();
    let before = model.memory_usage();
    assert!(
        (before - built) as f64 / mesh.tris.len() as f64 <= 64.0 + 248.0,
        "closest point needs no boundary data"
    );
    closest_point(&model, &pose, &Vec3::new(0.4, 0.2, 0.3), f64::INFINITY).unwrap();
    assert_eq!(model.memory_usage(), before);
    let points: Vec<Vec3> = (0..64).map(|_| rng.vec3(1.5)).collect();
    let answers: Vec<Vec<f64>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..4)
            .map(|_| {
                s.spawn(|| {
                    points
                        .iter()
                        .map(|p| signed_distance(&model, &pose, p).unwrap())
                        .collect::<Vec<f64>>()
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert!(answers.iter().all(|a| a == &answers[0]));
    assert!(
        model.memory_usage() > before,
        "the boundary data is counted"
    );
    // A copy answers the same (it builds its own on use).
    let copy = model.clone();
    for (p, &sd) in points.iter().zip(&answers[0]) {
        assert_eq!(signed_distance(&copy, &pose, p).unwrap(), sd);
    }
}

#[test]
fn bad_inputs_are_refused() {
    let mesh = Mesh::torus(1.0, 0.3, 8, 6);
    let model = mesh.model();
    let here = Pose::identity();
    let p = Vec3::new(0.5, 0.5, 0.5);
    let mut unbuilt = Model::new();
    assert_eq!(
        closest_point(&unbuilt, &here, &p, 1.0),
        Err(Error::UnprocessedModel)
    );
    unbuilt
        .add_triangle([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0)
        .unwrap();
    assert_eq!(
        signed_distance(&unbuilt, &here, &p),
        Err(Error::UnprocessedModel)
    );
    assert_eq!(
        winding_number(&unbuilt, &here, &p),
        Err(Error::UnprocessedModel)
    );
    for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY, 1e151] {
        let q = Vec3::new(0.0, bad, 0.0);
        assert_eq!(
            closest_point(&model, &here, &q, 1.0),
            Err(Error::NonFiniteCoordinate)
        );
        assert_eq!(
            signed_distance(&model, &here, &q),
            Err(Error::NonFiniteCoordinate)
        );
        let mut pose = here;
        pose.rotation[(1, 2)] = bad;
        assert_eq!(
            closest_point(&model, &pose, &p, 1.0),
            Err(Error::NonFinitePose)
        );
        assert_eq!(
            signed_distance(&model, &pose, &p),
            Err(Error::NonFinitePose)
        );
        let mut pose = here;
        pose.translation.z = bad;
        assert_eq!(
            closest_point(&model, &pose, &p, 1.0),
            Err(Error::NonFinitePose)
        );
    }
    for bad in [f64::NAN, -1.0, -0.0 - f64::MIN_POSITIVE, -f64::INFINITY] {
        assert_eq!(
            closest_point(&model, &here, &p, bad),
            Err(Error::InvalidArgument)
        );
    }
    // The largest accepted coordinates are answered.
    let far = Vec3::new(1e150, -1e150, 1e150);
    let r = closest_point(&model, &here, &far, f64::INFINITY).unwrap();
    assert!(r.distance.is_finite() && r.distance > 1e150);
}

/// A refit drops the boundary edges a signed distance made (they name the vertices shared at the
/// build): a closed sphere whose triangles are then shrunk apart (every vertex unshared, the
/// surface full of cracks) answers the brute-force winding number of the cracked soup.
#[test]
fn winding_number_after_a_refit_that_unshares_vertices() {
    let mut rng = Rng::new(7);
    let mesh = lumpy_sphere(&mut rng, 1.0, 0.2, 24, 12);
    let mut model = mesh.model();
    let pose = Pose::identity();
    let centre = Vec3::from([0.05, -0.02, 0.03]);
    let w = winding_number(&model, &pose, &centre).unwrap();
    assert!((w.abs() - 1.0).abs() < 1e-9, "closed sphere: {w}");
    let shrunk: Vec<T> = mesh
        .tris
        .iter()
        .map(|t| {
            let c: V = std::array::from_fn(|k| (t[0][k] + t[1][k] + t[2][k]) / 3.0);
            t.map(|p| std::array::from_fn(|k| c[k] + 0.8 * (p[k] - c[k])))
        })
        .collect();
    model.refit(&shrunk).unwrap();
    for p in query_points(&shrunk, &mut rng, 40)
        .into_iter()
        .chain([centre.into()])
    {
        let (d, _) = brute_closest(&shrunk, p);
        if d <= 1e-9 {
            continue;
        }
        let w = winding_number(&model, &pose, &Vec3::from(p)).unwrap();
        let wb = brute_winding(&shrunk, p);
        assert!((w - wb).abs() < winding_tol(2.0, d), "{w} vs brute {wb}");
    }
}

/// On the open bunny (124 boundary edges, whose loops' far fields decide most signs), the sign
/// of the signed distance is the exact winding number's (`winding_number`) decision: for points
/// in and around it, far away, next to the surface, and on either side of where the number
/// crosses 1/2 on segments from far outside to inside.
#[test]
fn signed_distance_sign_is_the_winding_numbers_on_the_bunny() {
    let mesh =
        load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/models/bunny.tris"));
    let model = mesh.model();
    let mut rng = Rng::new(2207);
    let e = extent(&mesh.tris);
    let (mut crossings, mut inside) = (0, 0);
    for _ in 0..4 {
        let pose = rng.pose(e);
        let world = mesh.world(&pose);
        let w = |p: &Vec3| winding_number(&model, &pose, p).unwrap().abs();
        let check = |p: Vec3| {
            let sd = signed_distance(&model, &pose, &p).unwrap();
            if sd != 0.0 {
                assert_eq!(sd < 0.0, w(&p) >= 0.5, "{p}: sd {sd}");
            }
            sd < 0.0
        };
        let mut points: Vec<Vec3> = query_points(&world, &mut rng, 200)
            .into_iter()
            .map(Vec3::from)
            .collect();
        points.extend((0..50).map(|_| Vec3::from(apply(&pose, rng.point(20.0 * e)))));
        for p in points {
            inside += usize::from(check(p));
        }
        // Across 1/2: bisect from a far point to the model's centre where that is inside.
        let centre = Vec3::from(apply(&pose, [0.0, 0.1, 0.0]));
        for _ in 0..40 {
            let far = centre + rng.vec3(1.0).normalize() * (3.0 * e);
            if w(&far) >= 0.5 || w(&centre) < 0.5 {
                continue;
            }
            let (mut lo, mut hi) = (far, centre);
            for _ in 0..60 {
                let m = (lo + hi) * 0.5;
                if w(&m) >= 0.5 { hi = m } else { lo = m }
            }
            let step = (centre - far) * 1e-9;
            for k in -3..=3 {
                check(lo + step * f64::from(k));
            }
            crossings += 1;
        }
    }
    assert!(crossings > 20 && inside > 0, "{crossings} {inside}");
}
