//! A primitive (sphere, capsule or box, `model/primitive.rs`) against a triangle model or against
//! another primitive: collision, distance, tolerance and pairs within a distance.
//!
//! Each pair query branches here at its entry when one of its models is a primitive. The work is
//! done in the primitive's frame: the mesh's hierarchy is searched against the one fixed volume
//! that holds the primitive, and each triangle reached is measured from the primitive's core (a
//! point, a segment, or the solid box) with the exact triangle kernels, less the radius. So every
//! answer is as exact as `tri_distance`, and "touching" means the same as between triangles.

use super::Stats;
use crate::bounding_volume::{DistanceVolume, Ssv};
use crate::bvh::{Bvh, NodeRef};
use crate::error::Error;
use crate::geometry::{ClosestPoints, Tri, tri_distance, tri_overlap};
use crate::math::{Pose, RelPose, Vec3};
use crate::model::{Core, Model, Primitive};
use std::time::Instant;

/// Two posed models of which at least one is a primitive, seen from a primitive's frame.
enum Pair<'a> {
    /// Two primitives; `rel` poses the second (model 2) in the first's frame.
    Primitives {
        a: Primitive,
        b: Primitive,
        rel: RelPose,
    },
    /// A primitive and a triangle model; `rel` poses the mesh in the primitive's frame.
    /// `mesh_first`: the mesh is the query's model 1.
    Mesh {
        prim: Primitive,
        bvh: &'a Bvh,
        rel: RelPose,
        mesh_first: bool,
    },
}

/// `None` if neither model is a primitive (the query goes on as between meshes); else the pair,
/// or the error of an unbuilt model or a bad pose.
fn pair<'a>(
    m1: &'a Model,
    pose1: &Pose,
    m2: &'a Model,
    pose2: &Pose,
) -> Option<Result<Pair<'a>, Error>> {
    let (p1, p2) = (m1.primitive(), m2.primitive());
    if p1.is_none() && p2.is_none() {
        return None;
    }
    let checked = || {
        m1.check_built()?;
        m2.check_built()?;
        pose1.validate()?;
        pose2.validate()?;
        Ok(match (p1, p2) {
            (Some(a), Some(b)) => Pair::Primitives {
                a,
                b,
                rel: RelPose::between(pose1, pose2),
            },
            (Some(prim), None) => Pair::Mesh {
                prim,
                bvh: m2.bvh()?,
                rel: RelPose::between(pose1, pose2),
                mesh_first: false,
            },
            (None, _) => Pair::Mesh {
                prim: p2.ok_or(Error::Internal)?,
                bvh: m1.bvh()?,
                rel: RelPose::between(pose2, pose1),
                mesh_first: true,
            },
        })
    };
    Some(checked())
}

impl Pair<'_> {
    /// The closest points of two primitives, `b` posed by `rel` in `a`'s frame (on `a`, then on
    /// `b`, in `a`'s frame).
    fn measure_primitives(a: &Primitive, b: &Primitive, rel: &RelPose) -> ClosestPoints {
        let ((ca, ra), (cb, rb)) = (a.core(), b.core());
        swept(cores(&ca, &cb, rel), ra, rb)
    }

    /// The answer as model 1 and model 2 see it, from closest points `gap` in the primitive's
    /// frame (on the primitive, then on the other) and the mesh's leaf slot, if any.
    fn found(&self, gap: ClosestPoints, slot: usize) -> Answer {
        let answer = |p1, p2, ids, tris| Answer {
            distance: gap.distance,
            p1,
            p2,
            ids,
            tris,
        };
        match self {
            Pair::Primitives { rel, .. } => {
                answer(gap.p, rel.apply_inverse(&gap.q), (0, 0), (0, 0))
            }
            Pair::Mesh {
                bvh,
                rel,
                mesh_first,
                ..
            } => {
                let on_mesh = rel.apply_inverse(&gap.q);
                let (id, tri) = (bvh.ids[slot], bvh.added[slot] as i32);
                if *mesh_first {
                    answer(on_mesh, gap.p, (id, 0), (tri, 0))
                } else {
                    answer(gap.p, on_mesh, (0, id), (0, tri))
                }
            }
        }
    }

    /// The ids of an element pair, in the query's order.
    fn contact(&self, slot: usize) -> (i32, i32) {
        match self {
            Pair::Primitives { .. } => (0, 0),
            Pair::Mesh {
                bvh, mesh_first, ..
            } => {
                let id = bvh.ids[slot];
                if *mesh_first { (id, 0) } else { (0, id) }
            }
        }
    }

    /// Visits the element pairs that `visit` does not prune: the one pair of two primitives, or
    /// the primitive against the mesh's triangles (see [`search_mesh`]). Returns the least bound
    /// of a pruned node (infinite if none).
    fn visit(&self, stats: &mut Stats, visit: &mut impl Visit) -> f64 {
        match self {
            Pair::Primitives { a, b, rel } => {
                stats.tri_tests += 1;
                visit.element(0, Pair::measure_primitives(a, b, rel));
                f64::INFINITY
            }
            Pair::Mesh { prim, bvh, rel, .. } => search_mesh(prim, bvh, rel, stats, visit),
        }
    }
}

/// What a search over a primitive's pairs does with them.
trait Visit {
    /// Nodes whose bound is at or above this are pruned.
    fn cutoff(&self) -> f64;
    /// An element pair (the mesh's leaf slot, 0 for a primitive) and its closest points in the
    /// primitive's frame; `true` stops the search.
    fn element(&mut self, slot: usize, gap: ClosestPoints) -> bool;
    /// Whether only contact matters: then a triangle's `gap` is distance 0 when it touches the
    /// primitive, else an infinite distance (no points), found by the cheaper overlap tests.
    fn contact_only(&self) -> bool {
        false
    }
}

/// Searches `bvh` (posed by `rel` in the primitive's frame) against the primitive, nearer child
/// first, pruning nodes by their swept sphere volume's distance bound from the primitive's
/// volume. Returns the least bound of a pruned node (infinite if none).
fn search_mesh(
    prim: &Primitive,
    bvh: &Bvh,
    rel: &RelPose,
    stats: &mut Stats,
    visit: &mut impl Visit,
) -> f64 {
    let (core, radius) = prim.core();
    let volume = prim.bound();
    let bound = |n: NodeRef, cutoff: f64| Ssv::distance_below(&volume, &bvh.ssv(n), rel, cutoff);
    let mut pruned = f64::INFINITY;
    let root = bvh.root();
    let mut stack: Vec<(NodeRef, f64)> = Vec::with_capacity(64);
    stack.push((root, bound(root, visit.cutoff())));
    stats.bv_tests += 1;
    while let Some((n, b)) = stack.pop() {
        let cutoff = visit.cutoff();
        if b >= cutoff {
            pruned = pruned.min(b);
            continue;
        }
        if n.is_leaf() {
            stats.tri_tests += 1;
            let slot = n.triangle();
            let t = bvh.tri(slot).map(|p| rel.apply(&p));
            // Against a box, the triangle's own box first: most leaves a volume bound lets in end
            // here, for a fraction of a face test.
            if let Core::Box(h) = core {
                let gap = box_gap(&h, &t);
                if gap >= cutoff {
                    pruned = pruned.min(gap);
                    continue;
                }
            }
            let gap = match core {
                Core::Box(h) if visit.contact_only() => ClosestPoints {
                    distance: if box_meets_triangle(&h, &t) {
                        0.0
                    } else {
                        f64::INFINITY
                    },
                    p: t[0],
                    q: t[0],
                },
                _ => swept(core_triangle(&core, &t), radius, 0.0),
            };
            if visit.element(slot, gap) {
                break;
            }
            continue;
        }
        let [c0, c1] = bvh.children(n);
        let (b0, b1) = (bound(c0, cutoff), bound(c1, cutoff));
        stats.bv_tests += 2;
        // The nearer child on top: it is visited first.
        if b0 <= b1 {
            stack.push((c1, b1));
            stack.push((c0, b0));
        } else {
            stack.push((c0, b0));
            stack.push((c1, b1));
        }
    }
    pruned
}

/// The closest points of two solids swept by radii `ra` and `rb` from cores whose closest points
/// are `c`: the cores' distance less both radii, or 0 with a common point when that is not
/// positive (the point at `min(ra, d)` from the first core towards the second, within both).
fn swept(c: ClosestPoints, ra: f64, rb: f64) -> ClosestPoints {
    let d = c.distance;
    let gap = (d - ra - rb).max(0.0);
    if gap > 0.0 {
        let u = (c.q - c.p) / d;
        ClosestPoints {
            distance: gap,
            p: c.p + u * ra,
            q: c.q - u * rb,
        }
    } else {
        let m = if d > 0.0 {
            c.p + (c.q - c.p) * (ra.min(d) / d)
        } else {
            c.p
        };
        ClosestPoints {
            distance: 0.0,
            p: m,
            q: m,
        }
    }
}

/// The closest points of a core and a triangle in its frame (on the core, then on `t`); distance
/// 0 with a common point when they meet.
fn core_triangle(core: &Core, t: &Tri) -> ClosestPoints {
    match core {
        Core::Segment(s) => tri_distance(s, t),
        Core::Box(h) => box_triangle(h, t),
    }
}

/// The closest points of two cores, `b` posed by `rel` in `a`'s frame (on `a`, then on `b`, in
/// `a`'s frame); distance 0 with a common point when they meet.
fn cores(a: &Core, b: &Core, rel: &RelPose) -> ClosestPoints {
    let pose = |t: &Tri| t.map(|p| rel.apply(&p));
    match (a, b) {
        (Core::Segment(s), Core::Segment(u)) => tri_distance(s, &pose(u)),
        (Core::Box(h), Core::Segment(u)) => box_triangle(h, &pose(u)),
        (Core::Segment(s), Core::Box(h)) => {
            // In the box's frame, then back.
            let c = box_triangle(h, &s.map(|p| rel.apply_inverse(&p)));
            ClosestPoints {
                distance: c.distance,
                p: rel.apply(&c.q),
                q: rel.apply(&c.p),
            }
        }
        (Core::Box(ha), Core::Box(hb)) => {
            // B's faces against A (which finds B inside A, or their surfaces meeting) ...
            let mut best = ClosestPoints {
                distance: f64::INFINITY,
                p: Vec3::zeros(),
                q: Vec3::zeros(),
            };
            for f in box_faces(hb) {
                let c = box_triangle(ha, &pose(&f));
                if c.distance < best.distance {
                    best = c;
                }
            }
            // ... and A inside B, whose surface it does not meet: then A's centre is strictly
            // inside B.
            let centre = rel.apply_inverse(&Vec3::zeros());
            if best.distance > 0.0 && (0..3).all(|i| centre[i].abs() < hb[i]) {
                best = ClosestPoints {
                    distance: 0.0,
                    p: Vec3::zeros(),
                    q: Vec3::zeros(),
                };
            }
            best
        }
    }
}

/// The two triangles of each of the six faces of the box of half sides `h`, face by face: the
/// face across axis `k` on side `s` (-1, then 1) is at `2 (2 k + (s + 1) / 2)`.
fn box_faces(h: &Vec3) -> [Tri; 12] {
    let mut out = [[Vec3::zeros(); 3]; 12];
    for k in 0..3 {
        for (side, sign) in [-1.0, 1.0].into_iter().enumerate() {
            let (u, v) = ((k + 1) % 3, (k + 2) % 3);
            let corner = |su: f64, sv: f64| {
                let mut c = Vec3::zeros();
                c[k] = sign * h[k];
                c[u] = su * h[u];
                c[v] = sv * h[v];
                c
            };
            let (a, b, c, d) = (
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            );
            let f = 2 * (2 * k + side);
            out[f] = [a, b, c];
            out[f + 1] = [a, c, d];
        }
    }
    out
}

/// The triangles of the faces of the box of half sides `h` (centred on the origin, on the axes)
/// that can hold its point nearest to the triangle `t`, or a point `t` meets: the faces with a
/// vertex of `t` on or beyond their plane. The box's point nearest to a point `q` outside lies on a
/// face only if `q` is on or beyond that face's plane, and a triangle meeting the surface has a
/// point in the plane of a face it meets. None: every vertex is strictly inside, and so is `t`.
fn facing(h: &Vec3, t: &Tri) -> impl Iterator<Item = Tri> {
    let faces = box_faces(h);
    let t = *t;
    let h = *h;
    (0..6)
        .filter(move |&j| {
            let (k, sign) = (j / 2, if j % 2 == 0 { -1.0 } else { 1.0 });
            // Exact: negation and comparison do not round.
            t.iter().any(|v| sign * v[k] >= h[k])
        })
        .flat_map(move |j| [faces[2 * j], faces[2 * j + 1]])
}

/// The closest points of the solid box of half sides `h` (centred on the origin, on the axes) and
/// the triangle `t` (on the box, then on `t`): distance 0 with a common point when the triangle
/// meets the box (crosses or touches its surface, or lies inside it). Measured on the faces
/// [`facing`] gives.
pub(crate) fn box_triangle(h: &Vec3, t: &Tri) -> ClosestPoints {
    let mut best: Option<ClosestPoints> = None;
    for face in facing(h, t) {
        let c = tri_distance(&face, t);
        if c.distance == 0.0 {
            return c;
        }
        if best.is_none_or(|b| c.distance < b.distance) {
            best = Some(c);
        }
    }
    best.unwrap_or(ClosestPoints {
        distance: 0.0,
        p: t[0],
        q: t[0],
    })
}

/// A lower bound on the distance between the box of half sides `h` and the triangle `t`: the
/// distance to the box around `t` on the same axes, rounded down (by more than the few roundings
/// of its computation).
fn box_gap(h: &Vec3, t: &Tri) -> f64 {
    let mut sum = 0.0;
    for k in 0..3 {
        let lo = t[0][k].min(t[1][k]).min(t[2][k]);
        let hi = t[0][k].max(t[1][k]).max(t[2][k]);
        let g = (lo - h[k]).max(-h[k] - hi).max(0.0);
        sum += g * g;
    }
    sum.sqrt() * (1.0 - 8.0 * f64::EPSILON)
}

/// Whether the triangle `t` meets the solid box of half sides `h`: exactly when [`box_triangle`]
/// answers 0 (the exact overlap test agrees with the exact distance), for less work.
fn box_meets_triangle(h: &Vec3, t: &Tri) -> bool {
    let mut faced = false;
    for face in facing(h, t) {
        if tri_overlap(&face, t) {
            return true;
        }
        faced = true;
    }
    !faced
}

/// Ids `(id1, id2)` of element pairs, and the work of finding them.
pub(super) type Pairs = (Vec<(i32, i32)>, Stats);

/// Element pairs at most `tolerance` apart (0: colliding) with a primitive, for the branches of
/// [`collide_into`](super::collide_into) and [`within_distance_into`](super::within_distance_into):
/// their ids `(id1, id2)` in the query's order (`first`: the first found only), and the work done.
/// `None` if neither model is a primitive; `Err(OutOfMemory)` if the list cannot grow.
pub(super) fn pairs(
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    tolerance: f64,
    first: bool,
) -> Option<Result<Pairs, Error>> {
    struct Within<'p> {
        pair: &'p Pair<'p>,
        pairs: Vec<(i32, i32)>,
        tolerance: f64,
        first: bool,
        failed: bool,
    }
    impl Visit for Within<'_> {
        fn cutoff(&self) -> f64 {
            // Pruned exactly when the bound exceeds the tolerance.
            self.tolerance.next_up()
        }
        fn element(&mut self, slot: usize, gap: ClosestPoints) -> bool {
            if gap.distance > self.tolerance {
                return false;
            }
            if self.pairs.try_reserve(1).is_err() {
                self.failed = true;
                return true;
            }
            self.pairs.push(self.pair.contact(slot));
            self.first
        }
        fn contact_only(&self) -> bool {
            self.tolerance == 0.0
        }
    }
    let start = Instant::now();
    let pair = match pair(m1, pose1, m2, pose2)? {
        Ok(p) => p,
        Err(e) => return Some(Err(e)),
    };
    let mut stats = Stats::default();
    let mut within = Within {
        pair: &pair,
        pairs: Vec::new(),
        tolerance,
        first,
        failed: false,
    };
    pair.visit(&mut stats, &mut within);
    if within.failed {
        return Some(Err(Error::OutOfMemory));
    }
    stats.query_time_secs = start.elapsed().as_secs_f64();
    Some(Ok((within.pairs, stats)))
}

/// What a search for the nearest pair with a primitive is for.
#[derive(Clone, Copy)]
pub(super) enum Goal {
    /// The distance within these error bounds (checked).
    Distance { rel_err: f64, abs_err: f64 },
    /// Whether the distance is at most this tolerance (checked): stops at a pair within it.
    Tolerance(f64),
}

/// The nearest element pair a search found, as model 1 and model 2 see it: the distance, the
/// closest points (each in its model's frame; a common point when touching), the elements' ids
/// and positions in the order added (0 for a primitive).
#[derive(Clone, Copy)]
pub(super) struct Answer {
    pub distance: f64,
    pub p1: Vec3,
    pub p2: Vec3,
    pub ids: (i32, i32),
    pub tris: (i32, i32),
}

/// What [`nearest`] found: the best pair (for a tolerance, the first within it, or the nearest
/// seen), the least bound of a pruned node (infinite if none), and the work done.
pub(super) struct Nearest {
    pub best: Option<Answer>,
    pub pruned: f64,
    pub stats: Stats,
}

/// The nearest element pair with a primitive, for the branches of
/// [`distance_into`](super::distance_into) and [`tolerance_into`](super::tolerance_into). `None`
/// if neither model is a primitive.
pub(super) fn nearest(
    m1: &Model,
    pose1: &Pose,
    m2: &Model,
    pose2: &Pose,
    goal: Goal,
) -> Option<Result<Nearest, Error>> {
    struct Best<F: Fn(f64) -> f64> {
        best: Option<(usize, ClosestPoints)>,
        /// The pruning cutoff for a best distance.
        cutoff: F,
        /// Stop at a pair this near.
        stop: f64,
    }
    impl<F: Fn(f64) -> f64> Visit for Best<F> {
        fn cutoff(&self) -> f64 {
            (self.cutoff)(self.best.map_or(f64::INFINITY, |(_, c)| c.distance))
        }
        fn element(&mut self, slot: usize, gap: ClosestPoints) -> bool {
            if self.best.is_none_or(|(_, b)| gap.distance < b.distance) {
                self.best = Some((slot, gap));
            }
            gap.distance <= self.stop
        }
    }
    let start = Instant::now();
    let pair = match pair(m1, pose1, m2, pose2)? {
        Ok(p) => p,
        Err(e) => return Some(Err(e)),
    };
    // A tolerance prunes what is beyond it, or reaches the best distance, and stops within it.
    let (rel_err, abs_err, stop, above) = match goal {
        Goal::Distance { rel_err, abs_err } => (rel_err, abs_err, 0.0, f64::INFINITY),
        Goal::Tolerance(t) => (0.0, 0.0, t, t.next_up()),
    };
    // As the mesh search: a bound b prunes when b (1 + rel_err) >= d and b + abs_err >= d.
    let scale = (1.0 + rel_err).min((1u64 << 50) as f64);
    let mut best = Best {
        best: None,
        cutoff: |d: f64| {
            let d = d.min(above);
            if abs_err == 0.0 {
                d
            } else {
                (d / scale).max(d - abs_err)
            }
        },
        stop,
    };
    let mut stats = Stats::default();
    let pruned = pair.visit(&mut stats, &mut best);
    stats.query_time_secs = start.elapsed().as_secs_f64();
    let best = best.best.map(|(slot, gap)| pair.found(gap, slot));
    Some(Ok(Nearest {
        best,
        pruned,
        stats,
    }))
}
