use super::ClosestPoints;
use crate::math::Vec3;

/// Closest points between segments `[p0, p1]` and `[q0, q1]` (either may have zero length).
pub fn segment_segment(p0: &Vec3, p1: &Vec3, q0: &Vec3, q1: &Vec3) -> ClosestPoints {
    let _ = (p0, p1, q0, q1);
    todo!("geometry helper")
}
