//! Self-collision (`self_collide`): the hierarchy searched against itself finds exactly the pairs
//! that brute force over all pairs finds with the same rule (`query::self_contact`), on the shared
//! models, closed meshes, random soups, meshes with planted intersections, folded and coplanar
//! neighbours and duplicated triangles; the rule itself on cases whose answer is known by
//! construction; and bad input.

mod common;

use common::{Mesh, Random, Rng, T};
use pqp::query::self_contact;
use pqp::{
    CollisionVolume, ContactMode, Error, Model, Pose, Vec3, VolumeKind, collide, self_collide,
};

fn build(mesh: &[T], volume: VolumeKind, collision: CollisionVolume) -> Model {
    let mut m = Model::new();
    m.set_volume(volume).unwrap();
    m.set_collision_volume(collision).unwrap();
    m.begin(mesh.len()).unwrap();
    for (i, t) in mesh.iter().enumerate() {
        m.add_triangle(t[0], t[1], t[2], i as i32).unwrap();
    }
    m.end().unwrap();
    m
}

fn tri(t: &T) -> pqp::geometry::Tri {
    t.map(Vec3::from)
}

/// All pairs `i < j` (ids are indices, added in order) that the rule reports.
fn brute(mesh: &[T]) -> Vec<(i32, i32)> {
    let mut out = Vec::new();
    for i in 0..mesh.len() {
        for j in i + 1..mesh.len() {
            if self_contact(&tri(&mesh[i]), &tri(&mesh[j])) {
                out.push((i as i32, j as i32));
            }
        }
    }
    out
}

/// Self-collision of `mesh` with every volume choice equals brute force, in both modes.
fn check(mesh: &[T]) -> Vec<(i32, i32)> {
    let want = brute(mesh);
    for (volume, collision) in [
        (VolumeKind::Rss, CollisionVolume::Obb),
        (VolumeKind::Hybrid, CollisionVolume::Ssv),
    ] {
        let m = build(mesh, volume, collision);
        let r = self_collide(&m, ContactMode::All).unwrap();
        let mut got: Vec<_> = r.pairs().iter().map(|p| (p.id1, p.id2)).collect();
        let n = got.len();
        got.sort();
        got.dedup();
        assert_eq!(n, got.len(), "a pair reported twice");
        assert_eq!(got, want);
        let first = self_collide(&m, ContactMode::First).unwrap();
        assert_eq!(first.colliding(), !want.is_empty());
        assert!(first.num_pairs() <= 1);
        if let Some(p) = first.pairs().first() {
            assert!(want.contains(&(p.id1, p.id2)));
        }
    }
    want
}

fn load(name: &str) -> Vec<T> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models");
    let dir = if dir.exists() {
        dir
    } else {
        std::path::PathBuf::from("/work/shared/models")
    };
    let text = std::fs::read_to_string(dir.join(name)).unwrap();
    let nums: Vec<f64> = text
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    (0..nums[0] as usize)
        .map(|k| {
            let v = |i: usize| {
                let o = 1 + 9 * k + 3 * i;
                [nums[o], nums[o + 1], nums[o + 2]]
            };
            [v(0), v(1), v(2)]
        })
        .collect()
}

#[test]
fn rule_on_known_cases() {
    let t = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| [Vec3::from(a), Vec3::from(b), Vec3::from(c)];
    let (o, x, y) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let base = t(o, x, y);
    // Sharing edge x y: bent (not coplanar), flat on the other side, folded onto it.
    assert!(!self_contact(&base, &t(x, y, [1.0, 1.0, 0.3])));
    assert!(!self_contact(&base, &t(y, x, [1.0, 1.0, 0.0])));
    assert!(self_contact(&base, &t(x, y, [0.2, 0.2, 0.0])));
    assert!(self_contact(&base, &t(x, y, [-3.0, -3.0, 0.0])));
    // Sharing vertex o: apart, bent, touching beyond it, crossing through, coplanar overlapping
    // wedges, coplanar wedges apart.
    assert!(!self_contact(
        &base,
        &t(o, [-1.0, 0.0, 0.0], [0.0, -1.0, 0.5])
    ));
    assert!(!self_contact(
        &base,
        &t(o, [1.0, 1.0, 1.0], [0.0, 1.0, 1.0])
    ));
    assert!(self_contact(&base, &t(o, [0.5, 0.5, 0.0], [0.0, 0.0, 1.0])));
    assert!(self_contact(
        &base,
        &t(o, [0.3, 0.3, 1.0], [0.3, 0.3, -1.0])
    ));
    assert!(self_contact(&base, &t(o, [2.0, 1.0, 0.0], [1.0, 2.0, 0.0])));
    assert!(!self_contact(
        &base,
        &t(o, [-2.0, 1.0, 0.0], [-1.0, -2.0, 0.0])
    ));
    // Identical, in any order; no shared vertex: crossing and apart.
    assert!(self_contact(&base, &base));
    assert!(self_contact(&base, &t(y, o, x)));
    assert!(self_contact(
        &base,
        &t([0.2, 0.2, -1.0], [0.3, 0.2, 1.0], [0.2, 0.3, 1.0])
    ));
    assert!(!self_contact(
        &base,
        &t([0.2, 0.2, 0.1], [0.3, 0.2, 1.0], [0.2, 0.3, 1.0])
    ));
    // A degenerate triangle lying in the shared edge; one sticking out along it beyond the
    // other's end (collinear overlap beyond the edge does not exist: x y is b's whole edge).
    assert!(!self_contact(&base, &t(x, y, [0.5, 0.5, 0.0])));
    assert!(!self_contact(&base, &t(x, y, [2.0, -1.0, 0.0])));
    // Two triangles sharing a vertex, one a segment reaching into the other.
    assert!(self_contact(&base, &t(o, [0.2, 0.2, 0.0], [0.2, 0.2, 0.0])));
}

#[test]
fn closed_meshes_have_no_self_intersection() {
    for mesh in [
        Mesh::torus(1.0, 0.3, 24, 12).tris,
        Mesh::sphere(1.0, 20, 10).tris,
        load("torus.tris"),
    ] {
        // The sphere's poles hold degenerate triangles (a point twice): still no report.
        assert!(check(&mesh).is_empty());
    }
}

#[test]
fn bunny_equals_brute_force() {
    let mesh = load("bunny.tris");
    check(&mesh);
}

#[test]
fn random_soups_equal_brute_force() {
    let mut rng = Rng::new(40);
    for k in 0..6 {
        let mut mesh = Mesh::soup(&mut rng, 150 + 50 * k, 1.0, 0.2).tris;
        // Some triangles share vertices with earlier ones (exact copies of their coordinates).
        for i in (10..mesh.len()).step_by(3) {
            let j = rng.int(0, i as i64 - 1) as usize;
            let (a, b) = (rng.int(0, 2) as usize, rng.int(0, 2) as usize);
            mesh[i][a] = mesh[j][b];
            if k % 2 == 0 {
                mesh[i][(a + 1) % 3] = mesh[j][(b + 1) % 3];
            }
        }
        assert!(!check(&mesh).is_empty());
    }
}

/// A torus with planted faults: a triangle crossing the tube, a neighbour folded onto its
/// neighbour, a vertex pulled through the far side, and duplicated triangles.
#[test]
fn planted_faults_are_found() {
    let base = Mesh::torus(1.0, 0.3, 16, 8).tris;
    assert!(brute(&base).is_empty());
    // A spike across the tube.
    let mut spiked = base.clone();
    spiked.push([[1.0, 0.0, -1.0], [1.05, 0.0, 1.0], [0.95, 0.05, 1.0]]);
    let want = check(&spiked);
    assert!(!want.is_empty() && want.iter().all(|p| p.1 == base.len() as i32));
    // Triangle 1 shares the edge a c with triangle 0 (a b c); moving its vertex d onto the far
    // side of the edge, inside triangle 0's plane, folds it onto triangle 0.
    let mut folded = base.clone();
    let [a, b, c] = folded[0];
    let inside = [
        (a[0] + b[0] + c[0]) / 3.0,
        (a[1] + b[1] + c[1]) / 3.0,
        (a[2] + b[2] + c[2]) / 3.0,
    ];
    folded[1][2] = inside;
    let got = check(&folded);
    // The centroid is rounded off the plane, so folded or not is the rule's exact call; the
    // pair is reported exactly when the rule says so, which the coplanar case below pins.
    assert_eq!(got, brute(&folded));
    // Exactly coplanar neighbours in the plane z = 0: a flat fan folded over.
    let flat = vec![
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.25, 0.25, 0.0]],
        [[0.0, 1.0, 0.0], [0.0, 0.0, 0.0], [-1.0, 0.5, 0.0]],
    ];
    assert_eq!(check(&flat), vec![(0, 1)]);
    // Duplicates: an exact copy and a permuted copy of triangle 5.
    let mut dup = base.clone();
    dup.push(base[5]);
    dup.push([base[5][2], base[5][0], base[5][1]]);
    let got = check(&dup);
    let n = base.len() as i32;
    for p in [(5, n), (5, n + 1), (n, n + 1)] {
        assert!(got.contains(&p), "{p:?} missing from {got:?}");
    }
    // A vertex pulled through the tube: its triangles cross the far side.
    let mut pulled = base.clone();
    // Triangle 32's first vertex is on the tube's outer equator; pulled into the hole, the
    // triangles around it cross the tube's inner side.
    let v = pulled[32][0];
    let through = [v[0] * 0.3, v[1] * 0.3, v[2]];
    for t in pulled.iter_mut() {
        for p in t.iter_mut() {
            if *p == v {
                *p = through;
            }
        }
    }
    assert!(!check(&pulled).is_empty());
}

/// A vertex written with a negative zero is the same point as with a positive one: triangles
/// using either share it (a built model stores them apart, so the search compares coordinates
/// there). And a saved model, loaded, answers as the model it was saved from.
#[test]
fn negative_zeros_and_loaded_models_equal_brute_force() {
    // A fan around the origin, the origin written four ways; the fan's blades meet only there.
    let zeros = [
        [0.0, 0.0, 0.0],
        [-0.0, 0.0, 0.0],
        [0.0, -0.0, -0.0],
        [-0.0, -0.0, -0.0],
    ];
    let mut fan = Vec::new();
    for k in 0..8 {
        let (a, b) = (k as f64 * 0.7, k as f64 * 0.7 + 0.5);
        let z = if k % 2 == 0 { 0.2 } else { -0.2 };
        fan.push([zeros[k % 4], [a.cos(), a.sin(), z], [b.cos(), b.sin(), z]]);
    }
    // One more through the origin, upright, crossing blade 0 (angles 0 to 0.5) beyond it.
    fan.push([zeros[1], [0.9, 0.1, 0.4], [0.9, 0.1, -0.1]]);
    let want = check(&fan);
    assert_eq!(want, vec![(0, 8)]);
    for mesh in [fan, Mesh::torus(1.0, 0.3, 24, 12).tris, load("bunny.tris")] {
        let m = build(&mesh, VolumeKind::Rss, CollisionVolume::Obb);
        let loaded = Model::from_bytes(&m.to_bytes().unwrap()).unwrap();
        let mut got: Vec<_> = self_collide(&loaded, ContactMode::All)
            .unwrap()
            .pairs()
            .iter()
            .map(|p| (p.id1, p.id2))
            .collect();
        got.sort();
        assert_eq!(got, brute(&mesh));
    }
}

/// Against the collision query of the model with itself: every self-collision pair is a colliding
/// pair, and colliding pairs of triangles sharing no vertex are exactly the self-collision pairs
/// of such triangles.
#[test]
fn agrees_with_collide_of_the_model_with_itself() {
    let mut rng = Rng::new(41);
    let mesh = Mesh::soup(&mut rng, 300, 1.0, 0.2).tris;
    let m = build(&mesh, VolumeKind::Rss, CollisionVolume::Obb);
    let id = Pose::identity();
    let all = collide(&m, &id, &m, &id, ContactMode::All).unwrap();
    let mut from_collide: Vec<_> = all
        .pairs()
        .iter()
        .filter(|p| p.id1 < p.id2)
        .map(|p| (p.id1, p.id2))
        .collect();
    from_collide.sort();
    let own = check(&mesh);
    // The soup's triangles share no vertex: the two answers are the same.
    assert_eq!(own, from_collide);
}

#[test]
fn unbuilt_models_are_refused() {
    let mut m = Model::new();
    assert_eq!(
        self_collide(&m, ContactMode::All).unwrap_err(),
        Error::UnprocessedModel
    );
    m.add_triangle([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0)
        .unwrap();
    assert_eq!(
        self_collide(&m, ContactMode::First).unwrap_err(),
        Error::UnprocessedModel
    );
    m.end().unwrap();
    assert!(!self_collide(&m, ContactMode::All).unwrap().colliding());
}
