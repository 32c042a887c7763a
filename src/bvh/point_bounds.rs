//! Per-triangle frames for the closest-point search of small models: a cheap lower bound on the
//! distance from a point to a triangle, so that the exact point-triangle routine runs only where
//! it could lower the best distance.
//!
//! The closest point of a small model descends the ray tree's boxes (see `query/point.rs`). A
//! triangle's box is a weak bound: on the bunny about 25 triangles per query pass it, but only 2
//! to 3 lower the best distance, and the exact routine costs some 340 instructions a call. Each
//! triangle here keeps, in the ray tree's order (so a leaf's triangles are adjacent), its plane
//! (unit normal `n` and offset) and per edge the edge's unit direction `t` and the unit normal `m`
//! of the edge in the plane pointing away from the triangle, with their offsets. A point's
//! distance to the triangle is then, by Pythagoras in the orthonormal frame `(n, m, t)`,
//! `h^2 + lateral^2`: `h` the distance to the plane, `lateral` 0 if the point lies on the inner
//! side of every edge's line, else the least over the edges it lies outside of, of `o^2 + a^2`
//! (`o` its distance outside the line, `a` how far it lies beyond the edge's ends along `t`).
//! Seven dot products with the point, no division, no branch on the region.
//!
//! Computed only for a model's first closest point (see [`RayTree::triangle_bounds`]), 248 bytes a
//! triangle.

use super::{Bvh, RayTree};
use crate::error::Error;
use crate::math::Vec3;

/// One triangle's frame: see the module's documentation. All NaN for a triangle the bound is not
/// trusted on (see [`TriangleFrame::new`]), which makes every bound NaN: never below a cutoff, so
/// never skipped.
#[derive(Clone, Copy, Debug)]
struct TriangleFrame {
    /// The unit normal and its offset (`n . v0`).
    plane: [f64; 4],
    /// Per edge `i` (from vertex `i` to `i + 1`), in column `i`: the unit normal in the plane
    /// pointing away from the triangle (rows x, y, z) and its offset (`m . v_i`, row 3). Edges
    /// side by side, so that the three compile to vector operations.
    side: [[f64; 3]; 4],
    /// Per edge `i`, in column `i`: the unit direction (rows x, y, z), and its products with the
    /// edge's two ends (rows 3 and 4).
    along: [[f64; 3]; 5],
}

const UNTRUSTED: TriangleFrame = TriangleFrame {
    plane: [f64::NAN; 4],
    side: [[f64::NAN; 3]; 4],
    along: [[f64::NAN; 3]; 5],
};

/// Triangles whose smallest angle has a sine below this (slivers, and collinear or repeated
/// vertices) get no frame: their normal's direction is too sensitive to rounding.
const LEAST_SINE: f64 = 1e-3;

impl TriangleFrame {
    /// The frame of triangle `v`, or [`UNTRUSTED`] for a sliver or degenerate one.
    ///
    /// Directions are computed from the edges scaled by a power of two to a largest coordinate
    /// in `[1, 2)` (exact), so that no product overflows or underflows whatever the model's
    /// scale; offsets from the vertices as they are. For a triangle whose angles all have a sine
    /// of at least [`LEAST_SINE`], the cross product's rounding (a few ulps of the product of
    /// two edges' lengths, at most `1e3` times the normal's length) turns the normal by at most a
    /// few thousand ulps; the edges' normals and directions follow it within a few ulps more.
    fn new(v: &[Vec3; 3]) -> TriangleFrame {
        let edges = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
        let largest = edges.iter().map(|e| e.amax()).fold(0.0, f64::max);
        if !(largest >= f64::MIN_POSITIVE * 2f64.powi(60) && largest.is_finite()) {
            return UNTRUSTED;
        }
        let s = 2f64.powi(-(largest.log2().floor() as i32));
        let e = edges.map(|e| e * s);
        let n = e[2].cross(&e[0]);
        let nn = n.norm_squared();
        let most = e.iter().map(|e| e.norm_squared()).fold(0.0, f64::max);
        // sin of every angle = |n| / (product of its two edges) >= |n| / most.
        let shaped = nn > LEAST_SINE * LEAST_SINE * most * most;
        if !shaped {
            return UNTRUSTED;
        }
        let n = n / nn.sqrt();
        let mut f = TriangleFrame {
            plane: [n.x, n.y, n.z, n.dot(&v[0])],
            ..UNTRUSTED
        };
        for i in 0..3 {
            let t = e[i].normalize();
            let m = t.cross(&n);
            let (a, b) = (v[i], v[(i + 1) % 3]);
            for (row, x) in [m.x, m.y, m.z, m.dot(&a)].into_iter().enumerate() {
                f.side[row][i] = x;
            }
            for (row, x) in [t.x, t.y, t.z, t.dot(&a), t.dot(&b)]
                .into_iter()
                .enumerate()
            {
                f.along[row][i] = x;
            }
        }
        f
    }
}

/// The frames of a ray tree's triangles, in its order (see the module's documentation).
#[derive(Clone, Debug, Default)]
pub(crate) struct TriangleBounds {
    frames: Vec<TriangleFrame>,
}

impl TriangleBounds {
    /// The frames of `tree`'s triangles (of `bvh`), or `Err(OutOfMemory)`.
    pub fn build(bvh: &Bvh, tree: &RayTree) -> Result<TriangleBounds, Error> {
        let n = bvh.num_tris();
        let mut frames = Vec::new();
        frames
            .try_reserve_exact(n)
            .map_err(|_| Error::OutOfMemory)?;
        frames.extend((0..n as u32).map(|j| TriangleFrame::new(&bvh.tri(tree.slot(j)))));
        Ok(TriangleBounds { frames })
    }

    /// Bytes held.
    pub fn memory_usage(&self) -> usize {
        self.frames.capacity() * std::mem::size_of::<TriangleFrame>()
    }

    /// The squared distance from `p` to the triangle at position `j` of the tree's order, within
    /// the rounding described at [`TriangleFrame::new`] (in distance, a few thousand ulps of the
    /// magnitudes of `p` and the triangle, times at most `1 / LEAST_SINE` where a rounded sign
    /// sends the least over the edges to the edge beside the nearest, near their common vertex);
    /// NaN for a triangle without a frame.
    ///
    /// No overflow: coordinates are at most 1e150 in magnitude (the library refuses more), so
    /// every term is below 1e302.
    #[inline(always)]
    pub fn distance_squared(&self, j: u32, p: &Vec3) -> f64 {
        let f = &self.frames[j as usize];
        let h = f.plane[0] * p.x + f.plane[1] * p.y + f.plane[2] * p.z - f.plane[3];
        let (m, t) = (&f.side, &f.along);
        let mut lateral = [0.0; 3];
        for i in 0..3 {
            let o = m[0][i] * p.x + m[1][i] * p.y + m[2][i] * p.z - m[3][i];
            let s = t[0][i] * p.x + t[1][i] * p.y + t[2][i] * p.z;
            let (before, beyond) = (t[3][i] - s, s - t[4][i]);
            let a = if before > beyond { before } else { beyond };
            let a = if a > 0.0 { a } else { 0.0 };
            // Only the edges whose outer side holds the point: the nearest point of a triangle
            // to a point outside it lies on such an edge.
            lateral[i] = if o > 0.0 {
                o * o + a * a
            } else {
                f64::INFINITY
            };
        }
        let least = |x: f64, y: f64| if y < x { y } else { x };
        let lateral = least(least(lateral[0], lateral[1]), lateral[2]);
        // Inside every edge's line: on the plane's normal through the triangle.
        let lateral = if lateral == f64::INFINITY {
            0.0
        } else {
            lateral
        };
        h * h + lateral
    }
}

impl RayTree {
    /// The frames of this tree's triangles (of `bvh`, the hierarchy it was built from), computed
    /// on the first call, or `Err(OutOfMemory)`.
    pub fn triangle_bounds(&self, bvh: &Bvh) -> Result<&TriangleBounds, Error> {
        if let Some(b) = self.points.get() {
            return Ok(b);
        }
        let b = TriangleBounds::build(bvh, self)?;
        Ok(self.points.get_or_init(|| b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::point_triangle;
    use crate::test_rng::{Random, Rng};

    /// The bound against the exact routine: within its allowance, over random triangles (well
    /// shaped, thin, huge, tiny, far off) and points near and far, on the surface, on edges and
    /// at vertices; degenerate triangles have no frame.
    #[test]
    fn bound_matches_exact_distance() {
        let mut r = Rng(33);
        let mut framed = 0;
        for round in 0..40_000 {
            let scale = [1.0, 1e-120, 1e-30, 1e30, 1e140][round % 5];
            let offset = Vec3::from(r.point(1.0)) * scale * [0.0, 1.0, 1e3][round / 5 % 3];
            let mut v = [0, 1, 2].map(|_| offset + Vec3::from(r.point(1.0)) * scale);
            match round / 15 % 6 {
                // Thin: one vertex near the opposite edge.
                1 => v[2] = v[0] + (v[1] - v[0]) * 0.4 + Vec3::from(r.point(1e-2)) * scale,
                // Degenerate: collinear or repeated.
                2 => v[2] = v[0] + (v[1] - v[0]) * 0.3,
                3 => v[1] = v[0],
                _ => {}
            }
            let f = TriangleFrame::new(&v);
            let q = match round / 90 % 5 {
                // On the triangle, on an edge, at a vertex.
                0 => {
                    let (a, b) = (r.unit(), r.unit());
                    let (a, b) = if a + b > 1.0 {
                        (1.0 - a, 1.0 - b)
                    } else {
                        (a, b)
                    };
                    v[0] + (v[1] - v[0]) * a + (v[2] - v[0]) * b
                }
                1 => v[1] + (v[2] - v[1]) * r.unit(),
                2 => v[2],
                3 => offset + Vec3::from(r.point(3.0)) * scale,
                _ => offset + Vec3::from(r.point(1e6)) * scale,
            };
            let bounds = TriangleBounds { frames: vec![f] };
            let d2 = bounds.distance_squared(0, &q);
            let exact = point_triangle(&q, &v).distance;
            let magnitude = q.abs().sum() + v.iter().map(|x| x.abs().sum()).fold(0.0, f64::max);
            if f.plane[0].is_nan() {
                assert!(d2.is_nan());
                continue;
            }
            framed += 1;
            let gap = (d2.sqrt() - exact).abs();
            assert!(
                gap <= 1e-10 * magnitude,
                "{round}: {v:?} {q:?}: bound {} exact {exact}",
                d2.sqrt()
            );
        }
        assert!(framed > 20_000, "{framed}");
    }
}
