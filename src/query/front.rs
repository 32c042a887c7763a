//! The BVTT front a distance result keeps for the next query (generalized front tracking).
//!
//! A search of the bounding volume test tree (BVTT) expands some of its nodes and leaves the rest
//! behind: pruned, tested as triangle pairs, or unvisited when it stops. The nodes left behind form
//! a cut of the BVTT (every triangle pair lies below one of them): the *front*. Under coherent
//! motion the next query starts from the front rather than from the root, and so skips the nodes
//! above it, which it would expand again anyway.
//!
//! Each front node keeps the lower bound it had (on the distance between the triangles below it).
//! When model 2 moves relative to model 1, a point `p` of it moves by `ΔR p + Δt`: the points of a
//! node within `e` of a point `o` move by at most `|ΔR o + Δt| + ‖ΔR‖ e` ([`Motion`]), so no
//! distance below the node shrinks by more than that. The old bound less that is still a lower
//! bound, and a node it keeps beyond the search's cutoff is pruned without a test.
//!
//! Most front nodes also keep a separating axis: a unit direction `n` along which the node's
//! model 1 volume and model 2 volume were at least the bound apart (the vector between closest
//! points, or the gap between the boxes that pruned the pair). Their gap along `n` shrinks only by
//! how far model 2's points move against `n`, at most `-n . (ΔR o + Δt) + |ΔR^T n| e`: under a
//! tumbling motion, mostly across `n`, far less than the whole displacement. On the tumbling tori
//! of BENCHMARKS.md this settles most of the front pairs the displacement bound leaves to a test.
//!
//! The front is used only on the same two models, with the triangle cache on, for a
//! priority-directed search, and when the relative pose moved little since the query that left it
//! (else a front that is fine where the models were close would cost more than it saves); it is
//! dropped once it has grown past [`Front::GROWTH`] times its size after the last search from the
//! root (the models moved on, leaving fine nodes where nothing is near). It is recorded only when
//! the last query on the same models was that near, so that queries at unrelated poses do not pay
//! for one: a coherent motion records from its second query and uses a front from its third.

use super::strategy::{Search, Strategy};
use super::traversal::NodePair;
use crate::bvh::{Bvh, NodeRef};
use crate::math::{Mat3, RelPose, UNDERFLOW_SLACK, Vec3};
use crate::model::Model;

/// How far the points of model 2 may have moved, in model 1's frame, since the front's bounds were
/// computed: a point `p` moves by `ΔR p + Δt`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Motion {
    dr: Mat3,
    dt: Vec3,
    /// At least the spectral norm of `ΔR`.
    dr_norm: f64,
    /// The bound for every point of model 2.
    whole: f64,
    /// The magnitude the rounding of the motion is relative to: the translations, and how far the
    /// models' points reach (an axis's rounding moves their projections by that much times it).
    slack_scale: f64,
}

/// A node of a front, with a separating axis when one is known (see the module docs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FrontPair {
    /// The node and its bound.
    pub pair: NodePair,
    /// A unit axis (in model 1's frame, from model 1's volume towards model 2's) along which the
    /// node's volumes were at least `pair.bound` apart; zero when none is known.
    pub axis: Vec3,
}

impl Motion {
    /// How far any point within `e` of `o` (model 2's frame) may have moved: at most
    /// `|ΔR o + Δt| + ‖ΔR‖ e`, rounded up generously.
    #[inline]
    fn bound(&self, o: &Vec3, e: f64) -> f64 {
        let m = (self.dr * o + self.dt).norm() + self.dr_norm * e;
        m * (1.0 + 1e-9)
            + 256.0 * f64::EPSILON * (o.norm() + e + self.slack_scale)
            + UNDERFLOW_SLACK
    }

    /// How much a front node's bound `bound` on the distance below model 2's node `b` may have
    /// shrunk: along the unit `axis` when it is not zero (see the module docs), else, or if that
    /// is less, the most its points may have moved.
    #[inline]
    pub fn of_node(&self, b2: &Bvh, b: NodeRef, bound: f64, axis: &Vec3) -> f64 {
        let (o, e) = b2.anchor(b);
        let moved = self.bound(&o, e).min(self.whole);
        if *axis != Vec3::zeros() {
            self.along(axis, bound, &o, e).min(moved)
        } else {
            moved
        }
    }

    /// How far any point within `e` of `o` (model 2's frame) may have moved against the unit
    /// vector `n` (model 1's frame): at most `-n . (ΔR o + Δt) + |ΔR^T n| e`, rounded up generously.
    ///
    /// The rounding of `n` is included. Its length and direction are those of a computed vector:
    /// between the closest points of a pair `bound` apart, or the gap between two boxes, each a few
    /// roundings of coordinates within the models' reach `S` off. Turned by up to about `eps S /
    /// bound`, it shows a separation less by that times the volumes' extent (`<= 2 S`): hence the
    /// `eps S^2 / bound` term, negligible unless the pair nearly touches.
    #[inline]
    fn along(&self, n: &Vec3, bound: f64, o: &Vec3, e: f64) -> f64 {
        let d = self.dr * o + self.dt;
        let m = -n.dot(&d) + self.dr.tr_mul(n).norm() * e;
        let size = d.abs().sum() + self.dr_norm * e;
        let s = self.slack_scale;
        m + 1e-9 * size
            + 256.0 * f64::EPSILON * (o.norm() + e + s)
            + 4096.0 * f64::EPSILON * s * s / bound
            + UNDERFLOW_SLACK
    }

    /// How far any point of model 2 may have moved.
    #[inline]
    pub fn whole(&self) -> f64 {
        self.whole
    }
}

/// An upper bound on the spectral norm of `m`: the least of its Frobenius norm and the square root
/// of the largest absolute row sum of `m^T m` (which bounds that matrix's largest eigenvalue),
/// rounded up. For a small rotation's change the second is within 16% of the spectral norm, the
/// first within 41%.
fn spectral_bound(m: &Mat3) -> f64 {
    let g = m.tr_mul(m);
    let rows = (0..3).map(|i| g[(i, 0)].abs() + g[(i, 1)].abs() + g[(i, 2)].abs());
    let gershgorin = rows.fold(0.0, f64::max);
    gershgorin.sqrt().min(m.norm()) * (1.0 + 1e-12)
}

/// What a distance result keeps of its last query's search, for the next (see the module docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct Front {
    uid1: u64,
    uid2: u64,
    /// The relative pose at which the front's bounds hold; `None`: no front.
    rel: Option<RelPose>,
    /// The models and relative pose of the last query, front or not: a front is recorded only
    /// when the next query comes near it (coherent motion), so that queries at unrelated poses
    /// do not pay for one.
    last: Option<(u64, u64, RelPose)>,
    /// The front nodes, each with a lower bound on the distance of the triangles below it.
    nodes: Vec<FrontPair>,
    /// Storage for the next front (no allocation per query once warm).
    spare: Vec<FrontPair>,
    /// The front's size after the last search from the root.
    base: usize,
}

/// The query a front is asked about: the two models with their hierarchies, the relative pose of
/// model 2 in model 1's frame, and how the query searches.
#[derive(Clone, Copy)]
pub(crate) struct FrontQuery<'a> {
    pub m1: &'a Model,
    pub m2: &'a Model,
    pub b1: &'a Bvh,
    pub b2: &'a Bvh,
    pub rel: &'a RelPose,
    pub search: &'a Search,
}

impl Front {
    /// A front of more than this many times its size after the last search from the root is
    /// dropped: past it, the fine nodes left where the models were near cost more than they save.
    const GROWTH: f64 = 1.25;
    /// The relative pose may have moved by at most this much (each rotation entry, and each
    /// translation coordinate in units of the models' root volume sizes) for the front to be used.
    const MOTION: f64 = 0.1;

    /// Storage for the front of the next query.
    pub fn take_spare(&mut self) -> Vec<FrontPair> {
        let mut v = std::mem::take(&mut self.spare);
        v.clear();
        v
    }

    /// Whether the query `q` should record its front for the next: the last query was on the
    /// same models, from a pose near this one, and the search is one that uses a front.
    pub fn worth_recording(&self, q: &FrontQuery) -> bool {
        self.last.as_ref().is_some_and(|(u1, u2, prev)| {
            Self::uses_front(q.search)
                && *u1 == q.m1.uid()
                && *u2 == q.m2.uid()
                && Self::change(prev, q.rel, q.b1, q.b2).is_some()
        })
    }

    /// Whether `search` starts from a front when it has one.
    fn uses_front(search: &Search) -> bool {
        search.triangle_cache && search.resolve(Strategy::Priority) == Strategy::Priority
    }

    /// The change of the relative pose from `prev` to `rel` (rotation, translation), when it is
    /// small enough for a front to pay.
    fn change(prev: &RelPose, rel: &RelPose, b1: &Bvh, b2: &Bvh) -> Option<(Mat3, Vec3)> {
        let dr = rel.rot - prev.rot;
        let dt = rel.trans - prev.trans;
        let scale = b1.root_size() + b2.root_size();
        (dr.amax() <= Self::MOTION && dt.amax() <= Self::MOTION * scale).then_some((dr, dt))
    }

    /// The front to start the query `q` from, if it suits it, with how much its bounds may
    /// have shrunk since they were computed.
    pub fn start(&self, q: &FrontQuery) -> Option<(&[FrontPair], Motion)> {
        let prev = self.rel.as_ref()?;
        let same = Self::uses_front(q.search)
            && self.uid1 == q.m1.uid()
            && self.uid2 == q.m2.uid()
            && !self.nodes.is_empty();
        if !same {
            return None;
        }
        let (dr, dt) = Self::change(prev, q.rel, q.b1, q.b2)?;
        let slack_scale = q.rel.trans.norm() + prev.trans.norm() + q.b1.reach() + q.b2.reach();
        let motion = Motion {
            dr,
            dt,
            dr_norm: spectral_bound(&dr),
            whole: 0.0,
            slack_scale,
        };
        let whole = motion.bound(&Vec3::zeros(), q.b2.reach());
        Some((&self.nodes[..], Motion { whole, ..motion }))
    }

    /// Keeps the front `new` of a query at `rel` (`None`: none was recorded); `from_front`: whether
    /// that query started from this front.
    pub fn finish(
        &mut self,
        m1: &Model,
        m2: &Model,
        rel: RelPose,
        new: Option<Vec<FrontPair>>,
        from_front: bool,
    ) {
        let same = self.uid1 == m1.uid() && self.uid2 == m2.uid();
        self.last = Some((m1.uid(), m2.uid(), rel));
        match new {
            // The search stopped before visiting anything (the cached pair touches): the old front
            // still covers every pair, but its bounds hold at its own pose only, which is kept.
            Some(v) if v.is_empty() && same && self.rel.is_some() => self.spare = v,
            Some(v) if !v.is_empty() && !self.outgrown(&v, from_front) => {
                if !from_front {
                    self.base = v.len();
                }
                self.spare = std::mem::replace(&mut self.nodes, v);
                (self.uid1, self.uid2, self.rel) = (m1.uid(), m2.uid(), Some(rel));
            }
            other => {
                // Dropped: the next query searches from the root.
                if let Some(v) = other {
                    self.spare = v;
                }
                self.nodes.clear();
                self.rel = None;
            }
        }
    }

    /// Whether the front `v` of a query that started from this front has grown too large to keep.
    fn outgrown(&self, v: &[FrontPair], from_front: bool) -> bool {
        from_front && v.len() as f64 > Self::GROWTH * self.base as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Lcg;
    use nalgebra::{Rotation3, Unit};

    /// A seeded source of uniform doubles in [-1, 1).
    fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut rng = Lcg(seed);
        move || rng.signed()
    }

    /// Every vertex below a node lies within the node's anchor distance of its anchor.
    #[test]
    fn anchors_reach_every_vertex_below() {
        let mut f = uniform(3);
        for (scale, offset) in [(1.0, 0.0), (1e-3, 1e3), (1e4, -5.0)] {
            let mut tris = Vec::new();
            for i in 0..300 {
                let c = [f() * scale + offset, f() * scale, f() * scale];
                let v = |f: &mut dyn FnMut() -> f64| {
                    [c[0] + 0.1 * scale * f(), c[1] + 0.1 * scale * f(), c[2]]
                };
                tris.push((v(&mut f), v(&mut f), v(&mut f), i));
            }
            let model = Model::from_triangles(tris).unwrap();
            let bvh = model.bvh().unwrap();
            fn below(b: &Bvh, r: NodeRef, out: &mut Vec<usize>) {
                if r.is_leaf() {
                    out.push(r.triangle());
                } else {
                    for c in b.children(r) {
                        below(b, c, out);
                    }
                }
            }
            let refs = (0..bvh.num_inner())
                .map(NodeRef::inner)
                .chain((0..300).map(NodeRef::leaf));
            for r in refs {
                let (o, e) = bvh.anchor(r);
                let mut tri = Vec::new();
                below(bvh, r, &mut tri);
                for t in tri {
                    for v in bvh.tri(t) {
                        assert!((v - o).norm() <= e, "node {r}: {} > {e}", (v - o).norm());
                    }
                }
            }
        }
    }

    /// A random motion for case `k` (scales and steps cycling through small to large), with the
    /// poses before and after: rotations `r0`, `r1` and translations `t0`, `t1`.
    fn random_motion(f: &mut dyn FnMut() -> f64, k: usize) -> (Motion, [Mat3; 2], [Vec3; 2]) {
        let rot = |f: &mut dyn FnMut() -> f64, angle: f64| -> Mat3 {
            let axis = Unit::new_normalize(Vec3::new(f(), f(), f() + 1e-3));
            Rotation3::from_axis_angle(&axis, angle).into_inner()
        };
        let scale = [1e-3, 1.0, 1e3][k % 3];
        let a0 = 3.0 * f();
        let r0 = rot(f, a0);
        let step = [1e-9, 1e-3, 0.1, 2.0][k % 4];
        let a1 = step * f();
        let r1 = rot(f, a1) * r0;
        let t0 = Vec3::new(f(), f(), f()) * scale;
        let t1 = t0 + Vec3::new(f(), f(), f()) * scale * step;
        let m = Motion {
            dr: r1 - r0,
            dt: t1 - t0,
            dr_norm: spectral_bound(&(r1 - r0)),
            whole: f64::INFINITY,
            slack_scale: t0.norm() + t1.norm(),
        };
        (m, [r0, r1], [t0, t1])
    }

    /// The motion bound holds for every point near the anchor, for small and large motions.
    #[test]
    fn motion_bounds_every_point_near_the_anchor() {
        let mut f = uniform(7);
        let mut tight = 0;
        for k in 0..2000 {
            let (m, [r0, r1], [t0, t1]) = random_motion(&mut f, k);
            let scale = [1e-3, 1.0, 1e3][k % 3];
            let o = Vec3::new(f(), f(), f()) * scale;
            let e = f().abs() * scale;
            let bound = m.bound(&o, e);
            for _ in 0..20 {
                let dir = Vec3::new(f(), f(), f()).normalize();
                let p = o + dir * (e * f().abs());
                let moved = ((r1 * p + t1) - (r0 * p + t0)).norm();
                assert!(moved <= bound, "case {k}: {moved} > {bound}");
                if moved > 0.5 * bound {
                    tight += 1;
                }
            }
        }
        // Not vacuous: the bound is often within a factor 2 of a point's actual motion.
        assert!(tight > 2000, "{tight}");
    }

    /// The motion along an axis bounds how far every point near the anchor moves against it, and
    /// is often far less than the whole displacement.
    #[test]
    fn motion_along_an_axis_bounds_every_point_near_the_anchor() {
        let mut f = uniform(11);
        let (mut smaller, mut cases) = (0, 0);
        for k in 0..2000 {
            let (m, [r0, r1], [t0, t1]) = random_motion(&mut f, k);
            let scale = [1e-3, 1.0, 1e3][k % 3];
            let o = Vec3::new(f(), f(), f()) * scale;
            let e = f().abs() * scale;
            let n = Vec3::new(f(), f(), f() + 1e-3).normalize();
            let shrink = m.along(&n, 1.0, &o, e);
            for _ in 0..20 {
                let dir = Vec3::new(f(), f(), f()).normalize();
                let p = o + dir * (e * f().abs());
                let against = -n.dot(&((r1 * p + t1) - (r0 * p + t0)));
                assert!(against <= shrink, "case {k}: {against} > {shrink}");
            }
            cases += 1;
            smaller += (shrink < 0.5 * m.bound(&o, e)) as usize;
        }
        // Not vacuous: against a random axis the shrink is often under half the displacement.
        assert!(smaller > cases / 4, "{smaller} of {cases}");
    }
}
