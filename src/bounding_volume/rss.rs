use super::{BoundingVolume, DistanceVolume};
use crate::math::{Mat3, RelPose, Vec3};

/// Rectangle swept sphere: the Minkowski sum of a rectangle and a sphere.
///
/// The rectangle spans `origin + s * axes.column(0) + t * axes.column(1)` for `s` in
/// `[0, lengths[0]]`, `t` in `[0, lengths[1]]`; `axes.column(2)` is its normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rss {
    /// Orthonormal axes (columns) in the model frame.
    pub axes: Mat3,
    /// The rectangle's corner, in the model frame.
    pub origin: Vec3,
    /// Side lengths along the first two axes.
    pub lengths: [f64; 2],
    /// Radius of the swept sphere.
    pub radius: f64,
}

impl BoundingVolume for Rss {
    fn fit(axes: &Mat3, points: &[Vec3]) -> Self {
        let _ = (axes, points);
        todo!("bounding volume helper")
    }
    fn contains(&self, p: &Vec3, eps: f64) -> bool {
        let _ = (p, eps);
        todo!("bounding volume helper")
    }
    fn size(&self) -> f64 {
        (self.lengths[0] * self.lengths[0] + self.lengths[1] * self.lengths[1]).sqrt()
            + 2.0 * self.radius
    }
}

impl DistanceVolume for Rss {
    fn distance(a: &Self, b: &Self, rel: &RelPose) -> f64 {
        let _ = (a, b, rel);
        todo!("bounding volume helper")
    }
}
