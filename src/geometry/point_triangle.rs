use super::{ClosestPoints, Tri};
use crate::math::Vec3;

/// Closest point of triangle `t` to point `p`: `ClosestPoints { p: *p, q: on the triangle, .. }`.
pub fn point_triangle(p: &Vec3, t: &Tri) -> ClosestPoints {
    let _ = (p, t);
    todo!("geometry helper")
}
