//! Error codes shared by the Rust API and the C ABI.
//!
//! The first five keep PQP 1.3's names and values so that code testing for them keeps working; the
//! rest are conditions PQP never checked.

use std::fmt;

/// Why a call failed. `code()` is the value the C ABI returns (`PQP_OK` is 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(i32)]
pub enum Error {
    /// A model's storage could not be allocated (`PQP_ERR_MODEL_OUT_OF_MEMORY`).
    ModelOutOfMemory = -1,
    /// A query's working storage could not be allocated (`PQP_ERR_OUT_OF_MEMORY`).
    OutOfMemory = -2,
    /// A query was given a model whose `end` has not succeeded (`PQP_ERR_UNPROCESSED_MODEL`).
    UnprocessedModel = -3,
    /// begin/add/end called out of order (`PQP_ERR_BUILD_OUT_OF_SEQUENCE`).
    BuildOutOfSequence = -4,
    /// `end` on a model with no triangles (`PQP_ERR_BUILD_EMPTY_MODEL`).
    BuildEmptyModel = -5,
    /// A vertex coordinate is NaN, infinite, or larger in magnitude than [`MAX_COORDINATE`]; the
    /// triangle is refused and the model stays usable (`PQP_ERR_NONFINITE_COORDINATE`). Also a
    /// ray's origin (the same limits) or direction (NaN or infinite).
    NonFiniteCoordinate = -6,
    /// A rotation or translation entry is NaN, infinite, or larger in magnitude than
    /// [`MAX_COORDINATE`] (`PQP_ERR_NONFINITE_POSE`).
    NonFinitePose = -7,
    /// An argument is out of its domain: unknown contact flag, negative or NaN error bound or
    /// tolerance, queue size < 1, index out of range, zero ray direction, negative or NaN `max_t`
    /// (`PQP_ERR_INVALID_ARGUMENT`).
    InvalidArgument = -8,
    /// A required pointer was NULL (C ABI only, `PQP_ERR_NULL_POINTER`).
    NullPointer = -9,
    /// The library hit an internal fault (a caught panic); no state was changed that the caller can
    /// observe beyond the result object being reset (C ABI only, `PQP_ERR_INTERNAL`).
    Internal = -10,
    /// A point set for a convex hull does not span a volume: fewer than four distinct points, or
    /// all of them collinear or coplanar, including an empty set (`PQP_ERR_DEGENERATE_POINTS`).
    DegeneratePoints = -11,
    /// A mesh given as a convex polyhedron is not one: open, not a closed oriented sphere, a face
    /// not planar or not strictly convex, a vertex unused, or a vertex above a face (not convex,
    /// or inside out), or flat (`PQP_ERR_INVALID_CONVEX_MESH`).
    InvalidConvexMesh = -12,
    /// A buffer given to hold a saved model is missing or too small; the size it needs was reported
    /// and nothing was written (`PQP_ERR_BUFFER_TOO_SMALL`).
    BufferTooSmall = -13,
    /// Bytes given as a saved model are not one: wrong magic or version, truncated, checksum
    /// mismatch, or contents that do not make a valid model (`PQP_ERR_INVALID_DATA`).
    InvalidData = -14,
    /// The model holds a primitive (a sphere, capsule or box: `pqp_model_set_sphere` and the
    /// like), and the call needs triangles or a hierarchy: closest point, signed distance, rays,
    /// self-collision, time of contact, refit, saving, PQP 1.3's volume view
    /// (`PQP_ERR_NOT_A_TRIANGLE_MESH`).
    NotATriangleMesh = -15,
}

/// Largest accepted magnitude of a coordinate or translation. Beyond it squared lengths overflow
/// `f64`, and no bounding volume could be fitted; such input is refused rather than answered wrongly.
pub const MAX_COORDINATE: f64 = 1e150;

impl Error {
    /// The integer the C ABI returns for this error.
    pub fn code(self) -> i32 {
        self as i32
    }

    /// A short description, the same text `pqp_error_string` returns.
    pub fn message(self) -> &'static str {
        match self {
            Error::ModelOutOfMemory => "model storage could not be allocated",
            Error::OutOfMemory => "query storage could not be allocated",
            Error::UnprocessedModel => "model has not been built (end not called or failed)",
            Error::BuildOutOfSequence => "model build calls out of sequence",
            Error::BuildEmptyModel => "model has no triangles",
            Error::NonFiniteCoordinate => "vertex coordinate is not finite or too large",
            Error::NonFinitePose => "pose entry is not finite or too large",
            Error::InvalidArgument => "invalid argument",
            Error::NullPointer => "null pointer",
            Error::Internal => "internal error",
            Error::DegeneratePoints => {
                "points do not span a volume (fewer than 4 distinct, collinear or coplanar)"
            }
            Error::InvalidConvexMesh => "mesh is not a closed convex polyhedron",
            Error::BufferTooSmall => "buffer missing or too small (the needed size was reported)",
            Error::InvalidData => "data is not a valid saved model",
            Error::NotATriangleMesh => "model is a primitive, not a triangle mesh",
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (code {})", self.message(), self.code())
    }
}

impl std::error::Error for Error {}
