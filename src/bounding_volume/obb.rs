use super::{BoundingVolume, OverlapVolume};
use crate::math::{Mat3, RelPose, Vec3};

/// Oriented bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb {
    /// Orthonormal axes (columns) in the model frame.
    pub axes: Mat3,
    /// Centre, in the model frame.
    pub center: Vec3,
    /// Half extents along the axes.
    pub half: Vec3,
}

impl BoundingVolume for Obb {
    fn fit(axes: &Mat3, points: &[Vec3]) -> Self {
        let _ = (axes, points);
        todo!("bounding volume helper")
    }
    fn contains(&self, p: &Vec3, eps: f64) -> bool {
        let _ = (p, eps);
        todo!("bounding volume helper")
    }
    fn size(&self) -> f64 {
        self.half.norm() * 2.0
    }
}

impl OverlapVolume for Obb {
    fn overlap(a: &Self, b: &Self, rel: &RelPose) -> bool {
        let _ = (a, b, rel);
        todo!("bounding volume helper")
    }
}
