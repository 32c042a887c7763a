/*
 * PQP.h -- drop-in replacement for the C++ interface of UNC's PQP 1.3, implemented by pqp-rs.
 *
 * Code written for PQP 1.3 compiles unchanged against this header (C++98 to C++20) and links with
 * -lpqp (or -lPQP). It is header-only: the classes (in PQP_Internal.h, with Tri.h and BV.h) and
 * the queries below are inline wrappers over the C interface in <pqp/pqp.h>.
 *
 *   PQP_Model m;                        models: on the stack, with new, as members, in containers
 *   m.BeginModel();
 *   m.AddTri(p1, p2, p3, id);           for each triangle (p1..p3 are PQP_REAL[3])
 *   m.EndModel();
 *   PQP_DistanceResult res;
 *   PQP_Distance(&res, R1, T1, &m1, R2, T2, &m2, 0.0, 0.0);
 *   res.Distance();                     or res.distance, res.p1, ... as in PQP 1.3
 *
 * Poses are PQP's: R is PQP_REAL[3][3] (its columns are the model's axes in world coordinates), T
 * is PQP_REAL[3], and a model point x is at R * x + T in the world.
 *
 * As in PQP 1.3: PQP_REAL is a typedef (PQP_Compile.h), the return values and contact flags are
 * `const int` constants, every public data member of the models and results is there and holds
 * what PQP 1.3 put in it after each call, and the build calls return PQP 1.3's codes.
 *
 * Differences from PQP 1.3 (all are fixes):
 * - Nothing is ever printed (MemUsage's msg argument is ignored).
 * - NULL arguments, NaN/infinite coordinates or poses, negative error bounds or tolerance, qsize < 1
 *   and unknown flags return error codes (PQP_ERR_NULL_POINTER, PQP_ERR_NONFINITE_COORDINATE,
 *   PQP_ERR_NONFINITE_POSE, PQP_ERR_INVALID_ARGUMENT) instead of crashing or answering wrongly. A
 *   query that returns an error leaves its result as it was.
 * - The distance between triangles is exact, and the requested error bounds are honoured.
 * - Built models are immutable and may be queried from many threads at once; the triangle cache
 *   that speeds up repeated distance queries lives in the result object, not in the model (so
 *   PQP_Model::last_tri is not written by queries).
 * - Models and results can be copied (deep, independent copies; PQP 1.3's copies shared arrays and
 *   freed them twice) and, from C++11 on, moved.
 * - PQP_Model::tris keeps the order the triangles were added in (PQP 1.3 reordered it).
 *
 * Extensions: pqp_handle() on every class gives the underlying C handle, for the functions of
 * <pqp/pqp.h> that PQP 1.3 did not have (for instance pqp_distance_result_overlap).
 */
#ifndef PQP_H
#define PQP_H

#ifndef __cplusplus
#error "PQP.h is a C++ header; C code includes <pqp/pqp.h>"
#endif

#include "PQP_Compile.h"
#include "PQP_Internal.h"

namespace pqp_detail {

/* A query's poses, widened to double for the C interface. */
struct poses
{
    double R1[9], T1[3], R2[9], T2[3];
    poses(PQP_REAL r1[3][3], PQP_REAL t1[3], PQP_REAL r2[3][3], PQP_REAL t2[3])
    {
        widen33(R1, r1);
        widen3(T1, t1);
        widen33(R2, r2);
        widen3(T2, t2);
    }
};

/* What a query returns before calling the C function: PQP_ERR_NULL_POINTER if an argument is NULL;
 * PQP_ERR_UNPROCESSED_MODEL for a model whose handle was never made (allocation failure, or moved
 * from), which cannot have been built; PQP_ERR_OUT_OF_MEMORY if the result's handle could not be
 * made; else PQP_OK. */
inline int query_status(const void *result, const void *result_handle, const void *R1,
                        const void *T1, const PQP_Model *o1, const void *R2, const void *T2,
                        const PQP_Model *o2)
{
    if (result == NULL || R1 == NULL || T1 == NULL || o1 == NULL || R2 == NULL || T2 == NULL ||
        o2 == NULL)
        return PQP_ERR_NULL_POINTER;
    if (o1->pqp_handle() == NULL || o2->pqp_handle() == NULL) return PQP_ERR_UNPROCESSED_MODEL;
    if (result_handle == NULL) return PQP_ERR_OUT_OF_MEMORY;
    return PQP_OK;
}

} /* namespace pqp_detail */

/* Finds the colliding triangle pairs of o1 at (R1, T1) and o2 at (R2, T2). flag is
 * PQP_ALL_CONTACTS (every pair) or PQP_FIRST_CONTACT (stop at the first). Triangles that touch
 * (share a point or an edge, or overlap in a plane) collide. */
inline int PQP_Collide(PQP_CollideResult *result, PQP_REAL R1[3][3], PQP_REAL T1[3],
                       PQP_Model *o1, PQP_REAL R2[3][3], PQP_REAL T2[3], PQP_Model *o2,
                       int flag = PQP_ALL_CONTACTS)
{
    pqp_collide_result *h = result != NULL ? result->pqp_handle() : NULL;
    int rc = pqp_detail::query_status(result, h, R1, T1, o1, R2, T2, o2);
    if (rc != PQP_OK) return rc;
    pqp_detail::poses p(R1, T1, R2, T2);
    rc = pqp_collide(h, p.R1, p.T1, o1->pqp_handle(), p.R2, p.T2, o2->pqp_handle(), flag);
    if (rc != PQP_OK) return rc;
    return result->pqp_take_answer(p.R1, p.T1, p.R2, p.T2);
}

#if PQP_BV_TYPE & RSS_TYPE

/* Computes the distance between o1 at (R1, T1) and o2 at (R2, T2), within the error bounds:
 * true <= distance <= min(true * (1 + rel_err), true + abs_err); abs_err = 0 is exact. qsize
 * (>= 1) is checked, and kept in the result, but does not choose the search (see pqp/pqp.h). */
inline int PQP_Distance(PQP_DistanceResult *result, PQP_REAL R1[3][3], PQP_REAL T1[3],
                        PQP_Model *o1, PQP_REAL R2[3][3], PQP_REAL T2[3], PQP_Model *o2,
                        PQP_REAL rel_err, PQP_REAL abs_err, int qsize = 2)
{
    pqp_distance_result *h = result != NULL ? result->pqp_handle() : NULL;
    int rc = pqp_detail::query_status(result, h, R1, T1, o1, R2, T2, o2);
    if (rc != PQP_OK) return rc;
    pqp_detail::poses p(R1, T1, R2, T2);
    rc = pqp_distance(h, p.R1, p.T1, o1->pqp_handle(), p.R2, p.T2, o2->pqp_handle(), rel_err,
                      abs_err, qsize);
    if (rc != PQP_OK) return rc;
    result->pqp_take_answer(p.R1, p.T1, p.R2, p.T2, rel_err, abs_err, qsize);
    return PQP_OK;
}

/* Decides whether o1 at (R1, T1) and o2 at (R2, T2) are within distance tolerance (>= 0). */
inline int PQP_Tolerance(PQP_ToleranceResult *result, PQP_REAL R1[3][3], PQP_REAL T1[3],
                         PQP_Model *o1, PQP_REAL R2[3][3], PQP_REAL T2[3], PQP_Model *o2,
                         PQP_REAL tolerance, int qsize = 2)
{
    pqp_tolerance_result *h = result != NULL ? result->pqp_handle() : NULL;
    int rc = pqp_detail::query_status(result, h, R1, T1, o1, R2, T2, o2);
    if (rc != PQP_OK) return rc;
    pqp_detail::poses p(R1, T1, R2, T2);
    rc = pqp_tolerance(h, p.R1, p.T1, o1->pqp_handle(), p.R2, p.T2, o2->pqp_handle(), tolerance,
                       qsize);
    if (rc != PQP_OK) return rc;
    result->pqp_take_answer(p.R1, p.T1, p.R2, p.T2, tolerance, qsize);
    return PQP_OK;
}

#endif /* PQP_BV_TYPE & RSS_TYPE */

#endif /* PQP_H */
