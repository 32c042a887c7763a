//! Saved models: a built model as bytes and back, without rebuilding (the layout is the
//! hierarchy's, see `docs/saved-model-format.md`).

use super::{BuildState, Model, NEXT_UID};
use crate::bvh::Bvh;
use crate::error::Error;
use std::sync::atomic::Ordering;

impl Model {
    /// Bytes a saved copy of this built model takes ([`serialize_into`](Model::serialize_into)
    /// writes that many): about 184 per triangle. `Err(UnprocessedModel)` if it is not built.
    pub fn serialized_size(&self) -> Result<usize, Error> {
        Ok(self.bvh()?.saved_size())
    }

    /// Writes a saved copy of this built model (its triangles, ids, order added, hierarchy and
    /// volume choices) at the start of `out`, and returns how many bytes it wrote
    /// ([`serialized_size`](Model::serialized_size)). The bytes are the same on every machine
    /// (little-endian, versioned, ending with a checksum); [`from_bytes`](Model::from_bytes)
    /// reads them back.
    ///
    /// `Err(UnprocessedModel)` if the model is not built, `Err(BufferTooSmall)` if `out` is
    /// shorter than [`serialized_size`](Model::serialized_size); nothing is written then.
    ///
    /// ```
    /// use pqp::{Error, Model};
    /// let m = Model::from_triangles([([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 7)]).unwrap();
    /// let mut small = [0u8; 16];
    /// assert_eq!(m.serialize_into(&mut small), Err(Error::BufferTooSmall));
    /// let mut buf = vec![0u8; m.serialized_size().unwrap()];
    /// assert_eq!(m.serialize_into(&mut buf), Ok(buf.len()));
    /// assert_eq!(Model::from_bytes(&buf).unwrap().num_triangles(), 1);
    /// ```
    pub fn serialize_into(&self, out: &mut [u8]) -> Result<usize, Error> {
        let bvh = self.bvh()?;
        let size = bvh.saved_size();
        let out = out.get_mut(..size).ok_or(Error::BufferTooSmall)?;
        bvh.save(self.volume, out);
        Ok(size)
    }

    /// A saved copy of this built model in a new vector (see
    /// [`serialize_into`](Model::serialize_into)). `Err(UnprocessedModel)` if it is not built,
    /// `Err(ModelOutOfMemory)` if the vector could not be allocated.
    pub fn to_bytes(&self) -> Result<Vec<u8>, Error> {
        let size = self.serialized_size()?;
        let mut out = Vec::new();
        out.try_reserve_exact(size)
            .map_err(|_| Error::ModelOutOfMemory)?;
        out.resize(size, 0);
        self.serialize_into(&mut out)?;
        Ok(out)
    }

    /// The built model that [`serialize_into`](Model::serialize_into) (or
    /// [`to_bytes`](Model::to_bytes)) saved, on this machine or any other: it answers every query
    /// exactly as the saved one did, with the same counts of bound and triangle tests, and has its
    /// volume choices. Nothing is rebuilt: the arrays are copied and checked, in time linear in
    /// the size, and the volumes checked against the vertices below them, in time `O(n log n)`
    /// (several times faster than [`end`](Model::end)).
    ///
    /// `Err(InvalidData)` if `bytes` are not a saved model: another format or version, truncated,
    /// corrupted (the checksum), or contents that do not make a valid model (indices out of range,
    /// a hierarchy that is not a tree over the triangles, non-finite or out-of-range coordinates,
    /// inconsistent counts, a bounding volume that does not contain the triangles below it); every
    /// index, the tree's shape and every volume are checked, whatever the checksum says, so that
    /// an accepted buffer gives a model that answers right for the triangles it holds (each
    /// volume contains them to within `2^-45 * S`, `S` the largest `|x| + |y| + |z|` of a
    /// vertex). Reads every version of the format (docs/saved-model-format.md); writes the
    /// newest.
    /// `Err(ModelOutOfMemory)` if the model could not be allocated (allocations are bounded by
    /// the length of `bytes`).
    pub fn from_bytes(bytes: &[u8]) -> Result<Model, Error> {
        let (bvh, volume) = Bvh::load(bytes)?;
        Ok(Model {
            state: BuildState::Built,
            pending: Vec::new(),
            collision: bvh.collision,
            bvh: Some(bvh),
            uid: NEXT_UID.fetch_add(1, Ordering::Relaxed),
            volume,
            primitive: None,
        })
    }
}
