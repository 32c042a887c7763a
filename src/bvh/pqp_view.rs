//! PQP 1.3's view of a hierarchy: what a PQP program reads in `PQP_Model::b`.
//!
//! PQP kept every node, leaves included, in one array of `2n - 1` volumes for `n` triangles: the
//! root first, and a node's two children in consecutive slots, given out depth first (when a node
//! is expanded its children take the next two free slots, then the first child's subtree is laid
//! out before the second's). A leaf names its triangle instead of a child. Each volume carries its
//! frame, a rectangle swept sphere and an oriented box on it, stored relative to its parent's
//! (the root's in model coordinates), so that a traversal composes one relative pose per step.
//!
//! This hierarchy stores only inner nodes, in model coordinates, with leaves computed from their
//! triangles; [`Bvh::pqp_view`] lays it out PQP's way. Nothing here is used by the queries.

use super::{Bvh, MAX_DEPTH, NodeRef};
use crate::error::Error;
use crate::math::{Mat3, Vec3};

/// One volume of PQP's layout (see the module's doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PqpBv {
    /// The frame: its columns are the axes, relative to the parent's frame (`Rp^T R` with `Rp`
    /// and `R` both in model coordinates); the root's in model coordinates.
    pub rot: Mat3,
    /// The rectangle's corner, relative to the parent's corner in the parent's frame
    /// (`Rp^T (c - cp)`); the root's in model coordinates.
    pub corner: Vec3,
    /// The rectangle's sides along the first two axes (`0` for a point or segment core).
    pub lengths: [f64; 2],
    /// The swept sphere's radius.
    pub radius: f64,
    /// The box's centre, relative to the parent's centre in the parent's frame; the root's in
    /// model coordinates.
    pub center: Vec3,
    /// The box's half extents along the axes.
    pub half: Vec3,
    /// `>= 0`: the first of the two children's slots; `< 0`: a leaf, holding the triangle added
    /// in position `-first_child - 1`.
    pub first_child: i32,
}

/// A volume's frame, corner and centre in model coordinates: what its children are relative to.
#[derive(Clone, Copy)]
struct Absolute {
    rot: Mat3,
    corner: Vec3,
    center: Vec3,
}

impl Bvh {
    /// Lays the hierarchy out as PQP 1.3 did (see the module's doc): calls `put(slot, bv)` once
    /// for every slot of `0..2 * num_tris() - 1`, in no particular order of slots.
    ///
    /// Inner volumes are the nodes' own; a leaf's are those the queries use for it (the
    /// rectangle around its triangle and the box fitted on that rectangle's axes). Rectangle and
    /// box share each volume's frame, as in PQP.
    ///
    /// `Err(ModelOutOfMemory)` if the work list cannot be allocated.
    pub(crate) fn pqp_view(&self, mut put: impl FnMut(usize, PqpBv)) -> Result<(), Error> {
        // (slot, node, the parent's absolute frame or None for the root). Depth first, the first
        // child on top: the stack holds at most one pending sibling per level, and the root.
        let mut work: Vec<(usize, NodeRef, Option<Absolute>)> = Vec::new();
        work.try_reserve_exact(MAX_DEPTH + 2)
            .map_err(|_| Error::ModelOutOfMemory)?;
        work.push((0, self.root(), None));
        let mut next = 1usize;
        while let Some((slot, r, parent)) = work.pop() {
            let (ssv, obb) = (self.ssv(r), self.obb(r));
            debug_assert_eq!(ssv.axes, obb.axes);
            let here = Absolute {
                rot: ssv.axes,
                corner: ssv.origin,
                center: obb.center,
            };
            let first_child = if !r.is_leaf() {
                let [c0, c1] = self.children(r);
                let first = next;
                next += 2;
                work.push((first + 1, c1, Some(here)));
                work.push((first, c0, Some(here)));
                first as i32
            } else {
                -(self.added[r.triangle()] as i32) - 1
            };
            let relative = match parent {
                None => here,
                Some(p) => Absolute {
                    rot: p.rot.tr_mul(&here.rot),
                    corner: p.rot.tr_mul(&(here.corner - p.corner)),
                    center: p.rot.tr_mul(&(here.center - p.center)),
                },
            };
            put(
                slot,
                PqpBv {
                    rot: relative.rot,
                    corner: relative.corner,
                    lengths: ssv.lengths,
                    radius: ssv.radius,
                    center: relative.center,
                    half: obb.half,
                    first_child,
                },
            );
        }
        debug_assert_eq!(next, 2 * self.num_tris() - 1);
        Ok(())
    }

    /// Calls `put(k, triangle, id)` for every triangle, `k` being its position in the order added
    /// (each of `0..num_tris()` once, in no particular order).
    pub(crate) fn for_each_added(&self, mut put: impl FnMut(usize, [Vec3; 3], i32)) {
        for (t, (&k, &id)) in self.added.iter().zip(&self.ids).enumerate() {
            put(k as usize, self.tri(t), id);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bounding_volume::BoundingVolume;
    use crate::bvh::{CollisionVolume, VolumeKind};
    use crate::test_rng::Lcg;

    /// The layout's tree, with each volume's absolute frame recomposed from its parent's: every
    /// slot is filled once, children come after their parent in consecutive slots, the
    /// recomposed volumes equal the hierarchy's (up to the composition's rounding), and every
    /// leaf names its triangle in the order added.
    #[test]
    fn the_view_is_pqp_layout_of_the_hierarchy() {
        let mut s = Lcg(3);
        for n in [1usize, 2, 3, 7, 64, 501] {
            let tris: Vec<([Vec3; 3], i32)> = (0..n)
                .map(|i| {
                    let c = Vec3::new(s.unit(), s.unit(), s.unit()) * 10.0;
                    let mut v = || c + Vec3::new(s.unit(), s.unit(), s.unit());
                    ([v(), v(), v()], 100 + i as i32)
                })
                .collect();
            let bvh = Bvh::build(tris.clone(), VolumeKind::Rss, CollisionVolume::Obb).unwrap();
            let mut slots: Vec<Option<PqpBv>> = vec![None; 2 * n - 1];
            bvh.pqp_view(|k, bv| assert!(slots[k].replace(bv).is_none(), "slot {k} twice"))
                .unwrap();
            let slots: Vec<PqpBv> = slots.into_iter().map(Option::unwrap).collect();
            // Walk the layout and the hierarchy together, composing frames.
            let mut stack = vec![(
                0usize,
                bvh.root(),
                Mat3::identity(),
                Vec3::zeros(),
                Vec3::zeros(),
            )];
            let mut leaves = vec![false; n];
            let mut next = 1;
            while let Some((k, r, prot, pcorner, pcenter)) = stack.pop() {
                let bv = slots[k];
                let rot = prot * bv.rot;
                let corner = prot * bv.corner + pcorner;
                let center = prot * bv.center + pcenter;
                let (ssv, obb) = (bvh.ssv(r), bvh.obb(r));
                assert!((rot - ssv.axes).amax() < 1e-12, "slot {k}");
                assert!((corner - ssv.origin).amax() < 1e-9, "slot {k}");
                assert!((center - obb.center).amax() < 1e-9, "slot {k}");
                assert_eq!(
                    (bv.lengths, bv.radius, bv.half),
                    (ssv.lengths, ssv.radius, obb.half)
                );
                if !r.is_leaf() {
                    // Depth first: a node's children take the next two free slots.
                    assert_eq!(bv.first_child as usize, next, "slot {k}");
                    next += 2;
                    let [c0, c1] = bvh.children(r);
                    let f = bv.first_child as usize;
                    stack.push((f + 1, c1, rot, corner, center));
                    stack.push((f, c0, rot, corner, center));
                } else {
                    let t = (-bv.first_child - 1) as usize;
                    assert!(!std::mem::replace(&mut leaves[t], true));
                    assert_eq!(bvh.tri(r.triangle()), tris[t].0);
                    for v in &tris[t].0 {
                        assert!(ssv.contains(v, 0.0) && obb.contains(v, 0.0));
                    }
                }
            }
            assert!(leaves.iter().all(|&x| x));
            // The root is in model coordinates, exactly.
            assert_eq!(slots[0].rot, bvh.ssv(bvh.root()).axes);
            assert_eq!(slots[0].corner, bvh.ssv(bvh.root()).origin);
            let mut seen = vec![false; n];
            bvh.for_each_added(|k, t, id| {
                assert!(!std::mem::replace(&mut seen[k], true));
                assert_eq!((t, id), tris[k]);
            });
            assert!(seen.iter().all(|&x| x));
        }
    }
}
