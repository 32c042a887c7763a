//! The bounding-volume hierarchy of a model: layout (this file) and top-down build (`build.rs`).
//!
//! Nodes live in one array, the root first; the two children of a node are adjacent. Each node
//! carries a swept sphere volume (a PSS, LSS or RSS, as the model's [`VolumeKind`] chooses) for the
//! distance and tolerance queries, and for collision when the model asks for it, and an overlap
//! volume (OBB) for collision, both fitted on the same principal axes and stored in model coordinates (a test
//! composes the relative pose with the volumes' axes, so no per-node frame chain is needed). Leaves
//! hold one triangle. Triangles are stored in leaf order so that a subtree's triangles are contiguous.

mod build;

pub(crate) use build::MAX_DEPTH;

use crate::bounding_volume::{Obb, Ssv};
use crate::geometry::Tri;
use crate::model::CollisionVolume;

/// One node of the hierarchy.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Node {
    /// Distance volume (and overlap volume when the model collides on swept spheres).
    pub ssv: Ssv,
    /// Overlap volume.
    pub obb: Obb,
    /// `>= 0`: index of the first child (the second is `child + 1`). `< 0`: a leaf holding
    /// triangle `-child - 1`.
    pub child: i32,
}

impl Node {
    /// The triangle index of a leaf, `None` for an inner node.
    #[inline]
    pub fn leaf_triangle(&self) -> Option<usize> {
        if self.child < 0 {
            Some((-(self.child as i64) - 1) as usize)
        } else {
            None
        }
    }

    /// The first child of an inner node (the second is `first + 1`).
    #[inline]
    pub fn first_child(&self) -> usize {
        self.child as usize
    }
}

/// A built hierarchy: nodes, and the triangles with their caller ids in leaf order.
#[derive(Debug)]
pub(crate) struct Bvh {
    pub nodes: Vec<Node>,
    pub tris: Vec<Tri>,
    pub ids: Vec<i32>,
    /// Which volume this model offers the collision query.
    pub collision: CollisionVolume,
}

impl Bvh {
    /// Bytes held by the hierarchy.
    pub fn memory_usage(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<Node>()
            + self.tris.capacity() * std::mem::size_of::<Tri>()
            + self.ids.capacity() * std::mem::size_of::<i32>()
            + std::mem::size_of::<Bvh>()
    }

    /// Depth of the tree (a single leaf has depth 1).
    #[cfg(test)]
    pub fn depth(&self) -> usize {
        fn rec(b: &Bvh, i: usize) -> usize {
            match b.nodes[i].leaf_triangle() {
                Some(_) => 1,
                None => {
                    let c = b.nodes[i].first_child();
                    1 + rec(b, c).max(rec(b, c + 1))
                }
            }
        }
        rec(self, 0)
    }
}
