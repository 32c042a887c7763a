//! Swept-sphere primitives as models (sphere, capsule, box) against brute force over all
//! triangles: random meshes and the example models at random poses, primitive against mesh (both
//! orders) and against primitive, triangles inside a primitive, touching and grazing contact, huge
//! and tiny scales, zero sizes; batches against single calls; what the other entry points answer.

mod common;

#[path = "../examples/workloads/mod.rs"]
mod workloads;

use common::{Mesh, Random, RandomPqp, Rng, T, V, add, apply, dot, norm, scale, sub, tri_tri};
use pqp::{
    ContactMode, DistanceOptions, DistanceResult, Error, Model, Pose, Primitive, Search, collide,
    collide_batch, distance, distance_batch, distance_into, tolerance, tolerance_batch,
    within_distance,
};

/// A posed solid in world coordinates, for brute force: the triangles of its core (a point or a
/// segment as a degenerate triangle, or a box's twelve faces, or a mesh's triangles), the radius
/// it is swept by, and for a box, its pose and half sides (to find what lies inside it).
struct Solid {
    core: Vec<T>,
    radius: f64,
    inside: Option<(Pose, V)>,
}

impl Solid {
    fn primitive(p: Primitive, pose: &Pose) -> Solid {
        let w = |v: V| apply(pose, v);
        match p {
            Primitive::Sphere { radius } => Solid {
                core: vec![[w([0.0; 3]); 3]],
                radius,
                inside: None,
            },
            Primitive::Capsule { radius, length } => {
                let (a, b) = (w([0.0, 0.0, -length / 2.0]), w([0.0, 0.0, length / 2.0]));
                Solid {
                    core: vec![[a, b, b]],
                    radius,
                    inside: None,
                }
            }
            Primitive::Box { size } => {
                let h = [size[0] / 2.0, size[1] / 2.0, size[2] / 2.0];
                let c = |i: usize| {
                    w([
                        if i & 1 == 1 { h[0] } else { -h[0] },
                        if i & 2 == 2 { h[1] } else { -h[1] },
                        if i & 4 == 4 { h[2] } else { -h[2] },
                    ])
                };
                // Each face as its four corners by index bits, split on a diagonal.
                let quads = [
                    [0, 1, 3, 2],
                    [4, 5, 7, 6],
                    [0, 1, 5, 4],
                    [2, 3, 7, 6],
                    [0, 2, 6, 4],
                    [1, 3, 7, 5],
                ];
                let core = quads
                    .iter()
                    .flat_map(|q| [[c(q[0]), c(q[1]), c(q[2])], [c(q[0]), c(q[2]), c(q[3])]])
                    .collect();
                Solid {
                    core,
                    radius: 0.0,
                    inside: Some((*pose, h)),
                }
            }
        }
    }

    fn mesh(tris: Vec<T>) -> Solid {
        Solid {
            core: tris,
            radius: 0.0,
            inside: None,
        }
    }

    /// Whether `p` is strictly inside the box (if a box).
    fn holds(&self, p: V) -> bool {
        self.inside.as_ref().is_some_and(|(pose, h)| {
            // Into the box's frame: R^T (p - T).
            let d = sub(
                p,
                [pose.translation.x, pose.translation.y, pose.translation.z],
            );
            (0..3).all(|i| {
                let axis = [
                    pose.rotation[(0, i)],
                    pose.rotation[(1, i)],
                    pose.rotation[(2, i)],
                ];
                dot(d, axis).abs() < h[i]
            })
        })
    }

    /// The brute-force distance to triangle `t` (world).
    fn to_tri(&self, t: &T) -> f64 {
        if t.iter().any(|&v| self.holds(v)) {
            return 0.0;
        }
        let d = self
            .core
            .iter()
            .map(|c| tri_tri(c, t))
            .fold(f64::INFINITY, f64::min);
        (d - self.radius).max(0.0)
    }

    /// The brute-force distance to another solid.
    fn to_solid(&self, o: &Solid) -> f64 {
        let inside = o.core.iter().flatten().any(|&v| self.holds(v))
            || self.core.iter().flatten().any(|&v| o.holds(v));
        if inside {
            return 0.0;
        }
        let d = self
            .core
            .iter()
            .flat_map(|a| o.core.iter().map(move |b| tri_tri(a, b)))
            .fold(f64::INFINITY, f64::min);
        (d - self.radius - o.radius).max(0.0)
    }

    /// How far `p` is outside the solid (0 inside), for checking closest points.
    fn outside(&self, p: V) -> f64 {
        if self.holds(p) {
            return 0.0;
        }
        let d = self
            .core
            .iter()
            .map(|c| tri_tri(c, &[p; 3]))
            .fold(f64::INFINITY, f64::min);
        (d - self.radius).max(0.0)
    }
}

fn primitive_model(p: Primitive) -> Model {
    let mut m = Model::new();
    m.set_primitive(p).unwrap();
    m
}

fn random_primitive(rng: &mut Rng, size: f64) -> Primitive {
    // Sometimes a zero size: a point, a sphere, a flat box.
    let kind = rng.below(3);
    let mut s = || {
        if rng.below(8) == 0 {
            0.0
        } else {
            rng.range(0.05, 1.0) * size
        }
    };
    match kind {
        0 => Primitive::Sphere { radius: s() },
        1 => Primitive::Capsule {
            radius: s(),
            length: s(),
        },
        _ => Primitive::Box {
            size: [s(), s(), s()],
        },
    }
}

fn vec(v: &pqp::Vec3) -> V {
    [v.x, v.y, v.z]
}

/// Checks every pair query of `a` (at `pa`) and `b` (at `pb`) against the brute-force solids
/// `sa` and `sb`: distance (and closest points), collision, tolerance and pairs within a
/// distance. `elements` lists b's triangles (world) with ids when b is a mesh, or `None`.
/// Answers within `eps` of a contact are left alone (brute force decides them in floating
/// point).
#[allow(clippy::too_many_arguments)]
fn check_pair(
    a: (&Model, Primitive),
    pa: &Pose,
    sa: &Solid,
    b: &Model,
    pb: &Pose,
    sb: &Solid,
    eps: f64,
    mesh_b: bool,
) {
    let (a, prim) = a;
    // Whether element `id` of b touches the primitive made smaller by eps: a contact brute
    // force's crossing tests decide with a margin.
    let small = Solid::primitive(shrink(prim, eps), pa);
    let deep = |id: i32| {
        if mesh_b {
            small.to_tri(&sb.core[id as usize]) == 0.0
        } else {
            small.to_solid(sb) == 0.0
        }
    };
    // Per element of b: its id and brute-force distance.
    let per: Vec<(i32, f64)> = if mesh_b {
        sb.core
            .iter()
            .enumerate()
            .map(|(i, t)| (i as i32, sa.to_tri(t)))
            .collect()
    } else {
        vec![(0, sa.to_solid(sb))]
    };
    let truth = per.iter().map(|e| e.1).fold(f64::INFINITY, f64::min);
    let r = distance(a, pa, b, pb, &DistanceOptions::exact()).unwrap();
    assert!(
        (r.distance - truth).abs() <= eps,
        "distance {} brute {}",
        r.distance,
        truth
    );
    // The closest points: on (or in) each solid, that far apart.
    let (p1, p2) = (apply(pa, vec(&r.p1)), apply(pb, vec(&r.p2)));
    assert!(
        sa.outside(p1) <= eps,
        "p1 off model 1 by {}",
        sa.outside(p1)
    );
    let off2 = if mesh_b {
        let t = &sb.core[r.id2 as usize];
        tri_tri(t, &[p2; 3])
    } else {
        sb.outside(p2)
    };
    assert!(off2 <= eps, "p2 off model 2 by {off2}");
    assert!((norm(sub(p1, p2)) - r.distance).abs() <= eps);
    assert_eq!(r.overlap, r.distance == 0.0);
    assert_eq!(r.id1, 0);
    if !mesh_b {
        assert_eq!((r.id2, r.tri1, r.tri2), (0, 0, 0));
    }
    // The same pair the other way round.
    let s = distance(b, pb, a, pa, &DistanceOptions::exact()).unwrap();
    assert!((s.distance - truth).abs() <= eps);
    assert_eq!(s.id2, 0);
    // Collision and pairs within a distance: the elements brute force puts in, except those
    // within eps of the boundary.
    let tol = if truth.is_finite() {
        truth * 1.5 + eps
    } else {
        1.0
    };
    let c = collide(a, pa, b, pb, ContactMode::All).unwrap();
    let w = within_distance(a, pa, b, pb, tol).unwrap();
    let f = collide(b, pb, a, pa, ContactMode::First).unwrap();
    assert!(f.num_pairs() <= 1);
    for (id, d) in &per {
        let hit = c.pairs().iter().any(|p| p.id1 == 0 && p.id2 == *id);
        if *d > eps {
            assert!(!hit, "element {id} at {d} collides");
        } else if *d == 0.0 && deep(*id) {
            assert!(hit, "element {id} inside or crossing does not collide");
        }
        let near = w.pairs().iter().any(|p| p.id1 == 0 && p.id2 == *id);
        if (d - tol).abs() > eps {
            assert_eq!(near, *d <= tol, "element {id} at {d}, tolerance {tol}");
        }
    }
    // Tolerance on either side of the distance.
    for (t, want) in [
        (truth + 2.0 * eps, true),
        ((truth - 2.0 * eps).max(0.0), false),
    ] {
        if !want && truth <= 2.0 * eps {
            continue;
        }
        let r = tolerance(a, pa, b, pb, t, &Search::default()).unwrap();
        assert_eq!(
            r.closer_than_tolerance, want,
            "tolerance {t}, distance {truth}"
        );
        if want {
            assert!(r.distance <= t);
        } else {
            assert!(r.distance > t && r.distance <= truth + eps);
        }
    }
    if truth > eps {
        assert!(!c.colliding());
    }
}

/// `p` made smaller by `eps` (radius and sides), to tell contacts decided within eps.
fn shrink(p: Primitive, eps: f64) -> Primitive {
    let less = |x: f64, by: f64| (x - by).max(0.0);
    match p {
        Primitive::Sphere { radius } => Primitive::Sphere {
            radius: less(radius, eps),
        },
        Primitive::Capsule { radius, length } => Primitive::Capsule {
            radius: less(radius, eps),
            length: less(length, 2.0 * eps),
        },
        Primitive::Box { size } => Primitive::Box {
            size: size.map(|x| less(x, 2.0 * eps)),
        },
    }
}

#[test]
fn primitives_against_random_meshes() {
    let mut rng = Rng::new(22);
    for case in 0..150 {
        let mesh = Mesh::soup(&mut rng, 40, 1.0, 0.4);
        let m = mesh.model();
        let p = random_primitive(&mut rng, 1.0);
        let a = primitive_model(p);
        let (pa, pb) = (rng.pose(1.0), rng.pose(0.5));
        let (sa, sb) = (Solid::primitive(p, &pa), Solid::mesh(mesh.world(&pb)));
        let _ = case;
        check_pair((&a, p), &pa, &sa, &m, &pb, &sb, 1e-9, true);
    }
}

#[test]
fn primitives_against_the_example_models() {
    let mut rng = Rng::new(2204);
    for name in ["bunny.tris", "torus.tris"] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples/models")
            .join(name);
        let tris = workloads::read_tris(&path).unwrap();
        let model = Model::from_triangles(tris.iter().copied()).unwrap();
        let mesh: Vec<T> = tris.iter().map(|t| [t.0, t.1, t.2]).collect();
        // The bunny is about 0.15 across, the torus about 1.
        let size = if name == "bunny.tris" { 0.15 } else { 1.0 };
        for _ in 0..25 {
            let p = random_primitive(&mut rng, 0.5 * size);
            let a = primitive_model(p);
            let (pa, pb) = (rng.pose(0.8 * size), rng.pose(0.2 * size));
            let world: Vec<T> = mesh.iter().map(|t| common::apply_tri(&pb, t)).collect();
            let (sa, sb) = (Solid::primitive(p, &pa), Solid::mesh(world));
            check_pair((&a, p), &pa, &sa, &model, &pb, &sb, 1e-9 * size, true);
        }
    }
}

#[test]
fn primitives_against_primitives() {
    let mut rng = Rng::new(3);
    for _ in 0..400 {
        let (p, q) = (
            random_primitive(&mut rng, 1.0),
            random_primitive(&mut rng, 1.0),
        );
        let (a, b) = (primitive_model(p), primitive_model(q));
        let (pa, pb) = (rng.pose(0.2), rng.pose(1.2));
        let (sa, sb) = (Solid::primitive(p, &pa), Solid::primitive(q, &pb));
        check_pair((&a, p), &pa, &sa, &b, &pb, &sb, 1e-9, false);
    }
}

#[test]
fn triangles_inside_a_primitive_collide_at_distance_zero() {
    let mut rng = Rng::new(5);
    for p in [
        Primitive::Sphere { radius: 1.0 },
        Primitive::Capsule {
            radius: 0.5,
            length: 3.0,
        },
        Primitive::Box {
            size: [1.0, 2.0, 3.0],
        },
    ] {
        let a = primitive_model(p);
        // Small triangles near the centre, wholly inside.
        let mesh = Mesh::soup(&mut rng, 30, 0.2, 0.05);
        let m = mesh.model();
        let pose = rng.pose(3.0);
        let r = distance(&a, &pose, &m, &pose, &DistanceOptions::exact()).unwrap();
        assert_eq!(r.distance, 0.0);
        assert!(r.overlap);
        let c = collide(&a, &pose, &m, &pose, ContactMode::All).unwrap();
        assert_eq!(c.num_pairs(), 30);
        let c = collide(&m, &pose, &a, &pose, ContactMode::First).unwrap();
        assert_eq!(c.num_pairs(), 1);
        assert_eq!(c.pairs()[0].id2, 0);
        // A mesh holding the primitive inside it (a big sphere around) does not touch it.
        let shell = Model::from_triangles(workloads::uv_sphere(10.0, 12, 24)).unwrap();
        assert!(
            !collide(&a, &pose, &shell, &pose, ContactMode::All)
                .unwrap()
                .colliding()
        );
        let d = distance(&a, &pose, &shell, &pose, &DistanceOptions::exact()).unwrap();
        assert!(d.distance > 5.0);
    }
}

#[test]
fn touching_and_grazing() {
    let tri = |z: f64| {
        Model::from_triangles([([-1.0, -1.0, z], [3.0, -1.0, z], [-1.0, 3.0, z], 9)]).unwrap()
    };
    let here = Pose::identity();
    for p in [
        Primitive::Sphere { radius: 1.0 },
        Primitive::Capsule {
            radius: 0.5,
            length: 1.0,
        },
        Primitive::Box {
            size: [0.5, 0.5, 2.0],
        },
    ] {
        let a = primitive_model(p);
        // Resting exactly on the plane z = 1 (the sphere's, the capsule's and the box's top).
        let on = tri(1.0);
        assert_eq!(
            distance(&a, &here, &on, &here, &DistanceOptions::exact())
                .unwrap()
                .distance,
            0.0
        );
        assert!(
            collide(&a, &here, &on, &here, ContactMode::All)
                .unwrap()
                .colliding()
        );
        assert_eq!(
            within_distance(&a, &here, &on, &here, 0.0)
                .unwrap()
                .num_pairs(),
            1
        );
        // Just above: apart by that much.
        let gap = 1e-12;
        let above = tri(1.0 + gap);
        let d = distance(&a, &here, &above, &here, &DistanceOptions::exact())
            .unwrap()
            .distance;
        assert!(d > 0.0 && (d - gap).abs() < 1e-15, "{p:?}: {d}");
        assert!(
            !collide(&a, &here, &above, &here, ContactMode::All)
                .unwrap()
                .colliding()
        );
        assert!(
            tolerance(&a, &here, &above, &here, 2e-12, &Search::default())
                .unwrap()
                .closer_than_tolerance
        );
    }
    // A box edge grazing a triangle's edge, and corner on corner.
    let b = primitive_model(Primitive::Box {
        size: [2.0, 2.0, 2.0],
    });
    let edge =
        Model::from_triangles([([1.0, 1.0, -5.0], [1.0, 1.0, 5.0], [4.0, 4.0, 0.0], 1)]).unwrap();
    assert!(
        collide(&b, &here, &edge, &here, ContactMode::All)
            .unwrap()
            .colliding()
    );
    let corner =
        Model::from_triangles([([1.0, 1.0, 1.0], [2.0, 1.0, 1.0], [1.0, 2.0, 2.0], 1)]).unwrap();
    assert!(
        collide(&b, &here, &corner, &here, ContactMode::All)
            .unwrap()
            .colliding()
    );
    let off = Pose::from_translation([1e-13, 0.0, 0.0]);
    assert!(
        !collide(&b, &here, &corner, &off, ContactMode::All)
            .unwrap()
            .colliding()
    );
    // Two boxes face to face, and two spheres touching.
    let c = primitive_model(Primitive::Box {
        size: [2.0, 2.0, 2.0],
    });
    let right = Pose::from_translation([2.0, 0.5, 0.5]);
    assert!(
        collide(&b, &here, &c, &right, ContactMode::All)
            .unwrap()
            .colliding()
    );
    let s = primitive_model(Primitive::Sphere { radius: 0.5 });
    let d = distance(
        &s,
        &here,
        &s,
        &Pose::from_translation([1.0, 0.0, 0.0]),
        &DistanceOptions::exact(),
    )
    .unwrap();
    assert_eq!(d.distance, 0.0);
}

#[test]
fn huge_and_tiny_scales() {
    let mut rng = Rng::new(7);
    for k in [1e-100, 1e-30, 1.0, 1e30, 1e100] {
        for _ in 0..20 {
            let mesh = Mesh::soup(&mut rng, 20, 1.0, 0.5);
            let scaled = Mesh {
                tris: mesh.tris.iter().map(|t| t.map(|v| scale(v, k))).collect(),
            };
            let p = random_primitive(&mut rng, 1.0);
            let big = match p {
                Primitive::Sphere { radius } => Primitive::Sphere { radius: radius * k },
                Primitive::Capsule { radius, length } => Primitive::Capsule {
                    radius: radius * k,
                    length: length * k,
                },
                Primitive::Box { size } => Primitive::Box {
                    size: size.map(|s| s * k),
                },
            };
            let pose = rng.pose(1.0);
            let at = |pose: &Pose, k: f64| Pose {
                rotation: pose.rotation,
                translation: pose.translation * k,
            };
            let r1 = distance(
                &primitive_model(p),
                &pose,
                &mesh.model(),
                &Pose::identity(),
                &DistanceOptions::exact(),
            )
            .unwrap();
            let rk = distance(
                &primitive_model(big),
                &at(&pose, k),
                &scaled.model(),
                &Pose::identity(),
                &DistanceOptions::exact(),
            )
            .unwrap();
            assert!(
                (rk.distance / k - r1.distance).abs() <= 1e-9,
                "scale {k}: {} {}",
                rk.distance / k,
                r1.distance
            );
            let c1 = collide(
                &primitive_model(p),
                &pose,
                &mesh.model(),
                &Pose::identity(),
                ContactMode::All,
            )
            .unwrap();
            let ck = collide(
                &primitive_model(big),
                &at(&pose, k),
                &scaled.model(),
                &Pose::identity(),
                ContactMode::All,
            )
            .unwrap();
            if r1.distance > 1e-9 || r1.distance == 0.0 && rk.distance == 0.0 {
                assert_eq!(c1.colliding(), ck.colliding());
            }
        }
    }
}

#[test]
fn zero_sizes() {
    let here = Pose::identity();
    let tri =
        Model::from_triangles([([-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0], 4)]).unwrap();
    let up = Pose::from_translation([0.0, 0.0, 2.0]);
    for (p, d) in [
        (Primitive::Sphere { radius: 0.0 }, 2.0),
        (
            Primitive::Capsule {
                radius: 0.0,
                length: 0.0,
            },
            2.0,
        ),
        (
            Primitive::Capsule {
                radius: 0.0,
                length: 1.0,
            },
            1.5,
        ),
        (
            Primitive::Capsule {
                radius: 0.5,
                length: 0.0,
            },
            1.5,
        ),
        (
            Primitive::Box {
                size: [0.0, 0.0, 0.0],
            },
            2.0,
        ),
        (
            Primitive::Box {
                size: [3.0, 3.0, 0.0],
            },
            2.0,
        ),
        (
            Primitive::Box {
                size: [0.0, 0.0, 1.0],
            },
            1.5,
        ),
    ] {
        let a = primitive_model(p);
        let r = distance(&a, &up, &tri, &here, &DistanceOptions::exact()).unwrap();
        assert_eq!(r.distance, d, "{p:?}");
        // Lowered onto the triangle, each touches it.
        let down = Pose::from_translation([0.0, 0.0, 2.0 - d]);
        assert!(
            collide(&a, &down, &tri, &here, ContactMode::All)
                .unwrap()
                .colliding(),
            "{p:?}"
        );
    }
    // A flat box crossing a triangle edge-on collides; a point in the triangle too.
    let flat = primitive_model(Primitive::Box {
        size: [3.0, 3.0, 0.0],
    });
    let tilted = Pose::new(
        [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]],
        [0.0, 0.0, 0.0],
    );
    assert!(
        collide(&flat, &tilted, &tri, &here, ContactMode::All)
            .unwrap()
            .colliding()
    );
    let point = primitive_model(Primitive::Sphere { radius: 0.0 });
    assert!(
        collide(
            &point,
            &Pose::from_translation([0.0, 0.0, 0.0]),
            &tri,
            &here,
            ContactMode::All
        )
        .unwrap()
        .colliding()
    );
}

#[test]
fn batches_answer_as_single_calls() {
    let mut rng = Rng::new(11);
    let mesh = Mesh::soup(&mut rng, 60, 1.0, 0.3).model();
    for p in [
        Primitive::Sphere { radius: 0.3 },
        Primitive::Capsule {
            radius: 0.2,
            length: 0.8,
        },
        Primitive::Box {
            size: [0.4, 0.6, 0.2],
        },
    ] {
        let a = primitive_model(p);
        let poses: Vec<(Pose, Pose)> = (0..64).map(|_| (rng.pose(1.0), rng.pose(0.3))).collect();
        for (m1, m2) in [(&a, &mesh), (&mesh, &a), (&a, &a)] {
            let d = distance_batch(m1, m2, &poses, &DistanceOptions::exact(), 0).unwrap();
            let c = collide_batch(m1, m2, &poses, 0).unwrap();
            let t = tolerance_batch(m1, m2, &poses, 0.1, &Search::default(), 0).unwrap();
            for (k, (p1, p2)) in poses.iter().enumerate() {
                let one = distance(m1, p1, m2, p2, &DistanceOptions::exact()).unwrap();
                assert_eq!(d[k].to_bits(), one.distance.to_bits());
                assert_eq!(
                    c[k],
                    collide(m1, p1, m2, p2, ContactMode::First)
                        .unwrap()
                        .colliding()
                );
                assert_eq!(t[k], one.distance <= 0.1);
            }
        }
    }
}

#[test]
fn approximate_distance_stays_within_its_bounds() {
    let mut rng = Rng::new(13);
    let mesh = Mesh::soup(&mut rng, 200, 1.0, 0.2).model();
    let a = primitive_model(Primitive::Capsule {
        radius: 0.1,
        length: 0.5,
    });
    for _ in 0..50 {
        let (pa, pb) = (rng.pose(3.0), rng.pose(0.5));
        let exact = distance(&a, &pa, &mesh, &pb, &DistanceOptions::exact())
            .unwrap()
            .distance;
        for (rel, abs) in [(0.5, f64::INFINITY), (0.0, 0.0), (1.0, 0.1)] {
            let d = distance(&a, &pa, &mesh, &pb, &DistanceOptions::approximate(rel, abs))
                .unwrap()
                .distance;
            assert!(d >= exact && d <= (exact * (1.0 + rel)).min(exact + abs) + 1e-12);
        }
    }
}

#[test]
fn a_result_moves_between_meshes_and_primitives() {
    // A result filled by a mesh pair, then used with a primitive and back: each answer as fresh.
    let mut rng = Rng::new(17);
    let (m, n) = (
        Mesh::soup(&mut rng, 50, 1.0, 0.3).model(),
        Mesh::soup(&mut rng, 50, 1.0, 0.3).model(),
    );
    let s = primitive_model(Primitive::Sphere { radius: 0.2 });
    let mut r = DistanceResult::new();
    for _ in 0..20 {
        let (p1, p2) = (rng.pose(1.0), rng.pose(1.0));
        for (a, b) in [(&m, &n), (&s, &n), (&m, &s), (&m, &n)] {
            distance_into(&mut r, a, &p1, b, &p2, &DistanceOptions::exact()).unwrap();
            let fresh = distance(a, &p1, b, &p2, &DistanceOptions::exact()).unwrap();
            assert_eq!(r.distance, fresh.distance);
            assert_eq!((r.id1, r.id2), (fresh.id1, fresh.id2));
        }
    }
}

#[test]
fn other_entry_points_answer_for_a_primitive() {
    let mut m = primitive_model(Primitive::Sphere { radius: 1.0 });
    let mesh =
        Model::from_triangles([([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0)]).unwrap();
    let here = Pose::identity();
    let p = pqp::Vec3::zeros();
    assert_eq!(m.num_triangles(), 0);
    assert!(m.is_built());
    assert_eq!(
        pqp::closest_point(&m, &here, &p, f64::INFINITY).err(),
        Some(Error::NotATriangleMesh)
    );
    assert_eq!(
        pqp::signed_distance(&m, &here, &p).err(),
        Some(Error::NotATriangleMesh)
    );
    assert_eq!(
        pqp::winding_number(&m, &here, &p).err(),
        Some(Error::NotATriangleMesh)
    );
    assert_eq!(
        pqp::ray_cast(&m, &here, &p, &pqp::Vec3::x(), f64::INFINITY).err(),
        Some(Error::NotATriangleMesh)
    );
    assert_eq!(
        pqp::self_collide(&m, ContactMode::All).err(),
        Some(Error::NotATriangleMesh)
    );
    assert_eq!(m.to_bytes().err(), Some(Error::NotATriangleMesh));
    assert_eq!(m.refit(&[]), Err(Error::NotATriangleMesh));
    let motion = pqp::Motion::new(here, here);
    assert_eq!(
        pqp::time_of_contact(&m, &motion, &mesh, &motion, 0.1).err(),
        Some(Error::NotATriangleMesh)
    );
    // Build calls: add and end refuse, begin clears it into a mesh.
    assert_eq!(
        m.add_triangle([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0),
        Err(Error::BuildOutOfSequence)
    );
    assert_eq!(m.end(), Err(Error::BuildOutOfSequence));
    assert!(m.primitive().is_some());
    let clone = m.clone();
    assert_eq!(m.begin(1), Err(Error::BuildOutOfSequence));
    assert_eq!(m.primitive(), None);
    assert!(!m.is_built());
    m.add_triangle([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0)
        .unwrap();
    m.end().unwrap();
    assert!(
        collide(&m, &here, &mesh, &here, ContactMode::All)
            .unwrap()
            .colliding()
    );
    // The clone kept the sphere; an unbuilt mesh against a primitive is refused.
    assert_eq!(clone.primitive(), Some(Primitive::Sphere { radius: 1.0 }));
    let unbuilt = Model::new();
    assert_eq!(
        collide(&clone, &here, &unbuilt, &here, ContactMode::All).err(),
        Some(Error::UnprocessedModel)
    );
    assert_eq!(
        distance(&unbuilt, &here, &clone, &here, &DistanceOptions::exact()).err(),
        Some(Error::UnprocessedModel)
    );
    let bad = Pose::from_translation([f64::NAN, 0.0, 0.0]);
    assert_eq!(
        distance(&clone, &bad, &mesh, &here, &DistanceOptions::exact()).err(),
        Some(Error::NonFinitePose)
    );
    assert_eq!(
        within_distance(&clone, &here, &mesh, &here, -1.0).err(),
        Some(Error::InvalidArgument)
    );
    let _ = (add, dot);
}

#[test]
fn primitives_inside_primitives_touch() {
    let mut rng = Rng::new(19);
    let big = [
        Primitive::Box {
            size: [4.0, 5.0, 6.0],
        },
        Primitive::Sphere { radius: 3.0 },
        Primitive::Capsule {
            radius: 2.0,
            length: 3.0,
        },
    ];
    let small = [
        Primitive::Box {
            size: [0.5, 0.2, 0.3],
        },
        Primitive::Sphere { radius: 0.3 },
        Primitive::Capsule {
            radius: 0.1,
            length: 0.5,
        },
        Primitive::Box {
            size: [0.0, 0.0, 0.0],
        },
    ];
    for outer in big {
        for inner in small {
            let (a, b) = (primitive_model(outer), primitive_model(inner));
            for _ in 0..10 {
                let pa = rng.pose(5.0);
                // Inner near outer's centre, turned anyhow.
                let near = Pose::new(rng.rotation(), rng.point(0.3));
                let pb = Pose {
                    rotation: pa.rotation * near.rotation,
                    translation: pa.transform_point(&near.translation),
                };
                for (m1, p1, m2, p2) in [(&a, &pa, &b, &pb), (&b, &pb, &a, &pa)] {
                    let r = distance(m1, p1, m2, p2, &DistanceOptions::exact()).unwrap();
                    assert_eq!(r.distance, 0.0, "{outer:?} around {inner:?}");
                    assert!(
                        collide(m1, p1, m2, p2, ContactMode::All)
                            .unwrap()
                            .colliding()
                    );
                }
            }
        }
    }
}
