use super::{ClosestPoints, Tri};

/// Distance between two triangles with a closest point on each (`p` on `a`, `q` on `b`). When
/// they intersect or touch, the distance is 0 and `p == q` is a common point.
pub fn tri_distance(a: &Tri, b: &Tri) -> ClosestPoints {
    let _ = (a, b);
    todo!("geometry helper")
}
