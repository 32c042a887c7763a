//! Error texts and the library's version.

use super::{
    PQP_ERR_BUFFER_TOO_SMALL, PQP_ERR_BUILD_EMPTY_MODEL, PQP_ERR_BUILD_OUT_OF_SEQUENCE,
    PQP_ERR_DEGENERATE_POINTS, PQP_ERR_INTERNAL, PQP_ERR_INVALID_ARGUMENT,
    PQP_ERR_INVALID_CONVEX_MESH, PQP_ERR_INVALID_DATA, PQP_ERR_MODEL_OUT_OF_MEMORY,
    PQP_ERR_NONFINITE_COORDINATE, PQP_ERR_NONFINITE_POSE, PQP_ERR_NOT_A_TRIANGLE_MESH,
    PQP_ERR_NULL_POINTER, PQP_ERR_OUT_OF_MEMORY, PQP_ERR_UNPROCESSED_MODEL, PQP_OK, boundary,
};
use std::ffi::{c_char, c_int};

/// Text for a status code, NUL-terminated and static. `Error::message` has the same texts (checked
/// by a test) without the terminator C needs.
fn error_text(code: c_int) -> &'static std::ffi::CStr {
    match code {
        PQP_OK => c"no error",
        PQP_ERR_MODEL_OUT_OF_MEMORY => c"model storage could not be allocated",
        PQP_ERR_OUT_OF_MEMORY => c"query storage could not be allocated",
        PQP_ERR_UNPROCESSED_MODEL => c"model has not been built (end not called or failed)",
        PQP_ERR_BUILD_OUT_OF_SEQUENCE => c"model build calls out of sequence",
        PQP_ERR_BUILD_EMPTY_MODEL => c"model has no triangles",
        PQP_ERR_NONFINITE_COORDINATE => c"vertex coordinate is not finite or too large",
        PQP_ERR_NONFINITE_POSE => c"pose entry is not finite or too large",
        PQP_ERR_INVALID_ARGUMENT => c"invalid argument",
        PQP_ERR_NULL_POINTER => c"null pointer",
        PQP_ERR_INTERNAL => c"internal error",
        PQP_ERR_DEGENERATE_POINTS => {
            c"points do not span a volume (fewer than 4 distinct, collinear or coplanar)"
        }
        PQP_ERR_INVALID_CONVEX_MESH => c"mesh is not a closed convex polyhedron",
        PQP_ERR_BUFFER_TOO_SMALL => c"buffer missing or too small (the needed size was reported)",
        PQP_ERR_INVALID_DATA => c"data is not a valid saved model",
        PQP_ERR_NOT_A_TRIANGLE_MESH => c"model is a primitive, not a triangle mesh",
        _ => c"unknown error code",
    }
}

/// Describes a status code.
///
/// @param code  a value returned by a pqp_ function (PQP_OK or a PQP_ERR_ code).
/// @return a static NUL-terminated English text, never NULL; "unknown error code" for a value that
///         is not a PQP code. The caller must not free it.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub extern "C" fn pqp_error_string(code: c_int) -> *const c_char {
    boundary(
        c"internal error".as_ptr(),
        || {},
        || error_text(code).as_ptr(),
    )
}

/// The library's version.
///
/// @return a static NUL-terminated text "MAJOR.MINOR.PATCH" (for this release "1.0.0"), never
///         NULL. The caller must not free it.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub extern "C" fn pqp_version() -> *const c_char {
    const VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "\0");
    boundary(c"1.0.0".as_ptr(), || {}, || VERSION.as_ptr().cast())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;
    use std::ffi::CStr;

    #[test]
    fn error_texts_match_the_rust_messages() {
        let all = [
            Error::ModelOutOfMemory,
            Error::OutOfMemory,
            Error::UnprocessedModel,
            Error::BuildOutOfSequence,
            Error::BuildEmptyModel,
            Error::NonFiniteCoordinate,
            Error::NonFinitePose,
            Error::InvalidArgument,
            Error::NullPointer,
            Error::Internal,
            Error::DegeneratePoints,
            Error::InvalidConvexMesh,
            Error::BufferTooSmall,
            Error::InvalidData,
            Error::NotATriangleMesh,
        ];
        let constants = [
            PQP_ERR_MODEL_OUT_OF_MEMORY,
            PQP_ERR_OUT_OF_MEMORY,
            PQP_ERR_UNPROCESSED_MODEL,
            PQP_ERR_BUILD_OUT_OF_SEQUENCE,
            PQP_ERR_BUILD_EMPTY_MODEL,
            PQP_ERR_NONFINITE_COORDINATE,
            PQP_ERR_NONFINITE_POSE,
            PQP_ERR_INVALID_ARGUMENT,
            PQP_ERR_NULL_POINTER,
            PQP_ERR_INTERNAL,
            PQP_ERR_DEGENERATE_POINTS,
            PQP_ERR_INVALID_CONVEX_MESH,
            PQP_ERR_BUFFER_TOO_SMALL,
            PQP_ERR_INVALID_DATA,
            PQP_ERR_NOT_A_TRIANGLE_MESH,
        ];
        for (e, c) in all.iter().zip(constants) {
            assert_eq!(e.code(), c);
            // SAFETY: pqp_error_string returns a static NUL-terminated string for any code.
            let text = unsafe { CStr::from_ptr(pqp_error_string(c)) };
            assert_eq!(text.to_str().unwrap(), e.message());
        }
        for c in [1, 2, -16, i32::MIN, i32::MAX] {
            // SAFETY: pqp_error_string returns a static NUL-terminated string for any code.
            let text = unsafe { CStr::from_ptr(pqp_error_string(c)) };
            assert_eq!(text.to_str().unwrap(), "unknown error code");
        }
    }

    #[test]
    fn version_is_the_package_version() {
        // SAFETY: pqp_version returns a static NUL-terminated string.
        let v = unsafe { CStr::from_ptr(pqp_version()) };
        assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
    }
}
