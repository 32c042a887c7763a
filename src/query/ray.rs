//! Ray casting: where a ray first meets a posed model.
//!
//! The ray is brought into the model's frame once. Its direction is scaled by a power of two (exact;
//! `t` is scaled back on output) and the coordinates are permuted and sheared so that the ray runs
//! along the third axis from the origin: a vertex `v` becomes `(x, y)`, the foot of `v - o` on the
//! plane across the ray, and `z`, the ray parameter of `v`'s plane across the dominant axis. The ray
//! meets a triangle when the origin of that plane lies in the projected triangle, decided by the
//! signs of the three 2D edge functions (the doubled areas the origin makes with each edge).
//!
//! **Watertight.** A vertex's projection depends on the vertex and the ray only, so triangles that
//! share it see the same point; an edge's function is the same expression for both triangles that
//! share it, with its operands swapped, so its floating-point value is exactly negated; and its sign
//! is exact (a float filter, and [`orient2d`]'s exact arithmetic where the filter cannot decide). A
//! triangle is hit when no two of its edge functions have opposite signs and not all are zero, so a
//! ray through a shared edge hits both triangles and one through a vertex hits every triangle around
//! it that is not edge-on: a ray can never slip between the triangles of a closed mesh.
//!
//! **Where.** On a hit, the barycentric weights are recomputed to a few ulps (rescaled, with exact
//! products), and `t` is their combination of the vertices' `z`: the hit point is a point of the
//! triangle (to within a few ulps of the coordinates' magnitude, see [`RayHit`]).
//!
//! **Search.** Nearest first through the model's four-wide tree of axis-aligned boxes
//! (`bvh/ray_tree.rs`, built on the model's first ray cast, with a copy of the triangles in its
//! leaf order, so that a leaf's triangles are one read): each node's four boxes
//! are cut by the ray at once (slab test with the reciprocal direction, the boxes grown by a
//! rounding allowance that covers both the test's rounding and the hit point's), and nodes whose
//! entry lies beyond the best hit so far are pruned.
//! Among hits at the same `t`, the triangle added first wins, so the answer does not depend on the
//! order of the search.
//!
//! **From a triangle.** A ray whose origin lies exactly on a triangle hits it at `t = 0`, whatever
//! the rounding of the projection says (it can put an origin on an edge just outside, or give an
//! origin inside a `t` of a few ulps). Wherever the origin lies in a triangle's box (exact
//! comparisons, a few per triangle on the search's paths that reject or confirm), an exact test
//! decides whether the origin is on it: in its plane (exact `orient3d`) and on the closed triangle
//! (exact `orient2d` signs in a coordinate plane on which the triangle has area).

use super::batch::{Workers, answer_all};
use super::ray_triangle::{
    edge, edge_sign, origin_on_triangle, triangle_normal, weights, zero_area,
};
use crate::bvh::{Bvh, Lane, MAX_DEPTH, RayTree, Slab, SlabRay};
use crate::error::{Error, MAX_COORDINATE};
use crate::geometry::predicates::{exponent, max_abs, pow2};
use crate::math::{Pose, Vec3};
use crate::model::Model;
use std::mem::MaybeUninit;

/// The nearest hit of a ray on a posed model.
///
/// Accuracy: `point` (which is `origin + t * direction`, world coordinates) lies within
/// `1e-14 * (|origin| + |T| + m)` of the hit triangle posed in the world, `m` being the largest
/// vertex coordinate of the model (in its frame) and `T` the pose's translation: it is a point of
/// the triangle up to the rounding of the coordinates. Along the ray the error grows as the ray grazes the triangle
/// (divided by the sine of the angle between the ray and the triangle's plane), as for any
/// floating-point answer to that question.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// The ray parameter of the hit: `origin + t * direction`, in `[0, max_t]`, in units of the
    /// direction given (which need not be a unit vector).
    pub t: f64,
    /// The hit point, world coordinates.
    pub point: Vec3,
    /// The unit normal of the hit triangle, `(p2 - p1) x (p3 - p1)` (its vertices in the order they
    /// were added), world coordinates: it points to either side of the ray, as the triangle's
    /// winding says.
    pub normal: Vec3,
    /// The caller's id of the hit triangle.
    pub triangle: i32,
}

/// Largest magnitude of a model-frame coordinate of the ray's origin. Rays of valid input stay
/// below it (an origin and a translation up to [`MAX_COORDINATE`], a rotation); beyond it (poses
/// that are not rotations) the edge functions could overflow, and the ray hits nothing.
const MAX_LOCAL: f64 = 4.0 * MAX_COORDINATE;

/// Ray casts against one model at one pose: the checked query arguments, shared by every ray.
pub(crate) struct RayCaster<'a> {
    bvh: &'a Bvh,
    tree: &'a RayTree,
    pose: Pose,
    max_t: f64,
}

/// A ray in the model's frame, ready for the triangle and box tests.
struct LocalRay {
    /// Origin.
    o: Vec3,
    /// Direction, scaled by `2^-k` so that its largest coordinate is in `[1, 2)`.
    d: Vec3,
    /// The permutation: `kz` the direction's dominant axis, `kx`, `ky` the others.
    kx: usize,
    ky: usize,
    kz: usize,
    /// The origin's coordinates on axes `kx`, `ky`, `kz`, and the direction's on `kz`.
    ox: f64,
    oy: f64,
    oz: f64,
    dz: f64,
    /// The shear that makes the ray the third axis: `x' = x - sx z`, `y' = y - sy z`.
    sx: f64,
    sy: f64,
    /// How far the boxes are grown at least: covers the slab test's rounding (in double
    /// precision) and how far a hit point may lie from its triangle.
    grow: f64,
}

/// The best hit so far: its parameter (in the scaled direction's units) and its position in the
/// ray tree's order.
#[derive(Clone, Copy)]
struct Best {
    t: f64,
    at: u32,
    /// The insertion index of the slot's triangle (ties between equal `t` go to the smallest).
    added: u32,
}

impl<'a> RayCaster<'a> {
    /// Checks the query's arguments shared by all rays: a built model, a finite pose, `max_t` not
    /// negative and not NaN.
    pub(crate) fn new(model: &'a Model, pose: &Pose, max_t: f64) -> Result<RayCaster<'a>, Error> {
        let bvh = model.bvh()?;
        pose.validate()?;
        if max_t.is_nan() || max_t < 0.0 {
            return Err(Error::InvalidArgument);
        }
        let tree = bvh.ray_tree()?;
        // The searches' copy of the triangles, made here on the first cast.
        tree.leaf_tris(bvh)?;
        Ok(RayCaster {
            bvh,
            tree,
            pose: *pose,
            max_t: max_t.max(0.0),
        })
    }

    /// `Err(NonFiniteCoordinate)` if the origin or the direction has a NaN, infinite or larger than
    /// [`MAX_COORDINATE`] coordinate (the direction may be as large as any finite value), and
    /// `Err(InvalidArgument)` if the direction is zero.
    pub(crate) fn check(origin: &Vec3, direction: &Vec3) -> Result<(), Error> {
        // Without short circuits (a NaN fails every comparison): a few vector comparisons.
        let o = origin.abs();
        let d = direction.abs();
        let ok = (o.x <= MAX_COORDINATE)
            & (o.y <= MAX_COORDINATE)
            & (o.z <= MAX_COORDINATE)
            & (d.x <= f64::MAX)
            & (d.y <= f64::MAX)
            & (d.z <= f64::MAX);
        if !ok {
            return Err(Error::NonFiniteCoordinate);
        }
        if direction.amax() == 0.0 {
            return Err(Error::InvalidArgument);
        }
        Ok(())
    }

    /// The nearest hit of one ray, whose arguments [`check`](RayCaster::check) accepted.
    pub(crate) fn cast(&self, origin: &Vec3, direction: &Vec3) -> Option<RayHit> {
        // The world direction scaled to a largest coordinate in [1, 2) (exact), then brought into
        // the model's frame and scaled again (exact too); `k1 + k2` undoes both on `t`.
        let (dw, k1) = unit_scale(direction);
        let r = &self.pose.rotation;
        let o = r.tr_mul(&(origin - self.pose.translation));
        let (d, k2) = unit_scale(&r.tr_mul(&dw));
        // Without short circuits (a NaN fails every comparison).
        let (oa, da) = (o.abs(), d.abs());
        let ok = (oa.x <= MAX_LOCAL)
            & (oa.y <= MAX_LOCAL)
            & (oa.z <= MAX_LOCAL)
            & (da.x <= f64::MAX)
            & (da.y <= f64::MAX)
            & (da.z <= f64::MAX)
            & (max_abs(&[&d]) != 0.0);
        if !ok {
            return None;
        }
        let ray = LocalRay::new(o, d, self.bvh.scale);
        // The local direction is the world's times 2^-k: a local parameter t is 2^-k t in the
        // world's units. The largest local parameter worth a look (rounded up).
        let k = k1 + k2;
        let limit = upper_scaled(self.max_t, k);
        let best = ray.search(self.bvh, self.tree, limit, |t| {
            let tw = scaled(t, -k);
            tw.is_finite() && tw <= self.max_t
        })?;
        let t = scaled(best.t, -k);
        let tri = &self.tree.leaf_tris(self.bvh).ok()?[best.at as usize];
        let [a, b, c] = &tri.v;
        let normal = unit(&(r * triangle_normal(a, b, c)));
        Some(RayHit {
            t,
            point: origin + direction * t,
            normal,
            triangle: tri.id,
        })
    }
}

impl LocalRay {
    fn new(o: Vec3, d: Vec3, model_scale: f64) -> LocalRay {
        let a = d.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        // Rounding in the box frame (the centre and origin moved, the direction turned) and the hit
        // point's distance from its triangle are a few ulps of the coordinates involved: this covers
        // both many times over, and the underflow of tiny models.
        let grow = 1e-12 * (o.abs().sum() + model_scale) + 1e-290;
        LocalRay {
            o,
            d,
            kx,
            ky,
            kz,
            ox: o[kx],
            oy: o[ky],
            oz: o[kz],
            dz: d[kz],
            sx: d[kx] / d[kz],
            sy: d[ky] / d[kz],
            grow,
        }
    }

    /// A vertex in the ray's frame: `(x', y')` across the ray, and `v - o` along the dominant axis.
    #[inline(always)]
    fn project(&self, v: &Vec3) -> [f64; 3] {
        let z = v[self.kz] - self.oz;
        [
            (v[self.kx] - self.ox) - self.sx * z,
            (v[self.ky] - self.oy) - self.sy * z,
            z,
        ]
    }

    /// The ray parameter where it meets triangle `t` (scaled direction's units), if it does at a
    /// parameter `>= 0` (a hit within rounding behind the origin counts as a hit at 0).
    ///
    /// Most triangles a search tests are missed, and most misses are decided here, inline, by
    /// two edge functions surely of opposite signs; the rest is [`confirm`](LocalRay::confirm).
    #[inline(always)]
    fn hit(&self, t: [&Vec3; 3]) -> Option<f64> {
        let [a, b, c] = [self.project(t[0]), self.project(t[1]), self.project(t[2])];
        let e = [edge(&b, &c), edge(&c, &a), edge(&a, &b)];
        // Without short circuits: a few vector comparisons rather than branches.
        let neg = (e[0].0 < -e[0].1) | (e[1].0 < -e[1].1) | (e[2].0 < -e[2].1);
        let pos = (e[0].0 > e[0].1) | (e[1].0 > e[1].1) | (e[2].0 > e[2].1);
        if neg && pos {
            // Surely missed, unless the origin lies on the triangle (then the rounding of the
            // projection can put it just outside): only possible where the triangle's vertices
            // are not all on one side of the origin along the dominant axis (the signs of the
            // `z`, differences of two doubles, are exact), the rest decided out of line.
            let (za, zb, zc) = (a[2], b[2], c[2]);
            if (za > 0.0 && zb > 0.0 && zc > 0.0) || (za < 0.0 && zb < 0.0 && zc < 0.0) {
                return None;
            }
            return self.starts_on(t);
        }
        self.confirm(t, [a, b, c], e)
    }

    /// `Some(0.0)` if the origin lies on triangle `t` (exactly), else `None`.
    #[inline(never)]
    fn starts_on(&self, t: [&Vec3; 3]) -> Option<f64> {
        (self.origin_in_box(t) && origin_on_triangle(t, &self.o)).then_some(0.0)
    }

    /// Whether the origin lies in the box of triangle `t` (exact comparisons): a cheap necessary
    /// condition for [`origin_on_triangle`].
    #[inline(always)]
    fn origin_in_box(&self, t: [&Vec3; 3]) -> bool {
        let o = &self.o;
        let lo = t[0].inf(t[1]).inf(t[2]);
        let hi = t[0].sup(t[1]).sup(t[2]);
        (lo.x <= o.x)
            & (o.x <= hi.x)
            & (lo.y <= o.y)
            & (o.y <= hi.y)
            & (lo.z <= o.z)
            & (o.z <= hi.z)
    }

    /// [`hit`](LocalRay::hit) past its quick rejection: `p` the projected vertices, `e` the
    /// filtered edge functions.
    #[inline(never)]
    fn confirm(&self, t: [&Vec3; 3], p: [[f64; 3]; 3], e: [(f64, f64); 3]) -> Option<f64> {
        // A ray starting on the triangle hits it at exactly 0, whatever its direction (in the
        // triangle's plane too) and whatever the projection's rounding says.
        if self.starts_on(t).is_some() {
            return Some(0.0);
        }
        let [a, b, c] = p;
        let s = [
            edge_sign(e[0], &b, &c),
            edge_sign(e[1], &c, &a),
            edge_sign(e[2], &a, &b),
        ];
        let (neg, pos) = (s.contains(&-1), s.contains(&1));
        if neg == pos || zero_area(&[*t[0], *t[1], *t[2]]) {
            // Opposite signs (a miss), or all zero (edge-on: its neighbours' edges are hit), or a
            // triangle without area.
            return None;
        }
        let w = weights(&[a, b, c], s);
        let z = [a[2] / self.dz, b[2] / self.dz, c[2] / self.dz];
        let t = w[0] * z[0] + w[1] * z[1] + w[2] * z[2];
        // The sum's rounding and the z's: a few ulps of the largest.
        let tol = 8.0 * f64::EPSILON * z[0].abs().max(z[1].abs()).max(z[2].abs());
        (t >= -tol).then_some(t.max(0.0))
    }

    /// [`hit`](LocalRay::hit) on the triangle in leaf slot `slot` of `bvh` (the tests' brute
    /// force, which reads the hierarchy rather than the ray tree's copy).
    #[cfg(test)]
    fn hit_slot(&self, bvh: &Bvh, slot: usize) -> Option<f64> {
        let f = &bvh.faces[slot];
        let v = &bvh.verts;
        self.hit([&v[f[0] as usize], &v[f[1] as usize], &v[f[2] as usize]])
    }

    /// The nearest hit among the triangles of `tree` (the ray layout of `bvh`) at a parameter
    /// `<= limit` that `accept` takes (ties: the triangle added first), searching nearer nodes
    /// first; `None` too if the tree's copy of the triangles cannot be made (out of memory).
    fn search(
        &self,
        bvh: &Bvh,
        tree: &RayTree,
        limit: f64,
        accept: impl Fn(f64) -> bool,
    ) -> Option<Best> {
        match SlabRay::new(&self.o, &self.d, self.grow, tree.extent()) {
            SlabRay::Single(s) => self.search_with(bvh, tree, &s, limit, accept),
            SlabRay::Double(s) => self.search_with(bvh, tree, &s, limit, accept),
        }
    }

    /// [`search`](LocalRay::search) with the slab tests of `slab`.
    fn search_with<T: Lane>(
        &self,
        bvh: &Bvh,
        tree: &RayTree,
        slab: &Slab<T>,
        limit: f64,
        accept: impl Fn(f64) -> bool,
    ) -> Option<Best> {
        // The triangles are read from the tree's copy, in its order.
        let tris = tree.leaf_tris(bvh).ok()?;
        let mut best: Option<Best> = None;
        // How far a node may start and still be visited: the best hit's parameter (a node starting
        // exactly there may hold a triangle added earlier), grown by a few ulps for the slab test's
        // last rounding, rounded up to the slab test's arithmetic, and at most its largest finite
        // value (which `RayTree::cut` needs; no point of the tree lies farther along the ray).
        // Updated with the best hit.
        let reach_of = |t: f64| T::above(t * (1.0 + 1e-14)).min(T::LARGEST);
        let mut reach = reach_of(limit);
        // Nodes still to visit (link, count as in `RayTree::links`) with their entry parameters,
        // the nearest on top: each level of the tree (at most `MAX_DEPTH`) leaves at most three
        // children behind. Left uninitialised (zeroing it would cost as much as a short search).
        let mut stack = [const { MaybeUninit::<(u32, u32, T)>::uninit() }; 3 * MAX_DEPTH + 4];
        let mut len = 0;
        // The node visited: an inner node (`count == 0`) or a leaf's run of the order.
        let (mut link, mut count) = (tree.root(), 0u32);
        loop {
            if count == 0 {
                let (enter, mask) = tree.cut(link, slab, reach);
                if mask != 0 {
                    let (links, counts) = tree.links(link);
                    let mut near = mask.trailing_zeros() as usize;
                    if mask & (mask - 1) != 0 {
                        // Several crossed: sorted farthest first, all but the nearest stacked.
                        let mut crossed = [(0usize, T::ZERO); 4];
                        let mut n = 0;
                        let mut m = mask;
                        while m != 0 {
                            let k = m.trailing_zeros() as usize;
                            m &= m - 1;
                            let t = enter[k];
                            let mut j = n;
                            while j > 0 && crossed[j - 1].1 < t {
                                crossed[j] = crossed[j - 1];
                                j -= 1;
                            }
                            crossed[j] = (k, t);
                            n += 1;
                        }
                        for &(k, t) in &crossed[..n - 1] {
                            if counts[k] == 0 {
                                tree.prefetch(links[k]);
                            } else {
                                let (first, n) = (links[k] as usize, counts[k] as usize);
                                RayTree::prefetch_items(tris.get(first..first + n));
                            }
                            // Checked indexing: the depth bound keeps it in range.
                            stack[len] = MaybeUninit::new((links[k], counts[k], t));
                            len += 1;
                        }
                        near = crossed[n - 1].0;
                    }
                    (link, count) = (links[near], counts[near]);
                    continue;
                }
            } else {
                for at in link..link + count {
                    let tri = &tris[at as usize];
                    let Some(t) = self.hit([&tri.v[0], &tri.v[1], &tri.v[2]]) else {
                        continue;
                    };
                    let added = tri.added;
                    let better = match best {
                        None => true,
                        Some(b) => t < b.t || (t == b.t && added < b.added),
                    };
                    if better && accept(t) {
                        best = Some(Best { t, at, added });
                        reach = reach_of(t);
                    }
                }
            }
            // The nearest stacked node that may still hold a better hit.
            loop {
                if len == 0 {
                    return best;
                }
                len -= 1;
                // SAFETY: the entries below `len` were written above.
                let (next, n, enter) = unsafe { stack[len].assume_init() };
                if enter <= reach {
                    (link, count) = (next, n);
                    break;
                }
            }
        }
    }
}

/// `v` scaled to unit length (by a power of two first, so that its squares neither under- nor
/// overflow).
fn unit(v: &Vec3) -> Vec3 {
    let (v, _) = unit_scale(v);
    v / v.norm()
}

/// `v` (not zero, no NaN) scaled by `2^-k` so that its largest coordinate is in `[1, 2)`, and
/// `k`.
fn unit_scale(v: &Vec3) -> (Vec3, i32) {
    let m = max_abs(&[v]);
    if m == 0.0 || !m.is_finite() {
        return (*v, 0);
    }
    let k = match exponent(m) {
        // Subnormal: its exponent, read after scaling into the normal range.
        -1023 => exponent(m * pow2(600)) - 600,
        k => k,
    };
    (v.map(|x| scaled(x, -k)), k)
}

/// `x * 2^k`, in steps so that no factor is out of range; it may over- or underflow.
fn scaled(x: f64, k: i32) -> f64 {
    if (-1000..=1000).contains(&k) {
        // The loop's single step.
        return x * pow2(k);
    }
    let mut y = x;
    let mut k = k;
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        y *= pow2(step);
        k -= step;
    }
    y
}

/// `x * 2^k` (`x >= 0`) rounded up: an underflow to 0 gives the smallest positive value.
fn upper_scaled(x: f64, k: i32) -> f64 {
    let y = scaled(x, k);
    if y == 0.0 && x > 0.0 {
        f64::from_bits(1)
    } else {
        y
    }
}

/// The nearest hit of a ray on a posed model: where `origin + t * direction` first meets a triangle
/// for `t` in `[0, max_t]`, or `None`.
///
/// The direction need not be a unit vector (`t` is in its units). Hits are watertight: a ray
/// through an edge or a vertex shared by triangles of a closed mesh hits one of them. Triangles are
/// hit from either side; a ray in a triangle's plane does not hit it (its neighbours' edges are
/// hit) unless it starts on it, nor does any ray hit a triangle without area. A ray starting on a
/// triangle (inside it, on an edge or on a vertex, exactly: the origin brought into the model's
/// frame is a point of the triangle) hits it at `t = 0`, whatever its direction, `max_t = 0`
/// included. Among hits at the same `t`, the triangle added first is reported. See [`RayHit`] for
/// the accuracy.
///
/// Errors: `UnprocessedModel` if the model is not built, `NonFinitePose` for a pose entry that is
/// NaN, infinite or larger than 1e150, `NonFiniteCoordinate` for an origin coordinate that is NaN,
/// infinite or larger than 1e150 or a direction coordinate that is NaN or infinite,
/// `InvalidArgument` for a zero direction or a `max_t` that is negative or NaN (`max_t` may be
/// infinite), `OutOfMemory` if the model's tree of axis-aligned boxes and its copy of the
/// triangles in the tree's leaf order, made on its first ray cast (about 40 + 80 = 120 bytes per
/// triangle, kept in the model), cannot be allocated.
///
/// ```
/// use pqp::{Model, Pose, Vec3, ray_cast};
/// let square = Model::from_triangles([
///     ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], 7),
///     ([0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], 8),
/// ])
/// .unwrap();
/// // Straight down through the shared diagonal: it hits (one of the two triangles).
/// let o = Vec3::new(0.5, 0.5, 2.0);
/// let hit = ray_cast(&square, &Pose::identity(), &o, &Vec3::new(0.0, 0.0, -4.0), f64::INFINITY)
///     .unwrap()
///     .unwrap();
/// assert_eq!(hit.t, 0.5);
/// assert!(hit.triangle == 7 || hit.triangle == 8);
/// assert_eq!(hit.normal, Vec3::new(0.0, 0.0, 1.0));
/// ```
pub fn ray_cast(
    model: &Model,
    pose: &Pose,
    origin: &Vec3,
    direction: &Vec3,
    max_t: f64,
) -> Result<Option<RayHit>, Error> {
    let caster = RayCaster::new(model, pose, max_t)?;
    RayCaster::check(origin, direction)?;
    Ok(caster.cast(origin, direction))
}

/// [`ray_cast`] for many rays (`origins[i]`, `directions[i]`), on `threads` threads (0: as many as
/// the machine has). Each answer is the one `ray_cast` gives for that ray.
///
/// Errors: as [`ray_cast`], for any ray (then nothing is cast), and `InvalidArgument` if the two
/// slices differ in length; `OutOfMemory` if the answers cannot be allocated.
pub fn ray_cast_batch(
    model: &Model,
    pose: &Pose,
    origins: &[Vec3],
    directions: &[Vec3],
    max_t: f64,
    threads: usize,
) -> Result<Vec<Option<RayHit>>, Error> {
    if origins.len() != directions.len() {
        return Err(Error::InvalidArgument);
    }
    let caster = RayCaster::new(model, pose, max_t)?;
    for (o, d) in origins.iter().zip(directions) {
        RayCaster::check(o, d)?;
    }
    caster.cast_all(
        |i| (origins[i], directions[i]),
        origins.len(),
        Workers::plain(threads),
    )
}

impl RayCaster<'_> {
    /// Casts rays `0..n` (`ray(i)`, already checked) on the threads `workers` gives, with the
    /// pair batches' dispatcher ([`answer_all`]): the answers in ray order.
    pub(crate) fn cast_all(
        &self,
        ray: impl Fn(usize) -> (Vec3, Vec3) + Sync,
        n: usize,
        workers: Workers,
    ) -> Result<Vec<Option<RayHit>>, Error> {
        answer_all(
            n,
            workers,
            || (),
            |_, i| {
                let (o, d) = ray(i);
                Ok(self.cast(&o, &d))
            },
        )
    }
}

#[cfg(test)]
#[path = "ray_tests.rs"]
mod tests;
