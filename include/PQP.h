/*
 * PQP.h -- drop-in replacement for the C++ interface of UNC's PQP 1.3, implemented by pqp-rs.
 *
 * Code written for PQP 1.3 compiles unchanged against this header (C++98 to C++20) and links with
 * -lpqp (or -lPQP). It is header-only: every function below is an inline wrapper over the C
 * interface in <pqp/pqp.h>, which it includes.
 *
 *   PQP_Model m;                        models: on the stack, with new, or as members
 *   m.BeginModel();
 *   m.AddTri(p1, p2, p3, id);           for each triangle (p1..p3 are PQP_REAL[3])
 *   m.EndModel();
 *   PQP_DistanceResult res;
 *   PQP_Distance(&res, R1, T1, &m1, R2, T2, &m2, 0.0, 0.0);
 *   res.Distance();
 *
 * Poses are PQP's: R is PQP_REAL[3][3] (its columns are the model's axes in world coordinates), T
 * is PQP_REAL[3], and a model point x is at R * x + T in the world.
 *
 * Differences from PQP 1.3 (all are fixes):
 * - Nothing is ever printed (MemUsage's msg argument is ignored).
 * - NULL arguments, NaN/infinite coordinates or poses, negative error bounds or tolerance, qsize < 1
 *   and unknown flags return error codes (PQP_ERR_NULL_POINTER, PQP_ERR_NONFINITE_COORDINATE,
 *   PQP_ERR_NONFINITE_POSE, PQP_ERR_INVALID_ARGUMENT) instead of crashing or answering wrongly.
 * - The distance between triangles is exact, and the requested error bounds are honoured.
 * - Built models are immutable and may be queried from many threads at once; the triangle cache
 *   that speeds up repeated distance queries lives in the result object, not in the model.
 * - Models and results cannot be copied (copying one in PQP 1.3 led to a double free); in C++11
 *   and later they can be moved.
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
#include "pqp/pqp.h"

#include <limits.h>
#include <stddef.h>
#include <stdint.h>

/* PQP_OK, PQP_ERR_* (PQP 1.3's five codes keep their values), PQP_ALL_CONTACTS and
 * PQP_FIRST_CONTACT come from <pqp/pqp.h>. */

namespace pqp_detail {

/* A 64-bit counter as PQP's int (saturating). */
inline int clamp_to_int(int64_t v)
{
    if (v > INT_MAX) return INT_MAX;
    if (v < INT_MIN) return INT_MIN;
    return static_cast<int>(v);
}

/* What P1() and P2() return if a result's handle could not be allocated (never NULL, as in PQP). */
inline const double *zero_point()
{
    static const double zero[3] = {0.0, 0.0, 0.0};
    return zero;
}

inline const double *point_or_zero(const double *p)
{
    return p != NULL ? p : zero_point();
}

} /* namespace pqp_detail */

/* A triangle model. Build it with BeginModel, AddTri (once per triangle) and EndModel; it can then
 * be queried, and is immutable. num_tris is the number of triangles added so far. */
class PQP_Model
{
public:
    /* Number of triangles in the model (kept in sync by the member functions; read only). */
    int num_tris;

    PQP_Model() : num_tris(0), pqp_handle_(pqp_model_create()) {}
    ~PQP_Model() { pqp_model_destroy(pqp_handle_); }

#if __cplusplus >= 201103L
    PQP_Model(const PQP_Model &) = delete;
    PQP_Model &operator=(const PQP_Model &) = delete;
    PQP_Model(PQP_Model &&other) noexcept : num_tris(other.num_tris), pqp_handle_(other.pqp_handle_)
    {
        other.pqp_handle_ = NULL;
        other.num_tris = 0;
    }
    PQP_Model &operator=(PQP_Model &&other) noexcept
    {
        if (this != &other) {
            pqp_model_destroy(pqp_handle_);
            pqp_handle_ = other.pqp_handle_;
            num_tris = other.num_tris;
            other.pqp_handle_ = NULL;
            other.num_tris = 0;
        }
        return *this;
    }
#endif

    /* Starts the model; n is a capacity hint. On a model already begun or built, clears it and
     * returns PQP_ERR_BUILD_OUT_OF_SEQUENCE (the model is then begun). */
    int BeginModel(int n = 8)
    {
        if (!ensure()) return PQP_ERR_MODEL_OUT_OF_MEMORY;
        int rc = pqp_model_begin(pqp_handle_, n);
        sync();
        return rc;
    }

    /* Adds a triangle with the caller's id (reported by queries). */
    int AddTri(const PQP_REAL *p1, const PQP_REAL *p2, const PQP_REAL *p3, int id)
    {
        if (!ensure()) return PQP_ERR_MODEL_OUT_OF_MEMORY;
        int rc = pqp_model_add_tri(pqp_handle_, p1, p2, p3, id);
        sync();
        return rc;
    }

    /* Builds the model's hierarchy; after it the model can be queried. */
    int EndModel()
    {
        if (!ensure()) return PQP_ERR_MODEL_OUT_OF_MEMORY;
        int rc = pqp_model_end(pqp_handle_);
        sync();
        return rc;
    }

    /* Bytes held by the model (clamped to INT_MAX). Never prints, whatever msg is. */
    int MemUsage(int msg) const
    {
        (void)msg;
        uint64_t bytes = pqp_model_memory_usage(pqp_handle_);
        return bytes > static_cast<uint64_t>(INT_MAX) ? INT_MAX : static_cast<int>(bytes);
    }

    /* pqp-rs extension: the C handle (NULL only if it could not be allocated). */
    pqp_model *pqp_handle() { return pqp_handle_; }
    const pqp_model *pqp_handle() const { return pqp_handle_; }

private:
#if __cplusplus < 201103L
    PQP_Model(const PQP_Model &);            /* not copyable */
    PQP_Model &operator=(const PQP_Model &); /* not copyable */
#endif

    /* A handle to work on: made again if allocation failed before, or after a move. */
    bool ensure()
    {
        if (pqp_handle_ == NULL) pqp_handle_ = pqp_model_create();
        return pqp_handle_ != NULL;
    }

    void sync() { num_tris = pqp_model_num_tris(pqp_handle_); }

    pqp_model *pqp_handle_;
};

/* The answer of PQP_Collide. */
struct PQP_CollideResult
{
    PQP_CollideResult() : pqp_handle_(pqp_collide_result_create()) {}
    ~PQP_CollideResult() { pqp_collide_result_destroy(pqp_handle_); }

#if __cplusplus >= 201103L
    PQP_CollideResult(const PQP_CollideResult &) = delete;
    PQP_CollideResult &operator=(const PQP_CollideResult &) = delete;
    PQP_CollideResult(PQP_CollideResult &&other) noexcept : pqp_handle_(other.pqp_handle_)
    {
        other.pqp_handle_ = NULL;
    }
    PQP_CollideResult &operator=(PQP_CollideResult &&other) noexcept
    {
        if (this != &other) {
            pqp_collide_result_destroy(pqp_handle_);
            pqp_handle_ = other.pqp_handle_;
            other.pqp_handle_ = NULL;
        }
        return *this;
    }
#endif

    /* Bounding-volume overlap tests of the last query. */
    int NumBVTests() const
    {
        return pqp_detail::clamp_to_int(pqp_collide_result_num_bv_tests(pqp_handle_));
    }
    /* Triangle-pair overlap tests of the last query. */
    int NumTriTests() const
    {
        return pqp_detail::clamp_to_int(pqp_collide_result_num_tri_tests(pqp_handle_));
    }
    /* Wall-clock time of the last query, in seconds. */
    double QueryTimeSecs() const { return pqp_collide_result_query_time_secs(pqp_handle_); }

    /* Frees the list of colliding pairs. */
    void FreePairsList() { pqp_collide_result_free_pairs(pqp_handle_); }

    /* 1 if the last query found a colliding triangle pair, else 0. */
    int Colliding() const { return pqp_collide_result_colliding(pqp_handle_); }
    /* Number of colliding pairs found. */
    int NumPairs() const { return pqp_collide_result_num_pairs(pqp_handle_); }
    /* Id of model 1's triangle of pair k (0 <= k < NumPairs(); -1 outside). */
    int Id1(int k) const { return pqp_collide_result_id1(pqp_handle_, k); }
    /* Id of model 2's triangle of pair k (0 <= k < NumPairs(); -1 outside). */
    int Id2(int k) const { return pqp_collide_result_id2(pqp_handle_, k); }

    /* pqp-rs extension: the C handle. */
    pqp_collide_result *pqp_handle()
    {
        if (pqp_handle_ == NULL) pqp_handle_ = pqp_collide_result_create();
        return pqp_handle_;
    }
    const pqp_collide_result *pqp_handle() const { return pqp_handle_; }

private:
#if __cplusplus < 201103L
    PQP_CollideResult(const PQP_CollideResult &);
    PQP_CollideResult &operator=(const PQP_CollideResult &);
#endif
    pqp_collide_result *pqp_handle_;
};

/* The answer of PQP_Distance. */
struct PQP_DistanceResult
{
    PQP_DistanceResult() : pqp_handle_(pqp_distance_result_create()) {}
    ~PQP_DistanceResult() { pqp_distance_result_destroy(pqp_handle_); }

#if __cplusplus >= 201103L
    PQP_DistanceResult(const PQP_DistanceResult &) = delete;
    PQP_DistanceResult &operator=(const PQP_DistanceResult &) = delete;
    PQP_DistanceResult(PQP_DistanceResult &&other) noexcept : pqp_handle_(other.pqp_handle_)
    {
        other.pqp_handle_ = NULL;
    }
    PQP_DistanceResult &operator=(PQP_DistanceResult &&other) noexcept
    {
        if (this != &other) {
            pqp_distance_result_destroy(pqp_handle_);
            pqp_handle_ = other.pqp_handle_;
            other.pqp_handle_ = NULL;
        }
        return *this;
    }
#endif

    /* Bounding-volume distance tests of the last query. */
    int NumBVTests() const
    {
        return pqp_detail::clamp_to_int(pqp_distance_result_num_bv_tests(pqp_handle_));
    }
    /* Triangle-pair distance tests of the last query. */
    int NumTriTests() const
    {
        return pqp_detail::clamp_to_int(pqp_distance_result_num_tri_tests(pqp_handle_));
    }
    /* Wall-clock time of the last query, in seconds. */
    double QueryTimeSecs() const { return pqp_distance_result_query_time_secs(pqp_handle_); }

    /* The distance found (0 when the models touch or overlap). */
    PQP_REAL Distance() const { return pqp_distance_result_distance(pqp_handle_); }
    /* A closest point on model 1, in model 1's frame. */
    const PQP_REAL *P1() const
    {
        return pqp_detail::point_or_zero(pqp_distance_result_p1(pqp_handle_));
    }
    /* A closest point on model 2, in model 2's frame. */
    const PQP_REAL *P2() const
    {
        return pqp_detail::point_or_zero(pqp_distance_result_p2(pqp_handle_));
    }

    /* pqp-rs extension: the C handle. */
    pqp_distance_result *pqp_handle()
    {
        if (pqp_handle_ == NULL) pqp_handle_ = pqp_distance_result_create();
        return pqp_handle_;
    }
    const pqp_distance_result *pqp_handle() const { return pqp_handle_; }

private:
#if __cplusplus < 201103L
    PQP_DistanceResult(const PQP_DistanceResult &);
    PQP_DistanceResult &operator=(const PQP_DistanceResult &);
#endif
    pqp_distance_result *pqp_handle_;
};

/* The answer of PQP_Tolerance. */
struct PQP_ToleranceResult
{
    PQP_ToleranceResult() : pqp_handle_(pqp_tolerance_result_create()) {}
    ~PQP_ToleranceResult() { pqp_tolerance_result_destroy(pqp_handle_); }

#if __cplusplus >= 201103L
    PQP_ToleranceResult(const PQP_ToleranceResult &) = delete;
    PQP_ToleranceResult &operator=(const PQP_ToleranceResult &) = delete;
    PQP_ToleranceResult(PQP_ToleranceResult &&other) noexcept : pqp_handle_(other.pqp_handle_)
    {
        other.pqp_handle_ = NULL;
    }
    PQP_ToleranceResult &operator=(PQP_ToleranceResult &&other) noexcept
    {
        if (this != &other) {
            pqp_tolerance_result_destroy(pqp_handle_);
            pqp_handle_ = other.pqp_handle_;
            other.pqp_handle_ = NULL;
        }
        return *this;
    }
#endif

    /* Bounding-volume distance tests of the last query. */
    int NumBVTests() const
    {
        return pqp_detail::clamp_to_int(pqp_tolerance_result_num_bv_tests(pqp_handle_));
    }
    /* Triangle-pair distance tests of the last query. */
    int NumTriTests() const
    {
        return pqp_detail::clamp_to_int(pqp_tolerance_result_num_tri_tests(pqp_handle_));
    }
    /* Wall-clock time of the last query, in seconds. */
    double QueryTimeSecs() const { return pqp_tolerance_result_query_time_secs(pqp_handle_); }

    /* 1 if the models are within the tolerance (distance <= tolerance), else 0. */
    int CloserThanTolerance() const
    {
        return pqp_tolerance_result_closer_than_tolerance(pqp_handle_);
    }
    /* When closer: the distance of a triangle pair within the tolerance. Otherwise: a lower bound
     * on the distance, greater than the tolerance. */
    PQP_REAL Distance() const { return pqp_tolerance_result_distance(pqp_handle_); }
    /* When closer: the point on model 1 of that pair, in model 1's frame. */
    const PQP_REAL *P1() const
    {
        return pqp_detail::point_or_zero(pqp_tolerance_result_p1(pqp_handle_));
    }
    /* When closer: the point on model 2 of that pair, in model 2's frame. */
    const PQP_REAL *P2() const
    {
        return pqp_detail::point_or_zero(pqp_tolerance_result_p2(pqp_handle_));
    }

    /* pqp-rs extension: the C handle. */
    pqp_tolerance_result *pqp_handle()
    {
        if (pqp_handle_ == NULL) pqp_handle_ = pqp_tolerance_result_create();
        return pqp_handle_;
    }
    const pqp_tolerance_result *pqp_handle() const { return pqp_handle_; }

private:
#if __cplusplus < 201103L
    PQP_ToleranceResult(const PQP_ToleranceResult &);
    PQP_ToleranceResult &operator=(const PQP_ToleranceResult &);
#endif
    pqp_tolerance_result *pqp_handle_;
};

namespace pqp_detail {

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

inline const double *matrix(PQP_REAL R[3][3])
{
    return R != NULL ? R[0] : NULL;
}

} /* namespace pqp_detail */

/* Finds the colliding triangle pairs of o1 at (R1, T1) and o2 at (R2, T2). flag is
 * PQP_ALL_CONTACTS (every pair) or PQP_FIRST_CONTACT (stop at the first). */
inline int PQP_Collide(PQP_CollideResult *result, PQP_REAL R1[3][3], PQP_REAL T1[3],
                       PQP_Model *o1, PQP_REAL R2[3][3], PQP_REAL T2[3], PQP_Model *o2,
                       int flag = PQP_ALL_CONTACTS)
{
    pqp_collide_result *h = result != NULL ? result->pqp_handle() : NULL;
    int rc = pqp_detail::query_status(result, h, R1, T1, o1, R2, T2, o2);
    if (rc != PQP_OK) return rc;
    return pqp_collide(h, pqp_detail::matrix(R1), T1, o1->pqp_handle(), pqp_detail::matrix(R2),
                       T2, o2->pqp_handle(), flag);
}

/* Computes the distance between o1 at (R1, T1) and o2 at (R2, T2), within the error bounds:
 * true <= distance <= min(true * (1 + rel_err), true + abs_err); abs_err = 0 is exact. qsize
 * (>= 1) is the search queue size. */
inline int PQP_Distance(PQP_DistanceResult *result, PQP_REAL R1[3][3], PQP_REAL T1[3],
                        PQP_Model *o1, PQP_REAL R2[3][3], PQP_REAL T2[3], PQP_Model *o2,
                        PQP_REAL rel_err, PQP_REAL abs_err, int qsize = 2)
{
    pqp_distance_result *h = result != NULL ? result->pqp_handle() : NULL;
    int rc = pqp_detail::query_status(result, h, R1, T1, o1, R2, T2, o2);
    if (rc != PQP_OK) return rc;
    return pqp_distance(h, pqp_detail::matrix(R1), T1, o1->pqp_handle(), pqp_detail::matrix(R2),
                        T2, o2->pqp_handle(), rel_err, abs_err, qsize);
}

/* Decides whether o1 at (R1, T1) and o2 at (R2, T2) are within distance tolerance (>= 0). */
inline int PQP_Tolerance(PQP_ToleranceResult *result, PQP_REAL R1[3][3], PQP_REAL T1[3],
                         PQP_Model *o1, PQP_REAL R2[3][3], PQP_REAL T2[3], PQP_Model *o2,
                         PQP_REAL tolerance, int qsize = 2)
{
    pqp_tolerance_result *h = result != NULL ? result->pqp_handle() : NULL;
    int rc = pqp_detail::query_status(result, h, R1, T1, o1, R2, T2, o2);
    if (rc != PQP_OK) return rc;
    return pqp_tolerance(h, pqp_detail::matrix(R1), T1, o1->pqp_handle(),
                         pqp_detail::matrix(R2), T2, o2->pqp_handle(), tolerance, qsize);
}

#endif /* PQP_H */
