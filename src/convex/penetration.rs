//! Penetration depth: the length of the smallest translation of model 2 that separates the models.
//!
//! With `P = A - B` (the Minkowski difference, model 2 posed in model 1's frame), the models
//! overlap when the origin is in `P`, and the smallest separating translation of B is the distance
//! from the origin to the boundary of `P`, along the normal of the nearest facet of `P`. That
//! distance is `min_n h_P(n)` over unit `n`, where `h_P(n) = max_a n.a - min_b n.b` is the support
//! function; the minimum is attained at a facet normal of `P`, and every facet normal of `P` is a
//! face normal of A, a negated face normal of B, or the cross product of an edge of A and an edge
//! of B whose arcs on the Gauss map cross.
//!
//! So the depth is computed exactly (up to the rounding of the final dot products) by evaluating
//! `h_P` on those candidates. Supports are found by hill climbing over the vertex graph (a local
//! maximum of a linear function on a convex polytope is global), started where the candidate says
//! the support is, so that true facets cost one neighbour scan. The Gauss-map test is relaxed by a
//! small angular slack: extra candidates cannot lower the minimum (`h_P(n)` is at least the depth
//! for every `n`, and it is evaluated with true supports), while a strict test could drop a true
//! facet by rounding. Cost: `O(F1 V2 + F2 V1)` at worst for the faces, `O(E1 E2)` arc tests.

use super::closest::{point_at, segment_segment_params};
use super::model::ConvexModel;
use crate::math::{RelPose, Vec3};

/// The deepest direction and witnesses, all in model 1's frame: translating model 2 by
/// `depth * normal` makes the models touch, `pa` on model 1 and `pb` on model 2 with
/// `pa = pb + depth * normal`.
pub(crate) struct Depth {
    pub depth: f64,
    pub normal: Vec3,
    pub pa: Vec3,
    pub pb: Vec3,
}

/// The vertex of `m` (positions `pts`, indexed like `m`'s vertices) maximising `dir . p`, by hill
/// climbing from `start`.
fn climb(m: &ConvexModel, pts: &[Vec3], dir: &Vec3, start: u32) -> (u32, f64) {
    let mut i = start;
    let mut best = dir.dot(&pts[i as usize]);
    loop {
        let mut moved = false;
        for &w in m.vertex_neighbours(i) {
            let v = dir.dot(&pts[w as usize]);
            if v > best {
                best = v;
                i = w;
                moved = true;
            }
        }
        if !moved {
            return (i, best);
        }
    }
}

/// Angular slack of the Gauss-map arc test (radians, as a sine).
const ARC_SLACK: f64 = 1e-9;

/// Whether unit `n` (orthogonal to `axis`) lies on the shorter great arc from `n1` to `n2` (both
/// orthogonal to `axis`), with slack.
fn on_arc(n: &Vec3, n1: &Vec3, n2: &Vec3, axis: &Vec3) -> bool {
    let t0 = n1.cross(n2).dot(axis);
    if t0.abs() < ARC_SLACK {
        return true;
    }
    let s = t0.signum();
    n1.cross(n).dot(axis) * s >= -ARC_SLACK && n.cross(n2).dot(axis) * s >= -ARC_SLACK
}

/// Penetration depth of model 2 (posed by `rel` in model 1's frame) into model 1. A result with
/// `depth <= 0` means the models do not overlap (some candidate direction separates them).
pub(crate) fn penetration_depth(a: &ConvexModel, b: &ConvexModel, rel: &RelPose) -> Depth {
    let va = a.vertices();
    let vb: Vec<Vec3> = b.vertices().iter().map(|v| rel.apply(v)).collect();
    let mut best = Depth {
        depth: f64::INFINITY,
        normal: Vec3::z(),
        pa: Vec3::zeros(),
        pb: Vec3::zeros(),
    };
    let mut hint_b = 0u32;
    let mut hint_a = 0u32;
    // Face normals of A: B's deepest vertex against the face.
    for f in 0..a.num_faces() {
        let (n, _) = a.face_plane(f);
        let (_, ha) = climb(a, va, &n, a.face(f)[0]);
        let (ib, hb) = climb(b, &vb, &-n, hint_b);
        hint_b = ib;
        let h = ha + hb;
        if h < best.depth {
            let pb = vb[ib as usize];
            best = Depth {
                depth: h,
                normal: n,
                pa: pb + n * h,
                pb,
            };
        }
    }
    // Face normals of B, negated: A's deepest vertex against the face.
    for g in 0..b.num_faces() {
        let m = rel.rot * b.face_plane(g).0;
        let (ia, ha) = climb(a, va, &-m, hint_a);
        hint_a = ia;
        let (_, hb) = climb(b, &vb, &m, b.face(g)[0]);
        let h = ha + hb;
        if h < best.depth {
            let pa = va[ia as usize];
            best = Depth {
                depth: h,
                normal: -m,
                pa,
                pb: pa + m * h,
            };
        }
    }
    // Edge pairs whose Gauss arcs cross: A's arc from its faces' normals, (-B)'s from the negated
    // normals of B's faces.
    struct EdgeB {
        dir: Vec3,
        m1: Vec3,
        m2: Vec3,
        tail: u32,
        t: Vec3,
        h: Vec3,
    }
    let eb: Vec<EdgeB> = (0..b.num_edges())
        .map(|e| {
            let (t, h) = b.edge(e);
            let (l, r) = b.edge_faces(e);
            let (pt, ph) = (vb[t as usize], vb[h as usize]);
            EdgeB {
                dir: (ph - pt).normalize(),
                m1: -(rel.rot * b.face_plane(l as usize).0),
                m2: -(rel.rot * b.face_plane(r as usize).0),
                tail: t,
                t: pt,
                h: ph,
            }
        })
        .collect();
    for e in 0..a.num_edges() {
        let (t, h) = a.edge(e);
        let (l, r) = a.edge_faces(e);
        let (pt, ph) = (va[t as usize], va[h as usize]);
        let u = (ph - pt).normalize();
        let (n1, n2) = (a.face_plane(l as usize).0, a.face_plane(r as usize).0);
        let mid = n1 + n2;
        for q in &eb {
            let c = u.cross(&q.dir);
            let cn = c.norm();
            if cn < 1e-12 {
                continue; // parallel edges span no facet of their own
            }
            let mut n = c / cn;
            if n.dot(&mid) < 0.0 {
                n = -n;
            }
            if !on_arc(&n, &n1, &n2, &u) || !on_arc(&n, &q.m1, &q.m2, &q.dir) {
                continue;
            }
            let (_, ha) = climb(a, va, &n, t);
            let (_, hb) = climb(b, &vb, &-n, q.tail);
            let depth = ha + hb;
            if depth < best.depth {
                let (s, w) = segment_segment_params(&pt, &ph, &q.t, &q.h);
                let pa = point_at(&pt, &ph, s);
                let pb = point_at(&q.t, &q.h, w);
                // Re-centre the witnesses on the exact depth along n.
                let mid_point = (pa + pb) * 0.5;
                best = Depth {
                    depth,
                    normal: n,
                    pa: mid_point + n * (0.5 * depth),
                    pb: mid_point - n * (0.5 * depth),
                };
            }
        }
    }
    best
}
