//! Saved models: a built model as bytes (pqp_model_serialize) and back (pqp_model_deserialize).

use super::legacy::LegacyView;
use super::model::pqp_model;
use super::{deref, deref_mut, status};
use crate::error::Error;
use crate::model::Model;
use std::ffi::{c_int, c_void};

/// Saves a built model into a buffer, to be loaded later, here or on another machine, by
/// pqp_model_deserialize (much faster than building it again). The bytes hold everything the model
/// is: its triangles and ids in the order added, its hierarchy and its volume choices. They are
/// the same on every machine (little-endian, whatever the host), start with a magic and a version
/// and end with a checksum over every byte; docs/saved-model-format.md describes them. About 184
/// bytes per triangle.
///
/// Call it first with buffer NULL to learn the size: it returns PQP_ERR_BUFFER_TOO_SMALL with the
/// size in *size. Then allocate that much and call again.
///
/// @param m         the model (built).
/// @param buffer    where to write, capacity bytes (any alignment); NULL to ask for the size.
/// @param capacity  bytes available at buffer.
/// @param size      receives the number of bytes written, or needed.
/// @return PQP_OK (*size bytes written at buffer); PQP_ERR_NULL_POINTER if m or size is NULL;
///         PQP_ERR_UNPROCESSED_MODEL if m is not built (nothing written); PQP_ERR_BUFFER_TOO_SMALL
///         PQP_ERR_NOT_A_TRIANGLE_MESH if m holds a primitive (pqp_model_set_sphere, ...);
///         if buffer is NULL or capacity is less than the model needs: *size is set to the bytes
///         needed and nothing is written at buffer; PQP_ERR_INTERNAL on an internal fault.
/// Thread safety: may run concurrently with queries and other getters on m (a built model may be
///                saved while other threads query it), not with build calls on m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_serialize(
    m: *const pqp_model,
    buffer: *mut c_void,
    capacity: usize,
    size: *mut usize,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = deref(m)?;
            if size.is_null() {
                return Err(Error::NullPointer);
            }
            let needed = m.model.serialized_size()?;
            if buffer.is_null() || capacity < needed {
                size.write(needed);
                return Err(Error::BufferTooSmall);
            }
            // `buffer` is not NULL and holds `capacity >= needed` writable bytes (the caller's
            // contract); bytes need no alignment.
            let out = std::slice::from_raw_parts_mut(buffer.cast::<u8>(), needed);
            let written = m.model.serialize_into(out)?;
            size.write(written);
            Ok(())
        })
    }
}

/// Loads a model saved by pqp_model_serialize into m, replacing whatever m held (empty, being
/// built, or built): m is then built, equal to the saved model (every query answers as the saved
/// model did, with the same counts of bound and triangle tests) with its volume choices. Nothing is
/// rebuilt: the bytes are checked and copied, in time linear in size (but the volumes: each vertex
/// is checked against each node above it).
///
/// Every byte is checked before m is touched: the magic, the version, the size, the checksum, and
/// then the contents (every index in range, the hierarchy a tree over the triangles of the
/// build's depth, coordinates finite and within 1e150, counts consistent, and every bounding
/// volume containing the triangles below it), so that no buffer, truncated, corrupted or crafted,
/// can crash, hang or give a model a query could misuse, and an accepted one, whatever its
/// checksum says, gives a model that answers right for the triangles it holds. The volumes are
/// checked to within a rounding allowance of 2^-45 S (about 2.8e-14 S; S the largest
/// |x| + |y| + |z| of a vertex), in time O(n log n) (each vertex against each node above it,
/// in straight passes: at most 73 n tests). Buffers of every
/// version of the format load (version 1, checksum Fletcher-64, and version 2, CRC-32C);
/// pqp_model_serialize writes version 2.
///
/// @param m       the model to replace.
/// @param buffer  the saved model, size bytes (any alignment).
/// @param size    its length in bytes: exactly what pqp_model_serialize gave.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if m or buffer is NULL; PQP_ERR_INVALID_DATA if the
///         bytes are not a saved model of this format and version (truncated, longer, corrupted,
///         or invalid contents); PQP_ERR_MODEL_OUT_OF_MEMORY if the model could not be allocated;
///         PQP_ERR_INTERNAL on an internal fault. On any error m is unchanged.
/// Thread safety: must not run concurrently with any other call using m.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_model_deserialize(
    m: *mut pqp_model,
    buffer: *const c_void,
    size: usize,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let m = deref_mut(m)?;
            if buffer.is_null() {
                return Err(Error::NullPointer);
            }
            // No saved model is that long, and a slice may not be.
            if size > isize::MAX as usize {
                return Err(Error::InvalidData);
            }
            // `buffer` is not NULL and holds `size` readable bytes (the caller's contract).
            let bytes = std::slice::from_raw_parts(buffer.cast::<u8>(), size);
            let model = Model::from_bytes(bytes)?;
            // PQP 1.3's views were of the old contents.
            m.model = model;
            m.view = LegacyView::default();
            Ok(())
        })
    }
}
