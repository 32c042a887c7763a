/*
 * pqp/pqp_cxx.h -- the C interface <pqp/pqp.h> for pqp-rs's C++ headers (PQP.h, BV.h, ...).
 *
 * In C the status codes and collision flags are macros. PQP 1.3 declared them as `const int`
 * variables, and C++ code written for it relies on that: `::PQP_OK`, `&PQP_FIRST_CONTACT`,
 * `using ::PQP_ALL_CONTACTS;`, or a local variable named like one. This header includes the C
 * interface and, in C++, turns those macros into constants of the same names and values.
 * tests/header.rs checks that every PQP_OK/PQP_ERR_ code and contact flag of pqp.h is listed here.
 */
#ifndef PQP_PQP_CXX_H
#define PQP_PQP_CXX_H

#ifndef __cplusplus
#error "pqp/pqp_cxx.h is for C++; C code includes <pqp/pqp.h>"
#endif

#include "pqp/pqp.h"

#ifdef PQP_OK
/* Each value is read while the macro still exists, the macro is removed, and a constant of the same
 * name takes its place (a constant expression, usable in switch labels and array bounds). */
namespace pqp_detail {
enum c_constants {
    ok = PQP_OK,
    err_model_out_of_memory = PQP_ERR_MODEL_OUT_OF_MEMORY,
    err_out_of_memory = PQP_ERR_OUT_OF_MEMORY,
    err_unprocessed_model = PQP_ERR_UNPROCESSED_MODEL,
    err_build_out_of_sequence = PQP_ERR_BUILD_OUT_OF_SEQUENCE,
    err_build_empty_model = PQP_ERR_BUILD_EMPTY_MODEL,
    err_nonfinite_coordinate = PQP_ERR_NONFINITE_COORDINATE,
    err_nonfinite_pose = PQP_ERR_NONFINITE_POSE,
    err_invalid_argument = PQP_ERR_INVALID_ARGUMENT,
    err_null_pointer = PQP_ERR_NULL_POINTER,
    err_internal = PQP_ERR_INTERNAL,
    err_degenerate_points = PQP_ERR_DEGENERATE_POINTS,
    err_invalid_convex_mesh = PQP_ERR_INVALID_CONVEX_MESH,
    err_buffer_too_small = PQP_ERR_BUFFER_TOO_SMALL,
    err_invalid_data = PQP_ERR_INVALID_DATA,
    err_not_a_triangle_mesh = PQP_ERR_NOT_A_TRIANGLE_MESH,
    all_contacts = PQP_ALL_CONTACTS,
    first_contact = PQP_FIRST_CONTACT
};
} /* namespace pqp_detail */

#undef PQP_OK
#undef PQP_ERR_MODEL_OUT_OF_MEMORY
#undef PQP_ERR_OUT_OF_MEMORY
#undef PQP_ERR_UNPROCESSED_MODEL
#undef PQP_ERR_BUILD_OUT_OF_SEQUENCE
#undef PQP_ERR_BUILD_EMPTY_MODEL
#undef PQP_ERR_NONFINITE_COORDINATE
#undef PQP_ERR_NONFINITE_POSE
#undef PQP_ERR_INVALID_ARGUMENT
#undef PQP_ERR_NULL_POINTER
#undef PQP_ERR_INTERNAL
#undef PQP_ERR_DEGENERATE_POINTS
#undef PQP_ERR_INVALID_CONVEX_MESH
#undef PQP_ERR_BUFFER_TOO_SMALL
#undef PQP_ERR_INVALID_DATA
#undef PQP_ERR_NOT_A_TRIANGLE_MESH
#undef PQP_ALL_CONTACTS
#undef PQP_FIRST_CONTACT

/* PQP 1.3's return values (the first six) and pqp-rs's further codes; see pqp/pqp.h. */
const int PQP_OK = pqp_detail::ok;
const int PQP_ERR_MODEL_OUT_OF_MEMORY = pqp_detail::err_model_out_of_memory;
const int PQP_ERR_OUT_OF_MEMORY = pqp_detail::err_out_of_memory;
const int PQP_ERR_UNPROCESSED_MODEL = pqp_detail::err_unprocessed_model;
const int PQP_ERR_BUILD_OUT_OF_SEQUENCE = pqp_detail::err_build_out_of_sequence;
const int PQP_ERR_BUILD_EMPTY_MODEL = pqp_detail::err_build_empty_model;
const int PQP_ERR_NONFINITE_COORDINATE = pqp_detail::err_nonfinite_coordinate;
const int PQP_ERR_NONFINITE_POSE = pqp_detail::err_nonfinite_pose;
const int PQP_ERR_INVALID_ARGUMENT = pqp_detail::err_invalid_argument;
const int PQP_ERR_NULL_POINTER = pqp_detail::err_null_pointer;
const int PQP_ERR_INTERNAL = pqp_detail::err_internal;
const int PQP_ERR_DEGENERATE_POINTS = pqp_detail::err_degenerate_points;
const int PQP_ERR_INVALID_CONVEX_MESH = pqp_detail::err_invalid_convex_mesh;
const int PQP_ERR_BUFFER_TOO_SMALL = pqp_detail::err_buffer_too_small;
const int PQP_ERR_INVALID_DATA = pqp_detail::err_invalid_data;
const int PQP_ERR_NOT_A_TRIANGLE_MESH = pqp_detail::err_not_a_triangle_mesh;

/* PQP_Collide's flag: every colliding pair, or stop at the first. */
const int PQP_ALL_CONTACTS = pqp_detail::all_contacts;
const int PQP_FIRST_CONTACT = pqp_detail::first_contact;
#endif /* PQP_OK */

#endif /* PQP_PQP_CXX_H */
