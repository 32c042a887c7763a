/*
 * PQP_Compile.h -- compile-time settings of the PQP 1.3 interface, as provided by pqp-rs.
 *
 * PQP 1.3 chose its scalar type and bounding volumes here. pqp-rs always computes in double and
 * always builds both volume kinds (rectangle swept spheres for distance and tolerance, oriented
 * boxes for collision), so these are fixed; they are kept for code that includes this file or tests
 * the macros. Defining PQP_REAL as anything but double before including this file is an error
 * (a conflicting macro redefinition), because the library's interface takes doubles.
 */
#ifndef PQP_COMPILE_H
#define PQP_COMPILE_H

/* The scalar type of every coordinate, rotation, translation and distance. */
#define PQP_REAL double

/* Bounding-volume kinds, and those a model carries (both). */
#define RSS_TYPE 1
#define OBB_TYPE 2
#define PQP_BV_TYPE (RSS_TYPE | OBB_TYPE)

#endif /* PQP_COMPILE_H */
