//! The volumes a model's hierarchy is built with, chosen by the caller before the build (see
//! [`Model::set_volume`](crate::Model::set_volume)). Here, below the model, as the builder and the
//! queries read them; `pqp::VolumeKind`, `pqp::CollisionVolume` and `pqp::model::...` re-export
//! them.

/// The swept sphere volume a model's hierarchy is built with, for the distance and tolerance
/// queries (and for collision with [`CollisionVolume::Ssv`]). Chosen before [`Model::end`](crate::Model::end); the
/// default, [`VolumeKind::Rss`], is PQP's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum VolumeKind {
    /// Rectangle swept spheres everywhere (PQP's choice): the tightest fit, the dearest test.
    #[default]
    Rss,
    /// Point swept spheres (spheres) everywhere: the cheapest test, the loosest fit.
    Pss,
    /// Line swept spheres (capsules) everywhere.
    Lss,
    /// Each node takes the kind whose fitted volume is smallest: spheres where the triangles are
    /// round, capsules where they are long, rectangles where they are flat. Measured fastest (see
    /// `examples/volume_family.rs`); building costs about twice as much, as it fits all three.
    Hybrid,
}

/// The volume the collision query tests a model's nodes with. Chosen before [`Model::end`](crate::Model::end); the
/// default, [`CollisionVolume::Obb`], is PQP's. Collision runs on swept sphere volumes only when
/// both models ask for it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CollisionVolume {
    /// Oriented bounding boxes (PQP's choice).
    #[default]
    Obb,
    /// The model's swept sphere volumes (see [`VolumeKind`]): two may overlap when their distance
    /// bound is 0.
    Ssv,
}
