/*
 * TriDist.h -- PQP 1.3's triangle and segment distance routines, as provided by pqp-rs (C++ only).
 *
 * TriDist and SegPoints keep PQP 1.3's names and arguments; they are inline wrappers over the C
 * functions pqp_triangle_distance and pqp_segment_distance of <pqp/pqp.h> (link with -lpqp or
 * -lPQP). They compute in double whatever PQP_REAL is (see PQP_Compile.h), and convert back.
 *
 * Differences from PQP 1.3 (all are fixes):
 * - The answers are exact: PQP 1.3's TriDist could be far off in near-degenerate configurations.
 * - When the triangles intersect or touch, TriDist returns 0 and p == q, a point common to both
 *   (PQP 1.3 gave arbitrary points).
 * - Degenerate triangles (collinear or repeated vertices) are the segment or point they span.
 * - A NaN, infinite or huge (beyond 1e150 in magnitude) coordinate makes the answer NaN, every
 *   output included, instead of an arbitrary value.
 */
#ifndef PQP_TRIDIST_H
#define PQP_TRIDIST_H

#ifndef __cplusplus
#error "TriDist.h is a C++ header; C code calls pqp_triangle_distance of <pqp/pqp.h>"
#endif

#include "PQP_Compile.h"
#include "pqp/pqp.h"

#include <limits>

/* The distance between triangle s (vertices s[0], s[1], s[2]) and triangle t, returned; a closest
 * pair of points is written to p (on s) and q (on t). When the triangles share a point the
 * distance is 0 and p == q is such a point. On a NaN, infinite or huge coordinate, NaN is returned
 * and p and q are set to NaN. */
inline PQP_REAL TriDist(PQP_REAL p[3], PQP_REAL q[3], const PQP_REAL s[3][3],
                        const PQP_REAL t[3][3])
{
    double sd[9], td[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            sd[3 * i + j] = (double)s[i][j];
            td[3 * i + j] = (double)t[i][j];
        }
    double d, pd[3], qd[3];
    if (pqp_triangle_distance(&d, pd, qd, sd, td) != PQP_OK) {
        d = std::numeric_limits<double>::quiet_NaN();
        pd[0] = pd[1] = pd[2] = qd[0] = qd[1] = qd[2] = d;
    }
    for (int i = 0; i < 3; i++) {
        p[i] = (PQP_REAL)pd[i];
        q[i] = (PQP_REAL)qd[i];
    }
    return (PQP_REAL)d;
}

/* The closest points of two segments: X on the segment P + a A and Y on the segment Q + b B
 * (a, b in [0, 1]; each segment is a start point and a direction vector, which may be zero).
 *
 * VEC is a direction from the first segment to the second: Y - X when the segments are apart;
 * when they touch (X == Y, decided in double before the conversion to PQP_REAL), A x B, negated
 * if needed so that VEC . (Q - P) >= 0 (the zero vector when A and B are parallel). On a NaN,
 * infinite or huge (beyond 1e150 in magnitude) coordinate, VEC, X and Y are set to NaN. */
inline void SegPoints(PQP_REAL VEC[3], PQP_REAL X[3], PQP_REAL Y[3], const PQP_REAL P[3],
                      const PQP_REAL A[3], const PQP_REAL Q[3], const PQP_REAL B[3])
{
    double Pd[3], Ad[3], Qd[3], Bd[3];
    for (int i = 0; i < 3; i++) {
        Pd[i] = (double)P[i];
        Ad[i] = (double)A[i];
        Qd[i] = (double)Q[i];
        Bd[i] = (double)B[i];
    }
    double d, x[3], y[3], v[3];
    if (pqp_segment_distance(&d, x, y, Pd, Ad, Qd, Bd) != PQP_OK) {
        d = std::numeric_limits<double>::quiet_NaN();
        x[0] = x[1] = x[2] = y[0] = y[1] = y[2] = v[0] = v[1] = v[2] = d;
    } else if (x[0] != y[0] || x[1] != y[1] || x[2] != y[2]) {
        for (int i = 0; i < 3; i++) v[i] = y[i] - x[i];
    } else {
        /* Touching: the normal of the two directions, towards the second segment's start. */
        v[0] = Ad[1] * Bd[2] - Ad[2] * Bd[1];
        v[1] = Ad[2] * Bd[0] - Ad[0] * Bd[2];
        v[2] = Ad[0] * Bd[1] - Ad[1] * Bd[0];
        double side = 0;
        for (int i = 0; i < 3; i++) side += v[i] * (Qd[i] - Pd[i]);
        if (side < 0)
            for (int i = 0; i < 3; i++) v[i] = -v[i];
    }
    for (int i = 0; i < 3; i++) {
        VEC[i] = (PQP_REAL)v[i];
        X[i] = (PQP_REAL)x[i];
        Y[i] = (PQP_REAL)y[i];
    }
}

#endif /* PQP_TRIDIST_H */
