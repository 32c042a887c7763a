//! Refit: new coordinates for a built hierarchy's triangles, without rebuilding its tree.
//!
//! Every inner node keeps the frame it was built with and gets new extents, bottom-up (children
//! have larger indices than their parent, so one backward pass over the node array visits every
//! child before its parent): its swept sphere volume, of the kind it had, is fitted around its
//! children's cores' corners padded with their radii (a leaf child: its triangle's vertices), and
//! its box around their boxes (a leaf child: the vertices). O(1) per node, O(n) in all. The
//! volumes take an allowance for rounding (see [`Ssv::fit_balls`], [`Obb::enclosing`]) so that
//! every node contains its triangles exactly as its `contains` measures it, as after a build; the
//! queries' own rounding allowances then hold unchanged.
//!
//! A refitted volume is looser than a rebuilt one (it contains its children's volumes, not just
//! its triangles, and keeps a frame chosen for the old shape): queries stay exact but may test
//! more pairs as the shape drifts from the one the tree was built on (see BENCHMARKS.md, Refit).

use super::build::share_vertices;
use super::{Bvh, Node, NodeBox, NodeKind, VolumeKind};
use crate::bounding_volume::{Obb, Ssv, SsvKind};
use crate::error::Error;
use crate::geometry::Tri;
use crate::math::Vec3;

impl Bvh {
    /// Moves the triangles to `tris`, given in the order they were added to the build (each
    /// triangle's insertion index, [`Bvh::added`]), and refits every volume. `tris` has one entry
    /// per triangle and only accepted coordinates (the model checks both). `volume` is the kind
    /// the hierarchy was built with.
    ///
    /// `Err(ModelOutOfMemory)` if the new vertex arrays cannot be allocated; the hierarchy is then
    /// unchanged (everything that can fail comes before the first write).
    pub fn refit(&mut self, tris: &[Tri], volume: VolumeKind) -> Result<(), Error> {
        debug_assert_eq!(tris.len(), self.num_tris());
        let mut corners: Vec<Tri> = Vec::new();
        corners
            .try_reserve_exact(tris.len())
            .map_err(|_| Error::ModelOutOfMemory)?;
        corners.extend(self.added.iter().map(|&k| tris[k as usize]));
        // Vertices equal before may differ now and the reverse: share them afresh.
        let (verts, faces) = share_vertices(&corners)?;
        drop(corners);
        self.verts = verts;
        self.faces = faces;
        // The winding number's boundary edges index the vertices shared at the last build or refit:
        // made again on the next signed distance.
        self.boundary = std::sync::OnceLock::new();
        // The ray tree's boxes are the old vertices': made again on the next ray cast.
        self.ray = std::sync::OnceLock::new();
        // Shared afresh: distinct bit patterns.
        self.distinct = std::sync::OnceLock::from(!super::has_negative_zero(&self.verts));

        let kind = match volume {
            VolumeKind::Pss => Some(SsvKind::Point),
            VolumeKind::Lss => Some(SsvKind::Line),
            VolumeKind::Rss => Some(SsvKind::Rect),
            // Each node keeps the kind it was given.
            VolumeKind::Hybrid => None,
        };
        for i in (0..self.nodes.len()).rev() {
            let node = &self.nodes[i];
            let frame = node.frame();
            let kind = kind.unwrap_or_else(|| node.ssv().kind());
            // Up to four core corners from each child, or three vertices.
            let mut centres = [Vec3::zeros(); 8];
            let mut pads = [0.0f64; 8];
            let mut points = [Vec3::zeros(); 6];
            let mut boxes = [Obb {
                axes: frame,
                center: Vec3::zeros(),
                half: Vec3::zeros(),
            }; 2];
            let (mut nc, mut np, mut nb) = (0usize, 0usize, 0usize);
            for c in node.children {
                match c.kind() {
                    NodeKind::Leaf(t) => {
                        for v in self.tri(t) {
                            centres[nc] = v;
                            points[np] = v;
                            nc += 1;
                            np += 1;
                        }
                    }
                    NodeKind::Inner(j) => {
                        let child = &self.nodes[j];
                        let ssv = child.ssv();
                        let mut k = [Vec3::zeros(); 4];
                        let nk = ssv.core_corners(&mut k);
                        for &corner in &k[..nk] {
                            centres[nc] = corner;
                            pads[nc] = ssv.radius;
                            nc += 1;
                        }
                        boxes[nb] = self.boxes[j].obb(child);
                        nb += 1;
                    }
                }
            }
            let ssv = Ssv::fit_balls(kind, &frame, &centres[..nc], &pads[..nc]);
            let obb = Obb::enclosing(&frame, &points[..np], &boxes[..nb]);
            let children = node.children;
            let mut new = Node::new(&ssv);
            new.children = children;
            self.nodes[i] = new;
            self.boxes[i] = NodeBox::new(&obb);
        }
        self.scale = Bvh::scale_bound(Bvh::inner_scale(&self.nodes), &self.verts);
        self.tiny = Bvh::has_tiny(&self.verts, &self.faces);
        Ok(())
    }
}
