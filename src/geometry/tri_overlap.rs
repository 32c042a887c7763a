use super::Tri;

/// Whether two triangles share a point. Touching and coplanar overlap count as contact.
pub fn tri_overlap(a: &Tri, b: &Tri) -> bool {
    let _ = (a, b);
    todo!("geometry helper")
}
