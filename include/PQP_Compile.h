/*
 * PQP_Compile.h -- compile-time settings of PQP 1.3's C++ interface, as pqp-rs provides them.
 *
 * PQP_REAL is the scalar type of every coordinate, rotation, translation and distance that the
 * interface takes and returns: a typedef, as in PQP 1.3, so `::PQP_REAL` and `using ::PQP_REAL;`
 * work. It is double unless PQP_USE_FLOAT is defined before this file is included (or the typedef
 * below is edited, as PQP 1.3's users did); either way the library computes in double: floats are
 * widened on the way in and rounded on the way out.
 *
 * PQP_BV_TYPE chose, in PQP 1.3, which volumes a model carried. pqp-rs always builds both, and a
 * BV always has both sets of members (R, Tr, l, r for the rectangle swept sphere and To, d for the
 * oriented box); the setting only chooses what BV::GetSize() measures, as it did in PQP 1.3.
 *
 * Unlike PQP 1.3's, this file does not declare float overloads of sqrt, sin, cos and fabs (they
 * clash with <cmath>'s in every modern C++ library); <math.h> is included as before.
 */
#ifndef PQP_COMPILE_H
#define PQP_COMPILE_H

#include <math.h>

#ifdef PQP_USE_FLOAT
typedef float PQP_REAL;
#else
typedef double PQP_REAL;
#endif

/* Bounding-volume kinds, and the ones a model carries (both). */
#define RSS_TYPE 1
#define OBB_TYPE 2
#ifndef PQP_BV_TYPE
#define PQP_BV_TYPE (RSS_TYPE | OBB_TYPE)
#endif

#endif /* PQP_COMPILE_H */
