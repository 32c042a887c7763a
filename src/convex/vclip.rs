//! V-Clip (Mirtich, *V-Clip: Fast and Robust Polyhedral Collision Detection*, ACM TOG 1998):
//! closest-feature tracking between two convex polyhedra.
//!
//! A state is a pair of features, one per model. A pair is *final* when each feature's closest
//! point to the other feature lies in the other feature's Voronoi region; then they are a globally
//! closest pair (the closest points are each other's nearest points on the other polyhedron, so the
//! two tangent planes at them separate the models). Otherwise one feature is replaced, and the
//! Voronoi plane that the closest point violates says by which neighbour. Points of the other
//! feature are tested against Voronoi planes directly (vertex against a region), and edges are
//! *clipped* against a region: where the edge crosses each Voronoi plane, the sign of the derivative
//! of the distance along the edge tells on which side of the crossing the edge's closest point lies,
//! without computing it.
//!
//! # Termination
//!
//! Let `delta(X, Y)` be the Euclidean distance between the point sets of the two features and
//! `dim` the sum of their dimensions (vertex 0, edge 1, face 2). Every update strictly decreases the
//! pair `(delta, dim)` in lexicographic order:
//!
//! * moving to a neighbour of higher dimension (vertex -> edge, edge -> face) happens only when the
//!   other feature's closest point lies strictly beyond the Voronoi plane shared with it, which
//!   makes that neighbour strictly closer: `delta` decreases;
//! * moving to a lower dimension (edge -> vertex when the closest point is beyond the vertex's plane;
//!   face -> one of its edges when the closest point of the face is on its boundary, chosen as the
//!   boundary edge nearest the other feature) keeps `delta` and lowers `dim`;
//! * the one non-local move, the *local minimum* of a vertex under a face's plane but inside its
//!   prism, jumps to the feature of the face's polyhedron nearest the vertex (or reports
//!   penetration when the vertex is inside): the face lies on the polyhedron, so that feature is
//!   strictly nearer than the face's plane is (equal only for a flat polyhedron, which we never
//!   build), and `delta` decreases;
//! * penetration (a vertex inside, an edge through a face) ends the search.
//!
//! So no state repeats and the search ends within `(V1+E1+F1)(V2+E2+F2)` updates. In floating point
//! a near-tie could be decided inconsistently between two states; the transition function is
//! deterministic on a finite set, so such a cycle is caught by Brent's cycle detection, and the
//! pair of least distance on the cycle is reported (the states on it are within rounding of a tie).
//! A hard bound of `4 (V1+E1+F1)(V2+E2+F2) + 64` iterations, beyond what either argument allows,
//! turns any remaining surprise into `Error::Internal` instead of a loop.

use super::closest::{point_at, point_segment_param, segment_segment_params};
use super::model::{ConvexModel, Plane};
use super::{Feature, FeatureKind};
use crate::error::Error;
use crate::math::{Mat3, RelPose, Vec3};

/// One model as the search sees it: its features, and the map from the other model's frame into
/// its own.
struct Side<'a> {
    m: &'a ConvexModel,
    rot: Mat3,
    trans: Vec3,
}

impl Side<'_> {
    #[inline]
    fn import(&self, p: &Vec3) -> Vec3 {
        self.rot * p + self.trans
    }
}

/// What a handler decides, for the pair `(X, Y)` it was called on.
enum Step {
    /// Replace X's feature.
    X(Feature),
    /// Replace Y's feature.
    Y(Feature),
    /// Final pair: closest points in X's and Y's frames, and their distance (0 when touching).
    Apart { px: Vec3, py: Vec3, dist: f64 },
    /// The models share a point: it, in X's frame and in Y's frame.
    Contact { px: Vec3, py: Vec3 },
}

/// A handler's decision mapped back to models 1 and 2.
enum Outcome {
    Update(usize, Feature),
    Apart([Vec3; 2], f64),
    Contact([Vec3; 2]),
}

/// Counters of one search.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Counters {
    pub iterations: u32,
    pub local_minima: u32,
    pub cycles: u32,
}

/// The answer of a search, points in each model's own frame.
pub(crate) struct VClipAnswer {
    pub state: [Feature; 2],
    pub intersecting: bool,
    pub distance: f64,
    pub points: [Vec3; 2],
    pub counters: Counters,
}

/// The Voronoi plane that `p` violates most (`eval < 0`), if any, with its neighbour.
fn most_violated(planes: impl Iterator<Item = (Plane, Feature)>, p: &Vec3) -> Option<Feature> {
    let mut best = None;
    let mut worst = 0.0;
    for (pl, f) in planes {
        let s = pl.eval(p);
        if s < worst {
            worst = s;
            best = Some(f);
        }
    }
    best
}

/// Clipping of segment `e(l) = a + l (b - a)`, `l` in `[lo, hi]`, against Voronoi planes.
///
/// `deriv(l)` has the sign of the derivative, along `b - a`, of the distance from `e(l)` to the
/// region's feature. The closest point `e(l*)` violates a plane exactly when either the whole
/// interval does, or the plane cuts the interval at `lc` and the distance still decreases into the
/// violated part (`deriv(lc) > 0` when the violated part is below `lc`, `< 0` when above), the
/// distance being convex along the segment. Returns the neighbour behind the first such plane.
fn locate(
    a: &Vec3,
    b: &Vec3,
    lo: f64,
    hi: f64,
    planes: impl Iterator<Item = (Plane, Feature)>,
    deriv: impl Fn(f64) -> f64,
) -> Option<Feature> {
    for (pl, f) in planes {
        let (sa, sb) = (pl.eval(a), pl.eval(b));
        let at = |l: f64| {
            if l <= 0.0 {
                sa
            } else if l >= 1.0 {
                sb
            } else {
                sa + l * (sb - sa)
            }
        };
        let (slo, shi) = (at(lo), at(hi));
        if slo < 0.0 && shi < 0.0 {
            return Some(f);
        }
        if slo < 0.0 {
            let lc = (sa / (sa - sb)).clamp(lo, hi);
            if deriv(lc) > 0.0 {
                return Some(f);
            }
        } else if shi < 0.0 {
            let lc = (sa / (sa - sb)).clamp(lo, hi);
            if deriv(lc) < 0.0 {
                return Some(f);
            }
        }
    }
    None
}

fn vertex_planes(m: &ConvexModel, v: u32) -> impl Iterator<Item = (Plane, Feature)> + '_ {
    m.vertex_planes(v).map(|(p, f, _)| (p, f))
}

/// Vertex-vertex: each vertex against the other's region (its edge planes).
fn vv(x: &Side, vx: u32, y: &Side, vy: u32) -> Step {
    let px = *x.m.vert(vx);
    let py_x = x.import(y.m.vert(vy));
    if let Some(f) = most_violated(vertex_planes(x.m, vx), &py_x) {
        return Step::X(f);
    }
    let py = *y.m.vert(vy);
    if let Some(f) = most_violated(vertex_planes(y.m, vy), &y.import(&px)) {
        return Step::Y(f);
    }
    Step::Apart {
        px,
        py,
        dist: (py_x - px).norm(),
    }
}

/// Vertex (X) - edge (Y).
fn ve(x: &Side, vx: u32, y: &Side, ey: u32) -> Step {
    let ed = &y.m.edges[ey as usize];
    let nb = y.m.edge_neighbours(ey);
    let v_y = y.import(x.m.vert(vx));
    // Beyond a vertex plane the edge's closest point is that vertex: same distance, lower dim.
    if ed.planes[0].eval(&v_y) < 0.0 {
        return Step::Y(nb[0]);
    }
    if ed.planes[1].eval(&v_y) < 0.0 {
        return Step::Y(nb[1]);
    }
    let (sl, sr) = (ed.planes[2].eval(&v_y), ed.planes[3].eval(&v_y));
    if sl < 0.0 || sr < 0.0 {
        return Step::Y(if sl <= sr { nb[2] } else { nb[3] });
    }
    // The edge against the vertex's region.
    let v = *x.m.vert(vx);
    let (ty, hy) = (y.m.vert(ed.tail), y.m.vert(ed.head));
    let (a, b) = (x.import(ty), x.import(hy));
    let d = b - a;
    if let Some(f) = locate(&a, &b, 0.0, 1.0, vertex_planes(x.m, vx), |l| {
        (point_at(&a, &b, l) - v).dot(&d)
    }) {
        return Step::X(f);
    }
    let py = point_at(ty, hy, point_segment_param(&v_y, ty, hy));
    Step::Apart {
        px: v,
        py,
        dist: (v_y - py).norm(),
    }
}

/// Where, relative to the region of X's edge `ex`, the point of Y's edge `ey` closest to `ex`
/// lies: the neighbour of `ex` to move to, or `None` inside the region. Vertex planes first (the
/// closest point beyond one keeps the distance); then the face planes on the part of `ey` between
/// the vertex planes, where a violation means strictly nearer.
fn edge_against_edge_region(x: &Side, ex: u32, y: &Side, ey: u32) -> Option<Feature> {
    let ed = &x.m.edges[ex as usize];
    let nb = x.m.edge_neighbours(ex);
    let (t, h) = (x.m.vert(ed.tail), x.m.vert(ed.head));
    let yd = &y.m.edges[ey as usize];
    let (a, b) = (x.import(y.m.vert(yd.tail)), x.import(y.m.vert(yd.head)));
    let d = b - a;
    let deriv = |l: f64| {
        let p = point_at(&a, &b, l);
        (p - point_at(t, h, point_segment_param(&p, t, h))).dot(&d)
    };
    let vplanes = [(ed.planes[0], nb[0]), (ed.planes[1], nb[1])];
    if let Some(f) = locate(&a, &b, 0.0, 1.0, vplanes.iter().copied(), deriv) {
        return Some(f);
    }
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for (pl, _) in vplanes {
        let (sa, sb) = (pl.eval(&a), pl.eval(&b));
        if sa < 0.0 && sb >= 0.0 {
            lo = lo.max(sa / (sa - sb));
        } else if sb < 0.0 && sa >= 0.0 {
            hi = hi.min(sa / (sa - sb));
        }
    }
    if lo > hi {
        // Only by rounding (the slab is not empty): take the crossing point.
        let m = 0.5 * (lo + hi);
        lo = m;
        hi = m;
    }
    let fplanes = [(ed.planes[2], nb[2]), (ed.planes[3], nb[3])];
    locate(&a, &b, lo, hi, fplanes.iter().copied(), deriv)
}

/// Closest points of two edges: parameters, in X's frame and Y's frame.
fn edge_edge_points(x: &Side, ex: u32, y: &Side, ey: u32) -> (Vec3, Vec3, f64) {
    let xd = &x.m.edges[ex as usize];
    let yd = &y.m.edges[ey as usize];
    let (tx, hx) = (x.m.vert(xd.tail), x.m.vert(xd.head));
    let (ty, hy) = (y.m.vert(yd.tail), y.m.vert(yd.head));
    let (a, b) = (x.import(ty), x.import(hy));
    let (s, t) = segment_segment_params(tx, hx, &a, &b);
    let px = point_at(tx, hx, s);
    let dist = (px - point_at(&a, &b, t)).norm();
    (px, point_at(ty, hy, t), dist)
}

/// Edge (X) - edge (Y).
fn ee(x: &Side, ex: u32, y: &Side, ey: u32) -> Step {
    if let Some(f) = edge_against_edge_region(x, ex, y, ey) {
        return Step::X(f);
    }
    if let Some(f) = edge_against_edge_region(y, ey, x, ex) {
        return Step::Y(f);
    }
    let (px, py, dist) = edge_edge_points(x, ex, y, ey);
    Step::Apart { px, py, dist }
}

/// The edge of face `f` nearest point `p` (all in the face's frame).
fn face_edge_nearest_point(m: &ConvexModel, f: u32, p: &Vec3) -> Feature {
    let mut best = (f64::INFINITY, m.face_edges(f as usize)[0]);
    for &e in m.face_edges(f as usize) {
        let ed = &m.edges[e as usize];
        let (t, h) = (m.vert(ed.tail), m.vert(ed.head));
        let d = (p - point_at(t, h, point_segment_param(p, t, h))).norm_squared();
        if d < best.0 {
            best = (d, e);
        }
    }
    Feature::edge(best.1)
}

/// The edge of face `f` nearest segment `[a, b]` (all in the face's frame).
fn face_edge_nearest_segment(m: &ConvexModel, f: u32, a: &Vec3, b: &Vec3) -> Feature {
    let mut best = (f64::INFINITY, m.face_edges(f as usize)[0]);
    for &e in m.face_edges(f as usize) {
        let ed = &m.edges[e as usize];
        let (t, h) = (m.vert(ed.tail), m.vert(ed.head));
        let (s, u) = segment_segment_params(a, b, t, h);
        let d = (point_at(a, b, s) - point_at(t, h, u)).norm_squared();
        if d < best.0 {
            best = (d, e);
        }
    }
    Feature::edge(best.1)
}

/// The feature of `m` nearest an outside point `p` (brute force: the local-minimum escape).
fn feature_nearest_point(m: &ConvexModel, p: &Vec3) -> Feature {
    let mut best = (f64::INFINITY, Feature::vertex(0));
    for (fi, f) in m.faces.iter().enumerate() {
        let d = f.plane.eval(p);
        if d > 0.0 && d < best.0 && m.face_side_planes(fi as u32).all(|(s, _)| s.eval(p) >= 0.0) {
            best = (d, Feature::face(fi as u32));
        }
    }
    for (ei, e) in m.edges.iter().enumerate() {
        let (t, h) = (m.vert(e.tail), m.vert(e.head));
        let l = point_segment_param(p, t, h);
        let d = (p - point_at(t, h, l)).norm();
        if d < best.0 {
            let f = if l <= 0.0 {
                Feature::vertex(e.tail)
            } else if l >= 1.0 {
                Feature::vertex(e.head)
            } else {
                Feature::edge(ei as u32)
            };
            best = (d, f);
        }
    }
    best.1
}

/// Vertex (X) - face (Y).
fn vf(x: &Side, vx: u32, y: &Side, fy: u32, ctr: &mut Counters) -> Step {
    let v = y.import(x.m.vert(vx));
    let plane = y.m.faces[fy as usize].plane;
    let mut violated = 0;
    let mut which = None;
    for (pl, f) in y.m.face_side_planes(fy) {
        if pl.eval(&v) < 0.0 {
            violated += 1;
            which = Some(f);
        }
    }
    if let Some(f) = which {
        // Outside the prism the face's closest point is on its boundary. Beyond exactly one side
        // plane it is on that edge; otherwise take the nearest edge.
        return Step::Y(if violated == 1 {
            f
        } else {
            face_edge_nearest_point(y.m, fy, &v)
        });
    }
    let d = plane.eval(&v);
    let px = *x.m.vert(vx);
    if d > 0.0 {
        // An edge of the vertex that descends towards the plane is strictly nearer the face.
        let mut best: Option<(f64, Feature)> = None;
        for (_, f, w) in x.m.vertex_planes(vx) {
            let pw = x.m.vert(w);
            let dw = plane.eval(&y.import(pw));
            if dw < d {
                let slope = (dw - d) / (pw - px).norm();
                if best.map_or(true, |(s, _)| slope < s) {
                    best = Some((slope, f));
                }
            }
        }
        if let Some((_, f)) = best {
            return Step::X(f);
        }
        return Step::Apart {
            px,
            py: v - plane.n * d,
            dist: d,
        };
    }
    if d == 0.0 {
        return Step::Contact { px, py: v };
    }
    // Under the plane, inside the prism: inside the polyhedron, or a local minimum of the search.
    ctr.local_minima += 1;
    if y.m.faces.iter().all(|f| f.plane.eval(&v) <= 0.0) {
        return Step::Contact { px, py: v };
    }
    Step::Y(feature_nearest_point(y.m, &v))
}

/// Edge (X) - face (Y). Never final: it ends in contact (the edge meets the face) or moves to a
/// lower-dimensional pair at the same distance.
fn ef(x: &Side, ex: u32, y: &Side, fy: u32) -> Step {
    let ed = &x.m.edges[ex as usize];
    let (a, b) = (y.import(x.m.vert(ed.tail)), y.import(x.m.vert(ed.head)));
    let plane = y.m.faces[fy as usize].plane;
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut excluded = false;
    for (pl, _) in y.m.face_side_planes(fy) {
        let (sa, sb) = (pl.eval(&a), pl.eval(&b));
        if sa < 0.0 && sb < 0.0 {
            excluded = true;
            break;
        }
        if sa < 0.0 {
            lo = lo.max(sa / (sa - sb));
        } else if sb < 0.0 {
            hi = hi.min(sa / (sa - sb));
        }
        if lo > hi {
            excluded = true;
            break;
        }
    }
    if excluded {
        // The edge misses the prism: the face's closest point to it is on the face's boundary.
        return Step::Y(face_edge_nearest_segment(y.m, fy, &a, &b));
    }
    let (dl, dh) = (
        plane.eval(&point_at(&a, &b, lo)),
        plane.eval(&point_at(&a, &b, hi)),
    );
    if dl == 0.0 || dh == 0.0 || (dl < 0.0) != (dh < 0.0) {
        let l = if dl == dh {
            lo
        } else {
            lo + (hi - lo) * (dl / (dl - dh))
        };
        let (tx, hx) = (x.m.vert(ed.tail), x.m.vert(ed.head));
        return Step::Contact {
            px: point_at(tx, hx, l),
            py: point_at(&a, &b, l),
        };
    }
    // The clipped part is on one side of the plane; its end nearest the plane, from the slope
    // computed on the endpoints exactly as the vertex-face handler computes it.
    let slope = plane.eval(&b) - plane.eval(&a);
    let above = dl > 0.0;
    let at_lo = if slope == 0.0 {
        !(lo > 0.0 && hi >= 1.0)
    } else {
        (slope > 0.0) == above
    };
    if at_lo && lo <= 0.0 {
        return Step::X(Feature::vertex(ed.tail));
    }
    if !at_lo && hi >= 1.0 {
        return Step::X(Feature::vertex(ed.head));
    }
    // The distance keeps decreasing out of the prism: the closest point is on the boundary.
    Step::Y(face_edge_nearest_segment(y.m, fy, &a, &b))
}

fn step(s: &[Side; 2], st: [Feature; 2], ctr: &mut Counters) -> Outcome {
    use FeatureKind::{Edge as E, Face as F, Vertex as V};
    let (i0, i1) = (st[0].index, st[1].index);
    let (r, swapped) = match (st[0].kind, st[1].kind) {
        (V, V) => (vv(&s[0], i0, &s[1], i1), false),
        (V, E) => (ve(&s[0], i0, &s[1], i1), false),
        (E, V) => (ve(&s[1], i1, &s[0], i0), true),
        (V, F) => (vf(&s[0], i0, &s[1], i1, ctr), false),
        (F, V) => (vf(&s[1], i1, &s[0], i0, ctr), true),
        (E, E) => (ee(&s[0], i0, &s[1], i1), false),
        (E, F) => (ef(&s[0], i0, &s[1], i1), false),
        (F, E) => (ef(&s[1], i1, &s[0], i0), true),
        // Never produced by the search; a face of model 1 is replaced by one of its edges.
        (F, F) => (
            Step::X(Feature::edge(s[0].m.face_edges(i0 as usize)[0])),
            false,
        ),
    };
    let (ix, iy) = if swapped { (1, 0) } else { (0, 1) };
    match r {
        Step::X(f) => Outcome::Update(ix, f),
        Step::Y(f) => Outcome::Update(iy, f),
        Step::Apart { px, py, dist } => {
            let mut p = [Vec3::zeros(); 2];
            p[ix] = px;
            p[iy] = py;
            Outcome::Apart(p, dist)
        }
        Step::Contact { px, py } => {
            let mut p = [Vec3::zeros(); 2];
            p[ix] = px;
            p[iy] = py;
            Outcome::Contact(p)
        }
    }
}

/// Closest points (each in its own frame) and distance of a pair that can be final.
fn pair_points(s: &[Side; 2], st: [Feature; 2]) -> Option<([Vec3; 2], f64)> {
    use FeatureKind::{Edge as E, Face as F, Vertex as V};
    let (i0, i1) = (st[0].index, st[1].index);
    let swap = |(a, b, d): (Vec3, Vec3, f64)| ([b, a], d);
    let keep = |(a, b, d): (Vec3, Vec3, f64)| ([a, b], d);
    let vertex_feature = |x: &Side, vx: u32, y: &Side, fy: Feature| -> (Vec3, Vec3, f64) {
        let px = *x.m.vert(vx);
        let p = y.import(&px);
        let q = match fy.kind {
            V => *y.m.vert(fy.index),
            E => {
                let ed = &y.m.edges[fy.index as usize];
                let (t, h) = (y.m.vert(ed.tail), y.m.vert(ed.head));
                point_at(t, h, point_segment_param(&p, t, h))
            }
            F => {
                let inside = y.m.face_side_planes(fy.index).all(|(pl, _)| pl.eval(&p) >= 0.0);
                if inside {
                    let pl = y.m.faces[fy.index as usize].plane;
                    p - pl.n * pl.eval(&p)
                } else {
                    let e = face_edge_nearest_point(y.m, fy.index, &p).index;
                    let ed = &y.m.edges[e as usize];
                    let (t, h) = (y.m.vert(ed.tail), y.m.vert(ed.head));
                    point_at(t, h, point_segment_param(&p, t, h))
                }
            }
        };
        (px, q, (p - q).norm())
    };
    match (st[0].kind, st[1].kind) {
        (V, _) => Some(keep(vertex_feature(&s[0], i0, &s[1], st[1]))),
        (_, V) => Some(swap(vertex_feature(&s[1], i1, &s[0], st[0]))),
        (E, E) => Some(keep(edge_edge_points(&s[0], i0, &s[1], i1))),
        _ => None,
    }
}

/// Number of features of a model.
fn feature_count(m: &ConvexModel) -> u64 {
    (m.num_vertices() + m.num_edges() + m.num_faces()) as u64
}

/// Runs V-Clip from `start` for model 2 posed in model 1's frame by `rel`.
pub(crate) fn vclip(
    m1: &ConvexModel,
    m2: &ConvexModel,
    rel: &RelPose,
    start: [Feature; 2],
) -> Result<VClipAnswer, Error> {
    let rt = rel.rot.transpose();
    let sides = [
        Side {
            m: m1,
            rot: rel.rot,
            trans: rel.trans,
        },
        Side {
            m: m2,
            rot: rt,
            trans: -(rt * rel.trans),
        },
    ];
    let bound = feature_count(m1)
        .saturating_mul(feature_count(m2))
        .saturating_mul(4)
        .saturating_add(64);
    let mut ctr = Counters::default();
    let mut state = start;
    // Brent's cycle detection: compare with a checkpoint moved at powers of two.
    let (mut checkpoint, mut power, mut lam) = (state, 1u64, 0u64);
    let mut steps: u64 = 0;
    loop {
        steps += 1;
        if steps > bound {
            return Err(Error::Internal);
        }
        ctr.iterations = ctr.iterations.saturating_add(1);
        match step(&sides, state, &mut ctr) {
            Outcome::Update(i, f) => state[i] = f,
            Outcome::Apart(points, distance) => {
                return Ok(VClipAnswer {
                    state,
                    intersecting: distance == 0.0,
                    distance,
                    points,
                    counters: ctr,
                })
            }
            Outcome::Contact(points) => {
                return Ok(VClipAnswer {
                    state,
                    intersecting: true,
                    distance: 0.0,
                    points,
                    counters: ctr,
                })
            }
        }
        if state == checkpoint {
            ctr.cycles += 1;
            return break_cycle(&sides, state, ctr);
        }
        lam += 1;
        if lam == power {
            checkpoint = state;
            power = power.saturating_mul(2);
            lam = 0;
        }
    }
}

/// A cycle (only possible through rounding at a near-tie): report its pair of least distance.
fn break_cycle(s: &[Side; 2], start: [Feature; 2], mut ctr: Counters) -> Result<VClipAnswer, Error> {
    let mut best: Option<([Feature; 2], [Vec3; 2], f64)> = None;
    let mut state = start;
    loop {
        if let Some((points, d)) = pair_points(s, state) {
            if best.as_ref().map_or(true, |b| d < b.2) {
                best = Some((state, points, d));
            }
        }
        match step(s, state, &mut ctr) {
            Outcome::Update(i, f) => state[i] = f,
            _ => return Err(Error::Internal),
        }
        if state == start {
            break;
        }
    }
    let (state, points, distance) = best.ok_or(Error::Internal)?;
    Ok(VClipAnswer {
        state,
        intersecting: distance == 0.0,
        distance,
        points,
        counters: ctr,
    })
}
