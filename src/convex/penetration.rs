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
//! facet by rounding. Only edge pairs whose arcs' bounding boxes share a cell of a grid over the
//! sphere are tested. Cost: `O(F1 V2 + F2 V1)` at worst for the faces (hill climbs are short in
//! practice); for the edges, `O(E1 E2)` arc tests at worst, near-linear for large hulls whose arcs
//! are short.

use super::model::ConvexModel;
use crate::math::{RelPose, Vec3};

/// The penetration depth and direction, in model 1's frame: translating model 2 by
/// `depth * normal` makes the models touch.
pub(crate) struct Depth {
    pub depth: f64,
    pub normal: Vec3,
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

/// An edge seen on the Gauss map: the arc of normals from `n1` to `n2` (its faces' normals, both
/// orthogonal to the edge's direction `u`), with a box around the arc.
struct Arc {
    u: Vec3,
    n1: Vec3,
    n2: Vec3,
    mid: Vec3,
    tail: u32,
    lo: Vec3,
    hi: Vec3,
}

impl Arc {
    fn new(tail: u32, t: Vec3, h: Vec3, n1: Vec3, n2: Vec3) -> Arc {
        // The arc lies in the triangle of its ends and of the crossing of its end tangents,
        // (n1 + n2) / (1 + n1.n2); for arcs near a half circle that point runs off, and the arc is
        // only known to be in the cube around the sphere.
        let c = n1.dot(&n2);
        let slack = Vec3::repeat(4.0 * ARC_SLACK);
        let (lo, hi) = if c > -0.5 {
            let apex = (n1 + n2) / (1.0 + c);
            (
                n1.inf(&n2).inf(&apex) - slack,
                n1.sup(&n2).sup(&apex) + slack,
            )
        } else {
            (Vec3::repeat(-2.0), Vec3::repeat(2.0))
        };
        Arc {
            u: super::model::unit(&(h - t)),
            n1,
            n2,
            mid: n1 + n2,
            tail,
            lo,
            hi,
        }
    }
}

/// Arcs binned in a uniform grid of `m^3` cells over `[-1, 1]^3` (sorted `(cell, arc)` pairs).
struct SphereGrid {
    m: usize,
    entries: Vec<(u32, u32)>,
}

impl SphereGrid {
    fn cell_range(&self, lo: f64, hi: f64) -> (usize, usize) {
        let f =
            |x: f64| (((x + 1.0) * 0.5 * self.m as f64).floor().max(0.0) as usize).min(self.m - 1);
        (f(lo), f(hi))
    }

    fn new(arcs: &[Arc]) -> SphereGrid {
        let m = (((arcs.len() as f64).sqrt() * 0.5).ceil() as usize).clamp(1, 64);
        let mut g = SphereGrid {
            m,
            entries: Vec::new(),
        };
        for (i, q) in arcs.iter().enumerate() {
            let mut cells = Vec::new();
            g.cells_of(q, |c| cells.push(c));
            g.entries.extend(cells.into_iter().map(|c| (c, i as u32)));
        }
        g.entries.sort_unstable();
        g
    }

    fn cells_of(&self, q: &Arc, mut f: impl FnMut(u32)) {
        let (x0, x1) = self.cell_range(q.lo.x, q.hi.x);
        let (y0, y1) = self.cell_range(q.lo.y, q.hi.y);
        let (z0, z1) = self.cell_range(q.lo.z, q.hi.z);
        for x in x0..=x1 {
            for y in y0..=y1 {
                for z in z0..=z1 {
                    f(((x * self.m + y) * self.m + z) as u32);
                }
            }
        }
    }

    /// Calls `f` with every arc sharing a cell with `q` (possibly more than once).
    fn for_each_near(&self, q: &Arc, mut f: impl FnMut(usize)) {
        self.cells_of(q, |c| {
            let start = self.entries.partition_point(|e| e.0 < c);
            for e in &self.entries[start..] {
                if e.0 != c {
                    break;
                }
                f(e.1 as usize);
            }
        });
    }
}

/// Penetration depth of model 2 (posed by `rel` in model 1's frame) into model 1. A result with
/// `depth <= 0` means the models do not overlap (some candidate direction separates them).
pub(crate) fn penetration_depth(a: &ConvexModel, b: &ConvexModel, rel: &RelPose) -> Depth {
    let va = a.vertices();
    let vb: Vec<Vec3> = b.vertices().iter().map(|v| rel.apply(v)).collect();
    let mut best = Depth {
        depth: f64::INFINITY,
        normal: Vec3::z(),
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
            best = Depth {
                depth: h,
                normal: n,
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
            best = Depth {
                depth: h,
                normal: -m,
            };
        }
    }
    // Edge pairs whose Gauss arcs cross: A's arcs between its faces' normals, (-B)'s between
    // the negated normals of B's faces. The arcs of B are binned in a grid over the sphere's
    // bounding cube, so that only arcs sharing a cell are tested (on large hulls arcs are short
    // and this is near-linear; on small ones it is the plain double loop).
    let arcs_a: Vec<Arc> = (0..a.num_edges())
        .map(|e| {
            let (t, h) = a.edge(e);
            let (l, r) = a.edge_faces(e);
            Arc::new(
                t,
                va[t as usize],
                va[h as usize],
                a.face_plane(l as usize).0,
                a.face_plane(r as usize).0,
            )
        })
        .collect();
    let arcs_b: Vec<Arc> = (0..b.num_edges())
        .map(|e| {
            let (t, h) = b.edge(e);
            let (l, r) = b.edge_faces(e);
            Arc::new(
                t,
                vb[t as usize],
                vb[h as usize],
                -(rel.rot * b.face_plane(l as usize).0),
                -(rel.rot * b.face_plane(r as usize).0),
            )
        })
        .collect();
    let grid = SphereGrid::new(&arcs_b);
    let mut seen = vec![u32::MAX; arcs_b.len()];
    for (ia, qa) in arcs_a.iter().enumerate() {
        grid.for_each_near(qa, |ib| {
            if seen[ib] == ia as u32 {
                return;
            }
            seen[ib] = ia as u32;
            let qb = &arcs_b[ib];
            let c = qa.u.cross(&qb.u);
            let cn = c.norm();
            if cn < 1e-12 {
                return; // parallel edges span no facet of their own
            }
            let mut n = c / cn;
            if n.dot(&qa.mid) < 0.0 {
                n = -n;
            }
            if !on_arc(&n, &qa.n1, &qa.n2, &qa.u) || !on_arc(&n, &qb.n1, &qb.n2, &qb.u) {
                return;
            }
            let (_, ha) = climb(a, va, &n, qa.tail);
            let (_, hb) = climb(b, &vb, &-n, qb.tail);
            let depth = ha + hb;
            if depth < best.depth {
                best = Depth { depth, normal: n };
            }
        });
    }
    best
}
