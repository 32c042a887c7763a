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
//! Features nearer than a contact distance (64 ulps of the scene's size, about the rounding of
//! posing a vertex) count as touching; a touching or overlapping pair ends the search with a
//! common point.
//!
//! # Termination
//!
//! Let `delta(X, Y)` be the Euclidean distance between the point sets of the two features and
//! `dim` the sum of their dimensions (vertex 0, edge 1, face 2). Every update strictly decreases the
//! pair `(delta, dim)` in lexicographic order:
//!
//! * moving to a neighbour of higher dimension (vertex -> edge, edge -> face) happens only when the
//!   other feature's closest point lies strictly beyond the Voronoi plane shared with that
//!   neighbour, which makes the neighbour strictly closer: `delta` decreases (edges test their
//!   vertex planes first, so a face plane is only ever tried for a closest point between them);
//! * moving to a lower dimension keeps `delta` and lowers `dim`: edge -> vertex when the closest
//!   point is beyond the vertex's plane; face -> edge when the face's closest point to the other
//!   feature is on the face's boundary (the other feature is outside the face's prism, or the
//!   distance keeps decreasing out of it), the edge being the nearest among those whose side plane
//!   the other feature's nearest point violates, which contain that closest point;
//! * the one non-local move, from a *local minimum* (a vertex under a face's plane but inside its
//!   prism), goes to the feature of the face's polyhedron nearest the vertex, or reports
//!   penetration when the vertex is inside: the face lies on the polyhedron, so that feature is
//!   strictly nearer than the face's plane is (equal only for a flat polyhedron, never built), and
//!   `delta` decreases;
//! * contact (a vertex inside, an edge through a face, features within the contact distance) ends
//!   the search, and so does a final pair.
//!
//! So no state repeats and the search ends within `(V1+E1+F1)(V2+E2+F2)` updates.
//!
//! In floating point a near-tie can be decided inconsistently by two states (we saw it only around
//! sliver faces a few ulps wide). The decisions that must agree are computed identically (a face's
//! side plane is its edge's plane negated bit for bit, a vertex's edge planes are the edges' vertex
//! planes negated, edge-face slopes use the same endpoint values as vertex-face descents), which
//! removes most of them. The transition function is deterministic on a finite set, so any
//! remaining cycle is caught by Brent's cycle detection, and the answer then comes from an
//! exhaustive scan of all feature pairs, which takes no Voronoi decision. A hard bound of
//! `4 (V1+E1+F1)(V2+E2+F2) + 64` iterations, beyond what either argument allows, turns any
//! remaining surprise into `Error::Internal` instead of a loop.

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
    /// Contact distance: features nearer than this (a few ulps of the scene's size, the rounding
    /// of the pose alone) touch.
    touch: f64,
}

impl<'a> Side<'a> {
    /// The two sides of a query of model 2 posed in model 1's frame by `rel`: each side maps the
    /// other model's points into its own frame.
    fn pair(m1: &'a ConvexModel, m2: &'a ConvexModel, rel: &RelPose) -> [Side<'a>; 2] {
        let rt = rel.rot.transpose();
        let touch = TOUCH_ULPS * f64::EPSILON * (m1.radius() + m2.radius() + rel.trans.norm());
        [
            Side {
                m: m1,
                rot: rel.rot,
                trans: rel.trans,
                touch,
            },
            Side {
                m: m2,
                rot: rt,
                trans: -(rt * rel.trans),
                touch,
            },
        ]
    }

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
    if (py_x - px).norm() <= x.touch {
        return Step::Contact {
            px,
            py: *y.m.vert(vy),
        };
    }
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
    let (ty, hy) = (y.m.vert(ed.tail), y.m.vert(ed.head));
    let py = point_at(ty, hy, point_segment_param(&v_y, ty, hy));
    if (v_y - py).norm() <= y.touch {
        return Step::Contact {
            px: *x.m.vert(vx),
            py,
        };
    }
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
    let (a, b) = (x.import(ty), x.import(hy));
    let d = b - a;
    if let Some(f) = locate(&a, &b, 0.0, 1.0, vertex_planes(x.m, vx), |l| {
        (point_at(&a, &b, l) - v).dot(&d)
    }) {
        return Step::X(f);
    }
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
    let (px, py, dist) = edge_edge_points(x, ex, y, ey);
    if dist <= x.touch {
        return Step::Contact { px, py };
    }
    if let Some(f) = edge_against_edge_region(x, ex, y, ey) {
        return Step::X(f);
    }
    if let Some(f) = edge_against_edge_region(y, ey, x, ex) {
        return Step::Y(f);
    }
    Step::Apart { px, py, dist }
}

/// The edge of face `f` nearest a point or segment outside the face's prism. `near(t, h)` gives,
/// for an edge `[t, h]`, the squared distance to it and the point of the query nearest it.
///
/// The face's closest point lies on an edge whose side plane is violated by the query's point
/// nearest that edge (the offset between the two closest points is in the face's normal cone
/// there, and not along the face's normal since the query is outside the prism). Only such edges
/// compete: comparing distances alone would let rounding ties between the nearly coincident edges
/// of a sliver face undo the move that led to the face. All edges compete if none qualifies (by
/// rounding).
fn face_edge_nearest(
    m: &ConvexModel,
    f: u32,
    near: impl Fn(&Vec3, &Vec3) -> (f64, Vec3),
) -> Feature {
    let mut best: Option<(f64, Feature)> = None;
    let mut any: Option<(f64, Feature)> = None;
    for (pl, e) in m.face_side_planes(f) {
        let ed = &m.edges[e.index as usize];
        let (d, q) = near(m.vert(ed.tail), m.vert(ed.head));
        if any.is_none_or(|(bd, _)| d < bd) {
            any = Some((d, e));
        }
        if pl.eval(&q) < 0.0 && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, e));
        }
    }
    best.or(any)
        .map_or(Feature::edge(m.face_edges(f as usize)[0]), |b| b.1)
}

/// The edge of face `f` nearest point `p` (in the face's frame); see `face_edge_nearest`.
fn face_edge_nearest_point(m: &ConvexModel, f: u32, p: &Vec3) -> Feature {
    face_edge_nearest(m, f, |t, h| {
        let d = (p - point_at(t, h, point_segment_param(p, t, h))).norm_squared();
        (d, *p)
    })
}

/// The edge of face `f` nearest segment `[a, b]` (in the face's frame); see `face_edge_nearest`.
fn face_edge_nearest_segment(m: &ConvexModel, f: u32, a: &Vec3, b: &Vec3) -> Feature {
    face_edge_nearest(m, f, |t, h| {
        let (s, u) = segment_segment_params(a, b, t, h);
        let q = point_at(a, b, s);
        ((q - point_at(t, h, u)).norm_squared(), q)
    })
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
    if d.abs() <= y.touch {
        return Step::Contact {
            px,
            py: v - plane.n * d,
        };
    }
    if d > 0.0 {
        // An edge of the vertex that descends towards the plane is strictly nearer the face.
        let mut best: Option<(f64, Feature)> = None;
        for (_, f, w) in x.m.vertex_planes(vx) {
            let pw = x.m.vert(w);
            let dw = plane.eval(&y.import(pw));
            if dw < d {
                let slope = (dw - d) / (pw - px).norm();
                if best.is_none_or(|(s, _)| slope < s) {
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
    let touch = y.touch;
    if dl.abs() <= touch || dh.abs() <= touch || (dl < 0.0) != (dh < 0.0) {
        let l = if dl.abs() <= touch {
            lo
        } else if dh.abs() <= touch {
            hi
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

/// Contact distance in units of `f64::EPSILON` times the scene's size (the models' radii about
/// their origins plus the distance between the origins): about the rounding of posing a vertex.
const TOUCH_ULPS: f64 = 64.0;

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
    let sides = Side::pair(m1, m2, rel);
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
                });
            }
            Outcome::Contact(points) => {
                return Ok(VClipAnswer {
                    state,
                    intersecting: true,
                    distance: 0.0,
                    points,
                    counters: ctr,
                });
            }
        }
        if state == checkpoint {
            return Ok(break_cycle(&sides, ctr));
        }
        lam += 1;
        if lam == power {
            checkpoint = state;
            power = power.saturating_mul(2);
            lam = 0;
        }
    }
}

/// A cycle (only possible through rounding at a near-tie, in practice around sliver faces): the
/// search cannot be trusted to continue, so the answer comes from a scan of all feature pairs,
/// `O(V1 F2 + V2 F1 + E1 E2)`, which needs no Voronoi decision.
fn break_cycle(s: &[Side; 2], mut ctr: Counters) -> VClipAnswer {
    ctr.cycles += 1;
    let (state, contact, points, distance) = exhaustive(s);
    VClipAnswer {
        state,
        intersecting: contact,
        distance,
        points,
        counters: ctr,
    }
}

/// Orders a pair found with model `x` first back into (model 1, model 2).
fn ordered<T>(x: usize, a: T, b: T) -> [T; 2] {
    if x == 0 { [a, b] } else { [b, a] }
}

/// Exhaustive closest pair: contact if a vertex of one model is inside the other or an edge of
/// one crosses a face of the other; otherwise the least distance over vertex-face pairs (vertex in
/// the face's prism) and edge-edge pairs (whose endpoints cover the vertex-edge and vertex-vertex
/// pairs). Returns the feature pair, the contact verdict, the points, and the distance.
fn exhaustive(s: &[Side; 2]) -> ([Feature; 2], bool, [Vec3; 2], f64) {
    let touch = s[0].touch;
    for x in 0..2 {
        let (sx, sy) = (&s[x], &s[1 - x]);
        for (vi, v) in sx.m.vertices().iter().enumerate() {
            let p = sy.import(v);
            let mut deepest = (f64::NEG_INFINITY, 0u32);
            for (fi, f) in sy.m.faces.iter().enumerate() {
                let d = f.plane.eval(&p);
                if d > deepest.0 {
                    deepest = (d, fi as u32);
                }
            }
            if deepest.0 <= touch {
                let st = ordered(x, Feature::vertex(vi as u32), Feature::face(deepest.1));
                return (st, true, ordered(x, *v, p), 0.0);
            }
        }
        for (ei, e) in sx.m.edges.iter().enumerate() {
            let (tx, hx) = (sx.m.vert(e.tail), sx.m.vert(e.head));
            let (a, b) = (sy.import(tx), sy.import(hx));
            for (fi, f) in sy.m.faces.iter().enumerate() {
                let (da, db) = (f.plane.eval(&a), f.plane.eval(&b));
                if (da > touch && db > touch) || (da < -touch && db < -touch) {
                    continue;
                }
                let l = if da == db {
                    0.0
                } else {
                    (da / (da - db)).clamp(0.0, 1.0)
                };
                let q = point_at(&a, &b, l);
                if sy
                    .m
                    .face_side_planes(fi as u32)
                    .all(|(pl, _)| pl.eval(&q) >= -touch)
                {
                    let st = ordered(x, Feature::edge(ei as u32), Feature::face(fi as u32));
                    return (st, true, ordered(x, point_at(tx, hx, l), q), 0.0);
                }
            }
        }
    }
    // Apart: the least distance.
    let mut best = (f64::INFINITY, [Feature::vertex(0); 2], [Vec3::zeros(); 2]);
    for x in 0..2 {
        let (sx, sy) = (&s[x], &s[1 - x]);
        for (vi, v) in sx.m.vertices().iter().enumerate() {
            let p = sy.import(v);
            for (fi, f) in sy.m.faces.iter().enumerate() {
                let d = f.plane.eval(&p);
                if d >= 0.0
                    && d < best.0
                    && sy
                        .m
                        .face_side_planes(fi as u32)
                        .all(|(pl, _)| pl.eval(&p) >= 0.0)
                {
                    let st = ordered(x, Feature::vertex(vi as u32), Feature::face(fi as u32));
                    best = (d, st, ordered(x, *v, p - f.plane.n * d));
                }
            }
        }
    }
    let feature = |m: &ConvexModel, e: u32, l: f64| {
        let ed = &m.edges[e as usize];
        if l <= 0.0 {
            Feature::vertex(ed.tail)
        } else if l >= 1.0 {
            Feature::vertex(ed.head)
        } else {
            Feature::edge(e)
        }
    };
    for (e0, d0) in s[0].m.edges.iter().enumerate() {
        let (t0, h0) = (s[0].m.vert(d0.tail), s[0].m.vert(d0.head));
        for (e1, d1) in s[1].m.edges.iter().enumerate() {
            let (t1, h1) = (s[1].m.vert(d1.tail), s[1].m.vert(d1.head));
            let (a, b) = (s[0].import(t1), s[0].import(h1));
            let (u, w) = segment_segment_params(t0, h0, &a, &b);
            let (p, q) = (point_at(t0, h0, u), point_at(&a, &b, w));
            let d = (p - q).norm();
            if d < best.0 {
                let st = [feature(s[0].m, e0 as u32, u), feature(s[1].m, e1 as u32, w)];
                best = (d, st, [p, point_at(t1, h1, w)]);
            }
        }
    }
    (
        best.1,
        best.0 <= touch,
        best.2,
        if best.0 <= touch { 0.0 } else { best.0 },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pose;
    use crate::test_rng::Lcg;

    /// The exhaustive fallback agrees with the search on random pairs.
    #[test]
    fn exhaustive_scan_agrees_with_search() {
        let mut rng = Lcg(7);
        let mut rnd = move || rng.signed();
        let mut hull = |n: usize| {
            let pts: Vec<[f64; 3]> = (0..n).map(|_| [rnd(), rnd(), rnd()]).collect();
            ConvexModel::from_points(&pts).unwrap()
        };
        let models: Vec<ConvexModel> = (0..8).map(|k| hull(5 + 3 * k)).collect();
        let mut contacts = 0;
        for k in 0..200 {
            let (m1, m2) = (&models[k % 8], &models[(k / 8) % 8]);
            let t = [0.9 * (k as f64).sin(), 1.7 * (k as f64 * 0.37).cos(), 0.4];
            let p2 = Pose::new([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], t);
            let rel = RelPose::between(&Pose::identity(), &p2);
            let sides = Side::pair(m1, m2, &rel);
            let ans = vclip(m1, m2, &rel, [Feature::vertex(0); 2]).unwrap();
            let (_, contact, points, d) = exhaustive(&sides);
            assert_eq!(contact, ans.intersecting, "pair {k}");
            assert!(
                (d - ans.distance).abs() < 1e-12,
                "pair {k}: {d} vs {}",
                ans.distance
            );
            if !contact {
                let q = rel.apply(&points[1]);
                assert!(((points[0] - q).norm() - d).abs() < 1e-12);
            }
            contacts += contact as usize;
        }
        assert!(contacts > 20 && contacts < 180, "{contacts}");
    }
}
