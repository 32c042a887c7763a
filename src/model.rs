//! A triangle model and PQP's build protocol: begin, add triangles, end.

pub use crate::bvh::{CollisionVolume, VolumeKind};

use crate::bvh::{Bvh, try_copy};
use crate::error::{Error, MAX_COORDINATE};
use crate::geometry::Tri;
use crate::math::Vec3;
use std::sync::atomic::{AtomicU64, Ordering};

// Swept-sphere primitives as models: `Model::set_sphere`, `set_capsule`, `set_box`.
mod primitive;
// Saved models: `Model::to_bytes`, `serialize_into`, `from_bytes`.
mod saved;

pub(crate) use primitive::Core;
pub use primitive::Primitive;

/// Where a model is in PQP's build protocol ([`Model::build_state`]); PQP 1.3's `build_state`,
/// whose `PQP_BUILD_STATE_EMPTY`, `_BEGUN` and `_PROCESSED` are 0, 1 and 2 as here.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BuildState {
    /// Fresh: `begin` expected (an `add` begins implicitly, as PQP does). `begin` clears a model
    /// and begins it, so only a fresh model is empty.
    Empty = 0,
    /// Begun (by `begin`, or by an `add` on an empty model), and no successful `end` since.
    Begun = 1,
    /// `end` succeeded: the hierarchy is built and the model is immutable.
    Built = 2,
}

/// A triangle model, built by [`begin`](Model::begin), [`add_triangle`](Model::add_triangle) and
/// [`end`](Model::end), exactly as PQP 1.3's `PQP_Model`.
///
/// A built model is immutable; it is `Send + Sync`, so any number of threads may query it at once.
///
/// ```
/// use pqp::Model;
/// let mut m = Model::new();
/// m.begin(1).unwrap();
/// m.add_triangle([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 7).unwrap();
/// m.end().unwrap();
/// assert_eq!(m.num_triangles(), 1);
/// assert!(m.is_built());
/// ```
///
/// `clone` (or [`try_clone`](Model::try_clone), which reports a failed allocation instead of
/// aborting) gives a deep, independent copy in the same state.
#[derive(Clone, Debug)]
pub struct Model {
    state: BuildState,
    /// Triangles in the order added, until `end` hands them to the hierarchy.
    pending: Vec<(Tri, i32)>,
    bvh: Option<Bvh>,
    /// Identifies this build of this model, for the triangle cache kept in distance results. A
    /// clone keeps it: its hierarchy is the same, bit for bit, so what a result cached for one
    /// (triangle slots, node pairs) holds for the other.
    uid: u64,
    /// The hierarchy's volumes, chosen before `end`.
    volume: VolumeKind,
    collision: CollisionVolume,
    /// The primitive a built model holds instead of triangles (then `bvh` is `None`).
    primitive: Option<Primitive>,
}

impl Default for Model {
    fn default() -> Self {
        Model::new()
    }
}

static NEXT_UID: AtomicU64 = AtomicU64::new(1);

impl Model {
    /// An empty model.
    pub fn new() -> Model {
        Model {
            state: BuildState::Empty,
            pending: Vec::new(),
            bvh: None,
            uid: 0,
            volume: VolumeKind::default(),
            collision: CollisionVolume::default(),
            primitive: None,
        }
    }

    /// Chooses the swept sphere volume the hierarchy will be built with (default
    /// [`VolumeKind::Rss`]). Any time before [`end`](Model::end); the choice stays for later builds
    /// of this model (`begin` does not reset it).
    ///
    /// `Err(BuildOutOfSequence)` on a built model (its hierarchy is immutable); the choice is then
    /// not changed.
    ///
    /// ```
    /// use pqp::{Model, VolumeKind};
    /// let mut m = Model::new();
    /// m.set_volume(VolumeKind::Hybrid).unwrap();
    /// m.add_triangle([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0).unwrap();
    /// m.end().unwrap();
    /// assert_eq!(m.volume(), VolumeKind::Hybrid);
    /// assert!(m.set_volume(VolumeKind::Rss).is_err());
    /// ```
    pub fn set_volume(&mut self, volume: VolumeKind) -> Result<(), Error> {
        if self.state == BuildState::Built {
            return Err(Error::BuildOutOfSequence);
        }
        self.volume = volume;
        Ok(())
    }

    /// Chooses the volume collision queries test this model's nodes with (default
    /// [`CollisionVolume::Obb`]). As [`set_volume`](Model::set_volume): before `end`, kept across
    /// builds, `Err(BuildOutOfSequence)` on a built model.
    pub fn set_collision_volume(&mut self, collision: CollisionVolume) -> Result<(), Error> {
        if self.state == BuildState::Built {
            return Err(Error::BuildOutOfSequence);
        }
        self.collision = collision;
        Ok(())
    }

    /// The swept sphere volume chosen for the hierarchy.
    pub fn volume(&self) -> VolumeKind {
        self.volume
    }

    /// The collision volume chosen.
    pub fn collision_volume(&self) -> CollisionVolume {
        self.collision
    }

    /// Starts a model, reserving room for `capacity_hint` triangles (a hint only).
    ///
    /// On a model that is not fresh (begun, or built) the model is cleared and
    /// `Err(BuildOutOfSequence)` is returned, as PQP does; the model is then ready for `add_triangle`.
    pub fn begin(&mut self, capacity_hint: usize) -> Result<(), Error> {
        let was_empty = self.state == BuildState::Empty;
        self.pending = Vec::new();
        self.bvh = None;
        self.primitive = None;
        self.uid = 0;
        // A hint is only a hint: a huge one must not abort the process.
        let _ = self.pending.try_reserve(capacity_hint.min(1 << 24));
        self.state = BuildState::Begun;
        if was_empty {
            Ok(())
        } else {
            Err(Error::BuildOutOfSequence)
        }
    }

    /// Adds a triangle with the caller's `id` (returned in query answers).
    ///
    /// Before `begin` it begins implicitly (PQP's behaviour). After `end` it is ignored and returns
    /// `Err(BuildOutOfSequence)`. A vertex with a NaN, infinite, or huge (> [`MAX_COORDINATE`])
    /// coordinate is refused with `Err(NonFiniteCoordinate)`: the triangle is not stored and the
    /// model stays usable, with the triangles it had; an empty model is begun all the same (the
    /// implicit begin comes first), so [`build_state`](Model::build_state) is then
    /// [`BuildState::Begun`]. Degenerate triangles (segments, points) are accepted.
    pub fn add_triangle(
        &mut self,
        p1: [f64; 3],
        p2: [f64; 3],
        p3: [f64; 3],
        id: i32,
    ) -> Result<(), Error> {
        match self.state {
            BuildState::Built => return Err(Error::BuildOutOfSequence),
            BuildState::Empty => self.state = BuildState::Begun,
            BuildState::Begun => {}
        }
        let ok = p1
            .iter()
            .chain(p2.iter())
            .chain(p3.iter())
            .all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE);
        if !ok {
            return Err(Error::NonFiniteCoordinate);
        }
        if self.pending.len() >= i32::MAX as usize {
            return Err(Error::ModelOutOfMemory);
        }
        self.pending
            .try_reserve(1)
            .map_err(|_| Error::ModelOutOfMemory)?;
        self.pending
            .push(([Vec3::from(p1), Vec3::from(p2), Vec3::from(p3)], id));
        Ok(())
    }

    /// Builds the bounding-volume hierarchy. After it the model is immutable and can be queried.
    ///
    /// As PQP 1.3's `EndModel`: `Err(BuildOutOfSequence)` only if already built (the model stays
    /// built); `Err(BuildEmptyModel)` if the model holds no triangle, begun or not (a fresh model
    /// included): it stays unbuilt, in the state it was in, until triangles are added and `end`
    /// succeeds; `Err(ModelOutOfMemory)` if the hierarchy could not be allocated.
    pub fn end(&mut self) -> Result<(), Error> {
        self.end_threads(1)
    }

    /// [`end`](Model::end) on up to `threads` threads (0: as many as the machine has cores, as
    /// [`std::thread::available_parallelism`] tells). The hierarchy, and so every query answer, is
    /// the same, bit for bit, whatever the number; only the time differs (1: this thread only, as
    /// `end`). More threads than cores is allowed, and no more are started than there are
    /// subtrees of a few thousand triangles to build (a small model is built on this thread).
    /// Errors as `end`.
    ///
    /// ```
    /// use pqp::Model;
    /// let mut m = Model::new();
    /// m.add_triangle([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 7).unwrap();
    /// m.end_threads(0).unwrap();
    /// assert!(m.is_built());
    /// ```
    pub fn end_threads(&mut self, threads: usize) -> Result<(), Error> {
        match self.state {
            BuildState::Built => return Err(Error::BuildOutOfSequence),
            BuildState::Empty => return Err(Error::BuildEmptyModel),
            BuildState::Begun if self.pending.is_empty() => return Err(Error::BuildEmptyModel),
            BuildState::Begun => {}
        }
        let tris = std::mem::take(&mut self.pending);
        let threads = match threads {
            0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
            t => t,
        };
        let bvh = Bvh::build_threads(tris, self.volume, self.collision, threads)?;
        self.bvh = Some(bvh);
        self.state = BuildState::Built;
        self.uid = NEXT_UID.fetch_add(1, Ordering::Relaxed);
        Ok(())
    }

    /// Moves the triangles of a built model: `tris[k]` holds the new vertices `(p1, p2, p3)` of the
    /// `k`th triangle added; ids, the tree and each node's frame stay, and every bounding volume
    /// is refitted bottom-up around the new triangles in O(n), without a rebuild. Every query
    /// stays exact; as the shape drifts from the one the model was built on the volumes get
    /// looser and queries slower (rebuild then: see BENCHMARKS.md, Refit, and `pqp_model_refit`).
    /// Like the build calls it needs the model to itself (`&mut self`).
    ///
    /// Errors, with the model unchanged: `Err(UnprocessedModel)` if the model is not built,
    /// `Err(InvalidArgument)` if `tris.len()` is not [`num_triangles`](Model::num_triangles),
    /// `Err(NonFiniteCoordinate)` if a coordinate is NaN, infinite or beyond
    /// [`MAX_COORDINATE`] in magnitude (as [`add_triangle`](Model::add_triangle)),
    /// `Err(ModelOutOfMemory)` if the new vertex arrays cannot be allocated,
    /// `Err(NotATriangleMesh)` if the model holds a [`Primitive`].
    ///
    /// ```
    /// use pqp::Model;
    /// let mut m = Model::from_triangles([([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 7)]).unwrap();
    /// m.refit(&[[[0.0, 0.0, 1.0], [2.0, 0.0, 1.0], [0.0, 2.0, 1.0]]]).unwrap();
    /// assert!(m.refit(&[]).is_err());
    /// ```
    pub fn refit(&mut self, tris: &[[[f64; 3]; 3]]) -> Result<(), Error> {
        if self.primitive.is_some() {
            return Err(Error::NotATriangleMesh);
        }
        let volume = self.volume;
        let bvh = match (&self.state, &mut self.bvh) {
            (BuildState::Built, Some(b)) => b,
            _ => return Err(Error::UnprocessedModel),
        };
        if tris.len() != bvh.num_tris() {
            return Err(Error::InvalidArgument);
        }
        let ok = tris
            .as_flattened()
            .as_flattened()
            .iter()
            .all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE);
        if !ok {
            return Err(Error::NonFiniteCoordinate);
        }
        let mut new: Vec<Tri> = Vec::new();
        new.try_reserve_exact(tris.len())
            .map_err(|_| Error::ModelOutOfMemory)?;
        new.extend(tris.iter().map(|t| t.map(Vec3::from)));
        bvh.refit(&new, volume)?;
        // A new build id: what results cached for the old shape (closest pairs, fronts with
        // their bounds) must not be reused.
        self.uid = NEXT_UID.fetch_add(1, Ordering::Relaxed);
        Ok(())
    }

    /// A deep copy of the model in its state (empty, being built, or built; the volume choices
    /// too), as `clone` makes it, but `Err(ModelOutOfMemory)` when its storage cannot be allocated
    /// (`clone` aborts the process then). The copy answers every query exactly as the original;
    /// building or dropping either never affects the other.
    ///
    /// ```
    /// use pqp::Model;
    /// let tri = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 4);
    /// let a = Model::from_triangles([tri]).unwrap();
    /// let b = a.try_clone().unwrap();
    /// drop(a);
    /// assert!(b.is_built());
    /// ```
    pub fn try_clone(&self) -> Result<Model, Error> {
        Ok(Model {
            state: self.state,
            pending: try_copy(&self.pending)?,
            bvh: match &self.bvh {
                Some(b) => Some(b.try_clone()?),
                None => None,
            },
            uid: self.uid,
            volume: self.volume,
            collision: self.collision,
            primitive: self.primitive,
        })
    }

    /// Builds a model from `(p1, p2, p3, id)` triangles in one call.
    ///
    /// ```
    /// let m = pqp::Model::from_triangles([([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0)]).unwrap();
    /// assert_eq!(m.num_triangles(), 1);
    /// ```
    pub fn from_triangles<I>(tris: I) -> Result<Model, Error>
    where
        I: IntoIterator<Item = ([f64; 3], [f64; 3], [f64; 3], i32)>,
    {
        let mut m = Model::new();
        m.begin(0)?;
        for (a, b, c, id) in tris {
            m.add_triangle(a, b, c, id)?;
        }
        m.end()?;
        Ok(m)
    }

    /// Whether `end` has succeeded.
    pub fn is_built(&self) -> bool {
        self.state == BuildState::Built
    }

    /// Where the model is in the build protocol.
    ///
    /// ```
    /// use pqp::{BuildState, Model};
    /// let mut m = Model::new();
    /// assert_eq!(m.build_state(), BuildState::Empty);
    /// m.add_triangle([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0).unwrap();
    /// assert_eq!(m.build_state(), BuildState::Begun);
    /// m.end().unwrap();
    /// assert_eq!(m.build_state(), BuildState::Built);
    /// ```
    pub fn build_state(&self) -> BuildState {
        self.state
    }

    /// Number of triangles stored (added so far, or in the built model; 0 for a [`Primitive`]).
    pub fn num_triangles(&self) -> usize {
        match &self.bvh {
            Some(b) => b.num_tris(),
            None => self.pending.len(),
        }
    }

    /// Bytes of memory the model holds (triangles, hierarchy and bookkeeping).
    pub fn memory_usage(&self) -> u64 {
        let pending = self.pending.capacity() * std::mem::size_of::<(Tri, i32)>();
        let bvh = self.bvh.as_ref().map_or(0, |b| b.memory_usage());
        (std::mem::size_of::<Model>() + pending + bvh) as u64
    }

    /// The hierarchy of a built triangle model (`Err(NotATriangleMesh)` for a [`Primitive`]).
    pub(crate) fn bvh(&self) -> Result<&Bvh, Error> {
        match (&self.state, &self.bvh, &self.primitive) {
            (BuildState::Built, Some(b), _) => Ok(b),
            (BuildState::Built, None, Some(_)) => Err(Error::NotATriangleMesh),
            _ => Err(Error::UnprocessedModel),
        }
    }

    /// `Ok` for a built model, a triangle model or a [`Primitive`].
    pub(crate) fn check_built(&self) -> Result<(), Error> {
        if self.primitive.is_some() {
            Ok(())
        } else {
            self.bvh().map(|_| ())
        }
    }

    /// Calls `put(k, triangle, id)` for every triangle the model holds (added so far, or built),
    /// `k` being its position in the order added: each of `0..num_triangles()` once, in no
    /// particular order.
    pub(crate) fn for_each_added(&self, mut put: impl FnMut(usize, Tri, i32)) {
        match &self.bvh {
            Some(b) => b.for_each_added(put),
            None => {
                for (k, &(t, id)) in self.pending.iter().enumerate() {
                    put(k, t, id);
                }
            }
        }
    }

    /// Identifies this build (distinct for every successful `end` in the process).
    pub(crate) fn uid(&self) -> u64 {
        self.uid
    }
}
